//! When and where the simulation runs: the public system sets ([`WindfallSystems`]), the
//! schedule the plugins were given ([`WindfallSchedule`]) and the overstep that poses bodies
//! between their last two fixed steps.
//!
//! This module is the bottom layer of the crate's ECS glue: every plugin orders its systems by
//! these sets and takes its schedule from its own constructor (as avian's plugins do), never from
//! a resource read while the app is being built.

use bevy::app::{
    App, FixedPostUpdate, FixedPreUpdate, FixedUpdate, PostUpdate, RunFixedMainLoop,
    RunFixedMainLoopSystems,
};
use bevy::ecs::reflect::ReflectResource;
use bevy::ecs::resource::Resource;
use bevy::ecs::schedule::{InternedScheduleLabel, IntoScheduleConfigs, ScheduleLabel, SystemSet};
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};

/// The crate's system sets, public ordering points for your own systems.
///
/// | set | schedule | what |
/// |---|---|---|
/// | `Prepare` | `RunFixedMainLoop`, before the fixed loop | live wind settings are taken in |
/// | `Wind` | the simulation schedule ([`FixedUpdate`]) | a rebuilt field lands; the wind clock advances |
/// | `Simulate` | the simulation schedule, after `Wind` | falling objects, cloth, aero bodies move, one domain after another ([`SimulateSystems`]); in `Update`, only on frames whose time moves |
/// | `WriteBack` | [`PostUpdate`], before transform propagation | objects are released and posed, meshes written |
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WindfallSystems {
    /// Before the fixed loop: what the frame changed is taken in.
    Prepare,
    /// Advance the wind clock.
    Wind,
    /// Move the objects the wind acts on, in the order of [`SimulateSystems`]. In a schedule
    /// that is not on the fixed timestep (`Update`), skipped on a frame whose time does not move
    /// (a paused `Time<Virtual>`), so a paused game shows every body where it was.
    Simulate,
    /// After the simulation, before transform propagation: poses and meshes.
    WriteBack,
}

/// The stages of [`WindfallSystems::Simulate`], one per domain, in this order (each part of the
/// crate steps in its own, as avian's `PhysicsStepSystems` order a physics step): a system of
/// yours can run after the leaves and before the cloth.
///
/// | set | what moves |
/// |---|---|
/// | `Falls` | single falling objects ([`FallingObject`](crate::freefall::FallingObject)) |
/// | `Clouds` | leaf clouds ([`LeafCloud`](crate::freefall::LeafCloud)) |
/// | `Cloth` | procedural cloth ([`Cloth`](crate::cloth::Cloth)) |
/// | `Aero` | rigid aero bodies and particle cloth ([`AeroBody`](crate::aero::AeroBody), [`PhysicalCloth`](crate::aero::PhysicalCloth)) |
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // Reads where the leaves are before the cloth moves.
/// fn between(clouds: Query<&bevy_windfall::freefall::cloud::LeafCloudState>) { let _ = clouds; }
///
/// App::new().add_plugins((MinimalPlugins, WindfallPlugins::default())).add_systems(
///     FixedUpdate,
///     between.after(SimulateSystems::Clouds).before(SimulateSystems::Cloth),
/// );
/// ```
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SimulateSystems {
    /// Single falling objects.
    Falls,
    /// Leaf clouds.
    Clouds,
    /// Procedural cloth.
    Cloth,
    /// Rigid aero bodies and particle cloth.
    Aero,
}

/// The frame-rate schedules in which [`WindfallSystems::Simulate`] waits for time to move.
#[derive(Resource, Default)]
struct PausableIn(Vec<InternedScheduleLabel>);

/// Whether this frame's time moves: in a frame-rate schedule, [`WindfallSystems::Simulate`]
/// runs only then.
fn time_moves(time: bevy::ecs::system::Res<Time>) -> bool {
    time.delta() > std::time::Duration::ZERO
}

/// The schedule the simulation runs in (a resource, inserted by the first plugin added;
/// [`FixedUpdate`] unless the plugins were given another). Read it to know where the
/// [`WindfallSystems::Wind`] and [`WindfallSystems::Simulate`] sets run; the plugins take their
/// schedule from their constructors (`WindfallPlugins::new(schedule)`), not from this resource.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Eq, bevy::reflect::Reflect)]
#[reflect(opaque, Resource, Default, Debug)]
pub struct WindfallSchedule(pub InternedScheduleLabel);

impl Default for WindfallSchedule {
    fn default() -> Self {
        Self(FixedUpdate.intern())
    }
}

impl WindfallSchedule {
    /// Whether the schedule runs on the fixed timestep, so poses between steps are
    /// interpolated.
    pub fn is_fixed(&self) -> bool {
        [
            FixedPreUpdate.intern(),
            FixedUpdate.intern(),
            FixedPostUpdate.intern(),
        ]
        .contains(&self.0)
    }
}

/// The schedule a plugin simulates in: the one it was given, or (`None`, its default) the one
/// already recorded by the group or an earlier plugin, else [`FixedUpdate`]. Plugins keep an
/// `Option` so that a default plugin follows its group (`WindfallPlugins::new(s)` with
/// `.set(WindPlugin::new(config))` runs the wind in `s` too) and can be built in a `const`.
pub(crate) fn resolve(app: &App, schedule: Option<InternedScheduleLabel>) -> InternedScheduleLabel {
    schedule.unwrap_or_else(|| {
        app.world()
            .get_resource::<WindfallSchedule>()
            .copied()
            .unwrap_or_default()
            .0
    })
}

/// Records `schedule` as the [`WindfallSchedule`]: the group does this first, so that its
/// plugins, given or defaulted, agree.
pub(crate) struct RecordSchedule(pub(crate) InternedScheduleLabel);

impl bevy::app::Plugin for RecordSchedule {
    fn build(&self, app: &mut App) {
        app.register_type::<WindfallSchedule>()
            .insert_resource(WindfallSchedule(self.0));
    }
}

/// Orders the sets in `schedule` and records it as the [`WindfallSchedule`] unless one is
/// recorded already (a plugin given another schedule than the recorded one is warned about,
/// since poses would be interpolated for the recorded one). Idempotent, so every plugin calls
/// it.
pub(crate) fn configure_sets(app: &mut App, schedule: InternedScheduleLabel) {
    match app.world().get_resource::<WindfallSchedule>() {
        None => {
            app.insert_resource(WindfallSchedule(schedule));
        }
        Some(current) if current.0 != schedule => {
            bevy::log::warn!(
                "bevy_windfall: a plugin simulates in {schedule:?} while others use {:?}; \
                 poses are interpolated for the latter",
                current.0
            );
        }
        Some(_) => {}
    }
    // A frame-rate schedule steps by the frame's time, which is zero while `Time<Virtual>` is
    // paused (a fixed step always has its timestep). Once per schedule: every plugin calls this.
    let fixed = WindfallSchedule(schedule).is_fixed();
    let mut pausable = app.world_mut().get_resource_or_init::<PausableIn>();
    if !fixed && !pausable.0.contains(&schedule) {
        pausable.0.push(schedule);
        app.configure_sets(schedule, WindfallSystems::Simulate.run_if(time_moves));
    }
    app.register_type::<WindfallSchedule>()
        .configure_sets(
            schedule,
            // WriteBack runs in PostUpdate: in a simulation schedule of PostUpdate it must come
            // after the step too (elsewhere the set is empty and the order holds by schedule).
            (
                WindfallSystems::Wind,
                WindfallSystems::Simulate,
                WindfallSystems::WriteBack,
            )
                .chain(),
        )
        .configure_sets(
            schedule,
            (
                SimulateSystems::Falls,
                SimulateSystems::Clouds,
                SimulateSystems::Cloth,
                SimulateSystems::Aero,
            )
                .chain()
                .in_set(WindfallSystems::Simulate),
        )
        .configure_sets(
            RunFixedMainLoop,
            WindfallSystems::Prepare.in_set(RunFixedMainLoopSystems::BeforeFixedMainLoop),
        )
        .configure_sets(
            PostUpdate,
            WindfallSystems::WriteBack.before(bevy::transform::TransformSystems::Propagate),
        );
}

/// How far the frame is into the next fixed step (0 to 1), or 1 if the simulation does not run
/// on the fixed timestep: where to pose bodies between their last two steps.
pub(crate) fn overstep(schedule: Option<&WindfallSchedule>, time: Option<&Time<Fixed>>) -> f32 {
    match (schedule.copied().unwrap_or_default().is_fixed(), time) {
        (true, Some(time)) => time.overstep_fraction(),
        _ => 1.0,
    }
}

/// Declares a simulation plugin that takes its schedule, as avian's plugins do: a struct with
/// `new(schedule)` and a `Default` that simulates in the schedule its group (or an earlier
/// plugin) recorded, else [`FixedUpdate`].
macro_rules! simulation_plugin {
    ($(#[$meta:meta])* $name:ident) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, Default)]
        pub struct $name {
            /// Where it simulates; `None` follows the recorded schedule, else `FixedUpdate`.
            pub(crate) schedule: Option<bevy::ecs::schedule::InternedScheduleLabel>,
        }

        impl $name {
            /// The plugin simulating in `schedule` instead of `FixedUpdate` (give every plugin
            /// the same one, or use `WindfallPlugins::new`).
            pub fn new(schedule: impl bevy::ecs::schedule::ScheduleLabel) -> Self {
                Self {
                    schedule: Some(schedule.intern()),
                }
            }

            /// The schedule it simulates in, its sets ordered there.
            fn configure(&self, app: &mut bevy::app::App) -> bevy::ecs::schedule::InternedScheduleLabel {
                let schedule = $crate::schedule::resolve(app, self.schedule);
                $crate::schedule::configure_sets(app, schedule);
                schedule
            }
        }
    };
}
pub(crate) use simulation_plugin;
