//! Spec §1 Table 1 (D^i, D_n^i) and §4.2 step 1 (K), as spec §1 rules:
//!
//! - D^t   = ‖G − C^t‖, the Euclidean distance (metres, all three axes) from the trunk centre
//!   after env step t to the goal G;
//! - K     = ‖G − C^0‖, the distance from the initial position to the goal;
//! - D_n^t = D^t / K, the normalised distance (1 at the start, 0 at the goal).
//!
//! K divides D^t, so a goal at (or numerically at) the start is an error when a reward that needs
//! D_n is on (spec §1), never a division by zero: [`StartGoalDistance`] holds a K that is safe
//! to divide by.

use nalgebra::Point3;

/// The smallest K = ‖G − C^0‖ accepted, in metres (10⁻⁶ m, a thousandth of the default
/// `accepted_error`).
///
/// Below it D_n = D / K amplifies the rounding of the positions (about 10⁻¹⁵ m at 10 m from the
/// origin) past 10⁻⁹, and such a goal lies inside any sensible reach cube at reset anyway.
pub const MIN_START_GOAL_DISTANCE: f64 = 1e-6;

/// D = ‖G − C‖, the Euclidean distance from `position` to `goal`, in metres.
pub fn distance_to_goal(position: &Point3<f64>, goal: &Point3<f64>) -> f64 {
    (goal - position).norm()
}

/// K = ‖G − C^0‖, checked to be finite and at least [`MIN_START_GOAL_DISTANCE`], so dividing by
/// it is always safe.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StartGoalDistance(f64);

impl StartGoalDistance {
    /// K for an episode starting at `initial` with goal `goal`, or `None` when it is not finite
    /// or shorter than [`MIN_START_GOAL_DISTANCE`].
    pub fn new(initial: &Point3<f64>, goal: &Point3<f64>) -> Option<Self> {
        Self::from_metres(distance_to_goal(initial, goal))
    }

    /// K given directly in metres, or `None` when it is not finite or shorter than
    /// [`MIN_START_GOAL_DISTANCE`] (NaN included).
    pub fn from_metres(k: f64) -> Option<Self> {
        (k.is_finite() && k >= MIN_START_GOAL_DISTANCE).then_some(StartGoalDistance(k))
    }

    /// K in metres.
    pub fn metres(self) -> f64 {
        self.0
    }

    /// D_n = D / K for a distance `d` in metres.
    pub fn normalise(self, d: f64) -> f64 {
        d / self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_is_euclidean_over_all_three_axes() {
        let d = distance_to_goal(&Point3::new(1.0, 2.0, 3.0), &Point3::new(4.0, 6.0, 15.0));
        assert_eq!(d, 13.0);
    }

    #[test]
    fn k_must_be_finite_and_not_too_small() {
        let start = Point3::new(0.0, 0.0, 0.5);
        assert_eq!(StartGoalDistance::new(&start, &start), None);
        assert_eq!(
            StartGoalDistance::from_metres(MIN_START_GOAL_DISTANCE * 0.999),
            None
        );
        assert_eq!(StartGoalDistance::from_metres(f64::NAN), None);
        assert_eq!(StartGoalDistance::from_metres(f64::INFINITY), None);
        let k =
            StartGoalDistance::from_metres(MIN_START_GOAL_DISTANCE).map(StartGoalDistance::metres);
        assert_eq!(k, Some(MIN_START_GOAL_DISTANCE));
        let k = StartGoalDistance::new(&start, &Point3::new(5.0, 0.0, 0.5));
        assert_eq!(k.map(|k| k.normalise(2.5)), Some(0.5));
    }

    #[test]
    fn the_start_normalises_to_exactly_one() {
        let (start, goal) = (Point3::new(0.1, -0.3, 0.55), Point3::new(5.0, 0.2, 0.62));
        let k = StartGoalDistance::new(&start, &goal);
        assert_eq!(
            k.map(|k| k.normalise(distance_to_goal(&start, &goal))),
            Some(1.0)
        );
    }
}
