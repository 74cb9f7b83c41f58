//! The free-fall paper's Fig. 15a: an aluminium coin (radius 1.0 cm, 1.5 mm thick) dropped in a
//! glass tank of still water from 50 cm. Its path is traced; its Reynolds number, I*, main
//! motion and current motion are shown. It is dropped again after it lands.

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_windfall::WindfallSystems;
use bevy_windfall::freefall::FallPreset;
use bevy_windfall::prelude::*;

use super::{Featured, Scene, SceneInfo, place_camera};

/// Tank inside size (x, height, z), m; the floor is at y = 0.
const TANK: Vec3 = Vec3::new(0.36, 0.62, 0.22);
const WATER_LEVEL: f32 = 0.56;
const RELEASE: Vec3 = Vec3::new(0.0, 0.5, 0.0);
const REST: f32 = 1.5;
const TRAIL: usize = 400;

pub fn plugin(app: &mut App) {
    app.add_systems(OnEnter(Scene::Coin), setup)
        .add_systems(
            FixedUpdate,
            record_trail
                .after(WindfallSystems::Simulate)
                .run_if(in_state(Scene::Coin)),
        )
        .add_systems(
            Update,
            (draw_trail, rest_and_drop, show_info).run_if(in_state(Scene::Coin)),
        );
}

#[derive(Component)]
struct Coin {
    trail: VecDeque<Vec3>,
}

#[derive(Component)]
struct Resting(Timer);

/// The paper's coin (Fig. 15a): steady at first, then fluttering.
pub fn coin() -> FallingObject {
    FallPreset::Coin.object()
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut camera: Single<&mut Transform, With<Camera3d>>,
    mut wind: ResMut<WindSettings>,
    mut settings: ResMut<FallSettings>,
) {
    let here = DespawnOnExit(Scene::Coin);
    place_camera(
        &mut camera,
        Vec3::new(0.05, 0.42, 0.74),
        Vec3::new(0.0, 0.25, 0.0),
    );
    // Still water (raise the wind in the panel for a current).
    wind.reference_speed = 0.0;
    settings.ground_height = 0.00075;
    commands.insert_resource(ClearColor(Color::srgb(0.93, 0.93, 0.9)));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 900.0,
        ..default()
    });
    commands.spawn((
        DirectionalLight {
            illuminance: 8_000.0,
            ..default()
        },
        Transform::from_xyz(0.6, 1.5, 1.0).looking_at(Vec3::ZERO, Vec3::Y),
        here.clone(),
    ));
    // Table, tank floor, water and glass walls.
    let mut solid = |size: Vec3, color: Color, at: Vec3| {
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::from_size(size))),
            MeshMaterial3d(materials.add(color)),
            Transform::from_translation(at),
            here.clone(),
        ));
    };
    solid(
        Vec3::new(1.6, 0.04, 1.0),
        Color::srgb(0.45, 0.33, 0.22),
        Vec3::new(0.0, -0.03, 0.0),
    );
    solid(
        Vec3::new(TANK.x, 0.01, TANK.z),
        Color::srgb(0.75, 0.78, 0.8),
        Vec3::new(0.0, -0.005, 0.0),
    );
    let water = materials.add(StandardMaterial {
        base_color: Color::srgba(0.45, 0.7, 0.9, 0.22),
        alpha_mode: AlphaMode::Blend,
        perceptual_roughness: 0.1,
        ..default()
    });
    let glass = materials.add(StandardMaterial {
        base_color: Color::srgba(0.85, 0.95, 1.0, 0.12),
        alpha_mode: AlphaMode::Blend,
        perceptual_roughness: 0.05,
        reflectance: 0.8,
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(TANK.x, WATER_LEVEL, TANK.z))),
        MeshMaterial3d(water),
        Transform::from_xyz(0.0, WATER_LEVEL / 2.0, 0.0),
        here.clone(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(TANK.x + 0.01, TANK.y, TANK.z + 0.01))),
        MeshMaterial3d(glass),
        Transform::from_xyz(0.0, TANK.y / 2.0, 0.0),
        here.clone(),
    ));
    // The coin: a disk in its local XZ plane, as FallingObject expects.
    commands.spawn((
        coin(),
        Featured,
        Name::new("coin"),
        Coin {
            trail: VecDeque::new(),
        },
        Mesh3d(meshes.add(Cylinder::new(0.01, 0.0015))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.8, 0.8, 0.82),
            metallic: 0.9,
            perceptual_roughness: 0.3,
            ..default()
        })),
        Transform::from_translation(RELEASE),
        here,
    ));
}

/// Every fixed step's position, so the trace does not depend on the frame rate.
fn record_trail(mut coins: Query<(Entity, &mut Coin)>, store: Res<FallStore>) {
    for (entity, mut coin) in &mut coins {
        if let Some(path) = store.fall(entity)
            && !path.landed()
        {
            coin.trail.push_back(path.position());
            if coin.trail.len() > TRAIL {
                coin.trail.pop_front();
            }
        }
    }
}

fn draw_trail(coins: Query<&Coin>, mut gizmos: Gizmos) {
    for coin in &coins {
        gizmos.linestrip(coin.trail.iter().copied(), Color::srgb(0.85, 0.2, 0.15));
    }
}

/// A landed coin rests, then drops again from the release point. Editing it in the panel
/// (a changed `FallingObject`) also drops it again, from where it is.
fn rest_and_drop(
    mut commands: Commands,
    mut landed: MessageReader<Landed>,
    mut coins: Query<(
        Entity,
        &mut Coin,
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
    for (entity, mut coin, mut transform, mut object, resting) in &mut coins {
        if let Some(mut rest) = resting
            && rest.0.tick(time.delta()).is_finished()
        {
            transform.translation = RELEASE;
            object.seed += 1;
            coin.trail.clear();
            commands.entity(entity).remove::<Resting>();
        }
    }
}

fn show_info(coin: Single<(&FallingObject, &FallState), With<Coin>>, mut info: ResMut<SceneInfo>) {
    let (object, state) = *coin;
    let Some(r) = state.regime() else {
        info.0 = "invalid object (see FallingObjectInvalid)".into();
        return;
    };
    let now = state
        .motion()
        .map_or(String::from("-"), |m| format!("{} {m:?}", m.label()));
    let shape = match object.shape {
        Shape::Disk {
            diameter,
            thickness,
        } => format!(
            "disk {:.1} cm across, {:.2} cm thick",
            diameter * 100.0,
            thickness * 100.0
        ),
        Shape::Rectangle { length, width, .. } => {
            format!("rectangle {:.1} × {:.1} cm", length * 100.0, width * 100.0)
        }
        Shape::Ellipse { major, minor, .. } => {
            format!("ellipse {:.1} × {:.1} cm", major * 100.0, minor * 100.0)
        }
    };
    info.0 = format!(
        "{shape}, {:.0} kg/m^3, in {}, dropped from 50 cm\n\
         Re = {:.3e}   I* = {:.2e}   U = {:.3} m/s\n\
         main motion (phase diagram): {} {:?}   now: {}{}",
        object.density,
        if object.fluid == Fluid::WATER {
            "water"
        } else {
            "air"
        },
        r.reynolds,
        r.inertia,
        r.descent_speed,
        r.main.label(),
        r.main,
        now,
        if state.landed() { " (landed)" } else { "" },
    );
}
