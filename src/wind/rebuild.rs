//! Rebuilding the wind field off the main thread: a large grid takes tens of milliseconds to
//! synthesise, which must not stall a frame. The new field lands a fixed number of steps after
//! the request, so two runs of a game land it at the same step whatever the machine.

use bevy::ecs::prelude::*;
use bevy::log::info;
use bevy::tasks::{AsyncComputeTaskPool, Task, TaskPool, block_on, futures::check_ready};

use super::config::WindConfig;
use super::error::WindError;
use super::field::WindField;

/// A [`WindField`] being synthesised on the [`AsyncComputeTaskPool`]: new turbulence. Editing
/// the turbulence in [`WindSettings`](super::settings::WindSettings) starts one for you, or
/// insert one; [`WindPlugin`](super::plugin::WindPlugin) swaps the new turbulence in exactly
/// [`WindRebuild::steps`] fixed steps later, waiting for the synthesis at that step if it is late,
/// so the swap happens at the same step on every machine (replays and lockstep multiplayer need
/// that), and sends [`WindRebuilt`]. Until then the old field keeps blowing.
///
/// A rebuild replaces the turbulence only: the field goes on with its own clock, easing and mean
/// wind (speed, direction, pulse), whatever was set while it built. Inserting another
/// `WindRebuild` replaces the one in flight; a [`WindField`] inserted after a rebuild (a new
/// one, a clone put back, one from a snapshot) wins, and the rebuild is dropped.
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
    task: Option<Task<WindField>>,
    steps: u32,
    elapsed: u32,
    /// Set when a [`WindField`] is inserted after this was: the field wins.
    pub(super) superseded: bool,
}

impl WindRebuild {
    /// Validates `config` now (a bad field is reported here, by name) and starts the synthesis;
    /// it lands after [`WindRebuild::DEFAULT_STEPS`] fixed steps.
    pub fn start(config: WindConfig) -> Result<Self, WindError> {
        config.validate()?;
        let pool = AsyncComputeTaskPool::get_or_init(TaskPool::default);
        let job = config.clone();
        let task = pool.spawn(async move {
            // Validated above, and `new` checks nothing more that could fail.
            WindField::new(job).expect("validated configuration")
        });
        Ok(Self {
            config,
            task: Some(task),
            steps: Self::DEFAULT_STEPS,
            elapsed: 0,
            superseded: false,
        })
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

/// Counts the [`WindRebuild`] in flight down by one fixed step; at its step, puts its turbulence
/// in (waiting for it if it is late): the live field goes on with it ([`WindField`]'s clock,
/// easing and mean wind kept), or it becomes the field if there is none. A rebuild superseded by
/// an inserted field is dropped.
pub(super) fn land_wind_rebuild(
    mut commands: Commands,
    mut rebuild: ResMut<WindRebuild>,
    live: Option<ResMut<WindField>>,
    mut rebuilt: MessageWriter<WindRebuilt>,
) {
    if rebuild.superseded {
        info!("a WindField was inserted after a rebuild was requested: the rebuild is dropped");
        commands.remove_resource::<WindRebuild>();
        return;
    }
    rebuild.elapsed += 1;
    if rebuild.elapsed < rebuild.steps {
        return;
    }
    let Some(task) = rebuild.task.as_mut() else {
        commands.remove_resource::<WindRebuild>();
        return;
    };
    let mut field = if cfg!(target_arch = "wasm32") {
        match check_ready(task) {
            Some(field) => field,
            None => return,
        }
    } else {
        block_on(task)
    };
    rebuild.task = None;
    match live {
        Some(mut live) => {
            field.carry_on_from(&live);
            *live = field;
        }
        None => commands.insert_resource(field),
    }
    rebuilt.write(WindRebuilt {
        config: rebuild.config.clone(),
    });
    commands.remove_resource::<WindRebuild>();
}

/// Sent when a [`WindRebuild`] has put its turbulence into the [`WindField`].
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
    /// The configuration the rebuild built (the field's turbulence now; its mean wind is the
    /// field's own, [`WindField::config`]).
    pub config: WindConfig,
}

/// Limits and constants of [`WindRebuild`].
impl WindRebuild {
    /// Fixed steps from a rebuild's request to its landing (0.5 s at 60 Hz): long enough for a
    /// 128² plane or a 64³ volume on a slow machine; a larger field that is not ready by then is
    /// waited for at that step.
    pub const DEFAULT_STEPS: u32 = 30;
}
