//! Spec §3's observation table as data: [`SPEC_TABLE`], the spec's 39 rows verbatim, and the
//! [`ObservationRow`] each is. A file of its own, importing nothing of the crate, so that both
//! [`crate::observation`] (which lays the rows out for any robot) and [`crate::robot`] (which
//! reads HyQ's joint ranges from them) can use it without importing each other.

use std::borrow::Cow;

/// One row of the observation: its index, name, declared bounds and whether the bounds are only
/// estimates (the spec's `*`).
#[derive(Clone, Debug, PartialEq)]
pub struct ObservationRow {
    /// The row's position in the observation vector.
    pub index: usize,
    /// The row's name, e.g. `"lf_haa_angle"`.
    pub name: Cow<'static, str>,
    /// The declared lower bound.
    pub min: f64,
    /// The declared upper bound.
    pub max: f64,
    /// True where the spec marks the range `*` "Actual range unknown, only estimated" (rows
    /// 33–38: trunk acceleration and position).
    pub estimated: bool,
}

const fn row(
    index: usize,
    name: &'static str,
    min: f64,
    max: f64,
    estimated: bool,
) -> ObservationRow {
    ObservationRow {
        index,
        name: Cow::Borrowed(name),
        min,
        max,
        estimated,
    }
}

/// The spec's §3 table verbatim: 39 rows of index, name, min, max and the estimated-range flag
/// (a `static`, so that every reader borrows the one copy).
pub static SPEC_TABLE: [ObservationRow; 39] = [
    row(0, "lf_haa_angle", -1.22173, 0.436332, false),
    row(1, "lf_hfe_angle", -0.872665, 1.22173, false),
    row(2, "lf_kfe_angle", -2.44346, -0.349066, false),
    row(3, "lh_haa_angle", -1.22173, 0.436332, false),
    row(4, "lh_hfe_angle", -1.22173, 0.872665, false),
    row(5, "lh_kfe_angle", 0.349066, 2.44346, false),
    row(6, "rf_haa_angle", -1.22173, 0.436332, false),
    row(7, "rf_hfe_angle", -0.872665, 1.22173, false),
    row(8, "rf_kfe_angle", -2.44346, -0.349066, false),
    row(9, "rh_haa_angle", -1.22173, 0.436332, false),
    row(10, "rh_hfe_angle", -1.22173, 0.872665, false),
    row(11, "rh_kfe_angle", 0.349066, 2.44346, false),
    row(12, "lf_haa_speed", -12.0, 12.0, false),
    row(13, "lf_hfe_speed", -12.0, 12.0, false),
    row(14, "lf_kfe_speed", -12.0, 12.0, false),
    row(15, "lh_haa_speed", -12.0, 12.0, false),
    row(16, "lh_hfe_speed", -12.0, 12.0, false),
    row(17, "lh_kfe_speed", -12.0, 12.0, false),
    row(18, "rf_haa_speed", -12.0, 12.0, false),
    row(19, "rf_hfe_speed", -12.0, 12.0, false),
    row(20, "rf_kfe_speed", -12.0, 12.0, false),
    row(21, "rh_haa_speed", -12.0, 12.0, false),
    row(22, "rh_hfe_speed", -12.0, 12.0, false),
    row(23, "rh_kfe_speed", -12.0, 12.0, false),
    row(24, "lf_contact_flag", 0.0, 1.0, false),
    row(25, "lh_contact_flag", 0.0, 1.0, false),
    row(26, "rf_contact_flag", 0.0, 1.0, false),
    row(27, "rh_contact_flag", 0.0, 1.0, false),
    row(28, "trunk_contact_flag", 0.0, 1.0, false),
    row(29, "trunk_rotation_w", -1.0, 1.0, false),
    row(30, "trunk_rotation_x", -1.0, 1.0, false),
    row(31, "trunk_rotation_y", -1.0, 1.0, false),
    row(32, "trunk_rotation_z", -1.0, 1.0, false),
    row(33, "trunk_accel_x", -50.0, 50.0, true),
    row(34, "trunk_accel_y", -50.0, 50.0, true),
    row(35, "trunk_accel_z", -50.0, 50.0, true),
    row(36, "trunk_position_x", -10.0, 10.0, true),
    row(37, "trunk_position_y", -10.0, 10.0, true),
    row(38, "trunk_position_z", 0.0, 1.0, true),
];
