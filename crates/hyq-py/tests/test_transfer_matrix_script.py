"""Invariant: examples/transfer_matrix.py --table-only turns the rows' `hyq compare --policy`
reports into the train x deploy table: each engine's travel and rates as the reports give them,
and for each engine a row did not train on, its mean travel over the training engines' per-episode
mean with hyq.stats' paired interval; bad rows and missing reports are refused in one line."""

import json
import subprocess
import sys
from pathlib import Path

import hyq.stats

REPO = Path(__file__).resolve().parents[3]
SCRIPT = REPO / "examples" / "transfer_matrix.py"
ENGINES = ["rapier", "dart", "mujoco"]


def write_row(root: Path, row: str, travel: dict[str, list[float]], reached: dict[str, int]) -> None:
    directory = root / row
    (directory / "compare").mkdir(parents=True)
    (directory / "run").mkdir()
    sides = []
    for engine in ENGINES:
        values = travel[engine]
        n = len(values)
        rates = {name: hyq.stats.wilson(reached[engine] if name == "reached" else 0, n)
                 for name in ["reached", "fell", "joint_limit"]}
        sides.append({"label": engine, "engine": engine, "travel_m": hyq.stats.mean_ci(values),
                      "rates": rates, "episodes": [{"travel_m": v} for v in values]})
    report = {"episodes": len(travel["rapier"]), "seed": 1000, "sides": sides}
    (directory / "compare" / "report.json").write_text(json.dumps(report), encoding="utf-8")
    (directory / "run" / "eval.json").write_text(
        json.dumps({"timing": {"wall_s": 150.0, "env_steps": 200_000, "load_average_start": [0.4, 0.3, 0.2],
                               "load_average_end": [1.25, 0.5, 0.3]}}), encoding="utf-8")


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, check=False)


def test_the_table_holds_each_engines_figures_and_the_held_out_ratio(tmp_path):
    travel = {"rapier": [3.0, 3.2, 2.8, 3.1], "dart": [2.0, 2.2, 1.9, 2.1], "mujoco": [3.9, 4.1, 3.8, 4.0]}
    write_row(tmp_path, "dart+mujoco", travel, {"rapier": 0, "dart": 1, "mujoco": 2})
    write_row(tmp_path, "rapier+dart+mujoco", travel, {"rapier": 0, "dart": 0, "mujoco": 0})
    out = run("--out", str(tmp_path), "--rows", "dart+mujoco,rapier+dart+mujoco", "--table-only")
    assert out.returncode == 0, out.stderr
    results = json.loads((tmp_path / "matrix.json").read_text(encoding="utf-8"))
    pair = results[0]
    assert list(pair["held_out"]) == ["rapier"]
    trained_mean = [(d + m) / 2 for d, m in zip(travel["dart"], travel["mujoco"])]
    expected = hyq.stats.ratio_of_means(travel["rapier"], trained_mean, seed=0, paired=True)
    assert pair["held_out"]["rapier"] == expected
    assert 0.9 < expected["mean"] < 1.1  # 3.025 over 3.0: the held-out engine walks as far
    assert results[1]["held_out"] == {}
    table = (tmp_path / "matrix.md").read_text(encoding="utf-8")
    assert table == out.stdout
    lines = table.splitlines()
    assert len(lines) == 4
    dart_travel = hyq.stats.text(hyq.stats.mean_ci(travel["dart"]), digits=2)
    assert lines[2].startswith(f"| dart + mujoco | {hyq.stats.text(hyq.stats.mean_ci(travel['rapier']), digits=2)} "
                               f"| **{dart_travel}** |")
    assert f"rapier {hyq.stats.text(expected)}" in lines[2]
    assert "| 0 [0, 49] / 1 [5, 70] / 2 [15, 85] |" in lines[2]
    assert "2.50 min, 200000 steps (load 0.4-1.2)" in lines[2]
    assert "none held out" in lines[3]


def test_bad_rows_and_missing_reports_are_refused_in_one_line(tmp_path):
    for rows in ["bullet", "rapier+rapier", "", "rapier+"]:
        out = run("--out", str(tmp_path), "--rows", rows, "--table-only")
        assert out.returncode != 0 and out.stderr.strip().startswith("error: --rows"), (rows, out.stderr)
        assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    out = run("--out", str(tmp_path), "--rows", "rapier", "--table-only")
    assert out.returncode != 0 and out.stderr.strip().startswith(f"error: {tmp_path / 'rapier'}"), out.stderr
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
