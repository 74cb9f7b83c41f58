//! Cost of one fixed step of 100 000 leaves in a [`LeafCloud`], against 100 000 bare drag
//! particles in the same wind stepped the same way (the same thread pool, the same chunks, the
//! wind read four points at a time as the cloud reads it):
//! v += (g + c |u − v| (u − v)) dt, x += v dt. Also the cost of posing the cloud for drawing and
//! what levels of detail save.
//!
//! The leaf's own work is also measured on one thread against a yardstick that does not move
//! with the crate: drag particles reading a frozen 64³ grid of velocities by trilinear
//! interpolation, written here.
//!
//! Run: `cargo bench --bench cloud`. Figures are in the README's Performance section.

use bevy_windfall::lod::LodTiers;
use std::hint::black_box;
use std::time::Duration;

use bevy::math::Vec3;
use bevy::tasks::{ParallelSliceMut, TaskPool, TaskPoolBuilder};
use bevy_windfall::freefall::cloud::{CloudLeaves, CloudStep};
use bevy_windfall::freefall::{CloudRegion, FallModel, LeafCloud};
use bevy_windfall::lod::{Focus, LodView};
use bevy_windfall::wind::{WindConfig, WindField};
use criterion::measurement::WallTime;
use criterion::{BatchSize, BenchmarkGroup, Criterion, criterion_main};

const LEAVES: u32 = 100_000;
const DT: f32 = 1.0 / 60.0;

fn storm(lod: LodTiers) -> LeafCloud {
    LeafCloud {
        count: LEAVES,
        seed: 7,
        region: CloudRegion {
            min: Vec3::new(-100.0, 2.0, -100.0),
            max: Vec3::new(100.0, 30.0, 100.0),
        },
        lod,
        ..LeafCloud::default()
    }
}

/// The cloud after two seconds of falling (motions under way, blends and pieces mixed), its
/// levels of detail measured from `focus`.
fn warmed(
    model: &FallModel,
    wind: &WindField,
    lod: LodTiers,
    focus: Option<Focus>,
    pool: &TaskPool,
) -> CloudLeaves {
    // Far below: every leaf is in the air for the whole run (the costly case).
    let mut leaves = storm(lod).leaves(model, -1.0e5).unwrap();
    for _ in 0..120 {
        leaves.step(&step(model, wind, focus), Some(pool));
    }
    leaves
}

fn step<'a>(model: &'a FallModel, wind: &'a WindField, focus: Option<Focus>) -> CloudStep<'a> {
    CloudStep {
        model,
        wind: Some(wind),
        dt: DT,
        wind_tilt: 0.6,
        focus,
    }
}

/// Rows `leaf_cloud_{with_wind,still_air}_one_thread{suffix}`: `steps` consecutive steps of the
/// warmed cloud `full` on this thread, in `wind` and in still air.
fn one_thread_rows(
    group: &mut BenchmarkGroup<'_, WallTime>,
    full: &CloudLeaves,
    model: &FallModel,
    wind: &WindField,
    steps: usize,
    suffix: &str,
) {
    for (air, field) in [("with_wind", Some(wind)), ("still_air", None)] {
        let name = format!("leaf_cloud_{air}_one_thread{suffix}");
        group.bench_function(name, |b| {
            b.iter_batched_ref(
                || full.clone(),
                |leaves| {
                    let step = CloudStep {
                        wind: field,
                        ..step(model, wind, None)
                    };
                    for _ in 0..steps {
                        black_box(leaves.step(&step, None));
                    }
                },
                BatchSize::LargeInput,
            )
        });
    }
}

/// The baseline: explicit drag particles, chunked on the same pool, each chunk reading the
/// wind with the crate's batched read (`velocities_at`, four points at a time in SIMD lanes).
fn drag_particles(mut particles: &mut [(Vec3, Vec3)], wind: &WindField, pool: Option<&TaskPool>) {
    let c = 0.5 * 1.2 * 1.2 * 2.4e-3 / 3.6e-4; // ½ ρ C_D A / m for the default leaf
    let step = |chunk: &mut [(Vec3, Vec3)]| {
        let positions: Vec<Vec3> = chunk.iter().map(|(x, _)| *x).collect();
        let mut winds = Vec::with_capacity(chunk.len());
        wind.velocities_at(&positions, wind.time(), &mut winds);
        for ((x, v), u) in chunk.iter_mut().zip(winds) {
            let relative = u - *v;
            *v += (Vec3::new(0.0, -9.81, 0.0) + c * relative.length() * relative) * DT;
            *x += *v * DT;
        }
    };
    match pool {
        Some(pool) => {
            particles.par_chunk_map_mut(pool, CloudLeaves::CHUNK, |_, chunk| step(chunk));
        }
        None => particles.chunks_mut(CloudLeaves::CHUNK).for_each(step),
    }
}

/// The yardstick that does not move with the crate: a drag particle reading a frozen 64³ grid of
/// velocities by trilinear interpolation (scalar f32, eight gathers), written here. The grid
/// holds the wind field's velocities at its nodes over the storm's region, 16 m above and below.
struct FrozenGrid {
    min: Vec3,
    inverse_cell: Vec3,
    velocities: Vec<Vec3>,
}

impl FrozenGrid {
    const N: usize = 64;

    fn sampled(wind: &WindField) -> Self {
        let region = storm(LodTiers::FULL).region;
        let (min, max) = (
            region.min - Vec3::new(0.0, 16.0, 0.0),
            region.max + Vec3::new(0.0, 16.0, 0.0),
        );
        let cell = (max - min) / (Self::N - 1) as f32;
        let n = Self::N;
        let points: Vec<Vec3> = (0..n * n * n)
            .map(|i| {
                min + cell * Vec3::new((i % n) as f32, (i / n % n) as f32, (i / (n * n)) as f32)
            })
            .collect();
        let mut velocities = Vec::with_capacity(points.len());
        wind.velocities_at(&points, wind.time(), &mut velocities);
        Self {
            min,
            inverse_cell: cell.recip(),
            velocities,
        }
    }

    fn at(&self, p: Vec3) -> Vec3 {
        let n = Self::N;
        let g = ((p - self.min) * self.inverse_cell)
            .clamp(Vec3::ZERO, Vec3::splat((n - 1) as f32 - 1e-3));
        let (i, j, k) = (g.x as usize, g.y as usize, g.z as usize);
        let f = g - Vec3::new(i as f32, j as f32, k as f32);
        let at = |a: usize, b: usize, c: usize| self.velocities[a + n * (b + n * c)];
        let x00 = at(i, j, k).lerp(at(i + 1, j, k), f.x);
        let x10 = at(i, j + 1, k).lerp(at(i + 1, j + 1, k), f.x);
        let x01 = at(i, j, k + 1).lerp(at(i + 1, j, k + 1), f.x);
        let x11 = at(i, j + 1, k + 1).lerp(at(i + 1, j + 1, k + 1), f.x);
        x00.lerp(x10, f.y).lerp(x01.lerp(x11, f.y), f.z)
    }
}

/// Frozen-grid drag particles, one thread: v += (g + c |u − v| (u − v)) dt, x += v dt.
fn frozen_drag_particles(particles: &mut [(Vec3, Vec3)], grid: &FrozenGrid) {
    let c = 0.5 * 1.2 * 1.2 * 2.4e-3 / 3.6e-4;
    for (x, v) in particles.iter_mut() {
        let relative = grid.at(*x) - *v;
        *v += (Vec3::new(0.0, -9.81, 0.0) + c * relative.length() * relative) * DT;
        *x += *v * DT;
    }
}

fn cloud(c: &mut Criterion) {
    let pool = TaskPoolBuilder::new().num_threads(2).build();
    let model = FallModel::default();
    let wind = WindField::new(WindConfig::default()).unwrap();
    let full = warmed(&model, &wind, LodTiers::FULL, None, &pool);
    println!(
        "cloud: {} bytes a leaf (the store's columns and cold state, spare capacity included)",
        full.memory_bytes() / full.len()
    );
    let mut group = c.benchmark_group("cloud_step_100k");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4));
    group.bench_function("leaf_cloud_with_wind", |b| {
        b.iter_batched_ref(
            || full.clone(),
            |leaves| leaves.step(&step(&model, &wind, None), Some(&pool)),
            BatchSize::LargeInput,
        )
    });
    let particles: Vec<(Vec3, Vec3)> = full.paths().map(|p| (p.position(), p.drift())).collect();
    group.bench_function("baseline_drag_particles_with_wind", |b| {
        b.iter_batched_ref(
            || particles.clone(),
            |p| drag_particles(p, &wind, Some(&pool)),
            BatchSize::LargeInput,
        )
    });
    // One thread (no pool): a leaf-step's cost in ns is the time / 100 000; in still air (no
    // wind read), the synthesis alone. Then the same in four lanes where the default is eight
    // (AVX2): what the wider lanes bring.
    let widths: &[(usize, &str)] = if bevy_windfall::widest_lanes() == 8 {
        &[(8, ""), (4, "_4_lanes")]
    } else {
        &[(4, "")]
    };
    for &(width, suffix) in widths {
        bevy_windfall::set_lane_width(width);
        one_thread_rows(&mut group, &full, &model, &wind, 1, suffix);
    }
    bevy_windfall::set_lanes(true);
    // The rows above step the warmed cloud once. Step by step the cost varies with how many
    // leaves cross a piece's end (printed). Sixteen consecutive steps, one thread, eight lanes
    // where there are (as the rows above): the mean a game's frames see is this row's time / 16.
    let still = CloudStep {
        wind: None,
        ..step(&model, &wind, None)
    };
    let mut leaves = full.clone();
    let pieces =
        |leaves: &CloudLeaves| -> u64 { leaves.paths().map(|p| u64::from(p.markov_steps())).sum() };
    let times: Vec<String> = (0..16)
        .map(|_| {
            let before = pieces(&leaves);
            let start = std::time::Instant::now();
            black_box(leaves.step(&still, None));
            let ms = start.elapsed().as_secs_f64() * 1e3;
            format!("{ms:.1} ({} ends)", pieces(&leaves) - before)
        })
        .collect();
    println!(
        "cloud: 16 steps in still air, one thread, ms each (the piece ends crossed): {}",
        times.join(" ")
    );
    one_thread_rows(&mut group, &full, &model, &wind, 16, "_16_steps");
    group.bench_function("baseline_drag_particles_with_wind_one_thread", |b| {
        b.iter_batched_ref(
            || particles.clone(),
            |p| drag_particles(p, &wind, None),
            BatchSize::LargeInput,
        )
    });
    let frozen = FrozenGrid::sampled(&wind);
    group.bench_function("baseline_frozen_drag_particles_one_thread", |b| {
        b.iter_batched_ref(
            || particles.clone(),
            |p| frozen_drag_particles(p, &frozen),
            BatchSize::LargeInput,
        )
    });
    // The camera at one edge of the 200 m square: near leaves every step, the rest less often.
    // Then in the middle of the storm, without and with Bevy's default view looking along +z:
    // what it does not see beyond `near` every fourth step.
    let (edge, centre) = (Vec3::new(0.0, 2.0, -100.0), Vec3::new(0.0, 2.0, 0.0));
    for (name, focus) in [
        ("leaf_cloud_with_wind_lod", Focus::from(edge)),
        ("leaf_cloud_with_wind_lod_centre", Focus::from(centre)),
        (
            "leaf_cloud_with_wind_lod_centre_view",
            Focus::looking(centre, Vec3::Z, LodView::default()),
        ),
    ] {
        let tiered = warmed(&model, &wind, LodTiers::default(), Some(focus), &pool);
        let advanced = tiered
            .clone()
            .step(&step(&model, &wind, Some(focus)), Some(&pool))
            .advanced;
        println!("{name}: {advanced} leaves stepped");
        group.bench_function(name, |b| {
            b.iter_batched_ref(
                || tiered.clone(),
                |leaves| leaves.step(&step(&model, &wind, Some(focus)), Some(&pool)),
                BatchSize::LargeInput,
            )
        });
    }
    let mut poses = Vec::new();
    group.bench_function("poses_for_drawing", |b| {
        b.iter(|| full.poses(0.5, Some(&pool), &mut poses))
    });
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::cloud);
}
criterion_main!(group::benches);
