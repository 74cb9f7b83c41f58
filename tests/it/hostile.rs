//! Hostile input, field by field: every public constructor and runtime knob of the wind, the
//! falling objects, the procedural cloth, the spectra and the ODE at NaN, ±∞, ±0, −1,
//! subnormal, the smallest normal, tiny, huge, ±`f32::MAX` and the float just below it. Each
//! case must either be refused with a typed error that names the field set, or be accepted and
//! then simulate with finite output and do what it should (fall, blow as set, stay near the
//! pole). `hostile_aero.rs` does the same for the aerodynamic bodies, `hostile_apps.rs` for
//! apps, removed resources and the probes that could abort or hang. The case counts are
//! printed (`--nocapture`) and quoted in the README's reliability section.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::cloth::{ClothError, ClothSim};
use bevy_windfall::freefall::ode::{Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{
    DatabaseConfig, FallError, FallModel, FallRelease, MarkovChain, TrajectoryDatabase, WindTilt,
};
use bevy_windfall::prelude::*;
use bevy_windfall::spectrum::fbm;
use bevy_windfall::wind::Pulse;
use common::hostile::{HOSTILE, TILT, case, finite, report};
use common::paper_coin;

type WindSetter = fn(&mut WindConfig, f32);

#[test]
fn wind_fields_are_refused_by_name_or_blow_as_set() {
    let base = WindConfig {
        grid: [16, 16],
        ..default()
    };
    let setters: [(&str, &[&str], WindSetter); 11] = [
        ("reference_speed", &["reference_speed"], |c, v| {
            c.reference_speed = v
        }),
        ("reference_height", &["reference_height"], |c, v| {
            c.reference_height = v
        }),
        // A roughness above the reference height is the height's fault as much as its own.
        ("roughness", &["roughness", "reference_height"], |c, v| {
            c.roughness = v
        }),
        ("beta", &["beta"], |c, v| c.beta = v),
        ("turbulence_intensity", &["turbulence_intensity"], |c, v| {
            c.turbulence_intensity = Some(v)
        }),
        ("cell_size", &["cell_size"], |c, v| c.cell_size = v),
        ("direction.x", &["direction"], |c, v| {
            c.direction = Vec2::new(v, 0.0)
        }),
        ("direction", &["direction"], |c, v| {
            c.direction = Vec2::new(v, -v)
        }),
        ("pulse.magnitude", &["pulse.magnitude"], |c, v| {
            c.pulse = Pulse::new(v, 1.0)
        }),
        ("pulse.frequency", &["pulse.frequency"], |c, v| {
            c.pulse = Pulse::new(0.5, v)
        }),
        ("temporal.period", &["temporal.period"], |c, v| {
            c.temporal = TemporalMode::Evolving {
                samples: 8,
                period: v,
            }
        }),
    ];
    let points = [
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(1e6, 50.0, -3e5),
        Vec3::new(0.0, 1e30, 0.0),
        Vec3::splat(f32::NAN),
        Vec3::splat(f32::INFINITY),
    ];
    for (name, fields, set) in setters {
        for value in HOSTILE {
            let mut config = base.clone();
            set(&mut config, value);
            let calm = name.starts_with("direction");
            if calm {
                config.turbulence_intensity = Some(0.0);
            }
            case(
                name,
                value,
                fields,
                WindField::new(config),
                WindError::field,
                |field| {
                    for p in points {
                        for t in [0.0, 1e6, -5.0, f32::NAN] {
                            finite(field.velocity_at(p, t), name);
                        }
                    }
                    assert!((field.direction().length() - 1.0).abs() < 1e-5, "{name}");
                    if calm {
                        // Any accepted direction, however long or short, blows at the set speed.
                        let c = field.config();
                        let v = field.velocity(Vec3::new(0.0, c.reference_height, 0.0));
                        assert!(
                            (v.length() - c.reference_speed).abs() < 1e-3 * c.reference_speed,
                            "direction {:?}: {v}",
                            c.direction
                        );
                    }
                },
            );
        }
    }
    // Validated on what is used: one f32 step above the roughness is no height at all.
    let mut config = base.clone();
    config.reference_height = config.roughness.next_up();
    assert_eq!(
        WindField::new(config).unwrap_err().field(),
        "reference_height"
    );
    report("wind");
}

#[test]
fn wind_knobs_keep_the_clock_and_samples_finite() {
    let mut field = WindField::new(WindConfig {
        grid: [16, 16],
        ..default()
    })
    .unwrap();
    let p = Vec3::new(3.0, 2.0, -1.0);
    for value in HOSTILE {
        field.time_scale = value;
        for _ in 0..3 {
            field.advance(1.0 / 60.0);
            field.advance(value);
        }
        field.set_clock(f64::from(value));
        assert!(field.time().is_finite(), "time_scale {value}");
        finite(field.velocity(p), "after the clock");
        case(
            "set_reference_speed",
            value,
            &["reference_speed"],
            field.clone().set_reference_speed(value).map(|_| ()),
            WindError::field,
            |_| {},
        );
        let mut turned = field.clone();
        case(
            "set_direction",
            value,
            &["direction"],
            turned.set_direction(Vec2::new(value, 1.0)),
            WindError::field,
            |_| {
                assert!((turned.direction().length() - 1.0).abs() < 1e-5);
                finite(turned.velocity(p), "turned");
            },
        );
    }
    report("wind knobs");
}

type FallSetter = fn(&mut FallingObject, f32);

#[test]
fn falling_objects_are_refused_by_name_or_fall() {
    let model = FallModel::default();
    let card = FallingObject {
        shape: Shape::Rectangle {
            length: 0.09,
            width: 0.06,
            thickness: 2e-4,
        },
        density: 700.0,
        ..default()
    };
    const CARD: &[&str] = &["shape.length", "shape.width", "shape.thickness"];
    const COIN: &[&str] = &["shape.diameter", "shape.thickness"];
    let setters: [(&str, &[&str], bool, FallSetter); 10] = [
        ("shape.length", CARD, false, |o, v| {
            if let Shape::Rectangle { length, .. } = &mut o.shape {
                *length = v;
            }
        }),
        ("shape.width", CARD, false, |o, v| {
            if let Shape::Rectangle { width, .. } = &mut o.shape {
                *width = v;
            }
        }),
        ("shape.diameter", COIN, true, |o, v| {
            if let Shape::Disk { diameter, .. } = &mut o.shape {
                *diameter = v;
            }
        }),
        ("shape.thickness", COIN, true, |o, v| {
            if let Shape::Disk { thickness, .. } = &mut o.shape {
                *thickness = v;
            }
        }),
        ("density", &["density"], true, |o, v| o.density = v),
        (
            "fluid.density",
            &["fluid.density", "density"],
            true,
            |o, v| o.fluid.density = v,
        ),
        (
            "fluid.kinematic_viscosity",
            &["fluid.kinematic_viscosity"],
            false,
            |o, v| o.fluid.kinematic_viscosity = v,
        ),
        ("gravity", &["gravity"], false, |o, v| o.gravity = v),
        ("deviation", &["deviation"], false, |o, v| o.deviation = v),
        ("wind_tilt", &["wind_tilt"], false, |o, v| o.wind_tilt = v),
    ];
    for (name, fields, coin, set) in setters {
        for value in HOSTILE {
            let mut object = if coin { paper_coin() } else { card.clone() };
            set(&mut object, value);
            let release = FallRelease::at(Vec3::new(0.0, 3.0, 0.0), 0.0);
            case(
                name,
                value,
                fields,
                object.path(&model, release),
                FallError::field,
                |mut path| {
                    let tilt = WindTilt {
                        max_angle: object.wind_tilt,
                        reference_speed: 4.0,
                    };
                    for _ in 0..240 {
                        path.advance(&model, 1.0 / 60.0, Vec3::new(3.0, 0.0, 0.0), &tilt);
                        finite(path.position(), name);
                        assert!(path.orientation().is_finite(), "{name} = {value}");
                    }
                    // Objects that descend measurably in 4 s must have come down.
                    let descent = object.regime().unwrap().descent_speed;
                    if descent > 1e-3 {
                        assert!(path.position().y < 3.0, "{name} = {value}: it must fall");
                    }
                },
            );
        }
    }
    report("free fall");
}

type ReleaseSetter = fn(&mut FallRelease, f32);

#[test]
fn releases_are_refused_by_name_or_fall_and_steps_stay_finite() {
    let model = FallModel::default();
    let object = FallingObject::default();
    let setters: [(&str, ReleaseSetter); 6] = [
        ("release.position", |r, v| r.position.x = v),
        ("release.position", |r, v| r.position.y = v),
        ("release.ground", |r, v| r.ground = v),
        ("release.velocity", |r, v| r.velocity = Vec3::splat(v)),
        ("release.rotation", |r, v| {
            r.rotation = Some(Quat::from_xyzw(v, 0.0, 0.0, 1.0))
        }),
        ("release.rotation", |r, v| {
            r.rotation = Some(Quat::from_xyzw(v, v, v, v))
        }),
    ];
    for (name, set) in setters {
        for value in HOSTILE {
            let mut release = FallRelease::at(Vec3::new(0.0, 3.0, 0.0), 0.0);
            set(&mut release, value);
            case(
                name,
                value,
                &[name],
                object.path(&model, release),
                FallError::field,
                |mut path| {
                    for _ in 0..120 {
                        path.advance(&model, 1.0 / 60.0, Vec3::ZERO, &TILT);
                        finite(path.position(), name);
                    }
                },
            );
        }
    }
    // A valid fall fed hostile steps and winds: it stays finite.
    let mut path = object
        .path(&model, FallRelease::at(Vec3::new(0.0, 30.0, 0.0), 0.0))
        .unwrap();
    for value in HOSTILE {
        let wind = Vec3::new(value, 0.0, -value);
        path.advance(&model, value, wind, &TILT);
        path.advance(&model, 1.0 / 60.0, wind, &TILT);
        finite(path.position(), "hostile step");
        assert!(path.orientation().is_finite());
    }
    // A database from hostile parameter lists falls back or filters as documented; its
    // falls stay finite and come down.
    for clusters in [0, 1, usize::MAX] {
        let config = DatabaseConfig {
            alphas: HOSTILE.to_vec(),
            gammas: HOSTILE.iter().rev().copied().collect(),
            clusters,
            flutter_lifts: HOSTILE.iter().map(|&v| f64::from(v)).collect(),
            seed: 1,
        };
        let model = FallModel::new(TrajectoryDatabase::build(&config), MarkovChain::default());
        let mut path = object
            .path(&model, FallRelease::at(Vec3::new(0.0, 3.0, 0.0), 0.0))
            .unwrap();
        for _ in 0..240 {
            path.advance(&model, 1.0 / 60.0, Vec3::X, &TILT);
            finite(path.position(), "hostile database");
        }
        assert!(path.position().y < 3.0, "clusters {clusters}");
    }
    report("releases");
}

type ClothSetter = fn(&mut Cloth, f32);

#[test]
fn cloths_are_refused_by_name_or_stay_on_their_pole() {
    let setters: [(&str, ClothSetter); 11] = [
        ("grid.width", |c, v| c.grid.width = v),
        ("grid.height", |c, v| c.grid.height = v),
        ("params.wind_steps_per_frame", |c, v| {
            c.params.wind_steps_per_frame = v
        }),
        ("params.amplitude", |c, v| c.params.amplitude = v),
        ("params.beta", |c, v| c.params.beta = v),
        ("params.swirl", |c, v| c.params.swirl = v),
        ("params.twist", |c, v| c.params.twist = v),
        ("params.bow", |c, v| c.params.bow = v),
        ("params.lean", |c, v| c.params.lean = v),
        ("params.max_stretch", |c, v| c.params.max_stretch = v),
        ("params.reference_speed", |c, v| {
            c.params.reference_speed = v
        }),
    ];
    let small = ClothGrid {
        rows: 6,
        columns: 9,
        ..default()
    };
    for (name, set) in setters {
        for value in HOSTILE {
            let mut cloth = Cloth {
                grid: small,
                ..default()
            };
            set(&mut cloth, value);
            let reach = 2.0 * (cloth.grid.width + cloth.grid.height);
            case(
                name,
                value,
                &[name],
                ClothSim::new(cloth.grid, cloth.params, cloth.attachment),
                ClothError::field,
                |mut sim| {
                    for _ in 0..20 {
                        sim.advance(1.0 / 50.0, cloth.params.wind_steps_per_frame);
                        sim.rebuild();
                        for p in sim.positions() {
                            assert!(
                                p.is_finite() && p.length() <= reach,
                                "{name} = {value}: {p}"
                            );
                        }
                    }
                },
            );
        }
    }
    let mut sim = ClothSim::new(small, ClothParams::default(), ClothAttachment::Pole).unwrap();
    for value in HOSTILE {
        sim.advance(value, value);
        sim.advance(1.0 / 50.0, value);
        sim.rebuild();
        assert!(
            sim.positions().iter().all(|p| p.is_finite()),
            "advance {value}"
        );
    }
    report("cloth");
}

#[test]
fn spectra_and_the_ode_refuse_by_name_or_stay_finite() {
    for value in HOSTILE {
        case(
            "beta",
            value,
            &["beta"],
            fbm(&[32, 12], value, 1),
            |e| e.field(),
            |field| {
                let var =
                    field.iter().map(|&v| f64::from(v).powi(2)).sum::<f64>() / field.len() as f64;
                assert!((var - 1.0).abs() < 1e-3, "β {value}: variance {var}");
            },
        );
        let start = OdeState {
            theta: 0.3,
            ..default()
        };
        let params = TanabeKaneko::FLUTTER;
        for (name, dt, duration) in [("dt", value, 1.0), ("duration", 0.01, value)] {
            case(
                name,
                value,
                &["dt", "duration"],
                params.trajectory(start, f64::from(dt), f64::from(duration), Integrator::Rk4),
                |e| e.field(),
                |run| assert!(run.iter().all(|s| s.x.is_finite() && s.y.is_finite())),
            );
        }
    }
    report("spectrum and ode");
}
