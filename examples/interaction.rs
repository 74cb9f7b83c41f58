//! Wind you can touch: a runner (a capsule with a `WindMover`) runs along a path of fallen maple
//! leaves through a meadow of GPU grass, past two flags, in a light breeze. The air it pushes (potential
//! flow round it, the ground as a mirror, a wake behind) is part of the `WindField`, so the grass
//! parts round it, the leaves on its path are kicked up and whirl in its wake, and the flags
//! stir as it passes; none of them knows about the runner.
//!
//! Keys: WASD or arrows walk, Shift runs, B sets off a blast where the runner stands (its
//! stamp). Left alone for two seconds it runs up and down the path by itself, stamping once a
//! lap.
//!
//! `cargo run --ignore-rust-version --example interaction`

mod common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::render::{SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial};

/// The runner's speeds, m/s: a walk and a run.
const WALK: f32 = 2.0;
const RUN: f32 = 7.0;
/// The runner's body, as the air sees it: a sphere of this radius at this height.
const BODY_RADIUS: f32 = 0.45;
const BODY_HEIGHT: f32 = 0.55;
/// Grass blades and the tallest, m.
const BLADES: u32 = 80_000;
const TALLEST: f32 = 0.35;
/// Half the width of the mown path the leaves lie on, m.
const PATH_HALF: f32 = 1.3;

fn main() {
    let wind = WindConfig {
        reference_speed: 2.5,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins::default().set(WindPlugin::new(wind)))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .add_systems(FixedUpdate, steer.before(WindfallSystems::Wind))
        .add_systems(Update, (blast, follow))
        .run();
}

/// The runner: how long since a key was last pressed (the autopilot takes over after two
/// seconds) and how far along its way up and down the path it is.
#[derive(Component, Default)]
struct Runner {
    idle: f32,
    lap: f32,
    /// Metres run on the autopilot since its last stamp, less 12.5.
    travelled: f32,
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut sway: ResMut<Assets<WindSwayMaterial>>,
    wind: Res<WindGpuBuffers>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 3.2, 7.5).looking_at(Vec3::new(0.0, 0.3, 0.0), Vec3::Y),
    ));
    common::meadow(
        &mut commands,
        &mut meshes,
        &mut materials,
        Vec3::new(4.0, 9.0, 6.0),
        60.0,
    );
    // A mown path along x, PATH m wide, between two strips of grass.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(30.0, 2.0 * PATH_HALF))),
        MeshMaterial3d(materials.add(Color::srgb(0.47, 0.40, 0.27))),
        Transform::from_xyz(0.0, 0.003, 0.0),
    ));
    let material = sway.add(WindSwayMaterial {
        base: StandardMaterial {
            perceptual_roughness: 0.85,
            double_sided: true,
            cull_mode: None,
            ..default()
        },
        extension: WindSway::new(&wind, SwaySettings::grass(TALLEST)),
    });
    for (near, far) in [(PATH_HALF, 6.0), (-8.0, -PATH_HALF)] {
        commands.spawn((
            Mesh3d(meshes.add(common::blades(
                BLADES / 2,
                TALLEST,
                Vec2::new(-12.0, near.min(far)),
                Vec2::new(12.0, near.max(far)),
            ))),
            MeshMaterial3d(material.clone()),
        ));
    }
    // A carpet of maple leaves on the path: let go just above it, down within a second.
    commands.spawn(LeafCloud {
        object: FallPreset::MapleLeaf.object(),
        count: 3_000,
        seed: 4,
        region: CloudRegion {
            min: Vec3::new(-11.0, 0.1, -PATH_HALF),
            max: Vec3::new(11.0, 0.8, PATH_HALF),
        },
        ..default()
    });
    // Two flags by the path, low enough for the runner's air to reach: a procedural one and a
    // physical one.
    let grid = ClothGrid {
        rows: 12,
        columns: 18,
        width: 1.2,
        height: 0.8,
    };
    let pole_height = 2.2;
    let pole = meshes.add(Cylinder::new(0.03, pole_height));
    let metal = materials.add(Color::srgb(0.75, 0.76, 0.78));
    for x in [-4.0, 3.0] {
        commands.spawn((
            Mesh3d(pole.clone()),
            MeshMaterial3d(metal.clone()),
            Transform::from_xyz(x, pole_height / 2.0, -PATH_HALF - 0.4),
        ));
    }
    commands.spawn((
        Cloth {
            grid,
            ..ClothPreset::FlagFlappingEvolving.cloth()
        },
        Transform::from_xyz(-3.97, pole_height, -PATH_HALF - 0.4),
    ));
    commands.spawn((
        PhysicalCloth { grid, ..default() },
        Transform::from_xyz(3.03, pole_height, -PATH_HALF - 0.4),
    ));
    // The runner: the air sees a sphere at its middle; the capsule is drawn over it.
    let body = commands
        .spawn((
            Runner::default(),
            WindMover {
                radius: BODY_RADIUS,
                ..default()
            },
            Transform::from_xyz(-10.0, BODY_HEIGHT, 0.0),
            Visibility::default(),
        ))
        .id();
    commands.spawn((
        Mesh3d(meshes.add(Capsule3d::new(0.3, 0.9))),
        MeshMaterial3d(materials.add(Color::srgb(0.85, 0.35, 0.20))),
        Transform::from_xyz(0.0, 0.2, 0.0),
        ChildOf(body),
    ));
    commands.spawn((
        Text::new("WASD/arrows walk, Shift runs, B: blast"),
        Node {
            position_type: PositionType::Absolute,
            top: Val::Px(8.0),
            left: Val::Px(8.0),
            ..default()
        },
    ));
}

/// Moves the runner each fixed step: by the keys, or (two seconds after the last key, and
/// from two seconds in) up and down the path at a run, stamping once a lap.
fn steer(
    keys: Res<ButtonInput<KeyCode>>,
    time: Res<Time>,
    mut runner: Single<(&mut Runner, &mut Transform)>,
    mut commands: Commands,
) {
    let (runner, transform) = &mut *runner;
    let dt = time.delta_secs();
    let pressed = |codes: [KeyCode; 2]| codes.iter().any(|k| keys.pressed(*k));
    let mut direction = Vec3::ZERO;
    for (codes, along) in [
        ([KeyCode::KeyW, KeyCode::ArrowUp], Vec3::NEG_Z),
        ([KeyCode::KeyS, KeyCode::ArrowDown], Vec3::Z),
        ([KeyCode::KeyA, KeyCode::ArrowLeft], Vec3::NEG_X),
        ([KeyCode::KeyD, KeyCode::ArrowRight], Vec3::X),
    ] {
        if pressed(codes) {
            direction += along;
        }
    }
    if direction != Vec3::ZERO {
        runner.idle = 0.0;
        let speed = if pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]) {
            RUN
        } else {
            WALK
        };
        transform.translation += direction.normalize() * speed * dt;
        transform.translation = transform.translation.clamp(
            Vec3::new(-12.0, BODY_HEIGHT, -8.0),
            Vec3::new(12.0, BODY_HEIGHT, 6.0),
        );
        return;
    }
    runner.idle += dt;
    if runner.idle < 2.0 {
        return;
    }
    // Up and down the path at a run, weaving a little: 20 m each way.
    let at = |s: f32| Vec3::new(-10.0 * s.cos(), BODY_HEIGHT, 0.3 * (3.0 * s).sin());
    let stride = (at(runner.lap + 1e-3) - at(runner.lap)).length() / 1e-3;
    runner.lap += RUN * dt / stride.max(1e-3);
    runner.travelled += RUN * dt;
    let next = at(runner.lap);
    // From wherever the keys left it, ease onto the path over a second.
    let blend = ((runner.idle - 2.0) / 1.0).min(1.0);
    transform.translation = transform.translation.lerp(next, blend);
    // Once a lap, 12.5 m into it, it stamps: a blast where it stands.
    if runner.travelled >= 12.5 {
        runner.travelled -= 40.0;
        commands.spawn(stamp(transform.translation));
    }
}

/// A blast at the runner's feet (at `at`): what B sets off.
fn stamp(at: Vec3) -> (WindSource, Transform) {
    (
        WindSource::blast(9.0, 12.0, 3.5),
        Transform::from_translation(at.with_y(0.2)),
    )
}

/// B sets off a blast where the runner stands.
fn blast(
    keys: Res<ButtonInput<KeyCode>>,
    runner: Single<&Transform, With<Runner>>,
    mut commands: Commands,
) {
    if keys.just_pressed(KeyCode::KeyB) {
        commands.spawn(stamp(runner.translation));
    }
}

/// The camera keeps the runner in view, a little behind its side of the meadow.
fn follow(
    runner: Single<&Transform, (With<Runner>, Without<Camera3d>)>,
    mut camera: Single<&mut Transform, With<Camera3d>>,
    time: Res<Time>,
) {
    let offset = Vec3::new(0.0, 2.9, 7.5);
    let eye = Vec3::new(0.5 * runner.translation.x, 0.3, 0.0) + offset;
    let ease = (2.0 * time.delta_secs()).min(1.0);
    let now = camera.translation.lerp(eye, ease);
    **camera = Transform::from_translation(now).looking_at(now - offset, Vec3::Y);
}
