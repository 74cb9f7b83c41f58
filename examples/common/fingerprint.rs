//! A fingerprint of falls: 1 000 falling objects of every preset and a cloud of 2 000 leaves,
//! 600 fixed steps in a gusty wind with a fan and a cart (a `WindMover`) driving through them,
//! then a physical flag (a `ParticleCloth`) flown for 5 s in that wind, hashed (every fall's position, drift, motion and
//! whether it landed, bit for bit). The crate's arithmetic is portable and its lanes and threads
//! change no bit, so the same hash comes out natively and in the browser, with the lanes or
//! without, on any number of threads: the showcase's tour prints it (CI compares the browser's
//! with the desktop's), and `tests/it/determinism.rs` runs it on 1, 2 and 4 threads.

use bevy::app::{App, TaskPoolOptions, TaskPoolPlugin};
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::prelude::*;

/// Fixed steps the fingerprint runs.
pub const STEPS: u32 = 600;

/// The hash of [`STEPS`] steps of the falls, on `threads` compute threads (`None`: Bevy's
/// default; the first app of a process sets the pools' size for the process).
pub fn fingerprint(threads: Option<usize>) -> u64 {
    let mut app = App::new();
    let pools = TaskPoolPlugin {
        task_pool_options: threads
            .map_or_else(TaskPoolOptions::default, TaskPoolOptions::with_num_threads),
    };
    let wind = WindConfig {
        reference_speed: 6.0,
        grid: [48, 48],
        seed: 11,
        temporal: TemporalMode::Evolving {
            samples: 8,
            period: 10.0,
        },
        ..default()
    };
    app.add_plugins((
        MinimalPlugins.set(pools),
        TransformPlugin,
        WindfallPlugins::default().set(WindPlugin::new(wind)),
    ))
    .insert_resource(Time::<Fixed>::from_hz(60.0))
    .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    let presets = [
        FallPreset::MapleLeaf,
        FallPreset::OakLeaf,
        FallPreset::BirchLeaf,
        FallPreset::PaperSheet,
        FallPreset::PlayingCard,
        FallPreset::Samara,
        FallPreset::Coin,
    ];
    for i in 0..1000u32 {
        let object = FallingObject {
            seed: u64::from(i),
            ..presets[i as usize % presets.len()].object()
        };
        let at = Vec3::new(
            (i % 40) as f32 * 1.5 - 30.0,
            6.0 + (i / 40) as f32 * 0.7,
            0.0,
        );
        app.world_mut()
            .spawn((object, Transform::from_translation(at)));
    }
    app.world_mut().spawn(LeafCloud {
        count: 2000,
        seed: 5,
        region: CloudRegion {
            min: Vec3::new(-20.0, 3.0, -20.0),
            max: Vec3::new(20.0, 25.0, 20.0),
        },
        recycle_after: Some(1.0),
        ..default()
    });
    app.world_mut().spawn((
        WindSource::fan(12.0, 0.7, 14.0),
        Transform::from_xyz(-25.0, 4.0, 0.0).looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::Y),
    ));
    app.world_mut().spawn((
        Cart,
        WindMover {
            radius: 0.6,
            ..default()
        },
        Transform::from_xyz(-30.0, 0.7, 0.5),
    ));
    app.add_systems(FixedUpdate, drive.before(WindfallSystems::Wind));
    for _ in 0..=STEPS {
        app.update();
    }
    let mut hash = Fnv::default();
    let world = app.world_mut();
    let mut falls: Vec<(Entity, Vec3, Vec3, u8, bool)> = world
        .resource::<FallStore>()
        .falls()
        .map(|(e, p)| {
            (
                e,
                p.position(),
                p.drift(),
                p.motion().index() as u8,
                p.landed(),
            )
        })
        .collect();
    falls.sort_by_key(|f| f.0.index_u32());
    for (_, position, drift, motion, landed) in falls {
        hash.vector(position);
        hash.vector(drift);
        hash.byte(motion);
        hash.byte(u8::from(landed));
    }
    for state in world.query::<&LeafCloudState>().iter(world) {
        for path in state.leaves().into_iter().flat_map(|l| l.paths()) {
            hash.vector(path.position());
            hash.vector(path.drift());
        }
    }
    for p in physical_flag(world.resource::<WindField>()) {
        hash.vector(p);
    }
    hash.0
}

/// A physical flag (a `ParticleCloth` of 12 × 18 nodes, 1.2 × 0.8 m of 0.15 kg/m², on a pole
/// 6 m up) flown for 5 s at 60 steps a second in the fingerprint's wind, from the field's clock
/// on: its nodes' positions.
fn physical_flag(wind: &WindField) -> Vec<Vec3> {
    use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning};
    let grid = ClothGrid {
        rows: 12,
        columns: 18,
        width: 1.2,
        height: 0.8,
    };
    let mut flag = ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
        .expect("a valid flag");
    let (pole, start, dt) = (Vec3::new(-5.0, 6.0, 5.0), wind.time(), 1.0 / 60.0);
    for i in 0..300 {
        let t = start + i as f32 * dt;
        flag.step(dt, Vec3::new(0.0, -9.81, 0.0), &|p| {
            wind.velocity_at(pole + p, t)
        });
    }
    flag.positions().to_vec()
}

/// The fingerprint's cart.
#[derive(Component)]
struct Cart;

/// Drives the cart along +X at 7 m/s through the falls, back to the start (a teleport) at the
/// far side.
fn drive(time: Res<Time>, mut carts: Query<&mut Transform, With<Cart>>) {
    for mut t in &mut carts {
        t.translation.x += 7.0 * time.delta_secs();
        if t.translation.x > 30.0 {
            t.translation.x = -30.0;
        }
    }
}

/// FNV-1a, 64 bits: a hash the same on every platform (`std`'s are not promised to be).
pub struct Fnv(pub u64);

impl Default for Fnv {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    /// Hashes one byte.
    pub fn byte(&mut self, b: u8) {
        self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
    }

    /// Hashes a vector's bits (every NaN alike).
    pub fn vector(&mut self, v: Vec3) {
        for c in v.to_array() {
            // NaN's payload is not portable: every NaN hashes alike.
            let bits = if c.is_nan() {
                f32::NAN.to_bits()
            } else {
                c.to_bits()
            };
            bits.to_le_bytes().into_iter().for_each(|b| self.byte(b));
        }
    }
}
