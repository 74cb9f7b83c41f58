//! A curtain on a rod: in an open window of a wall across the wind, it billows into the room and
//! flutters (the cloth paper's curtain row of Table 1, `ClothAttachment::Rod`). (A fan blowing
//! in through a window is a local `WindSource`: see the `wind_sources` example.)
//!
//! `cargo run --example curtain`

mod common;

use std::f32::consts::FRAC_PI_2;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

/// The window's sill and lintel, m; it is 2 m wide, centred on z = 0.
const SILL: f32 = 0.9;
const LINTEL: f32 = 2.8;

fn main() {
    let breeze = WindConfig {
        reference_speed: 6.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(breeze)))
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
    // Inside the room (+X, downwind), looking back at the window.
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(4.5, 2.0, 2.5).looking_at(Vec3::new(0.0, 1.8, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 7_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 6.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(20.0, 20.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.55, 0.45, 0.35))),
    ));
    // The wall (the plane x = 0) around the window: below, above, and either side.
    let wall = materials.add(Color::srgb(0.86, 0.82, 0.74));
    for (size, centre) in [
        (Vec3::new(0.2, SILL, 6.0), Vec3::new(0.0, SILL / 2.0, 0.0)),
        (
            Vec3::new(0.2, 4.0 - LINTEL, 6.0),
            Vec3::new(0.0, (LINTEL + 4.0) / 2.0, 0.0),
        ),
        (
            Vec3::new(0.2, LINTEL - SILL, 2.0),
            Vec3::new(0.0, (LINTEL + SILL) / 2.0, -2.0),
        ),
        (
            Vec3::new(0.2, LINTEL - SILL, 2.0),
            Vec3::new(0.0, (LINTEL + SILL) / 2.0, 2.0),
        ),
    ] {
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::from_size(size))),
            MeshMaterial3d(wall.clone()),
            Transform::from_translation(centre),
        ));
    }
    // The rod, and the curtain hanging from it: the rod runs along the cloth's local +X (world
    // −Z), the cloth billows along its local +Z (world +X), into the room.
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(0.05, 0.05, 2.6))),
        MeshMaterial3d(materials.add(Color::srgb(0.3, 0.3, 0.32))),
        Transform::from_xyz(0.25, LINTEL + 0.08, 0.0),
    ));
    commands.spawn((
        Cloth {
            grid: ClothGrid {
                rows: 30,
                columns: 36,
                width: 1.85,
                height: 1.95,
            },
            ..ClothPreset::CurtainFlutteringEvolving.cloth()
        },
        Transform::from_xyz(0.25, LINTEL + 0.05, 0.92)
            .with_rotation(Quat::from_rotation_y(FRAC_PI_2)),
    ));
}
