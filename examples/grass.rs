//! Grass that sways on the GPU in the very wind that carries the leaves: 60 000 blades in one
//! mesh (one draw call), bent vertex by vertex by a `WindSwayMaterial`, whose vertex shader
//! samples the `WindField` that `WindfallPlugins` uploads each frame (the WESL module
//! `bevy_windfall::wind`). Gusts cross the meadow as waves of bending grass.
//!
//! `cargo run --example grass`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::render::{SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial};

/// Blades, and the tallest blade, m.
const BLADES: u32 = 60_000;
const TALLEST: f32 = 0.42;

fn main() {
    let wind = WindConfig {
        reference_speed: 6.0,
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
    mut sway: ResMut<Assets<WindSwayMaterial>>,
    wind: Res<WindGpuBuffers>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 1.6, 7.0).looking_at(Vec3::new(0.0, 0.2, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 8.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(40.0, 40.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.30, 0.42, 0.20))),
    ));
    // The blades' material: a standard one, bent by the wind (grass rooted at y = 0).
    let material = sway.add(WindSwayMaterial {
        base: StandardMaterial {
            perceptual_roughness: 0.85,
            double_sided: true,
            cull_mode: None,
            ..default()
        },
        extension: WindSway::new(&wind, SwaySettings::grass(TALLEST)),
    });
    commands.spawn((
        Mesh3d(meshes.add(common::blades(
            BLADES,
            TALLEST,
            Vec2::new(-8.0, -8.0),
            Vec2::new(8.0, 5.0),
        ))),
        MeshMaterial3d(material),
    ));
}
