"""The hunting example (examples/hunting_simulation.py, docs/PYTHON.md "A hunting simulation"),
run in its quick mode: the motion decays at 40 m/s and grows to a limit cycle at 70 m/s from a
small start, the three contact models agree over the first steps, and each model's cost is
reported. Quick mode names no critical speed (its runs are too short and too few), and the table
build's progress reaches its last node."""
import json
import os
import subprocess
import sys

import numpy as np

SOURCE = os.environ.get("RAILCONTACT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_hunting_example_quick(tmp_path):
    out = tmp_path / "hunting"
    r = subprocess.run([sys.executable, os.path.join(SOURCE, "examples", "hunting_simulation.py"), "--quick",
                        "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]
    summary = json.loads((out / "hunting_summary.json").read_text())
    import railcontact
    assert summary["railcontact_version"] == railcontact.__version__
    assert summary["critical_speed_small_start_m_per_s"] is None
    assert summary["critical_speed_large_start_m_per_s"] is None
    assert "critical speed:" not in r.stdout and "no critical speed" in r.stdout
    # The table build's progress: its last line is the last node, with nothing left (the nodes of the
    # grid and those the build added where the contact jumps).
    nodes = summary["table"]["nodes_built"]
    assert nodes == summary["table"]["y_values"] * summary["table"]["yaw_values"]  # not refined
    table_lines = [line for line in r.stderr.splitlines() if "table nodes" in line]
    assert table_lines and f"table nodes {nodes}/{nodes};" in table_lines[-1], table_lines[-3:]
    assert table_lines[-1].endswith("about 0 s left"), table_lines[-1]
    # From a 0.5 mm start: decaying at 40 m/s, a flange-contact limit cycle at 70 m/s.
    rows = np.genfromtxt(out / "hunting.csv", delimiter=",", names=True, dtype=None, encoding=None)
    assert rows["amplitude_small_start_m"][0] < 1e-3 < rows["amplitude_small_start_m"][1] < 8e-3
    # The cost of each model is reported (its speed is measured by benchmarks, docs/BENCHMARKS.md,
    # not asserted here: a timing depends on the machine's load).
    cost = {c["model"]: c for c in summary["cost"]}
    assert set(cost) == {"table", "on-the-fly nh-fastsim", "on-the-fly fastsim"}, sorted(cost)
    for c in cost.values():
        assert c["evaluations"] > 0 and 0.0 < c["us_per_evaluation"] < 1e7, c
    # On the fly the stages' times add up to most of the evaluations' (the rest is Python's and the
    # binding's); by load every stage runs.
    for name in ("on-the-fly nh-fastsim", "on-the-fly fastsim"):
        stages = cost[name]["stage_us_per_evaluation"]
        assert set(stages) == {"search", "area", "normal", "height", "kinematics", "tangential", "assembly"}, stages
        assert all(us > 0.0 for us in stages.values()), stages
        assert 0.5 * cost[name]["us_per_evaluation"] < sum(stages.values()) <= cost[name]["us_per_evaluation"], cost[name]
    assert cost["table"]["stage_us_per_evaluation"] == {}
    # The three models over the same first 20 ms at 70 m/s: the same motion to a few micrometres.
    runs = np.genfromtxt(out / "hunting_runs.csv", delimiter=",", names=True, dtype=None, encoding=None)
    ends = {m: runs["y_m"][runs["model"] == m][-1] for m in set(runs["model"])}
    assert abs(ends["table"] - ends["on-the-fly nh-fastsim"]) < 5e-6
    assert abs(ends["table"] - ends["on-the-fly fastsim"]) < 50e-6
    for figure in ("hunting_time.png", "hunting_bifurcation.png", "hunting_models.png"):
        assert (out / figure).stat().st_size > 10000
