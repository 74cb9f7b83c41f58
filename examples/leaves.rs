//! Autumn leaves: 600 leaves fall from a tree into gusty wind, land, rest and fall again.
//!
//! Each leaf is a [`FallingObject`] with its own size, density and seed; the phase diagram and
//! the Markov chain pick its motions (steady, fluttering, chaotic, tumbling for leaves in air).
//!
//! Keys: Up/Down wind speed, Left/Right turn the wind.
//! `cargo run --example leaves --features example_scenes -- [--frames N] [--screenshot PATH]`

mod common;

use std::f32::consts::{FRAC_PI_2, TAU};

use bevy::prelude::*;
use bevy_windfall::freefall::{FallRng, PrimitiveMotion};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindGizmos;

const LEAVES: usize = 600;
/// Centre and radius of the canopy leaves fall from, m.
const CANOPY: Vec3 = Vec3::new(0.0, 5.5, 0.0);
const CANOPY_RADIUS: f32 = 2.2;
/// Seconds a leaf rests on the ground before it is released again.
const REST: f32 = 1.5;

fn main() {
    let mut app = common::example_app("bevy_windfall: leaves");
    app.add_plugins(WindfallPlugins.set(WindPlugin::new(WindConfig {
        reference_speed: 2.5,
        grid: [96, 96],
        cell_size: 1.0,
        temporal: TemporalMode::Evolving {
            samples: 16,
            period: 20.0,
        },
        seed: 5,
        ..default()
    })))
    // Just above the grass plane, so resting leaves do not flicker into it.
    .insert_resource(FreeFallSettings {
        ground_height: 0.005,
    })
    .insert_resource(WindGizmos {
        enabled: false,
        ..default()
    })
    .insert_resource(ClearColor(Color::srgb(0.62, 0.74, 0.86)))
    .insert_resource(Spawner(FallRng::new(99)))
    .add_systems(Startup, setup)
    .add_systems(Update, (rest_and_release, controls, show_info))
    .run();
}

#[derive(Resource)]
struct Spawner(FallRng);

impl Spawner {
    /// A point in the lower half of the canopy.
    fn canopy_point(&mut self) -> Vec3 {
        let r = &mut self.0;
        let angle = r.uniform() * TAU;
        let radius = CANOPY_RADIUS * r.uniform().sqrt();
        let height = CANOPY.y - 0.8 + 1.4 * r.uniform();
        Vec3::new(
            CANOPY.x + radius * angle.cos(),
            height,
            CANOPY.z + radius * angle.sin(),
        )
    }
}

/// A leaf on the ground, waiting to fall again.
#[derive(Component)]
struct Resting(Timer);

#[derive(Component)]
struct InfoText;

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut spawner: ResMut<Spawner>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-4.0, 3.0, 14.0).looking_at(Vec3::new(1.5, 3.4, 0.0), Vec3::Y),
    ));
    common::meadow(
        &mut commands,
        &mut meshes,
        &mut materials,
        Vec3::new(-5.0, 10.0, 6.0),
        80.0,
    );
    // The tree: a trunk and a few overlapping crowns, open underneath so leaves can be seen
    // leaving it.
    let bark = materials.add(Color::srgb(0.33, 0.22, 0.14));
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.22, 5.0))),
        MeshMaterial3d(bark),
        Transform::from_xyz(CANOPY.x, 2.5, CANOPY.z),
    ));
    let crown = materials.add(StandardMaterial {
        base_color: Color::srgb(0.72, 0.42, 0.12),
        perceptual_roughness: 0.9,
        ..default()
    });
    for (offset, radius) in [
        (Vec3::new(0.0, 1.4, 0.0), 1.8),
        (Vec3::new(1.2, 0.9, 0.4), 1.3),
        (Vec3::new(-1.1, 1.0, -0.3), 1.3),
        (Vec3::new(0.2, 0.8, -1.2), 1.2),
    ] {
        commands.spawn((
            Mesh3d(meshes.add(Sphere::new(radius))),
            MeshMaterial3d(crown.clone()),
            Transform::from_translation(CANOPY + offset),
        ));
    }
    // Leaves: ellipses 6-10 cm long, double-sided, in five autumn colours.
    let colours = [
        Color::srgb(0.85, 0.33, 0.08),
        Color::srgb(0.93, 0.62, 0.10),
        Color::srgb(0.70, 0.15, 0.08),
        Color::srgb(0.55, 0.45, 0.10),
        Color::srgb(0.95, 0.78, 0.25),
    ]
    .map(|c| common::two_sided(&mut materials, c));
    commands.spawn((InfoText, common::info_text()));
    for i in 0..LEAVES {
        let rng = &mut spawner.0;
        let major = 0.06 + 0.04 * rng.uniform();
        let minor = major * (0.5 + 0.2 * rng.uniform());
        let shape = Shape::Ellipse {
            major,
            minor,
            thickness: 3.0e-4,
        };
        // The mesh lies in the local XZ plane, normal +Y, long axis along Z (the axis a leaf
        // tumbles about).
        let mesh = Mesh::from(Ellipse::new(minor / 2.0, major / 2.0))
            .rotated_by(Quat::from_rotation_x(-FRAC_PI_2));
        let density = 350.0 + 300.0 * rng.uniform();
        let position = spawner.canopy_point();
        commands.spawn((
            FallingObject {
                shape,
                density,
                seed: i as u64,
                ..default()
            },
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(colours[i % colours.len()].clone()),
            Transform::from_translation(position),
        ));
    }
}

/// A leaf that lands rests a moment, then falls again from a new point in the canopy.
fn rest_and_release(
    mut commands: Commands,
    mut landed: MessageReader<Landed>,
    mut resting: Query<(Entity, &mut Resting, &mut Transform, &mut FallingObject)>,
    mut spawner: ResMut<Spawner>,
    time: Res<Time>,
) {
    for message in landed.read() {
        commands
            .entity(message.entity)
            .insert(Resting(Timer::from_seconds(REST, TimerMode::Once)));
    }
    for (entity, mut rest, mut transform, mut object) in &mut resting {
        if rest.0.tick(time.delta()).is_finished() {
            transform.translation = spawner.canopy_point();
            object.seed += LEAVES as u64;
            commands.entity(entity).remove::<Resting>();
        }
    }
}

fn controls(keys: Res<ButtonInput<KeyCode>>, mut wind: ResMut<WindField>, time: Res<Time>) {
    let speed = wind.config().reference_speed;
    let step = 3.0 * time.delta_secs();
    if keys.pressed(KeyCode::ArrowUp) {
        let _ = wind.set_reference_speed((speed + step).min(30.0));
    }
    if keys.pressed(KeyCode::ArrowDown) {
        let _ = wind.set_reference_speed((speed - step).max(0.0));
    }
    let turn = if keys.pressed(KeyCode::ArrowLeft) {
        time.delta_secs()
    } else if keys.pressed(KeyCode::ArrowRight) {
        -time.delta_secs()
    } else {
        0.0
    };
    if turn != 0.0 {
        let d = wind.config().direction;
        let _ = wind.set_direction(Vec2::from_angle(turn).rotate(d));
    }
}

fn show_info(
    falls: Query<&FallState>,
    wind: Res<WindField>,
    mut text: Query<&mut Text, With<InfoText>>,
) {
    let mut counts = [0usize; 6];
    let mut grounded = 0;
    let mut example = None;
    for state in &falls {
        if state.landed() {
            grounded += 1;
        } else if let Some(m) = state.motion() {
            counts[m.index()] += 1;
        }
        example = example.or(state.regime().copied());
    }
    let mut line = format!(
        "{LEAVES} leaves   wind {:.1} m/s at 10 m (keys Up/Down, Left/Right)\n",
        wind.config().reference_speed
    );
    if let Some(r) = example {
        line += &format!(
            "a leaf: Re = {:.2e}, I* = {:.2}, U = {:.2} m/s: main motion {:?}\n",
            r.reynolds, r.inertia, r.descent_speed, r.main
        );
    }
    for m in PrimitiveMotion::ALL {
        if counts[m.index()] > 0 {
            line += &format!("{} {:?}: {}   ", m.label(), m, counts[m.index()]);
        }
    }
    line += &format!("on the ground: {grounded}");
    if let Ok(mut t) = text.single_mut() {
        t.0 = line;
    }
}
