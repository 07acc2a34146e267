"""The paired change of a figure between two `hyq compare --policy` reports of the same episodes.

    python examples/paired_change.py BEFORE/report.json AFTER/report.json [--figure travel_m]

Both reports must come from the same policy, engines, `--seed` and `--episodes`, so that episode
k of one starts from the same reset as episode k of the other. For each engine it prints the mean
of (after − before) over the episode pairs with its 95 % bootstrap interval (`hyq.stats.mean_ci`,
seeded, so the same reports print the same lines). A paired interval is narrower than the two
reports' intervals side by side, because the episodes' shared starts cancel.
"""

from __future__ import annotations

import argparse
import json
import sys

import hyq.stats


def episodes(path: str) -> dict[str, list[dict]]:
    """Each engine's per-episode rows of a report.json, by the engine's label."""
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
        return {side["label"]: side["episodes"] for side in report["sides"]}
    except (OSError, ValueError, KeyError, TypeError) as err:
        raise SystemExit(f"error: {path}: not a `hyq compare --policy` report.json ({err})") from None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--figure", default="travel_m", help="a per-episode key (default: travel_m)")
    args = parser.parse_args()
    before, after = episodes(args.before), episodes(args.after)
    if before.keys() != after.keys():
        raise SystemExit(f"error: the reports cover different engines: {sorted(before)} and {sorted(after)}")
    for label, rows in before.items():
        other = after[label]
        if len(rows) != len(other):
            raise SystemExit(f"error: {label}: {len(rows)} episodes before, {len(other)} after")
        try:
            diffs = [b[args.figure] - a[args.figure] for a, b in zip(rows, other)]
        except KeyError:
            raise SystemExit(f"error: --figure {args.figure}: not a per-episode key of the reports") from None
        change = hyq.stats.mean_ci(diffs)
        lo, hi = change["ci95"]
        print(f"{label}: {args.figure} after - before {change['mean']:+.3f} [{lo:+.3f}, {hi:+.3f}] "
              f"({len(diffs)} pairs)")


if __name__ == "__main__":
    sys.exit(main())
