"""Invariant: examples/paired_change.py prints, per engine, the mean of (after − before) over the
episode pairs of two `hyq compare --policy` reports with hyq.stats' interval of it, and refuses
reports whose engines or episode counts differ with one line."""

import json
import subprocess
import sys
from pathlib import Path

import hyq.stats

REPO = Path(__file__).resolve().parents[3]
SCRIPT = REPO / "examples" / "paired_change.py"


def report(path: Path, travel: dict[str, list[float]]) -> str:
    sides = [{"label": label, "episodes": [{"travel_m": t} for t in values]} for label, values in travel.items()]
    path.write_text(json.dumps({"sides": sides}), encoding="utf-8")
    return str(path)


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, check=False)


def test_each_engine_gets_the_paired_mean_and_its_interval(tmp_path):
    before = report(tmp_path / "a.json", {"rapier": [1.0, 2.0, 3.0, 4.0], "dart": [1.0, 1.0, 1.0, 1.0]})
    after = report(tmp_path / "b.json", {"rapier": [1.5, 2.1, 3.7, 4.2], "dart": [1.0, 1.0, 1.0, 1.0]})
    out = run(before, after)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    change = hyq.stats.mean_ci([0.5, 0.1, 0.7, 0.2])
    lo, hi = change["ci95"]
    assert lines[0] == f"rapier: travel_m after - before {change['mean']:+.3f} [{lo:+.3f}, {hi:+.3f}] (4 pairs)"
    assert lines[1] == "dart: travel_m after - before +0.000 [+0.000, +0.000] (4 pairs)"


def test_mismatched_reports_are_refused_in_one_line(tmp_path):
    before = report(tmp_path / "a.json", {"rapier": [1.0, 2.0]})
    for name, other in [("engines", {"dart": [1.0, 2.0]}), ("episodes", {"rapier": [1.0]})]:
        out = run(before, report(tmp_path / f"{name}.json", other))
        assert out.returncode != 0 and out.stderr.strip().startswith("error:"), out.stderr
        assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    out = run(before, str(tmp_path / "missing.json"))
    assert out.returncode != 0 and "not a `hyq compare --policy` report.json" in out.stderr
