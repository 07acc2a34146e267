//! Prints the bundled robot model: bodies, joints, tracked bodies, mass and spawn clearance.
//!
//! `cargo run -p hyq-physics --example model_summary`

use hyq_physics::na::Isometry3;

fn main() {
    let model = hyq_physics::bundled::hyq();
    println!(
        "robot {} total mass {:.4} kg",
        model.name(),
        model.total_mass()
    );
    for (i, l) in model.links().iter().enumerate() {
        println!(
            "link {i:2} {:14} parent {:?} joint {:?} mass {:.4} com {:?} shapes {} lumped {:?}",
            l.name,
            l.parent,
            l.parent_joint,
            l.mass,
            l.com.as_slice(),
            l.collisions.len(),
            l.lumped
        );
    }
    for (i, j) in model.joints().iter().enumerate() {
        println!(
            "joint {i:2} {:7} {:13} {} -> {} limits [{:.4}, {:.4}] effort {} vel {} damping {}",
            j.name,
            j.urdf_name,
            j.parent,
            j.child,
            j.lower,
            j.upper,
            j.effort,
            j.velocity,
            j.damping
        );
    }
    let state = model.spawn_state();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    if let Err(e) = model.link_poses(&state.trunk.pose, &state.q, &mut poses) {
        eprintln!("forward kinematics failed: {e}");
        return;
    }
    for (i, t) in model.tracked().iter().enumerate() {
        println!(
            "tracked {i} {:6} link {} shapes {:?} lowest z at spawn {:.6}",
            t.name,
            t.link,
            t.shapes,
            model.tracked_lowest_z(i, &poses)
        );
    }
    println!(
        "lowest point of the robot at spawn: {:.6} m",
        model.lowest_z(&poses)
    );
    println!(
        "centre of mass at spawn: {:?}",
        model.centre_of_mass(&poses).as_slice()
    );
}
