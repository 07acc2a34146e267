// Changed by the hyq-env project (Apache-2.0 §4(b)); the changes: PATCHES.md at this crate's root.
//! The dense assembly of rapier 0.36.1, kept to test the patched one against: the body jacobians,
//! both augmented mass matrices, their (LU) factorizations and the free accelerations exactly as
//! rapier 0.36.1 computed them (its `update_body_jacobians`, `update_mass_matrix`,
//! `update_acceleration` and energy guard, renamed, factorizations returned instead of stored).

use super::{Force, Multibody, concat_rb_mass_matrix};
use crate::alloc_prelude::*;
use crate::dynamics::{RigidBodySet, RigidBodyVelocity};
use crate::math::{
    ANG_DIM, AngDim, DIM, DVector, Dim, Jacobian, Pose, Real, SPATIAL_DIM, SimdAngVector,
};
#[cfg(feature = "dim3")]
use crate::utils::mat_to_na;
use crate::utils::{AngularInertiaOps, CrossProduct, CrossProductMatrix, IndexMut2, vect_to_na};
use na::{DMatrix, Dyn, LU, OMatrix, SMatrix};

impl Multibody {
    pub(super) fn dense_update_body_jacobians(&mut self) {
        for i in 0..self.links.len() {
            let link = &self.links[i];

            if self.body_jacobians[i].ncols() != self.ndofs {
                // TODO: use a resize instead.
                self.body_jacobians[i] = Jacobian::zeros(self.ndofs);
            }

            let parent_to_world;

            if i != 0 {
                let parent_id = link.parent_internal_id;
                let parent_link = &self.links[parent_id];
                parent_to_world = parent_link.local_to_world;

                let (link_j, parent_j) = self.body_jacobians.index_mut_const(i, parent_id);
                link_j.copy_from(parent_j);

                {
                    let mut link_j_v = link_j.fixed_rows_mut::<DIM>(0);
                    let parent_j_w = parent_j.fixed_rows::<ANG_DIM>(DIM);

                    let shift_tr = vect_to_na(link.shift02).gcross_matrix_tr();
                    link_j_v.gemm(1.0, &shift_tr, &parent_j_w, 1.0);
                }
            } else {
                self.body_jacobians[i].fill(0.0);
                parent_to_world = Pose::IDENTITY;
            }

            let ndofs = link.joint.ndofs();
            let mut tmp = SMatrix::<Real, SPATIAL_DIM, SPATIAL_DIM>::zeros();
            let mut link_joint_j = tmp.columns_mut(0, ndofs);
            let mut link_j_part = self.body_jacobians[i].columns_mut(link.assembly_id, ndofs);
            link.joint.jacobian(
                &(parent_to_world.rotation * link.joint.data.local_frame1.rotation),
                &mut link_joint_j,
            );
            link_j_part += link_joint_j;

            {
                let link_j = &mut self.body_jacobians[i];
                let (mut link_j_v, link_j_w) =
                    link_j.rows_range_pair_mut(0..DIM, DIM..DIM + ANG_DIM);
                let shift_tr = vect_to_na(link.shift23).gcross_matrix_tr();
                link_j_v.gemm(1.0, &shift_tr, &link_j_w, 1.0);
            }
        }
    }

    pub(super) fn dense_update_mass_matrix(
        &mut self,
        dt: Real,
        bodies: &RigidBodySet,
    ) -> (LU<Real, Dyn, Dyn>, LU<Real, Dyn, Dyn>) {
        assert!(self.ndofs > 0, "no DoF to assemble");

        if self.augmented_mass.ncols() != self.ndofs {
            // TODO: do a resize instead of a full reallocation.
            self.augmented_mass = DMatrix::zeros(self.ndofs, self.ndofs);
            self.acc_augmented_mass = DMatrix::zeros(self.ndofs, self.ndofs);
        } else {
            self.augmented_mass.fill(0.0);
            self.acc_augmented_mass.fill(0.0);
        }

        self.augmented_mass_indices.clear();

        // Resize coriolis workspaces if the link count or number of DOFs change.
        let coriolis_ndofs = self.coriolis_v.first().map(|m| m.ncols());
        if self.coriolis_v.len() != self.links.len() || coriolis_ndofs != Some(self.ndofs) {
            self.coriolis_v = vec![OMatrix::<Real, Dim, Dyn>::zeros(self.ndofs); self.links.len()];
            self.coriolis_w =
                vec![OMatrix::<Real, AngDim, Dyn>::zeros(self.ndofs); self.links.len()];
            self.i_coriolis_dt = vec![Jacobian::zeros(self.ndofs); self.links.len()];
        }

        let mut curr_assembly_id = 0;

        for i in 0..self.links.len() {
            let link = &self.links[i];
            let rb = &bodies[link.rigid_body];
            let rb_mass = rb.mprops.effective_mass();
            let rb_inertia = rb.mprops.effective_angular_inertia().into_matrix();
            let body_jacobian = &self.body_jacobians[i];

            // NOTE: the mass matrix index reordering operates on the assumption that the assembly
            //       ids are traversed in order. This assert is here to ensure the assumption always
            //       hold.
            assert_eq!(
                curr_assembly_id, link.assembly_id,
                "Internal error: contiguity assumption on assembly_id does not hold."
            );
            curr_assembly_id += link.joint.ndofs();

            if link.joint.kinematic {
                for k in link.assembly_id..link.assembly_id + link.joint.ndofs() {
                    self.augmented_mass_indices.remove(k);
                }
            } else {
                for k in link.assembly_id..link.assembly_id + link.joint.ndofs() {
                    self.augmented_mass_indices.keep(k);
                }
            }

            #[allow(unused_mut)] // mut is needed for 3D but not for 2D.
            let mut augmented_inertia = rb_inertia;

            #[cfg(feature = "dim3")]
            {
                // Derivative of gyroscopic forces.
                let gyroscopic_matrix = rb.vels.angvel.gcross_matrix() * rb_inertia
                    - (rb_inertia * rb.vels.angvel).gcross_matrix();

                augmented_inertia += gyroscopic_matrix * dt;
            }

            // TODO: optimize that (knowing the structure of the augmented inertia matrix).
            // TODO: this could be better optimized in 2D.
            #[allow(clippy::useless_conversion)] // Needed in 3D, no-op in 2D
            let rb_mass_matrix_wo_gyro = concat_rb_mass_matrix(rb_mass, rb_inertia.into());
            #[allow(clippy::useless_conversion)] // Needed in 3D, no-op in 2D
            let rb_mass_matrix = concat_rb_mass_matrix(rb_mass, augmented_inertia.into());
            self.augmented_mass
                .quadform(1.0, &rb_mass_matrix_wo_gyro, body_jacobian, 1.0);
            self.acc_augmented_mass
                .quadform(1.0, &rb_mass_matrix, body_jacobian, 1.0);

            /*
             *
             * Coriolis matrix.
             *
             */
            let rb_j = &self.body_jacobians[i];
            let rb_j_w = rb_j.fixed_rows::<ANG_DIM>(DIM);

            let ndofs = link.joint.ndofs();

            if i != 0 {
                let parent_id = link.parent_internal_id;
                let parent_link = &self.links[parent_id];
                let parent_rb = &bodies[parent_link.rigid_body];
                let parent_j = &self.body_jacobians[parent_id];
                let parent_j_w = parent_j.fixed_rows::<ANG_DIM>(DIM);
                let parent_w = SimdAngVector::<Real>::from(parent_rb.vels.angvel).gcross_matrix();

                let (coriolis_v, parent_coriolis_v) = self.coriolis_v.index_mut2(i, parent_id);
                let (coriolis_w, parent_coriolis_w) = self.coriolis_w.index_mut2(i, parent_id);

                coriolis_v.copy_from(parent_coriolis_v);
                coriolis_w.copy_from(parent_coriolis_w);

                // [c1 - c0].gcross() * (JDot + JDot/u * qdot)"
                let shift_cross_tr = vect_to_na(link.shift02).gcross_matrix_tr();
                coriolis_v.gemm(1.0, &shift_cross_tr, parent_coriolis_w, 1.0);

                // JDot (but the 2.0 originates from the sum of two identical terms in JDot and JDot/u * gdot)
                let dvel_cross = vect_to_na(
                    rb.vels.angvel.gcross(link.shift02) + 2.0 * link.joint_velocity.linvel,
                )
                .gcross_matrix_tr();
                coriolis_v.gemm(1.0, &dvel_cross, &parent_j_w, 1.0);

                // JDot/u * qdot
                coriolis_v.gemm(
                    1.0,
                    &vect_to_na(link.joint_velocity.linvel).gcross_matrix_tr(),
                    &parent_j_w,
                    1.0,
                );
                coriolis_v.gemm(1.0, &(parent_w * shift_cross_tr), &parent_j_w, 1.0);

                #[cfg(feature = "dim3")]
                {
                    let vel_wrt_joint_w = vect_to_na(link.joint_velocity.angvel).gcross_matrix();
                    coriolis_w.gemm(-1.0, &vel_wrt_joint_w, &parent_j_w, 1.0);
                }

                // JDot (but the 2.0 originates from the sum of two identical terms in JDot and JDot/u * gdot)
                if !link.joint.kinematic {
                    let mut coriolis_v_part = coriolis_v.columns_mut(link.assembly_id, ndofs);

                    let mut tmp1 = SMatrix::<Real, SPATIAL_DIM, SPATIAL_DIM>::zeros();
                    let mut rb_joint_j = tmp1.columns_mut(0, ndofs);
                    link.joint.jacobian(
                        &(parent_link.local_to_world.rotation
                            * link.joint.data.local_frame1.rotation),
                        &mut rb_joint_j,
                    );

                    let rb_joint_j_v = rb_joint_j.fixed_rows::<DIM>(0);
                    coriolis_v_part.gemm(2.0, &parent_w, &rb_joint_j_v, 1.0);

                    #[cfg(feature = "dim3")]
                    {
                        let rb_joint_j_w = rb_joint_j.fixed_rows::<ANG_DIM>(DIM);
                        let mut coriolis_w_part = coriolis_w.columns_mut(link.assembly_id, ndofs);
                        coriolis_w_part.gemm(1.0, &parent_w, &rb_joint_j_w, 1.0);
                    }
                }
            } else {
                self.coriolis_v[i].fill(0.0);
                self.coriolis_w[i].fill(0.0);
            }

            let coriolis_v = &mut self.coriolis_v[i];
            let coriolis_w = &mut self.coriolis_w[i];

            {
                // [c3 - c2].gcross() * (JDot + JDot/u * qdot)
                let shift_cross_tr = vect_to_na(link.shift23).gcross_matrix_tr();
                coriolis_v.gemm(1.0, &shift_cross_tr, coriolis_w, 1.0);

                // JDot
                let dvel_cross = vect_to_na(rb.vels.angvel.gcross(link.shift23)).gcross_matrix_tr();
                coriolis_v.gemm(1.0, &dvel_cross, &rb_j_w, 1.0);

                // JDot/u * qdot
                coriolis_v.gemm(
                    1.0,
                    &(SimdAngVector::<Real>::from(rb.vels.angvel).gcross_matrix() * shift_cross_tr),
                    &rb_j_w,
                    1.0,
                );
            }

            let coriolis_v = &mut self.coriolis_v[i];
            let coriolis_w = &mut self.coriolis_w[i];

            /*
             * Meld with the mass matrix.
             */
            {
                let mut i_coriolis_dt_v = self.i_coriolis_dt[0].fixed_rows_mut::<DIM>(0);
                i_coriolis_dt_v.copy_from(coriolis_v);
                let rb_mass_dt = vect_to_na(rb_mass * dt);
                i_coriolis_dt_v
                    .column_iter_mut()
                    .for_each(|mut c| c.component_mul_assign(&rb_mass_dt));
            }

            #[cfg(feature = "dim2")]
            {
                let mut i_coriolis_dt_w = self.i_coriolis_dt[0].fixed_rows_mut::<ANG_DIM>(DIM);
                // NOTE: this is just an axpy, but on row columns.
                i_coriolis_dt_w.zip_apply(coriolis_w, |o, x| *o = x * dt * rb_inertia);
            }
            #[cfg(feature = "dim3")]
            {
                let mut i_coriolis_dt_w = self.i_coriolis_dt[0].fixed_rows_mut::<ANG_DIM>(DIM);
                i_coriolis_dt_w.gemm(dt, &mat_to_na(rb_inertia), coriolis_w, 0.0);
            }

            self.acc_augmented_mass
                .gemm_tr(1.0, rb_j, &self.i_coriolis_dt[0], 1.0);
        }

        /*
         * Damping and armature.
         *
         * Damping is a velocity-proportional force made implicit, so it adds
         * `dt · d` to the mass-matrix diagonal. Armature is a "reflected
         * rotor inertia" (additional inertia to account for the joint’s
         * mass and geometry itself): it adds to the diagonal directly.
         */
        for i in 0..self.ndofs {
            let diag = self.damping[i] * dt + self.armature[i];
            self.acc_augmented_mass[(i, i)] += diag;
            self.augmented_mass[(i, i)] += diag;
        }

        // Implicit joint springs: `dt²·k` on the mass-matrix diagonal (force term in `update_acceleration`)
        // keeps a stiff spring on a low-inertia link stable where an explicit position motor injects energy.
        // The spring lives on the link's `MultibodyJoint` so it travels with the link through topology changes.
        let dt2 = dt * dt;
        for li in 0..self.links.len() {
            let mut idx = self.links[li].assembly_id;
            let locked = self.links[li].joint.data.locked_axes.bits();
            for a in 0..SPATIAL_DIM {
                if (locked >> a) & 1 == 0 {
                    let k = self.links[li].joint.spring_stiffness[a];
                    if k != 0.0 {
                        let d = k * dt2;
                        self.acc_augmented_mass[(idx, idx)] += d;
                        self.augmented_mass[(idx, idx)] += d;
                    }
                    idx += 1;
                }
            }
        }

        let effective_dim = self
            .augmented_mass_indices
            .dim_after_removal(self.acc_augmented_mass.nrows());

        // PERF: since we clone the matrix anyway for LU, should be directly output
        //       a new matrix instead of applying permutations?
        self.augmented_mass_indices
            .rearrange_columns(&mut self.acc_augmented_mass, true);
        self.augmented_mass_indices
            .rearrange_columns(&mut self.augmented_mass, true);

        self.augmented_mass_indices
            .rearrange_rows(&mut self.acc_augmented_mass, true);
        self.augmented_mass_indices
            .rearrange_rows(&mut self.augmented_mass, true);

        let acc_inv = LU::new(
            self.acc_augmented_mass
                .view((0, 0), (effective_dim, effective_dim))
                .into_owned(),
        );
        let inv = LU::new(
            self.augmented_mass
                .view((0, 0), (effective_dim, effective_dim))
                .into_owned(),
        );
        (inv, acc_inv)
    }

    pub(super) fn dense_update_acceleration(
        &mut self,
        dt: Real,
        bodies: &RigidBodySet,
        inv: &LU<Real, Dyn, Dyn>,
        acc_inv: &LU<Real, Dyn, Dyn>,
    ) {
        if self.ndofs == 0 {
            return; // Nothing to do.
        }

        self.accelerations.fill(0.0);

        // If there is significant movement, the semi-implicit coriolis term
        // occasionally cause instabilities due to the matrix being near singular.
        // To prevent that, we enable a check that verifies the result and fallbacks
        // to the explicit term if needed
        let check_implicit_coriolis_divergence = dt * self.velocities.amax() >= 1.0e-3;
        // Generalized forces that derive from positions or external inputs
        // (gravity, user forces, spring position terms).
        let mut pos_forces = DVector::zeros(if check_implicit_coriolis_divergence {
            self.ndofs
        } else {
            0
        });

        // Eqn 42 to 45
        for i in 0..self.links.len() {
            let link = &self.links[i];
            let rb = &bodies[link.rigid_body];

            let mut acc = RigidBodyVelocity::zero();

            if i != 0 {
                let parent_id = link.parent_internal_id;
                let parent_link = &self.links[parent_id];
                let parent_rb = &bodies[parent_link.rigid_body];

                acc += self.workspace.accs[parent_id];
                // The 2.0 originates from the two identical terms of Jdot (the terms become
                // identical once they are multiplied by the generalized velocities).
                acc.linvel += 2.0 * parent_rb.vels.angvel.gcross(link.joint_velocity.linvel);
                #[cfg(feature = "dim3")]
                {
                    acc.angvel += parent_rb.vels.angvel.cross(link.joint_velocity.angvel);
                }

                acc.linvel += parent_rb
                    .vels
                    .angvel
                    .gcross(parent_rb.vels.angvel.gcross(link.shift02));
                acc.linvel += self.workspace.accs[parent_id].angvel.gcross(link.shift02);
            }

            acc.linvel += rb.vels.angvel.gcross(rb.vels.angvel.gcross(link.shift23));
            acc.linvel += acc.angvel.gcross(link.shift23);

            self.workspace.accs[i] = acc;

            // TODO: should gyroscopic forces already be computed by the rigid-body itself
            //       (at the same time that we add the gravity force)?
            let gyroscopic;
            let rb_inertia = rb.mprops.effective_angular_inertia();
            let rb_mass = rb.mprops.effective_mass();

            #[cfg(feature = "dim3")]
            {
                let angvel = rb.vels.angvel;
                let inertia_times_angvel = rb_inertia * angvel;
                gyroscopic = angvel.cross(inertia_times_angvel);
            }
            #[cfg(feature = "dim2")]
            {
                gyroscopic = 0.0;
            }

            let external_forces = Force::new(
                rb.forces.force - rb_mass * acc.linvel,
                rb.forces.torque - gyroscopic - rb_inertia * acc.angvel,
            );
            self.accelerations.gemv_tr(
                1.0,
                &self.body_jacobians[i],
                external_forces.as_vector(),
                1.0,
            );

            if check_implicit_coriolis_divergence {
                let applied_forces = Force::new(rb.forces.force, rb.forces.torque);
                pos_forces.gemv_tr(
                    1.0,
                    &self.body_jacobians[i],
                    applied_forces.as_vector(),
                    1.0,
                );
            }
        }

        self.accelerations
            .cmpy(-1.0, &self.damping, &self.velocities, 1.0);

        // Implicit joint springs: backward-Euler at `q⁺ = q + dt·v⁺` gives `-k·(q − rest) − k·dt·v⁺`,
        // with the `v⁺` part implicit via the `dt²·k` mass-matrix diagonal (see `update_mass_matrix`).
        // Consistency requires BOTH `-k·(q − rest)` and `-k·dt·v` here, else the spring is only semi-implicit.
        for li in 0..self.links.len() {
            let mut idx = self.links[li].assembly_id;
            let locked = self.links[li].joint.data.locked_axes.bits();
            for a in 0..SPATIAL_DIM {
                if (locked >> a) & 1 == 0 {
                    let k = self.links[li].joint.spring_stiffness[a];
                    if k != 0.0 {
                        let q = self.links[li].joint.coords[a];
                        let rest = self.links[li].joint.spring_ref[a];
                        let spring_pos_force = -k * (q - rest);
                        self.accelerations[idx] += spring_pos_force - k * dt * self.velocities[idx];
                        if check_implicit_coriolis_divergence {
                            pos_forces[idx] += spring_pos_force;
                        }
                    }
                    idx += 1;
                }
            }
        }

        // Snapshot the full generalized forces: the energy guard may need them
        // for a re-solve with the plain mass matrix.
        let gen_forces = if check_implicit_coriolis_divergence {
            self.accelerations.clone()
        } else {
            DVector::zeros(0)
        };

        self.augmented_mass_indices
            .with_rearranged_rows_mut(&mut self.accelerations, |accs| {
                acc_inv.solve_mut(accs);
            });

        if check_implicit_coriolis_divergence {
            self.dense_free_velocity_energy_guard(dt, &gen_forces, &pos_forces, inv);
        }
    }

    // If the semi-implicit coriolis solve introduces more energy than the external
    // forces’ work, we recalculate without the coriolis term in the mass matrix.
    //
    // This operates by calculating the effective kinematic energy added by the
    // external forces after the solve with the semi-implicit mass matrix, and
    // compare it with the force’s work. If the energy delta exceeds a threshold
    // (indicating undesired/unrealistic energy injection), we fall back to re-solving
    // the forces effect but using only the mass matrix without the implicit coriolis
    // terms.
    fn dense_free_velocity_energy_guard(
        &mut self,
        dt: Real,
        gen_forces: &DVector,
        pos_forces: &DVector,
        inv: &LU<Real, Dyn, Dyn>,
    ) {
        let eff_dim = self.augmented_mass_indices.dim_after_removal(self.ndofs);
        if eff_dim == 0 {
            return;
        }

        // Move all quantities to the kinematic-reduced ordering of the
        // factorized matrices (no-op when there is no kinematic dof).
        let mut v = self.velocities.clone();
        let mut f = gen_forces.clone();
        let mut f_pos = pos_forces.clone();
        self.augmented_mass_indices.rearrange_rows(&mut v, true);
        self.augmented_mass_indices.rearrange_rows(&mut f, true);
        self.augmented_mass_indices.rearrange_rows(&mut f_pos, true);

        let m = self.augmented_mass.view((0, 0), (eff_dim, eff_dim));
        let v = v.rows(0, eff_dim);
        let f = f.rows(0, eff_dim);
        let f_pos = f_pos.rows(0, eff_dim);

        let energy_delta_minus_work = |accelerations: &DVector| -> Option<Real> {
            let mut a = accelerations.clone();
            self.augmented_mass_indices.rearrange_rows(&mut a, true);
            let a = a.rows(0, eff_dim).into_owned();
            if !a.iter().all(|x| x.is_finite()) {
                return None;
            }
            let m_a = m * &a;
            let energy_delta = dt * v.dot(&m_a) + 0.5 * dt * dt * a.dot(&m_a);
            let work = dt * v.dot(&f) + 0.5 * dt * dt * a.dot(&f_pos);
            // Margin: a small fraction of the current kinetic energy to absorb
            // discretization error on healthy steps.
            let kinetic_energy = 0.5 * v.dot(&(m * v));
            let energy_margin = 1.0e-2 * kinetic_energy + 1.0e-8;
            Some(energy_delta - work - energy_margin)
        };

        match energy_delta_minus_work(&self.accelerations) {
            Some(excess) if excess <= 0.0 => (), // Implicit update didn’t introduce too much extra energy.
            _ => {
                // The implicit solve injected energy (or produced non-finite
                // values): fall back to the plain mass matrix.
                self.accelerations.copy_from(gen_forces);
                self.augmented_mass_indices.with_rearranged_rows_mut(
                    &mut self.accelerations,
                    |accs| {
                        inv.solve_mut(accs);
                    },
                );

                // Last-chance check: if all else fails, just clear the accelerations vector
                // instead of breaking the simulation. Hopefully it will get back to a
                // sane result in a close timestep.
                if !self.accelerations.iter().all(|x| x.is_finite()) {
                    self.accelerations.fill(0.0);
                }
            }
        }
    }
}

/// The patched assembly against the dense one of rapier 0.36.1, on random configurations,
/// velocities and applied forces of a HyQ-shaped tree (a free trunk and four 3-joint legs) and of
/// a generic chain (fixed root, revolute, prismatic, spherical and kinematic joints, a branch,
/// joint springs, damping and armature). The body jacobians must be exactly equal; both
/// augmented mass matrices, their factorizations' solves and the free accelerations must be
/// equal within `TOLERANCES`; the augmented mass matrix (positive definite here) must have been
/// factorized by Cholesky, and its solves are compared with those of the dense LU factorization.
#[cfg(all(test, feature = "dim3"))]
mod tests {
    use super::super::MultibodyLu;
    use super::*;
    use crate::math::{Rotation, Vector};
    use crate::prelude::{
        GenericJointBuilder, JointAxesMask, MassProperties, MultibodyJointHandle,
        MultibodyJointSet, PrismaticJointBuilder, RevoluteJointBuilder, RigidBodyBuilder,
        RigidBodyHandle, SphericalJointBuilder,
    };
    use std::println;

    struct Rng(oorandom::Rand32);

    impl Rng {
        /// Uniform in `[lo, hi)`.
        fn range(&mut self, lo: Real, hi: Real) -> Real {
            lo + (hi - lo) * self.0.rand_float() as Real
        }

        fn vector(&mut self, scale: Real) -> Vector {
            Vector::new(
                self.range(-scale, scale),
                self.range(-scale, scale),
                self.range(-scale, scale),
            )
        }

        fn rotation(&mut self) -> Rotation {
            Rotation::from_scaled_axis(self.vector(3.0))
        }

        /// A link with random mass, centre of mass and (full) inertia tensor.
        fn body(
            &mut self,
            bodies: &mut RigidBodySet,
            dynamic: bool,
            mass: Real,
        ) -> RigidBodyHandle {
            let principal = Vector::new(
                self.range(0.2, 1.0),
                self.range(0.2, 1.0),
                self.range(0.2, 1.0),
            ) * mass
                * 0.01;
            let props = MassProperties::with_principal_inertia_frame(
                self.vector(0.05),
                mass,
                principal,
                self.rotation(),
            );
            let builder = if dynamic {
                RigidBodyBuilder::dynamic()
            } else {
                RigidBodyBuilder::fixed()
            };
            let handle = bodies.insert(
                builder
                    .translation(self.vector(1.0))
                    .additional_mass_properties(props),
            );
            // Fold the mass properties in now (a pipeline step would do it).
            bodies[handle]
                .recompute_mass_properties_from_colliders(&crate::geometry::ColliderSet::new());
            handle
        }
    }

    fn hinge(rng: &mut Rng) -> crate::prelude::GenericJoint {
        let axis = rng.vector(1.0).normalize();
        let mut joint: crate::prelude::GenericJoint = RevoluteJointBuilder::new(axis)
            .local_anchor1(rng.vector(0.3))
            .local_anchor2(rng.vector(0.3))
            .build()
            .into();
        joint.local_frame1.rotation = rng.rotation() * joint.local_frame1.rotation;
        joint
    }

    /// A HyQ-shaped tree: a free trunk and four legs of three revolute joints.
    fn hyq_like(
        rng: &mut Rng,
        bodies: &mut RigidBodySet,
        joints: &mut MultibodyJointSet,
    ) -> MultibodyJointHandle {
        let trunk = rng.body(bodies, true, 70.0);
        let mut handle = None;
        for _ in 0..4 {
            let mut parent = trunk;
            for mass in [2.9, 2.6, 0.9] {
                let child = rng.body(bodies, true, mass);
                handle = joints.insert(parent, child, hinge(rng), true);
                parent = child;
            }
        }
        handle.expect("the joints were inserted")
    }

    /// A generic tree on a fixed root: revolute, prismatic, spherical and kinematic joints,
    /// a branch, springs, damping and armature.
    fn generic_chain(
        rng: &mut Rng,
        bodies: &mut RigidBodySet,
        joints: &mut MultibodyJointSet,
    ) -> MultibodyJointHandle {
        let root = rng.body(bodies, false, 5.0);
        let a = rng.body(bodies, true, 3.0);
        let b = rng.body(bodies, true, 2.0);
        let c = rng.body(bodies, true, 1.5);
        let d = rng.body(bodies, true, 1.0);
        let e = rng.body(bodies, true, 0.5);
        let f = rng.body(bodies, true, 0.7);
        let mut spring = hinge(rng);
        spring.set_limits(crate::prelude::JointAxis::AngX, [-1.0, 1.0]);
        joints.insert(root, a, spring, true);
        let slide = PrismaticJointBuilder::new(rng.vector(1.0).normalize())
            .local_anchor1(rng.vector(0.3))
            .local_anchor2(rng.vector(0.3))
            .build();
        joints.insert(a, b, slide, true);
        let ball = SphericalJointBuilder::new()
            .local_anchor1(rng.vector(0.3))
            .local_anchor2(rng.vector(0.3))
            .build();
        joints.insert(b, c, ball, true);
        joints.insert_kinematic(c, d, hinge(rng), true);
        joints.insert(d, e, hinge(rng), true);
        // A branch off the second link: a cylindrical joint (slides along and turns about x).
        let two = GenericJointBuilder::new(
            JointAxesMask::LIN_Y
                | JointAxesMask::LIN_Z
                | JointAxesMask::ANG_Y
                | JointAxesMask::ANG_Z,
        )
        .local_anchor1(rng.vector(0.3))
        .local_anchor2(rng.vector(0.3))
        .build();
        let h = joints.insert(b, f, two, true).expect("inserted");
        h
    }

    /// Random coordinates, velocities, springs, damping, armature and applied forces.
    fn randomize(rng: &mut Rng, mb: &mut Multibody, bodies: &mut RigidBodySet) {
        let n = mb.ndofs();
        let disp: Vec<Real> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        mb.apply_displacements(&disp);
        for v in mb.generalized_velocity_mut().iter_mut() {
            *v = rng.range(-8.0, 8.0);
        }
        for d in mb.damping_mut().iter_mut() {
            *d = rng.range(0.0, 2.0);
        }
        for a in mb.armature_mut().iter_mut() {
            *a = rng.range(0.0, 0.05);
        }
        for link in mb.links_mut() {
            if rng.range(0.0, 1.0) < 0.5 {
                link.joint
                    .set_spring(3, rng.range(0.0, 50.0), rng.range(-0.5, 0.5));
            }
        }
        for link in mb.links() {
            let rb = bodies.index_mut_internal(link.rigid_body);
            rb.forces.force = rng.vector(100.0);
            rb.forces.torque = rng.vector(20.0);
        }
    }

    /// How far the patched results may be from the dense ones, relative to the largest entry of
    /// the dense result (`0.0`: exactly equal).
    struct Tolerances {
        /// The augmented mass matrix and its solves.
        mass: Real,
        /// The matrix with the implicit Coriolis and gyroscopic terms.
        acc_mass: Real,
        /// The free accelerations.
        accelerations: Real,
    }

    /// The tolerances of the current patches, about ten times the worst differences seen
    /// (f32 rounding): the composite-rigid-body assembly of the mass matrix (worst seen 3.1e-7)
    /// and the implicit Coriolis and gyroscopic terms added in another order (2.5e-7); solves
    /// and free accelerations (worst seen 1.6e-6) amplify those by the matrices' conditioning.
    const TOLERANCES: Tolerances = Tolerances {
        mass: 3.0e-6,
        acc_mass: 3.0e-6,
        accelerations: 2.0e-5,
    };

    /// The largest difference between `a` and `b` relative to the largest entry of `b`
    /// (`0.0` when they are equal, infinite when they differ and `b` is zero).
    fn relative_difference<'a>(
        a: impl IntoIterator<Item = &'a Real>,
        b: impl IntoIterator<Item = &'a Real> + Clone,
    ) -> Real {
        let scale = b
            .clone()
            .into_iter()
            .fold(0.0 as Real, |m, x| m.max(x.abs()));
        let diff =
            a.into_iter().zip(b).fold(
                0.0 as Real,
                |m, (x, y)| if x == y { m } else { m.max((x - y).abs()) },
            );
        if diff == 0.0 { 0.0 } else { diff / scale }
    }

    /// The worst relative differences seen, reported by each test.
    #[derive(Default, Debug)]
    struct Worst {
        mass: Real,
        acc_mass: Real,
        solves: Real,
        accelerations: Real,
    }

    /// One random sample: the patched path and the dense one from the same state. With
    /// `massless`, the last two links inserted have no mass and no inertia, and their DoFs no
    /// damping, armature or spring: the mass matrices are singular.
    fn compare_one(rng: &mut Rng, hyq: bool, massless: bool, worst: &mut Worst) {
        let mut bodies = RigidBodySet::new();
        let mut joints = MultibodyJointSet::new();
        let handle = if hyq {
            hyq_like(rng, &mut bodies, &mut joints)
        } else {
            generic_chain(rng, &mut bodies, &mut joints)
        };
        let massless_bodies: Vec<RigidBodyHandle> = if massless {
            bodies
                .iter()
                .map(|(h, _)| h)
                .skip(bodies.len() - 2)
                .collect()
        } else {
            Vec::new()
        };
        for &h in &massless_bodies {
            bodies[h].set_additional_mass_properties(MassProperties::default(), true);
            bodies[h]
                .recompute_mass_properties_from_colliders(&crate::geometry::ColliderSet::new());
        }
        let dt = rng.range(1.0e-4, 2.0e-3);
        let mb = joints.get_mut(handle).expect("the multibody exists").0;
        if !massless {
            // The comparisons below must run on real masses and inertias.
            for link in mb.links() {
                let rb = &bodies[link.rigid_body];
                assert!(rb.mass() > 0.0, "a test link has no mass");
                let inertia = rb.mass_properties().local_mprops.principal_inertia();
                assert!(inertia.min_element() > 0.0, "a test link has no inertia");
            }
        }
        mb.forward_kinematics(&bodies, true);
        randomize(rng, mb, &mut bodies);
        // The massless links' DoFs get no damping, armature or spring either.
        let massless_dofs: Vec<usize> = mb
            .links()
            .filter(|link| massless_bodies.contains(&link.rigid_body))
            .flat_map(|link| link.assembly_id..link.assembly_id + link.joint.ndofs())
            .collect();
        for &k in &massless_dofs {
            mb.damping_mut()[k] = 0.0;
            mb.armature_mut()[k] = 0.0;
        }
        for link in mb.links_mut() {
            if massless_bodies.contains(&link.rigid_body) {
                for axis in 0..SPATIAL_DIM {
                    link.joint.set_spring(axis, 0.0, 0.0);
                }
            }
        }
        mb.forward_kinematics(&bodies, true);
        mb.update_rigid_bodies(&mut bodies, true);
        mb.update_velocities(&mut bodies);

        let mut dense = mb.clone();
        dense.dense_update_body_jacobians();
        let (inv, acc_inv) = dense.dense_update_mass_matrix(dt, &bodies);
        dense.dense_update_acceleration(dt, &bodies, &inv, &acc_inv);

        mb.update_mass_matrix(dt, &bodies);
        mb.update_acceleration(dt, &bodies);

        for i in 0..mb.num_links() {
            assert_eq!(
                mb.body_jacobian(i),
                &dense.body_jacobians[i],
                "jacobian of link {i}"
            );
        }
        let dim = inv.lu_internal().nrows();
        let view = |m: &DMatrix<Real>| m.view((0, 0), (dim, dim)).into_owned();
        let finite = |v: &DVector| v.iter().map(|x| x.is_finite()).collect::<Vec<_>>();
        if massless {
            // Singular: no panic, and no non-finite free acceleration where rapier 0.36.1
            // had a finite one.
            assert!(!inv.is_invertible() && !acc_inv.is_invertible());
            // The augmented mass matrix is not positive definite: no Cholesky factor, the LU
            // factorization instead.
            assert!(!mb.inv_augmented_mass.cholesky);
            assert_eq!(
                finite(&mb.accelerations),
                finite(&dense.accelerations),
                "finite free accelerations"
            );
            if TOLERANCES.mass == 0.0 && TOLERANCES.acc_mass == 0.0 {
                // Bit-identical patches: the same bits, NaNs included.
                let bits = |m: &[Real]| m.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(mb.acc_inv_augmented_mass.lu.as_slice()),
                    bits(acc_inv.lu_internal().as_slice())
                );
                assert_eq!(
                    bits(mb.inv_augmented_mass.lu.as_slice()),
                    bits(inv.lu_internal().as_slice())
                );
                assert_eq!(
                    bits(mb.accelerations.as_slice()),
                    bits(dense.accelerations.as_slice()),
                    "free accelerations"
                );
            }
            return;
        }

        let mass = relative_difference(
            view(&mb.augmented_mass).iter(),
            view(&dense.augmented_mass).iter(),
        );
        assert!(mass <= TOLERANCES.mass, "augmented mass: {mass:e}");
        worst.mass = worst.mass.max(mass);
        let acc_mass = relative_difference(
            view(&mb.acc_augmented_mass).iter(),
            view(&dense.acc_augmented_mass).iter(),
        );
        assert!(
            acc_mass <= TOLERANCES.acc_mass,
            "augmented mass with the implicit coriolis and gyroscopic terms: {acc_mass:e}"
        );
        worst.acc_mass = worst.acc_mass.max(acc_mass);
        // Positive definite: factorized by Cholesky, whose solves are compared below with those
        // of the dense assembly's LU factorization.
        assert!(mb.inv_augmented_mass.cholesky);
        if TOLERANCES.acc_mass == 0.0 {
            assert_eq!(
                &mb.acc_inv_augmented_mass.lu,
                acc_inv.lu_internal(),
                "LU factors (acc)"
            );
        }
        for _ in 0..3 {
            let b = DVector::from_fn(dim, |_, _| rng.range(-1.0, 1.0));
            let (mut x, mut x_dense) = (b.clone(), b.clone());
            assert!(mb.inv_augmented_mass.solve_mut(&mut x));
            assert!(inv.solve_mut(&mut x_dense));
            let solve = relative_difference(x.iter(), x_dense.iter());
            // A solve amplifies the matrix's relative differences by its condition number,
            // which the accelerations' tolerance covers.
            assert!(solve <= TOLERANCES.accelerations, "solve: {solve:e}");
            worst.solves = worst.solves.max(solve);
        }
        assert!(mb.accelerations.iter().all(|a| a.is_finite()));
        let accelerations =
            relative_difference(mb.accelerations.iter(), dense.accelerations.iter());
        assert!(
            accelerations <= TOLERANCES.accelerations,
            "free accelerations: {accelerations:e}\n{}\n{}",
            mb.accelerations.transpose(),
            dense.accelerations.transpose()
        );
        worst.accelerations = worst.accelerations.max(accelerations);
    }

    #[test]
    fn patched_multibody_dynamics_equal_the_dense_assembly_on_a_hyq_shaped_tree() {
        let mut rng = Rng(oorandom::Rand32::new(12));
        let mut worst = Worst::default();
        for _ in 0..40 {
            compare_one(&mut rng, true, false, &mut worst);
        }
        println!("HyQ-shaped tree, worst relative differences: {worst:?}");
    }

    #[test]
    fn patched_multibody_dynamics_equal_the_dense_assembly_on_a_generic_chain() {
        let mut rng = Rng(oorandom::Rand32::new(34));
        let mut worst = Worst::default();
        for _ in 0..40 {
            compare_one(&mut rng, false, false, &mut worst);
        }
        println!("generic chain, worst relative differences: {worst:?}");
    }

    /// `MultibodyLu` performs nalgebra's `LU` operations in the same order: the same factors and
    /// the same solves, bit for bit, on the top-left block of a larger matrix, on vectors and
    /// several columns, small and large, regular and singular.
    #[test]
    fn multibody_lu_is_bit_identical_to_nalgebra_lu() {
        let mut rng = Rng(oorandom::Rand32::new(78));
        let bits = |m: &[Real]| m.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for dim in [1, 2, 5, 18, 40] {
            for case in 0..6 {
                let mut matrix = DMatrix::from_fn(dim + 2, dim + 2, |_, _| rng.range(-1.0, 1.0));
                match case {
                    // Singular: a zero column, a zero row, two equal columns.
                    1 => matrix.column_mut(dim / 2).fill(0.0),
                    2 => matrix.row_mut(dim - 1).fill(0.0),
                    3 if dim > 1 => {
                        let c = matrix.column(0).into_owned();
                        matrix.column_mut(1).copy_from(&c);
                    }
                    // Diagonally dominant: few row interchanges.
                    4 => {
                        for i in 0..dim {
                            matrix[(i, i)] += 4.0;
                        }
                    }
                    _ => {}
                }
                let reference = LU::new(matrix.view((0, 0), (dim, dim)).into_owned());
                let mut lu = MultibodyLu::default();
                lu.factorize(&matrix, dim);
                assert_eq!(
                    bits(lu.lu.as_slice()),
                    bits(reference.lu_internal().as_slice()),
                    "factors, dim {dim}, case {case}"
                );
                for ncols in [1, 3] {
                    let b = DMatrix::from_fn(dim, ncols, |_, _| rng.range(-1.0, 1.0));
                    let (mut x, mut x_reference) = (b.clone(), b);
                    assert_eq!(lu.solve_mut(&mut x), reference.solve_mut(&mut x_reference));
                    assert_eq!(
                        bits(x.as_slice()),
                        bits(x_reference.as_slice()),
                        "solve, dim {dim}, case {case}, {ncols} columns"
                    );
                }
            }
        }
    }

    /// `MultibodyLu::factorize_symmetric` on a symmetric matrix: on a positive-definite one a
    /// Cholesky factorization whose solves equal those of nalgebra's `LU` within 1e-5 of their
    /// largest entry (f32; the matrices' condition numbers are below 10); on a singular, indefinite
    /// or NaN-holding one the LU factorization, bit for bit nalgebra's, with the same solves.
    #[test]
    fn symmetric_factorization_is_cholesky_or_falls_back_to_lu() {
        let mut rng = Rng(oorandom::Rand32::new(91));
        let bits = |m: &[Real]| m.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut worst: Real = 0.0;
        for dim in [1, 2, 5, 18, 40] {
            for case in 0..5 {
                let b = DMatrix::from_fn(dim + 2, dim + 2, |_, _| rng.range(-1.0, 1.0));
                // Symmetric positive definite, then spoilt by the case.
                let mut matrix = &b * b.transpose() / (dim as Real) + DMatrix::identity(dim + 2, dim + 2);
                let last = dim - 1;
                match case {
                    // Singular: a zero row and column.
                    1 => {
                        matrix.row_mut(last).fill(0.0);
                        matrix.column_mut(last).fill(0.0);
                    }
                    // Indefinite.
                    2 => matrix[(last, last)] = -1.0,
                    // A NaN.
                    3 => matrix[(last, last)] = Real::NAN,
                    _ => {}
                }
                let positive_definite = case == 0 || case == 4;
                let reference = LU::new(matrix.view((0, 0), (dim, dim)).into_owned());
                let mut factorization = MultibodyLu::default();
                // Reuse a factorization of another kind and size: nothing of it may remain.
                factorization.factorize(&DMatrix::from_element(3, 3, 1.0), 3);
                factorization.factorize_symmetric(&matrix, dim);
                assert_eq!(
                    factorization.cholesky, positive_definite,
                    "dim {dim}, case {case}"
                );
                if !positive_definite {
                    assert_eq!(
                        bits(factorization.lu.as_slice()),
                        bits(reference.lu_internal().as_slice()),
                        "LU factors, dim {dim}, case {case}"
                    );
                }
                for ncols in [1, 3] {
                    let rhs = DMatrix::from_fn(dim, ncols, |_, _| rng.range(-1.0, 1.0));
                    let (mut x, mut x_reference) = (rhs.clone(), rhs);
                    let solved = factorization.solve_mut(&mut x);
                    assert_eq!(solved, reference.solve_mut(&mut x_reference));
                    if positive_definite {
                        let difference = relative_difference(x.iter(), x_reference.iter());
                        assert!(difference <= 1.0e-5, "solve, dim {dim}: {difference:e}");
                        worst = worst.max(difference);
                    } else {
                        assert_eq!(
                            bits(x.as_slice()),
                            bits(x_reference.as_slice()),
                            "solve, dim {dim}, case {case}, {ncols} columns"
                        );
                    }
                }
            }
        }
        println!("Cholesky solves against LU, worst relative difference: {worst:e}");
    }

    /// Links without mass or inertia (and, on their DoFs, no damping, armature or spring) make
    /// the mass matrices singular: the patched path does not panic and has a non-finite free
    /// acceleration only where rapier 0.36.1 had one.
    #[test]
    fn a_singular_mass_matrix_is_handled_as_by_the_dense_assembly() {
        let mut rng = Rng(oorandom::Rand32::new(56));
        let mut worst = Worst::default();
        for _ in 0..20 {
            compare_one(&mut rng, false, true, &mut worst);
            compare_one(&mut rng, true, true, &mut worst);
        }
    }
}
