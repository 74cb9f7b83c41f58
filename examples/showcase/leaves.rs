//! Autumn leaves fall from a tree into gusty wind, land, rest and fall again. Most are
//! procedural [`FallingObject`]s (phase diagram, Markov chain, trajectory database); a few
//! yellow-green ones are physical [`AeroBody`] plates with per-face lift and drag.

use std::f32::consts::{FRAC_PI_2, TAU};

use bevy::prelude::*;
use bevy_windfall::aero::{AeroState, PlateState};
use bevy_windfall::freefall::{FallRng, PrimitiveMotion};
use bevy_windfall::prelude::*;

use super::{Featured, Scene, SceneInfo, common, place_camera};

const LEAVES: usize = 400;
const PHYSICAL_LEAVES: usize = 40;
/// Centre and radius of the canopy leaves fall from, m.
const CANOPY: Vec3 = Vec3::new(0.0, 5.5, 0.0);
const CANOPY_RADIUS: f32 = 2.2;
/// Seconds a leaf rests on the ground before it is released again.
const REST: f32 = 1.5;

pub fn plugin(app: &mut App) {
    app.insert_resource(Spawner(FallRng::new(99)))
        .add_systems(OnEnter(Scene::Leaves), setup)
        .add_systems(
            Update,
            (rest_and_release, respawn_physical, show_info).run_if(in_state(Scene::Leaves)),
        );
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

    /// A physical leaf at rest at a canopy point, turned at random.
    fn physical_start(&mut self) -> AeroState {
        let tilt = self.0.uniform() * TAU;
        AeroState::new(PlateState {
            position: self.canopy_point(),
            rotation: Quat::from_rotation_z(0.4 * tilt.sin()) * Quat::from_rotation_y(tilt),
            ..default()
        })
    }
}

/// A leaf on the ground, waiting to fall again.
#[derive(Component)]
struct Resting(Timer);

#[allow(clippy::too_many_arguments)]
fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut spawner: ResMut<Spawner>,
    mut camera: Single<&mut Transform, With<Camera3d>>,
    mut wind: ResMut<WindField>,
    mut settings: ResMut<FreeFallSettings>,
) {
    let here = DespawnOnExit(Scene::Leaves);
    place_camera(
        &mut camera,
        Vec3::new(-4.0, 3.0, 14.0),
        Vec3::new(1.5, 3.4, 0.0),
    );
    let _ = wind.set_reference_speed(2.5);
    // Just above the grass plane, so resting leaves do not flicker into it.
    settings.ground_height = 0.005;
    commands.insert_resource(ClearColor(Color::srgb(0.62, 0.74, 0.86)));
    let sun = Vec3::new(-5.0, 10.0, 6.0);
    for entity in common::meadow(&mut commands, &mut meshes, &mut materials, sun, 80.0) {
        commands.entity(entity).insert(here.clone());
    }
    // The tree: a trunk and a few overlapping crowns, open underneath.
    let bark = materials.add(Color::srgb(0.33, 0.22, 0.14));
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.22, 5.0))),
        MeshMaterial3d(bark),
        Transform::from_xyz(CANOPY.x, 2.5, CANOPY.z),
        here.clone(),
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
            here.clone(),
        ));
    }
    let colours = [
        Color::srgb(0.85, 0.33, 0.08),
        Color::srgb(0.93, 0.62, 0.10),
        Color::srgb(0.70, 0.15, 0.08),
        Color::srgb(0.55, 0.45, 0.10),
    ]
    .map(|c| common::two_sided(&mut materials, c));
    // Procedural leaves: ellipses 6-10 cm long in the local XZ plane, long axis along Z (the
    // axis a leaf tumbles about). The first one is the panel's featured leaf.
    for i in 0..LEAVES {
        let rng = &mut spawner.0;
        let major = 0.06 + 0.04 * rng.uniform();
        let minor = major * (0.5 + 0.2 * rng.uniform());
        let mesh = Mesh::from(Ellipse::new(minor / 2.0, major / 2.0))
            .rotated_by(Quat::from_rotation_x(-FRAC_PI_2));
        let mut leaf = commands.spawn((
            FallingObject {
                shape: Shape::Ellipse {
                    major,
                    minor,
                    thickness: 3.0e-4,
                },
                density: 350.0 + 300.0 * rng.uniform(),
                seed: i as u64,
                ..default()
            },
            Mesh3d(meshes.add(mesh)),
            MeshMaterial3d(colours[i % colours.len()].clone()),
            Transform::from_translation(spawner.canopy_point()),
            here.clone(),
        ));
        if i == 0 {
            leaf.insert(Featured);
        }
    }
    // Physical leaves: rigid 7.3 × 4.2 cm plates, each face with lift and drag.
    let plate = RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2)
        .expect("a valid plate");
    let mesh = meshes.add(Plane3d::new(Vec3::Y, Vec2::new(0.0365, 0.021)));
    let green = common::two_sided(&mut materials, Color::srgb(0.62, 0.7, 0.15));
    for _ in 0..PHYSICAL_LEAVES {
        let start = spawner.physical_start();
        commands.spawn((
            AeroBody::new(plate.clone()),
            Transform::from_translation(start.state.position),
            start,
            Mesh3d(mesh.clone()),
            MeshMaterial3d(green.clone()),
            here.clone(),
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
        if let Ok(mut e) = commands.get_entity(message.entity) {
            e.insert(Resting(Timer::from_seconds(REST, TimerMode::Once)));
        }
    }
    for (entity, mut rest, mut transform, mut object) in &mut resting {
        if rest.0.tick(time.delta()).is_finished() {
            transform.translation = spawner.canopy_point();
            object.seed += LEAVES as u64;
            commands.entity(entity).remove::<Resting>();
        }
    }
}

/// A physical leaf on the ground (it has no contact) starts again in the canopy.
fn respawn_physical(mut bodies: Query<&mut AeroState>, mut spawner: ResMut<Spawner>) {
    for mut state in &mut bodies {
        if state.state.position.y < 0.0 {
            *state = spawner.physical_start();
        }
    }
}

fn show_info(
    falls: Query<&FallState>,
    featured: Single<&FallState, With<Featured>>,
    mut info: ResMut<SceneInfo>,
) {
    let mut counts = [0usize; 6];
    let mut grounded = 0;
    for state in &falls {
        if state.landed() {
            grounded += 1;
        } else if let Some(m) = state.motion() {
            counts[m.index()] += 1;
        }
    }
    let mut line =
        format!("{LEAVES} procedural leaves (orange), {PHYSICAL_LEAVES} physical plates (green)\n");
    if let Some(r) = featured.regime() {
        line += &format!(
            "featured leaf: Re = {:.2e}, I* = {:.2}, U = {:.2} m/s, main motion {:?}\n",
            r.reynolds, r.inertia, r.descent_speed, r.main
        );
    }
    for m in PrimitiveMotion::ALL {
        if counts[m.index()] > 0 {
            line += &format!("{} {:?}: {}   ", m.label(), m, counts[m.index()]);
        }
    }
    line += &format!("on the ground: {grounded}");
    info.0 = line;
}
