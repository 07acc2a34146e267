//! The statistics of the repetitions: medians, ratios taken within a repetition, and each
//! target's verdict.

use std::collections::BTreeMap;

use super::plan::Series;

/// The figures of one repetition (a series is absent when its run was skipped or failed).
pub type Rep = BTreeMap<Series, f64>;

/// The median, min and max of `values` (`None` when empty).
pub fn summary(values: &[f64]) -> Option<(f64, f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let median = if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    };
    Some((median, v[0], v[n - 1]))
}

/// The samples of `series` over the repetitions.
pub fn samples(reps: &[Rep], series: Series) -> Vec<f64> {
    reps.iter()
        .filter_map(|r| r.get(&series).copied())
        .collect()
}

/// The per-repetition ratios num / den, taken only within a repetition that has both.
pub fn ratios(reps: &[Rep], num: Series, den: Series) -> Vec<f64> {
    reps.iter()
        .filter_map(|r| Some(r.get(&num)? / r.get(&den)?))
        .collect()
}

/// What a target asks of a figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The ratio num / den must be at least `target`.
    RatioAtLeast {
        /// Numerator.
        num: Series,
        /// Denominator.
        den: Series,
        /// The bound.
        target: f64,
    },
    /// The series must be at most `target`.
    AtMost {
        /// The figure.
        series: Series,
        /// The bound.
        target: f64,
    },
}

/// One target of issue 7, with its label.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// What is compared.
    pub label: &'static str,
    /// The bound.
    pub goal: Goal,
}

/// The targets, in report order.
pub const TARGETS: [Target; 11] = [
    Target {
        label: "rapier / MuJoCo from Python",
        goal: Goal::RatioAtLeast {
            num: Series::Rapier,
            den: Series::MujocoPy,
            target: 1.0,
        },
    },
    Target {
        label: "rapier / MuJoCo C loop (stretch)",
        goal: Goal::RatioAtLeast {
            num: Series::Rapier,
            den: Series::MujocoC,
            target: 1.0,
        },
    },
    Target {
        label: "DART / DART from Python (Bullet)",
        goal: Goal::RatioAtLeast {
            num: Series::Dart,
            den: Series::DartPyBullet,
            target: 2.0,
        },
    },
    Target {
        label: "DART / DART from Python (ODE)",
        goal: Goal::RatioAtLeast {
            num: Series::Dart,
            den: Series::DartPyOde,
            target: 1.5,
        },
    },
    Target {
        label: "vector env N = 2: 2 threads / 1 thread",
        goal: Goal::RatioAtLeast {
            num: Series::Vec2,
            den: Series::Vec1,
            target: 1.9,
        },
    },
    Target {
        label: "vector env N = 2: CPU efficiency, 2 threads / 1 thread (load-independent proxy)",
        goal: Goal::RatioAtLeast {
            num: Series::Vec2Cpu,
            den: Series::Vec1Cpu,
            target: 0.95,
        },
    },
    Target {
        label: "spec evaluation share, rapier",
        goal: Goal::AtMost {
            series: Series::RapierSpecShare,
            target: 0.01,
        },
    },
    Target {
        label: "spec evaluation share, DART",
        goal: Goal::AtMost {
            series: Series::DartSpecShare,
            target: 0.01,
        },
    },
    Target {
        label: "MuJoCo backend / MuJoCo from Python",
        goal: Goal::RatioAtLeast {
            num: Series::Mujoco,
            den: Series::MujocoPy,
            target: 1.3,
        },
    },
    Target {
        label: "MuJoCo backend / MuJoCo from Python (stretch)",
        goal: Goal::RatioAtLeast {
            num: Series::Mujoco,
            den: Series::MujocoPy,
            target: 1.5,
        },
    },
    Target {
        label: "spec evaluation share, MuJoCo",
        goal: Goal::AtMost {
            series: Series::MujocoSpecShare,
            target: 0.01,
        },
    },
];

/// One evaluated target: its values (ratios or the series), their summary and the verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Median, min and max of the compared values (`None`: not measured).
    pub summary: Option<(f64, f64, f64)>,
    /// Whether the median meets the bound.
    pub met: Option<bool>,
    /// "met", "not met: …" or "not measured".
    pub text: String,
}

/// Evaluates `goal` on the repetitions (the verdict is taken on the median).
pub fn evaluate(reps: &[Rep], goal: Goal) -> Verdict {
    let values = match goal {
        Goal::RatioAtLeast { num, den, .. } => ratios(reps, num, den),
        Goal::AtMost { series, .. } => samples(reps, series),
    };
    let Some(s) = summary(&values) else {
        return Verdict {
            summary: None,
            met: None,
            text: "not measured".into(),
        };
    };
    let median = s.0;
    let (met, text) = match goal {
        Goal::RatioAtLeast { target, .. } => {
            if median >= target {
                (true, "met".to_string())
            } else {
                (
                    false,
                    format!(
                        "not met: {:.0} % of the target, {:.2}× short",
                        100.0 * median / target,
                        target / median
                    ),
                )
            }
        }
        Goal::AtMost { target, .. } => {
            if median <= target {
                (true, "met".to_string())
            } else {
                (
                    false,
                    format!(
                        "not met: {:.2} % against {:.2} %",
                        100.0 * median,
                        100.0 * target
                    ),
                )
            }
        }
    };
    Verdict {
        summary: Some(s),
        met: Some(met),
        text,
    }
}
