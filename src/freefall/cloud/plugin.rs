//! ECS glue: [`LeafCloudState`] and the [`LeafCloudPlugin`].

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::tasks::ComputeTaskPool;
use bevy::time::{Fixed, Time};

use super::leaves::{CloudLeaves, CloudStep, CloudStepReport, LeafPose};
use super::{CloudRegion, LeafCloud, LeafCloudInvalid};
use crate::freefall::model::FallModel;
use crate::freefall::model::error::FallError;
use crate::freefall::object::FallSettings;
use crate::lifecycle::Described;
use crate::schedule::{SimulateSystems, WindfallSystems};
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

crate::schedule::simulation_plugin!(
    /// Steps every [`LeafCloud`] on the fixed timestep (in [`WindfallSystems::Simulate`]) and poses
    /// its leaves once per frame (in [`WindfallSystems::WriteBack`]).
    LeafCloudPlugin
);

impl Plugin for LeafCloudPlugin {
    fn build(&self, app: &mut App) {
        let schedule = self.configure(app);
        crate::lifecycle::observe::<LeafCloud>(app);
        if !app.world().contains_resource::<FallModel>() {
            app.insert_resource(FallModel::default());
        }
        crate::lod::register_types(app);
        app.register_type::<LeafCloud>()
            .register_type::<LeafCloudState>()
            .register_type::<LeafCloudInvalid>()
            .register_type::<CloudRegion>()
            .init_resource::<FallSettings>()
            // Only with a cloud to move (a system with nothing to do still costs a wake-up).
            .add_systems(
                schedule,
                step_clouds
                    .in_set(SimulateSystems::Clouds)
                    .run_if(any_with_component::<LeafCloud>),
            )
            .add_systems(
                PostUpdate,
                (
                    (
                        crate::lifecycle::set_up_pending::<LeafCloud>
                            .run_if(resource_added::<FallModel>),
                        crate::lifecycle::set_up_changed::<LeafCloud>,
                    )
                        .chain()
                        .run_if(any_with_component::<LeafCloud>),
                    pose_clouds.run_if(any_with_component::<LeafCloudState>),
                )
                    .chain()
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}

impl Described for LeafCloud {
    type Invalid = LeafCloudInvalid;
    type Key = LeafCloud;
    type Data = &'static mut LeafCloudState;
    type Context = (
        Option<Res<'static, FallSettings>>,
        Option<Res<'static, FallModel>>,
    );
    const SUBJECT: &'static str = "LeafCloud";
    const CONSEQUENCE: &'static str = "it does not fall";

    /// The cloud without its leaves' look: a new look redraws them, it does not let them go
    /// again (as for a single [`FallingObject`](crate::freefall::FallingObject)).
    fn key(&self) -> LeafCloud {
        let mut key = self.clone();
        key.object.look = None;
        key
    }

    /// Lets every leaf go; without a model (removed by the user) nothing is released.
    fn set_up(
        &self,
        _: Entity,
        mut state: Mut<LeafCloudState>,
        (settings, model): &mut (Option<Res<FallSettings>>, Option<Res<FallModel>>),
        _: &mut Commands,
    ) -> Option<Result<(), FallError>> {
        let model = model.as_deref()?;
        let ground = settings.as_ref().map_or(0.0, |s| s.ground_height);
        state.poses.clear();
        state.last = CloudStepReport::default();
        Some(match self.leaves(model, ground) {
            Ok(leaves) => {
                state.leaves = Some(leaves);
                Ok(())
            }
            Err(error) => {
                state.leaves = None;
                Err(error)
            }
        })
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
    let pool = ComputeTaskPool::try_get().map(|p| &**p);
    for (cloud, mut state) in &mut clouds {
        let step = CloudStep {
            model: &model,
            wind: wind.as_deref(),
            dt: time.delta_secs(),
            wind_tilt: cloud.object.wind_tilt,
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
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    fixed: Option<Res<Time<Fixed>>>,
) {
    let s = crate::schedule::overstep(schedule.as_deref(), fixed.as_deref());
    let pool = ComputeTaskPool::try_get().map(|p| &**p);
    for mut state in &mut clouds {
        let state = &mut *state;
        match state.leaves.as_ref() {
            Some(leaves) => leaves.poses(s, pool, &mut state.poses),
            None => state.poses.clear(),
        }
    }
}
