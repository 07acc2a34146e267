//! The terrain generators are deterministic functions of their parameters and seed (the same
//! seed gives the same grid bit for bit, another seed another grid), make the ground they say
//! (rough heights within ± the amplitude, a plane of the given angle through the anchor, steps
//! of the given height and depth starting where asked), and refuse every parameter out of range
//! with an error naming it; a grid is refused beyond the cap of 1024 × 1024 heights.

use hyq_physics::terrain::generate::{Climb, Extent, Relief, Rough, Slope, Stairs, generate};
use hyq_physics::terrain::{HeightGrid, MAX_GRID_POINTS};

fn extent(size: f64, resolution: f64) -> Extent {
    Extent {
        center: [1.0, -0.5],
        size: [size, size],
        resolution,
    }
}

fn rough(amplitude: f64, feature: f64) -> Relief {
    Relief::Rough(Rough { amplitude, feature })
}

fn stairs(step_height: f64, step_depth: f64, climb: Climb) -> Relief {
    Relief::Stairs(Stairs {
        step_height,
        step_depth,
        direction_deg: 0.0,
        climb,
        start: 0.5,
    })
}

#[test]
fn the_same_seed_gives_the_same_grid_bit_for_bit() {
    let e = extent(4.0, 0.05);
    let a = generate(&e, &rough(0.05, 0.2), [0.0, 0.0], 3).expect("valid");
    let b = generate(&e, &rough(0.05, 0.2), [0.0, 0.0], 3).expect("valid");
    let c = generate(&e, &rough(0.05, 0.2), [0.0, 0.0], 4).expect("valid");
    let bits = |g: &HeightGrid| g.heights().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_ne!(bits(&a), bits(&c));
    // A fixed seed's grid is pinned: the stream (ChaCha8) and the arithmetic are portable, so
    // a change here changes every terrain users have drawn.
    assert_eq!((a.columns(), a.rows()), (81, 81));
    let sum: f64 = a.heights().iter().sum();
    assert_eq!(a.heights()[0], 1.2296746394325776e-2);
    assert_eq!(sum, -8.056466212055865);
}

#[test]
fn rough_ground_stays_within_its_amplitude_and_uses_it() {
    let g = generate(&extent(4.0, 0.05), &rough(0.05, 0.2), [0.0, 0.0], 9).expect("valid");
    assert!(g.min_height() >= -0.05 && g.max_height() <= 0.05);
    assert!(
        g.max_height() - g.min_height() > 0.07,
        "{} .. {}",
        g.min_height(),
        g.max_height()
    );
    // Bumps are a feature across: neighbouring samples 5 cm apart differ by at most the
    // steepest lattice gradient, 2 × amplitude / feature.
    assert!(g.steepest_gradient() <= 2.0 * 0.05 / 0.2 * 1.5 + 1e-12);
    assert!(
        generate(&extent(4.0, 0.05), &rough(0.0, 0.2), [0.0, 0.0], 9)
            .expect("valid")
            .heights()
            .iter()
            .all(|&h| h == 0.0)
    );
}

#[test]
fn a_slope_is_a_plane_of_its_angle_through_the_anchor() {
    let anchor = [0.3, -0.2];
    let relief = Relief::Slope(Slope {
        angle_deg: 10.0,
        direction_deg: 90.0,
    });
    let g = generate(&extent(4.0, 0.1), &relief, anchor, 0).expect("valid");
    let tan = 10f64.to_radians().tan();
    for (x, y) in [(0.3, -0.2), (1.7, 0.9), (-0.5, -2.1), (2.2, 1.4)] {
        let expected = tan * (y - anchor[1]);
        assert!((g.height_at(x, y) - expected).abs() < 1e-12, "({x}, {y})");
    }
    assert!((g.steepest_gradient() - tan).abs() < 1e-9);
}

#[test]
fn stairs_rise_or_fall_a_step_per_depth_from_their_start() {
    let up = generate(
        &extent(4.0, 0.02),
        &stairs(0.1, 0.4, Climb::Up),
        [0.0, 0.0],
        0,
    )
    .expect("valid");
    let down = generate(
        &extent(4.0, 0.02),
        &stairs(0.1, 0.4, Climb::Down),
        [0.0, 0.0],
        0,
    )
    .expect("valid");
    // Treads (away from the risers, which rise across one 2 cm cell).
    for (x, steps) in [(-0.5, 0.0), (0.4, 0.0), (0.6, 1.0), (1.0, 2.0), (2.45, 5.0)] {
        assert!(
            (up.height_at(x, 0.0) - 0.1 * steps).abs() < 1e-12,
            "up at x = {x}"
        );
        assert!(
            (down.height_at(x, 0.0) + 0.1 * steps).abs() < 1e-12,
            "down at x = {x}"
        );
        // Stairs along +x are level across y.
        assert_eq!(up.height_at(x, -1.9), up.height_at(x, 1.4));
    }
}

#[test]
fn out_of_range_parameters_are_refused_by_name() {
    let e = extent(4.0, 0.05);
    let cases: Vec<(&str, Extent, Relief)> = vec![
        ("amplitude_m", e, rough(-0.01, 0.2)),
        ("amplitude_m", e, rough(f64::NAN, 0.2)),
        ("amplitude_m", e, rough(1.5, 0.2)),
        ("feature_m", e, rough(0.05, 0.01)),
        ("feature_m", e, rough(0.05, f64::INFINITY)),
        (
            "slope_deg",
            e,
            Relief::Slope(Slope {
                angle_deg: 50.0,
                direction_deg: 0.0,
            }),
        ),
        (
            "direction_deg",
            e,
            Relief::Slope(Slope {
                angle_deg: 5.0,
                direction_deg: f64::NAN,
            }),
        ),
        ("step_height_m", e, stairs(0.0, 0.3, Climb::Up)),
        ("step_height_m", e, stairs(-0.1, 0.3, Climb::Up)),
        ("step_depth_m", e, stairs(0.1, 0.05, Climb::Up)),
        ("resolution_m", extent(4.0, 0.0), rough(0.05, 0.2)),
        ("resolution_m", extent(4.0, f64::NAN), rough(0.05, 0.2)),
        ("size_m", extent(-4.0, 0.05), rough(0.05, 0.2)),
        ("resolution_m", extent(200.0, 0.001), rough(0.05, 0.2)),
    ];
    for (name, e, relief) in cases {
        let err = generate(&e, &relief, [0.0, 0.0], 0)
            .expect_err(&format!("{name} out of range must be refused"))
            .to_string();
        assert!(err.contains(name), "{name}: {err}");
        assert!(!err.contains('\n'), "{err}");
    }
}

#[test]
fn grids_are_capped_and_checked() {
    let too_many = 1025 * 1024;
    assert!(too_many > MAX_GRID_POINTS);
    let err = HeightGrid::new([0.0, 0.0], [10.0, 10.0], 1025, 1024, vec![0.0; too_many])
        .expect_err("over the cap")
        .to_string();
    assert!(
        err.contains("1048576") && err.contains("1024 × 1024"),
        "{err}"
    );
    let at_cap = HeightGrid::new([0.0, 0.0], [10.0, 10.0], 1024, 1024, vec![0.0; 1 << 20]);
    assert!(at_cap.is_ok());
    for (columns, rows, heights, what) in [
        (1, 5, vec![0.0; 5], "at least 2"),
        (2, 2, vec![0.0; 3], "3 values"),
        (2, 2, vec![0.0, f64::NAN, 0.0, 0.0], "not finite"),
        (2, 2, vec![0.0, 0.0, 150.0, 0.0], "beyond"),
    ] {
        let err = HeightGrid::new([0.0, 0.0], [1.0, 1.0], columns, rows, heights)
            .expect_err(what)
            .to_string();
        assert!(err.contains(what), "{what}: {err}");
    }
    let err = HeightGrid::new([99.0, 0.0], [4.0, 1.0], 2, 2, vec![0.0; 4])
        .expect_err("outside the world")
        .to_string();
    assert!(err.contains("within ±100"), "{err}");
}
