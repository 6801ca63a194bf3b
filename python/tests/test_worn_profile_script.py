"""scripts/make_worn_profile.py writes the shipped worn profiles (data/profiles/UIC60_gauge_corner_worn.prr,
S1002_hollow_worn.prw) to the byte: the files are its output, not edited by hand (their wear is
checked against the new profiles by tests/worn_profile_test.cpp)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "make_worn_profile.py")


@pytest.mark.parametrize("wear, shipped", [("gauge-corner", "UIC60_gauge_corner_worn.prr"),
                                           ("hollow", "S1002_hollow_worn.prw")])
def test_the_script_writes_the_shipped_profile(wear, shipped, tmp_path):
    out = tmp_path / shipped
    subprocess.run([sys.executable, SCRIPT, wear, str(out)], check=True)
    with open(os.path.join(ROOT, "data", "profiles", shipped), "rb") as f:
        assert out.read_bytes() == f.read()


def test_an_unknown_wear_is_refused_with_the_usage(tmp_path):
    r = subprocess.run([sys.executable, SCRIPT, "flange", str(tmp_path / "x.prr")], capture_output=True, text=True)
    assert r.returncode == 2
    assert "WEAR: gauge-corner (60E1 rail head, writes a .prr) or hollow (S1002 wheel, writes a .prw)" in r.stderr
    assert not (tmp_path / "x.prr").exists()
