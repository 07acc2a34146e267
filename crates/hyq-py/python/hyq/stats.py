"""Interval estimates for judging a policy from a handful of episodes, computed by the Rust
crate hyq-stats (the code ``hyq compare --policy`` uses), in the shape its ``report.json``
gives every estimate::

    import hyq.stats

    hyq.stats.mean_ci([4.1, 3.8, 4.4], seed=0)  # {"mean": 4.1, "ci95": [3.8, 4.4]}
    hyq.stats.wilson(3, 20)                     # {"mean": 0.15, "ci95": [...], "k": 3, "n": 20}
    hyq.stats.ratio_of_means(b, a, seed=0)      # {"mean": ..., "ci95": [...], "excludes_one": ...}

``mean_ci`` is the mean with its 95 % percentile-bootstrap interval (10,000 resamples drawn from
ChaCha8 seeded with ``seed``: the same values and seed give the same interval bit for bit);
``wilson`` a rate of k successes in n trials with its Wilson 95 % interval; ``ratio_of_means``
the ratio of two means with its bootstrap interval, resampled as pairs by default (episode k of
both samples started alike). Empty input, a value that is not a finite number, k > n or a
denominator whose mean can be 0 raise ``ValueError`` naming what was wrong.
"""

from collections.abc import Iterable

from hyq import _core

#: Bootstrap resamples per interval.
RESAMPLES: int = _core.STATS_RESAMPLES


def _floats(values: Iterable[float], name: str) -> list[float]:
    try:
        return [float(v) for v in values]
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name}: a sequence of numbers is needed ({e})") from None


def _seed(seed: int) -> int:
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**64:
        raise ValueError(f"seed must be an integer in [0, 2**64), got {seed!r}")
    return seed


def mean_ci(values: Iterable[float], seed: int = 0) -> dict:
    """The mean of ``values`` with its 95 % bootstrap interval: ``{"mean", "ci95": [lo, hi]}``."""
    mean, lo, hi = _core.stats_mean_ci(_floats(values, "values"), _seed(seed))
    return {"mean": mean, "ci95": [lo, hi]}


def wilson(k: int, n: int) -> dict:
    """k of n with its Wilson 95 % interval: ``{"mean": k/n, "ci95": [lo, hi], "k", "n"}``."""
    for name, v in (("k", k), ("n", n)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 0:
            raise ValueError(f"{name} must be a non-negative integer, got {v!r}")
    rate, lo, hi = _core.stats_wilson(k, n)
    return {"mean": rate, "ci95": [lo, hi], "k": k, "n": n}


def ratio_of_means(
    numerator: Iterable[float],
    denominator: Iterable[float],
    seed: int = 0,
    paired: bool = True,
) -> dict:
    """The ratio of the means with its 95 % bootstrap interval:
    ``{"mean", "ci95": [lo, hi], "excludes_one"}``."""
    ratio, lo, hi, excludes_one = _core.stats_ratio_of_means(
        _floats(numerator, "numerator"),
        _floats(denominator, "denominator"),
        bool(paired),
        _seed(seed),
    )
    return {"mean": ratio, "ci95": [lo, hi], "excludes_one": excludes_one}


def text(estimate: dict, digits: int = 3) -> str:
    """``"4.100 [3.800, 4.400]"``; a rate (with ``k`` and ``n``) as ``"3/20 [5 %, 36 %]"``."""
    lo, hi = estimate["ci95"]
    if "k" in estimate:
        return f"{estimate['k']}/{estimate['n']} [{100 * lo:.0f} %, {100 * hi:.0f} %]"
    return f"{estimate['mean']:.{digits}f} [{lo:.{digits}f}, {hi:.{digits}f}]"
