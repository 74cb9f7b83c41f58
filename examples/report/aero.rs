//! Aero: the rigid plate's implicit step against the explicit baseline, by time step.

use std::time::Instant;

use bevy::math::{Quat, Vec3};
use bevy_windfall::aero::{AeroCoefficients, PlateState, RigidPlate};

use super::plot::{Plot, Series};
use super::{Report, sci};

pub const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);

pub fn still(_: Vec3) -> Vec3 {
    Vec3::ZERO
}

/// A business card, 8.5 × 5.5 cm, 0.3 mm, 700 kg/m³, 3 × 3 faces.
pub fn card() -> RigidPlate {
    RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 3)
        .expect("a valid card")
}

fn tilted() -> PlateState {
    PlateState {
        rotation: Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.3),
        angular_velocity: Vec3::new(3.0, 1.0, -2.0),
        velocity: Vec3::new(1.0, -0.5, 0.0),
        ..Default::default()
    }
}

pub fn report(r: &mut Report) {
    let card = card();
    let c = *card.coefficients();
    let terminal = (2.0 * card.mass() * 9.81 / (c.density * c.drag * card.area())).sqrt();
    let rate = c.density * c.drag * card.area() * terminal / card.mass();
    r.section(
        "Aero: rigid plate, error against run time",
        &format!(
            "A card falling broadside for 5 s: closed-form terminal speed {terminal:.4} m/s, \
             drag rate ρ C_D A v_t / m = {rate:.1} 1/s (explicit limit dt < {:.3} s). Path \
             error: distance from the 1 s position of a tilted, spinning card computed with the \
             implicit step at dt = 1/4000 s. Energy rise: the largest rise of total energy over \
             one step in still air, relative to its terms (it should never rise).",
            2.0 / rate
        ),
    );
    let mut reference = tilted();
    for _ in 0..4000 {
        card.step(&mut reference, 1.0 / 4000.0, G, &still, false);
    }
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for implicit in [true, false] {
        let name = if implicit {
            "implicit drag (ours)"
        } else {
            "explicit Euler"
        };
        let step = |s: &mut PlateState, dt: f32| {
            if implicit {
                card.step(s, dt, G, &still, true);
            } else {
                card.step_explicit(s, dt, G, &still);
            }
        };
        let mut points = Vec::new();
        for dt in [1.0 / 240.0, 1.0 / 120.0, 1.0 / 60.0, 1.0 / 30.0, 0.1, 0.25] {
            let steps = (5.0 / dt) as usize;
            let mut s = PlateState::default();
            let begin = Instant::now();
            for _ in 0..steps {
                step(&mut s, dt);
            }
            let micros = begin.elapsed().as_secs_f64() * 1e6 / steps as f64;
            let speed_error = f64::from((-s.velocity.y / terminal - 1.0).abs());
            let mut s = tilted();
            for _ in 0..(1.0 / dt).round() as usize {
                step(&mut s, dt);
            }
            let path = f64::from(s.position.distance(reference.position));
            let mut s = tilted();
            let mut rise = 0.0f32;
            for _ in 0..steps {
                let before = card.energy(&s, G);
                step(&mut s, dt);
                let (k, p) = card.energy_terms(&s, G);
                rise = rise.max((k + p - before) / (k + p.abs()).max(1e-12));
            }
            points.push((micros / f64::from(dt), path));
            rows.push(vec![
                name.into(),
                if dt < 0.05 {
                    format!("1/{:.0}", 1.0 / dt)
                } else {
                    format!("{dt}")
                },
                sci(speed_error),
                sci(path),
                sci(f64::from(rise)),
                format!("{micros:.2}"),
            ]);
        }
        series.push(Series::new(name, points));
    }
    r.table(
        &[
            "integrator",
            "dt (s)",
            "terminal-speed error",
            "path error at 1 s (m)",
            "largest energy rise",
            "µs per step",
        ],
        &rows,
    );
    r.figure(
        "aero_plate",
        &Plot {
            title: "Rigid card: path error at 1 s against run time (dt = 1/240 … 0.25 s)",
            x_label: "µs per simulated second",
            y_label: "path error (m)",
            series,
        },
    );
}
