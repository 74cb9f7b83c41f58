//! Generation and sampling cost of the wind field, side by side with baselines:
//! - generation against bare rustfft n-D inverse transforms of the same size (SIMD and scalar
//!   planners), three of them, one per wind component;
//! - sampling against the `noise` crate's `Fbm<Perlin>` at 4 octaves;
//! - sampling with 16 local sources against sampling with none.
//!
//! Run: `cargo bench --bench wind`. Figures are in the README's Performance section.

use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use bevy::math::{Vec2, Vec3};
use bevy_windfall::spectrum::{FftBackend, Synthesizer};
use bevy_windfall::wind::{
    SpatialMode, TemporalMode, WindConfig, WindField, WindPlugin, WindSource,
};
use criterion::{BenchmarkId, Criterion, criterion_main};
use noise::{Fbm, MultiFractal, NoiseFn, Perlin};
use rustfft::{Fft, FftPlanner, FftPlannerScalar, num_complex::Complex};

/// A bare n-D inverse FFT: rustfft along each axis, lines gathered into a contiguous buffer.
struct BareInverse {
    dims: Vec<usize>,
    ffts: Vec<Arc<dyn Fft<f32>>>,
}

impl BareInverse {
    fn new(dims: &[usize], simd: bool) -> Self {
        let mut simd_planner = FftPlanner::new();
        let mut scalar_planner = FftPlannerScalar::new();
        let ffts = dims
            .iter()
            .map(|&n| {
                if simd {
                    simd_planner.plan_fft_inverse(n)
                } else {
                    scalar_planner.plan_fft_inverse(n)
                }
            })
            .collect();
        Self {
            dims: dims.to_vec(),
            ffts,
        }
    }

    fn run(&self, data: &mut [Complex<f32>]) {
        let len: usize = self.dims.iter().product();
        let mut stride = len;
        let mut buffer = Vec::new();
        for (axis, fft) in self.ffts.iter().enumerate() {
            let n = self.dims[axis];
            stride /= n;
            if stride == 1 {
                fft.process(data);
                continue;
            }
            buffer.resize(n * stride, Complex::default());
            for block in data.chunks_exact_mut(n * stride) {
                for i in 0..n {
                    for j in 0..stride {
                        buffer[j * n + i] = block[i * stride + j];
                    }
                }
                fft.process(&mut buffer);
                for i in 0..n {
                    for j in 0..stride {
                        block[i * stride + j] = buffer[j * n + i];
                    }
                }
            }
        }
    }
}

fn generation(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate_3_components");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let cases: [(&str, [usize; 2], SpatialMode, Vec<usize>); 4] = [
        ("2d_256", [256, 256], SpatialMode::Plane, vec![256, 256]),
        (
            "3d_64",
            [64, 64],
            SpatialMode::Volume { vertical_nodes: 64 },
            vec![64; 3],
        ),
        (
            "3d_100",
            [100, 100],
            SpatialMode::Volume {
                vertical_nodes: 100,
            },
            vec![100; 3],
        ),
        (
            "3d_128",
            [128, 128],
            SpatialMode::Volume {
                vertical_nodes: 128,
            },
            vec![128; 3],
        ),
    ];
    for (name, grid, spatial, dims) in cases {
        for (label, fft) in [
            ("windfall_portable", FftBackend::Portable),
            ("windfall_simd", FftBackend::Simd),
        ] {
            let config = WindConfig {
                grid,
                spatial,
                fft,
                ..WindConfig::default()
            };
            group.bench_function(BenchmarkId::new(label, name), |b| {
                b.iter(|| WindField::new(black_box(config.clone())).unwrap())
            });
        }
        // The first field of a grid: the amplitude table and the FFT plans made afresh (what
        // `WindField::new` costs before `Synthesizer::shared` has the grid).
        group.bench_function(BenchmarkId::new("windfall_portable_first", name), |b| {
            b.iter(|| {
                let synth = Synthesizer::new(&dims, 5.0 / 3.0, FftBackend::Portable).unwrap();
                black_box((synth.pair(1), synth.field(2)))
            })
        });
        let len: usize = dims.iter().product();
        for (label, simd) in [("rustfft_simd_x3", true), ("rustfft_scalar_x3", false)] {
            let bare = BareInverse::new(&dims, simd);
            let spectrum: Vec<Complex<f32>> = (0..len)
                .map(|i| Complex::new((i % 7) as f32, (i % 3) as f32))
                .collect();
            let mut data = spectrum.clone();
            group.bench_function(BenchmarkId::new(label, name), |b| {
                b.iter(|| {
                    for _ in 0..3 {
                        data.copy_from_slice(&spectrum);
                        bare.run(&mut data);
                    }
                    black_box(data[1])
                })
            });
        }
    }
    group.finish();
}

/// 4096 points spread over a 97 × 20 × 89 m box.
fn points() -> Vec<Vec3> {
    (0..4096)
        .map(|i| {
            let f = i as f32;
            Vec3::new(f * 0.37 % 97.0, 0.5 + f * 0.11 % 20.0, f * 0.73 % 89.0)
        })
        .collect()
}

fn sampling(c: &mut Criterion) {
    let mut group = c.benchmark_group("sample_4096_points");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let points = points();
    let modes = [
        ("plane_frozen", SpatialMode::Plane, TemporalMode::Frozen),
        (
            "volume_evolving",
            SpatialMode::Volume { vertical_nodes: 32 },
            TemporalMode::Evolving {
                samples: 16,
                period: 16.0,
            },
        ),
    ];
    for (name, spatial, temporal) in modes {
        let field = WindField::new(WindConfig {
            spatial,
            temporal,
            grid: [64, 64],
            direction: Vec2::new(1.0, 0.3),
            ..WindConfig::default()
        })
        .unwrap();
        let mut out = Vec::with_capacity(points.len());
        group.bench_function(BenchmarkId::new("windfall_vec3", name), |b| {
            b.iter(|| {
                field.velocities_at(black_box(&points), 1.25, &mut out);
                black_box(out[7])
            })
        });
    }
    let fbm = Fbm::<Perlin>::new(7).set_octaves(4);
    group.bench_function(BenchmarkId::new("noise_fbm_perlin_4oct", "scalar"), |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for p in black_box(&points) {
                sum += fbm.get([f64::from(p.x), f64::from(p.y), f64::from(p.z)]);
            }
            sum
        })
    });
    group.finish();
}

/// The field of a headless app after one fixed step with `sources` placed: what systems sample.
fn field_with(sources: &[(WindSource, Vec3)]) -> WindField {
    use bevy::prelude::*;
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .add_plugins(WindPlugin::new(WindConfig {
            grid: [64, 64],
            direction: Vec2::new(1.0, 0.3),
            ..WindConfig::default()
        }));
    for &(source, at) in sources {
        app.world_mut()
            .spawn((source, Transform::from_translation(at)));
    }
    app.world_mut().run_schedule(FixedUpdate);
    let field = app.world().resource::<WindField>().clone();
    assert_eq!(field.source_count(), sources.len());
    field
}

/// Local sources: 4096 points sampled with none, with 16 scattered over the points' 97 × 89 m
/// area (5 m each: most points are outside every one, as in a game), and with 16 that all cover
/// every point (the worst case). The target: 16 sources cost at most 2× none.
fn sources(c: &mut Criterion) {
    let mut group = c.benchmark_group("sample_4096_points_with_sources");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let points = points();
    let kinds = |i: usize, reach: f32| match i % 4 {
        0 => WindSource::sphere(reach, Vec3::new(2.0, 1.0, 0.0)),
        1 => WindSource::fan(reach, 0.5, 6.0),
        2 => WindSource::vortex(reach, 8.0).with_updraft(2.0),
        _ => WindSource::blast(20.0, 1.0, reach),
    };
    let scattered: Vec<(WindSource, Vec3)> = (0..16)
        .map(|i| {
            let f = i as f32;
            (
                kinds(i, 5.0),
                Vec3::new(f * 23.0 % 97.0, 2.0, f * 41.0 % 89.0),
            )
        })
        .collect();
    let covering: Vec<(WindSource, Vec3)> = (0..16)
        .map(|i| (kinds(i, 200.0), Vec3::new(48.0, 10.0, 44.0)))
        .collect();
    let cases = [
        ("none", field_with(&[])),
        ("16_scattered", field_with(&scattered)),
        ("16_covering_every_point", field_with(&covering)),
    ];
    for (name, field) in cases {
        let mut out = Vec::with_capacity(points.len());
        group.bench_function(BenchmarkId::new("plane_frozen", name), |b| {
            b.iter(|| {
                field.velocities_at(black_box(&points), 2.0, &mut out);
                black_box(out[7])
            })
        });
    }
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::generation, super::sampling, super::sources);
}
criterion_main!(group::benches);
