"""Invariant: `--eps-curriculum START:END:STEPS[:STAGES]` (examples/recipes.py) gives the
training envs' reach cube START in its first stage and END, to the bit, from STEPS env steps on,
in equal stages between; bad input is refused in one line."""

import pytest


def test_the_stages_run_from_start_to_end_at_steps(recipes):
    r = recipes
    c = r.eps_curriculum("0.5:0.1:600000")
    assert c == {"start": 0.5, "end": 0.1, "steps": 600000, "stages": 5}
    assert r.curriculum_stage(c, 0) == (0, 0.5)
    assert r.curriculum_stage(c, 149_999) == (0, 0.5)
    assert r.curriculum_stage(c, 150_000)[0] == 1
    assert r.curriculum_stage(c, 150_000)[1] == pytest.approx(0.4)
    assert r.curriculum_stage(c, 450_000)[1] == pytest.approx(0.2)
    # The last stage is the recipe's cube to the bit (0.5 + (0.1 - 0.5) is not 0.1).
    assert r.curriculum_stage(c, 599_999)[0] == 3
    assert r.curriculum_stage(c, 600_000) == (4, 0.1)
    assert r.curriculum_stage(c, 10**9) == (4, 0.1)
    sides = [r.curriculum_stage(c, t)[1] for t in range(0, 700_000, 1000)]
    assert all(a >= b for a, b in zip(sides, sides[1:]))


def test_two_stages_switch_once(recipes):
    r = recipes
    c = r.eps_curriculum("0.3:0.1:512:2")
    assert [r.curriculum_stage(c, t) for t in (0, 511, 512)] == [(0, 0.3), (0, 0.3), (1, 0.1)]


@pytest.mark.parametrize("text, says", [
    ("0.5:0.1", "expected START:END:STEPS[:STAGES]"),
    ("0.5:0.1:1e5", "expected START:END:STEPS[:STAGES]"),
    ("a:0.1:100", "expected START:END:STEPS[:STAGES]"),
    ("0.5:0.1:100:3:4", "expected START:END:STEPS[:STAGES]"),
    ("nan:0.1:100", "finite sides above 0 m"),
    ("0.5:inf:100", "finite sides above 0 m"),
    ("0.5:0:100", "finite sides above 0 m"),
    ("-0.5:0.1:100", "finite sides above 0 m"),
    ("0.5:0.1:0", "STEPS must be at least 1"),
    ("0.5:0.1:100:1", "STAGES at least 2"),
])
def test_bad_curricula_are_refused_in_one_line(recipes, text, says):
    with pytest.raises(SystemExit) as e:
        recipes.eps_curriculum(text)
    message = str(e.value)
    assert message.startswith(f"error: --eps-curriculum {text!r}: ") and says in message
    assert "\n" not in message
