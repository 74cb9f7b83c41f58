//! Avian rigid bodies in the wind: light boards of three sizes dropped into a 6 m/s wind tumble
//! and glide as per-face lift and drag (the lift-and-drag paper's eq. 3.1 on every triangle)
//! push them, then rest on the ground under avian's contacts. Each board is an ordinary avian3d
//! body plus `AvianAero::default()`, which takes its faces from the board's own `Mesh3d`.
//!
//! `cargo run --example avian_body --features avian`

mod common;

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy_windfall::aero::AvianAero;
use bevy_windfall::prelude::*;

fn main() {
    let wind = WindConfig {
        reference_speed: 6.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        // With the `avian` feature, the group adds `AvianAeroPlugin` in avian's schedule.
        .add_plugins((
            PhysicsPlugins::default(),
            WindfallPlugins::default().set(WindPlugin::new(wind)),
        ))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(Update, drop_boards)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-1.0, 3.0, 9.0).looking_at(Vec3::new(1.5, 2.2, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 10.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        RigidBody::Static,
        Collider::half_space(Vec3::Y),
        Mesh3d(meshes.add(Plane3d::default().mesh().size(60.0, 60.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
}

/// Every 0.8 s, drops a board (60 × 40, 40 × 30 or 30 × 20 cm, 1 cm thick, 3 kg/m²) from 6 m,
/// turned a little; boards beyond 30 are removed, oldest first.
fn drop_boards(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    time: Res<Time>,
    mut next: Local<f32>,
    mut dropped: Local<usize>,
    mut boards: Local<Vec<Entity>>,
) {
    if time.elapsed_secs() < *next {
        return;
    }
    *next = time.elapsed_secs() + 0.8;
    *dropped += 1;
    let k = *dropped as f32;
    let (size, color) = [
        (Vec2::new(0.6, 0.4), Color::srgb(0.85, 0.55, 0.20)),
        (Vec2::new(0.4, 0.3), Color::srgb(0.20, 0.45, 0.80)),
        (Vec2::new(0.3, 0.2), Color::srgb(0.85, 0.20, 0.25)),
    ][*dropped % 3];
    // The faces come from this one-sided plane (the law is two-sided); the material shows
    // both sides.
    let mesh = meshes.add(Plane3d::default().mesh().size(size.x, size.y));
    let board = commands.spawn((
        RigidBody::Dynamic,
        Collider::cuboid(size.x, 0.01, size.y),
        Mass(3.0 * size.x * size.y),
        AvianAero::default(),
        Mesh3d(mesh),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: color,
            double_sided: true,
            cull_mode: None,
            ..default()
        })),
        Transform::from_xyz(-3.0, 6.0, (k * 0.618).fract() * 3.0 - 1.5)
            .with_rotation(Quat::from_euler(EulerRot::XYZ, 0.3 * k.sin(), k, 0.2)),
    ));
    boards.push(board.id());
    if boards.len() > 30 {
        let oldest = boards.remove(0);
        commands.entity(oldest).despawn();
    }
}
