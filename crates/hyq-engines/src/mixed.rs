//! [`AnyBackend`]: one `Backend` type whose value runs on any engine this build has, so that one
//! `VecEnv<AnyBackend>` (or `Env<AnyBackend>`) holds envs on different engines.
//!
//! Each value is one engine's backend inside an enum; every `Backend` method is one `match` to
//! that engine's own method (every provided method too, so an engine that overrides one keeps
//! its own). An engine's arm is compiled only with its feature. The match costs a predictable
//! branch per backend call, a few per physics sub-step, against the tens of microseconds the
//! sub-step itself takes; a front that runs one engine names that engine's type instead and
//! pays nothing (`with_engine!`).
//!
//! The engine of a value is chosen by its options ([`AnyOptions`]): [`AnyOptions::read`] turns
//! an engine's name and the environment's `[physics.<name>]` table into that engine's options,
//! and `AnyBackend::build` builds that engine. The default options name no engine, and building
//! with them is an error: `Env::<AnyBackend>::new`, which reads `[physics.mixed]` (a table no
//! configuration has), is refused with a line that says how a mixed env is built (hyq-env's
//! `VecEnv::with_options` and `Env::with_options`).

use std::sync::Arc;

use hyq_physics::dynamics::Dynamics;
use hyq_physics::inertia::MassProperties;
use hyq_physics::state::{PhysicsParams, RobotState, TrunkState};
use hyq_physics::terrain::Terrain;
use hyq_physics::{Backend, PhysicsError, RobotModel};
use nalgebra::{Isometry3, Vector3};
use serde::{Deserialize, Serialize};

use crate::OptionsSource;
#[cfg(feature = "dart")]
use crate::backends::Dart;
#[cfg(feature = "mujoco")]
use crate::backends::Mujoco;
#[cfg(feature = "rapier")]
use crate::backends::Rapier;

/// One engine's backend, whichever engine it is (see the module docs).
// rapier's world lives inline (about 10 kB) and MuJoCo's and DART's behind their C pointers:
// every value is built once and stays inside its env, never moved on a hot path, so the size
// costs 10 kB per env and boxing rapier would add a pointer chase to every backend call.
#[allow(clippy::large_enum_variant)]
pub enum AnyBackend {
    /// On rapier.
    #[cfg(feature = "rapier")]
    Rapier(Rapier),
    /// On DART.
    #[cfg(feature = "dart")]
    Dart(Dart),
    /// On MuJoCo.
    #[cfg(feature = "mujoco")]
    Mujoco(Mujoco),
}

/// The options of an [`AnyBackend`]: the engine it runs and that engine's own options.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum AnyOptions {
    /// No engine chosen: building with these is an error (see the module docs).
    #[default]
    Unset,
    /// rapier, with its options.
    #[cfg(feature = "rapier")]
    Rapier(<Rapier as Backend>::Options),
    /// DART, with its options.
    #[cfg(feature = "dart")]
    Dart(<Dart as Backend>::Options),
    /// MuJoCo, with its options.
    #[cfg(feature = "mujoco")]
    Mujoco(<Mujoco as Backend>::Options),
}

impl AnyOptions {
    /// The options of the engine named `engine`, read from `source`: `Ok(None)` when this build
    /// lacks that engine or no engine has that name (the front says which, in its usual words).
    pub fn read<S: OptionsSource>(engine: &str, source: &S) -> Result<Option<Self>, S::Error> {
        match engine {
            #[cfg(feature = "rapier")]
            n if n == Rapier::NAME => source.engine_options(n).map(|o| Some(Self::Rapier(o))),
            #[cfg(feature = "dart")]
            n if n == Dart::NAME => source.engine_options(n).map(|o| Some(Self::Dart(o))),
            #[cfg(feature = "mujoco")]
            n if n == Mujoco::NAME => source.engine_options(n).map(|o| Some(Self::Mujoco(o))),
            _ => Ok(None),
        }
    }

    /// The name of the engine these options choose (`None` when unset).
    pub fn engine(&self) -> Option<&'static str> {
        match self {
            Self::Unset => None,
            #[cfg(feature = "rapier")]
            Self::Rapier(_) => Some(Rapier::NAME),
            #[cfg(feature = "dart")]
            Self::Dart(_) => Some(Dart::NAME),
            #[cfg(feature = "mujoco")]
            Self::Mujoco(_) => Some(Mujoco::NAME),
        }
    }
}

/// `$body` with `$b` bound to the engine backend inside `$any` (an `AnyBackend`, `&` or
/// `&mut`). The `#[cfg]`s are read here, in this crate, so the macro stays private.
macro_rules! dispatch {
    ($any:expr, $b:ident => $body:expr) => {
        match $any {
            #[cfg(feature = "rapier")]
            AnyBackend::Rapier($b) => $body,
            #[cfg(feature = "dart")]
            AnyBackend::Dart($b) => $body,
            #[cfg(feature = "mujoco")]
            AnyBackend::Mujoco($b) => $body,
        }
    };
}

impl AnyBackend {
    /// The name of the engine this value runs on (`Backend::NAME` of that engine).
    pub fn engine(&self) -> &'static str {
        fn name<B: Backend>(_: &B) -> &'static str {
            B::NAME
        }
        dispatch!(self, b => name(b))
    }
}

impl Backend for AnyBackend {
    type Options = AnyOptions;

    /// Not an engine's name: the table `[physics.mixed]` does not exist, so `Env::new` on this
    /// backend gets [`AnyOptions::Unset`] and is refused (see the module docs).
    const NAME: &'static str = "mixed";

    fn build(
        model: Arc<RobotModel>,
        params: &PhysicsParams,
        options: &AnyOptions,
    ) -> Result<Self, PhysicsError> {
        match options {
            AnyOptions::Unset => Err(PhysicsError::Backend {
                backend: Self::NAME,
                message: "no engine chosen: a mixed-engine env is built with its engine's \
                          options (hyq_engines::AnyOptions::read), as VecEnv::with_options does"
                    .into(),
            }),
            #[cfg(feature = "rapier")]
            AnyOptions::Rapier(o) => Rapier::build(model, params, o).map(Self::Rapier),
            #[cfg(feature = "dart")]
            AnyOptions::Dart(o) => Dart::build(model, params, o).map(Self::Dart),
            #[cfg(feature = "mujoco")]
            AnyOptions::Mujoco(o) => Mujoco::build(model, params, o).map(Self::Mujoco),
        }
    }

    fn engine_name(&self) -> &'static str {
        self.engine()
    }

    fn model(&self) -> &Arc<RobotModel> {
        dispatch!(self, b => b.model())
    }

    fn params(&self) -> &PhysicsParams {
        dispatch!(self, b => b.params())
    }

    fn apply_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.apply_state(state))
    }

    fn apply_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.apply_joint_torques(torques))
    }

    fn step(&mut self) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.step())
    }

    fn joint_positions(&self, out: &mut [f64]) {
        dispatch!(self, b => b.joint_positions(out))
    }

    fn joint_velocities(&self, out: &mut [f64]) {
        dispatch!(self, b => b.joint_velocities(out))
    }

    fn trunk(&self) -> TrunkState {
        dispatch!(self, b => b.trunk())
    }

    fn contacts(&self, out: &mut [bool]) {
        dispatch!(self, b => b.contacts(out))
    }

    fn link_poses(&self, out: &mut [Isometry3<f64>]) {
        dispatch!(self, b => b.link_poses(out))
    }

    fn total_mass(&self) -> f64 {
        dispatch!(self, b => b.total_mass())
    }

    fn apply_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.apply_dynamics(dynamics))
    }

    fn body_mass_properties(&self, link: usize) -> MassProperties {
        dispatch!(self, b => b.body_mass_properties(link))
    }

    fn apply_trunk_velocity_change(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.apply_trunk_velocity_change(dv))
    }

    fn set_dynamics(&mut self, dynamics: &Dynamics) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.set_dynamics(dynamics))
    }

    fn reset_with_dynamics(
        &mut self,
        dynamics: &Dynamics,
        state: &RobotState,
    ) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.reset_with_dynamics(dynamics, state))
    }

    fn push_trunk(&mut self, dv: &Vector3<f64>) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.push_trunk(dv))
    }

    fn terrain(&self) -> &Terrain {
        dispatch!(self, b => b.terrain())
    }

    fn apply_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.apply_terrain(terrain))
    }

    fn set_terrain(&mut self, terrain: &Terrain) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.set_terrain(terrain))
    }

    fn set_state(&mut self, state: &RobotState) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.set_state(state))
    }

    fn set_joint_torques(&mut self, torques: &[f64]) -> Result<(), PhysicsError> {
        dispatch!(self, b => b.set_joint_torques(torques))
    }

    fn read_state(&self, out: &mut RobotState) {
        dispatch!(self, b => b.read_state(out))
    }

    fn state(&self) -> RobotState {
        dispatch!(self, b => b.state())
    }
}
