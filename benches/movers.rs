//! What `WindMover`s cost: a headless app stepping a 10 000-leaf `LeafCloud` in the default
//! wind with 100 entities walking a kilometre away, plain (the baseline) or each a `WindMover`
//! (culled: nothing of them reaches a leaf), and with the 100 movers walking through the cloud;
//! and the same app without the cloud (what the frame costs without the leaves). The issue's
//! bound: 100 far movers add at most a tenth of the cloud's own step,
//! (far − cloud) ≤ 0.1 × (cloud − no cloud).
//!
//! Run: `cargo bench --ignore-rust-version --bench movers`.

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::prelude::*;
use criterion::{Criterion, criterion_main};

const LEAVES: u32 = 10_000;
const MOVERS: usize = 100;

/// Walks each mover round a circle of its own at 6 m/s, before the wind is placed.
#[derive(Component)]
struct Walker {
    centre: Vec3,
    phase: f32,
}

fn walk(time: Res<Time<Fixed>>, mut walkers: Query<(&Walker, &mut Transform)>) {
    let t = time.elapsed_secs();
    for (w, mut transform) in &mut walkers {
        let angle = w.phase + t * 6.0 / 3.0;
        transform.translation = w.centre + Vec3::new(3.0 * angle.cos(), 0.0, 3.0 * angle.sin());
    }
}

/// The app: `cloud` leaves or none, 100 walkers about `at`, each a `WindMover` if `movers`.
fn app(cloud: bool, at: Vec3, movers: bool) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()))
        .insert_resource(Time::<Fixed>::from_hz(60.0))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_systems(FixedUpdate, walk.before(WindfallSystems::Wind));
    if cloud {
        app.world_mut().spawn(LeafCloud {
            count: LEAVES,
            seed: 3,
            region: CloudRegion {
                min: Vec3::new(-50.0, 2.0, -50.0),
                max: Vec3::new(50.0, 40.0, 50.0),
            },
            ..default()
        });
    }
    for i in 0..MOVERS {
        let spot = Vec3::new(
            (i % 10) as f32 * 9.0 - 45.0,
            0.5,
            (i / 10) as f32 * 9.0 - 45.0,
        );
        let mut walker = app.world_mut().spawn((
            Walker {
                centre: at + spot,
                phase: i as f32,
            },
            Transform::from_translation(at + spot),
        ));
        if movers {
            walker.insert(WindMover::default());
        }
    }
    app.finish();
    app.cleanup();
    // Two seconds: the leaves under way, the movers walking.
    for _ in 0..120 {
        app.update();
    }
    app
}

fn movers(c: &mut Criterion) {
    let mut group = c.benchmark_group("movers");
    group
        .sample_size(60)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(8));
    let far = Vec3::new(1000.0, 0.0, 1000.0);
    for (name, cloud, at, movers) in [
        ("app_update_no_cloud", false, far, false),
        ("app_update_no_cloud_100_movers", false, far, true),
        ("app_update_cloud_10k", true, far, false),
        ("app_update_cloud_10k_100_far_movers", true, far, true),
        (
            "app_update_cloud_10k_100_movers_in_it",
            true,
            Vec3::ZERO,
            true,
        ),
    ] {
        group.bench_function(name, |b| {
            let mut app = app(cloud, at, movers);
            b.iter(|| app.update())
        });
    }
    group.finish();
}

#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::movers);
}
criterion_main!(group::benches);
