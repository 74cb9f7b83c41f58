//! No hidden ordering between the crate's systems: Bevy 0.20 can shuffle the order of systems
//! that no constraint orders (`ScheduleBuildSettings::shuffle_seed`). Falling objects, a leaf
//! cloud, a procedural flag, a particle cloth and a rigid plate, in a gusty wind with a fan, are
//! stepped with every schedule of the app shuffled by several seeds; every run ends on the same
//! bits as the unshuffled one.

use bevy::ecs::schedule::ScheduleBuildSettings;
use bevy::prelude::*;
use bevy_windfall::aero::{PhysicalCloth, PhysicalClothState, Pinning};
use bevy_windfall::freefall::cloud::LeafCloudState;
use bevy_windfall::freefall::{FallPreset, LeafCloud};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindSource;

use crate::common::{headless_app_with_meshes, ready};

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
    app.add_plugins(WindfallPlugins.set(WindPlugin::new(wind)));
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
    world.spawn((
        Cloth {
            grid: ClothGrid {
                rows: 8,
                columns: 12,
                ..default()
            },
            params: ClothPreset::FlagFlappingFrozen.params(),
            ..default()
        },
        Transform::from_xyz(3.0, 4.0, 0.0),
    ));
    world.spawn((
        PhysicalCloth {
            grid: ClothGrid {
                rows: 6,
                columns: 9,
                width: 1.2,
                height: 0.8,
            },
            pinning: Pinning::PoleColumn,
            ..default()
        },
        Transform::from_xyz(6.0, 4.0, 0.0),
    ));
    let plate =
        RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 3).unwrap();
    world.spawn((AeroBody::new(plate), Transform::from_xyz(-3.0, 12.0, 0.0)));
    world.spawn((
        WindSource::fan(8.0, 0.7, 10.0),
        Transform::from_xyz(-12.0, 4.0, 0.0).looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::Y),
    ));
    if let Some(seed) = shuffle_seed {
        let mut schedules = app.world_mut().resource_mut::<Schedules>();
        for (_, schedule) in schedules.iter_mut() {
            let settings = ScheduleBuildSettings {
                shuffle_seed: Some(seed),
                ..schedule.get_build_settings()
            };
            schedule.set_build_settings(settings);
        }
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
        hash.vectors(&[position, drift]);
        hash.byte(u8::from(landed));
    }
    for state in world.query::<&LeafCloudState>().iter(world) {
        for path in state.leaves().into_iter().flat_map(|l| l.paths()) {
            hash.vectors(&[path.position(), path.drift()]);
        }
    }
    for state in world.query::<&ClothState>().iter(world) {
        hash.vectors(state.sim.positions());
    }
    for state in world.query::<&PhysicalClothState>().iter(world) {
        hash.vectors(state.0.positions());
    }
    for transform in world
        .query_filtered::<&Transform, With<AeroBody>>()
        .iter(world)
    {
        let q = transform.rotation;
        hash.vectors(&[transform.translation, q.xyz(), Vec3::splat(q.w)]);
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

/// FNV-1a, 64 bits.
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn byte(&mut self, b: u8) {
        self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
    }

    fn vectors(&mut self, vectors: &[Vec3]) {
        for v in vectors {
            for c in v.to_array() {
                c.to_bits()
                    .to_le_bytes()
                    .into_iter()
                    .for_each(|b| self.byte(b));
            }
        }
    }
}
