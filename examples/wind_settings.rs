//! Setting the wind as the game runs: `WindSettings` is the one place an app sets its wind, and
//! `WindField` is what blows, for systems to read. The mean wind (speed, direction) applies at
//! the next fixed step; the turbulence (here β, the spectrum's slope) is rebuilt in the
//! background and lands a fixed number of steps later. A windsock of leaves shows it: a column
//! of falling leaves drifts with the wind.
//!
//! Keys: ↑/↓ speed, ←/→ direction, T smoother or rougher turbulence (β 5/3 or 3).
//!
//! `cargo run --example wind_settings`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;

fn main() {
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(WindConfig {
            reference_speed: 3.0,
            ..default()
        })))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(Update, (steer_the_wind, show_the_wind))
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 4.0, 14.0).looking_at(Vec3::new(2.0, 3.0, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(-3.0, 8.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(60.0, 60.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.50, 0.26))),
    ));
    // Leaves let go from a small box 6 m up, again and again: where they drift shows the wind.
    commands.spawn(LeafCloud {
        count: 600,
        region: CloudRegion {
            min: Vec3::new(-4.5, 6.0, -0.5),
            max: Vec3::new(-3.5, 7.0, 0.5),
        },
        recycle_after: Some(0.5),
        ..default()
    });
    commands.spawn(Text::new(""));
}

/// The arrow keys and T edit the settings; the plugin takes them in.
fn steer_the_wind(keys: Res<ButtonInput<KeyCode>>, mut wind: ResMut<WindSettings>) {
    if keys.just_pressed(KeyCode::ArrowUp) {
        wind.reference_speed += 1.0;
    } else if keys.just_pressed(KeyCode::ArrowDown) {
        wind.reference_speed = (wind.reference_speed - 1.0).max(0.0);
    } else if keys.just_pressed(KeyCode::ArrowLeft) {
        wind.direction = Vec2::from_angle(15f32.to_radians()).rotate(wind.direction);
    } else if keys.just_pressed(KeyCode::ArrowRight) {
        wind.direction = Vec2::from_angle(-15f32.to_radians()).rotate(wind.direction);
    } else if keys.just_pressed(KeyCode::KeyT) {
        wind.beta = if wind.beta < 2.0 { 3.0 } else { 5.0 / 3.0 };
    }
}

/// What blows (the field), and a rebuild in flight.
fn show_the_wind(
    wind: Res<WindField>,
    rebuild: Option<Res<bevy_windfall::wind::WindRebuild>>,
    mut text: Single<&mut Text>,
) {
    let c = wind.config();
    let building = rebuild.map_or(String::new(), |r| {
        format!(
            "   rebuilding: beta {:.2} in {} steps",
            r.config().beta,
            r.steps_left()
        )
    });
    text.0 = format!(
        "wind {:.0} m/s toward ({:.2}, {:.2}), beta {:.2}{building}\n\
         Up/Down speed   Left/Right direction   T turbulence",
        c.reference_speed, c.direction.x, c.direction.y, c.beta
    );
}
