//! Procedural beside physical, in the same wind: on the left a P-descriptor flag (`Cloth`) and
//! procedural leaves (`FallingObject`); on the right a particle flag (`PhysicalCloth`) and rigid
//! plates with lift and drag (`AeroBody`).
//!
//! `cargo run --example aero --features example_scenes -- [--frames N] [--screenshot PATH]`

mod common;

use std::f32::consts::{FRAC_PI_2, TAU};

use bevy::prelude::*;
use bevy_windfall::aero::{AeroState, PhysicalCloth, Pinning, PlateState};
use bevy_windfall::freefall::FallRng;
use bevy_windfall::prelude::*;

const LEAVES: usize = 120;
/// Leaves are released in these boxes (centre x, height), left procedural, right physical.
const LEFT: f32 = -3.0;
const RIGHT: f32 = 3.0;
const RELEASE_HEIGHT: f32 = 6.0;

fn main() {
    let mut app = common::example_app("bevy_windfall: procedural and physical");
    app.add_plugins(WindfallPlugins.set(WindPlugin::new(WindConfig {
        reference_speed: 4.0,
        grid: [64, 64],
        temporal: TemporalMode::Evolving {
            samples: 16,
            period: 16.0,
        },
        seed: 11,
        ..default()
    })))
    .insert_resource(FreeFallSettings {
        ground_height: 0.005,
    })
    .insert_resource(ClearColor(Color::srgb(0.62, 0.74, 0.86)))
    .insert_resource(Spawner(FallRng::new(4)))
    .add_systems(Startup, setup)
    .add_systems(Update, (respawn_procedural, respawn_physical, labels))
    .run();
}

#[derive(Resource)]
struct Spawner(FallRng);

impl Spawner {
    fn point(&mut self, centre_x: f32) -> Vec3 {
        let r = &mut self.0;
        Vec3::new(
            centre_x + 2.0 * (r.uniform() - 0.5),
            RELEASE_HEIGHT + r.uniform(),
            -1.0 + 2.0 * (r.uniform() - 0.5),
        )
    }
}

#[derive(Component)]
struct Label;

fn leaf_mesh(meshes: &mut Assets<Mesh>) -> Handle<Mesh> {
    // 7.3 × 4.2 cm in the local XZ plane, normal +Y, long axis along Z.
    meshes
        .add(Mesh::from(Ellipse::new(0.021, 0.0365)).rotated_by(Quat::from_rotation_x(-FRAC_PI_2)))
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut spawner: ResMut<Spawner>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 3.4, 10.5).looking_at(Vec3::new(0.0, 3.0, 0.0), Vec3::Y),
    ));
    common::meadow(
        &mut commands,
        &mut meshes,
        &mut materials,
        Vec3::new(-4.0, 9.0, 7.0),
        60.0,
    );
    let pole = materials.add(Color::srgb(0.3, 0.3, 0.32));
    let cloth_material = common::two_sided;
    let grid = ClothGrid {
        rows: 16,
        columns: 24,
        width: 1.5,
        height: 1.0,
    };
    // Left: the procedural flag.
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.04, 5.0))),
        MeshMaterial3d(pole.clone()),
        Transform::from_xyz(LEFT - 1.0, 2.5, -1.5),
    ));
    commands.spawn((
        Cloth {
            grid,
            params: ClothPreset::FlagFlappingFrozen.params(),
            ..default()
        },
        MeshMaterial3d(cloth_material(&mut materials, Color::srgb(0.8, 0.15, 0.15))),
        Transform::from_xyz(LEFT - 1.0, 5.0, -1.5),
    ));
    // Right: the particle flag.
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.04, 5.0))),
        MeshMaterial3d(pole),
        Transform::from_xyz(RIGHT - 1.0, 2.5, -1.5),
    ));
    commands.spawn((
        PhysicalCloth {
            grid,
            areal_density: 0.15,
            pinning: Pinning::PoleColumn,
            ..default()
        },
        MeshMaterial3d(cloth_material(&mut materials, Color::srgb(0.15, 0.3, 0.8))),
        Transform::from_xyz(RIGHT - 1.0, 5.0, -1.5),
    ));
    // Leaves: procedural on the left, rigid plates on the right, same size and density.
    let leaf = leaf_mesh(&mut meshes);
    let orange = cloth_material(&mut materials, Color::srgb(0.9, 0.45, 0.1));
    let yellow = cloth_material(&mut materials, Color::srgb(0.95, 0.8, 0.2));
    let plate = RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2)
        .expect("a valid plate");
    for i in 0..LEAVES {
        commands.spawn((
            FallingObject {
                seed: i as u64,
                ..default()
            },
            Mesh3d(leaf.clone()),
            MeshMaterial3d(orange.clone()),
            Transform::from_translation(spawner.point(LEFT)),
        ));
        let start = spawner.point(RIGHT);
        let tilt = spawner.0.uniform() * TAU;
        commands.spawn((
            AeroBody::new(plate.clone()),
            AeroState::new(PlateState {
                position: start,
                rotation: Quat::from_rotation_z(0.4 * tilt.sin()) * Quat::from_rotation_y(tilt),
                ..default()
            }),
            Mesh3d(leaf.clone()),
            MeshMaterial3d(yellow.clone()),
            Transform::from_translation(start),
        ));
    }
    commands.spawn((Label, common::info_text()));
}

fn respawn_procedural(
    mut landed: MessageReader<Landed>,
    mut objects: Query<(&mut Transform, &mut FallingObject)>,
    mut spawner: ResMut<Spawner>,
) {
    for message in landed.read() {
        if let Ok((mut transform, mut object)) = objects.get_mut(message.entity) {
            transform.translation = spawner.point(LEFT);
            object.seed += LEAVES as u64;
        }
    }
}

/// Rigid plates have no ground: put those that fell through it back up.
fn respawn_physical(mut bodies: Query<&mut AeroState>, mut spawner: ResMut<Spawner>) {
    for mut state in &mut bodies {
        if state.state.position.y < 0.0 {
            let tilt = spawner.0.uniform() * TAU;
            *state = AeroState::new(PlateState {
                position: spawner.point(RIGHT),
                rotation: Quat::from_rotation_z(0.4 * tilt.sin()) * Quat::from_rotation_y(tilt),
                ..default()
            });
        }
    }
}

fn labels(wind: Res<WindField>, mut text: Query<&mut Text, With<Label>>) {
    if let Ok(mut t) = text.single_mut() {
        t.0 = format!(
            "wind {:.1} m/s at 10 m\n\
             left: procedural (P-descriptor flag, FallingObject leaves)\n\
             right: physical (particle flag with lift and drag, rigid-plate leaves)",
            wind.config().reference_speed
        );
    }
}
