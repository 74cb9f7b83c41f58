//! A flag on a pole, flapping in travelling waves: the cloth paper's P-type Fourier-descriptor
//! yarns, shaped by 1/f^β noise that travels with the wind (Table 1's flag row, evolving wind).
//! The flag streams downwind, turns with the wind, and hangs in calm air.
//!
//! Spawned with nothing but a `Cloth` and a `Transform`: `WindfallPlugins` gives it a mesh and
//! a red fabric. (Changing the wind as the game runs: the `wind_settings` example.)
//!
//! `cargo run --example flag`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

fn main() {
    let wind = WindConfig {
        reference_speed: 5.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(wind)))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-2.5, 5.0, 6.0).looking_at(Vec3::new(1.0, 4.6, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(-3.0, 8.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(30.0, 30.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
    // A 6 m pole; the flag's pole edge runs down from its top.
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.05, 6.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.75, 0.76, 0.78))),
        Transform::from_xyz(0.0, 3.0, 0.0),
    ));
    commands.spawn((
        Cloth {
            grid: ClothGrid {
                rows: 28,
                columns: 42,
                width: 2.1,
                height: 1.4,
            },
            ..ClothPreset::FlagFlappingEvolving.cloth()
        },
        Transform::from_xyz(0.05, 5.95, 0.0),
    ));
}
