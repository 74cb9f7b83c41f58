//! No hidden ordering between the crate's systems: Bevy 0.20 can shuffle the order of systems
//! that no constraint orders (`ScheduleBuildSettings::shuffle_seed`). Falling objects, a leaf
//! cloud, a procedural flag, a particle cloth and a rigid plate, in a gusty wind with a fan, are
//! stepped with every schedule of the app shuffled by several seeds; every run ends on the same
//! bits as the unshuffled one.

use bevy::ecs::schedule::ScheduleBuildSettings;
use bevy::prelude::*;
use bevy_windfall::aero::PhysicalClothState;
use bevy_windfall::freefall::cloud::LeafCloudState;
use bevy_windfall::freefall::{FallPreset, LeafCloud};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindSource;

use crate::bevy_integration::{card, physical_flag, small_flag};
use crate::common::{headless_app_with_meshes, ready};
use crate::determinism::fingerprint::Fnv;

/// Fixed steps each run takes (3 s at 60 Hz).
const STEPS: usize = 180;

/// What a run ends on, and the order its schedules ran their systems in.
struct Run {
    hash: u64,
    order: Vec<String>,
}

fn run(shuffle_seed: Option<u64>) -> Run {
    let mut app = headless_app_with_meshes();
    let wind = WindConfig {
        reference_speed: 6.0,
        grid: [32, 32],
        seed: 3,
        temporal: TemporalMode::Evolving {
            samples: 8,
            period: 10.0,
        },
        ..default()
    };
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(wind)));
    let world = app.world_mut();
    for i in 0..40u32 {
        let preset = [
            FallPreset::MapleLeaf,
            FallPreset::PaperSheet,
            FallPreset::Samara,
            FallPreset::Coin,
        ][i as usize % 4];
        let object = FallingObject {
            seed: u64::from(i),
            ..preset.object()
        };
        let at = Vec3::new(i as f32 * 0.7 - 14.0, 8.0 + (i % 5) as f32, 0.0);
        world.spawn((object, Transform::from_translation(at)));
    }
    world.spawn(LeafCloud {
        count: 300,
        seed: 9,
        region: CloudRegion {
            min: Vec3::new(-10.0, 2.0, -10.0),
            max: Vec3::new(10.0, 12.0, 10.0),
        },
        ..default()
    });
    world.spawn((small_flag(), Transform::from_xyz(3.0, 4.0, 0.0)));
    world.spawn((physical_flag(), Transform::from_xyz(6.0, 4.0, 0.0)));
    world.spawn((card(), Transform::from_xyz(-3.0, 12.0, 0.0)));
    world.spawn((
        WindSource::fan(8.0, 0.7, 10.0),
        Transform::from_xyz(-12.0, 4.0, 0.0).looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::Y),
    ));
    if let Some(seed) = shuffle_seed {
        shuffle_schedules(&mut app, seed);
    }
    ready(&mut app);
    for _ in 0..STEPS {
        app.update();
    }
    let schedules = app.world().resource::<Schedules>();
    let mut order = Vec::new();
    for (label, schedule) in schedules.iter() {
        if let Ok(systems) = schedule.systems() {
            order.push(format!("{label:?}"));
            order.extend(systems.map(|(_, system)| system.name().to_string()));
        }
    }
    Run {
        hash: hash_state(app.world_mut()),
        order,
    }
}

/// Lets Bevy order every schedule's unordered systems by `seed`.
fn shuffle_schedules(app: &mut App, seed: u64) {
    let mut schedules = app.world_mut().resource_mut::<Schedules>();
    for (_, schedule) in schedules.iter_mut() {
        let settings = ScheduleBuildSettings {
            shuffle_seed: Some(seed),
            ..schedule.get_build_settings()
        };
        schedule.set_build_settings(settings);
    }
}

/// Every fall, leaf, cloth node and body, bit for bit.
fn hash_state(world: &mut World) -> u64 {
    let mut hash = Fnv::default();
    let mut falls: Vec<(Entity, Vec3, Vec3, bool)> = world
        .resource::<FallStore>()
        .falls()
        .map(|(e, p)| (e, p.position(), p.drift(), p.landed()))
        .collect();
    falls.sort_by_key(|f| f.0.index_u32());
    for (_, position, drift, landed) in falls {
        hash_vectors(&mut hash, &[position, drift]);
        hash.byte(u8::from(landed));
    }
    for state in world.query::<&LeafCloudState>().iter(world) {
        for path in state.leaves().into_iter().flat_map(|l| l.paths()) {
            hash_vectors(&mut hash, &[path.position(), path.drift()]);
        }
    }
    for state in world.query::<&ClothState>().iter(world) {
        hash_vectors(&mut hash, state.sim.positions());
    }
    for state in world.query::<&PhysicalClothState>().iter(world) {
        hash_vectors(&mut hash, state.0.positions());
    }
    for transform in world
        .query_filtered::<&Transform, With<AeroBody>>()
        .iter(world)
    {
        let q = transform.rotation;
        hash_vectors(
            &mut hash,
            &[transform.translation, q.xyz(), Vec3::splat(q.w)],
        );
    }
    hash.0
}

#[test]
fn shuffled_schedules_end_on_the_same_bits() {
    let reference = run(None);
    let mut orders = vec![reference.order.clone()];
    for seed in [1, 2, 3, 4] {
        let shuffled = run(Some(seed));
        assert_eq!(
            shuffled.hash, reference.hash,
            "shuffle seed {seed}: the state differs from the unshuffled run's"
        );
        orders.push(shuffled.order);
    }
    // The shuffle moved systems: otherwise the runs above compared one order with itself.
    orders.sort();
    orders.dedup();
    assert!(
        orders.len() >= 3,
        "only {} distinct system orders in 5 runs",
        orders.len()
    );
}

fn hash_vectors(hash: &mut Fnv, vectors: &[Vec3]) {
    for v in vectors {
        hash.vector(*v);
    }
}

/// What a system ordered between the clouds and the particle cloth saw on each fixed step.
#[derive(Resource, Default)]
struct Seen {
    /// The cloud's clock before any domain stepped.
    before: Vec<f64>,
    /// (the cloud's clock, the cloth's nodes) in the user's system.
    between: Vec<(f64, Vec<Vec3>)>,
    /// The cloth's nodes after the last domain stepped.
    after: Vec<Vec<Vec3>>,
}

fn cloud_clock(world: &mut World) -> f64 {
    let mut states = world.query::<&LeafCloudState>();
    states
        .iter(world)
        .next()
        .and_then(|s| s.leaves())
        .map_or(f64::NAN, |l| l.clock())
}

fn cloth_nodes(world: &mut World) -> Vec<Vec3> {
    let mut states = world.query::<&PhysicalClothState>();
    states.single(world).unwrap().0.positions().to_vec()
}

/// A user's system ordered `.after(SimulateSystems::Clouds).before(SimulateSystems::Aero)` runs
/// on every fixed step after the leaves have moved and before the particle cloth does, however
/// the schedule is shuffled.
#[test]
fn a_system_runs_between_the_leaves_and_the_cloth() {
    for shuffle in [None, Some(1), Some(2), Some(3)] {
        let mut app = headless_app_with_meshes();
        app.add_plugins(WindfallPlugins::default())
            .init_resource::<Seen>();
        let world = app.world_mut();
        world.spawn(LeafCloud {
            count: 50,
            ..default()
        });
        world.spawn((physical_flag(), Transform::from_xyz(6.0, 4.0, 0.0)));
        app.add_systems(
            FixedUpdate,
            (
                (|world: &mut World| {
                    let clock = cloud_clock(world);
                    world.resource_mut::<Seen>().before.push(clock);
                })
                .after(WindfallSystems::Wind)
                .before(SimulateSystems::Falls),
                (|world: &mut World| {
                    let seen = (cloud_clock(world), cloth_nodes(world));
                    world.resource_mut::<Seen>().between.push(seen);
                })
                .after(SimulateSystems::Clouds)
                .before(SimulateSystems::Aero),
                (|world: &mut World| {
                    let nodes = cloth_nodes(world);
                    world.resource_mut::<Seen>().after.push(nodes);
                })
                .after(SimulateSystems::Aero),
            ),
        );
        if let Some(seed) = shuffle {
            shuffle_schedules(&mut app, seed);
        }
        ready(&mut app);
        let steps_before = app.world().resource::<Seen>().between.len();
        for _ in 0..20 {
            app.update();
        }
        let dt = app
            .world()
            .resource::<Time<Fixed>>()
            .timestep()
            .as_secs_f64();
        let seen = app.world().resource::<Seen>();
        for (i, (clock, nodes)) in seen.between.iter().enumerate().skip(steps_before + 1) {
            // The leaves have taken this step: the cloud's clock is a step past where it was
            // before the domains stepped.
            let before = seen.before[i];
            assert!(
                (clock - before - dt).abs() < 1e-9,
                "step {i}: the cloud's clock {clock}, {before} before the step"
            );
            // The cloth has not: it is where the last step left it.
            assert!(
                nodes == &seen.after[i - 1],
                "step {i}: the cloth moved first"
            );
            assert!(nodes != &seen.after[i], "step {i}: the cloth did not move");
        }
        assert!(
            seen.between.len() >= steps_before + 20,
            "{}",
            seen.between.len()
        );
    }
}
