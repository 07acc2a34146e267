"""Invariant: ``hyq.stats`` gives hyq-stats' estimates in report.json's shape: a mean's
bootstrap interval holds the mean, is seeded (the same values and seed give the same interval)
and narrows as 1/sqrt(n); a rate's Wilson interval stays in [0, 1] and matches the formula; a
ratio says whether its interval excludes 1; bad input is a ValueError naming what was wrong."""

import math
import random

import pytest

import hyq.stats


def test_a_mean_comes_with_a_seeded_interval_around_it():
    values = [4.1, 3.8, 4.4, 5.0, 3.2, 4.6]
    e = hyq.stats.mean_ci(values, seed=7)
    assert set(e) == {"mean", "ci95"}
    lo, hi = e["ci95"]
    assert e["mean"] == pytest.approx(sum(values) / len(values), abs=1e-12)
    assert min(values) <= lo < e["mean"] < hi <= max(values)
    assert hyq.stats.mean_ci(values, seed=7) == e
    assert hyq.stats.mean_ci(values, seed=8) != e
    # A constant sample's interval is the point.
    assert hyq.stats.mean_ci([2.5] * 4)["ci95"] == [2.5, 2.5]
    assert hyq.stats.text(e, 2) == f"{e['mean']:.2f} [{lo:.2f}, {hi:.2f}]"
    assert hyq.stats.RESAMPLES == 10_000


def test_the_interval_narrows_as_one_over_the_root_of_the_episodes():
    rng = random.Random(3)
    draw = [rng.gauss(4.0, 1.0) for _ in range(400)]
    for n in (25, 100, 400):
        values = draw[:n]
        lo, hi = hyq.stats.mean_ci(values, seed=1)["ci95"]
        mean = sum(values) / n
        sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
        # About 2 * 1.96 standard errors wide, the standard error being sd / sqrt(n).
        assert 3.3 < (hi - lo) / (sd / math.sqrt(n)) < 4.3, n


def test_a_rate_is_wilsons_interval_with_k_and_n():
    r = hyq.stats.wilson(3, 20)
    assert (r["mean"], r["k"], r["n"]) == (0.15, 3, 20)
    z = 1.959963984540054
    p, n = 0.15, 20
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    assert r["ci95"] == pytest.approx([centre - half, centre + half], abs=1e-12)
    assert hyq.stats.wilson(0, 20)["ci95"][0] == 0.0
    assert hyq.stats.wilson(20, 20)["ci95"][1] == 1.0
    assert hyq.stats.text(r) == "3/20 [5 %, 36 %]"


def test_a_ratio_says_whether_it_excludes_one():
    a = [2.0, 2.2, 1.8, 2.0]
    r = hyq.stats.ratio_of_means([2 * x for x in a], a, seed=3)
    assert (r["mean"], r["ci95"], r["excludes_one"]) == (2.0, [2.0, 2.0], True)
    same = hyq.stats.ratio_of_means(a, a, seed=3, paired=False)
    assert same["ci95"][0] <= 1.0 <= same["ci95"][1] and not same["excludes_one"]


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: hyq.stats.mean_ci([]), "no values"),
        (lambda: hyq.stats.mean_ci([1.0, float("nan")]), "value 1 is NaN"),
        (lambda: hyq.stats.mean_ci(["a"]), "values"),
        (lambda: hyq.stats.mean_ci([1.0], seed=-1), "seed"),
        (lambda: hyq.stats.wilson(5, 3), "more successes than trials"),
        (lambda: hyq.stats.wilson(0, 0), "0 trials"),
        (lambda: hyq.stats.wilson(-1, 3), "k must be"),
        (lambda: hyq.stats.ratio_of_means([1.0], [0.5, -0.5]), "different lengths"),
        (lambda: hyq.stats.ratio_of_means([1.0, 1.0], [0.5, -0.5]), "unbounded"),
    ],
)
def test_bad_input_is_a_value_error_naming_it(call, words):
    with pytest.raises(ValueError, match=words):
        call()
