//! Hostile input, round 4, items 10 and 11: a particle cloth's steps of any accepted length, and
//! the lightest nodes its constructor accepts.

use bevy::prelude::*;
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning};
use bevy_windfall::cloth::ClothGrid;

const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);

fn flag() -> ParticleCloth {
    let grid = ClothGrid {
        rows: 8,
        columns: 12,
        width: 1.5,
        height: 1.0,
    };
    ParticleCloth::new(grid, 0.2, AeroCoefficients::default(), Pinning::PoleColumn).unwrap()
}

fn fastest(cloth: &ParticleCloth) -> f32 {
    cloth
        .velocities()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f32::max)
}

/// Item 10: after settling in 5 m/s, steps of 1e-9 and 1e-6 s, and frame times alternating
/// between 1/60 s and 0.1 ms, move the flag no faster than steady frames do (they reached
/// 2e6 m/s and 161 220 m/s).
#[test]
fn slivers_of_steps_add_no_energy() {
    let wind = |_: Vec3| Vec3::new(5.0, 0.0, 0.0);
    let mut steady = flag();
    for _ in 0..120 {
        steady.step(1.0 / 60.0, G, &wind);
    }
    let mut steady_peak = 0.0f32;
    let mut mixed = steady.clone();
    for _ in 0..60 {
        steady.step(1.0 / 60.0, G, &wind);
        steady_peak = steady_peak.max(fastest(&steady));
    }
    for tiny in [1e-9, 1e-6, 1e-4] {
        let mut sliver = mixed.clone();
        let before = sliver.energy(G);
        sliver.step(tiny, G, &wind);
        assert!(
            fastest(&sliver) <= steady_peak,
            "a step of {tiny} s: {} m/s against {steady_peak} m/s steady",
            fastest(&sliver)
        );
        // In still air (no wind to feed it) a sliver adds no energy.
        sliver.step(tiny, G, &|_| Vec3::ZERO);
        assert!(sliver.energy(G) <= before + 1e-6 * before.abs().max(1.0));
    }
    let mut peak = 0.0f32;
    for frame in 0..120 {
        let dt = if frame % 2 == 0 { 1.0 / 60.0 } else { 1e-4 };
        mixed.step(dt, G, &wind);
        peak = peak.max(fastest(&mixed));
        assert!(mixed.positions().iter().all(|p| p.is_finite()));
    }
    assert!(
        peak <= 2.0 * steady_peak,
        "alternating frames: {peak} m/s against {steady_peak} m/s steady"
    );
}

/// Item 11: node masses below 1e-5 kg are refused by name; from there up the cloth stays finite
/// in still air and in a gale.
#[test]
fn the_lightest_nodes_are_refused_or_stay_finite() {
    let grid = ClothGrid {
        rows: 4,
        columns: 6,
        width: 1.0,
        height: 0.5,
    };
    let nodes = 24.0;
    let area = 0.5;
    for node_mass in [1e-12f32, 1e-9, 1e-6, 9e-6] {
        let refused = ParticleCloth::new(
            grid,
            node_mass * nodes / area,
            AeroCoefficients::default(),
            Pinning::PoleColumn,
        )
        .unwrap_err();
        assert_eq!(refused.field(), "areal_density", "{node_mass} kg");
    }
    for node_mass in [1.1e-5f32, 3e-5, 1e-4, 1e-3] {
        for speed in [0.0, 5.0, 30.0] {
            let mut cloth = ParticleCloth::new(
                grid,
                node_mass * nodes / area,
                AeroCoefficients::default(),
                Pinning::PoleColumn,
            )
            .unwrap();
            for _ in 0..120 {
                cloth.step(1.0 / 60.0, G, &|_| Vec3::new(speed, 0.0, 1.0));
            }
            assert!(
                cloth.positions().iter().all(|p| p.is_finite()),
                "{node_mass} kg in {speed} m/s"
            );
        }
    }
}

/// The largest relative stretch of a structural edge (along the yarns and between them).
fn stretch(cloth: &ParticleCloth, grid: ClothGrid) -> f32 {
    let p = cloth.positions();
    let (rows, columns) = (grid.rows, grid.columns);
    let dx = grid.width / (columns - 1) as f32;
    let dy = if rows > 1 {
        grid.height / (rows - 1) as f32
    } else {
        1.0
    };
    let mut most = 0.0f32;
    for k in 0..rows {
        for j in 0..columns {
            let i = k * columns + j;
            if j + 1 < columns {
                most = most.max(p[i].distance(p[i + 1]) / dx - 1.0);
            }
            if k + 1 < rows {
                most = most.max(p[i].distance(p[i + columns]) / dy - 1.0);
            }
        }
    }
    most
}

/// The air a node carries across the sheet, kg: an eighth of a flat plate's ρ π c / 4 per area
/// (c the smaller side), as `ParticleCloth` documents it.
fn added_mass(grid: ClothGrid) -> f32 {
    let per_area = 0.125
        * AeroCoefficients::AIR_DENSITY
        * std::f32::consts::FRAC_PI_4
        * grid.width.min(grid.height);
    per_area * grid.width * grid.height / (grid.rows * grid.columns) as f32
}

/// A 1.2 × 0.8 m cloth of `rows × columns` nodes of `node_mass` kg, pinned by its top row or
/// its pole column, and the wind `speed` m/s at `angle` rad across its plane.
fn random_cloth(
    (rows, columns): (usize, usize),
    node_mass: f32,
    top_row: bool,
    (speed, angle): (f32, f32),
) -> (ClothGrid, ParticleCloth, Vec3) {
    let grid = ClothGrid {
        rows,
        columns,
        width: 1.2,
        height: 0.8,
    };
    let areal = node_mass * (rows * columns) as f32 / (grid.width * grid.height);
    let pinning = if top_row {
        Pinning::TopRow
    } else {
        Pinning::PoleColumn
    };
    let cloth = ParticleCloth::new(grid, areal, AeroCoefficients::default(), pinning).unwrap();
    (
        grid,
        cloth,
        speed * Vec3::new(angle.cos(), 0.0, angle.sin()),
    )
}

proptest::proptest! {
    // A fixed seed: CI runs the same 64 cases each time (the wider random sweep behind the
    // ranges below, 20 000 cloths, is in docs/testing.md).
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(42),
        ..Default::default()
    })]

    /// Any grid, nodes of a gram to 100 g, wind up to a storm (35 m/s, up to 45° across the
    /// cloth's plane), gravity up to 3 g and
    /// any sequence of frame times from a microsecond to 1/30 s: the nodes stay finite and no
    /// edge stretches more than 10 %; in still air, with frames up to 1/60 s, a cloth at least as
    /// heavy as the air it carries gains no energy. What does not hold yet (lighter nodes,
    /// longer frames) is measured in docs/testing.md.
    #[test]
    fn particle_cloth_holds_for_any_grid_mass_wind_gravity_and_frames(
        rows in 2usize..8,
        columns in 2usize..10,
        // Log-uniform: each decade of node mass as likely as the next.
        log_mass in -3.0f32..-1.0,
        wind in (0.0f32..35.0, -std::f32::consts::FRAC_PI_4..std::f32::consts::FRAC_PI_4),
        gravity in 0.0f32..30.0,
        frames in proptest::collection::vec(1e-6f32..(1.0 / 30.0), 1..40),
        top_row in proptest::prelude::any::<bool>(),
    ) {
        let node_mass = 10f32.powf(log_mass);
        let (grid, mut cloth, u) = random_cloth((rows, columns), node_mass, top_row, wind);
        let g = Vec3::new(0.0, -gravity, 0.0);
        let mut still = cloth.clone();
        // Released from rest in still air, the cloth only loses energy (to within a hundredth of
        // its weight times its size: the projection's first-order error).
        let start = still.energy(g);
        let mass = node_mass * (rows * columns) as f32;
        let slack = 1e-2 * mass * gravity.max(1.0) * (grid.width + grid.height);
        let mut short_frames = true;
        for &dt in &frames {
            cloth.step(dt, g, &|_| u);
            proptest::prop_assert!(cloth.positions().iter().all(|p| p.is_finite()));
            let s = stretch(&cloth, grid);
            proptest::prop_assert!(s <= 0.1, "stretch {s} after a step of {dt} s");
            still.step(dt, g, &|_| Vec3::ZERO);
            proptest::prop_assert!(still.positions().iter().all(|p| p.is_finite()));
            let s = stretch(&still, grid);
            proptest::prop_assert!(s <= 0.1, "stretch {s} in still air after a step of {dt} s");
            short_frames &= dt <= 1.0 / 60.0;
            if short_frames && node_mass >= added_mass(grid) {
                let e = still.energy(g);
                proptest::prop_assert!(e <= start + slack, "energy {start} → {e} J in still air, step {dt} s");
            }
        }
    }

    /// Nodes lighter than a gram (down to the constructor's 1e-5 kg): finite in any wind,
    /// gravity and frames up to 1/30 s (their stretch and energy are not yet bounded:
    /// docs/testing.md).
    #[test]
    fn the_lightest_particle_cloths_stay_finite(
        rows in 2usize..8,
        columns in 2usize..10,
        log_mass in -4.95f32..-3.0,
        wind in (0.0f32..35.0, -std::f32::consts::FRAC_PI_4..std::f32::consts::FRAC_PI_4),
        gravity in 0.0f32..30.0,
        frames in proptest::collection::vec(1e-6f32..(1.0 / 30.0), 1..40),
        top_row in proptest::prelude::any::<bool>(),
    ) {
        let (_, mut cloth, u) = random_cloth((rows, columns), 10f32.powf(log_mass), top_row, wind);
        let g = Vec3::new(0.0, -gravity, 0.0);
        for &dt in &frames {
            cloth.step(dt, g, &|_| u);
            proptest::prop_assert!(cloth.positions().iter().all(|p| p.is_finite()), "{dt} s");
        }
    }
}
