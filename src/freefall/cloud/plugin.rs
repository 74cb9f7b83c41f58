//! ECS glue: [`LeafCloudState`] and the [`LeafCloudPlugin`].

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::tasks::ComputeTaskPool;
use bevy::time::{Fixed, Time};

use super::leaves::{CloudLeaves, CloudStep, CloudStepReport, LeafPose};
use super::{CloudRegion, LeafCloud};
use crate::WindfallSystems;
use crate::freefall::path::WindTilt;
use crate::freefall::{FallModel, FreeFallError, FreeFallSettings};
use crate::lod::{LodFocus, LodTiers};
use crate::wind::WindField;

/// Runtime state of a [`LeafCloud`] (required component): its leaves, what the last step did
/// and the poses to draw.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct LeafCloudState {
    #[reflect(ignore)]
    leaves: Option<CloudLeaves>,
    #[reflect(ignore)]
    poses: Vec<LeafPose>,
    /// What the last fixed step did.
    #[reflect(ignore)]
    last: CloudStepReport,
    #[reflect(ignore)]
    released_for: Option<LeafCloud>,
}

impl LeafCloudState {
    /// The leaves, once the cloud is set up.
    pub fn leaves(&self) -> Option<&CloudLeaves> {
        self.leaves.as_ref()
    }

    /// Every leaf's shown pose this frame, in order (written in `PostUpdate`).
    pub fn poses(&self) -> &[LeafPose] {
        &self.poses
    }

    /// What the last fixed step did.
    pub fn last_step(&self) -> CloudStepReport {
        self.last
    }
}

/// Why a [`LeafCloud`] does not fall: the error names the field. Inserted in place of the
/// leaves (logged once), removed once the component is changed and valid.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct LeafCloudInvalid(pub FreeFallError);

/// Steps every [`LeafCloud`] on the fixed timestep (in [`WindfallSystems::Simulate`]) and poses
/// its leaves once per frame (in [`WindfallSystems::WriteBack`]).
#[derive(Default)]
pub struct LeafCloudPlugin;

impl Plugin for LeafCloudPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        let schedule = crate::simulation_schedule(app);
        if !app.world().contains_resource::<FallModel>() {
            app.insert_resource(FallModel::default());
        }
        app.register_type::<LeafCloud>()
            .register_type::<LeafCloudState>()
            .register_type::<LeafCloudInvalid>()
            .register_type::<LodFocus>()
            .register_type::<crate::lod::LodView>()
            .register_type::<CloudRegion>()
            .register_type::<LodTiers>()
            .init_resource::<FreeFallSettings>()
            .add_observer(release_on_insert)
            // Only with a cloud to move (a system with nothing to do still costs a wake-up).
            .add_systems(
                schedule,
                step_clouds
                    .in_set(WindfallSystems::Simulate)
                    .run_if(any_with_component::<LeafCloud>),
            )
            .add_systems(
                PostUpdate,
                (
                    release_clouds.run_if(any_with_component::<LeafCloud>),
                    pose_clouds.run_if(any_with_component::<LeafCloudState>),
                )
                    .chain()
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}

fn release_on_insert(
    event: On<Insert, LeafCloud>,
    mut commands: Commands,
    mut clouds: Query<(&LeafCloud, &mut LeafCloudState)>,
    settings: Option<Res<FreeFallSettings>>,
    model: Option<Res<FallModel>>,
) {
    let Some(model) = model else {
        return;
    };
    let ground = settings.map_or(0.0, |s| s.ground_height);
    if let Ok((cloud, mut state)) = clouds.get_mut(event.entity) {
        release(
            &mut commands,
            event.entity,
            cloud,
            &mut state,
            ground,
            &model,
        );
    }
}

fn release_clouds(
    mut commands: Commands,
    mut clouds: Query<(Entity, &LeafCloud, &mut LeafCloudState), Changed<LeafCloud>>,
    settings: Option<Res<FreeFallSettings>>,
    model: Option<Res<FallModel>>,
) {
    let Some(model) = model else {
        return;
    };
    let ground = settings.map_or(0.0, |s| s.ground_height);
    for (entity, cloud, mut state) in &mut clouds {
        if !state.released_for.as_ref().is_some_and(|r| same(r, cloud)) {
            release(&mut commands, entity, cloud, &mut state, ground, &model);
        }
    }
}

/// The same description, NaN fields included (a NaN is not equal to itself, so `==` alone would
/// release an invalid cloud again, and log it again, every time it is touched).
fn same(a: &LeafCloud, b: &LeafCloud) -> bool {
    a == b || format!("{a:?}") == format!("{b:?}")
}

fn release(
    commands: &mut Commands,
    entity: Entity,
    cloud: &LeafCloud,
    state: &mut LeafCloudState,
    ground: f32,
    model: &FallModel,
) {
    state.released_for = Some(cloud.clone());
    state.poses.clear();
    state.last = CloudStepReport::default();
    match cloud.leaves(model, ground) {
        Ok(leaves) => {
            state.leaves = Some(leaves);
            commands.entity(entity).remove::<LeafCloudInvalid>();
        }
        Err(error) => {
            bevy::log::warn!("LeafCloud {entity}: {error}; it does not fall");
            state.leaves = None;
            commands.entity(entity).insert(LeafCloudInvalid(error));
        }
    }
}

fn step_clouds(
    mut clouds: Query<(&LeafCloud, &mut LeafCloudState)>,
    foci: crate::lod::Foci,
    wind: Option<Res<WindField>>,
    model: Option<Res<FallModel>>,
    time: Res<Time>,
) {
    let Some(model) = model else {
        return;
    };
    let focus = crate::lod::focus(&foci);
    let reference_speed = wind.as_deref().map_or(1.0, |w| w.config().reference_speed);
    let pool = ComputeTaskPool::try_get().map(|p| &**p);
    for (cloud, mut state) in &mut clouds {
        let step = CloudStep {
            model: &model,
            wind: wind.as_deref(),
            dt: time.delta_secs(),
            tilt: WindTilt {
                max_angle: cloud.object.wind_tilt,
                reference_speed,
            },
            focus,
        };
        let state = &mut *state;
        if let Some(leaves) = state.leaves.as_mut() {
            state.last = leaves.step(&step, pool);
        }
    }
}

fn pose_clouds(
    mut clouds: Query<&mut LeafCloudState>,
    schedule: Option<Res<crate::WindfallSchedule>>,
    fixed: Option<Res<Time<Fixed>>>,
) {
    let s = crate::overstep(schedule.as_deref(), fixed.as_deref());
    let pool = ComputeTaskPool::try_get().map(|p| &**p);
    for mut state in &mut clouds {
        let state = &mut *state;
        match state.leaves.as_ref() {
            Some(leaves) => leaves.poses(s, pool, &mut state.poses),
            None => state.poses.clear(),
        }
    }
}
