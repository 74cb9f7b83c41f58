//! A leaf cloud with levels of detail: 30 000 maple leaves in one `LeafCloud` entity (one array,
//! stepped in parallel, drawn in one draw call), recycled from the top once they have rested.
//! With `LodFocus` on the camera, leaves beyond `lod.near` are stepped every 2nd fixed step and
//! beyond `lod.far` every 4th, and still move smoothly every frame. The camera circles the
//! cloud; the text counts how many leaves each step advanced.
//!
//! `cargo run --example leaf_cloud`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

fn main() {
    let wind = WindConfig {
        reference_speed: 3.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(wind)))
        .add_plugins(common::ScreenshotPlugin)
        .add_systems(Startup, setup)
        .add_systems(Update, (circle_the_cloud, show_detail))
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    // The camera is the focus of the levels of detail.
    commands.spawn((Camera3d::default(), LodFocus, Transform::default()));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 10.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(80.0, 80.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
    commands.spawn(LeafCloud {
        object: FallPreset::MapleLeaf.object(),
        count: 30_000,
        region: CloudRegion {
            min: Vec3::new(-15.0, 1.0, -15.0),
            max: Vec3::new(15.0, 9.0, 15.0),
        },
        lod: LodTiers {
            near: 8.0,
            far: 18.0,
        },
        recycle_after: Some(2.0),
        ..default()
    });
    commands.spawn(Text::new(""));
}

/// Circles the cloud once a minute, 30 m out and 3 m up.
fn circle_the_cloud(time: Res<Time>, mut camera: Single<&mut Transform, With<Camera3d>>) {
    let angle = 0.1 * time.elapsed_secs();
    let at = Vec3::new(30.0 * angle.cos(), 3.0, 30.0 * angle.sin());
    **camera = Transform::from_translation(at).looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::Y);
}

/// How many leaves the last fixed step advanced: with levels of detail, far fewer than all.
fn show_detail(clouds: Query<&LeafCloudState>, mut text: Single<&mut Text>) {
    for state in &clouds {
        let total = state.leaves().map_or(0, |l| l.len());
        let step = state.last_step();
        text.0 = format!(
            "{total} leaves, {} stepped in the last fixed step",
            step.advanced
        );
    }
}
