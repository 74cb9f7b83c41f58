//! Falling leaves: maple, oak and birch leaves let go from a bough, each falling in the motions
//! the free-fall paper gives its preset (steady, fluttering, chaotic, tumbling, a helix),
//! carried by a light breeze, and resting where they land.
//!
//! A leaf is nothing but `FallPreset::….object()` and a `Transform`: `WindfallPlugins` draws it
//! with its preset's outline and colours, lit on both sides.
//!
//! `cargo run --example falling_leaves`

mod common;

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

/// Leaves on the ground and in the air at most; the oldest go first.
const MAX_LEAVES: usize = 400;
/// Seconds between two leaves.
const EVERY: f32 = 0.12;

fn main() {
    let breeze = WindConfig {
        reference_speed: 1.5,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(breeze)))
        .add_plugins(common::ScreenshotPlugin)
        .add_systems(Startup, setup)
        .add_systems(Update, let_leaves_go)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.6, 1.4, 2.5).looking_at(Vec3::new(0.5, 1.1, -0.3), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 8_000.0,
            ..default()
        },
        Transform::from_xyz(2.0, 6.0, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)));
    // A lawn, and the bough the leaves come from.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(12.0, 12.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.05, 3.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.30, 0.20, 0.12))),
        Transform::from_xyz(0.0, 2.6, -0.3).with_rotation(Quat::from_rotation_z(1.45)),
    ));
}

/// Lets a leaf go every [`EVERY`] seconds from a random point under the bough, turned at
/// random, and removes the oldest beyond [`MAX_LEAVES`].
fn let_leaves_go(
    mut commands: Commands,
    time: Res<Time>,
    mut next: Local<f32>,
    mut count: Local<u64>,
    mut leaves: Local<VecDeque<Entity>>,
) {
    if time.elapsed_secs() < *next {
        return;
    }
    *next = time.elapsed_secs() + EVERY;
    *count += 1;
    // A low-discrepancy sequence spreads the leaves evenly along the bough.
    let u = (*count as f32 * 0.618_034).fract();
    let v = (*count as f32 * 0.754_878).fract();
    let preset = [
        FallPreset::MapleLeaf,
        FallPreset::OakLeaf,
        FallPreset::BirchLeaf,
    ][*count as usize % 3];
    let leaf = commands.spawn((
        FallingObject {
            seed: *count,
            ..preset.object()
        },
        Transform::from_xyz(2.6 * (u - 0.5), 2.5, 0.6 * (v - 0.5) - 0.3)
            .with_rotation(Quat::from_euler(EulerRot::YXZ, 6.3 * v, 0.8 * u, 0.0)),
    ));
    leaves.push_back(leaf.id());
    while leaves.len() > MAX_LEAVES {
        let oldest = leaves.pop_front().expect("more than MAX_LEAVES");
        commands.entity(oldest).despawn();
    }
}
