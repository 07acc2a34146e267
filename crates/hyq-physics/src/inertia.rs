//! Rigid-body mass properties: validation and the lumping of bodies joined by fixed joints.
//!
//! An inertia tensor `I` (about the centre of mass) is physically valid when it is symmetric,
//! positive semi-definite, and its principal moments `a, b, c` satisfy the triangle inequality
//! `a + b ≥ c` (for every ordering). A moving body additionally needs a positive mass and a
//! positive definite tensor, or its dynamics cannot be solved.
//!
//! Lumping (parallel-axis theorem): bodies `i` with mass `mᵢ`, centre of mass `cᵢ` and tensor
//! `Iᵢ` (expressed in a common frame) combine into `m = Σ mᵢ`, `c = Σ mᵢ cᵢ / m`,
//! `I = Σ [Iᵢ + mᵢ (‖dᵢ‖² E − dᵢ dᵢᵀ)]` with `dᵢ = cᵢ − c`.

use nalgebra::{Matrix3, Vector3};

/// Mass properties of a rigid body in some frame: mass (kg), centre of mass (m) and the inertia
/// tensor about the centre of mass, with the frame's axes (kg·m²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass (m).
    pub com: Vector3<f64>,
    /// Inertia tensor about the centre of mass (kg·m²).
    pub inertia: Matrix3<f64>,
}

impl MassProperties {
    /// No mass at all (the neutral element of [`MassProperties::combine`]).
    pub fn zero() -> Self {
        Self {
            mass: 0.0,
            com: Vector3::zeros(),
            inertia: Matrix3::zeros(),
        }
    }

    /// Combines two bodies given in the same frame (parallel-axis theorem).
    pub fn combine(&self, other: &Self) -> Self {
        let mass = self.mass + other.mass;
        if mass <= 0.0 {
            return Self::zero();
        }
        let com = (self.com * self.mass + other.com * other.mass) / mass;
        let shifted = |p: &Self| {
            let d = p.com - com;
            p.inertia + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * p.mass
        };
        Self {
            mass,
            com,
            inertia: shifted(self) + shifted(other),
        }
    }
}

/// Relative tolerance of the validity checks, against the largest principal moment: the URDF's
/// figures are rounded to a few digits, so exact equality cannot be demanded.
const RELATIVE_TOLERANCE: f64 = 1e-9;

/// Checks that `inertia` is a valid inertia tensor; `definite` also requires it to be
/// invertible (a moving body). Returns the reason, with the numbers, when it is not.
pub fn check_inertia(inertia: &Matrix3<f64>, definite: bool) -> Result<(), String> {
    if inertia.iter().any(|v| !v.is_finite()) {
        return Err(format!(
            "non-finite tensor entry in {:?}",
            inertia.as_slice()
        ));
    }
    let asymmetry = (inertia - inertia.transpose()).abs().max();
    let scale = inertia.abs().max();
    if asymmetry > RELATIVE_TOLERANCE * scale.max(f64::MIN_POSITIVE) {
        return Err(format!("tensor is not symmetric (asymmetry {asymmetry:e})"));
    }
    let mut moments: [f64; 3] = inertia.symmetric_eigenvalues().into();
    moments.sort_by(f64::total_cmp);
    let [a, b, c] = moments;
    let tol = RELATIVE_TOLERANCE * c.abs().max(f64::MIN_POSITIVE);
    if a < -tol {
        return Err(format!(
            "tensor is not positive semi-definite (principal moments {a:e}, {b:e}, {c:e} kg·m²)"
        ));
    }
    if definite && a <= 0.0 {
        return Err(format!(
            "tensor of a moving body must be positive definite (principal moments {a:e}, {b:e}, {c:e} kg·m²)"
        ));
    }
    if a + b < c - tol {
        return Err(format!(
            "principal moments {a:e}, {b:e}, {c:e} kg·m² violate the triangle inequality \
             ({a:e} + {b:e} < {c:e})"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    //! Validity rules and the parallel-axis combination on textbook cases.
    use super::*;

    #[test]
    fn valid_tensors_pass() {
        check_inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0)), true)
            .expect("a + b = c is on the boundary and valid");
        check_inertia(&Matrix3::zeros(), false).expect("a point mass is a valid part");
    }

    #[test]
    fn invalid_tensors_fail_with_the_numbers() {
        let triangle = check_inertia(&Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 3.0)), false)
            .expect_err("1 + 1 < 3");
        assert!(triangle.contains("triangle"), "{triangle}");
        let negative = check_inertia(
            &Matrix3::from_diagonal(&Vector3::new(-1.0, 2.0, 2.0)),
            false,
        )
        .expect_err("negative moment");
        assert!(negative.contains("semi-definite"), "{negative}");
        let singular = check_inertia(&Matrix3::zeros(), true).expect_err("a moving body");
        assert!(singular.contains("positive definite"), "{singular}");
        let mut asym = Matrix3::identity();
        asym[(0, 1)] = 0.5;
        assert!(
            check_inertia(&asym, false)
                .expect_err("asymmetric")
                .contains("symmetric")
        );
    }

    #[test]
    fn combine_uses_the_parallel_axis_theorem() {
        let a = MassProperties {
            mass: 1.0,
            com: Vector3::new(-1.0, 0.0, 0.0),
            inertia: Matrix3::zeros(),
        };
        let b = MassProperties {
            com: Vector3::new(1.0, 0.0, 0.0),
            ..a
        };
        let c = a.combine(&b);
        assert_eq!(c.mass, 2.0);
        assert_eq!(c.com, Vector3::zeros());
        // Two unit point masses 1 m from the centre on x: I = diag(0, 2, 2).
        assert!(
            (c.inertia - Matrix3::from_diagonal(&Vector3::new(0.0, 2.0, 2.0)))
                .abs()
                .max()
                < 1e-15
        );
        assert_eq!(
            MassProperties::zero().combine(&MassProperties::zero()),
            MassProperties::zero()
        );
    }
}
