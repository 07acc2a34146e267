//! Invariant: a physics blow-up (a backend error such as `Diverged`, or any non-finite reading)
//! ends the episode with the reason `diverged` (terminated) and never emits NaN: the
//! observation is the last finite one, the reward 0 with every term 0 and every multiplier 1,
//! the distances and attitude those of the last finite state; the env must then be reset and
//! works again.

mod common;

use common::{reset, scripted};
use hyq_env::{Divergence, EnvError, Reason, ResetOptions};
use hyq_physics::PhysicsError;

fn check_diverged_step(env: &mut hyq_env::Env<hyq_env::testing::ScriptedBackend>) {
    let before = env.observation().to_vec();
    let info_before = env.info().clone();
    let s = env.step(&[0.2; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.terminated && !s.truncated);
    assert_eq!(s.reward, 0.0);
    assert!(s.info.reasons.contains(Reason::Diverged));
    assert!(!s.info.reasons.contains(Reason::Fell));
    assert_eq!(s.observation, before.as_slice());
    assert!(s.observation.iter().all(|v| v.is_finite()));
    assert!(s.observation_f32.iter().all(|v| v.is_finite()));
    let r = s.info.reward;
    assert_eq!(
        [
            r.r_b,
            r.r_n,
            r.r_e,
            r.r_reach,
            r.joint_penalty,
            r.fall_penalty,
            r.total
        ],
        [0.0; 7]
    );
    assert_eq!([r.m_yaw, r.m_pitch, r.m_height], [1.0; 3]);
    assert_eq!(s.info.distance_to_goal, info_before.distance_to_goal);
    assert_eq!(s.info.yaw, info_before.yaw);
    assert_eq!(s.info.t, info_before.t + 1);
    assert!(s.info.divergence.is_some());
    // The state the env reports stays the last finite one too.
    assert_eq!(env.joint_angles(), &before[..12]);
    let t = env.trunk();
    assert!(
        t.linvel
            .iter()
            .chain(t.pose.translation.vector.iter())
            .all(|v| v.is_finite())
    );
    assert!(
        env.policy_input()
            .joint_angles
            .iter()
            .all(|v| v.is_finite())
    );
    let err = env.step(&[0.0; 12]).err();
    assert!(matches!(err, Some(EnvError::EpisodeOver { .. })), "{err:?}");
    let r = env
        .reset(None, &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.info.t, 0);
    env.backend_mut().clear_script();
    assert!(env.step(&[0.0; 12]).is_ok());
}

#[test]
fn a_backend_diverged_error_in_a_middle_substep_ends_the_episode_finitely() {
    let mut env = scripted(&[("task.fall_penalty", "1")]);
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    env.backend_mut().set_script(|w| {
        if w.substep == 14 {
            w.q[0] = f64::NAN;
            return Err(PhysicsError::Diverged {
                what: "angle of joint lf_haa".into(),
            });
        }
        Ok(())
    });
    check_diverged_step(&mut env);
    let msg = env.info().divergence.clone();
    assert!(msg.is_none(), "reset clears it: {msg:?}");
}

#[test]
fn a_non_finite_reading_without_an_error_is_a_divergence_too() {
    for corrupt in 0..3 {
        let mut env = scripted(&[]);
        reset(&mut env, 0);
        env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
        env.backend_mut().set_script(move |w| {
            if w.substep == 20 {
                match corrupt {
                    0 => w.qd[5] = f64::INFINITY,
                    1 => w.trunk.pose.translation.z = f64::NAN,
                    _ => w.trunk.linvel.y = f64::NAN,
                }
            }
            Ok(())
        });
        check_diverged_step(&mut env);
    }
}

#[test]
fn a_velocity_so_large_the_acceleration_overflows_is_a_divergence() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.backend_mut().set_script(|w| {
        if w.substep == 10 {
            w.trunk.linvel.x = f64::MAX;
        }
        Ok(())
    });
    let before = env.observation().to_vec();
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.contains(Reason::Diverged));
    assert_eq!(s.observation, before.as_slice());
}

#[test]
fn a_divergence_on_the_last_step_also_reports_the_timeout() {
    let mut env = scripted(&[("task.max_time_steps", "1")]);
    reset(&mut env, 0);
    env.backend_mut().set_script(|_| {
        Err(PhysicsError::Diverged {
            what: "everything".into(),
        })
    });
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.contains(Reason::Diverged));
    assert!(s.info.reasons.contains(Reason::Timeout));
    assert!(s.terminated && !s.truncated);
}

/// The info's `divergence` of a step whose sub-steps `script` corrupts, after one good step.
fn divergence_of(
    script: impl FnMut(&mut hyq_env::testing::ScriptedWorld<'_>) -> Result<(), PhysicsError>
    + Send
    + 'static,
) -> Divergence {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    env.backend_mut().set_script(script);
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.contains(Reason::Diverged));
    s.info
        .divergence
        .clone()
        .unwrap_or_else(|| panic!("no divergence in {:?}", s.info))
}

#[test]
fn the_divergence_cause_is_typed_and_reads_as_the_info_reports_it() {
    let cause = divergence_of(|_| {
        Err(PhysicsError::Diverged {
            what: "angle of joint lf_haa".into(),
        })
    });
    assert!(matches!(cause, Divergence::Substep(_)), "{cause:?}");
    assert_eq!(
        cause.to_string(),
        "simulation diverged: angle of joint lf_haa is not finite after the step"
    );

    // In the last sub-step of the step (the first step took sub-steps 1-10).
    let cause = divergence_of(|w| {
        if w.substep == 20 {
            w.qd[2] = f64::INFINITY;
        }
        Ok(())
    });
    assert!(
        matches!(cause, Divergence::NonFiniteReading { .. }),
        "{cause:?}"
    );
    assert_eq!(
        cause.to_string(),
        "speed of joint lf_kfe (inf) is not finite after the step"
    );

    let cause = divergence_of(|w| {
        w.trunk.pose.translation.y = -250.0;
        Ok(())
    });
    assert_eq!(
        cause.to_string(),
        format!(
            "trunk_position_y = -250.0 m: the trunk left the world, which must lie within \
             ±{} m of the origin on each axis (m), the world of every engine: beyond it \
             rapier's f32 positions are too coarse for faithful physics",
            hyq_env::WORLD_HALF_EXTENT_M
        )
    );

    let cause = divergence_of(|w| {
        w.qd[2] = 1e39;
        Ok(())
    });
    assert_eq!(
        cause,
        Divergence::BeyondFloat32 {
            index: 14,
            name: "lf_kfe_speed".into(),
            value: 1e39
        }
    );
    assert_eq!(
        cause.to_string(),
        "observation row 14 (lf_kfe_speed) = 1e39 is beyond float32's range (±3.4028235e38)"
    );

    let cause = divergence_of(|w| {
        if w.substep == 20 {
            w.trunk.linvel.x = f64::MAX;
        }
        Ok(())
    });
    assert!(matches!(cause, Divergence::Observation(_)), "{cause:?}");
}
