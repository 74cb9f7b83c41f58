//! Rebuilding the wind field off the main thread: a large grid takes tens of milliseconds to
//! synthesise, which must not stall a frame. The new field lands a fixed number of steps after
//! the request, so two runs of a game land it at the same step whatever the machine.

use bevy::ecs::prelude::*;
use bevy::log::{info, warn};
use bevy::tasks::{AsyncComputeTaskPool, Task, TaskPool, block_on, futures::check_ready};

use super::field::validate_extra;
use super::{WindConfig, WindError, WindField, WindSettings};

/// Fixed steps from a rebuild's request to its landing (0.5 s at 60 Hz): long enough for a
/// 128² plane or a 64³ volume on a slow machine; a larger field that is not ready by then is
/// waited for at that step.
pub const REBUILD_STEPS: u32 = 30;

/// A [`WindField`] being synthesised on the [`AsyncComputeTaskPool`]. Insert one (or edit
/// [`WindSettings`], which starts one for you); [`WindPlugin`](super::WindPlugin) swaps the new
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
/// assert_eq!(job.steps(), bevy_windfall::wind::REBUILD_STEPS);
/// # Ok::<(), WindError>(())
/// ```
#[derive(Resource)]
pub struct WindRebuild {
    config: WindConfig,
    task: Option<Task<WindField>>,
    /// The field being replaced, once known (a different one at landing: dropped).
    replaces: Option<u64>,
    steps: u32,
    elapsed: u32,
}

impl WindRebuild {
    /// Validates `config` now (a bad field is reported here, by name) and starts the synthesis;
    /// it lands after [`REBUILD_STEPS`] fixed steps.
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

/// Counts the [`WindRebuild`] in flight down by one fixed step; at its step, swaps in the new
/// field (waiting for it if it is late), with the old clock and the live speed and direction.
pub fn land_wind_rebuild(
    mut commands: Commands,
    rebuild: Option<ResMut<WindRebuild>>,
    old: Option<Res<WindField>>,
    settings: Option<Res<WindSettings>>,
    mut rebuilt: MessageWriter<WindRebuilt>,
) {
    let Some(mut rebuild) = rebuild else {
        return;
    };
    let current = old.as_ref().map(|f| f.generation());
    match (rebuild.replaces, current) {
        (None, _) => rebuild.replaces = current,
        (Some(a), Some(b)) if a != b => {
            info!("a WindField was inserted while a rebuild was building: the rebuild is dropped");
            commands.remove_resource::<WindRebuild>();
            return;
        }
        _ => {}
    }
    rebuild.elapsed += 1;
    if rebuild.elapsed < rebuild.steps {
        return;
    }
    let Some(task) = rebuild.task.as_mut() else {
        commands.remove_resource::<WindRebuild>();
        return;
    };
    let field = if cfg!(target_arch = "wasm32") {
        match check_ready(task) {
            Some(field) => field,
            None => return,
        }
    } else {
        block_on(task)
    };
    rebuild.task = None;
    let mut field = field;
    if let Some(old) = old.as_deref() {
        // Speed and direction changed while it built (directly or through the settings).
        let (speed, direction) = match settings.as_deref() {
            Some(s) => (s.reference_speed, s.direction),
            None => (old.config().reference_speed, old.config().direction),
        };
        if let Err(e) = field
            .set_reference_speed(speed)
            .and_then(|()| field.set_direction(direction))
        {
            warn!("WindRebuild: {e}; the rebuilt field keeps its own speed and direction");
        }
        field.continue_clock_of(old);
    }
    rebuilt.write(WindRebuilt {
        config: field.config().clone(),
    });
    commands.insert_resource(field);
    commands.remove_resource::<WindRebuild>();
}
