//! Hostile input, round 4: the shared lifecycle of the described components (`FallingObject`,
//! `LeafCloud`, `Cloth`, `PhysicalCloth`) and the order of the crate's sets in the schedules a
//! user may pass. Items 1–6 of the round's probe, and a randomised sweep of insert, change,
//! remove and despawn sequences.

use crate::common;

use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_windfall::aero::{PhysicalCloth, PhysicalClothInvalid};
use bevy_windfall::cloth::ClothInvalid;
use bevy_windfall::freefall::{
    CloudRegion, FallModel, FallPreset, FallingObjectInvalid, LeafCloudInvalid, LeafCloudState,
};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindSourceInvalid;
use common::{headless_app_with_meshes, ready};
use proptest::prelude::*;

fn app() -> App {
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default());
    ready(&mut app);
    app
}

fn cloud() -> LeafCloud {
    LeafCloud {
        object: FallPreset::MapleLeaf.object(),
        count: 50,
        seed: 3,
        region: CloudRegion {
            min: Vec3::new(-5.0, 6.0, -5.0),
            max: Vec3::new(5.0, 9.0, 5.0),
        },
        ..default()
    }
}

fn small_grid() -> ClothGrid {
    ClothGrid {
        rows: 4,
        columns: 6,
        ..default()
    }
}

/// How often a marker `M` was inserted on any entity.
#[derive(Resource, Default)]
struct Inserts(usize);

fn count_inserts<M: Component>(app: &mut App) {
    app.init_resource::<Inserts>()
        .add_observer(|_: On<Insert<M>>, mut n: ResMut<Inserts>| n.0 += 1);
}

/// Item 1: a new look for a cloud's leaves redraws them; it does not let the cloud go again.
#[test]
fn a_clouds_new_look_does_not_let_its_leaves_go_again() {
    let mut app = app();
    let entity = app.world_mut().spawn(cloud()).id();
    for _ in 0..60 {
        app.update();
    }
    let clock = |app: &App| {
        let state = app.world().get::<LeafCloudState>(entity).unwrap();
        state.leaves().unwrap().clock()
    };
    let before = clock(&app);
    assert!(before > 0.9, "a second of falling: {before}");
    app.world_mut()
        .get_mut::<LeafCloud>(entity)
        .unwrap()
        .object
        .look = Some(FallPreset::PaperSheet);
    app.update();
    assert!(
        clock(&app) > before,
        "the cloud's clock went from {before} s to {} s on a new look",
        clock(&app)
    );
    // Its motion is a change that does: a new seed lets the leaves go again.
    app.world_mut().get_mut::<LeafCloud>(entity).unwrap().seed += 1;
    app.update();
    assert!(clock(&app) < 0.1, "{}", clock(&app));
}

/// Item 2: a valid edit of a cloth whose transform is still NaN keeps its marker: one insert
/// (one warning) however many edits and frames.
#[test]
fn an_edit_does_not_clear_a_marker_whose_cause_remains() {
    for physical in [false, true] {
        let mut app = app();
        if physical {
            count_inserts::<PhysicalClothInvalid>(&mut app);
        } else {
            count_inserts::<ClothInvalid>(&mut app);
        }
        let nan = Transform::from_xyz(f32::NAN, 2.0, 0.0);
        let entity = if physical {
            let cloth = PhysicalCloth {
                grid: small_grid(),
                ..default()
            };
            app.world_mut().spawn((cloth, nan)).id()
        } else {
            let cloth = Cloth {
                grid: small_grid(),
                ..default()
            };
            app.world_mut().spawn((cloth, nan)).id()
        };
        for frame in 0..6 {
            app.update();
            let mut e = app.world_mut().entity_mut(entity);
            if physical {
                e.get_mut::<PhysicalCloth>().unwrap().areal_density = 0.1 + 0.01 * frame as f32;
            } else {
                e.get_mut::<Cloth>().unwrap().params.amplitude = 0.5 + 0.01 * frame as f32;
            }
        }
        app.update();
        let world = app.world();
        let marked = if physical {
            world
                .get::<PhysicalClothInvalid>(entity)
                .map(|m| m.0.field())
        } else {
            world.get::<ClothInvalid>(entity).map(|m| m.0.field())
        };
        assert_eq!(marked, Some("transform"), "physical: {physical}");
        assert_eq!(
            world.resource::<Inserts>().0,
            1,
            "physical: {physical}: the marker was inserted again"
        );
        // Fixed, the marker goes.
        *app.world_mut().get_mut::<Transform>(entity).unwrap() = Transform::from_xyz(0.0, 2.0, 0.0);
        app.update();
        app.update();
        let world = app.world();
        assert!(world.get::<PhysicalClothInvalid>(entity).is_none());
        assert!(world.get::<ClothInvalid>(entity).is_none());
    }
}

/// Item 2, for sources: a valid source inserted again on a NaN transform is reported once.
#[test]
fn a_source_inserted_again_on_a_nan_transform_is_reported_once() {
    let mut app = app();
    count_inserts::<WindSourceInvalid>(&mut app);
    let fan = WindSource::fan(10.0, 0.4, 3.0);
    let entity = app
        .world_mut()
        .spawn((fan, Transform::from_xyz(f32::NAN, 1.0, 0.0)))
        .id();
    for _ in 0..7 {
        app.update();
        app.world_mut().entity_mut(entity).insert(fan);
    }
    app.update();
    assert!(app.world().get::<WindSourceInvalid>(entity).is_some());
    assert_eq!(app.world().resource::<Inserts>().0, 1);
}

/// Item 3: removing a described component takes its marker with it.
#[test]
fn removing_a_description_removes_its_marker() {
    let mut app = app();
    let bad_fall = FallingObject {
        density: f32::NAN,
        ..default()
    };
    let bad_grid = ClothGrid {
        columns: 1,
        ..small_grid()
    };
    let mut bad_cloud = cloud();
    bad_cloud.object.density = -1.0;
    let place = Transform::from_xyz(0.0, 3.0, 0.0);
    let world = app.world_mut();
    let fall = world.spawn((bad_fall, place)).id();
    let cloth = world
        .spawn((
            Cloth {
                grid: bad_grid,
                ..default()
            },
            place,
        ))
        .id();
    let physical = world
        .spawn((
            PhysicalCloth {
                grid: bad_grid,
                ..default()
            },
            place,
        ))
        .id();
    let leaves = world.spawn(bad_cloud).id();
    app.update();
    let world = app.world();
    assert!(world.get::<FallingObjectInvalid>(fall).is_some());
    assert!(world.get::<ClothInvalid>(cloth).is_some());
    assert!(world.get::<PhysicalClothInvalid>(physical).is_some());
    assert!(world.get::<LeafCloudInvalid>(leaves).is_some());
    let world = app.world_mut();
    world.entity_mut(fall).remove::<FallingObject>();
    world.entity_mut(cloth).remove::<Cloth>();
    world.entity_mut(physical).remove::<PhysicalCloth>();
    world.entity_mut(leaves).remove::<LeafCloud>();
    app.update();
    let world = app.world();
    assert!(world.get::<FallingObjectInvalid>(fall).is_none());
    assert!(world.get::<ClothInvalid>(cloth).is_none());
    assert!(world.get::<PhysicalClothInvalid>(physical).is_none());
    assert!(world.get::<LeafCloudInvalid>(leaves).is_none());
}

/// Item 4: objects and clouds spawned while the `FallModel` is gone start when it returns.
#[test]
fn falls_spawned_without_a_model_start_when_it_returns() {
    let mut app = app();
    app.world_mut().remove_resource::<FallModel>();
    app.update();
    let fall = app
        .world_mut()
        .spawn((
            FallPreset::MapleLeaf.object(),
            Transform::from_xyz(0.0, 5.0, 0.0),
        ))
        .id();
    let leaves = app.world_mut().spawn(cloud()).id();
    for _ in 0..10 {
        app.update();
    }
    assert!(app.world().resource::<FallStore>().fall(fall).is_none());
    app.world_mut().insert_resource(FallModel::default());
    for _ in 0..30 {
        app.update();
    }
    let world = app.world();
    let path = world.resource::<FallStore>().fall(fall);
    assert!(path.is_some_and(|p| p.position().y < 5.0), "the leaf fell");
    let state = world.get::<LeafCloudState>(leaves).unwrap();
    assert!(
        state
            .leaves()
            .is_some_and(|l| l.len() == 50 && l.clock() > 0.4)
    );
}

/// Changes `Doomed` entities' descriptions in `Update` and despawns them in `PostUpdate`.
#[derive(Component)]
struct Doomed;

fn edit_doomed(
    mut cloths: Query<&mut Cloth, With<Doomed>>,
    mut falls: Query<&mut FallingObject, With<Doomed>>,
) {
    for mut cloth in &mut cloths {
        cloth.params.amplitude *= 0.9;
    }
    for mut fall in &mut falls {
        fall.density = f32::NAN;
    }
}

fn despawn_doomed(mut commands: Commands, doomed: Query<Entity, With<Doomed>>) {
    for entity in &doomed {
        commands.entity(entity).despawn();
    }
}

/// Item 5: a user's system that despawns, in `PostUpdate`, entities whose descriptions changed
/// (or were refused) that frame: no panic, whatever the order.
#[test]
fn despawning_in_post_update_an_entity_changed_that_frame_is_fine() {
    for round in 0..3 {
        let mut app = app();
        app.add_systems(Update, edit_doomed).add_systems(
            PostUpdate,
            // Its despawns applied at the sync point after the crate's set-up, before the
            // inserts the set-up queued.
            despawn_doomed.before_ignore_deferred(WindfallSystems::WriteBack),
        );
        for i in 0..4 {
            let place = Transform::from_xyz(i as f32, 3.0, 0.0);
            let world = app.world_mut();
            world.spawn((
                Cloth {
                    grid: small_grid(),
                    ..default()
                },
                place,
            ));
            world.spawn((FallPreset::PaperSheet.object(), place));
        }
        app.update();
        let world = app.world_mut();
        let all: Vec<Entity> = world
            .query_filtered::<Entity, Or<(With<Cloth>, With<FallingObject>)>>()
            .iter(world)
            .collect();
        for entity in all {
            world.entity_mut(entity).insert(Doomed);
        }
        for _ in 0..3 {
            app.update();
        }
        let world = app.world_mut();
        let left = world.query::<&Cloth>().iter(world).count();
        assert_eq!(left, 0, "round {round}");
    }
}

/// Item 6: in every schedule a user may pass, a fall's pose shows the step just taken.
#[test]
fn in_any_schedule_the_pose_shows_the_step_just_taken() {
    fn check(schedule: impl ScheduleLabel + Clone) {
        let label = format!("{schedule:?}");
        let mut app = common::headless_app();
        app.add_plugins(WindfallPlugins::new(schedule))
            .insert_resource(TimeUpdateStrategy::ManualDuration(
                std::time::Duration::from_millis(40),
            ));
        ready(&mut app);
        let leaf = app
            .world_mut()
            .spawn((
                FallPreset::PaperSheet.object(),
                Transform::from_xyz(0.0, 10.0, 0.0),
            ))
            .id();
        for frame in 0..40 {
            app.update();
            let world = app.world();
            let shown = world.get::<Transform>(leaf).unwrap().translation;
            let path = world.resource::<FallStore>().fall(leaf).unwrap();
            let latest = path.position();
            assert!(
                shown.distance(latest) < 1e-4,
                "{label}, frame {frame}: shown {shown}, latest step {latest}"
            );
        }
    }
    check(PreUpdate);
    check(Update);
    check(PostUpdate);
}

/// What a randomised sequence does to one of three entities.
#[derive(Clone, Copy, Debug)]
enum Op {
    /// Inserts a valid (true) or refused (false) description of kind `kind` (0–3).
    Insert(usize, bool),
    /// Edits the description it has to a valid or refused one.
    Edit(bool),
    Remove,
    Despawn,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (0usize..4, any::<bool>()).prop_map(|(k, ok)| Op::Insert(k, ok)),
        any::<bool>().prop_map(Op::Edit),
        Just(Op::Remove),
        Just(Op::Despawn),
    ]
}

/// The description of kind `kind`, valid or not (and told apart by a seed-like field).
fn describe(e: &mut EntityWorldMut, kind: usize, ok: bool, n: u32) {
    let grid = ClothGrid {
        columns: if ok { 6 } else { 1 },
        ..small_grid()
    };
    match kind {
        0 => {
            let mut fall = FallPreset::MapleLeaf.object();
            fall.seed = u64::from(n);
            fall.density = if ok { fall.density } else { f32::NAN };
            e.insert(fall);
        }
        1 => {
            let mut leaves = cloud();
            leaves.count = 8;
            leaves.seed = u64::from(n);
            leaves.object.density = if ok { 500.0 } else { -1.0 };
            e.insert(leaves);
        }
        2 => {
            let mut cloth = Cloth { grid, ..default() };
            cloth.params.seed = u64::from(n);
            e.insert(cloth);
        }
        _ => {
            let cloth = PhysicalCloth {
                grid,
                areal_density: 0.1 + n as f32 * 1e-3,
                ..default()
            };
            e.insert(cloth);
        }
    }
}

/// Which described kind the entity has now, if any.
fn kind_of(e: &EntityRef) -> Option<usize> {
    [
        e.contains::<FallingObject>(),
        e.contains::<LeafCloud>(),
        e.contains::<Cloth>(),
        e.contains::<PhysicalCloth>(),
    ]
    .iter()
    .position(|&has| has)
}

fn markers(e: &EntityRef) -> [bool; 4] {
    [
        e.contains::<FallingObjectInvalid>(),
        e.contains::<LeafCloudInvalid>(),
        e.contains::<ClothInvalid>(),
        e.contains::<PhysicalClothInvalid>(),
    ]
}

/// A slot's entity and the description it has now: (kind, valid), or none.
type Slot = (Entity, Option<(usize, bool)>);

fn run_sequence(schedule: usize, ops: &[(usize, Op)]) {
    let mut app = headless_app_with_meshes();
    match schedule {
        0 => app.add_plugins(WindfallPlugins::default()),
        1 => app.add_plugins(WindfallPlugins::new(Update)),
        _ => app.add_plugins(WindfallPlugins::new(PostUpdate)),
    };
    ready(&mut app);
    let place = Transform::from_xyz(0.0, 4.0, 0.0);
    let mut slots: Vec<Option<Slot>> = vec![None; 3];
    for (n, &(slot, op)) in ops.iter().enumerate() {
        let n = n as u32;
        let world = app.world_mut();
        let current = slots[slot];
        match (op, current) {
            (Op::Insert(kind, ok), None) => {
                let mut e = world.spawn(place);
                describe(&mut e, kind, ok, n);
                slots[slot] = Some((e.id(), Some((kind, ok))));
            }
            (Op::Insert(kind, ok), Some((entity, described))) => {
                let mut e = world.entity_mut(entity);
                // One description an entity: a new kind replaces the old one.
                if described.is_some_and(|(k, _)| k != kind) {
                    e.remove::<(FallingObject, LeafCloud, Cloth, PhysicalCloth)>();
                }
                describe(&mut e, kind, ok, n);
                slots[slot] = Some((entity, Some((kind, ok))));
            }
            (Op::Edit(ok), Some((entity, Some((kind, _))))) => {
                describe(&mut world.entity_mut(entity), kind, ok, n);
                slots[slot] = Some((entity, Some((kind, ok))));
            }
            (Op::Remove, Some((entity, Some(_)))) => {
                world
                    .entity_mut(entity)
                    .remove::<(FallingObject, LeafCloud, Cloth, PhysicalCloth)>();
                slots[slot] = Some((entity, None));
            }
            (Op::Despawn, Some((entity, _))) => {
                world.despawn(entity);
                slots[slot] = None;
            }
            _ => {}
        }
        app.update();
        app.update();
        for (entity, described) in slots.iter().flatten() {
            let e = app.world().entity(*entity);
            let mut expected = [false; 4];
            if let Some((kind, ok)) = described {
                assert_eq!(kind_of(&e), Some(*kind));
                expected[*kind] = !ok;
            }
            assert_eq!(
                markers(&e),
                expected,
                "schedule {schedule}, after {:?}",
                &ops[..=n as usize]
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Random insert, change, remove and despawn sequences over three entities, in the fixed
    /// schedule, `Update` and `PostUpdate`: no panic, and each entity's marker is exactly the
    /// one its current description calls for.
    #[test]
    fn markers_follow_the_description_through_any_lifecycle(
        schedule in 0usize..3,
        ops in prop::collection::vec((0usize..3, op()), 1..14),
    ) {
        run_sequence(schedule, &ops);
    }
}
