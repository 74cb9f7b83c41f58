//! Rebuilding the wind field off the main thread: a large grid takes tens of milliseconds to
//! synthesise, which must not stall a frame.

use bevy::ecs::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, TaskPool, futures::check_ready};

use super::field::validate_extra;
use super::{WindConfig, WindError, WindField};

/// A [`WindField`] being synthesised on the [`AsyncComputeTaskPool`]. Insert it as a resource;
/// [`WindPlugin`](super::WindPlugin) swaps the new field in once it is ready (keeping the wind
/// clock) and sends [`WindRebuilt`]. Until then the old field keeps blowing. Inserting another
/// `WindRebuild` replaces (and drops) the one in flight.
#[derive(Resource)]
pub struct WindRebuild {
    config: WindConfig,
    task: Task<WindField>,
}

impl WindRebuild {
    /// Validates `config` now (a bad field is reported here, by name) and starts the synthesis.
    pub fn start(config: WindConfig) -> Result<Self, WindError> {
        validate_extra(&config)?;
        let pool = AsyncComputeTaskPool::get_or_init(TaskPool::default);
        let job = config.clone();
        let task = pool.spawn(async move {
            // Validated above, and `new` checks nothing more that could fail.
            WindField::new(job).expect("validated configuration")
        });
        Ok(Self { config, task })
    }

    /// The configuration being built.
    pub fn config(&self) -> &WindConfig {
        &self.config
    }
}

/// Sent when a [`WindRebuild`] has replaced the [`WindField`].
#[derive(Message, Clone, Debug)]
pub struct WindRebuilt {
    /// The configuration now in effect.
    pub config: WindConfig,
}

/// Polls the [`WindRebuild`] in flight; swaps in the finished field.
pub fn finish_wind_rebuild(
    mut commands: Commands,
    rebuild: Option<ResMut<WindRebuild>>,
    old: Option<Res<WindField>>,
    mut rebuilt: MessageWriter<WindRebuilt>,
) {
    let Some(mut rebuild) = rebuild else {
        return;
    };
    if let Some(mut field) = check_ready(&mut rebuild.task) {
        if let Some(old) = old {
            field.continue_clock_of(&old);
        }
        rebuilt.write(WindRebuilt {
            config: field.config().clone(),
        });
        commands.insert_resource(field);
        commands.remove_resource::<WindRebuild>();
    }
}
