//! The [`FallPlugin`]: steps every [`FallingObject`] on the fixed timestep (the app's
//! [`FallStore`], one driver for all of them) and poses it once per frame.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;
use bevy::tasks::ComputeTaskPool;
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

use super::fall_lod::FallLod;
use super::fall_store::FallStore;
use super::model::FallModel;
use super::object::{FallSettings, FallState, FallingObject, FallingObjectInvalid, Landed};
use super::store::air::Air;
use super::store::step::Step;
use crate::schedule::{SimulateSystems, WindfallSystems};
use crate::wind::WindField;

crate::schedule::simulation_plugin!(
    /// Moves every [`FallingObject`] on the fixed timestep and poses it once per frame.
    FallPlugin
);

impl Plugin for FallPlugin {
    fn build(&self, app: &mut App) {
        let schedule = self.configure(app);
        crate::lifecycle::observe::<FallingObject>(app);
        if !app.world().contains_resource::<FallModel>() {
            app.insert_resource(FallModel::default());
        }
        crate::lod::register_types(app);
        app.register_type::<FallingObject>()
            .register_type::<FallState>()
            .register_type::<FallingObjectInvalid>()
            .register_type::<FallSettings>()
            .register_type::<FallLod>()
            .register_type::<FallModel>()
            .register_type::<super::object::FallPreset>()
            .init_resource::<FallSettings>()
            .init_resource::<FallStore>()
            .add_message::<Landed>()
            .add_observer(forget_fall)
            // Every system runs only when there is something for it: a system the executor hands
            // to a worker costs a thread wake-up even when it has nothing to do.
            .add_systems(
                schedule,
                step_objects
                    .in_set(SimulateSystems::Falls)
                    .run_if(any_with_component::<FallingObject>),
            )
            // Releasing here (not in the simulation) reads the transform the user set this
            // frame before `pose_objects` would overwrite it.
            .add_systems(
                PostUpdate,
                (
                    (
                        crate::lifecycle::set_up_pending::<FallingObject>
                            .run_if(resource_added::<FallModel>),
                        crate::lifecycle::set_up_changed::<FallingObject>,
                        take_lod,
                        pose_objects,
                    )
                        .chain()
                        .run_if(any_with_component::<FallingObject>),
                    crate::lod::check_tiers::<FallLod>.run_if(crate::lod::any_tiers::<FallLod>),
                )
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}

/// Steps every fall of the app's [`FallStore`] (the bands due, in parallel chunks with Bevy's
/// `multi_threaded` feature; the same bits on any number of threads), then tells each object
/// whose motion changed or that landed or was lifted, and sends the landings sorted by entity.
#[allow(clippy::too_many_arguments)]
fn step_objects(
    mut store: ResMut<FallStore>,
    mut states: Query<&mut FallState>,
    foci: crate::lod::Foci,
    wind: Option<Res<WindField>>,
    model: Option<Res<FallModel>>,
    time: Res<Time>,
    mut landed: MessageWriter<Landed>,
    mut warned: Local<bool>,
) {
    // The model may have been removed: the falls wait, with one warning, until it is back.
    let Some(model) = model else {
        if !std::mem::replace(&mut *warned, true) {
            bevy::log::warn!("FallModel was removed: falling objects hold still until it is back");
        }
        return;
    };
    *warned = false;
    let wind = wind.as_deref();
    let step = Step {
        model: &model,
        air: wind.map_or(Air::Still, Air::Field),
        focus: crate::lod::focus(&foci),
        width: crate::portable::lane_width(),
        recycle_after: None,
    };
    let pool = ComputeTaskPool::try_get().map(|p| &**p);
    let store = &mut *store;
    let report = store.falls.step(time.delta_secs(), &step, pool);
    let mut landings: Vec<Landed> = report
        .landed
        .iter()
        .filter_map(|&h| {
            let fall = store.falls.view(h)?;
            Some(Landed {
                entity: store.entity(h)?,
                position: fall.position(),
                flight_time: fall.time(),
            })
        })
        .collect();
    landings.sort_by_key(|l| l.entity);
    for &handle in report.changed.iter().chain(&report.landed) {
        let (Some(entity), Some(fall)) = (store.entity(handle), store.falls.view(handle)) else {
            continue;
        };
        if let Ok(mut state) = states.get_mut(entity) {
            state.mirror(fall.motion(), fall.landed());
        }
    }
    landed.write_batch(landings);
}

/// A [`FallingObject`] removed (or its entity despawned) takes its fall with it.
fn forget_fall(
    event: On<Remove<FallingObject>>,
    store: Option<ResMut<FallStore>>,
    mut states: Query<&mut FallState>,
) {
    if let Some(mut store) = store {
        store.remove(event.entity);
    }
    if let Ok(mut state) = states.get_mut(event.entity) {
        *state = FallState::default();
    }
}

/// Takes in each object's levels of detail when its [`FallLod`] is added, changed or removed.
fn take_lod(
    mut store: ResMut<FallStore>,
    changed: Query<(Entity, &FallLod), Changed<FallLod>>,
    mut removed: RemovedComponents<FallLod>,
) {
    for (entity, lod) in &changed {
        store.set_lod(entity, Some(lod.0).filter(|l| l.check().is_ok()));
    }
    for entity in removed.read() {
        store.set_lod(entity, None);
    }
}

/// Poses every object: its fall's shown pose at the frame's share of the fixed step, taken in
/// the query's pass (one lane wide: the bits the store's lanes give) and written to its
/// transform; in parallel batches only when the compute pool has more than one thread.
fn pose_objects(
    store: Res<FallStore>,
    mut objects: Query<(&FallState, &mut Transform)>,
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
) {
    let s = crate::schedule::overstep(schedule.as_deref(), time.as_deref());
    let falls = &store.falls;
    let now = falls.clock.seconds + f64::from(s * falls.clock.last_dt);
    let pose = |(state, mut transform): (&FallState, Mut<Transform>)| {
        if let Some(pose) = state.handle.and_then(|h| falls.pose(h, now)) {
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
        }
    };
    if ComputeTaskPool::try_get().is_some_and(|p| p.thread_num() > 1) {
        objects.par_iter_mut().for_each(pose);
    } else {
        objects.iter_mut().for_each(pose);
    }
}
