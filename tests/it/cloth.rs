//! Cloth: descriptor length, eq. 7 and eq. 8, travelling waves, wind coupling, mesh, extremes.
use crate::common;

use std::f32::consts::PI;

use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::prelude::*;
use bevy_windfall::cloth::*;
use bevy_windfall::wind::WindConfig;
use common::{headless_app, headless_app_with_meshes, ready};
use proptest::prelude::*;

fn sim(grid: ClothGrid, params: ClothParams) -> ClothSim {
    ClothSim::new(grid, params, ClothAttachment::Pole).unwrap()
}

#[test]
fn filtered_yarns_keep_their_length() {
    let segments = 40;
    let noise = bevy_windfall::spectrum::fbm(&[16, 64], 2.5, 4).unwrap();
    for filter in [
        HarmonicFilter::All,
        HarmonicFilter::LowPass { max: 2 },
        HarmonicFilter::BandPass { min: 3, max: 7 },
        HarmonicFilter::BandPass { min: 30, max: 40 },
    ] {
        let mut descriptor = DescriptorFilter::new(segments, filter);
        for row in 0..16 {
            let angles: Vec<f32> = (0..segments).map(|j| PI * noise[row * 64 + j]).collect();
            let mut directions = vec![Vec2::ZERO; segments];
            descriptor.directions(&angles, &mut directions);
            let mut points = vec![Vec2::ZERO; segments + 1];
            descriptor::trace_yarn(Vec2::ZERO, &directions, 0.05, &mut points);
            let length: f32 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
            let expected = segments as f32 * 0.05;
            assert!(
                ((length - expected) / expected).abs() < 1e-5,
                "{filter:?}: {length}"
            );
        }
    }
    // The public contract.
    let points = descriptor::yarn_from_angles(&[0.3, -1.0, 2.0, 0.0], 0.5);
    assert_eq!(points.len(), 5);
    let length: f32 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    assert!((length - 2.0).abs() < 1e-5);
}

/// Largest distance between a node and its neighbour one yarn nearer the leading yarn, the pole
/// edge included.
fn worst_neighbour_gap(s: &ClothSim) -> f32 {
    let (rows, columns) = (s.grid().rows, s.grid().columns);
    let leading = s.params().leading.index(rows);
    let p = s.positions();
    let mut worst = 0.0f32;
    for k in 0..rows {
        if k == leading {
            continue;
        }
        let toward = if k < leading { k + 1 } else { k - 1 };
        for j in 0..columns {
            worst = worst.max(p[k * columns + j].distance(p[toward * columns + j]));
        }
    }
    worst
}

#[test]
fn neighbouring_yarns_never_exceed_l_eq_7() {
    let grid = ClothGrid::default();
    for preset in ClothPreset::ALL {
        for leading in [LeadingYarn::Top, LeadingYarn::Center, LeadingYarn::Bottom] {
            for stretch in [1.0, 1.3] {
                let params = ClothParams {
                    leading,
                    max_stretch: stretch,
                    twist: 0.7,
                    ..preset.params()
                };
                let mut s = sim(grid, params);
                for _ in 0..20 {
                    s.advance(0.05, params.wind_steps_per_frame);
                    s.rebuild();
                    let limit = grid.row_spacing() * stretch * (1.0 + 1e-5);
                    assert!(worst_neighbour_gap(&s) <= limit, "{preset:?} {leading:?}");
                }
            }
        }
    }
}

#[test]
fn pole_edge_is_where_eq_8_puts_it() {
    let grid = ClothGrid {
        rows: 9,
        ..default()
    };
    let (bow, lean) = (0.1, 0.05);
    let params = ClothParams {
        bow,
        lean,
        ..ClothPreset::BannerFlappingFrozen.params()
    };
    let mut s = sim(grid, params);
    // At the reference speed the arcs have their full size: W1 and W2 of the edge's length.
    let steps = ClothSim::steps_for_speed(params.reference_speed, grid.width);
    let spacing = grid.row_spacing();
    for _ in 0..10 {
        s.advance(0.1, steps);
        s.rebuild();
        let edge: Vec<Vec3> = (0..grid.rows)
            .map(|k| s.positions()[k * grid.columns])
            .collect();
        for (k, got) in edge.iter().enumerate() {
            let alpha = k as f32 * PI / (grid.rows - 1) as f32;
            let arc = if k == 0 || k + 1 == grid.rows {
                0.0
            } else {
                alpha.sin()
            };
            let across = Vec2::new(got.x, got.z);
            let expected = Vec2::new(bow, lean) * grid.height * arc;
            assert!(
                across.distance(expected) < 1e-4,
                "row {k}: {got} vs {expected}"
            );
        }
        // A hem of fixed length: every node a row spacing from the one above it (eq. 7 holds on
        // the pole edge too), so the bow lifts the lower end up the pole by about (π W / 2)² / H.
        for (k, pair) in edge.windows(2).enumerate() {
            let gap = pair[0].distance(pair[1]);
            assert!((gap - spacing).abs() < 1e-5, "rows {k}, {}: {gap}", k + 1);
        }
        let lift = grid.height + edge[grid.rows - 1].y;
        let expected = (PI * Vec2::new(bow, lean).length() / 2.0).powi(2) * grid.height;
        assert!(
            (lift - expected).abs() < 0.2 * expected,
            "the lower end rose {lift} m, about {expected} m expected"
        );
    }
}

fn cloth_app(wind: Option<WindConfig>, cloth: Cloth) -> (App, Entity) {
    let mut app = headless_app();
    app.add_plugins(ClothPlugin::default());
    if let Some(config) = wind {
        app.add_plugins(bevy_windfall::wind::WindPlugin::new(config));
    }
    let entity = app.world_mut().spawn(cloth).id();
    ready(&mut app);
    (app, entity)
}

#[test]
fn wind_field_sets_speed_and_streaming_direction() {
    let config = WindConfig {
        reference_speed: 6.0,
        direction: Vec2::new(0.0, 1.0), // toward +Z
        turbulence_intensity: Some(0.0),
        ..default()
    };
    let cloth = Cloth::default();
    let (mut app, entity) = cloth_app(Some(config), cloth);
    app.world_mut()
        .entity_mut(entity)
        .insert(Transform::from_xyz(0.0, 10.0, 0.0));
    for _ in 0..240 {
        app.update();
    }
    let state = app.world().get::<ClothState>(entity).unwrap();
    // Noise moving at the wind's 6 m/s along a 1.5 m yarn of 32 cells: 2.56 cells a frame.
    let expected = 6.0 * 32.0 / (50.0 * 1.5);
    assert!(
        (state.wind_steps_per_frame - expected).abs() < 1e-3,
        "{}",
        state.wind_steps_per_frame
    );
    // Local +X turned onto +Z: a rotation of −90° about Y.
    assert!((state.yaw + PI / 2.0).abs() < 0.01, "yaw {}", state.yaw);
    // Without a wind field the cloth's own parameter drives it.
    let (mut app, entity) = cloth_app(None, Cloth::default());
    app.update();
    let state = app.world().get::<ClothState>(entity).unwrap();
    assert_eq!(
        state.wind_steps_per_frame,
        Cloth::default().params.wind_steps_per_frame
    );
    assert!(state.sim.shift_along() > 0.0);
}

fn positions_after(seed: u64, steps: usize) -> Vec<u32> {
    let cloth = Cloth {
        params: ClothParams {
            seed,
            ..ClothPreset::CurtainFlutteringEvolving.params()
        },
        ..default()
    };
    let (mut app, entity) = cloth_app(Some(WindConfig::default()), cloth);
    // Up in the wind (at the ground the log law gives calm air, and a calm flag hangs still).
    app.world_mut()
        .entity_mut(entity)
        .insert(Transform::from_xyz(0.0, 10.0, 0.0));
    for _ in 0..steps {
        app.update();
    }
    let mut state = app.world_mut().get_mut::<ClothState>(entity).unwrap();
    state.sim.rebuild();
    state
        .sim
        .positions()
        .iter()
        .flat_map(|p| p.to_array())
        .map(f32::to_bits)
        .collect()
}

#[test]
fn same_seed_same_cloth_bit_for_bit() {
    let a = positions_after(5, 120);
    assert_eq!(a, positions_after(5, 120));
    assert_ne!(a, positions_after(6, 120));
}

#[test]
fn mesh_is_double_sided_and_rewritten_in_place() {
    let mut app = headless_app_with_meshes();
    app.add_plugins(ClothPlugin::default());
    let grid = ClothGrid {
        rows: 5,
        columns: 7,
        ..default()
    };
    let entity = app.world_mut().spawn(Cloth { grid, ..default() }).id();
    ready(&mut app);
    let read = |app: &App| {
        let handle = app.world().get::<Mesh3d>(entity).unwrap().0.clone();
        let mesh = app.world().resource::<Assets<Mesh>>().get(&handle).unwrap();
        let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION)
        else {
            panic!("positions")
        };
        let Some(VertexAttributeValues::Float32x3(n)) = mesh.attribute(Mesh::ATTRIBUTE_NORMAL)
        else {
            panic!("normals")
        };
        (p.clone(), n.clone(), mesh.indices().unwrap().len())
    };
    let (p0, n0, indices) = read(&app);
    assert_eq!(p0.len(), 2 * 5 * 7);
    assert_eq!(indices, 12 * 4 * 6);
    for i in 0..35 {
        assert_eq!(p0[i], p0[i + 35]);
        let (front, back) = (Vec3::from(n0[i]), Vec3::from(n0[i + 35]));
        assert!((front.length() - 1.0).abs() < 1e-4 && (front + back).length() < 1e-6);
    }
    for _ in 0..10 {
        app.update();
    }
    let (p1, _, _) = read(&app);
    assert_ne!(p0, p1, "the mesh moves");
    // Same handle: edited in place, not replaced.
    assert_eq!(app.world().resource::<Assets<Mesh>>().len(), 1);
}

#[test]
fn bad_configuration_names_its_field() {
    let grid = ClothGrid::default();
    let params = ClothParams::default();
    let cases: Vec<(&str, ClothGrid, ClothParams)> = vec![
        ("grid.rows", ClothGrid { rows: 0, ..grid }, params),
        ("grid.columns", ClothGrid { columns: 1, ..grid }, params),
        ("grid.width", ClothGrid { width: 0.0, ..grid }, params),
        (
            "grid.height",
            ClothGrid {
                height: f32::NAN,
                ..grid
            },
            params,
        ),
        (
            "grid",
            ClothGrid {
                rows: 1 << 12,
                columns: 1 << 12,
                ..grid
            },
            params,
        ),
        (
            "params.amplitude",
            grid,
            ClothParams {
                amplitude: 4.0,
                ..params
            },
        ),
        (
            "params.beta",
            grid,
            ClothParams {
                beta: -1.0,
                ..params
            },
        ),
        (
            "params.wind_steps_per_frame",
            grid,
            ClothParams {
                wind_steps_per_frame: f32::INFINITY,
                ..params
            },
        ),
        (
            "params.max_stretch",
            grid,
            ClothParams {
                max_stretch: 0.5,
                ..params
            },
        ),
        (
            "params.filter",
            grid,
            ClothParams {
                filter: HarmonicFilter::BandPass { min: 5, max: 3 },
                ..params
            },
        ),
        (
            "params.model.frames",
            grid,
            ClothParams {
                model: ClothWindModel::Evolving { frames: 1 },
                ..params
            },
        ),
        (
            "params.model.frames",
            grid,
            ClothParams {
                model: ClothWindModel::Evolving { frames: 1 << 40 },
                ..params
            },
        ),
        ("params.bow", grid, ClothParams { bow: 2.0, ..params }),
        (
            "params.reference_speed",
            grid,
            ClothParams {
                reference_speed: 0.0,
                ..params
            },
        ),
    ];
    for (field, grid, params) in cases {
        let err = ClothSim::new(grid, params, ClothAttachment::Pole)
            .err()
            .expect(field);
        assert_eq!(err.field(), field, "{err}");
    }
    // Through the plugin: an invalid cloth gets a ClothInvalid, not a panic.
    let (app, entity) = cloth_app(
        None,
        Cloth {
            grid: ClothGrid { columns: 1, ..grid },
            ..default()
        },
    );
    assert_eq!(
        app.world().get::<ClothInvalid>(entity).unwrap().0.field(),
        "grid.columns"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// θ up to π, shifts up to 50, tiny and 1×N grids, time steps up to 0.25 s: finite shapes
    /// that keep eq. 7.
    #[test]
    fn extreme_but_valid_cloths_stay_finite(
        rows in 1usize..12,
        columns in 2usize..40,
        amplitude in 0.0f32..=PI,
        beta in 0.0f32..6.0,
        wind_speed in 0.0f32..=50.0,
        swirl in -50.0f32..=50.0,
        twist in -10.0f32..10.0,
        dt in 0.0f32..=0.25,
        non_frozen in any::<bool>(),
        rod in any::<bool>(),
        seed in any::<u64>(),
    ) {
        let grid = ClothGrid { rows, columns, width: 1.0, height: 0.6 };
        let params = ClothParams {
            amplitude, beta, wind_steps_per_frame: wind_speed, swirl, twist, seed,
            model: if non_frozen { ClothWindModel::Evolving { frames: 4 } } else { ClothWindModel::Frozen },
            ..ClothParams::default()
        };
        let attachment = if rod { ClothAttachment::Rod } else { ClothAttachment::Pole };
        let mut s = ClothSim::new(grid, params, attachment).unwrap();
        for _ in 0..5 {
            s.advance(dt, wind_speed);
            s.rebuild();
            prop_assert!(s.positions().iter().all(|p| p.is_finite()));
            prop_assert!(worst_neighbour_gap(&s) <= grid.row_spacing() * (1.0 + 1e-5) + 1e-6);
        }
        let mesh = mesh::build(rows, columns, s.positions());
        let Some(VertexAttributeValues::Float32x3(n)) = mesh.attribute(Mesh::ATTRIBUTE_NORMAL) else { panic!() };
        prop_assert!(n.iter().all(|n| Vec3::from(*n).is_finite()));
    }
}

#[test]
fn zero_and_huge_wind_are_fine() {
    for speed in [0.0, 1.0e4] {
        let config = WindConfig {
            reference_speed: speed,
            ..default()
        };
        let (mut app, entity) = cloth_app(Some(config), Cloth::default());
        for _ in 0..30 {
            app.update();
        }
        let mut state = app.world_mut().get_mut::<ClothState>(entity).unwrap();
        state.sim.rebuild();
        assert!(state.sim.positions().iter().all(|p| p.is_finite()));
        assert!(state.wind_steps_per_frame <= 50.0 && state.yaw.is_finite());
    }
}

/// Largest distance between neighbouring yarns' nodes past the pole edge (which eq. 8 bows).
fn worst_gap_anywhere(s: &ClothSim) -> (f32, usize) {
    let (rows, columns) = (s.grid().rows, s.grid().columns);
    let p = s.positions();
    let mut worst = (0.0f32, 0);
    for k in 0..rows - 1 {
        for j in 0..columns {
            let gap = p[k * columns + j].distance(p[(k + 1) * columns + j]);
            if gap > worst.0 {
                worst = (gap, j);
            }
        }
    }
    worst
}

#[test]
fn eq_7_holds_on_every_preset_in_a_wind_gusting_for_long() {
    // The held-out probe: 24 × 36 nodes, 1.5 m, on a pole, the wind's speed wandering over
    // 0–50 noise cells a frame, for many frames; every gap between neighbouring yarns, the pole
    // edge's included, stays within L = row spacing × max_stretch (to rounding).
    let grid = ClothGrid {
        rows: 24,
        columns: 36,
        width: 1.5,
        height: 1.0,
    };
    for preset in ClothPreset::ALL {
        let params = preset.params();
        let mut s = sim(grid, params);
        let limit = grid.row_spacing() * params.max_stretch;
        let mut worst = (0.0f32, 0usize, 0usize);
        let steps = if preset == ClothPreset::FlagFlappingFrozen {
            20_000
        } else {
            2_000
        };
        for i in 0..steps {
            let t = i as f32 * 0.02;
            let speed = 25.0 + 25.0 * (0.37 * t).sin() * (0.11 * t + 1.0).cos();
            s.advance(0.02, speed);
            s.rebuild();
            let (gap, j) = worst_gap_anywhere(&s);
            if gap > worst.0 {
                worst = (gap, j, i);
            }
        }
        println!(
            "{preset:?}: worst gap {:.3} mm over L (column {}, step {})",
            (worst.0 - limit) * 1e3,
            worst.1,
            worst.2
        );
        assert!(
            worst.0 <= limit * (1.0 + 1e-5),
            "{preset:?}: a gap of {} m at column {} (step {}), L = {limit} m",
            worst.0,
            worst.1,
            worst.2
        );
    }
}
