//! The free-fall paper's coin (Fig. 15a): an aluminium coin, 2 cm across and 1.5 mm thick,
//! dropped from 50 cm in a tank of still water. `FallPreset::Coin` falls in water
//! (`Fluid::WATER`): steady at first, then fluttering from side to side, as the phase diagram
//! says for its Reynolds number and I*. Its path is traced; it is dropped again a second after
//! it lands.
//!
//! `cargo run --example coin_in_water`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

/// Inside of the tank (x, height, z), m; its floor is at y = 0.
const TANK: Vec3 = Vec3::new(0.36, 0.62, 0.22);
/// Where the coin is let go.
const RELEASE: Vec3 = Vec3::new(0.0, 0.5, 0.0);

fn main() {
    App::new()
        .add_plugins(DefaultPlugins)
        // Still water: no wind.
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(WindConfig {
            reference_speed: 0.0,
            ..default()
        })))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.93, 0.93, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(Update, (drop_again, trace))
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.05, 0.40, 0.70).looking_at(Vec3::new(0.0, 0.25, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 8_000.0,
            ..default()
        },
        Transform::from_xyz(0.6, 1.5, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // The table, and the water as a pale blue, see-through block.
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(1.2, 0.02, 0.8))),
        MeshMaterial3d(materials.add(Color::srgb(0.45, 0.32, 0.22))),
        Transform::from_xyz(0.0, -0.01, 0.0),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(TANK.x, 0.9 * TANK.y, TANK.z))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgba(0.55, 0.75, 0.90, 0.25),
            alpha_mode: AlphaMode::Blend,
            ..default()
        })),
        Transform::from_xyz(0.0, 0.45 * TANK.y, 0.0),
    ));
    // The coin lies flat, as it is held before the drop; it rests on the floor (its half
    // thickness up).
    commands.insert_resource(FallSettings {
        ground_height: 0.00075,
    });
    commands.spawn((
        FallPreset::Coin.object(),
        Transform::from_translation(RELEASE),
    ));
}

/// A second after the coin lands, lets it go again (a new seed: a new fall).
fn drop_again(
    mut landed: MessageReader<Landed>,
    mut coins: Query<(&mut FallingObject, &mut Transform)>,
    time: Res<Time>,
    mut due: Local<Option<f32>>,
) {
    for _ in landed.read() {
        *due = Some(time.elapsed_secs() + 1.0);
    }
    if due.is_some_and(|t| time.elapsed_secs() >= t) {
        *due = None;
        for (mut coin, mut transform) in &mut coins {
            *transform = Transform::from_translation(RELEASE);
            coin.seed += 1;
        }
    }
}

/// Traces the coin's path with gizmos (cleared at each drop).
fn trace(
    coins: Query<&Transform, With<FallingObject>>,
    mut path: Local<Vec<Vec3>>,
    mut gizmos: Gizmos,
) {
    for transform in &coins {
        let at = transform.translation;
        if path.last().is_some_and(|last| last.y < at.y - 0.01) {
            path.clear();
        }
        path.push(at);
    }
    gizmos.linestrip(path.iter().copied(), Color::srgb(0.8, 0.2, 0.1));
}
