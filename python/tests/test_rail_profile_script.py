"""scripts/make_rail_profile.py writes the shipped upright rail heads (data/profiles/UIC60_upright.prr,
54E1_upright.prr) to the byte: the files are its output, not edited by hand (their dimensions are
checked by tests/rail_profile_generator_test.cpp)."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


@pytest.mark.parametrize("rail, shipped", [("60E1", "UIC60_upright.prr"), ("54E1", "54E1_upright.prr")])
def test_the_script_writes_the_shipped_profile(rail, shipped, tmp_path):
    out = tmp_path / shipped
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_rail_profile.py"), rail, str(out)], check=True)
    with open(os.path.join(ROOT, "data", "profiles", shipped), "rb") as f:
        assert out.read_bytes() == f.read()


def test_an_unknown_rail_is_refused_with_the_usage(tmp_path):
    r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_rail_profile.py"), "49E1",
                        str(tmp_path / "x.prr")], capture_output=True, text=True)
    assert r.returncode == 2
    assert "RAIL: 60E1 (UIC 60) or 54E1 (UIC 54)" in r.stderr
    assert not (tmp_path / "x.prr").exists()
