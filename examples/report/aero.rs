//! Aero: the rigid plate's implicit step against the explicit baseline, by time step.

use std::time::Instant;

use bevy::math::{Quat, Vec3};
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning, PlateState, RigidPlate};
use bevy_windfall::cloth::ClothGrid;

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

/// Nodes of `p` against `reference`: RMS distance over `width`.
fn rms_error(p: &[Vec3], reference: &[Vec3], width: f32) -> f64 {
    let sq: f64 = p
        .iter()
        .zip(reference)
        .map(|(a, b)| f64::from(a.distance_squared(*b)))
        .sum();
    (sq / p.len() as f64).sqrt() / f64::from(width)
}

/// The largest relative stretch of a structural edge of a `grid` cloth at `p`.
fn largest_strain(grid: ClothGrid, p: &[Vec3]) -> f32 {
    let c = grid.columns;
    let dx = grid.width / (c - 1) as f32;
    let dy = grid.height / (grid.rows - 1) as f32;
    let mut strain = 0.0f32;
    for (i, a) in p.iter().enumerate() {
        if (i + 1) % c != 0 {
            strain = strain.max(a.distance(p[i + 1]) / dx - 1.0);
        }
        if i + c < p.len() {
            strain = strain.max(a.distance(p[i + c]) / dy - 1.0);
        }
    }
    strain
}

/// The particle cloth by time step: a 24 × 16 flag in a uniform 8 m/s wind.
pub fn particle_cloth(r: &mut Report) {
    const SHORT: f32 = 0.1;
    r.section(
        "Aero: particle cloth, error against run time",
        "A 1.5 × 1 m flag, 24 × 16 nodes, 0.15 kg/m², pinned along its pole column, in a uniform \
         8 m/s wind from hanging still. The cloth advances in whole 1 ms substeps whatever the \
         frame's dt (the rest of a frame is carried into the next), so runs whose frames add up \
         to the same milliseconds are the same cloth. Error: RMS node distance from the run at dt = 1/3840 s, over the \
         flag's width, at 0.1 s (before flapping sets in) and at 1 s (flapping: a flag in wind is \
         unstable, so runs that differ by any step drift apart to the size of its flapping). \
         Strain: the largest relative stretch of a structural edge at 1 s. Time: the 1 s run.",
    );
    let grid = ClothGrid {
        rows: 16,
        columns: 24,
        width: 1.5,
        height: 1.0,
    };
    let wind = Vec3::new(8.0, 0.0, 3.0);
    // Positions after `seconds` at step `dt`, and the wall time it took, µs.
    let run = |dt: f32, seconds: f32| {
        let mut cloth =
            ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
                .expect("valid cloth");
        let steps = ((seconds / dt).round() as usize).max(1);
        let begin = Instant::now();
        for _ in 0..steps {
            cloth.step(dt, G, &|_| wind);
        }
        let micros = begin.elapsed().as_secs_f64() * 1e6;
        (cloth.positions().to_vec(), micros)
    };
    let (reference_short, _) = run(1.0 / 3840.0, SHORT);
    let (reference_long, _) = run(1.0 / 3840.0, 1.0);
    let mut rows = Vec::new();
    let mut points = Vec::new();
    let steps: &[f32] = if r.quick {
        &[1.0 / 60.0, 0.1]
    } else {
        &[
            1.0 / 960.0,
            1.0 / 480.0,
            1.0 / 240.0,
            1.0 / 120.0,
            1.0 / 60.0,
            1.0 / 30.0,
            0.1,
        ]
    };
    for &dt in steps {
        let (short, _) = run(dt, SHORT);
        let (long, micros) = run(dt, 1.0);
        let error = rms_error(&short, &reference_short, grid.width);
        points.push((micros, error));
        rows.push(vec![
            if dt < 0.05 {
                format!("1/{:.0}", 1.0 / dt)
            } else {
                format!("{dt}")
            },
            sci(error),
            sci(rms_error(&long, &reference_long, grid.width)),
            format!("{:.1} %", largest_strain(grid, &long) * 100.0),
            format!("{micros:.0}"),
        ]);
    }
    r.table(
        &[
            "dt (s)",
            "error at 0.1 s / width",
            "error at 1 s / width",
            "largest strain at 1 s",
            "µs per simulated s",
        ],
        &rows,
    );
    r.figure(
        "aero_particle_cloth",
        &Plot {
            title: "Particle flag: error at 0.1 s against run time (dt = 1/960 … 0.1 s)",
            x_label: "µs per simulated second",
            y_label: "RMS error / width",
            series: vec![Series::new(
                "1 ms substeps, implicit normal pressure",
                points,
            )],
        },
    );
}
