//! The inspector: a drop-in egui panel (feature `egui`) that tunes the wind (speed, direction,
//! turbulence, frozen or evolving, a rebuild in the background once a control is let go), the
//! falling objects and cloths (a change lets them go again or rebuilds them) and the local wind
//! sources. Here a flag, a row of named falling objects and a fan to tune.
//!
//! `cargo run --example inspector --features egui`

mod common;

use bevy::prelude::*;
use bevy_windfall::inspector::WindfallInspectorPlugin;
use bevy_windfall::prelude::*;

fn main() {
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins((WindfallPlugins::default(), WindfallInspectorPlugin))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(Update, drop_again)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-1.0, 2.4, 7.5).looking_at(Vec3::new(-1.0, 1.8, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(-2.0, 8.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(30.0, 30.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.04, 4.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.75, 0.76, 0.78))),
        Transform::from_xyz(-3.0, 2.0, -1.0),
    ));
    // Named entities come first in the panel.
    commands.spawn((
        Name::new("flag"),
        ClothPreset::FlagFlappingEvolving.cloth(),
        Transform::from_xyz(-2.95, 4.0, -1.0),
    ));
    for (k, preset) in [
        FallPreset::MapleLeaf,
        FallPreset::OakLeaf,
        FallPreset::PlayingCard,
        FallPreset::PaperSheet,
    ]
    .into_iter()
    .enumerate()
    {
        commands.spawn((
            Name::new(format!("{preset:?}")),
            preset.object(),
            Transform::from_xyz(-2.5 + 0.4 * k as f32, 4.5, 1.0),
        ));
    }
    commands.spawn((
        Name::new("fan"),
        WindSource::fan(8.0, 0.5, 6.0),
        Transform::from_xyz(-4.0, 1.0, 1.0).looking_to(Vec3::X, Vec3::Y),
    ));
}

/// Lets each object go again from 4.5 m upwind of the camera, a second after it lands (the wind
/// carries them across the view).
fn drop_again(
    time: Res<Time>,
    mut landed: MessageReader<Landed>,
    mut waiting: Local<Vec<(Entity, f32)>>,
    mut objects: Query<(&mut FallingObject, &mut Transform)>,
) {
    let now = time.elapsed_secs();
    waiting.extend(landed.read().map(|l| (l.entity, now + 1.0)));
    waiting.retain(|&(entity, due)| {
        if now < due {
            return true;
        }
        if let Ok((mut object, mut transform)) = objects.get_mut(entity) {
            transform.translation = Vec3::new(-2.5, 4.5, 1.0);
            object.seed += 1;
        }
        false
    });
}
