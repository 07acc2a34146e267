//! Spec §1 (Nomenclature, Table 2 and Figure 1): HyQ's legs, joint kinds and joint order.
//!
//! Legs are `lf, lh, rf, rh` (left front, left hind, right front, right hind); each leg has
//! three joints `haa, hfe, kfe` (hip abduction/adduction, hip flexion/extension, knee
//! flexion/extension). The spec order of the twelve joints (spec §1, the order of the §3
//! table's rows 0–11 and 12–23) is leg-major:
//!
//! `lf_haa, lf_hfe, lf_kfe, lh_haa, lh_hfe, lh_kfe, rf_haa, rf_hfe, rf_kfe, rh_haa, rh_hfe, rh_kfe`
//!
//! These names are HyQ's. The rules in this crate never depend on them: they take a robot
//! description (slices of joints and feet), so another robot reuses them with its own names.
//! HyQ-specific code (the robot description, its tests) uses these types to spell HyQ's joints.

use std::fmt;

/// One of HyQ's four legs (spec Table 2), in the spec's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Leg {
    /// `lf`: left front.
    LeftFront,
    /// `lh`: left hind.
    LeftHind,
    /// `rf`: right front.
    RightFront,
    /// `rh`: right hind.
    RightHind,
}

impl Leg {
    /// The four legs in the spec's order: `lf, lh, rf, rh`.
    pub const ALL: [Leg; 4] = [
        Leg::LeftFront,
        Leg::LeftHind,
        Leg::RightFront,
        Leg::RightHind,
    ];

    /// The spec's short form (`"lf"`, `"lh"`, `"rf"`, `"rh"`), also the foot's name in the §3
    /// contact rows (`lf_contact_flag`).
    pub const fn short_name(self) -> &'static str {
        match self {
            Leg::LeftFront => "lf",
            Leg::LeftHind => "lh",
            Leg::RightFront => "rf",
            Leg::RightHind => "rh",
        }
    }

    /// Whether this is a front leg (its knee range is negative in the §3 table).
    pub const fn is_front(self) -> bool {
        matches!(self, Leg::LeftFront | Leg::RightFront)
    }
}

impl fmt::Display for Leg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.short_name())
    }
}

/// One of the three joint kinds of a HyQ leg (spec Table 2), in the spec's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum JointKind {
    /// `haa`: hip abduction/adduction.
    Haa,
    /// `hfe`: hip flexion/extension.
    Hfe,
    /// `kfe`: knee flexion/extension.
    Kfe,
}

impl JointKind {
    /// The three joint kinds in the spec's order: `haa, hfe, kfe`.
    pub const ALL: [JointKind; 3] = [JointKind::Haa, JointKind::Hfe, JointKind::Kfe];

    /// The spec's short form: `"haa"`, `"hfe"` or `"kfe"`.
    pub const fn short_name(self) -> &'static str {
        match self {
            JointKind::Haa => "haa",
            JointKind::Hfe => "hfe",
            JointKind::Kfe => "kfe",
        }
    }
}

impl fmt::Display for JointKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.short_name())
    }
}

/// One of HyQ's twelve actuated joints: a leg and a joint kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct HyqJoint {
    /// The leg the joint belongs to.
    pub leg: Leg,
    /// Which of the leg's three joints it is.
    pub kind: JointKind,
}

/// The names of HyQ's joints in the spec's order, indexed like [`HyqJoint::ALL`].
const HYQ_JOINT_NAMES: [&str; 12] = [
    "lf_haa", "lf_hfe", "lf_kfe", "lh_haa", "lh_hfe", "lh_kfe", "rf_haa", "rf_hfe", "rf_kfe",
    "rh_haa", "rh_hfe", "rh_kfe",
];

impl HyqJoint {
    /// HyQ's twelve joints in the spec's order (leg-major: `lf_haa, lf_hfe, lf_kfe, lh_haa, …`).
    pub const ALL: [HyqJoint; 12] = {
        let mut all = [HyqJoint {
            leg: Leg::LeftFront,
            kind: JointKind::Haa,
        }; 12];
        let mut i = 0;
        while i < 12 {
            all[i] = HyqJoint {
                leg: Leg::ALL[i / 3],
                kind: JointKind::ALL[i % 3],
            };
            i += 1;
        }
        all
    };

    /// The joint's position in the spec order (0 for `lf_haa` … 11 for `rh_kfe`): its row in
    /// the §3 table's angle block, and its index in actions and joint limits.
    pub const fn index(self) -> usize {
        self.leg as usize * 3 + self.kind as usize
    }

    /// The spec's name of the joint, `"<leg>_<kind>"` (e.g. `"lf_haa"`). The URDF's joint is
    /// this name followed by `_joint`.
    pub const fn name(self) -> &'static str {
        HYQ_JOINT_NAMES[self.index()]
    }

    /// The joint with the spec name `name` (e.g. `"rh_kfe"`), if there is one.
    pub fn from_name(name: &str) -> Option<HyqJoint> {
        HYQ_JOINT_NAMES
            .iter()
            .position(|n| *n == name)
            .map(|i| HyqJoint::ALL[i])
    }
}

impl fmt::Display for HyqJoint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spec_order_is_leg_major_as_printed_in_rulings() {
        let printed = [
            "lf_haa", "lf_hfe", "lf_kfe", "lh_haa", "lh_hfe", "lh_kfe", "rf_haa", "rf_hfe",
            "rf_kfe", "rh_haa", "rh_hfe", "rh_kfe",
        ];
        for (i, joint) in HyqJoint::ALL.iter().enumerate() {
            assert_eq!(joint.index(), i);
            assert_eq!(joint.name(), printed[i]);
            assert_eq!(
                joint.name(),
                format!("{}_{}", joint.leg.short_name(), joint.kind.short_name())
            );
            assert_eq!(HyqJoint::from_name(printed[i]), Some(*joint));
        }
        assert_eq!(HyqJoint::from_name("lf_foot"), None);
    }

    #[test]
    fn only_lf_and_rf_are_front_legs() {
        let front: Vec<_> = Leg::ALL
            .iter()
            .filter(|l| l.is_front())
            .map(|l| l.short_name())
            .collect();
        assert_eq!(front, ["lf", "rf"]);
    }
}
