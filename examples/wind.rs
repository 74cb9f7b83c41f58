//! The wind field made visible: tracer particles carried by the wind leave streaks, and a grid
//! of arrows near the ground is coloured by speed as in Fig. 13 of the free-fall paper
//! (red V > 2U, pink U < V ≤ 2U, blue U/2 < V ≤ U, dark V ≤ U/2).
//!
//! Keys: ↑/↓ wind speed, ←/→ turn the wind, E frozen / evolving turbulence, Space pause.
//! `cargo run --example wind --features example_scenes -- [--frames N] [--screenshot PATH]`

mod common;

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindGizmos;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// Tracers fill this box (x, z half-sizes and height), m.
const BOX: Vec3 = Vec3::new(30.0, 16.0, 20.0);
const TRACERS: usize = 1200;
const TRAIL: usize = 30;

fn main() {
    let mut app = common::example_app("bevy_windfall: wind");
    app.add_plugins(WindfallPlugins.set(WindPlugin::new(wind_config(TemporalMode::Frozen))))
        .add_plugins(WindfallDebugPlugin)
        .insert_gizmo_config(
            WindGizmos {
                half_extent: Vec2::new(BOX.x - 1.0, BOX.z - 1.0),
                spacing: 2.5,
                height: 1.5,
                ..default()
            },
            GizmoConfig::default(),
        )
        .insert_resource(ClearColor(Color::srgb(0.55, 0.7, 0.85)))
        .insert_resource(TracerRng(Pcg64::seed_from_u64(7)))
        .add_systems(Startup, setup)
        .add_systems(FixedUpdate, move_tracers.in_set(WindfallSystems::Simulate))
        .add_systems(Update, (draw_trails, controls, show_info))
        .run();
}

fn wind_config(temporal: TemporalMode) -> WindConfig {
    WindConfig {
        reference_speed: 6.0,
        grid: [96, 96],
        cell_size: 1.5,
        temporal,
        seed: 3,
        ..default()
    }
}

#[derive(Component)]
struct Tracer {
    trail: VecDeque<Vec3>,
}

#[derive(Resource)]
struct TracerRng(Pcg64);

#[derive(Component)]
struct InfoText;

fn random_point(rng: &mut Pcg64, upwind_only: Option<Vec3>) -> Vec3 {
    let mut p = Vec3::new(
        rng.random_range(-BOX.x..BOX.x),
        rng.random_range(0.3..BOX.y),
        rng.random_range(-BOX.z..BOX.z),
    );
    if let Some(dir) = upwind_only {
        // Re-enter on the upwind faces.
        if dir.x.abs() > dir.z.abs() {
            p.x = -BOX.x * dir.x.signum();
        } else {
            p.z = -BOX.z * dir.z.signum();
        }
    }
    p
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut rng: ResMut<TracerRng>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-8.0, 26.0, 52.0).looking_at(Vec3::new(2.0, 4.0, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(10.0, 30.0, 20.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(2.0 * BOX.x, 2.0 * BOX.z))),
        MeshMaterial3d(materials.add(Color::srgb(0.35, 0.5, 0.3))),
    ));
    // A 10 m mast marks the reference height.
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.15, 10.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.9, 0.9, 0.9))),
        Transform::from_xyz(-BOX.x + 2.0, 5.0, -BOX.z + 2.0),
    ));
    let dot = meshes.add(Sphere::new(0.12).mesh().ico(1).unwrap());
    let white = materials.add(StandardMaterial {
        base_color: Color::WHITE,
        emissive: LinearRgba::rgb(0.6, 0.6, 0.6),
        ..default()
    });
    for _ in 0..TRACERS {
        let p = random_point(&mut rng.0, None);
        commands.spawn((
            Tracer {
                trail: VecDeque::from([p]),
            },
            Mesh3d(dot.clone()),
            MeshMaterial3d(white.clone()),
            Transform::from_translation(p),
        ));
    }
    commands.spawn((InfoText, common::info_text()));
}

/// Tracers move with the wind: a forward-Euler step of dx/dt = V(x, t), on the fixed timestep.
fn move_tracers(
    time: Res<Time<Fixed>>,
    wind: Res<WindField>,
    mut rng: ResMut<TracerRng>,
    mut tracers: Query<(&mut Tracer, &mut Transform)>,
) {
    let dt = time.delta_secs();
    let dir = wind.direction();
    for (mut tracer, mut transform) in &mut tracers {
        let mut p = transform.translation + wind.velocity(transform.translation) * dt;
        // Reflect off a layer just above the ground, where the log-law wind dies out.
        if p.y < 0.6 {
            p.y = 1.2 - p.y;
        }
        let outside = p.x.abs() > BOX.x || p.z.abs() > BOX.z || p.y > BOX.y * 1.5;
        if outside {
            p = random_point(&mut rng.0, Some(dir));
            tracer.trail.clear();
        }
        tracer.trail.push_front(p);
        tracer.trail.truncate(TRAIL);
        transform.translation = p;
    }
}

fn draw_trails(wind: Res<WindField>, tracers: Query<&Tracer>, mut gizmos: Gizmos) {
    for tracer in &tracers {
        let Some(&head) = tracer.trail.front() else {
            continue;
        };
        let color =
            WindGizmos::speed_class_color(wind.velocity(head).length(), wind.mean_speed_at(head.y));
        gizmos.linestrip(tracer.trail.iter().copied(), color);
    }
}

/// The keys edit [`WindSettings`]: speed and direction apply on the next fixed step, the
/// temporal mode (E) by a background rebuild while the old field keeps blowing.
fn controls(
    keys: Res<ButtonInput<KeyCode>>,
    mut settings: ResMut<WindSettings>,
    mut wind: ResMut<WindField>,
) {
    if keys.just_pressed(KeyCode::ArrowUp) {
        settings.reference_speed += 1.0;
    }
    if keys.just_pressed(KeyCode::ArrowDown) {
        settings.reference_speed = (settings.reference_speed - 1.0).max(0.0);
    }
    for (key, angle) in [(KeyCode::ArrowLeft, 0.3f32), (KeyCode::ArrowRight, -0.3)] {
        if keys.just_pressed(key) {
            settings.direction = Vec2::from_angle(angle).rotate(settings.direction);
        }
    }
    if keys.just_pressed(KeyCode::KeyE) {
        settings.temporal = match settings.temporal {
            TemporalMode::Frozen => TemporalMode::Evolving {
                samples: 32,
                period: 60.0,
            },
            TemporalMode::Evolving { .. } => TemporalMode::Frozen,
        };
    }
    if keys.just_pressed(KeyCode::Space) {
        wind.paused = !wind.paused;
    }
}

fn show_info(wind: Res<WindField>, mut text: Single<&mut Text, With<InfoText>>) {
    let c = wind.config();
    let sigma = wind.sigma();
    let mode = match c.temporal {
        TemporalMode::Frozen => "frozen",
        TemporalMode::Evolving { .. } => "evolving",
    };
    text.0 = format!(
        "U(10 m) = {:.1} m/s   U(2 m) = {:.1} m/s   u* = {:.2} m/s   z0 = {} m\n\
         sigma u, v, w = {:.2}, {:.2}, {:.2} m/s   beta = {:.2}   {mode}{}\n\
         Up/Down: speed   Left/Right: direction   E: frozen/evolving   Space: pause",
        wind.mean_speed_at(c.reference_height),
        wind.mean_speed_at(2.0),
        wind.friction_velocity(),
        c.roughness,
        sigma.x,
        sigma.y,
        sigma.z,
        c.beta,
        if wind.paused { "   (paused)" } else { "" },
    );
}
