//! Invariant: MuJoCo's failures are errors of the call that met them, never an exit of the
//! process and never silent wrong physics:
//! - torques that make the accelerations blow up end the step with `Diverged`, whose text is
//!   MuJoCo's own warning (MuJoCo's automatic reset is off, so it cannot quietly restart the
//!   robot); the world refuses to step until `set_state`, and then replays a fresh world;
//! - an error MuJoCo raises inside a step (here its memory arena overflows, in a world compiled
//!   with too little memory) is a one-line error with MuJoCo's text, the process goes on, and
//!   after `set_state` the world repeats exactly the same steps (MuJoCo's default handler for
//!   such an error prints it and exits the process);
//! - the same error while compiling is the model being refused, with MuJoCo's text.

use hyq_conformance::fixtures::{Robot, build_default, first_difference, random_pd_run};
use hyq_mujoco::raw::{Layout, StepError, World, layout};
use hyq_mujoco::{MujocoBackend, MujocoOptions, world_mjcf};
use hyq_physics::{Backend, PhysicsError, PhysicsParams, bundled};

/// The backend's world of the bundled HyQ at its spawn state.
fn hyq() -> MujocoBackend {
    build_default(&Robot::bundled("hyq"), &MujocoOptions::default())
}

#[test]
fn exploding_torques_are_a_divergence_with_mujocos_warning_and_the_world_recovers() {
    let model = bundled::hyq();
    let mut world = hyq();
    let huge = vec![1e300; model.num_joints()];
    world
        .set_joint_torques(&huge)
        .expect("finite torques are valid");
    match world.step() {
        Err(PhysicsError::Diverged { what }) => {
            assert!(what.contains("QACC"), "MuJoCo's warning: {what}");
            assert!(!what.contains('\n'), "{what:?}");
        }
        other => panic!("expected Diverged, got {other:?}"),
    }
    let mut flags = vec![true; model.tracked().len()];
    world.contacts(&mut flags);
    assert!(
        flags.iter().all(|f| !f),
        "no contact reported after a failed step"
    );
    let err = world.step().expect_err("a diverged world refuses to step");
    assert!(err.to_string().contains("call set_state"), "{err}");
    world
        .set_state(&model.spawn_state())
        .expect("the spawn state is valid");
    let replay = random_pd_run(&mut world, 2, 0.0, 0..500);
    let fresh = random_pd_run(&mut hyq(), 2, 0.0, 0..500);
    assert_eq!(first_difference(&fresh, &replay), None);
}

/// The backend's world with MuJoCo's arena limited to `memory` (an MJCF `<size memory>`).
fn world_with_memory(memory: &str) -> Result<(World, Layout), String> {
    let model = bundled::hyq();
    let mjcf = world_mjcf(&model, &PhysicsParams::default(), &MujocoOptions::default())
        .expect("the bundled HyQ has an MJCF");
    let xml = mjcf.xml.replace(
        "<worldbody>",
        &format!("<size memory=\"{memory}\"/>\n  <worldbody>"),
    );
    let layout = layout(&model, &mjcf);
    World::new(&xml, &layout)
        .map(|w| (w, layout))
        .map_err(|e| e.to_string())
}

/// Steps from the spawn state until the first failure (at most 1000 steps).
fn steps_until_failure(world: &mut World, num_tracked: usize) -> (usize, Option<StepError>) {
    let model = bundled::hyq();
    let s = model.spawn_state();
    let t = s.trunk.pose.translation.vector;
    let pose = [t.x, t.y, t.z, 1.0, 0.0, 0.0, 0.0];
    world
        .set_state(&pose, &[0.0; 6], &s.q, &s.qd)
        .expect("the spawn state fits in the arena");
    let mut contacts = vec![0; num_tracked];
    for k in 0..1000 {
        if let Err(e) = world.step(&mut contacts) {
            return (k, Some(e));
        }
    }
    (1000, None)
}

#[test]
fn an_error_inside_mujoco_is_an_error_of_the_step_and_the_world_recovers() {
    let (mut world, layout) = world_with_memory("2K").expect("2 kB compile");
    let (at, err) = steps_until_failure(&mut world, layout.num_tracked);
    let Some(StepError::Failed(message)) = err else {
        panic!("2 kB of arena must run out when the feet land (got {err:?} after {at} steps)");
    };
    assert!(
        message.contains("mj_stackAlloc"),
        "MuJoCo's text: {message}"
    );
    assert!(
        message.contains("<size memory"),
        "MuJoCo's advice: {message}"
    );
    assert!(!message.contains('\n'), "{message:?}");
    // The process is still here; a reset world fails at the same step with the same message.
    let (again, err_again) = steps_until_failure(&mut world, layout.num_tracked);
    assert_eq!(again, at);
    assert_eq!(err_again, Some(StepError::Failed(message)));
    // With MuJoCo's default arena the same run goes on.
    let (mut roomy, layout) = world_with_memory("1M").expect("1 MB compile");
    assert_eq!(steps_until_failure(&mut roomy, layout.num_tracked).0, 1000);
}

#[test]
fn an_error_while_compiling_is_a_refused_model_with_mujocos_text() {
    let err = world_with_memory("6K").expect_err("6 kB cannot hold the compiler's first step");
    assert!(err.starts_with("MuJoCo refused the model:"), "{err}");
    assert!(err.contains("mj_stackAlloc"), "{err}");
}
