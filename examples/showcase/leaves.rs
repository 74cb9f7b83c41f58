//! Autumn leaves fall from a tree into gusty wind, land, rest and fall again. Most are
//! procedural [`FallingObject`]s of four kinds (maple, oak, birch and the paper's leaf, each a
//! [`FallPreset`] with its own Markov chain); a few yellow-green ones are physical [`AeroBody`]
//! plates with per-face lift and drag. Behind them a storm of [`STORM`] more leaves blows across
//! the meadow: one [`LeafCloud`] entity, stepped in parallel chunks and drawn in one draw call.
//! The camera stands by the trunk, where leaves pass close.

use bevy::prelude::*;
use bevy_windfall::aero::{AeroState, PlateState};
use bevy_windfall::freefall::{
    CloudRegion, FallLod, FallPreset, LeafCloud, LeafCloudState, PrimitiveMotion,
};
use bevy_windfall::lod::LodTiers;
use bevy_windfall::prelude::*;
use bevy_windfall::render::{
    LeafCloudLook, SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial,
};
use bevy_windfall::wind::WindSource;

use super::population::{CANOPY, Canopy, LEAVES, Stream, leaf};
use super::{Featured, Scene, SceneInfo, common, place_camera};

const PHYSICAL_LEAVES: usize = 30;
/// Leaves in the background storm (a [`LeafCloud`]).
pub const STORM: u32 = 24_000;
/// Seconds a leaf rests on the ground before it is released again: at least this, and up to
/// twice as long (drawn per landing, so the leaves do not fall in waves).
const REST: f32 = 2.0;

pub fn plugin(app: &mut App) {
    let args = app.world().resource::<common::ExampleArgs>();
    // `--view tree|meadow` picks the first view, `--blades N` the meadow's grass.
    let view = args.choice("--view", &[("tree", 0), ("meadow", 1)]);
    let blades = args.number("--blades", 0..=super::grass::BLADES);
    app.insert_resource(Spawner(Canopy(Stream::new(99))))
        .insert_resource(StartView(view.unwrap_or(0)))
        .insert_resource(super::grass::Blades(blades.unwrap_or(super::grass::BLADES)))
        .init_resource::<View>()
        .add_systems(OnEnter(Scene::Leaves), setup)
        .add_systems(
            Update,
            (
                rest_and_release,
                respawn_physical,
                wander,
                gust_fronts,
                blast_on_key,
                switch_view,
                show_info,
            )
                .run_if(in_state(Scene::Leaves)),
        );
}

/// A dust devil wandering round the meadow: a [`WindSource`] vortex with an updraft, lifting
/// the leaves it passes over.
#[derive(Component)]
struct DustDevil;

/// Where the dust devil is at `t` seconds: a slow loop round the tree, through the camera's view.
fn devil_at(t: f32) -> Vec3 {
    Vec3::new(
        CANOPY.x + 1.5 + 1.5 * (0.21 * t).cos(),
        1.2,
        CANOPY.z - 0.5 + 1.8 * (0.13 * t).sin(),
    )
}

/// A gust front that sweeps across the meadow downwind every [`GUST_EVERY`] seconds: the
/// grass bends as it passes, and the leaves in it are carried along.
#[derive(Component)]
struct GustFront;

const GUST_EVERY: f32 = 9.0;

fn gust_fronts(
    mut commands: Commands,
    gusts: Query<Entity, With<GustFront>>,
    wind: Res<WindField>,
    time: Res<Time>,
    mut next: Local<f32>,
) {
    if time.elapsed_secs() < *next {
        return;
    }
    *next = time.elapsed_secs() + GUST_EVERY;
    // From 14 m upwind of the tree, along the mean wind; inserting the component again fires it
    // again.
    let downwind = wind.direction();
    let place = Transform::from_translation(CANOPY.with_y(0.0) - downwind * 14.0)
        .looking_to(downwind, Vec3::Y);
    let gust = WindSource::gust(3.0, 5.0, 4.0, 30.0);
    match gusts.single() {
        Ok(entity) => {
            commands.entity(entity).insert((gust, place));
        }
        Err(_) => {
            commands.spawn((gust, place, GustFront, DespawnOnExit(Scene::Leaves)));
        }
    }
}

fn wander(mut devil: Query<&mut Transform, With<DustDevil>>, time: Res<Time>) {
    for mut t in &mut devil {
        t.translation = devil_at(time.elapsed_secs());
    }
}

/// The camera's places (eye, target): beside the trunk looking up through the falling leaves,
/// and a view over the meadow round the tree, where the dust devil and a blast move the leaves
/// on the ground.
const VIEWS: [(Vec3, Vec3); 2] = [
    (Vec3::new(4.6, 1.4, 3.0), Vec3::new(2.2, 2.6, -0.6)),
    (Vec3::new(10.0, 3.2, 11.0), Vec3::new(1.0, 3.4, -0.5)),
];

/// Which of [`VIEWS`] the camera starts at (`--view`).
#[derive(Resource)]
struct StartView(usize);

/// Which of [`VIEWS`] the camera is at.
#[derive(Resource, Default)]
struct View(usize);

/// C: the other view.
fn switch_view(
    keys: Res<ButtonInput<KeyCode>>,
    mut camera: Single<&mut Transform, With<Camera3d>>,
    mut view: ResMut<View>,
) {
    if keys.just_pressed(KeyCode::KeyC) {
        view.0 = (view.0 + 1) % VIEWS.len();
        let (eye, target) = VIEWS[view.0];
        place_camera(&mut camera, eye, target);
    }
}

/// A blast that goes off with B and is despawned once over.
#[derive(Component)]
struct Blast(Timer);

/// B: a burst at ground level by the tree (its centre a metre down, so the air leaves the ground
/// upward and outward) sweeps the resting leaves up and away.
fn blast_on_key(
    mut commands: Commands,
    keys: Res<ButtonInput<KeyCode>>,
    mut blasts: Query<(Entity, &mut Blast)>,
    time: Res<Time>,
) {
    if keys.just_pressed(KeyCode::KeyB) {
        commands.spawn((
            WindSource::blast(16.0, 12.0, 5.0),
            Transform::from_translation(CANOPY.with_y(-1.0) + Vec3::new(1.8, 0.0, 0.6)),
            Blast(Timer::from_seconds(1.5, TimerMode::Once)),
            DespawnOnExit(Scene::Leaves),
        ));
    }
    for (entity, mut blast) in &mut blasts {
        if blast.0.tick(time.delta()).is_finished() {
            commands.entity(entity).despawn();
        }
    }
}

/// A material that sways in the wind.
trait IntoSway {
    fn into_sway(self, gpu: &WindGpuBuffers, settings: SwaySettings) -> WindSwayMaterial;
}

impl IntoSway for StandardMaterial {
    fn into_sway(self, gpu: &WindGpuBuffers, settings: SwaySettings) -> WindSwayMaterial {
        WindSwayMaterial {
            base: self,
            extension: WindSway::new(gpu, settings),
        }
    }
}

#[derive(Resource)]
struct Spawner(Canopy);

impl Spawner {
    /// A physical leaf at rest at a canopy point, turned at random.
    fn physical_start(&mut self) -> AeroState {
        AeroState::new(PlateState {
            position: self.0.point(),
            rotation: self.0.turn(),
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
    mut wind: ResMut<WindSettings>,
    mut settings: ResMut<FallSettings>,
    mut swaying: ResMut<Assets<WindSwayMaterial>>,
    gpu: Res<WindGpuBuffers>,
    start: Res<StartView>,
    blades: Res<super::grass::Blades>,
    mut view: ResMut<View>,
) {
    let here = DespawnOnExit(Scene::Leaves);
    // Beside the tree, downwind of the trunk, looking up through the falling leaves, or
    // (`--view meadow`) over the meadow.
    view.0 = start.0;
    let (eye, target) = VIEWS[view.0];
    place_camera(&mut camera, eye, target);
    wind.reference_speed = 2.0;
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
    // The crown sways in the GPU wind (each ball bends from its bottom up), and 120 000 blades
    // of grass round the tree bend in the same gusts and in the dust devil's swirl.
    let crown = |radius: f32| {
        StandardMaterial {
            base_color: Color::srgb(0.72, 0.42, 0.12),
            perceptual_roughness: 0.9,
            ..default()
        }
        .into_sway(&gpu, SwaySettings::crown(-radius, 2.0 * radius))
    };
    for (offset, radius) in [
        (Vec3::new(0.0, 1.4, 0.0), 1.8),
        (Vec3::new(1.2, 0.9, 0.4), 1.3),
        (Vec3::new(-1.1, 1.0, -0.3), 1.3),
        (Vec3::new(0.2, 0.8, -1.2), 1.2),
    ] {
        commands.spawn((
            Mesh3d(meshes.add(Sphere::new(radius))),
            MeshMaterial3d(swaying.add(crown(radius))),
            Transform::from_translation(CANOPY + offset),
            here.clone(),
        ));
    }
    let grass = super::grass::spawn(
        &mut commands,
        &mut meshes,
        &mut swaying,
        &gpu,
        blades.0,
        Vec2::new(-7.0, -9.0),
        Vec2::new(11.0, 9.0),
    );
    commands.entity(grass).insert(here.clone());
    // Each leaf is drawn as its preset (`WindfallPlugins`' default look).
    for i in 0..LEAVES {
        let transform =
            Transform::from_translation(spawner.0.midair()).with_rotation(spawner.0.turn());
        let mut entity = commands.spawn((
            leaf(i),
            // Levels of detail round the camera (its `LodFocus`): within 15 m every fixed step,
            // to 30 m every second, beyond every fourth; no leaf looks any different for it.
            FallLod(LodTiers {
                near: 15.0,
                far: 30.0,
            }),
            transform,
            here.clone(),
        ));
        if i == 0 {
            entity.insert((Featured, Name::new("featured leaf")));
        }
    }
    // The storm: leaves blowing across the meadow round and behind the tree, each let go again
    // from 16 m up a few seconds after it lands. The camera is the cloud's level-of-detail focus
    // (see `main.rs`): leaves beyond 25 m are stepped every second step, beyond 60 m every fourth.
    commands.spawn((
        LeafCloud {
            object: FallPreset::MapleLeaf.object(),
            count: STORM,
            seed: 11,
            region: CloudRegion {
                min: Vec3::new(-36.0, 0.5, -40.0),
                max: Vec3::new(24.0, 16.0, 8.0),
            },
            lod: LodTiers::default(),
            recycle_after: Some(3.0),
        },
        LeafCloudLook::default(),
        Name::new("storm"),
        here.clone(),
    ));
    commands.spawn((
        WindSource::vortex(2.4, 5.0).with_updraft(2.5),
        Transform::from_translation(devil_at(0.0)),
        DustDevil,
        Name::new("dust devil"),
        here.clone(),
    ));
    // Physical leaves: rigid 7.3 × 4.2 cm plates, each face with lift and drag.
    let plate = RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2)
        .expect("a valid plate");
    let mesh = meshes.add(FallPreset::Leaf.object().mesh());
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

/// A leaf that lands rests a while, then falls again from a new point in the canopy.
fn rest_and_release(
    mut commands: Commands,
    mut landed: MessageReader<Landed>,
    mut resting: Query<(Entity, &mut Resting, &mut Transform, &mut FallingObject)>,
    mut spawner: ResMut<Spawner>,
    time: Res<Time>,
) {
    for message in landed.read() {
        // A leaf that a gust lifts and sets down again keeps its first rest's end, so gusts
        // make the fallen leaves skitter without holding them on the ground.
        if resting.contains(message.entity) {
            continue;
        }
        if let Ok(mut e) = commands.get_entity(message.entity) {
            let rest = REST * (1.0 + spawner.0.0.uniform());
            e.insert(Resting(Timer::from_seconds(rest, TimerMode::Once)));
        }
    }
    for (entity, mut rest, mut transform, mut object) in &mut resting {
        if rest.0.tick(time.delta()).is_finished() {
            transform.translation = spawner.0.point();
            transform.rotation = spawner.0.turn();
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
    storm: Query<&LeafCloudState>,
    featured: Single<(&FallingObject, &FallState), With<Featured>>,
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
    let storm_down = storm
        .iter()
        .filter_map(LeafCloudState::leaves)
        .map(|l| l.resting())
        .sum::<usize>();
    let mut line = format!(
        "{LEAVES} leaves: maple, oak, birch, the paper's; {PHYSICAL_LEAVES} physical plates (green); \
         storm: {STORM} leaves in one cloud ({storm_down} down)\n"
    );
    let (object, state) = *featured;
    if let Some(r) = state.regime() {
        line += &format!(
            "featured ({:.0} mm): Re = {:.1e}, I* = {:.3}, U = {:.2} m/s, main {:?}\n",
            object.shape.lengths().0 * 1e3,
            r.reynolds,
            r.inertia,
            r.descent_speed,
            r.main
        );
    }
    let airborne = counts.iter().filter(|c| **c > 0).count();
    line += &format!("in the air, {airborne} motions at once:");
    for m in PrimitiveMotion::ALL {
        if counts[m.index()] > 0 {
            line += &format!("  {} {}", m.label(), counts[m.index()]);
        }
    }
    line += &format!("   on the ground: {grounded}   B: a blast   C: view");
    info.0 = line;
}
