//! Spec §6.1 (Reach Goal): at the end of each step the trunk centre C is
//! inside the cube of side ε_reach (`accepted_error`) centred on the goal G, faces included:
//!
//! reached ⇔ |C_i − G_i| ≤ ε_reach / 2 for each of x, y and z.
//!
//! It is a cube, not a ball: the corner (ε/2, ε/2, ε/2) is reached, at a Euclidean distance
//! of ε·√3/2.

use nalgebra::Point3;

/// Whether `position` is inside the cube of side `accepted_error` (metres) centred on `goal`,
/// faces included.
pub fn goal_reached(position: &Point3<f64>, goal: &Point3<f64>, accepted_error: f64) -> bool {
    let half_side = 0.5 * accepted_error;
    (position - goal)
        .iter()
        .all(|offset| offset.abs() <= half_side)
}
