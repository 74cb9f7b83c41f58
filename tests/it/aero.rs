//! Aero: the face law's properties, and a rigid plate's terminal velocity, drift, stability and
//! energy.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::aero::*;
use bevy_windfall::wind::{WindConfig, WindPlugin};
use common::{headless_app, ready};
use proptest::prelude::*;

const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);

fn still(_: Vec3) -> Vec3 {
    Vec3::ZERO
}

#[test]
fn drag_opposes_and_lift_is_perpendicular_and_zero_at_both_extremes() {
    let v = Vec3::new(0.0, -3.0, 0.0);
    // Flow into the face (θ = 0): drag only, exactly ½ C_D ρ v² A.
    let f = face_force(v, Vec3::Y, 0.01, 1.2, 1.0, AeroCoefficients::AIR_DENSITY);
    let expected = 0.5 * 1.2 * AeroCoefficients::AIR_DENSITY * 9.0 * 0.01;
    assert!((f - Vec3::new(0.0, expected, 0.0)).length() < 1e-6, "{f:?}");
    // Flow along the face: nothing at all.
    assert_eq!(
        face_force(v, Vec3::X, 0.01, 1.2, 1.0, AeroCoefficients::AIR_DENSITY),
        Vec3::ZERO
    );
    // Either side of the face is the same face.
    let n = Vec3::new(0.3, 1.0, -0.2);
    assert_eq!(
        face_force(v, n, 0.01, 1.2, 1.0, AeroCoefficients::AIR_DENSITY),
        face_force(v, -n, 0.01, 1.2, 1.0, AeroCoefficients::AIR_DENSITY)
    );
    // Lift peaks at 45° and vanishes at 0° and 90°.
    let lift_at = |deg: f32| {
        let a = deg.to_radians();
        face_force(v, Vec3::new(a.sin(), a.cos(), 0.0), 1.0, 0.0, 1.0, 1.0).length()
    };
    assert!(lift_at(0.0) < 1e-6 && lift_at(90.0) < 1e-5);
    assert!(lift_at(45.0) > lift_at(30.0) && lift_at(45.0) > lift_at(60.0));
    assert!((lift_at(45.0) - 0.5 * 9.0 * 0.5).abs() < 1e-5);
}

#[test]
fn degenerate_faces_give_zero_not_nan() {
    let v = Vec3::new(1.0, 2.0, 3.0);
    for (v, n, a) in [
        (Vec3::ZERO, Vec3::Y, 1.0),
        (v, Vec3::ZERO, 1.0),
        (v, Vec3::NAN, 1.0),
        (Vec3::NAN, Vec3::Y, 1.0),
        (v, Vec3::Y, 0.0),
        (v, Vec3::Y, f32::NAN),
    ] {
        assert_eq!(
            face_force(v, n, a, 1.2, 1.0, AeroCoefficients::AIR_DENSITY),
            Vec3::ZERO,
            "{v:?} {n:?} {a}"
        );
    }
    // A force beyond f32's range is clamped, not dropped: it still opposes the motion.
    let huge = face_force(
        Vec3::splat(1e30),
        Vec3::Y,
        1e30,
        1.2,
        1.0,
        AeroCoefficients::AIR_DENSITY,
    );
    assert!(huge.is_finite() && huge.dot(Vec3::ONE) < 0.0, "{huge}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// Drag power ≤ 0 and lift ⟂ v_rel for any face and flow.
    #[test]
    fn drag_does_no_positive_work_and_lift_is_perpendicular(
        v in prop::array::uniform3(-100.0f32..100.0),
        n in prop::array::uniform3(-1.0f32..1.0),
        area in 0.0f32..2.0,
        cd in 0.0f32..3.0,
        cl in 0.0f32..3.0,
    ) {
        let (v, n) = (Vec3::from_array(v), Vec3::from_array(n));
        let total = face_force(v, n, area, cd, cl, AeroCoefficients::AIR_DENSITY);
        prop_assert!(total.is_finite());
        let drag = face_force(v, n, area, cd, 0.0, AeroCoefficients::AIR_DENSITY);
        let lift = face_force(v, n, area, 0.0, cl, AeroCoefficients::AIR_DENSITY);
        prop_assert!(drag.dot(v) <= 1e-6 * drag.length() * v.length() + 1e-9);
        prop_assert!(lift.dot(v).abs() <= 1e-4 * lift.length() * v.length() + 1e-9);
        prop_assert!(total.dot(v) <= 1e-4 * total.length() * v.length() + 1e-9);
    }
}

fn card() -> RigidPlate {
    // 8.5 × 5.5 cm, 0.3 mm, 700 kg/m³: a business card.
    RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 3).unwrap()
}

#[test]
fn broadside_plate_reaches_the_closed_form_terminal_velocity() {
    for (dt, cells) in [(1.0 / 60.0, 1), (1.0 / 60.0, 4), (0.25, 2)] {
        let plate = RigidPlate::rectangle(
            0.085,
            0.055,
            3e-4,
            700.0,
            AeroCoefficients::default(),
            cells,
        )
        .unwrap();
        let mut s = PlateState::default();
        for _ in 0..(10.0 / dt) as usize {
            plate.step(&mut s, dt, G, &still, true);
        }
        let c = plate.coefficients();
        let terminal = (2.0 * plate.mass() * 9.81 / (c.density * c.drag * plate.area())).sqrt();
        let speed = -s.velocity.y;
        assert!(
            (speed / terminal - 1.0).abs() < 0.02,
            "dt {dt}: {speed} vs {terminal}"
        );
        assert!(s.velocity.x.abs() < 1e-4 && s.velocity.z.abs() < 1e-4);
    }
}

#[test]
fn tilted_plate_drifts_sideways_by_lift() {
    let drift = |lift: f32| {
        let plate = RigidPlate::rectangle(
            0.085,
            0.055,
            3e-4,
            700.0,
            AeroCoefficients {
                lift,
                ..Default::default()
            },
            3,
        )
        .unwrap();
        let mut s = PlateState {
            rotation: Quat::from_rotation_z(0.4),
            ..Default::default()
        };
        for _ in 0..30 {
            plate.step(&mut s, 1.0 / 60.0, G, &still, true);
        }
        s.position.x
    };
    let (with, without) = (drift(1.0), drift(0.0));
    // The plate's upward normal leans toward −x (rotation about +z by 0.4): pushed toward −x.
    assert!(with < -0.01, "drift with lift {with}");
    assert!(
        without.abs() < 0.2 * with.abs(),
        "drift without lift {without}"
    );
}

#[test]
fn light_leaf_in_a_gale_relaxes_to_the_wind_without_overshoot() {
    // 0.1 g leaf, 5 × 4 cm, in a uniform 70 m/s wind, 10 s in steps of 1/30 s and 0.25 s.
    let leaf =
        RigidPlate::rectangle(0.05, 0.04, 1e-4, 500.0, AeroCoefficients::default(), 2).unwrap();
    assert!((leaf.mass() - 1e-4).abs() < 1e-6);
    let gale = |_: Vec3| Vec3::new(70.0, 0.0, 0.0);
    for dt in [1.0 / 30.0, 0.25] {
        // Tilted so the wind meets the face at about 45°.
        let mut s = PlateState {
            rotation: Quat::from_rotation_z(0.8),
            ..Default::default()
        };
        let mut max_x = 0.0f32;
        let mut lag = 70.0f32;
        for _ in 0..(10.0 / dt) as usize {
            leaf.step(&mut s, dt, G, &gale, false);
            assert!(s.velocity.is_finite() && s.rotation.is_finite(), "{s:?}");
            max_x = max_x.max(s.velocity.x);
            // The lag behind the wind only shrinks.
            assert!(70.0 - s.velocity.x <= lag + 1e-3, "dt {dt}: lag grew");
            lag = 70.0 - s.velocity.x;
        }
        assert!(
            max_x <= 70.0 * (1.0 + 1e-4),
            "dt {dt}: overshoot to {max_x}"
        );
        // Edge-on to the flow a flat plate has no drag in this model (no skin friction), so the
        // last metres per second come slowly.
        assert!(s.velocity.x > 50.0, "dt {dt}: only {}", s.velocity.x);
    }
}

#[test]
fn bad_configuration_names_its_field() {
    let c = AeroCoefficients::default();
    let cases = [
        (
            RigidPlate::rectangle(
                0.1,
                0.1,
                1e-3,
                500.0,
                AeroCoefficients { drag: -1.0, ..c },
                1,
            ),
            "drag",
        ),
        (
            RigidPlate::rectangle(
                0.1,
                0.1,
                1e-3,
                500.0,
                AeroCoefficients {
                    lift: f32::NAN,
                    ..c
                },
                1,
            ),
            "lift",
        ),
        (
            RigidPlate::rectangle(
                0.1,
                0.1,
                1e-3,
                500.0,
                AeroCoefficients { density: 0.0, ..c },
                1,
            ),
            "density",
        ),
        (RigidPlate::rectangle(0.0, 0.1, 1e-3, 500.0, c, 1), "length"),
        (RigidPlate::new(vec![], 0.0, Vec3::ONE, c), "mass"),
        (
            RigidPlate::new(vec![], 1.0, Vec3::new(1.0, -1.0, 1.0), c),
            "inertia.y",
        ),
    ];
    for (result, field) in cases {
        assert_eq!(result.unwrap_err().field(), field);
    }
}

fn run(seed: f32) -> Vec<u32> {
    let plate = card();
    let mut s = PlateState {
        rotation: Quat::from_euler(bevy::math::EulerRot::XYZ, 0.3 * seed, 0.2, -0.5),
        angular_velocity: Vec3::new(1.0, -2.0, 0.5),
        ..Default::default()
    };
    let wind = |p: Vec3| Vec3::new(3.0 + (p.y * 2.0).sin(), 0.0, (p.x * 3.0).cos());
    for _ in 0..300 {
        plate.step(&mut s, 1.0 / 60.0, G, &wind, false);
    }
    let q = s.rotation;
    [s.position.x, s.position.y, s.position.z, q.x, q.y, q.z, q.w]
        .map(f32::to_bits)
        .to_vec()
}

#[test]
fn same_input_same_flight_bit_for_bit() {
    assert_eq!(run(1.0), run(1.0));
    assert_ne!(run(1.0), run(2.0));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// Without wind the total energy never grows (beyond f32 rounding), from any pose and spin,
    /// with any step up to 0.25 s; in a random uniform wind up to 70 m/s nothing becomes NaN.
    #[test]
    fn energy_never_grows_in_still_air_and_gales_stay_finite(
        euler in prop::array::uniform3(-3.0f32..3.0),
        spin in prop::array::uniform3(-30.0f32..30.0),
        velocity in prop::array::uniform3(-20.0f32..20.0),
        dt in 1e-3f32..0.25,
        size in 0.005f32..0.5,
        density in 50.0f32..3000.0,
        wind in prop::array::uniform3(-70.0f32..70.0),
    ) {
        let plate = RigidPlate::rectangle(size, 0.7 * size, size * 0.01, density, AeroCoefficients::default(), 2).unwrap();
        let start = PlateState {
            rotation: Quat::from_euler(bevy::math::EulerRot::XYZ, euler[0], euler[1], euler[2]),
            angular_velocity: Vec3::from_array(spin),
            velocity: Vec3::from_array(velocity),
            ..Default::default()
        };
        let mut s = start;
        let mut energy = plate.energy(&s, G);
        for _ in 0..50 {
            plate.step(&mut s, dt, G, &still, true);
            let (kinetic, potential) = plate.energy_terms(&s, G);
            let e = kinetic + potential;
            // f32 rounding of the sum is about 1e-7 of its terms' size, per operation.
            let rounding = 1e-5 * (kinetic + potential.abs()) + 1e-12;
            prop_assert!(e <= energy + rounding, "{energy} → {e}");
            energy = e;
        }
        let gale = Vec3::from_array(wind);
        let mut s = start;
        for _ in 0..50 {
            plate.step(&mut s, dt, G, &|_| gale, false);
            prop_assert!(s.velocity.is_finite() && s.angular_velocity.is_finite() && s.rotation.is_finite());
            prop_assert!((s.velocity - gale).length() <= (start.velocity - gale).length().max(200.0));
        }
    }
}

fn body_app(wind: Option<WindConfig>) -> (App, Entity) {
    let mut app = headless_app();
    if let Some(config) = wind {
        app.add_plugins(WindPlugin {
            config: Some(config),
            ..default()
        });
    }
    app.add_plugins(AeroPlugin::default());
    let body = app
        .world_mut()
        .spawn((AeroBody::new(card()), Transform::from_xyz(0.0, 20.0, 0.0)))
        .id();
    ready(&mut app);
    (app, body)
}

#[test]
fn plugin_drops_the_card_from_its_transform_in_still_air() {
    let (mut app, body) = body_app(None);
    for _ in 0..600 {
        app.update();
    }
    let state = app.world().get::<AeroState>(body).unwrap().state;
    let plate = card();
    let c = plate.coefficients();
    let terminal = (2.0 * plate.mass() * 9.81 / (c.density * c.drag * plate.area())).sqrt();
    assert!(
        (-state.velocity.y / terminal - 1.0).abs() < 0.02,
        "{:?}",
        state.velocity
    );
    // Each update is exactly one fixed step (no overstep), so the transform shows the body as
    // it was one step ago, as avian's interpolation does: within one step's travel above it.
    let t = app.world().get::<Transform>(body).unwrap();
    let lag = t.translation.y - state.position.y;
    assert!(
        lag > 0.0 && lag <= -state.velocity.y / 60.0 * 1.05,
        "{lag} m above the state"
    );
    // 10 s of fall from 20 m at about 1.1 m/s.
    assert!(
        state.position.y < 20.0 - 0.9 * terminal * 9.0,
        "{:?}",
        state.position
    );
}

#[test]
fn plugin_carries_the_card_downwind() {
    let calm = WindConfig {
        reference_speed: 5.0,
        turbulence_intensity: Some(0.0),
        ..default()
    };
    let (mut app, body) = body_app(Some(calm));
    for _ in 0..300 {
        app.update();
    }
    let state = app.world().get::<AeroState>(body).unwrap().state;
    assert!(state.position.x > 1.0, "{:?}", state.position);
    assert!(state.velocity.x > 0.0 && state.velocity.x < 5.0 * 1.5);
}

fn flag(areal_density: f32) -> ParticleCloth {
    let grid = bevy_windfall::cloth::ClothGrid {
        rows: 12,
        columns: 18,
        width: 1.5,
        height: 1.0,
    };
    ParticleCloth::new(
        grid,
        areal_density,
        AeroCoefficients::default(),
        Pinning::PoleColumn,
    )
    .unwrap()
}

#[test]
fn physical_flag_hangs_in_still_air_and_streams_in_wind() {
    let pins: Vec<Vec3> = flag(0.2).positions().iter().step_by(18).copied().collect();
    let mut hanging = flag(0.2);
    for _ in 0..240 {
        hanging.step(1.0 / 60.0, G, &still);
    }
    // The pole column has not moved; the cloth keeps its lengths; the free edge has dropped.
    let after: Vec<Vec3> = hanging.positions().iter().step_by(18).copied().collect();
    assert_eq!(pins, after);
    // Millisecond substeps, the yarns solved together: a few per cent of stretch at most.
    assert!(
        hanging.max_strain() < 0.08,
        "strain {}",
        hanging.max_strain()
    );
    let free_corner = hanging.positions()[17];
    assert!(
        free_corner.y < -0.5 && free_corner.x < 0.8,
        "{free_corner:?}"
    );
    let mut streaming = flag(0.2);
    let breeze = |_: Vec3| Vec3::new(8.0, 0.0, 0.0);
    // It flies: over seconds 2–6 the free top corner is on average well downwind and at most
    // 30° below the pole's top, the Beaufort 5 flag of `physical_flag.rs` (it hangs far lower in
    // still air).
    let mut mean = Vec3::ZERO;
    for step in 0..360 {
        streaming.step(1.0 / 60.0, G, &breeze);
        if step >= 120 {
            mean += streaming.positions()[17] / 240.0;
        }
    }
    let droop = (-mean.y).atan2(mean.x).to_degrees();
    assert!(mean.x > 1.1 && droop <= 30.0, "{mean:?}: {droop:.1}°");
    assert!(
        streaming.max_strain() < 0.08,
        "strain {}",
        streaming.max_strain()
    );
}

/// A 12 × 18 flag flapping in an 8 m/s breeze for 2 s, and what its yarns' solves report.
fn yarn_solves_in_a_breeze() -> YarnSolves {
    let mut cloth = flag(0.15);
    assert_eq!(cloth.yarn_solves(), YarnSolves::default());
    let breeze = |_: Vec3| Vec3::new(8.0, 0.0, 0.0);
    for _ in 0..120 {
        cloth.step(1.0 / 60.0, G, &breeze);
    }
    cloth.yarn_solves()
}

/// The yarns' solves can be watched: each solve and its iterations are counted, and on so mild
/// a load no pivot of the lines' blocks needs guarding.
#[test]
fn physical_flag_reports_its_yarn_solves() {
    let solves = yarn_solves_in_a_breeze();
    // At least one linearisation per substep: 2 s of the default ticks.
    let substeps = (2.0 / ParticleCloth::SUBSTEP).round() as u64;
    assert!(solves.solves >= substeps, "{solves:?}");
    assert!(solves.iterations >= solves.solves, "{solves:?}");
    assert!(solves.unconverged <= solves.solves, "{solves:?}");
    assert_eq!(solves.guarded_pivots, 0, "{solves:?}");
    assert!((0.0..=1.0).contains(&solves.last_residual), "{solves:?}");
}

/// A cloth that reads the wind for all its nodes at once (as the plugin does) flies exactly as
/// one that reads it point by point, and a batch that leaves nodes out gives them still air.
#[test]
fn a_batched_wind_read_flies_the_flag_as_point_reads_do() {
    let field = bevy_windfall::wind::WindField::new(bevy_windfall::wind::WindConfig {
        reference_speed: 7.0,
        ..Default::default()
    })
    .unwrap();
    let lift = Vec3::new(0.3, 4.0, -1.2);
    let (mut points, mut batched) = (flag(0.15), flag(0.15));
    let bits = |c: &ParticleCloth| -> Vec<u32> {
        c.positions()
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .map(f32::to_bits)
            .collect()
    };
    let mut world = Vec::new();
    for _ in 0..90 {
        points.step(1.0 / 60.0, G, &|p: Vec3| field.velocity(p + lift));
        batched.step_batched(1.0 / 60.0, G, |nodes, velocities| {
            world.clear();
            world.extend(nodes.iter().map(|p| *p + lift));
            field.velocities(&world, velocities);
        });
    }
    assert_eq!(bits(&points), bits(&batched));
    assert!(points.positions().iter().all(|p| p.is_finite()));
    let (mut calm, mut empty) = (flag(0.15), flag(0.15));
    for _ in 0..30 {
        calm.step(1.0 / 60.0, G, &still);
        empty.step_batched(1.0 / 60.0, G, |_, velocities| velocities.clear());
    }
    assert_eq!(bits(&calm), bits(&empty));
}

/// A flag hanging in light air holds a nearly steady tension, and each substep's yarn solve
/// starts from the last one's (scaled to its substep): once it hangs, a solve takes at most
/// half the iterations of one from zero (9.7 a solve for this flag at 1.5 m/s, measured with
/// the warm start switched off; 3.5–4.2 with it).
#[test]
fn a_hanging_flags_yarn_solves_start_from_its_tension() {
    let mut cloth = flag(0.15);
    let light_air = |_: Vec3| Vec3::new(1.5, 0.0, 0.0);
    for _ in 0..60 {
        cloth.step(1.0 / 60.0, G, &light_air);
    }
    let settled = cloth.yarn_solves();
    for _ in 0..60 {
        cloth.step(1.0 / 60.0, G, &light_air);
    }
    let solves = cloth.yarn_solves();
    let per_solve =
        (solves.iterations - settled.iterations) as f64 / (solves.solves - settled.solves) as f64;
    println!("{per_solve:.2} iterations a solve, {solves:?}");
    assert!(per_solve <= 5.0, "{per_solve:.2} iterations a solve");
    assert_eq!(solves.unconverged, settled.unconverged, "{solves:?}");
}

/// Every yarn solve of a flag in a breeze reaches its tolerance within the iteration limit.
#[test]
#[ignore = "not met: 51 of 500 solves stop at the 12-iteration limit (5.5 iterations a solve \
            on average with the warm start, 4 ms ticks; 96 of 1000 at 2 ms; 245 and 8.5 from zero), measured with the \
            counters of physical_flag_reports_its_yarn_solves; a limit of 64 meets it at no \
            measurable cost but 4 ms ticks then swing +6.2 % over 1 ms at 8 m/s (docs/aero.md)"]
fn physical_flag_yarn_solves_reach_their_tolerance() {
    let solves = yarn_solves_in_a_breeze();
    assert_eq!(solves.unconverged, 0, "{solves:?}");
}

#[test]
fn physical_flag_survives_gales_and_huge_steps() {
    for dt in [1.0 / 30.0, 0.25] {
        let mut cloth = flag(0.05);
        let gale = |p: Vec3| Vec3::new(70.0, 5.0 * (p.y * 9.0).sin(), 3.0 * (p.x * 7.0).cos());
        let mut energy_start = f32::NAN;
        for step in 0..60 {
            cloth.step(dt, G, &gale);
            assert!(cloth.positions().iter().all(|p| p.is_finite()), "dt {dt}");
            // A flapping edge may whip past the wind speed, never run away.
            assert!(
                cloth.velocities().iter().all(|v| v.length() < 3.0 * 70.0),
                "dt {dt}"
            );
            if step == 0 {
                energy_start = cloth.energy(G);
            }
        }
        assert!(
            cloth.max_strain() < 0.5,
            "dt {dt}: strain {}",
            cloth.max_strain()
        );
        assert!(energy_start.is_finite());
    }
}

/// The air only takes energy out (the pressure and skin friction are implicit), but XPBD's
/// compliant constraints store and release energy within a step, so the test is the physical
/// bound: released from rest, the cloth never has more energy than it started with, and it
/// loses energy as it swings.
#[test]
fn physical_flag_never_exceeds_its_starting_energy_in_still_air() {
    let mut cloth = flag(0.2);
    let start = cloth.energy(G);
    let mut energy = start;
    for _ in 0..300 {
        cloth.step(1.0 / 60.0, G, &still);
        energy = cloth.energy(G);
        assert!(energy <= start, "{start} → {energy}");
    }
    assert!(energy < start - 0.1, "{start} → {energy}");
}

#[test]
fn bad_cloth_configuration_names_its_field() {
    let grid = bevy_windfall::cloth::ClothGrid::default();
    let c = AeroCoefficients::default();
    let e = ParticleCloth::new(grid, 0.0, c, Pinning::TopRow).unwrap_err();
    assert_eq!(e.field(), "areal_density");
    let e = ParticleCloth::new(
        grid,
        0.2,
        AeroCoefficients { drag: -1.0, ..c },
        Pinning::TopRow,
    )
    .unwrap_err();
    assert_eq!(e.field(), "drag");
}

#[test]
fn physical_flag_is_deterministic() {
    let run = || {
        let mut cloth = flag(0.15);
        let wind = |p: Vec3| Vec3::new(6.0 + (p.y * 3.0).sin(), 0.5 * (p.x * 5.0).cos(), 1.0);
        for _ in 0..120 {
            cloth.step(1.0 / 60.0, G, &wind);
        }
        cloth
            .positions()
            .iter()
            .flat_map(|p| p.to_array().map(f32::to_bits))
            .collect::<Vec<u32>>()
    };
    assert_eq!(run(), run());
}

#[test]
fn coefficients_can_be_tuned_live_and_bad_ones_are_refused_by_name() {
    let mut plate = card();
    let before = *plate.coefficients();
    let bad = AeroCoefficients {
        drag: -1.0,
        ..before
    };
    assert_eq!(
        plate.set_coefficients(bad).map_err(|e| e.field()),
        Err("drag")
    );
    assert_eq!(*plate.coefficients(), before);
    // Four times the drag halves the broadside terminal speed (v_t ∝ 1/√C_D).
    let terminal = |plate: &RigidPlate| {
        let mut s = PlateState::default();
        for _ in 0..600 {
            plate.step(&mut s, 1.0 / 60.0, G, &still, true);
        }
        -s.velocity.y
    };
    let slow = terminal(&plate);
    plate
        .set_coefficients(AeroCoefficients {
            drag: 4.0 * before.drag,
            ..before
        })
        .unwrap();
    let ratio = terminal(&plate) / slow;
    assert!((ratio - 0.5).abs() < 0.02, "ratio {ratio}");
}

/// The opt-in reactive air (Lighthill's force along the yarns) only takes energy out in still
/// air: released from rest, a flag and a curtain (under gravity tilted out of its plane, so that
/// it swings) never have more energy than they started with (beyond f32 rounding), and lose
/// some as they swing.
#[test]
fn reactive_air_never_exceeds_the_starting_energy_in_still_air() {
    const G: Vec3 = Vec3::new(0.0, -9.81, 3.0);
    for pinning in [Pinning::PoleColumn, Pinning::TopRow] {
        let grid = bevy_windfall::cloth::ClothGrid {
            rows: 12,
            columns: 18,
            width: 1.5,
            height: 1.0,
        };
        let mut cloth = ParticleCloth::new(grid, 0.2, AeroCoefficients::default(), pinning)
            .unwrap()
            .with_reactive_air();
        let start = cloth.energy(G);
        let mut energy = start;
        for _ in 0..300 {
            cloth.step(1.0 / 60.0, G, &still);
            energy = cloth.energy(G);
            assert!(
                energy <= start + 1e-6 * start.abs(),
                "{pinning:?}: {start} → {energy}"
            );
        }
        assert!(
            energy < start - 0.01 * start.abs(),
            "{pinning:?}: {start} → {energy}"
        );
        assert_eq!(cloth.reactive_guarded_pivots(), 0);
    }
}

/// Under the reactive air a flag stays finite and its yarns bounded from a gale to winds far
/// beyond weather, flipping sign from node to node and frame to frame or not finite at all.
#[test]
fn reactive_air_survives_gales_and_wild_winds() {
    type Wind = fn(Vec3) -> Vec3;
    let winds: [(&str, Wind); 4] = [
        ("gale", |p| {
            Vec3::new(70.0, 5.0 * (p.y * 9.0).sin(), 3.0 * (p.x * 7.0).cos())
        }),
        ("1e30 m/s", |_| Vec3::new(1e30, 0.0, 0.0)),
        ("±1e6 node to node", |p| {
            Vec3::new(1e6 * (p.x * 1e3).sin().signum(), 0.0, 1e6)
        }),
        ("NaN", |_| Vec3::NAN),
    ];
    for (label, wind) in winds {
        for dt in [1.0 / 60.0, 0.25] {
            let mut cloth = flag(0.05).with_reactive_air();
            for step in 0..40 {
                let flip = if step % 2 == 0 { 1.0 } else { -1.0 };
                cloth.step(dt, G, &|p| wind(p) * flip);
                assert!(
                    cloth.positions().iter().all(|p| p.is_finite()),
                    "{label}, dt {dt}"
                );
                assert!(cloth.energy(G).is_finite(), "{label}, dt {dt}");
            }
            assert!(
                cloth.max_strain() <= 0.5,
                "{label}, dt {dt}: strain {}",
                cloth.max_strain()
            );
        }
    }
}
