//! Cost of one cloth frame: the fixed-step advance, the shape rebuild (noise → descriptor →
//! yarns → eq. 7) and the in-place mesh attribute update, without the GPU upload.
//!
//! Run: `cargo bench --bench cloth`. Figures are in the README's Performance section.

use bevy_windfall::cloth::mesh;
use std::hint::black_box;
use std::time::Duration;

use bevy_windfall::cloth::{ClothAttachment, ClothGrid, ClothPreset, ClothSim};
use criterion::{BenchmarkId, Criterion, criterion_main};

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("cloth_frame");
    group
        .sample_size(50)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for size in [16usize, 32, 64, 128] {
        for preset in [
            ClothPreset::FlagFlappingFrozen,
            ClothPreset::FlagFlappingEvolving,
        ] {
            let grid = ClothGrid {
                rows: size,
                columns: size,
                width: 1.5,
                height: 1.0,
            };
            let params = preset.params();
            let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).unwrap();
            let mut mesh = mesh::build(size, size, sim.positions());
            let name = format!("{size}x{size}/{preset:?}");
            group.bench_function(BenchmarkId::new("step_rebuild_mesh", name), |b| {
                b.iter(|| {
                    sim.advance(1.0 / 64.0, params.wind_steps_per_frame);
                    sim.rebuild();
                    mesh::write(&mut mesh, size, size, black_box(sim.positions()));
                })
            });
        }
    }
    // Levels of detail (`ClothLod`): the 64 × 64 flag traced on a grid 1, 2 and 4 times
    // coarser; the mesh (positions and normals) is still written in full.
    for stride in [1usize, 2, 4] {
        let size = 64;
        let grid = ClothGrid {
            rows: size,
            columns: size,
            width: 1.5,
            height: 1.0,
        };
        let params = ClothPreset::FlagFlappingFrozen.params();
        let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).unwrap();
        let mut mesh = mesh::build(size, size, sim.positions());
        let name = format!("64x64/stride_{stride}");
        group.bench_function(BenchmarkId::new("step_rebuild_mesh_lod", name), |b| {
            b.iter(|| {
                sim.advance(1.0 / 64.0, params.wind_steps_per_frame);
                sim.rebuild_at_stride(1.0, stride);
                mesh::write(&mut mesh, size, size, black_box(sim.positions()));
            })
        });
    }
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::frame);
}
criterion_main!(group::benches);
