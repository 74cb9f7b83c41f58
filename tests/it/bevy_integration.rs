//! The crate as a Bevy citizen: what an inspector, an editor or a scene file sees through the
//! type registry, entities ready the frame they are spawned, smooth motion between fixed steps,
//! and a simulation schedule of the user's choice.

use crate::common;

use std::time::Duration;

use bevy::ecs::reflect::{ReflectComponent, ReflectResource};
use bevy::mesh::{Mesh3d, VertexAttributeValues};
use bevy::prelude::*;
use bevy::reflect::GetPath;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::aero::{PhysicalCloth, PhysicalClothState, Pinning};
use bevy_windfall::freefall::cloud::LeafCloudState;
use bevy_windfall::freefall::{FallLod, FallPreset, LeafCloud};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::{WindShelter, WindSource};
use common::{STEP, headless_app_with_meshes, ready};

pub(crate) fn card() -> AeroBody {
    AeroBody::new(
        RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 3).unwrap(),
    )
}

pub(crate) fn small_flag() -> Cloth {
    Cloth {
        grid: ClothGrid {
            rows: 8,
            columns: 12,
            ..default()
        },
        params: ClothPreset::FlagFlappingFrozen.params(),
        ..default()
    }
}

pub(crate) fn physical_flag() -> PhysicalCloth {
    PhysicalCloth {
        grid: ClothGrid {
            rows: 6,
            columns: 9,
            width: 1.2,
            height: 0.8,
        },
        pinning: Pinning::PoleColumn,
        ..default()
    }
}

fn full_app() -> App {
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default());
    ready(&mut app);
    app
}

#[test]
fn every_user_facing_type_is_reflected_and_registered() {
    let app = full_app();
    let registry = app.world().resource::<AppTypeRegistry>().read();
    let components = [
        ("FallingObject", true),
        ("FallState", true),
        ("FallingObjectInvalid", false),
        ("Cloth", true),
        ("ClothState", true),
        ("ClothInvalid", false),
        ("AeroBody", true),
        ("AeroState", true),
        ("PhysicalCloth", true),
        ("PhysicalClothInvalid", false),
    ];
    for (name, default) in components {
        let r = registry
            .get_with_short_type_path(name)
            .unwrap_or_else(|| panic!("{name} is not registered"));
        assert!(
            r.data::<ReflectComponent>().is_some(),
            "{name}: no ReflectComponent"
        );
        assert_eq!(
            r.data::<ReflectDefault>().is_some(),
            default,
            "{name}: ReflectDefault"
        );
    }
    for name in ["WindSettings", "FallSettings"] {
        let r = registry
            .get_with_short_type_path(name)
            .unwrap_or_else(|| panic!("{name} is not registered"));
        assert!(
            r.data::<ReflectResource>().is_some(),
            "{name}: no ReflectResource"
        );
        assert!(
            r.data::<ReflectDefault>().is_some(),
            "{name}: no ReflectDefault"
        );
    }
    // Their fields are visible too: what an inspector lists.
    for (name, field) in [
        ("FallingObject", "main_motion"),
        ("Cloth", "params"),
        ("ClothParams", "amplitude"),
        ("WindConfig", "beta"),
        ("PhysicalCloth", "areal_density"),
    ] {
        let info = registry.get_with_short_type_path(name).unwrap().type_info();
        let fields: Vec<&str> = info.as_struct().unwrap().field_names().to_vec();
        assert!(fields.contains(&field), "{name}: {fields:?}");
    }
}

/// A falling object made the way a scene file or an editor makes one: its reflected default,
/// edited by field path and inserted through `ReflectComponent`, then edited again the same way.
#[test]
fn a_falling_object_made_and_edited_through_reflection_falls() {
    let mut app = full_app();
    let registry = app.world().resource::<AppTypeRegistry>().clone();
    let entity = app
        .world_mut()
        .spawn(Transform::from_xyz(0.0, 3.0, 0.0))
        .id();
    {
        let registry = registry.read();
        let r = registry.get_with_short_type_path("FallingObject").unwrap();
        let mut object = r.data::<ReflectDefault>().unwrap().default();
        *object
            .reflect_path_mut("seed")
            .unwrap()
            .try_downcast_mut::<u64>()
            .unwrap() = 77;
        let mut entity_mut = app.world_mut().entity_mut(entity);
        r.data::<ReflectComponent>().unwrap().insert(
            &mut entity_mut,
            object.as_partial_reflect(),
            &registry,
        );
    }
    for _ in 0..30 {
        app.update();
    }
    let y = app.world().get::<Transform>(entity).unwrap().translation.y;
    assert!(y < 3.0 - 0.05, "it did not fall: y = {y}");
    assert_eq!(app.world().get::<FallingObject>(entity).unwrap().seed, 77);

    // An inspector's edit through `ReflectComponent` releases it again from where it is.
    let before = app
        .world()
        .resource::<FallStore>()
        .fall(entity)
        .unwrap()
        .time();
    {
        let registry = registry.read();
        let r = registry.get_with_short_type_path("FallingObject").unwrap();
        let reflect = r.data::<ReflectComponent>().unwrap();
        let mut object = reflect
            .reflect_mut(app.world_mut().entity_mut(entity))
            .unwrap();
        *object
            .reflect_path_mut("density")
            .unwrap()
            .try_downcast_mut::<f32>()
            .unwrap() *= 2.0;
    }
    app.update();
    let after = app
        .world()
        .resource::<FallStore>()
        .fall(entity)
        .unwrap()
        .time();
    assert!(
        after < before,
        "not released again: {before} s, then {after} s"
    );
}

#[test]
fn wind_settings_edited_by_field_path_apply_on_the_next_step() {
    let mut app = full_app();
    let registry = app.world().resource::<AppTypeRegistry>().clone();
    {
        let registry = registry.read();
        let r = registry.get_with_short_type_path("WindSettings").unwrap();
        assert!(r.data::<ReflectResource>().is_some());
        // Resources live on entities: an inspector reaches them through ReflectComponent.
        let id = app.world().component_id::<WindSettings>().unwrap();
        let holder = app.world().resource_entities().get(id).unwrap();
        let reflect = r.data::<ReflectComponent>().unwrap();
        let mut settings = reflect
            .reflect_mut(app.world_mut().entity_mut(holder))
            .unwrap();
        *settings
            .reflect_path_mut("config.reference_speed")
            .unwrap()
            .try_downcast_mut::<f32>()
            .unwrap() = 9.0;
    }
    app.update();
    let wind = app.world().resource::<WindField>();
    assert!(
        (wind.mean_speed_at(10.0) - 9.0).abs() < 1e-3,
        "{}",
        wind.mean_speed_at(10.0)
    );
}

#[derive(Resource, Default)]
struct Spawned(Vec<Entity>);

fn spawn_everything(mut commands: Commands, mut spawned: ResMut<Spawned>, mut once: Local<bool>) {
    if std::mem::replace(&mut *once, true) {
        return;
    }
    spawned.0 = vec![
        commands
            .spawn((
                FallPreset::OakLeaf.object(),
                Transform::from_xyz(0.0, 4.0, 0.0),
            ))
            .id(),
        commands
            .spawn((small_flag(), Transform::from_xyz(3.0, 4.0, 0.0)))
            .id(),
        commands
            .spawn((physical_flag(), Transform::from_xyz(6.0, 4.0, 0.0)))
            .id(),
    ];
}

/// Spawned by a system during `Update`, before any fixed step can see them: by the end of that
/// frame each has its state and mesh, so it is drawn in the frame it appears.
#[test]
fn entities_spawned_in_a_frame_are_ready_in_that_frame() {
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default())
        .init_resource::<Spawned>()
        .add_systems(Update, spawn_everything);
    app.finish();
    app.cleanup();
    // The first update advances no time: no fixed step runs in it.
    app.update();
    let spawned = app.world().resource::<Spawned>().0.clone();
    assert_eq!(spawned.len(), 3);
    let world = app.world();
    let leaf = world.get::<FallState>(spawned[0]).unwrap();
    assert!(leaf.regime().is_some() && leaf.motion().is_some());
    assert!(world.get::<ClothState>(spawned[1]).is_some());
    assert!(world.get::<Mesh3d>(spawned[1]).is_some());
    assert!(world.get::<PhysicalClothState>(spawned[2]).is_some());
    assert!(world.get::<Mesh3d>(spawned[2]).is_some());
}

/// Per-update motion of something drawn: a rigid transform, or every vertex of a mesh.
fn meshes_positions(app: &App, entity: Entity) -> Vec<Vec3> {
    let mesh = app.world().get::<Mesh3d>(entity).unwrap();
    let meshes = app.world().resource::<Assets<Mesh>>();
    match meshes
        .get(&mesh.0)
        .unwrap()
        .attribute(Mesh::ATTRIBUTE_POSITION)
    {
        Some(VertexAttributeValues::Float32x3(p)) => p.iter().map(|&v| Vec3::from(v)).collect(),
        _ => panic!("no positions"),
    }
}

fn pose(app: &App, entity: Entity) -> Vec<Vec3> {
    let t = app.world().get::<Transform>(entity).unwrap();
    // The translation and two points on the body, so turning counts as motion too.
    vec![
        t.translation,
        t.transform_point(Vec3::X * 0.05),
        t.transform_point(Vec3::Z * 0.05),
    ]
}

/// Reads the points of an entity whose motion is tracked.
type Probe = fn(&App, Entity) -> Vec<Vec3>;

fn displacement(a: &[Vec3], b: &[Vec3]) -> f32 {
    a.iter().zip(b).map(|(p, q)| p.distance(*q)).sum()
}

/// Steps show as updates that barely move between updates that move a whole step. Smooth
/// motion moves about as much in each update as the average of its neighbours.
fn assert_smooth(name: &str, moves: &[f32]) {
    let mut jerky = 0;
    for w in moves.windows(3) {
        let neighbours = 0.5 * (w[0] + w[2]);
        if neighbours > 0.0 && !(0.5..=1.7).contains(&(w[1] / neighbours)) {
            jerky += 1;
        }
    }
    let share = jerky as f32 / (moves.len() - 2) as f32;
    assert!(
        share < 0.05,
        "{name}: {:.0} % of updates move unlike their neighbours (first: {:?})",
        share * 100.0,
        &moves[..12]
    );
}

/// An app of `plugins` with 144 Hz frames and four bodies moved on the simulation's step, each
/// with how to read what is shown of it: a paper sheet let go `height` m up, a rigid plate 30 m
/// up, a particle-cloth flag and a procedural flag.
fn bodies_at_144_hz(
    plugins: WindfallPlugins,
    height: f32,
) -> (App, [(&'static str, Probe, Entity); 4]) {
    let mut app = headless_app_with_meshes();
    app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 144.0,
    )))
    .add_plugins(plugins);
    ready(&mut app);
    let world = app.world_mut();
    let sheet = world
        .spawn((
            FallPreset::PaperSheet.object(),
            Transform::from_xyz(0.0, height, 0.0),
        ))
        .id();
    let plate = world
        .spawn((card(), Transform::from_xyz(2.0, 30.0, 0.0)))
        .id();
    let cloth = world
        .spawn((physical_flag(), Transform::from_xyz(4.0, 4.0, 0.0)))
        .id();
    let flag = world
        .spawn((small_flag(), Transform::from_xyz(8.0, 4.0, 0.0)))
        .id();
    let tracks: [(&'static str, Probe, Entity); 4] = [
        ("falling object", pose, sheet),
        ("rigid plate", pose, plate),
        ("particle cloth", meshes_positions, cloth),
        ("procedural cloth", meshes_positions, flag),
    ];
    (app, tracks)
}

/// 144 Hz frames over a 60 Hz fixed step: every body moved on the fixed step (falling object,
/// rigid plate, particle cloth, procedural cloth) moves a similar amount in every frame.
#[test]
fn bodies_move_smoothly_at_144_hz_over_a_60_hz_step() {
    let (mut app, tracks) = bodies_at_144_hz(WindfallPlugins::default(), 30.0);
    assert_eq!(app.world().resource::<Time<Fixed>>().timestep(), STEP);
    // Settle for a second, then record 2 s.
    for _ in 0..144 {
        app.update();
    }
    let mut last: Vec<Vec<Vec3>> = tracks.iter().map(|(_, f, e)| f(&app, *e)).collect();
    let mut moves = vec![Vec::new(); tracks.len()];
    for _ in 0..288 {
        app.update();
        for (i, (_, f, e)) in tracks.iter().enumerate() {
            let now = f(&app, *e);
            moves[i].push(displacement(&last[i], &now));
            last[i] = now;
        }
    }
    for (i, (name, _, _)) in tracks.iter().enumerate() {
        assert_smooth(name, &moves[i]);
    }
}

/// Pausing `Time<Virtual>` freezes what is on screen: in the frames after the pause every body
/// (falling object, rigid plate, particle cloth, procedural cloth) shows exactly the pose of the
/// last frame before it, and after the pause it moves on from there; with the simulation on the
/// fixed step (144 Hz frames) and in `Update`.
#[test]
fn a_paused_game_shows_every_body_where_it_was() {
    paused_frames_show_the_last_poses(WindfallPlugins::default());
    paused_frames_show_the_last_poses(WindfallPlugins::new(Update));
}

fn paused_frames_show_the_last_poses(plugins: WindfallPlugins) {
    let (mut app, tracks) = bodies_at_144_hz(plugins, 12.0);
    let shown =
        |app: &App| -> Vec<Vec<Vec3>> { tracks.iter().map(|(_, f, e)| f(app, *e)).collect() };
    // Pause at several shares of a fixed step, each after a few frames of motion.
    for frames in [1, 5, 17, 30] {
        for _ in 0..frames {
            app.update();
        }
        let before = shown(&app);
        app.world_mut().resource_mut::<Time<Virtual>>().pause();
        for frame in 0..6 {
            app.update();
            let now = shown(&app);
            for (i, (name, _, _)) in tracks.iter().enumerate() {
                let moved = displacement(&before[i], &now[i]);
                assert!(
                    moved == 0.0,
                    "{name} moved {moved} m in paused frame {frame} (after {frames} frames)"
                );
            }
        }
        app.world_mut().resource_mut::<Time<Virtual>>().unpause();
    }
    // And it moves again.
    let before = shown(&app);
    for _ in 0..12 {
        app.update();
    }
    let after = shown(&app);
    for (i, (name, _, _)) in tracks.iter().enumerate() {
        assert!(
            displacement(&before[i], &after[i]) > 0.0,
            "{name} stays paused"
        );
    }
}

/// An app of `plugins` whose frames last 40 ms, set up.
fn frames_of_40_ms<M>(plugins: impl bevy::app::Plugins<M>) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin, plugins))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_millis(
            40,
        )));
    ready(&mut app);
    app
}

/// Drops a paper sheet from 10 m and runs `frames` frames: how far the wind clock ran, s, and
/// the sheet's height after each frame.
fn drop_a_sheet(app: &mut App, frames: usize) -> (f32, Vec<f32>) {
    let leaf = app
        .world_mut()
        .spawn((
            FallPreset::PaperSheet.object(),
            Transform::from_xyz(0.0, 10.0, 0.0),
        ))
        .id();
    let t0 = app.world().resource::<WindField>().time();
    let mut heights = Vec::new();
    for _ in 0..frames {
        app.update();
        heights.push(app.world().get::<Transform>(leaf).unwrap().translation.y);
    }
    (app.world().resource::<WindField>().time() - t0, heights)
}

/// `WindfallPlugins::new(Update)`: the simulation steps once per frame by the frame's time.
#[test]
fn the_simulation_schedule_can_be_chosen() {
    let mut app = frames_of_40_ms(WindfallPlugins::new(Update));
    let (clock, heights) = drop_a_sheet(&mut app, 25);
    assert!(
        (clock - 1.0).abs() < 1e-4,
        "wind clock ran {clock} s in 25 × 40 ms"
    );
    // It moves down in every frame, not only on fixed steps.
    assert!(heights.windows(2).all(|w| w[1] < w[0]), "{heights:?}");
}

/// Single plugins take their schedule from their constructors, as avian's do: added in any
/// order, with no resource inserted first, the wind and a fall both run once per frame in
/// `Update` (before, a plugin added without the resource stayed in `FixedUpdate` silently).
#[test]
fn single_plugins_take_their_schedule_in_any_order() {
    use bevy::ecs::schedule::ScheduleLabel;
    // The group's constructor returns the group itself.
    let _: WindfallPlugins = WindfallPlugins::new(Update);
    let mut app = frames_of_40_ms((
        FallPlugin::new(Update),
        WindPlugin::default().in_schedule(Update),
    ));
    assert_eq!(
        app.world().resource::<WindfallSchedule>().0,
        Update.intern(),
        "the first plugin records its schedule"
    );
    let (clock, heights) = drop_a_sheet(&mut app, 10);
    // Ten frames of 40 ms: the clock ran exactly 0.4 s (in `FixedUpdate` at 64 Hz it would have
    // run 25 whole steps, 0.390625 s), and the sheet moved down in every frame.
    assert!((clock - 0.4).abs() < 1e-4, "wind clock ran {clock} s");
    assert!(heights.windows(2).all(|w| w[1] < w[0]), "{heights:?}");
}

/// A plugin left at its default schedule follows its group: `WindfallPlugins::new(Update)` with
/// its own `WindPlugin` runs the wind clock once per frame too.
#[test]
fn a_default_plugin_follows_its_group() {
    let mut app = frames_of_40_ms(
        WindfallPlugins::new(Update).set(WindPlugin::new(WindConfig {
            grid: [16, 16],
            ..default()
        })),
    );
    let (clock, _) = drop_a_sheet(&mut app, 10);
    assert!((clock - 0.4).abs() < 1e-4, "wind clock ran {clock} s");
}

/// Removing a component and inserting the same description again sets it up again: a sheet
/// taken off and put back falls.
#[test]
fn a_removed_and_reinserted_object_falls_again() {
    let mut app = full_app();
    let sheet = FallPreset::PaperSheet.object();
    let leaf = app
        .world_mut()
        .spawn((sheet.clone(), Transform::from_xyz(0.0, 10.0, 0.0)))
        .id();
    app.update();
    app.world_mut().entity_mut(leaf).remove::<FallingObject>();
    app.update();
    // Put back 5 m up: released again from there (before, the memo of the first release
    // outlived the component, and the old fall, let go at 10 m, went on).
    app.world_mut()
        .entity_mut(leaf)
        .insert((sheet, Transform::from_xyz(3.0, 5.0, 0.0)));
    app.update();
    let path = app
        .world()
        .resource::<FallStore>()
        .fall(leaf)
        .expect("a fall");
    assert!(
        path.position().distance(Vec3::new(3.0, 5.0, 0.0)) < 0.5,
        "{}",
        path.position()
    );
    for _ in 0..20 {
        app.update();
    }
    assert!(app.world().get::<Transform>(leaf).unwrap().translation.y < 5.0);
}

/// Systems with nothing to do do not run (each would cost a thread wake-up a frame), yet
/// whatever is spawned after a long idle stretch moves from its first frames, and what is
/// removed last is cleared: the last wind source and shelter leave the field, the last invalid
/// levels of detail lose their error.
#[test]
fn idle_plugins_wake_for_what_comes_later_and_clear_what_goes() {
    let mut app = full_app();
    for _ in 0..20 {
        app.update();
    }
    let leaf = app
        .world_mut()
        .spawn((
            FallPreset::MapleLeaf.object(),
            Transform::from_xyz(0.0, 6.0, 0.0),
            FallLod(bevy_windfall::lod::LodTiers {
                near: f32::NAN,
                far: 1.0,
            }),
        ))
        .id();
    let cloud = app
        .world_mut()
        .spawn(LeafCloud {
            count: 40,
            ..default()
        })
        .id();
    let flag = app
        .world_mut()
        .spawn((small_flag(), Transform::from_xyz(5.0, 3.0, 0.0)))
        .id();
    let body = app
        .world_mut()
        .spawn((card(), Transform::from_xyz(-5.0, 4.0, 0.0)))
        .id();
    let source = app
        .world_mut()
        .spawn((
            WindSource::sphere(2.0, Vec3::X * 6.0),
            Transform::from_xyz(20.0, 3.0, 20.0),
        ))
        .id();
    let shelter = app
        .world_mut()
        .spawn((
            WindShelter::wall(Vec3::new(0.5, 3.0, 10.0)),
            Transform::from_xyz(-30.0, 0.0, -30.0),
        ))
        .id();
    let cloud_start: Vec<Vec3> = {
        let state = app.world().get::<LeafCloudState>(cloud).unwrap();
        state
            .leaves()
            .unwrap()
            .paths()
            .map(|p| p.position())
            .collect()
    };
    for _ in 0..30 {
        app.update();
    }
    let world = app.world();
    assert!(world.get::<Transform>(leaf).unwrap().translation.y < 5.9);
    assert!(world.get::<Transform>(body).unwrap().translation.y < 3.9);
    let moved = world
        .get::<LeafCloudState>(cloud)
        .unwrap()
        .leaves()
        .unwrap()
        .paths()
        .zip(&cloud_start)
        .filter(|(p, start)| p.position().distance(**start) > 0.01)
        .count();
    assert_eq!(moved, cloud_start.len(), "every cloud leaf moves");
    let mesh = world.get::<Mesh3d>(flag).expect("the flag has its mesh");
    assert!(world.resource::<Assets<Mesh>>().get(&mesh.0).is_some());
    let field = world.resource::<WindField>();
    assert_eq!((field.source_count(), field.shelter_count()), (1, 1));
    assert!(field.velocity(Vec3::new(20.0, 3.0, 20.0)).x > field.mean_speed_at(3.0) + 3.0);
    assert!(world.get::<bevy_windfall::lod::LodInvalid>(leaf).is_some());
    // The last of each goes.
    app.world_mut().despawn(source);
    app.world_mut().despawn(shelter);
    app.world_mut().entity_mut(leaf).remove::<FallLod>();
    app.update();
    app.update();
    let field = app.world().resource::<WindField>();
    assert_eq!((field.source_count(), field.shelter_count()), (0, 0));
    assert!(
        app.world()
            .get::<bevy_windfall::lod::LodInvalid>(leaf)
            .is_none()
    );
}

/// A hitch: one rendered frame asked for 16 fixed steps (at Bevy's default 64 Hz its largest, a
/// quarter of a second; at this app's 60 Hz its 0.25 s `max_delta` runs 14 of them) moves a
/// physical cloth by `ParticleCloth::MAX_STEP` (50 ms) only, the same cloth as three frames of
/// one fixed step each (12 ticks of 4 ms either way), in a steady wind; the rest of the hitch is
/// dropped.
#[test]
fn a_hitch_costs_a_physical_cloth_three_frames_of_work() {
    let steady = WindConfig {
        reference_speed: 6.0,
        turbulence_intensity: Some(0.0),
        ..default()
    };
    let run = |frames: u32, steps_per_frame: u32| {
        let mut app = headless_app_with_meshes();
        app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(steady.clone())));
        let cloth = app
            .world_mut()
            .spawn((physical_flag(), Transform::from_xyz(0.0, 3.0, 0.0)))
            .id();
        ready(&mut app);
        app.insert_resource(TimeUpdateStrategy::FixedTimesteps(steps_per_frame));
        for _ in 0..frames {
            app.update();
        }
        let state = app.world().get::<PhysicalClothState>(cloth).unwrap();
        state.0.positions().to_vec()
    };
    let hitch = run(1, 16);
    let three = run(3, 1);
    let one = run(1, 1);
    assert_eq!(
        hitch, three,
        "a hitch's frame moves the cloth as three frames do"
    );
    assert_ne!(hitch, one);
}
