//! Hostile input for the aerodynamic bodies (see `hostile.rs`): plates, their states, the
//! face law and the particle cloth, every number at every hostile value.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning, PlateState, face_force};
use bevy_windfall::prelude::*;
use common::hostile::{HOSTILE, case, finite, report};

type PlateSetter = fn(&mut PlateState, f32);
type CoefficientSetter = fn(&mut AeroCoefficients, f32);
type ParticleSetter = fn(&mut (ClothGrid, f32, AeroCoefficients), f32);

#[test]
fn aero_bodies_are_refused_by_name_or_fly_finite() {
    let coefficient_setters: [(&str, CoefficientSetter); 3] = [
        ("drag", |c, v| c.drag = v),
        ("lift", |c, v| c.lift = v),
        ("density", |c, v| c.density = v),
    ];
    let gravity = Vec3::new(0.0, -9.81, 0.0);
    let wind = |_: Vec3| Vec3::new(2.0, 0.0, 0.0);
    let fly = |plate: &RigidPlate, what: &str| {
        let mut s = PlateState {
            position: Vec3::new(0.0, 2.0, 0.0),
            ..default()
        };
        for _ in 0..60 {
            plate.step(&mut s, 1.0 / 60.0, gravity, &wind, false);
            finite(s.position, what);
            assert!(s.rotation.is_finite() && s.velocity.is_finite(), "{what}");
        }
    };
    for (name, set) in coefficient_setters {
        for value in HOSTILE {
            let mut c = AeroCoefficients::default();
            set(&mut c, value);
            case(
                name,
                value,
                &[name],
                RigidPlate::rectangle(0.07, 0.04, 3e-4, 500.0, c, 2),
                |e: &bevy_windfall::aero::AeroError| e.field(),
                |plate| fly(&plate, name),
            );
        }
    }
    for (index, name) in ["length", "width", "thickness", "density"]
        .into_iter()
        .enumerate()
    {
        for value in HOSTILE {
            let mut sizes = [0.07, 0.04, 3e-4, 500.0];
            sizes[index] = value;
            let [l, w, t, d] = sizes;
            case(
                name,
                value,
                &[name],
                RigidPlate::rectangle(l, w, t, d, AeroCoefficients::default(), 2),
                |e: &bevy_windfall::aero::AeroError| e.field(),
                |plate| fly(&plate, name),
            );
        }
    }
    let plate =
        RigidPlate::rectangle(0.07, 0.04, 3e-4, 500.0, AeroCoefficients::default(), 2).unwrap();
    let state_setters: [(&str, PlateSetter); 5] = [
        ("state.position", |s, v| s.position.y = v),
        ("state.velocity", |s, v| s.velocity.x = v),
        ("state.angular_velocity", |s, v| s.angular_velocity.z = v),
        ("state.rotation", |s, v| {
            s.rotation = Quat::from_xyzw(v, 0.0, 0.0, 1.0)
        }),
        ("state.rotation", |s, v| {
            s.rotation = Quat::from_xyzw(v, v, v, v)
        }),
    ];
    for (name, set) in state_setters {
        for value in HOSTILE {
            let mut s = PlateState {
                position: Vec3::new(0.0, 2.0, 0.0),
                ..default()
            };
            set(&mut s, value);
            case(
                name,
                value,
                &[name],
                s.validate().map(|()| s),
                |e: &bevy_windfall::aero::AeroError| e.field(),
                |mut s| {
                    for _ in 0..30 {
                        plate.step(&mut s, 1.0 / 60.0, gravity, &wind, false);
                        finite(s.position, name);
                    }
                },
            );
            // Refused or not, a step never makes it worse than it was.
            let before = s;
            plate.step(&mut s, 1.0 / 60.0, gravity, &wind, false);
            if before.validate().is_err() {
                assert_eq!(format!("{s:?}"), format!("{before:?}"), "{name} = {value}");
            }
        }
    }
    // Hostile gravity and steps leave a valid state valid.
    let mut s = PlateState::default();
    for value in HOSTILE {
        plate.step(&mut s, value, Vec3::splat(value), &wind, false);
        plate.step(&mut s, 1.0 / 60.0, Vec3::new(0.0, value, 0.0), &wind, false);
        assert!(s.validate().is_ok(), "gravity {value}: {s:?}");
    }
    report("aero bodies");
}

#[test]
fn the_face_law_is_finite_for_every_input() {
    let mut count = 0;
    for value in HOSTILE {
        let args = [
            (Vec3::new(value, 1.0, 0.0), Vec3::Y, 1.0, 1.2, 1.0, 1.2),
            (Vec3::X, Vec3::new(value, 1.0, value), 1.0, 1.2, 1.0, 1.2),
            (Vec3::X, Vec3::ONE, value, 1.2, 1.0, 1.2),
            (Vec3::X, Vec3::ONE, 1.0, value, 1.0, 1.2),
            (Vec3::X, Vec3::ONE, 1.0, 1.2, value, 1.2),
            (Vec3::X, Vec3::ONE, 1.0, 1.2, 1.0, value),
        ];
        for (v, n, area, drag, lift, density) in args {
            let f = face_force(v, n, area, drag, lift, density);
            finite(f, "face_force");
            count += 1;
        }
        // Any finite normal length gives the unit normal's force.
        if value.is_finite() && value > 0.0 {
            let unit = face_force(Vec3::new(1.0, -2.0, 0.5), Vec3::Y, 0.01, 1.2, 1.0, 1.2);
            let scaled = face_force(
                Vec3::new(1.0, -2.0, 0.5),
                Vec3::Y * value,
                0.01,
                1.2,
                1.0,
                1.2,
            );
            assert!(
                (unit - scaled).length() < 1e-5 * unit.length(),
                "|n| = {value}"
            );
        }
    }
    println!("hostile face law: {count} cases, all finite");
}

#[test]
fn particle_cloths_are_refused_by_name_or_hang_finite() {
    let grid = ClothGrid {
        rows: 5,
        columns: 7,
        ..default()
    };
    let setters: [(&str, ParticleSetter); 5] = [
        ("areal_density", |c, v| c.1 = v),
        ("grid.width", |c, v| c.0.width = v),
        ("grid.height", |c, v| c.0.height = v),
        ("drag", |c, v| c.2.drag = v),
        ("density", |c, v| c.2.density = v),
    ];
    for (name, set) in setters {
        for value in HOSTILE {
            let mut input = (grid, 0.15, AeroCoefficients::default());
            set(&mut input, value);
            // A weightless or overweight node is the density's or the sizes' doing.
            let fields: &[&str] = match name {
                "grid.width" | "grid.height" => &[name, "areal_density"],
                _ => &[name],
            };
            case(
                name,
                value,
                fields,
                ParticleCloth::new(input.0, input.1, input.2, Pinning::PoleColumn),
                |e: &bevy_windfall::aero::AeroError| e.field(),
                |mut cloth| {
                    for _ in 0..5 {
                        cloth.step(1.0 / 60.0, Vec3::new(0.0, -9.81, 0.0), &|_| Vec3::X * 3.0);
                    }
                    assert!(cloth.positions().iter().all(|p| p.is_finite()), "{name}");
                    assert!(cloth.max_strain() < 0.5, "{name} = {value}");
                },
            );
        }
    }
    // Grid problems keep the grid's own field names.
    let flat = ClothGrid {
        height: 0.0,
        ..grid
    };
    let e = ParticleCloth::new(flat, 0.15, AeroCoefficients::default(), Pinning::PoleColumn);
    assert_eq!(e.unwrap_err().field(), "grid.height");
    let thin = ClothGrid { columns: 1, ..grid };
    let e = ParticleCloth::new(thin, 0.15, AeroCoefficients::default(), Pinning::PoleColumn);
    assert_eq!(e.unwrap_err().field(), "grid.columns");
    report("particle cloth");
}
