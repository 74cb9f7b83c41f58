//! A physical flag beside a procedural one, in the same wind. On the left a `Cloth`: the cloth
//! paper's Fourier-descriptor yarns, whose waves are drawn from the wind's spectrum. On the
//! right a `PhysicalCloth`: a particle cloth (XPBD) of 0.15 kg/m² pushed by per-face lift and
//! drag (the lift-and-drag paper's eq. 3.1) and gravity. Both are spawned with nothing but
//! their component and a `Transform`; `WindfallPlugins` draws the procedural one red and the
//! physical one blue. Keys: ↑/↓ wind speed.
//!
//! `cargo run --example physical_flag`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

/// Both flags: 1.5 × 1 m, 16 × 24 nodes, on poles 5 m tall.
const GRID: ClothGrid = ClothGrid {
    rows: 16,
    columns: 24,
    width: 1.5,
    height: 1.0,
};
const POLE: f32 = 5.0;

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
        .add_systems(Update, wind_speed)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.5, 4.6, 7.5).looking_at(Vec3::new(0.5, 4.3, 0.0), Vec3::Y),
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
    let pole = meshes.add(Cylinder::new(0.04, POLE));
    let metal = materials.add(Color::srgb(0.75, 0.76, 0.78));
    for x in [-1.5, 1.5] {
        commands.spawn((
            Mesh3d(pole.clone()),
            MeshMaterial3d(metal.clone()),
            Transform::from_xyz(x, POLE / 2.0, 0.0),
        ));
    }
    // Left: procedural. Right: physical.
    commands.spawn((
        Cloth {
            grid: GRID,
            ..ClothPreset::FlagFlappingEvolving.cloth()
        },
        Transform::from_xyz(-1.45, POLE, 0.0),
    ));
    commands.spawn((
        PhysicalCloth {
            grid: GRID,
            ..default()
        },
        Transform::from_xyz(1.55, POLE, 0.0),
    ));
    commands.spawn(Text::new(""));
}

/// ↑/↓ change the mean wind by 1 m/s (in [`WindSettings`], applied at the next fixed step); the
/// text shows the wind that blows.
fn wind_speed(
    keys: Res<ButtonInput<KeyCode>>,
    mut settings: ResMut<WindSettings>,
    wind: Res<WindField>,
    mut text: Single<&mut Text>,
) {
    if keys.just_pressed(KeyCode::ArrowUp) {
        settings.reference_speed += 1.0;
    } else if keys.just_pressed(KeyCode::ArrowDown) {
        settings.reference_speed = (settings.reference_speed - 1.0).max(0.0);
    }
    let speed = wind.config().reference_speed;
    text.0 =
        format!("wind {speed:.1} m/s (Up/Down)\nleft: procedural Cloth   right: PhysicalCloth");
}
