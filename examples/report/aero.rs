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

/// The particle cloth over what changes its answer and its cost: the tick (its substep's
/// length) and the grid. A 1.5 × 1 m flag in a uniform 8 m/s wind from hanging still.
pub fn particle_cloth(r: &mut Report) {
    const SHORT: f32 = 0.1;
    r.section(
        "Aero: particle cloth, error against run time",
        "A 1.5 × 1 m flag of 0.15 kg/m² pinned along its pole column, in a uniform 8 m/s wind \
         from hanging still, stepped at 60 frames a second (any frame rate gives the same cloth: \
         each frame is simulated in whole ticks). What changes the answer is the tick (the \
         substep's length, `ParticleCloth::tick`, 4 ms by default) and the grid. Ticks: a \
         16-row flag, error the RMS node distance from the run with ticks of 0.25 ms over the \
         flag's width at 0.1 s (before flapping sets in; a flag in wind is unstable, so later \
         runs that differ by anything drift apart by the size of its flapping). Grids: the \
         default ticks, error the distance of the free edge's middle from the 48-row flag's \
         over the width, at 0.1 s. Time: one simulated second, this machine, one thread.",
    );
    let wind = Vec3::new(8.0, 0.0, 3.0);
    let flag = |rows: usize| ClothGrid {
        rows,
        columns: rows * 3 / 2,
        width: 1.5,
        height: 1.0,
    };
    // Positions after `seconds` with ticks of `tick` on `rows` rows, and the wall time of 1 s, µs.
    let run = |rows: usize, tick: f32, seconds: f32| {
        let mut cloth = ParticleCloth::new(
            flag(rows),
            0.15,
            AeroCoefficients::default(),
            Pinning::PoleColumn,
        )
        .expect("valid cloth");
        cloth.tick = tick;
        let steps = ((seconds * 60.0).round() as usize).max(1);
        let begin = Instant::now();
        for _ in 0..steps {
            cloth.step(1.0 / 60.0, G, &|_| wind);
        }
        let micros = begin.elapsed().as_secs_f64() * 1e6 / f64::from(seconds);
        (cloth.positions().to_vec(), micros)
    };
    // The free edge's middle: the mean of the two middle rows' last nodes.
    let middle = |rows: usize, p: &[Vec3]| {
        let columns = rows * 3 / 2;
        let (a, b) = (
            (rows / 2 - 1) * columns + columns - 1,
            (rows / 2) * columns + columns - 1,
        );
        (p[a] + p[b]) * 0.5
    };
    let ticks: &[f32] = if r.quick {
        &[4e-3, 2e-3]
    } else {
        &[4e-3, 2e-3, 1e-3, 5e-4]
    };
    let (reference, _) = run(16, 2.5e-4, SHORT);
    let (mut table, mut by_tick) = (Vec::new(), Vec::new());
    for &tick in ticks {
        let (short, _) = run(16, tick, SHORT);
        let (_, micros) = run(16, tick, 1.0);
        let error = rms_error(&short, &reference, 1.5);
        by_tick.push((micros, error));
        table.push(vec![
            format!("16 × 24, ticks of {} ms", tick * 1e3),
            sci(error),
            format!("{micros:.0}"),
        ]);
    }
    let grids: &[usize] = if r.quick {
        &[8, 16]
    } else {
        &[8, 12, 16, 24, 32]
    };
    let (finest, _) = run(48, ParticleCloth::SUBSTEP, SHORT);
    let target = middle(48, &finest);
    let mut by_grid = Vec::new();
    for &rows in grids {
        let (short, _) = run(rows, ParticleCloth::SUBSTEP, SHORT);
        let (_, micros) = run(rows, ParticleCloth::SUBSTEP, 1.0);
        let error = f64::from(middle(rows, &short).distance(target) / 1.5);
        by_grid.push((micros, error));
        table.push(vec![
            format!("{rows} × {}, ticks of 4 ms", rows * 3 / 2),
            sci(error),
            format!("{micros:.0}"),
        ]);
    }
    r.table(
        &["flag", "error at 0.1 s / width", "µs per simulated s"],
        &table,
    );
    r.figure(
        "aero_particle_cloth",
        &Plot {
            title: "Particle flag: error at 0.1 s against run time, over ticks and grids",
            x_label: "µs per simulated second",
            y_label: "error / width",
            series: vec![
                Series::new("ticks of 4 … 0.5 ms (16 rows)", by_tick),
                Series::new("8 … 32 rows (ticks of 4 ms)", by_grid),
            ],
        },
    );
}
