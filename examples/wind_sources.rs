//! Local wind: `WindSource` components add to the wind field where they are, and everything in
//! the crate feels them. Maple leaves fill a courtyard in a light breeze; a fan blows a jet
//! across it, a dust devil (a vortex with an updraft) whirls leaves up, and keys set off a blast
//! (B) at the centre and a gust front (G) that sweeps across. Sources are ordinary entities:
//! move, turn or despawn them as any other.
//!
//! `cargo run --example wind_sources`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

fn main() {
    let breeze = WindConfig {
        reference_speed: 1.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(breeze)))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(Update, (blast_and_gust, turn_the_fan))
        .run();
}

#[derive(Component)]
struct Fan;

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 3.5, 12.0).looking_at(Vec3::new(0.0, 2.0, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 10.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(30.0, 30.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.34, 0.33, 0.31))),
    ));
    // Leaves to show the wind, let go again from the top 3 s after they land.
    commands.spawn(LeafCloud {
        object: FallPreset::MapleLeaf.object(),
        count: 10_000,
        region: CloudRegion {
            min: Vec3::new(-9.0, 0.5, -5.0),
            max: Vec3::new(9.0, 6.0, 5.0),
        },
        recycle_after: Some(3.0),
        ..default()
    });
    // A fan on a post at the left, blowing along its forward (−Z of its transform): 8 m/s on
    // the axis, a cone of 0.35 rad, reaching 14 m.
    let housing = (
        Mesh3d(meshes.add(Cylinder::new(0.4, 0.2))),
        MeshMaterial3d(materials.add(Color::srgb(0.2, 0.22, 0.25))),
        // The cylinder's axis (local Y) turned onto the fan's forward.
        Transform::from_rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
    );
    commands.spawn((
        Fan,
        WindSource::fan(14.0, 0.35, 8.0),
        Transform::from_xyz(-9.0, 1.5, 0.0).looking_to(Vec3::X, Vec3::Y),
        Visibility::default(),
        children![housing],
    ));
    // A dust devil at the right: a vortex of radius 4 m, 7 m/s at its core, lifting 3 m/s.
    commands.spawn((
        WindSource::vortex(4.0, 7.0).with_updraft(3.0),
        Transform::from_xyz(5.0, 1.0, -1.0),
    ));
    commands.spawn(Text::new(
        "B: blast at the centre   G: gust front from the right",
    ));
}

/// B: a blast at the centre (24 m/s at its front, which runs outward at 12 m/s for 8 m).
/// G: a gust front from the right, 6 m/s stronger than the wind, 3 m thick and 20 m across.
fn blast_and_gust(mut commands: Commands, keys: Res<ButtonInput<KeyCode>>) {
    if keys.just_pressed(KeyCode::KeyB) {
        commands.spawn((
            WindSource::blast(24.0, 12.0, 8.0),
            Transform::from_xyz(0.0, 0.5, 0.0),
        ));
    }
    if keys.just_pressed(KeyCode::KeyG) {
        commands.spawn((
            WindSource::gust(6.0, 5.0, 3.0, 20.0),
            Transform::from_xyz(10.0, 1.0, 0.0).looking_to(Vec3::NEG_X, Vec3::Y),
        ));
    }
}

/// The fan sweeps slowly from side to side, like an oscillating fan.
fn turn_the_fan(time: Res<Time>, mut fan: Single<&mut Transform, With<Fan>>) {
    let sweep = 0.5 * (0.4 * time.elapsed_secs()).sin();
    fan.rotation = Quat::from_rotation_y(sweep) * Quat::from_rotation_arc(Vec3::NEG_Z, Vec3::X);
}
