//! Aero costs: `face_force` over 100 000 faces; one fixed step of a physically driven leaf (a
//! `RigidPlate` of 2 × 2 faces) against the procedural `FallingObject` leaf in the same wind;
//! one step of a flag as a P-descriptor `ClothSim` (24 × 16 and 36 × 24 nodes) and as a
//! `ParticleCloth` (36 × 24 and 72 × 48).
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
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::faces);
}
criterion_main!(group::benches);
