//! The randomized stability suite: every part over wide ranges (β in [0, 5], wind 0–70 m/s,
//! steps up to 0.25 s, feathers to coins, degenerate meshes, lighter-than-fluid objects), with
//! invalid inputs mixed in. A valid input never gives NaN, a panic or a blow-up; an invalid one
//! gives a typed error naming a field that is indeed out of range. 11 500 cases in this file
//! (the per-part files add about 3 000 more).

use crate::common;

use bevy_windfall::freefall::Shape;
use std::f32::consts::PI;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::aero::{AeroError, Face, ParticleCloth, Pinning, PlateState, face_force};
use bevy_windfall::cloth::{ClothSim, ClothWindModel};
use bevy_windfall::freefall::{FallModel, FallPath, WindTilt};
use bevy_windfall::prelude::*;
use proptest::prelude::*;

const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);

/// A wind of `speed` m/s in the direction given by two angles.
fn wind_vector(speed: f32, yaw: f32, pitch: f32) -> Vec3 {
    speed
        * Vec3::new(
            yaw.cos() * pitch.cos(),
            pitch.sin(),
            yaw.sin() * pitch.cos(),
        )
}

/// The fields of `c` outside their documented ranges.
fn bad_wind_fields(c: &WindConfig) -> Vec<&'static str> {
    let mut bad = Vec::new();
    if !(c.roughness.is_finite() && c.roughness > 0.0) {
        bad.push("roughness");
    }
    if !(c.reference_speed.is_finite() && (0.0..=1e4).contains(&c.reference_speed)) {
        bad.push("reference_speed");
    }
    if !(c.beta.is_finite() && c.beta >= 0.0) {
        bad.push("beta");
    }
    if c.turbulence_intensity
        .is_some_and(|i| !(0.0..=10.0).contains(&i))
    {
        bad.push("turbulence_intensity");
    }
    if c.grid[0] < 2 {
        bad.push("grid.x");
    }
    if c.grid[1] < 2 {
        bad.push("grid.z");
    }
    if !(c.cell_size.is_finite() && c.cell_size > 0.0) {
        bad.push("cell_size");
    }
    bad
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// Any wind configuration, valid or not: a field that samples finite and bounded
    /// everywhere and at any time, or an error naming a field that is out of range.
    #[test]
    fn wind_builds_and_samples_finite_or_names_the_bad_field(
        speed in -5.0f32..75.0,
        beta in -0.5f32..5.0,
        roughness in -0.05f32..2.0,
        intensity in proptest::option::of(-0.2f32..3.0),
        grid in prop::array::uniform2(0usize..24),
        cell in -0.5f32..8.0,
        evolving in any::<bool>(),
        seed in any::<u64>(),
        probes in prop::collection::vec((prop::array::uniform3(-500.0f32..500.0), 0.0f32..1e4), 4),
    ) {
        let config = WindConfig {
            reference_speed: speed,
            beta,
            roughness,
            turbulence_intensity: intensity,
            grid,
            cell_size: cell,
            temporal: if evolving { TemporalMode::Evolving { samples: 4, period: 3.0 } } else { TemporalMode::Frozen },
            seed,
            ..default()
        };
        let bad = bad_wind_fields(&config);
        match WindField::new(config) {
            Err(e) => prop_assert!(bad.contains(&e.field()), "{e} but bad = {bad:?}"),
            Ok(field) => {
                prop_assert!(bad.is_empty(), "accepted {bad:?}");
                for (p, t) in probes {
                    let p = Vec3::from_array(p);
                    let v = field.velocity_at(p, t);
                    prop_assert!(v.is_finite(), "{v:?} at {p:?}");
                    // The mean at that height plus a generous 12 σ of turbulence there.
                    let h = p.y.max(0.0);
                    let scale = (field.mean_speed_at(h) / speed.max(1e-6)).max(1.0);
                    let bound = field.mean_speed_at(h) + 12.0 * field.sigma().length() * scale + 1e-3;
                    prop_assert!(v.length() <= bound, "|v| = {} > {bound}", v.length());
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// Feathers (1 mm, barely heavier than air) to coins (3 cm of metal) and lighter-than-fluid
    /// objects, in air or water, wind to 70 m/s, steps to 0.25 s: refused by name when lighter,
    /// otherwise finite poses and unit orientations all the way down.
    #[test]
    fn falling_objects_from_feathers_to_coins(
        size in -3.0f32..-1.5,
        thin in -3.0f32..-0.5,
        ratio in -2.0f32..1.2,
        water in any::<bool>(),
        shape in 0u8..3,
        dt in 1e-3f32..0.25,
        wind in (0.0f32..70.0, 0.0f32..(2.0 * PI), -0.5f32..0.5),
        seed in any::<u64>(),
    ) {
        let chord = 10f32.powf(size);
        let thickness = (chord * 10f32.powf(thin)).max(Shape::MIN_SIZE);
        let fluid = if water { Fluid::WATER } else { Fluid::AIR };
        // From 1 % of the fluid's density (a balloon) to 16 times water's (a gold coin).
        let density = fluid.density * 10f32.powf(ratio).min(16_000.0 / fluid.density);
        let shape = match shape {
            0 => Shape::Disk { diameter: chord, thickness },
            1 => Shape::Rectangle { length: 1.5 * chord, width: chord, thickness },
            _ => Shape::Ellipse { major: 1.5 * chord, minor: chord, thickness },
        };
        let object = FallingObject { shape, density, fluid, seed, ..default() };
        let regime = match object.regime() {
            Err(e) => {
                prop_assert_eq!(e.field(), "density");
                prop_assert!(density <= fluid.density, "refused a sinking object: {}", e);
                return Ok(());
            }
            Ok(r) => r,
        };
        prop_assert!(density > fluid.density);
        prop_assert!(regime.reynolds > 0.0 && regime.inertia > 0.0 && regime.descent_speed > 0.0);
        let model = FallModel::default();
        let start = Vec3::new(0.0, 10.0, 0.0);
        let mut path = FallPath::new(&model, object.scales(&regime), regime.main, seed, start, 0.0)
    .expect("a release within bounds");
        let tilt = WindTilt { max_angle: 0.6, reference_speed: 4.0 };
        let u = wind_vector(wind.0, wind.1, wind.2);
        for step in 1..=100 {
            path.advance(&model, dt, u, &tilt);
            let (p, q) = path.smoothed(0.5);
            prop_assert!(p.is_finite() && q.is_finite(), "{p:?} {q:?}");
            prop_assert!((q.length() - 1.0).abs() < 1e-3);
            // It moves with the wind plus its own motion: never farther than the wind carries
            // it plus a generous multiple of its descent speed.
            let reach = (wind.0 + 20.0 * regime.descent_speed + 1.0) * dt * step as f32;
            prop_assert!((p - start).length() <= reach, "{p:?} beyond {reach}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2500, ..ProptestConfig::default() })]

    /// Rigid plates from a 2 mm paper scrap to a 20 cm steel sheet, any pose, wind to 70 m/s,
    /// steps to 0.25 s: finite, and never faster relative to the wind than free fall over the
    /// elapsed time allows.
    #[test]
    fn rigid_plates_stay_finite_and_bounded(
        size in -2.7f32..-0.7,
        density in 50.0f32..8000.0,
        cells in 1usize..4,
        euler in prop::array::uniform3(-PI..PI),
        dt in 1e-3f32..0.25,
        wind in (0.0f32..70.0, 0.0f32..(2.0 * PI), -0.5f32..0.5),
        cd in 0.0f32..3.0,
        cl in 0.0f32..3.0,
        water in any::<bool>(),
    ) {
        let length = 10f32.powf(size);
        let coefficients = AeroCoefficients { drag: cd, lift: cl, density: if water { 997.0 } else { 1.204 } };
        let plate = RigidPlate::rectangle(length, 0.6 * length, 0.01 * length, density, coefficients, cells).unwrap();
        let u = wind_vector(wind.0, wind.1, wind.2);
        let mut s = PlateState {
            rotation: Quat::from_euler(EulerRot::XYZ, euler[0], euler[1], euler[2]),
            ..default()
        };
        for step in 1..=60 {
            plate.step(&mut s, dt, G, &|_| u, false);
            prop_assert!(s.position.is_finite() && s.velocity.is_finite() && s.angular_velocity.is_finite());
            prop_assert!((s.rotation.length() - 1.0).abs() < 1e-3);
            let bound = u.length() + 9.81 * dt * step as f32 + 1e-3;
            prop_assert!((s.velocity - u).length() <= bound, "{} > {bound}", (s.velocity - u).length());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1300, ..ProptestConfig::default() })]

    /// Degenerate meshes: faces of zero or huge area, zero, NaN or unnormalised normals, mixed
    /// with good ones. A bad mass or inertia is refused by name; the faces never produce NaN.
    #[test]
    fn degenerate_meshes_give_no_nan_or_a_named_error(
        faces in prop::collection::vec(
            (prop::array::uniform3(-1.0f32..1.0), prop::array::uniform3(-2.0f32..2.0), 0u8..4, 0.0f32..1.0),
            0..8,
        ),
        mass in -1e-3f32..1.0,
        inertia in prop::array::uniform3(-1e-4f32..1e-2),
        wind in (0.0f32..70.0, 0.0f32..(2.0 * PI), -0.5f32..0.5),
        dt in 1e-3f32..0.25,
    ) {
        let faces: Vec<Face> = faces
            .into_iter()
            .map(|(center, normal, kind, area)| Face {
                center: Vec3::from_array(center),
                normal: match kind {
                    0 => Vec3::ZERO,
                    1 => Vec3::NAN,
                    _ => Vec3::from_array(normal),
                },
                area: if kind == 3 { 0.0 } else { area },
            })
            .collect();
        let u = wind_vector(wind.0, wind.1, wind.2);
        for f in &faces {
            let force = face_force(u, f.normal, f.area, 1.2, 1.0, 1.204);
            prop_assert!(force.is_finite(), "{f:?} → {force:?}");
        }
        let inertia = Vec3::from_array(inertia);
        match RigidPlate::new(faces, mass, inertia, AeroCoefficients::default()) {
            Err(AeroError::Invalid(bevy_windfall::InvalidValue { field, value, .. })) => {
                let named = match field {
                    "mass" => mass,
                    "inertia.x" => inertia.x,
                    "inertia.y" => inertia.y,
                    "inertia.z" => inertia.z,
                    other => return Err(TestCaseError::fail(format!("unexpected field {other}"))),
                };
                prop_assert!(named <= 0.0 && named == value);
            }
            Ok(plate) => {
                prop_assert!(mass > 0.0 && inertia.min_element() > 0.0);
                let mut s = PlateState::default();
                for _ in 0..30 {
                    plate.step(&mut s, dt, G, &|_| u, false);
                    prop_assert!(s.velocity.is_finite() && s.position.is_finite() && s.rotation.is_finite());
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1200, ..ProptestConfig::default() })]

    /// Procedural cloth: θ to π, β to 5, shifts to ±50, 1×N to 16×24 grids, steps to 0.25 s,
    /// bad numbers mixed in. Valid cloth stays finite, keeps its leading yarn's length and eq. 7's
    /// bound between yarns; invalid cloth is refused by a named field.
    #[test]
    fn cloth_keeps_its_yarns_or_names_the_bad_field(
        rows in 0usize..16,
        columns in 0usize..24,
        amplitude in -0.2f32..=(PI + 0.2),
        beta in -0.2f32..5.0,
        wind_speed in 0.0f32..63.0,
        swirl in -50.0f32..=50.0,
        twist in -10.0f32..10.0,
        dt in 0.0f32..=0.25,
        non_frozen in any::<bool>(),
        seed in any::<u64>(),
    ) {
        let grid = ClothGrid { rows, columns, width: 1.5, height: 1.0 };
        let params = ClothParams {
            amplitude, beta, wind_steps_per_frame: wind_speed, swirl, twist, seed,
            model: if non_frozen { ClothWindModel::Evolving { frames: 4 } } else { ClothWindModel::Frozen },
            ..ClothParams::default()
        };
        let mut sim = match ClothSim::new(grid, params, ClothAttachment::Pole) {
            Err(e) => {
                let field = e.field();
                let bad = match field {
                    "grid.rows" => rows < 1,
                    "grid.columns" => columns < 2,
                    "params.amplitude" => !(0.0..=PI).contains(&amplitude),
                    "params.beta" => beta < 0.0,
                    _ => false,
                };
                prop_assert!(bad, "refused {field}: {e}");
                return Ok(());
            }
            Ok(sim) => sim,
        };
        prop_assert!(rows >= 1 && columns >= 2 && (0.0..=PI).contains(&amplitude) && beta >= 0.0);
        let leading = params.leading.index(rows);
        let gap = grid.row_spacing() * params.max_stretch;
        for _ in 0..4 {
            sim.advance(dt, wind_speed);
            sim.rebuild();
            let p = sim.positions();
            prop_assert!(p.iter().all(|p| p.is_finite()));
            // The leading yarn keeps its length (unit steps of the descriptor, eq. 4); the
            // others stay within eq. 7's distance of their neighbours.
            let yarn = &p[leading * columns..(leading + 1) * columns];
            let length: f32 = yarn.windows(2).map(|w| w[0].distance(w[1])).sum();
            prop_assert!((length - grid.width).abs() <= 1e-4 * grid.width, "yarn {length}");
            // Eq. 7 holds everywhere, on the pole edge (a hem eq. 8 bows) too.
            for (a, b) in p.iter().zip(&p[columns..]) {
                prop_assert!(a.distance(*b) <= gap * (1.0 + 1e-5) + 1e-6, "eq. 7 broken");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Particle cloth (XPBD) from silk to canvas in gales to 70 m/s, steps to 0.25 s: finite,
    /// and held by its tethers (no node farther from the pins than the cloth's extent).
    #[test]
    fn particle_cloth_stays_finite_and_attached(
        rows in 2usize..6,
        columns in 2usize..8,
        areal_density in 0.02f32..1.0,
        wind in (0.0f32..70.0, 0.0f32..(2.0 * PI), -0.5f32..0.5),
        dt in 1e-3f32..0.25,
        top_row in any::<bool>(),
    ) {
        let grid = ClothGrid { rows, columns, width: 1.0, height: 0.7 };
        let pinning = if top_row { Pinning::TopRow } else { Pinning::PoleColumn };
        let mut cloth = ParticleCloth::new(grid, areal_density, AeroCoefficients::default(), pinning).unwrap();
        let u = wind_vector(wind.0, wind.1, wind.2);
        // Each node is tethered to its pin, within its rest distance; so no node is farther
        // from the first pin than the pins are apart plus the cloth's extent from them.
        let reach = (grid.width + grid.height) * (1.0 + 1e-4);
        for _ in 0..10 {
            cloth.step(dt, G, &|_| u);
            let p = cloth.positions();
            prop_assert!(p.iter().all(|p| p.is_finite()));
            let far = p.iter().map(|q| q.distance(p[0])).fold(0.0, f32::max);
            prop_assert!(far <= reach, "a node tore away: {far} > {reach}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// The whole plugin group in one headless app: a random wind, a falling object, an aero
    /// body and a flag, fixed steps to 0.25 s. Every transform stays finite.
    #[test]
    fn the_plugins_together_stay_finite(
        speed in 0.0f32..70.0,
        beta in 0.0f32..5.0,
        step in 1e-3f32..0.25,
        density in 100.0f32..9000.0,
        size in 0.005f32..0.1,
        seed in any::<u64>(),
    ) {
        let mut app = App::new();
        app.add_plugins((MinimalPlugins, TransformPlugin))
            .insert_resource(Time::<Fixed>::from_seconds(f64::from(step)))
            .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
            .add_plugins(WindfallPlugins::default().set(WindPlugin::new(WindConfig {
                reference_speed: speed, beta, grid: [16, 16], seed, ..default()
            })));
        let shape = Shape::Disk { diameter: size, thickness: size * 0.05 };
        let plate = RigidPlate::rectangle(size, size, size * 0.05, density, AeroCoefficients::default(), 1).unwrap();
        let entities = [
            app.world_mut().spawn((FallingObject { shape, density, seed, ..default() }, Transform::from_xyz(0.0, 5.0, 0.0))).id(),
            app.world_mut().spawn((AeroBody::new(plate), Transform::from_xyz(1.0, 5.0, 0.0))).id(),
            app.world_mut().spawn(Cloth::default()).id(),
        ];
        common::ready(&mut app);
        for _ in 0..20 {
            app.update();
        }
        for e in entities {
            let t = app.world().get::<Transform>(e).unwrap();
            prop_assert!(t.translation.is_finite() && t.rotation.is_finite(), "{t:?}");
        }
        prop_assert!(app.world().get::<ClothState>(entities[2]).unwrap().sim.positions().iter().all(|p| p.is_finite()));
    }
}
