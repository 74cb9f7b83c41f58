//! Rebuilding the wind field off the main thread: a large grid takes tens of milliseconds to
//! synthesise, which must not stall a frame. The new field lands a fixed number of steps after
//! the request, so two runs of a game land it at the same step whatever the machine.

use bevy::ecs::prelude::*;
use bevy::math::Vec2;
use bevy::tasks::{AsyncComputeTaskPool, Task, TaskPool};

use super::config::WindConfig;
use super::error::WindError;
use super::field::{WindField, next_generation};
use super::pulse::Pulse;

/// A [`WindField`] being synthesised on the [`AsyncComputeTaskPool`]. Insert one (or edit
/// [`WindSettings`](super::settings::WindSettings), which starts one for you); [`WindPlugin`](super::plugin::WindPlugin) swaps the new
/// field in exactly [`WindRebuild::steps`] fixed steps later, waiting for the synthesis at that
/// step if it is late, so the swap happens at the same step on every machine (replays and
/// lockstep multiplayer need that). The new field keeps the old one's clock, and [`WindRebuilt`]
/// is sent. Until then the old field keeps blowing.
///
/// The mean speed, direction and [`Pulse`] are merged three ways: each one that was changed on
/// the live field while the rebuild was building (directly or through the settings) keeps its
/// new value; each one nobody changed takes the rebuild's own. Inserting another `WindRebuild`
/// replaces the one in flight. The later request wins between a rebuild and a [`WindField`]
/// inserted by hand: a field made ([`WindField::new`]) after the rebuild was started wins, and
/// the rebuild is dropped; a field made before it is replaced when the rebuild lands.
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
    /// The field being replaced and its mean wind then, once known (a different field at
    /// landing: dropped).
    pub(super) replaces: Option<(u64, Mean)>,
    /// The generation the next [`WindField::new`] would have had when this was requested: a
    /// live field of this generation or later was made after the request.
    pub(super) requested: u64,
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

/// [`WindRebuild::start`], replacing `replaces` (its generation and mean wind now) if known.
pub(crate) fn start_rebuild(
    config: WindConfig,
    replaces: Option<(u64, Mean)>,
) -> Result<WindRebuild, WindError> {
    let requested = next_generation();
    config.validate()?;
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
        requested,
        steps: WindRebuild::DEFAULT_STEPS,
        elapsed: 0,
    })
}

/// What a rebuild merges: a field's mean speed, direction and pulse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Mean {
    speed: f32,
    direction: Vec2,
    pulse: Pulse,
}

impl Mean {
    pub(crate) fn of(field: &WindField) -> Self {
        let c = field.config();
        Self {
            speed: c.reference_speed,
            direction: c.direction,
            pulse: c.pulse,
        }
    }

    /// The three-way merge: what `live` changed since `base` wins, `own` keeps the rest.
    fn merge(base: Self, live: Self, own: Self) -> Self {
        Self {
            speed: if live.speed != base.speed {
                live.speed
            } else {
                own.speed
            },
            direction: if live.direction != base.direction {
                live.direction
            } else {
                own.direction
            },
            pulse: if live.pulse != base.pulse {
                live.pulse
            } else {
                own.pulse
            },
        }
    }
}

/// Gives the rebuilt `field` the clock of the `old` one and the merged mean wind (see
/// [`WindRebuild`]); `base` is the old field's mean wind when the rebuild started.
pub(super) fn hand_over(
    field: &mut WindField,
    old: &WindField,
    base: Mean,
) -> Result<(), WindError> {
    let mean = Mean::merge(base, Mean::of(old), Mean::of(field));
    let own = Mean::of(field);
    if mean.speed != own.speed {
        field.set_reference_speed(mean.speed)?;
    }
    if mean.direction != own.direction {
        field.set_direction(mean.direction)?;
    }
    if mean.pulse != own.pulse {
        field.set_pulse(mean.pulse)?;
    }
    field.continue_clock_of(old);
    Ok(())
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
    pub const DEFAULT_STEPS: u32 = 30;
}
