//! The `WindField`: spectrum in time, amplitudes, profile, modes, extremes, errors.

use crate::common::measure;
use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindField;
use measure::{fit_slope, mean_variance, series_spectrum};
use proptest::prelude::*;

fn config() -> WindConfig {
    WindConfig {
        reference_speed: 5.0,
        seed: 21,
        ..default()
    }
}

/// Mean power spectrum of the u, v, w turbulence seen at fixed points at the reference height
/// while the frozen pattern blows past for exactly one period of the grid.
fn frozen_point_spectra(field: &WindField, points: usize, per_cell: usize) -> [Vec<f64>; 3] {
    let c = field.config();
    let n = c.grid[0] * per_cell;
    let dt = c.grid[0] as f32 * c.cell_size / c.reference_speed / n as f32;
    let mut spectra: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; n / 2 + 1]);
    for p in 0..points {
        // On a node line: between nodes, linear interpolation steepens the spectrum (across the
        // wind it mixes the coherent low and incoherent high frequencies of two lines; along it,
        // it multiplies the spectrum by sinc²).
        let at = Vec3::new(0.0, c.reference_height, p as f32 * c.cell_size);
        let series: Vec<Vec3> = (0..n)
            .map(|i| field.velocity_at(at, i as f32 * dt) - Vec3::X * c.reference_speed)
            .collect();
        for (axis, spectrum) in spectra.iter_mut().enumerate() {
            let s: Vec<f32> = series.iter().map(|v| v[axis]).collect();
            for (t, p) in spectrum.iter_mut().zip(series_spectrum(&s)) {
                *t += p;
            }
        }
    }
    spectra
}

#[test]
fn frozen_time_series_has_kolmogorov_slope() {
    // A line along the wind only follows f^−β at frequencies above the transverse grid's
    // frequency spacing, so the transverse axes are as long as the one along the wind.
    for (spatial, grid, k_hi) in [
        (SpatialMode::Plane, [256, 256], 32),
        (SpatialMode::Volume { vertical_nodes: 64 }, [64, 64], 12),
    ] {
        // Low frequencies have few modes per realisation: average over independent seeds (the
        // slope of 16 seeds scatters by ±0.05 from block to block, of 48 by about ±0.03).
        // One sample per cell of travel reads the nodes themselves; finer sampling adds the
        // sinc² roll-off of linear interpolation (−0.1 in slope at an eighth of Nyquist).
        let mut total: [Vec<f64>; 3] = Default::default();
        for seed in 0..48 {
            let field = WindField::new(WindConfig {
                spatial,
                grid,
                seed,
                ..config()
            })
            .unwrap();
            for (t, s) in total
                .iter_mut()
                .zip(frozen_point_spectra(&field, grid[1], 1))
            {
                t.resize(s.len(), 0.0);
                t.iter_mut().zip(s).for_each(|(t, s)| *t += s);
            }
        }
        // k counts cycles per period of the grid along the wind.
        for (axis, spectrum) in total.iter().enumerate() {
            let slope = fit_slope(spectrum, 2, k_hi);
            assert!(
                (slope + 5.0 / 3.0).abs() <= 0.1,
                "{spatial:?} component {axis}: slope {slope:.3}"
            );
        }
    }
}

#[test]
fn components_follow_eq_12_ratios_and_surface_layer_level() {
    // What anemometers at the reference height record while the frozen pattern blows past for
    // one period of the grid: eight masts across the wind, sampled between the nodes. One
    // realisation's variances rest on a few low modes (σv/σu ranges over 0.66–1.07 for eight
    // seeds): the variances are pooled over 32 seeds.
    let mut samples: [Vec<f32>; 3] = Default::default();
    for seed in 21..53 {
        let field = WindField::new(WindConfig { seed, ..config() }).unwrap();
        let c = field.config();
        let period = c.grid[0] as f32 * c.cell_size / c.reference_speed;
        let steps = 4 * c.grid[0];
        for mast in 0..8 {
            let p = Vec3::new(
                0.37,
                c.reference_height,
                (mast as f32 * 7.3 + 0.41) * c.cell_size,
            );
            for i in 0..steps {
                let v = field.velocity_at(p, i as f32 * period / steps as f32);
                for (axis, s) in samples.iter_mut().enumerate() {
                    s.push(v[axis]);
                }
            }
        }
    }
    let sd: Vec<f64> = samples.iter().map(|s| mean_variance(s).1.sqrt()).collect();
    let u_star = f64::from(WindField::new(config()).unwrap().friction_velocity());
    // World axes: x along the wind (u), y up (w), z across (v). Pooled, the ratios hold to a
    // few per cent, and interpolating between nodes smooths
    // every component alike (a little below the nodes' 2.5 u*).
    assert!(
        (sd[2] / sd[0] - 0.88).abs() < 0.06,
        "σv/σu = {}",
        sd[2] / sd[0]
    );
    assert!(
        (sd[1] / sd[0] - 0.55).abs() < 0.04,
        "σw/σu = {}",
        sd[1] / sd[0]
    );
    assert!(
        (sd[0] / u_star - 2.5).abs() < 0.35,
        "σu/u* = {}",
        sd[0] / u_star
    );
    // The user's intensity overrides it.
    let gusty = WindField::new(WindConfig {
        turbulence_intensity: Some(0.5),
        ..config()
    })
    .unwrap();
    assert!((gusty.sigma().x - 0.5 * 5.0).abs() < 1e-5);
}

#[test]
fn mean_profile_is_the_log_law_in_both_modes() {
    for spatial in [
        SpatialMode::Plane,
        SpatialMode::Volume { vertical_nodes: 8 },
    ] {
        let field = WindField::new(WindConfig {
            spatial,
            grid: [32, 32],
            ..config()
        })
        .unwrap();
        let u_star = field.friction_velocity();
        assert!((u_star - WindField::VON_KARMAN * 5.0 / (10.0f32 / 0.3).ln()).abs() < 1e-6);
        for h in [0.5f32, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0] {
            let law = u_star / WindField::VON_KARMAN * (h / 0.3).ln();
            assert!((field.mean_speed_at(h) - law).abs() < 1e-4 * law);
        }
        // The turbulence has zero mean over the whole pattern: one plane in Plane mode, every
        // layer above the reference height (where its scale is 1) in Volume mode.
        let layers: Vec<f32> = match spatial {
            SpatialMode::Plane => vec![10.0],
            SpatialMode::Volume { vertical_nodes } => {
                (0..vertical_nodes).map(|j| 10.0 + j as f32).collect()
            }
        };
        let mut sum = 0.0f64;
        for &y in &layers {
            for i in 0..32 {
                for k in 0..32 {
                    let v = field.velocity_at(Vec3::new(i as f32, y, k as f32), 0.0);
                    sum += f64::from(v.x - field.mean_speed_at(y));
                }
            }
        }
        let mean_turbulence = sum / (1024 * layers.len()) as f64;
        assert!(
            mean_turbulence.abs() < 1e-5,
            "{spatial:?}: {mean_turbulence}"
        );
        for h in [0.3f32, 0.1, 0.0, -10.0] {
            assert_eq!(field.mean_speed_at(h), 0.0);
            assert_eq!(
                field.velocity_at(Vec3::new(1.0, h, 2.0), 3.0),
                Vec3::ZERO,
                "below z0: still air"
            );
        }
    }
}

#[test]
fn plane_mode_scales_with_height_by_eq_14() {
    let field = WindField::new(config()).unwrap();
    let p = Vec2::new(7.3, -2.1);
    let at = |h: f32| field.velocity_at(Vec3::new(p.x, h, p.y), 1.5);
    let reference = at(10.0);
    for h in [1.0f32, 3.0, 30.0] {
        let factor = (h / 0.3).ln() / (10.0f32 / 0.3).ln();
        assert!((at(h) - reference * factor).length() < 1e-4 * reference.length());
    }
}

#[test]
fn frozen_pattern_translates_and_evolving_pattern_changes() {
    let frozen = WindField::new(config()).unwrap();
    let evolving = WindField::new(WindConfig {
        temporal: TemporalMode::Evolving {
            samples: 16,
            period: 8.0,
        },
        ..config()
    })
    .unwrap();
    let start = Vec3::new(4.2, 10.0, 3.1);
    // Ride along with the mean wind: frozen turbulence looks the same.
    let riding = |f: &WindField, t: f32| f.velocity_at(start + Vec3::X * 5.0 * t, t);
    for t in [0.5f32, 1.25, 3.0] {
        assert!((riding(&frozen, t) - riding(&frozen, 0.0)).length() < 1e-3);
    }
    let change = (riding(&evolving, 2.0) - riding(&evolving, 0.0)).length();
    assert!(
        change > 0.05 * evolving.sigma().x,
        "evolving changed only {change}"
    );
    // ... and the evolution repeats with its period.
    assert!((riding(&evolving, 8.0) - riding(&evolving, 0.0)).length() < 1e-3);
}

#[test]
fn direction_rotates_the_mean_wind() {
    let field = WindField::new(WindConfig {
        direction: Vec2::new(0.0, -2.0),
        turbulence_intensity: Some(0.0),
        ..config()
    })
    .unwrap();
    let v = field.velocity_at(Vec3::new(1.0, 10.0, 1.0), 0.0);
    assert!((v - Vec3::new(0.0, 0.0, -5.0)).length() < 1e-5, "{v}");
    assert_eq!(WindField::new(config()).unwrap().direction(), Vec3::X);
}

#[test]
fn batch_sampling_equals_single_sampling() {
    let field = WindField::new(config()).unwrap();
    let points: Vec<Vec3> = (0..100)
        .map(|i| Vec3::new(i as f32 * 0.7, 1.0 + i as f32 * 0.1, -(i as f32)))
        .collect();
    let mut out = Vec::new();
    field.velocities_at(&points, 2.5, &mut out);
    assert_eq!(out.len(), points.len());
    for (p, v) in points.iter().zip(&out) {
        assert_eq!(*v, field.velocity_at(*p, 2.5));
    }
}

#[test]
fn every_bad_configuration_names_its_field() {
    let cases: Vec<(&str, WindConfig)> = vec![
        (
            "roughness",
            WindConfig {
                roughness: 0.0,
                ..default()
            },
        ),
        (
            "roughness",
            WindConfig {
                roughness: -1.0,
                ..default()
            },
        ),
        (
            "roughness",
            WindConfig {
                roughness: f32::NAN,
                ..default()
            },
        ),
        (
            "reference_height",
            WindConfig {
                reference_height: 0.3,
                ..default()
            },
        ),
        (
            "reference_height",
            WindConfig {
                reference_height: 0.1,
                ..default()
            },
        ),
        (
            "reference_height",
            WindConfig {
                reference_height: f32::INFINITY,
                ..default()
            },
        ),
        (
            "reference_speed",
            WindConfig {
                reference_speed: -1.0,
                ..default()
            },
        ),
        (
            "reference_speed",
            WindConfig {
                reference_speed: f32::NAN,
                ..default()
            },
        ),
        (
            "reference_speed",
            WindConfig {
                reference_speed: f32::INFINITY,
                ..default()
            },
        ),
        (
            "reference_speed",
            WindConfig {
                reference_speed: 2e4,
                ..default()
            },
        ),
        (
            "beta",
            WindConfig {
                beta: -0.1,
                ..default()
            },
        ),
        (
            "beta",
            WindConfig {
                beta: f32::NAN,
                ..default()
            },
        ),
        (
            "direction",
            WindConfig {
                direction: Vec2::ZERO,
                ..default()
            },
        ),
        (
            "turbulence_intensity",
            WindConfig {
                turbulence_intensity: Some(-0.1),
                ..default()
            },
        ),
        (
            "turbulence_intensity",
            WindConfig {
                turbulence_intensity: Some(50.0),
                ..default()
            },
        ),
        (
            "grid.x",
            WindConfig {
                grid: [1, 8],
                ..default()
            },
        ),
        (
            "grid.z",
            WindConfig {
                grid: [8, 0],
                ..default()
            },
        ),
        (
            "cell_size",
            WindConfig {
                cell_size: 0.0,
                ..default()
            },
        ),
        (
            "cell_size",
            WindConfig {
                cell_size: -2.0,
                ..default()
            },
        ),
        (
            "spatial.vertical_nodes",
            WindConfig {
                spatial: SpatialMode::Volume { vertical_nodes: 1 },
                ..default()
            },
        ),
        (
            "temporal.samples",
            WindConfig {
                temporal: TemporalMode::Evolving {
                    samples: 1,
                    period: 1.0,
                },
                ..default()
            },
        ),
        (
            "temporal.period",
            WindConfig {
                temporal: TemporalMode::Evolving {
                    samples: 8,
                    period: 0.0,
                },
                ..default()
            },
        ),
        (
            "grid",
            WindConfig {
                grid: [1 << 14, 1 << 14],
                ..default()
            },
        ),
    ];
    for (field, config) in cases {
        let err = WindField::new(config.clone()).expect_err(field);
        assert_eq!(err.field(), field, "{config:?}: {err}");
        assert!(
            err.to_string().contains(field),
            "message names the field: {err}"
        );
    }
    // Setters validate too and leave the field unchanged.
    let mut wind = WindField::new(config()).unwrap();
    assert_eq!(
        wind.set_reference_speed(f32::NAN).unwrap_err().field(),
        "reference_speed"
    );
    assert_eq!(
        wind.set_direction(Vec2::ZERO).unwrap_err().field(),
        "direction"
    );
    assert_eq!(wind.config().reference_speed, 5.0);
}

fn any_mode() -> impl Strategy<Value = (SpatialMode, TemporalMode)> {
    (any::<bool>(), any::<bool>()).prop_map(|(volume, evolving)| {
        (
            if volume {
                SpatialMode::Volume { vertical_nodes: 4 }
            } else {
                SpatialMode::Plane
            },
            if evolving {
                TemporalMode::Evolving {
                    samples: 4,
                    period: 3.0,
                }
            } else {
                TemporalMode::Frozen
            },
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every valid configuration, sampled anywhere at any time, gives a finite velocity.
    #[test]
    fn velocity_is_finite_for_extreme_but_valid_input(
        speed in prop_oneof![Just(0.0f32), 1e-6f32..1.0, 1.0f32..1e4],
        roughness in prop_oneof![1e-6f32..1e-3, 1e-3f32..3.0],
        height_over in prop_oneof![1e-6f32..1e-3, 1e-3f32..1e3],
        beta in 0.0f32..12.0,
        intensity in proptest::option::of(0.0f32..10.0),
        cell in prop_oneof![1e-4f32..1e-2, 1e-2f32..1e3],
        (spatial, temporal) in any_mode(),
        position in prop::array::uniform3(prop_oneof![
            -1e30f32..1e30, -1e4f32..1e4, Just(f32::MAX), Just(f32::MIN), Just(0.0)
        ]),
        time in prop_oneof![-1e30f32..1e30, 0.0f32..1e5, Just(f32::MAX)],
        seed in any::<u64>(),
    ) {
        let field = WindField::new(WindConfig {
            reference_speed: speed,
            roughness,
            reference_height: roughness * (1.0 + height_over),
            beta,
            turbulence_intensity: intensity,
            cell_size: cell,
            spatial,
            temporal,
            grid: [4, 6],
            seed,
            ..default()
        });
        // Only a reference height that rounds onto the roughness may be rejected.
        if let Ok(field) = field {
            let v = field.velocity_at(Vec3::from_array(position), time);
            prop_assert!(v.is_finite(), "{v} at {position:?}, t={time}");
        }
    }
}

#[test]
fn non_finite_position_or_time_gives_a_finite_velocity() {
    let field = WindField::new(config()).unwrap();
    for p in [
        Vec3::NAN,
        Vec3::INFINITY,
        Vec3::new(1.0, f32::NEG_INFINITY, 2.0),
    ] {
        for t in [0.0, f32::NAN, f32::INFINITY] {
            assert!(field.velocity_at(p, t).is_finite());
        }
    }
}

/// The batched read (four points at a time in SIMD lanes) gives every point the bits of the
/// single read, in every spatial and temporal mode, with shelters and sources, at awkward
/// points (below the roughness length, far off, not finite).
#[test]
fn the_batched_read_gives_the_bits_of_single_reads() {
    use bevy::prelude::Transform;
    let modes = [
        (SpatialMode::Plane, TemporalMode::Frozen),
        (
            SpatialMode::Volume { vertical_nodes: 8 },
            TemporalMode::Frozen,
        ),
        (
            SpatialMode::Plane,
            TemporalMode::Evolving {
                samples: 6,
                period: 9.0,
            },
        ),
    ];
    let mut points: Vec<Vec3> = (0..203)
        .map(|i| {
            let t = i as f32;
            Vec3::new(
                37.1 * t.sin() * t,
                0.01 + 0.37 * (t % 40.0),
                -11.3 * t + 3.0,
            )
        })
        .collect();
    points.extend([
        Vec3::new(1e7, 1e6, -1e7),
        Vec3::new(f32::NAN, 1.0, 0.0),
        Vec3::new(0.0, f32::INFINITY, 0.0),
        Vec3::new(0.0, -5.0, 0.0),
    ]);
    for (spatial, temporal) in modes {
        let mut app = crate::common::headless_app();
        app.add_plugins(WindPlugin::new(WindConfig {
            grid: [24, 24],
            spatial,
            temporal,
            pulse: bevy_windfall::wind::Pulse::new(0.3, 0.4),
            ..config()
        }));
        crate::common::ready(&mut app);
        app.world_mut().spawn((
            bevy_windfall::wind::WindSource::vortex(8.0, 6.0),
            Transform::from_xyz(5.0, 0.0, 3.0),
        ));
        app.world_mut().spawn((
            bevy_windfall::wind::WindShelter::wall(Vec3::new(0.2, 2.0, 6.0)),
            Transform::from_xyz(-8.0, 1.0, 0.0),
        ));
        for _ in 0..5 {
            app.update();
        }
        let wind = app.world().resource::<WindField>();
        assert!(wind.source_count() == 1 && wind.shelter_count() == 1);
        let mut batched = Vec::new();
        wind.velocities_at(&points, 2.5, &mut batched);
        for (p, v) in points.iter().zip(&batched) {
            let one = wind.velocity_at(*p, 2.5);
            assert_eq!(
                v.to_array().map(f32::to_bits),
                one.to_array().map(f32::to_bits),
                "{spatial:?} {temporal:?} at {p}"
            );
        }
    }
}
