//! Levels of detail for falls: [`FallLod`] for a single falling object, the clock the tiers of
//! objects and of a cloud's leaves run on ([`FallClock`]), and each fall's [`TierClock`].
//!
//! A fall in tier n (see [`LodTiers`](crate::lod::LodTiers)) is advanced every n-th fixed step
//! over the whole time since its last step, so it follows the same path (pieces are sampled by
//! time) and lands at the same time, reading the wind less often. What is shown runs along the
//! path's Bézier between its last two control points at the share of the last step's span that
//! has passed, so a fall stepped every fourth step moves as smoothly as one stepped every step.
//! When the steps grow further apart (a coarser tier) that span is shown over the longer wait.
//! When a step comes before the last span was shown (a change to a finer tier), what was shown
//! then is eased out over two old spans, so the shown pose never jumps.

use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use super::model::FallModel;
use super::model::path::{FallPath, StepOutcome, WindTilt};
use crate::lod::LodTiers;

/// Levels of detail for a single [`FallingObject`](super::object::FallingObject): with a
/// [`LodFocus`](crate::lod::LodFocus) on the camera, the object is stepped every fixed step
/// within `near` m of it, every second step to `far`, every fourth beyond, over the whole time
/// since its last step, exactly as a [`LeafCloud`](super::cloud::LeafCloud)'s leaves are. It follows
/// the same path (its pieces are sampled by time), reads the wind less often, moves smoothly
/// between its steps, and eases back without a jump when it comes nearer. Without this
/// component an object is stepped every fixed step.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::FallLod;
/// use bevy_windfall::prelude::*;
///
/// fn setup(mut commands: Commands) {
///     // On the camera (here an entity with only a transform).
///     commands.spawn((LodFocus, Transform::from_xyz(0.0, 2.0, 10.0)));
///     for i in 0..1000 {
///         commands.spawn((
///             FallingObject { seed: i, ..default() },
///             FallLod::default(),
///             Transform::from_xyz(i as f32 * 0.5, 10.0, 0.0),
///         ));
///     }
/// }
/// # let _ = setup;
/// ```
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct FallLod(pub LodTiers);

impl crate::lod::HasLodTiers for FallLod {
    fn tiers(&self) -> LodTiers {
        self.0
    }
}

/// The clock the tiers of single objects run on: seconds and fixed steps since the plugin
/// started, and the last step's length.
#[derive(Resource, Clone, Copy, Debug, Default)]
pub(crate) struct FallClock {
    pub seconds: f64,
    pub steps: u64,
    pub last_dt: f32,
}

impl FallClock {
    /// One more fixed step of `dt` seconds.
    pub fn tick(&mut self, dt: f32) {
        self.seconds += f64::from(dt);
        self.steps += 1;
        self.last_dt = dt;
    }

    /// Whether an object of `tier` (1, 2 or 4) with index `index` is due on this step: the
    /// objects of a tier take turns, so the work per step is even.
    pub fn due(&self, tier: u32, index: u32) -> bool {
        (self.steps + u64::from(index)) & u64::from(tier.max(1) - 1) == 0
    }

    /// Fixed steps from this one to the next on which an object of `tier` with index `index`
    /// is due (1 to `tier`).
    pub fn steps_to_next(&self, tier: u32, index: u32) -> u32 {
        let tier = tier.max(1);
        tier - ((self.steps + u64::from(index)) & u64::from(tier - 1)) as u32
    }
}

/// When a fall was last stepped, how long that step was, and what is left of an easing.
#[derive(Clone, Debug, Default)]
pub(crate) struct TierClock {
    /// The clock at the last step, s.
    updated: f64,
    /// Seconds the last step covered (one to four fixed steps, by the tier).
    span: f32,
    /// Set when a step came sooner than the one before it: what was shown then, eased out.
    /// (Boxed: rare, and a cloud's leaves stream through the cache every step.)
    from: Option<Box<Easing>>,
}

/// How far the shown pose was from the path when the fall was stepped, eased out by `end`.
#[derive(Clone, Copy, Debug)]
struct Easing {
    /// Shown position − the path's, at `start`.
    offset: Vec3,
    /// Shown rotation × the path's inverse, at `start`.
    turn: Quat,
    start: f64,
    /// The clock when the easing is over (it is not pushed back by later steps).
    end: f64,
}

impl Easing {
    /// The share of the easing still to go at `now`: 1 at its start, 0 from its end.
    fn left(&self, now: f64) -> f32 {
        let length = (self.end - self.start).max(1e-9);
        ((self.end - now) / length).clamp(0.0, 1.0) as f32
    }
}

impl TierClock {
    /// A fall last stepped at `clock`, over a step of `span` seconds.
    pub(crate) fn stepped_at(clock: f64, span: f32) -> Self {
        Self {
            updated: clock,
            span,
            from: None,
        }
    }

    /// True until the first step after a release ([`Self::default`] or
    /// [`Self::stepped_at`] with a zero span): a fall just let go takes that step at once
    /// rather than wait for its tier's turn.
    pub(crate) fn fresh(&self) -> bool {
        self.span == 0.0 && self.from.is_none()
    }

    /// The share of the last step's span that has passed at `now`, in [0, 1].
    fn share(&self, now: f64) -> f32 {
        if self.span > 0.0 {
            ((now - self.updated) as f32 / self.span).clamp(0.0, 1.0)
        } else {
            1.0
        }
    }

    /// Whether a step at `clock` is a plain one: no easing under way and the last span shown in
    /// full (what [`Self::advance`] then does is the path's step and [`Self::stepped`]).
    pub(crate) fn plain_at(&self, clock: f64) -> bool {
        !self.easing(clock) && self.share(clock) >= 1.0 - 1e-3
    }

    /// The seconds since the last step, at `clock`.
    pub(crate) fn waited(&self, clock: f64) -> f32 {
        (clock - self.updated) as f32
    }

    /// Records a plain step of `waited` seconds taken at `clock`, the next `next` seconds on.
    pub(crate) fn stepped(&mut self, clock: f64, next: f32, waited: f32) {
        self.from = None;
        self.updated = clock;
        self.span = if next > waited { next } else { waited };
    }

    /// True while an easing is under way at `now`.
    pub(crate) fn easing(&self, now: f64) -> bool {
        self.from.as_ref().is_some_and(|e| e.end > now)
    }

    /// The pose shown at `now`: `path`'s Bézier at the share of the span that has passed, plus
    /// what is left of an easing.
    pub(crate) fn shown(&self, path: &FallPath, now: f64) -> (Vec3, Quat) {
        let (position, rotation) = path.smoothed(self.share(now));
        match self.from.as_deref() {
            Some(e) => {
                let left = e.left(now);
                (
                    position + e.offset * left,
                    (Quat::IDENTITY.lerp(e.turn, left) * rotation).normalize(),
                )
            }
            None => (position, rotation),
        }
    }

    /// Advances `path` at `clock` over the time since its last step, in `wind`, and starts an
    /// easing if what is shown now lags the path (or carries one on). `next` is how long until
    /// the next step, s, as far as the tier now tells: the new span is shown over the longer of
    /// it and the step just taken, so a change to a coarser tier slows what is shown for one
    /// span instead of holding it still. Returns what the step did and the seconds it covered.
    pub(crate) fn advance(
        &mut self,
        path: &mut FallPath,
        model: &FallModel,
        clock: f64,
        next: f32,
        wind: Vec3,
        tilt: &WindTilt,
    ) -> (StepOutcome, f32) {
        let waited = self.waited(clock);
        let running = self.from.as_ref().map(|e| e.end).filter(|&end| end > clock);
        // (The share is a ratio of f64 clock differences rounded to f32: a step of the same
        // span can come out a rounding short of 1, which is no lag worth easing.)
        let lagging = self.share(clock) < 1.0 - 1e-3;
        let before = (running.is_some() || lagging).then(|| self.shown(path, clock));
        // A new easing lasts two of the spans before (it catches up at most half a step per
        // step); one under way keeps its end.
        let end = running.unwrap_or(clock + 2.0 * f64::from(self.span.max(waited)));
        let outcome = path.advance(model, waited, wind, tilt);
        self.from = before.map(|(shown_position, shown_rotation)| {
            let (position, rotation) = path.smoothed(0.0);
            Box::new(Easing {
                offset: shown_position - position,
                turn: (shown_rotation * rotation.inverse()).normalize(),
                start: clock,
                end,
            })
        });
        self.updated = clock;
        self.span = if next > waited { next } else { waited };
        (outcome, waited)
    }
}
