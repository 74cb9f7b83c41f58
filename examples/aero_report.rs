//! Error against run time for the rigid plate: terminal-velocity error and energy drift by time
//! step, for the implicit step (`RigidPlate::step`) and the explicit baseline
//! (`RigidPlate::step_explicit`). Prints Markdown tables.
//! `cargo run --release --example aero_report`

use std::time::Instant;

use bevy::math::{Quat, Vec3};
use bevy_windfall::aero::{AeroCoefficients, PlateState, RigidPlate};

const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);

fn still(_: Vec3) -> Vec3 {
    Vec3::ZERO
}

fn main() {
    // A business card, 8.5 × 5.5 cm, 0.3 mm, 700 kg/m³, 3 × 3 faces.
    let card =
        RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 3).unwrap();
    let c = *card.coefficients();
    let terminal = (2.0 * card.mass() * 9.81 / (c.density * c.drag * card.area())).sqrt();
    let rate = c.density * c.drag * card.area() * terminal / card.mass();
    println!("## Rigid plate: error against run time (release)\n");
    println!(
        "Card falling broadside for 5 s; closed-form terminal speed {terminal:.4} m/s; drag rate \
         at it ρ C_D A v_t / m = {rate:.1} 1/s (explicit limit dt < {:.3} s). Energy drift: the \
         largest rise of total energy over one step, relative to the energy's terms, for a card \
         released tilted and spinning (it should never rise).\n",
        2.0 / rate
    );
    let tilted = PlateState {
        rotation: Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.3),
        angular_velocity: Vec3::new(3.0, 1.0, -2.0),
        velocity: Vec3::new(1.0, -0.5, 0.0),
        ..Default::default()
    };
    let mut reference = tilted;
    for _ in 0..4000 {
        card.step(&mut reference, 1.0 / 4000.0, G, &still, false);
    }
    println!(
        "Path error: distance from the 1 s position of the tilted card computed with the implicit \
         step at dt = 1/4000 s.\n"
    );
    println!(
        "| integrator | dt (s) | terminal-speed error | path error at 1 s (m) | largest energy rise | µs per step |"
    );
    println!("|---|---|---|---|---|---|");
    for implicit in [true, false] {
        for dt in [1.0 / 240.0, 1.0 / 120.0, 1.0 / 60.0, 1.0 / 30.0, 0.1, 0.25] {
            let step = |s: &mut PlateState| {
                if implicit {
                    card.step(s, dt, G, &still, true);
                } else {
                    card.step_explicit(s, dt, G, &still);
                }
            };
            let mut s = PlateState::default();
            let steps = (5.0 / dt) as usize;
            let begin = Instant::now();
            for _ in 0..steps {
                step(&mut s);
            }
            let micros = begin.elapsed().as_secs_f64() * 1e6 / steps as f64;
            let speed = -s.velocity.y;
            let error = if speed.is_finite() {
                format!("{:.2e}", (speed / terminal - 1.0).abs())
            } else {
                "NaN".into()
            };
            let mut s = tilted;
            for _ in 0..(1.0 / dt).round() as usize {
                step(&mut s);
            }
            let path = s.position.distance(reference.position);
            let path = if path.is_finite() {
                format!("{path:.2e}")
            } else {
                "NaN".into()
            };
            let mut s = tilted;
            let mut rise = 0.0f32;
            let mut finite = true;
            for _ in 0..steps {
                let before = card.energy(&s, G);
                step(&mut s);
                let (k, p) = card.energy_terms(&s, G);
                finite &= (k + p).is_finite();
                rise = rise.max((k + p - before) / (k + p.abs()).max(1e-12));
            }
            let rise = if finite {
                format!("{rise:.1e}")
            } else {
                "NaN".into()
            };
            println!(
                "| {} | {dt:.4} | {error} | {path} | {rise} | {micros:.2} |",
                if implicit {
                    "implicit drag (ours)"
                } else {
                    "explicit Euler"
                },
            );
        }
    }
}
