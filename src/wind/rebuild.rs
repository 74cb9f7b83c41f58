//! Rebuilding the wind field off the main thread: a large grid takes tens of milliseconds to
//! synthesise, which must not stall a frame. The new field lands a fixed number of steps after
//! the request, so two runs of a game land it at the same step whatever the machine.

use bevy::ecs::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, TaskPool};

use super::config::WindConfig;
use super::error::WindError;
use super::field::WindField;
use super::field::validate_extra;

/// Fixed steps from a rebuild's request to its landing (0.5 s at 60 Hz): long enough for a
/// 128² plane or a 64³ volume on a slow machine; a larger field that is not ready by then is
/// waited for at that step.
pub(crate) const REBUILD_STEPS: u32 = 30;

/// A [`WindField`] being synthesised on the [`AsyncComputeTaskPool`]. Insert one (or edit
/// [`WindSettings`](super::settings::WindSettings), which starts one for you); [`WindPlugin`](super::plugin::WindPlugin) swaps the new
/// field in exactly [`WindRebuild::steps`] fixed steps later, waiting for the synthesis at that
/// step if it is late, so the swap happens at the same step on every machine (replays and
/// lockstep multiplayer need that). The new field keeps the old one's clock and its current mean
/// speed and direction (edits made while it was building are not lost), and [`WindRebuilt`] is
/// sent. Until then the old field keeps blowing. Inserting another `WindRebuild` replaces the one
/// in flight; a [`WindField`] inserted meanwhile by hand wins over the rebuild, which is dropped.
///
/// In a browser (wasm32) the synthesis cannot be waited for, so a late one lands at the first
/// step after it is ready.
///
/// # Example
///
/// ```
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::wind::WindRebuild;
///
/// let smoother = WindConfig { beta: 3.0, ..WindConfig::default() };
/// let job = WindRebuild::start(smoother)?;
/// assert_eq!(job.steps(), bevy_windfall::wind::WindRebuild::DEFAULT_STEPS);
/// # Ok::<(), WindError>(())
/// ```
#[derive(Resource)]
pub struct WindRebuild {
    config: WindConfig,
    pub(super) task: Option<Task<WindField>>,
    /// The field being replaced, once known (a different one at landing: dropped).
    pub(super) replaces: Option<u64>,
    pub(super) steps: u32,
    pub(super) elapsed: u32,
}

impl WindRebuild {
    /// Validates `config` now (a bad field is reported here, by name) and starts the synthesis;
    /// it lands after [`WindRebuild::DEFAULT_STEPS`](crate::wind::WindRebuild::DEFAULT_STEPS) fixed steps.
    pub fn start(config: WindConfig) -> Result<Self, WindError> {
        start_rebuild(config, None)
    }

    /// The same, landing after `steps` fixed steps (at least 1).
    pub fn with_steps(mut self, steps: u32) -> Self {
        self.steps = steps.max(1);
        self
    }

    /// The configuration being built.
    pub fn config(&self) -> &WindConfig {
        &self.config
    }

    /// Fixed steps from the request to the landing.
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Fixed steps left until the landing.
    pub fn steps_left(&self) -> u32 {
        self.steps.saturating_sub(self.elapsed)
    }
}

/// [`WindRebuild::start`], replacing the field of generation `replaces` if known.
pub(crate) fn start_rebuild(
    config: WindConfig,
    replaces: Option<u64>,
) -> Result<WindRebuild, WindError> {
    validate_extra(&config)?;
    let pool = AsyncComputeTaskPool::get_or_init(TaskPool::default);
    let job = config.clone();
    let task = pool.spawn(async move {
        // Validated above, and `new` checks nothing more that could fail.
        WindField::new(job).expect("validated configuration")
    });
    Ok(WindRebuild {
        config,
        task: Some(task),
        replaces,
        steps: REBUILD_STEPS,
        elapsed: 0,
    })
}

/// Sent when a [`WindRebuild`] has replaced the [`WindField`].
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::wind::WindRebuilt;
///
/// fn announce(mut rebuilt: MessageReader<WindRebuilt>) {
///     for r in rebuilt.read() {
///         info!("new wind: β = {}, seed {}", r.config.beta, r.config.seed);
///     }
/// }
/// # let _ = announce;
/// ```
#[derive(Message, Clone, Debug)]
pub struct WindRebuilt {
    /// The configuration now in effect.
    pub config: WindConfig,
}

/// Limits and constants of [`WindRebuild`].
impl WindRebuild {
    /// Fixed steps from a rebuild's request to its landing (0.5 s at 60 Hz): long enough for a
    /// 128² plane or a 64³ volume on a slow machine; a larger field that is not ready by then is
    /// waited for at that step.
    pub const DEFAULT_STEPS: u32 = REBUILD_STEPS;
}
