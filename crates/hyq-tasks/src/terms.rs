//! The reward terms, each a pure function of explicit numbers, unscaled (the scales and the
//! sum are [`crate::step`]'s). Vectors are in the trunk's frame unless said otherwise.
//!
//! | term | value | anchor |
//! |---|---|---|
//! | `tracking_lin_vel` | exp(−‖c_xy − v_xy‖² / σ) | both |
//! | `tracking_ang_vel` | exp(−(c_yaw − ω_z)² / σ) | both |
//! | `lin_vel_z` | v_z² | both |
//! | `ang_vel_xy` | ω_x² + ω_y² | both |
//! | `orientation` | g_x² + g_y², g the projected gravity | both |
//! | `torques` | Σ τ² | legged_gym |
//! | `torques_abs` | ‖τ‖ + Σ\|τ\| | Playground |
//! | `joint_acc` | Σ ((q̇ − q̇_prev) / Δt)² | legged_gym |
//! | `action_rate` | Σ (a − a_prev)² | both |
//! | `feet_air_time` | Σ (t_air − t_min) over feet touching down, if moving | both |
//! | `foot_slip` | Σ ‖v_foot,xy‖² over feet in contact, if moving | Playground |
//! | `stand_still` | Σ \|q − q₀\|, if standing | both |
//! | `joint_limits` | Σ max(0, q_lo − q) + max(0, q − q_hi) over the soft limits | both |
//! | `termination` | 1 on a terminating step | both |
//! | `base_height` | (h − h_target)², h the trunk's height above the ground | legged_gym |
//! | `collision` | the number of penalised bodies touching the ground | legged_gym |
//! | `goal_heading` | the angle between the trunk's heading and the bearing to the goal | (the reach's) |
//! | `goal_line` | the trunk's distance from the line through the start and the goal | (the reach's) |
//! | `goal_line_approach` | how fast that distance falls: (d_prev − d) / Δt | (the reach's) |
//!
//! "Moving" and "standing" compare the command's norm with the preset's gate.

/// exp(−err²/σ): 1 for a perfect follower, in (0, 1] for any finite error, 0 only when the
/// squared error overflows.
pub fn tracking(err_sq: f64, sigma: f64) -> f64 {
    (-err_sq / sigma).exp()
}

/// The forward/sideways tracking term: exp(−‖c − v‖²/σ), `command` and `velocity` the xy parts.
pub fn tracking_lin_vel(command: [f64; 2], velocity: [f64; 2], sigma: f64) -> f64 {
    let e = [command[0] - velocity[0], command[1] - velocity[1]];
    tracking(e[0] * e[0] + e[1] * e[1], sigma)
}

/// The yaw-rate tracking term: exp(−(c − ω_z)²/σ).
pub fn tracking_ang_vel(command: f64, yaw_rate: f64, sigma: f64) -> f64 {
    let e = command - yaw_rate;
    tracking(e * e, sigma)
}

/// v_z², the trunk's vertical speed squared (m²/s²).
pub fn lin_vel_z(v_z: f64) -> f64 {
    v_z * v_z
}

/// ω_x² + ω_y², the trunk's roll and pitch rates squared.
pub fn ang_vel_xy(omega: [f64; 3]) -> f64 {
    omega[0] * omega[0] + omega[1] * omega[1]
}

/// g_x² + g_y²: how far the trunk is from level (0 level, 1 on its side).
pub fn orientation(projected_gravity: [f64; 3]) -> f64 {
    projected_gravity[0].powi(2) + projected_gravity[1].powi(2)
}

/// Σ x², the sum of squares.
pub fn sum_sq(xs: &[f64]) -> f64 {
    xs.iter().map(|x| x * x).sum()
}

/// Σ τ² (N²·m²).
pub fn torques(tau: &[f64]) -> f64 {
    sum_sq(tau)
}

/// Playground's ‖τ‖ + Σ|τ| (N·m).
pub fn torques_abs(tau: &[f64]) -> f64 {
    sum_sq(tau).sqrt() + tau.iter().map(|t| t.abs()).sum::<f64>()
}

/// Σ ((q̇ − q̇_prev) / Δt)², the joint accelerations squared.
pub fn joint_acc(qd: &[f64], qd_prev: &[f64], dt: f64) -> f64 {
    qd.iter()
        .zip(qd_prev)
        .map(|(a, b)| ((a - b) / dt).powi(2))
        .sum()
}

/// Σ (a − a_prev)², the action's change squared.
pub fn action_rate(action: &[f64], previous: &[f64]) -> f64 {
    action
        .iter()
        .zip(previous)
        .map(|(a, b)| (a - b).powi(2))
        .sum()
}

/// Σ (t_air − `threshold`) over the feet that touched down this step (`air_at_touchdown`
/// holds the air time of a foot touching down, 0 for every other), if `moving`.
pub fn feet_air_time(air_at_touchdown: &[f64], threshold: f64, moving: bool) -> f64 {
    if !moving {
        return 0.0;
    }
    air_at_touchdown
        .iter()
        .filter(|t| **t > 0.0)
        .map(|t| t - threshold)
        .sum()
}

/// Σ ‖v_foot,xy‖² over the feet in contact (world frame, m²/s²), if `moving`.
pub fn foot_slip(foot_velocity_xy: &[[f64; 2]], contact: &[bool], moving: bool) -> f64 {
    if !moving {
        return 0.0;
    }
    foot_velocity_xy
        .iter()
        .zip(contact)
        .filter(|(_, c)| **c)
        .map(|(v, _)| v[0] * v[0] + v[1] * v[1])
        .sum()
}

/// Σ |q − q₀| (rad), if `standing` (the command's norm is below the gate), else 0.
pub fn stand_still(q: &[f64], standing_pose: &[f64], standing: bool) -> f64 {
    if !standing {
        return 0.0;
    }
    q.iter()
        .zip(standing_pose)
        .map(|(a, b)| (a - b).abs())
        .sum()
}

/// A joint's soft limits: its range shrunk about its middle by `factor` in (0, 1]
/// (legged_gym's `soft_dof_pos_limit`, Playground's `soft_joint_pos_limit_factor`).
pub fn soft_limits(lower: f64, upper: f64, factor: f64) -> [f64; 2] {
    let mid = 0.5 * (lower + upper);
    let half = 0.5 * (upper - lower) * factor;
    [mid - half, mid + half]
}

/// Σ max(0, q_lo − q) + max(0, q − q_hi) over `soft` limits (rad): how far joints are past
/// them.
pub fn joint_limits(q: &[f64], soft: &[[f64; 2]]) -> f64 {
    q.iter()
        .zip(soft)
        .map(|(q, [lo, hi])| (lo - q).max(0.0) + (q - hi).max(0.0))
        .sum()
}

/// (h − `target`)², the trunk's height above the ground `height` off its target (m²).
pub fn base_height(height: f64, target: f64) -> f64 {
    (height - target).powi(2)
}

/// How many of the penalised bodies touch the ground (legged_gym's `collision`, which counts
/// the bodies whose contact force exceeds 0.1 N; here a body's contact flag).
pub fn collision(contacts: &[bool]) -> f64 {
    contacts.iter().map(|c| f64::from(u8::from(*c))).sum()
}

/// The angle (rad, in [0, π]) between the trunk's `heading` and the direction from the trunk
/// at `trunk` to `goal`, all horizontal (world x and y): 0 when the trunk faces the goal. A zero
/// heading (the trunk's x axis vertical) or a trunk on the goal leaves no angle: 0.
pub fn goal_heading(trunk: [f64; 2], heading: [f64; 2], goal: [f64; 2]) -> f64 {
    let to_goal = [goal[0] - trunk[0], goal[1] - trunk[1]];
    let cross = heading[0] * to_goal[1] - heading[1] * to_goal[0];
    let dot = heading[0] * to_goal[0] + heading[1] * to_goal[1];
    if cross == 0.0 && dot == 0.0 {
        // atan2 of two signed zeros may be ±π.
        return 0.0;
    }
    cross.atan2(dot).abs()
}

/// The horizontal distance (m) from `trunk` to the line through `start` and `goal` (world x and
/// y): how far the trunk is off the straight walk from its start to the goal. A goal straight
/// above the start leaves no line: the horizontal distance from the start.
pub fn goal_line(start: [f64; 2], goal: [f64; 2], trunk: [f64; 2]) -> f64 {
    let line = [goal[0] - start[0], goal[1] - start[1]];
    let off = [trunk[0] - start[0], trunk[1] - start[1]];
    let length = line[0].hypot(line[1]);
    if length == 0.0 {
        return off[0].hypot(off[1]);
    }
    ((line[0] * off[1] - line[1] * off[0]) / length).abs()
}

/// How fast the trunk closes on the start–goal line (m/s): the step's fall of the distance
/// [`goal_line`] gives, `previous` (the previous step's, 0 after reset: the trunk starts on the
/// line) minus `now`, over `dt`. Positive towards the line, negative away; over an episode it
/// sums, times Δt, to −(the final distance), whatever the path.
pub fn goal_line_approach(previous: f64, now: f64, dt: f64) -> f64 {
    (previous - now) / dt
}
