//! The plugin group and the debug plugin: the top layer, which only assembles the domains'
//! plugins.

#[cfg(feature = "gizmos")]
use bevy::app::{App, Plugin};
use bevy::app::{FixedUpdate, PluginGroup, PluginGroupBuilder};
use bevy::ecs::schedule::{InternedScheduleLabel, ScheduleLabel};

use crate::{aero, cloth, freefall, wind};

/// All of bevy_windfall's plugins. Add the group after `DefaultPlugins`
/// (`add_plugins(WindfallPlugins::default())`, the simulation in [`FixedUpdate`](bevy::app::FixedUpdate)),
/// a single plugin, or disable one: `WindfallPlugins::default().build().disable::<ClothPlugin>()`. Simulate
/// in another schedule with [`WindfallPlugins::new`], as avian's `PhysicsPlugins::new(schedule)`.
///
/// With the features that bring them, the group also holds what draws and what couples:
/// `WindfallRenderPlugin` (feature `render`, on by default: default looks, leaf clouds, the wind
/// on the GPU; it does nothing in an app without Bevy's renderer) and `AvianAeroPlugin`
/// (feature `avian`, in avian's default schedule: replace it with
/// `.set(AvianAeroPlugin::new(schedule))` if avian runs elsewhere).
///
/// [`ClothPlugin`]: cloth::ClothPlugin
#[derive(Clone, Copy, Debug, Default)]
pub struct WindfallPlugins {
    /// Where the simulation runs; `None` is `FixedUpdate`.
    schedule: Option<InternedScheduleLabel>,
}

impl WindfallPlugins {
    /// All the plugins, simulating (the [`WindfallSystems::Wind`](crate::WindfallSystems::Wind)
    /// and [`WindfallSystems::Simulate`](crate::WindfallSystems::Simulate) sets) in `schedule`
    /// instead of `FixedUpdate`. In a schedule other than the fixed ones the step is the frame's
    /// and poses are not interpolated.
    pub fn new(schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: Some(schedule.intern()),
        }
    }
}

impl PluginGroup for WindfallPlugins {
    fn build(self) -> PluginGroupBuilder {
        let s = self.schedule;
        let recorded = s.unwrap_or_else(|| FixedUpdate.intern());
        let group = PluginGroupBuilder::start::<Self>()
            .add(crate::schedule::RecordSchedule(recorded))
            .add(wind::WindPlugin {
                schedule: s,
                ..Default::default()
            })
            .add(freefall::FallPlugin { schedule: s })
            .add(freefall::LeafCloudPlugin { schedule: s })
            .add(aero::AeroPlugin { schedule: s })
            .add(cloth::ClothPlugin { schedule: s });
        #[cfg(feature = "render")]
        let group = group.add(crate::render::WindfallRenderPlugin);
        #[cfg(feature = "avian")]
        let group = group.add(aero::AvianAeroPlugin::default());
        group
    }
}

/// Debug drawing (feature `gizmos`), added by you, like avian's `PhysicsDebugPlugin`: wind
/// arrows ([`wind::WindGizmos`]), fall trails ([`freefall::FallGizmos`]) and cloth yarns
/// ([`cloth::ClothGizmos`]), each a gizmo config group, all off until enabled in the
/// `GizmoConfigStore`. Needs Bevy's gizmo plugin (in `DefaultPlugins`).
#[cfg(feature = "gizmos")]
pub struct WindfallDebugPlugin;

#[cfg(feature = "gizmos")]
impl Plugin for WindfallDebugPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins((
            wind::WindGizmosPlugin,
            freefall::FallGizmosPlugin,
            cloth::ClothGizmosPlugin,
        ));
    }
}
