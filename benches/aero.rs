//! Aero costs: `face_force` over 100 000 faces; one fixed step of a physically driven leaf (a
//! `RigidPlate` of 2 × 2 faces) against the procedural `FallingObject` leaf in the same wind;
//! one step of a flag as a P-descriptor `ClothSim` (24 × 16 and 36 × 24 nodes) and as a
//! `ParticleCloth` (36 × 24 and 72 × 48); and the yardstick the particle cloth is held to, a
//! plain position-based game cloth of the same 36 × 24 nodes ([`PlainCloth`], written here so
//! that it does not move when the crate does), both in an 8 m/s wind.
//!
//! Run: `cargo bench --bench aero`. Figures are in the README's Performance section.

use std::hint::black_box;
use std::time::Duration;

use bevy::math::Vec3;
use bevy_windfall::aero::{
    AeroCoefficients, ParticleCloth, Pinning, PlateState, RigidPlate, face_force,
};
use bevy_windfall::cloth::{ClothAttachment, ClothGrid, ClothPreset, ClothSim};
use bevy_windfall::freefall::{FallModel, FallPath, FallingObject, WindTilt};
use bevy_windfall::wind::{WindConfig, WindField};
use criterion::{BatchSize, Criterion, criterion_main};

const DT: f32 = 1.0 / 60.0;

fn faces(c: &mut Criterion) {
    let n = 100_000;
    let data: Vec<(Vec3, Vec3)> = (0..n)
        .map(|i| {
            let f = i as f32;
            (
                Vec3::new(
                    (f * 0.37).sin() * 5.0,
                    -(f * 0.11).cos() * 4.0 - 1.0,
                    (f * 0.05).sin(),
                ),
                Vec3::new((f * 0.7).cos(), 1.0, (f * 0.3).sin()),
            )
        })
        .collect();
    let mut group = c.benchmark_group("aero");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("face_force_100k", |b| {
        b.iter(|| {
            let mut total = Vec3::ZERO;
            for (v, n) in &data {
                total += face_force(*v, *n, 1e-3, 1.2, 1.0, AeroCoefficients::AIR_DENSITY);
            }
            black_box(total)
        })
    });

    let wind = WindField::new(WindConfig::default()).unwrap();
    let model = FallModel::default();
    let object = FallingObject::default();
    let regime = object.regime().unwrap();
    let path = FallPath::new(
        &model,
        object.scales(&regime),
        regime.main,
        1,
        Vec3::new(3.0, 8.0, 2.0),
        f32::NEG_INFINITY,
    )
    .expect("a release within bounds");
    let tilt = WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    };
    group.bench_function("leaf_step/procedural", |b| {
        b.iter_batched_ref(
            || path.clone(),
            |p| {
                let u = wind.velocity(p.position());
                p.advance(&model, DT, u, &tilt)
            },
            BatchSize::SmallInput,
        )
    });
    // The same leaf as a rigid plate: 7.3 × 4.2 cm, 0.3 mm, 500 kg/m³, 2 × 2 faces.
    let plate =
        RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2).unwrap();
    let start = PlateState {
        position: Vec3::new(3.0, 8.0, 2.0),
        velocity: Vec3::new(1.0, -1.0, 0.0),
        rotation: bevy::math::Quat::from_rotation_z(0.3),
        ..Default::default()
    };
    group.bench_function("leaf_step/physical_rigid_plate", |b| {
        b.iter_batched_ref(
            || start,
            |s| {
                plate.step(
                    s,
                    DT,
                    Vec3::new(0.0, -9.81, 0.0),
                    &|p| wind.velocity(p),
                    false,
                )
            },
            BatchSize::SmallInput,
        )
    });
    // A flag of 24 × 16 nodes and one of 36 × 24 as a P-descriptor cloth (advance + rebuild);
    // the particle cloth of 36 × 24 and 72 × 48 nodes (1.5 × 1 m, 0.15 kg/m²), each step
    // measured on a flag already flapping (a second of the same wind first).
    let params = ClothPreset::FlagFlappingFrozen.params();
    let gravity = Vec3::new(0.0, -9.81, 0.0);
    let grid = |rows: usize, columns: usize| ClothGrid {
        rows,
        columns,
        width: 1.5,
        height: 1.0,
    };
    for (rows, columns) in [(16, 24), (24, 36)] {
        let mut procedural =
            ClothSim::new(grid(rows, columns), params, ClothAttachment::Pole).unwrap();
        group.bench_function(format!("flag_step_{columns}x{rows}/procedural"), |b| {
            b.iter(|| {
                procedural.advance(DT, params.wind_steps_per_frame);
                procedural.rebuild();
                black_box(procedural.positions()[0])
            })
        });
    }
    let blowing = |p: Vec3| wind.velocity(p + Vec3::new(0.0, 5.0, 0.0));
    for (rows, columns) in [(24, 36), (48, 72)] {
        let mut physical = ParticleCloth::new(
            grid(rows, columns),
            0.15,
            AeroCoefficients::default(),
            Pinning::PoleColumn,
        )
        .unwrap();
        for _ in 0..60 {
            physical.step(DT, gravity, &blowing);
        }
        group.bench_function(
            format!("flag_step_{columns}x{rows}/physical_particles"),
            |b| {
                b.iter(|| {
                    physical.step(DT, gravity, &blowing);
                    black_box(physical.positions()[0])
                })
            },
        );
    }
    // The yardstick and the particle cloth in the same 8 m/s wind (at 5 m, log law, turbulence).
    let breeze = WindField::new(WindConfig {
        reference_speed: 8.0,
        ..WindConfig::default()
    })
    .unwrap();
    let field = &breeze;
    let breeze = |p: Vec3| breeze.velocity(p + Vec3::new(0.0, 5.0, 0.0));
    let mut plain = PlainCloth::new(36, 24, 1.5, 1.0, 0.15);
    let mut physical = ParticleCloth::new(
        grid(24, 36),
        0.15,
        AeroCoefficients::default(),
        Pinning::PoleColumn,
    )
    .unwrap();
    for _ in 0..60 {
        plain.step(DT, gravity, &breeze);
        physical.step(DT, gravity, &breeze);
    }
    group.bench_function("flag_step_36x24_8ms/plain_position_based", |b| {
        b.iter(|| {
            plain.step(DT, gravity, &breeze);
            black_box(plain.x[0])
        })
    });
    group.bench_function("flag_step_36x24_8ms/physical_particles", |b| {
        b.iter(|| {
            physical.step(DT, gravity, &breeze);
            black_box(physical.positions()[0])
        })
    });
    // The same flag reading the wind for all its nodes at once (`step_batched` with
    // `WindField::velocities`, as the `PhysicalCloth` plugin does: the same bits).
    let mut batched = physical.clone();
    let mut lifted = Vec::new();
    let mut read = |nodes: &[Vec3], velocities: &mut Vec<Vec3>| {
        lifted.clear();
        lifted.extend(nodes.iter().map(|p| *p + Vec3::new(0.0, 5.0, 0.0)));
        field.velocities(&lifted, velocities);
    };
    group.bench_function("flag_step_36x24_8ms/physical_particles_batched_wind", |b| {
        b.iter(|| {
            batched.step_batched(DT, gravity, &mut read);
            black_box(batched.positions()[0])
        })
    });
    // The same flag with ticks of 2 ms, half the default (`ParticleCloth::SUBSTEP`, 4 ms): twice
    // the ticks a frame (tests/it/physical_flag.rs `ticks_give_the_same_flag` measures what it
    // changes).
    let mut short_ticks = physical.clone();
    short_ticks.tick = 2e-3;
    for _ in 0..60 {
        short_ticks.step(DT, gravity, &breeze);
    }
    group.bench_function("flag_step_36x24_8ms/physical_particles_2ms_ticks", |b| {
        b.iter(|| {
            short_ticks.step(DT, gravity, &breeze);
            black_box(short_ticks.positions()[0])
        })
    });
    group.finish();
}

/// A plain position-based cloth as game engines ship it (Müller et al., "Position based
/// dynamics", 2007): Verlet integration with explicit gravity and a pull toward the wind,
/// structural links (rows and columns) and shear links (both diagonals of every cell), eight
/// Gauss–Seidel sweeps a frame, the first column pinned. No added mass, no implicit air.
struct PlainCloth {
    x: Vec<Vec3>,
    previous: Vec<Vec3>,
    inverse_mass: Vec<f32>,
    links: Vec<(u32, u32, f32)>,
    /// The pull toward the wind per node, 1/s (a drag rate: ½ ρ C_D A / m at 1 m/s).
    pull: f32,
}

impl PlainCloth {
    const SWEEPS: usize = 8;

    fn new(columns: usize, rows: usize, width: f32, height: f32, areal_density: f32) -> Self {
        let (dx, dy) = (width / (columns - 1) as f32, height / (rows - 1) as f32);
        let x: Vec<Vec3> = (0..rows * columns)
            .map(|i| Vec3::new((i % columns) as f32 * dx, -((i / columns) as f32) * dy, 0.0))
            .collect();
        let inverse_mass = (0..rows * columns)
            .map(|i| if i % columns == 0 { 0.0 } else { 1.0 })
            .collect();
        let mut links = Vec::new();
        let mut link = |a: usize, b: usize| links.push((a as u32, b as u32, x[a].distance(x[b])));
        for k in 0..rows {
            for j in 0..columns {
                let i = k * columns + j;
                if j + 1 < columns {
                    link(i, i + 1);
                }
                if k + 1 < rows {
                    link(i, i + columns);
                }
                if j + 1 < columns && k + 1 < rows {
                    link(i, i + columns + 1);
                    link(i + 1, i + columns);
                }
            }
        }
        let node_area = width * height / (rows * columns) as f32;
        let pull = 0.5 * AeroCoefficients::AIR_DENSITY * node_area / (areal_density * node_area);
        Self {
            previous: x.clone(),
            x,
            inverse_mass,
            links,
            pull,
        }
    }

    fn step(&mut self, dt: f32, gravity: Vec3, wind: &impl Fn(Vec3) -> Vec3) {
        for ((x, previous), w) in self
            .x
            .iter_mut()
            .zip(&mut self.previous)
            .zip(&self.inverse_mass)
        {
            if *w == 0.0 {
                continue;
            }
            let v = (*x - *previous) / dt;
            let relative = wind(*x) - v;
            let acceleration = gravity + self.pull * relative.length() * relative;
            *previous = *x;
            *x += v * dt + acceleration * dt * dt;
        }
        for _ in 0..Self::SWEEPS {
            for &(a, b, rest) in &self.links {
                let (a, b) = (a as usize, b as usize);
                let (wa, wb) = (self.inverse_mass[a], self.inverse_mass[b]);
                let delta = self.x[b] - self.x[a];
                let length = delta.length();
                if wa + wb == 0.0 || length == 0.0 {
                    continue;
                }
                let correction = delta * ((length - rest) / (length * (wa + wb)));
                self.x[a] += wa * correction;
                self.x[b] -= wb * correction;
            }
        }
    }
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::faces);
}
criterion_main!(group::benches);
