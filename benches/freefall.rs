//! Cost of one fixed step for 10 000 falling objects: wind sampling plus the procedural path,
//! each part alone, the whole plugin in a headless app, and a drag-particle baseline (the
//! "particle with drag and lift parameters" the paper says CG tools offer).
//!
//! Run: `cargo bench --bench freefall`. Figures are in the README's Performance section.

use std::hint::black_box;
use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::freefall::{
    FallLod, FallModel, FallPath, FallPlugin, FallSettings, FallStore, FallingObject, WindTilt,
};
use bevy_windfall::lod::LodFocus;
use bevy_windfall::wind::{WindConfig, WindField, WindPlugin};
use criterion::{BatchSize, Criterion, criterion_main};

const OBJECTS: usize = 10_000;
const DT: f32 = 1.0 / 60.0;
/// Where the app benches let their objects go from, above `release_point`.
const ALOFT: Vec3 = Vec3::new(0.0, 200.0, 0.0);

fn release_point(i: usize) -> Vec3 {
    let h = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    let f = |shift: u32| ((h >> shift) & 0xFFFF) as f32 / 65535.0;
    Vec3::new(60.0 * f(0), 5.0 + 10.0 * f(16), 60.0 * f(32))
}

fn paths(model: &FallModel) -> Vec<FallPath> {
    (0..OBJECTS)
        .map(|i| {
            let object = FallingObject {
                seed: i as u64,
                ..FallingObject::default()
            };
            let regime = object.regime().unwrap();
            FallPath::new(
                model,
                object.scales(&regime),
                regime.main,
                i as u64,
                release_point(i),
                f32::NEG_INFINITY,
            )
            .expect("a release within bounds")
        })
        .collect()
}

/// Explicit drag particle: v += (g + c |u − v| (u − v)) dt, x += v dt, the wind read with the
/// crate's batched read (`velocities_at`, four points at a time in SIMD lanes).
fn drag_particles(points: &mut [(Vec3, Vec3)], wind: &WindField, dt: f32) {
    let c = 0.5 * 1.2 * 1.2 * 2.4e-3 / 3.6e-4; // ½ ρ C_D A / m for the default leaf
    let positions: Vec<Vec3> = points.iter().map(|(x, _)| *x).collect();
    let mut winds = Vec::with_capacity(points.len());
    wind.velocities_at(&positions, wind.time(), &mut winds);
    for ((x, v), u) in points.iter_mut().zip(winds) {
        let relative = u - *v;
        *v += (Vec3::new(0.0, -9.81, 0.0) + c * relative.length() * relative) * dt;
        *x += *v * dt;
    }
}

/// A headless app of 10 000 falling objects, one fixed step per update, in wind or still air,
/// with levels of detail (`FallLod`, a `LodFocus` at (30, 2, −20)) or without.
fn falling_app(lod: bool, wind: bool) -> App {
    falling_app_of(OBJECTS, lod, wind)
}

/// [`falling_app`] with `objects` objects.
fn falling_app_of(objects: usize, lod: bool, wind: bool) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_seconds(f64::from(DT)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(FallPlugin::default())
        .insert_resource(FallSettings {
            // Far below (within the ±1e7 m a ground may be): every object falls for the whole
            // run.
            ground_height: -1.0e6,
        });
    if wind {
        app.add_plugins(WindPlugin::default());
    }
    for i in 0..objects {
        let mut e = app.world_mut().spawn((
            FallingObject {
                seed: i as u64,
                ..default()
            },
            // 200 m up: the bench runs for a minute of simulated time or more, and objects let
            // go at 5–15 m would soon fall below the log law's roughness height, where the wind
            // is zero (the figures of issue 18's first two sessions timed mostly that).
            Transform::from_translation(release_point(i) + ALOFT),
        ));
        if lod {
            e.insert(FallLod::default());
        }
    }
    if lod {
        app.world_mut().spawn((
            LodFocus,
            Transform::from_translation(Vec3::new(30.0, 2.0, -20.0) + ALOFT),
        ));
    }
    app.finish();
    app.cleanup();
    app.update();
    // Past the first steps (taken at once by every object with levels of detail).
    for _ in 0..8 {
        app.update();
    }
    // Every object falls (an invalid one would make the figure meaningless: it is not
    // stepped).
    let falling = app
        .world()
        .resource::<FallStore>()
        .falls()
        .filter(|(_, p)| !p.landed())
        .count();
    assert_eq!(falling, objects, "every object must be falling");
    app
}

/// After a bench: every object is still well above the roughness height (in the wind).
fn assert_aloft(app: &mut App) {
    let lowest = app
        .world()
        .resource::<FallStore>()
        .falls()
        .map(|(_, p)| p.position().y)
        .fold(f32::INFINITY, f32::min);
    assert!(
        lowest > 10.0,
        "an object fell to {lowest} m: out of the wind"
    );
}

/// What Bevy itself charges for `entities` entities whose transforms change every frame (a
/// trivial system writes them; propagation, change detection, schedule).
fn baseline_app(entities: usize) -> App {
    baseline_app_with(entities, |_| {})
}

/// [`baseline_app`] with `extra` applied before it is finished (plugins, resources).
fn baseline_app_with(entities: usize, extra: impl FnOnce(&mut App)) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .add_systems(Update, |mut q: Query<&mut Transform>| {
            q.par_iter_mut().for_each(|mut t| t.translation.y -= 1e-3);
        });
    for i in 0..entities {
        app.world_mut()
            .spawn(Transform::from_translation(release_point(i)));
    }
    extra(&mut app);
    app.finish();
    app.cleanup();
    app.update();
    app
}

fn step(c: &mut Criterion) {
    let model = FallModel::default();
    let wind = WindField::new(WindConfig::default()).unwrap();
    let tilt = WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    };
    let fresh = paths(&model);
    let mut group = c.benchmark_group("freefall_step_10k");
    group
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("procedural_with_wind", |b| {
        b.iter_batched_ref(
            || fresh.clone(),
            |paths| {
                for p in paths.iter_mut() {
                    let u = wind.velocity(p.position());
                    p.advance(&model, DT, u, &tilt);
                }
            },
            BatchSize::LargeInput,
        )
    });
    // The same two seconds into the fall: pieces end, the chain steps, the database is
    // searched, motion changes blend (the first step above does none of that).
    let mut warmed = fresh.clone();
    for _ in 0..120 {
        for p in warmed.iter_mut() {
            let u = wind.velocity(p.position());
            p.advance(&model, DT, u, &tilt);
        }
    }
    group.bench_function("procedural_with_wind_warmed", |b| {
        b.iter_batched_ref(
            || warmed.clone(),
            |paths| {
                for p in paths.iter_mut() {
                    let u = wind.velocity(p.position());
                    p.advance(&model, DT, u, &tilt);
                }
            },
            BatchSize::LargeInput,
        )
    });
    group.bench_function("procedural_still_air", |b| {
        b.iter_batched_ref(
            || fresh.clone(),
            |paths| {
                for p in paths.iter_mut() {
                    p.advance(&model, DT, Vec3::ZERO, &tilt);
                }
            },
            BatchSize::LargeInput,
        )
    });
    let points: Vec<Vec3> = (0..OBJECTS).map(release_point).collect();
    group.bench_function("wind_sampling_only", |b| {
        b.iter(|| {
            let mut sum = Vec3::ZERO;
            for p in &points {
                sum += wind.velocity(*p);
            }
            black_box(sum)
        })
    });
    let mut read = Vec::new();
    group.bench_function("wind_sampling_batched", |b| {
        b.iter(|| {
            wind.velocities_at(&points, wind.time(), &mut read);
            black_box(&read);
        })
    });
    let particles: Vec<(Vec3, Vec3)> = points.iter().map(|p| (*p, Vec3::ZERO)).collect();
    group.bench_function("baseline_drag_particle_with_wind", |b| {
        b.iter_batched_ref(
            || particles.clone(),
            |p| drag_particles(p, &wind, DT),
            BatchSize::LargeInput,
        )
    });
    group.bench_function("plugin_app_update", |b| {
        let mut app = falling_app(false, true);
        b.iter(|| app.update());
        assert_aloft(&mut app);
    });
    // The same with `FallLod` and the camera 20 m off one edge of the 60 m square: a few
    // objects every step, most every second or fourth.
    // Still air: what the wind's reads cost in the frame.
    group.bench_function("plugin_app_update_still_air", |b| {
        let mut app = falling_app(false, false);
        b.iter(|| app.update())
    });
    group.bench_function("plugin_app_update_lod", |b| {
        let mut app = falling_app(true, true);
        b.iter(|| app.update());
        assert_aloft(&mut app);
    });
    // The same app with no object: what the plugins' systems and the fixed-step loop cost
    // whatever the number of objects.
    group.bench_function("plugin_app_update_no_objects", |b| {
        let mut app = falling_app_of(0, false, true);
        b.iter(|| app.update())
    });
    // What Bevy itself charges for 10 000 entities whose transforms change every frame
    // (a trivial system writes them; propagation, change detection, schedule).
    group.bench_function("baseline_bevy_10k_moving_transforms", |b| {
        let mut app = baseline_app(OBJECTS);
        b.iter(|| app.update())
    });
    // Every plugin of the crate in the baseline's app with nothing to move: what the crate
    // costs a frame when a game uses none of it (one fixed step per frame, as in the benches
    // above and in a game at the fixed rate).
    group.bench_function("windfall_plugins_unused", |b| {
        let mut app = baseline_app_with(0, |app| {
            app.insert_resource(Time::<Fixed>::from_seconds(f64::from(DT)))
                .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
                .add_plugins(bevy_windfall::WindfallPlugins::default());
        });
        b.iter(|| app.update())
    });
    // The baseline's app, one fixed step per frame, no plugin of ours.
    group.bench_function("baseline_bevy_no_entities_fixed_step", |b| {
        let mut app = baseline_app_with(0, |app| {
            app.insert_resource(Time::<Fixed>::from_seconds(f64::from(DT)))
                .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
        });
        b.iter(|| app.update())
    });
    // The baseline's app with no entity: Bevy's own frame (time, schedules, propagation).
    group.bench_function("baseline_bevy_no_entities", |b| {
        let mut app = baseline_app(0);
        b.iter(|| app.update())
    });
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::step);
}
criterion_main!(group::benches);
