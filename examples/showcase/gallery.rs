//! The free-fall paper at a glance: its six primitive motions side by side (Fig. 1 and Fig. 9),
//! each trail coloured by the motion it was drawn in, and its three Fig. 15 objects going
//! through their sequences (coin: steady → fluttering; paper: tumbling → spiral; leaf: steady →
//! tumbling → helix). Still air, so only the synthesis shows. Each object falls again after it
//! lands on the shelf; the shelf's front shows each fall seen from above, as the paper's Fig. 8
//! does.

use bevy::prelude::*;
use bevy_windfall::WindfallSystems;
use bevy_windfall::freefall::FallGizmos;
use bevy_windfall::freefall::{FallPreset, MarkovChain, PrimitiveMotion};
use bevy_windfall::prelude::*;

use super::text::SceneLabel;
use super::{Scene, SceneInfo, place_camera};

/// How far every object falls, m (the Fig. 15 objects from their own heights, shown scaled to
/// this one), onto a shelf this high.
const HEIGHT: f32 = 4.0;
const SHELF: f32 = 1.6;
const SPACING: f32 = 1.3;
const REST: f32 = 1.2;
/// Fixed steps of trail kept (15 s at 60 Hz).
const TRAIL: usize = 900;

pub fn plugin(app: &mut App) {
    app.add_systems(OnEnter(Scene::Gallery), setup)
        .add_systems(
            FixedUpdate,
            record_trails
                .after(WindfallSystems::Simulate)
                .run_if(in_state(Scene::Gallery)),
        )
        .add_systems(
            Update,
            (rest_and_drop, draw_trails, show_info).run_if(in_state(Scene::Gallery)),
        );
}

/// A column of the gallery: where its object is let go (in its column's frame), how the column
/// is placed and scaled, and the trail: world positions with the motion's colour, and the
/// horizontal offsets from the release point in metres of the object's own fall.
#[derive(Component)]
struct Exhibit {
    release: Vec3,
    column: Transform,
    trail: Vec<(Vec3, Vec2, Color)>,
    /// The fall before, drawn faint while the next one starts.
    previous: Vec<(Vec3, Vec2, Color)>,
}

#[derive(Component)]
struct Resting(Timer);

/// A chain that starts in `motion` and stays there.
fn only(motion: PrimitiveMotion) -> MarkovChain {
    let mut initial = [0.0; 6];
    initial[motion.index()] = 1.0;
    let mut transitions = [[0.0; 6]; 6];
    for (i, row) in transitions.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    MarkovChain::new(initial, transitions).expect("a valid chain")
}

fn name(motion: PrimitiveMotion) -> &'static str {
    match motion {
        PrimitiveMotion::SteadyDescent => "steady descent",
        PrimitiveMotion::Fluttering => "fluttering",
        PrimitiveMotion::Chaotic => "chaotic",
        PrimitiveMotion::Tumbling => "tumbling",
        PrimitiveMotion::Helix => "helix",
        PrimitiveMotion::Spiral => "spiral",
    }
}

#[allow(clippy::too_many_arguments)]
fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut camera: Single<&mut Transform, With<Camera3d>>,
    mut wind: ResMut<WindSettings>,
    mut settings: ResMut<FallSettings>,
) {
    let here = DespawnOnExit(Scene::Gallery);
    let middle = 4.6 * SPACING;
    place_camera(
        &mut camera,
        Vec3::new(middle, 4.5, 10.6),
        Vec3::new(middle, 2.7, 0.0),
    );
    // Still air: the paper's §2–3 synthesis alone. Every object falls in its column's frame,
    // whose floor is the shelf.
    wind.reference_speed = 0.0;
    settings.ground_height = 0.0;
    commands.insert_resource(ClearColor(Color::srgb(0.93, 0.93, 0.90)));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 800.0,
        ..default()
    });
    commands.spawn((
        DirectionalLight {
            illuminance: 7_000.0,
            ..default()
        },
        Transform::from_xyz(-3.0, 8.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y),
        here.clone(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(40.0, 20.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.80, 0.80, 0.76))),
        Transform::from_xyz(middle, 0.0, 0.0),
        here.clone(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(12.0 * SPACING, SHELF, 1.6))),
        MeshMaterial3d(materials.add(Color::srgb(0.97, 0.97, 0.95))),
        Transform::from_xyz(middle, SHELF / 2.0, 0.0),
        here.clone(),
    ));
    // A plate that shows which side is up: light on top, dark below.
    let top = materials.add(Color::srgb(0.95, 0.93, 0.85));
    let bottom = materials.add(Color::srgb(0.25, 0.35, 0.55));
    let plate = |commands: &mut Commands, mesh: Handle<Mesh>, entity: Entity| {
        commands.entity(entity).with_children(|c| {
            c.spawn((Mesh3d(mesh.clone()), MeshMaterial3d(top.clone())));
            c.spawn((
                Mesh3d(mesh),
                MeshMaterial3d(bottom.clone()),
                Transform::from_rotation(Quat::from_rotation_z(std::f32::consts::PI)),
            ));
        });
    };
    // The six motions: a 36 × 20 cm card-stock ellipse, forced into each.
    let exhibit = FallingObject {
        shape: Shape::Ellipse {
            major: 0.36,
            minor: 0.20,
            thickness: 3.0e-4,
        },
        density: 500.0,
        ..default()
    };
    let ellipse = meshes.add(ellipse_mesh(0.36, 0.20, Some(FallPreset::Leaf)));
    for (i, motion) in PrimitiveMotion::ALL.into_iter().enumerate() {
        let x = i as f32 * SPACING;
        let release = Vec3::new(0.0, HEIGHT, 0.0);
        let place = Transform::from_xyz(x, SHELF, 0.0);
        let column = commands
            .spawn((place, Visibility::default(), here.clone()))
            .id();
        let object = commands
            .spawn((
                FallingObject {
                    main_motion: Some(motion),
                    markov: Some(only(motion)),
                    seed: i as u64,
                    ..exhibit.clone()
                },
                Exhibit {
                    release,
                    column: place,
                    trail: Vec::new(),
                    previous: Vec::new(),
                },
                Transform::from_translation(release)
                    .with_rotation(Quat::from_rotation_y(0.5 + i as f32)),
                Visibility::default(),
                ChildOf(column),
            ))
            .id();
        plate(&mut commands, ellipse.clone(), object);
        label(
            &mut commands,
            Vec3::new(x, 0.3, 0.8),
            format!("{}\n{}", motion.label(), name(motion)),
            motion.label(),
            FallGizmos::motion_color(motion),
        );
    }
    // The paper's Fig. 15, each object from its own height, shown scaled to the same height.
    let coin_mesh = meshes.add(Cylinder::new(0.01, 0.0015));
    let paper_mesh = meshes.add(ellipse_mesh(0.08, 0.02, Some(FallPreset::PaperSheet)));
    let leaf = meshes.add(FallPreset::Leaf.object().mesh());
    let figures = [
        (
            FallPreset::Coin,
            0.5,
            coin_mesh,
            "(a) coin x8\nsteady,\nfluttering",
        ),
        (
            FallPreset::PaperSheet,
            3.1,
            paper_mesh,
            "(b) paper x1.3\ntumbling,\nspiral",
        ),
        (
            FallPreset::Leaf,
            2.0,
            leaf,
            "(c) leaf x2\nsteady, tumbling,\nhelix",
        ),
    ];
    for (i, (preset, height, mesh, text)) in figures.into_iter().enumerate() {
        let x = (6.6 + 1.2 * i as f32) * SPACING;
        let scale = HEIGHT / height;
        let place = Transform::from_xyz(x, SHELF, 0.0).with_scale(Vec3::splat(scale));
        let column = commands
            .spawn((place, Visibility::default(), here.clone()))
            .id();
        let release = Vec3::new(0.0, height, 0.0);
        let object = commands
            .spawn((
                FallingObject {
                    seed: 100 + i as u64,
                    ..preset.object()
                },
                Exhibit {
                    release,
                    column: place,
                    trail: Vec::new(),
                    previous: Vec::new(),
                },
                Transform::from_translation(release)
                    .with_rotation(Quat::from_rotation_y(1.0 + i as f32)),
                Visibility::default(),
                ChildOf(column),
            ))
            .id();
        plate(&mut commands, mesh, object);
        label(
            &mut commands,
            Vec3::new(x, 0.34, 0.8),
            text.to_string(),
            &text[..3],
            Color::srgb(0.15, 0.15, 0.15),
        );
    }
}

/// A label at `at` in the scene: `full` on a wide window, `short` on a small one.
fn label(commands: &mut Commands, at: Vec3, full: String, short: &str, color: Color) {
    commands.spawn((
        SceneLabel {
            at,
            full,
            short: short.to_string(),
            color,
        },
        DespawnOnExit(Scene::Gallery),
    ));
}

/// An object that lands rests a moment, then falls again from its release point.
fn rest_and_drop(
    mut commands: Commands,
    mut landed: MessageReader<Landed>,
    mut objects: Query<(
        Entity,
        &mut Exhibit,
        &mut Transform,
        &mut FallingObject,
        Option<&mut Resting>,
    )>,
    time: Res<Time>,
) {
    for message in landed.read() {
        if let Ok(mut e) = commands.get_entity(message.entity) {
            e.insert(Resting(Timer::from_seconds(REST, TimerMode::Once)));
        }
    }
    for (entity, mut exhibit, mut transform, mut object, resting) in &mut objects {
        if let Some(mut rest) = resting
            && rest.0.tick(time.delta()).is_finished()
        {
            exhibit.previous = std::mem::take(&mut exhibit.trail);
            transform.translation = exhibit.release;
            object.seed += 1000;
            commands.entity(entity).remove::<Resting>();
        }
    }
}

/// Every fixed step's position, so the trails do not depend on the frame rate.
fn record_trails(mut exhibits: Query<(Entity, &mut Exhibit)>, store: Res<FallStore>) {
    for (entity, mut exhibit) in &mut exhibits {
        let Some(path) = store.fall(entity) else {
            continue;
        };
        if path.landed() {
            continue;
        }
        if exhibit.trail.len() >= 4 * TRAIL {
            exhibit.trail.drain(..3 * TRAIL);
        }
        let world = exhibit.column.transform_point(path.position());
        let offset = path.position() - exhibit.release;
        let color = FallGizmos::motion_color(path.motion());
        exhibit
            .trail
            .push((world, Vec2::new(offset.x, offset.z), color));
    }
}

/// Each trail in 3-D, and on the shelf's front the same fall seen from above (its horizontal
/// path, magnified to fill a square), as the paper's Fig. 8.
fn draw_trails(exhibits: Query<&Exhibit>, mut gizmos: Gizmos) {
    for exhibit in &exhibits {
        let centre = Vec3::new(exhibit.column.translation.x, 0.95, 0.81);
        let half = 0.5;
        gizmos.rect(
            Isometry3d::from_translation(centre),
            Vec2::splat(2.0 * half),
            Color::srgb(0.6, 0.6, 0.6),
        );
        // The last fall faint under the current one, until the current one is longer.
        let fresh = exhibit.trail.len() < exhibit.previous.len() / 2;
        for (trail, alpha) in [(&exhibit.previous, 0.3), (&exhibit.trail, 1.0)] {
            if alpha < 1.0 && !fresh {
                continue;
            }
            let trail = &trail[trail.len().saturating_sub(TRAIL)..];
            let faded = |c: &Color| c.with_alpha(alpha);
            gizmos.linestrip_gradient(trail.iter().map(|(p, _, c)| (*p, faded(c))));
            let extent = trail
                .iter()
                .fold(0.02f32, |m, (_, h, _)| m.max(h.x.abs()).max(h.y.abs()));
            let k = 0.9 * half / extent;
            gizmos.linestrip_gradient(
                trail
                    .iter()
                    .map(|(_, h, c)| (centre + Vec3::new(h.x * k, -h.y * k, 0.0), faded(c))),
            );
        }
    }
}

fn show_info(mut info: ResMut<SceneInfo>) {
    info.0 = "Left: the six primitive motions (36 x 20 cm plates); right: the paper's Fig. 15 \
              objects. Trails are coloured by the motion they were drawn in; plates are light on \
              top, dark below. On the shelf: each fall seen from above (the paper's Fig. 8), \
              magnified to fit."
        .into();
}

/// An ellipse `major` × `minor` m drawn as `look` ([`FallingObject::mesh`]).
fn ellipse_mesh(major: f32, minor: f32, look: Option<FallPreset>) -> Mesh {
    FallingObject {
        shape: Shape::Ellipse {
            major,
            minor,
            thickness: 3e-4,
        },
        look,
        ..default()
    }
    .mesh()
}
