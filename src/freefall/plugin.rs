//! The [`FallPlugin`]: steps every [`FallingObject`] on the fixed timestep and poses it once
//! per frame.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::tasks::{ComputeTaskPool, ParallelSliceMut};
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

use super::lod::{FallClock, FallLod, TierClock};
use super::model::FallModel;
use super::model::path::usual::{UsualJob, run_usual};
use super::model::path::{FallPath, StepOutcome, WindTilt};
use super::model::piece::Piece;
use super::object::{FallSettings, FallState, FallingObject, FallingObjectInvalid, Landed};
use crate::lod::LodFocus;
use crate::schedule::WindfallSystems;
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
        app.register_type::<FallingObject>()
            .register_type::<FallState>()
            .register_type::<FallingObjectInvalid>()
            .register_type::<FallSettings>()
            .register_type::<FallLod>()
            .register_type::<crate::lod::LodInvalid>()
            .register_type::<LodFocus>()
            .register_type::<crate::lod::LodView>()
            .register_type::<crate::lod::LodTiers>()
            .register_type::<FallModel>()
            .register_type::<super::presets::FallPreset>()
            .init_resource::<FallSettings>()
            .init_resource::<FallClock>()
            .add_message::<Landed>()
            // Every system runs only when there is something for it: a system the executor hands
            // to a worker costs a thread wake-up even when it has nothing to do.
            .add_systems(
                schedule,
                step_objects
                    .in_set(WindfallSystems::Simulate)
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

/// What stepping a falling object reads and writes.
type Fall<'a> = (
    Entity,
    &'a FallingObject,
    Mut<'a, FallState>,
    Option<&'a FallLod>,
);

/// Objects a parallel task steps together.
const OBJECT_CHUNK: usize = 256;

/// Steps every fall; objects are independent, so chunks of them run in parallel (with Bevy's
/// `multi_threaded` feature), the usual steps of each chunk four at a time in SIMD lanes, and
/// the landings are written sorted by entity, so neither the messages nor any bit depends on the
/// thread schedule. An object with [`FallLod`] is stepped when its tier is due (see
/// [`crate::lod`]), over the time since its last step.
#[allow(clippy::too_many_arguments)]
fn step_objects(
    mut objects: Query<(Entity, &FallingObject, &mut FallState, Option<&FallLod>)>,
    foci: crate::lod::Foci,
    wind: Option<Res<WindField>>,
    model: Option<Res<FallModel>>,
    time: Res<Time>,
    mut clock: ResMut<FallClock>,
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
    let dt = time.delta_secs();
    clock.tick(dt);
    let step = ObjectStep {
        model: &model,
        wind: wind.as_deref(),
        focus: crate::lod::focus(&foci),
        clock: *clock,
        dt,
        lanes: crate::math::lanes_enabled(),
    };
    let mut falls: Vec<Fall> = objects.iter_mut().collect();
    let mut landings: Vec<Landed> = match ComputeTaskPool::try_get() {
        Some(pool) if falls.len() > OBJECT_CHUNK => falls
            .par_chunk_map_mut(pool, OBJECT_CHUNK, |_, chunk| step_chunk(chunk, &step))
            .into_iter()
            .flatten()
            .collect(),
        _ => falls
            .chunks_mut(OBJECT_CHUNK)
            .flat_map(|chunk| step_chunk(chunk, &step))
            .collect(),
    };
    landings.sort_by_key(|l| l.entity);
    landed.write_batch(landings);
}

/// What the chunks of one step share.
struct ObjectStep<'a> {
    model: &'a FallModel,
    wind: Option<&'a WindField>,
    focus: Option<crate::lod::Focus>,
    clock: FallClock,
    dt: f32,
    lanes: bool,
}

/// Steps a chunk of objects: the usual steps in lanes, the rest one at a time; returns the
/// landings.
fn step_chunk(chunk: &mut [Fall], step: &ObjectStep) -> Vec<Landed> {
    let (clock, dt) = (step.clock, step.dt);
    let mut landings = Vec::new();
    // The objects due this step, and where they are.
    let (mut due, mut positions) = (Vec::new(), Vec::new());
    for (i, (entity, _, state, lod)) in chunk.iter_mut().enumerate() {
        let state = &mut **state;
        let Some(path) = state.path.as_ref() else {
            continue;
        };
        // Its first step with levels of detail is taken at once (a fall just let go does
        // not wait for its turn), as if it had been stepped on the step before.
        let first = state.tier.is_none() && lod.is_some();
        if first {
            state.tier = Some(TierClock::stepped_at(clock.seconds - f64::from(dt), dt));
        }
        let tier = lod
            .zip(step.focus)
            .map_or(1, |(l, f)| f.tier(&l.0, path.position()));
        if first || clock.due(tier, entity.index_u32()) {
            due.push((i, tier));
            positions.push(path.position());
        }
    }
    // Resting objects feel the wind too: a strong enough one lifts them again. Four points
    // at a time.
    let mut winds = Vec::new();
    match step.wind {
        Some(w) => w.velocities(&positions, &mut winds),
        None => winds.resize(positions.len(), Vec3::ZERO),
    }
    let (mut swings, mut curves) = (Vec::new(), Vec::new());
    for (&(i, tier), velocity) in due.iter().zip(winds) {
        let (entity, object, state, lod) = &mut chunk[i];
        let state = &mut **state;
        let Some(path) = state.path.as_mut() else {
            continue;
        };
        let tilt = WindTilt::in_wind(object.wind_tilt, step.wind);
        let job = UsualJob::new(i, velocity, dt, tilt);
        if step.lanes && state.tier.is_none() && path.usual(job.dt) {
            match path.piece() {
                Piece::Swing { .. } => swings.push(job),
                Piece::Curve { .. } => curves.push(job),
            }
            continue;
        }
        let outcome = match state.tier.as_mut() {
            Some(t) => {
                let next = clock.steps_to_next(tier, entity.index_u32()) as f32 * dt;
                let (outcome, _) =
                    t.advance(path, step.model, clock.seconds, next, velocity, &tilt);
                // Back at full detail for good (the component was removed) once eased.
                if lod.is_none() && !t.easing(clock.seconds) {
                    state.tier = None;
                }
                outcome
            }
            None => path.advance(step.model, dt, velocity, &tilt),
        };
        if outcome == StepOutcome::Landed {
            landings.push(landing(*entity, path));
        }
    }
    let db = step.model.database();
    for jobs in [&swings, &curves] {
        run_usual(chunk, jobs, path_of, db, |fall, _, landed| {
            if landed && let Some(path) = fall.2.path.as_ref() {
                landings.push(landing(fall.0, path));
            }
        });
    }
    landings
}

/// The fall of an object whose usual step is being taken (it has one).
fn path_of<'a>(fall: &'a mut Fall<'_>) -> &'a mut FallPath {
    fall.2.path.as_mut().expect("a usual step has a path")
}

/// The message of `entity`'s fall reaching the ground.
fn landing(entity: Entity, path: &FallPath) -> Landed {
    Landed {
        entity,
        position: path.position(),
        flight_time: path.time(),
    }
}

fn pose_objects(
    mut objects: Query<(&FallState, &mut Transform)>,
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    clock: Option<Res<FallClock>>,
) {
    let s = crate::schedule::overstep(schedule.as_deref(), time.as_deref());
    let clock = clock.as_deref().copied().unwrap_or_default();
    let now = clock.seconds + f64::from(s * clock.last_dt);
    objects.par_iter_mut().for_each(|(state, mut transform)| {
        if let Some(path) = state.path() {
            let (position, rotation): (Vec3, Quat) = match &state.tier {
                Some(tier) => tier.shown(path, now),
                None => path.smoothed(s),
            };
            transform.translation = position;
            transform.rotation = rotation;
        }
    });
}
