//! Local wind: [`WindSource`] components (spheres, fans, vortices, blasts) whose velocities add to
//! the [`WindField`](super::WindField) where they are.
//!
//! Each profile is compact (exactly zero beyond its extent, so a sample far away costs one
//! distance test) and smooth (no jump at its edge), built from the fade `(1 − s²)²`, which is 1 at
//! s = 0, falls monotonically and reaches 0 with zero slope at s = 1.

use bevy::ecs::component::Component;
use bevy::ecs::reflect::ReflectComponent;
use bevy::math::Vec3;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

use super::pulse::Pulse;

/// What a [`WindSource`] blows, in metres and m/s.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub enum SourceShape {
    /// `velocity` (world frame) at the centre, fading to zero at `radius`.
    Sphere {
        /// m.
        radius: f32,
        /// m/s at the centre, world frame.
        velocity: Vec3,
    },
    /// A jet along the entity's forward direction (local −Z), spreading in a cone.
    Fan {
        /// How far it reaches, m.
        range: f32,
        /// The cone's half angle, rad, in [0, π/2].
        half_angle: f32,
        /// m/s on the axis at the fan.
        speed: f32,
    },
    /// A horizontal swirl about local +Y, right-handed for a positive `peak_speed`.
    Vortex {
        /// Nothing beyond this distance from the centre, m.
        radius: f32,
        /// Tangential speed at the core's edge (radius / 5), m/s.
        peak_speed: f32,
        /// Upward speed on the axis, fading like the swirl's envelope (0 for a pure swirl), m/s.
        updraft: f32,
    },
    /// A one-shot outward pulse whose front runs outward at `front_speed` from when the source
    /// starts (when it is added: the start of the next fixed step).
    Blast {
        /// Outward speed at the front, m/s (≥ 0).
        peak_speed: f32,
        /// Speed of the front, m/s.
        front_speed: f32,
        /// Nothing beyond this distance; the blast is over once its front has passed it, m.
        radius: f32,
    },
    /// A gust front: a slab across the entity's forward direction (local −Z) travelling forward
    /// from the entity, adding wind along that direction as it passes.
    Gust {
        /// Wind it adds along forward, m/s.
        strength: f32,
        /// Speed of the front, m/s.
        front_speed: f32,
        /// Thickness of the slab along the travel, m.
        width: f32,
        /// How far it travels and how wide it is across, m.
        range: f32,
    },
}

/// A local wind: its velocity adds to the global [`WindField`](super::WindField) in
/// [`WindField::velocity`](super::WindField::velocity), `velocity_at` and `velocities_at`, from
/// the first fixed step after it is spawned (or moved) to the step after it is despawned. The
/// entity's position and rotation place it (its global transform, so sources move and may be
/// parented); its scale is ignored: sizes are in metres.
///
/// One constructor per shape, which keeps its arguments as given: a source a plugin cannot place
/// (a number not finite, a size negative or beyond [`MAX_COORDINATE`](crate::guard::MAX_COORDINATE),
/// a fan's angle outside [0, π/2], a blast's speed negative) blows nothing and the entity gets a
/// [`WindSourceInvalid`] naming the field (`shape.radius`, …); [`WindSource::validate`] says so
/// beforehand. One source never cancels another (each adds at most ±1e6 m/s per axis), and a
/// blast never blows inward.
///
/// A blast or a gust is one-shot: it starts when it is added (its age counts from the start of
/// the next fixed step, so after n steps it is n steps old) and is inert once
/// its front has passed `radius` ([`WindSource::finished`]); the entity stays (despawn it, or
/// insert the component again to fire it again).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::wind::WindSource;
///
/// fn setup(mut commands: Commands) {
///     // A fan on the wall blowing along −Z, a whirlwind in the field, a grenade going off.
///     commands.spawn((WindSource::fan(8.0, 0.35, 6.0), Transform::from_xyz(0.0, 1.5, 5.0)));
///     commands.spawn((WindSource::vortex(4.0, 9.0), Transform::from_xyz(-6.0, 0.0, 0.0)));
///     commands.spawn((WindSource::blast(25.0, 15.0, 12.0), Transform::from_xyz(3.0, 0.2, 0.0)));
/// }
/// App::new()
///     .add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()))
///     .add_systems(Startup, setup)
///     .update();
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform)]
pub struct WindSource {
    /// What it blows.
    pub shape: SourceShape,
    /// Multiplies the velocity: 0 switches it off, 2 doubles it.
    pub strength: f32,
    /// A periodic swell of the strength, its phase counted from when the source started (so it
    /// starts at full `strength` and swells first); none by default.
    pub pulse: Pulse,
}

impl Default for WindSource {
    /// A 3 m sphere blowing 5 m/s along +X.
    fn default() -> Self {
        Self::sphere(3.0, Vec3::new(5.0, 0.0, 0.0))
    }
}

impl WindSource {
    fn new(shape: SourceShape) -> Self {
        Self {
            shape,
            strength: 1.0,
            pulse: Pulse::default(),
        }
    }

    /// This source with a [`Pulse`]: its strength swells by ±`magnitude` (relative, clamped to
    /// [0, 1]) `frequency` times a second (clamped to [0, 100] Hz; non-finite values become 0),
    /// like Unity's WindZone pulse. The mean over a period is unchanged.
    pub fn with_pulse(mut self, magnitude: f32, frequency: f32) -> Self {
        self.pulse = Pulse::new(magnitude, frequency).clamped();
        self
    }

    /// `velocity` (world frame, m/s) at the centre, fading smoothly and monotonically to zero at
    /// `radius` (m): v(r) = velocity (1 − r²/R²)².
    pub fn sphere(radius: f32, velocity: Vec3) -> Self {
        Self::new(SourceShape::Sphere { radius, velocity })
    }

    /// A jet along the entity's forward direction ([`Transform::forward`], local −Z): inside a
    /// cone of `half_angle` rad (in [0, π/2]), up to `range` m, blowing outward from the
    /// fan at `speed` m/s on the axis, fading to zero at the cone's edge and at `range`. Nothing
    /// behind the fan or outside the cone.
    pub fn fan(range: f32, half_angle: f32, speed: f32) -> Self {
        Self::new(SourceShape::Fan {
            range,
            half_angle,
            speed,
        })
    }

    /// A horizontal swirl about the entity's local +Y axis, right-handed (at local +X the wind
    /// blows toward local −Z; a negative `peak_speed` reverses it): zero on the axis, rising
    /// linearly to `peak_speed` at the core's edge (radius / 5) as a Rankine vortex, falling as
    /// 1/r outside it, and fading to nothing at `radius` m from the centre (measured in 3-D, so
    /// the whirl is a ball, flat within radius / 2 of the centre's height).
    pub fn vortex(radius: f32, peak_speed: f32) -> Self {
        Self::new(SourceShape::Vortex {
            radius,
            peak_speed,
            updraft: 0.0,
        })
    }

    /// A vortex that also lifts: `updraft` m/s upward on its axis, fading outward like the swirl
    /// (a dust devil). Ignored by other shapes.
    pub fn with_updraft(mut self, updraft: f32) -> Self {
        if let SourceShape::Vortex { updraft: u, .. } = &mut self.shape {
            *u = updraft;
        }
        self
    }

    /// A one-shot outward pulse: it starts when the component is added (at the start of the next
    /// fixed step), its front runs outward at `front_speed` m/s, blowing outward (never inward)
    /// at `peak_speed` m/s right at the front (a shock) and easing to nothing a fifth of `radius`
    /// behind it, the speed fading over the outer half of `radius`; it is gone once that band
    /// has passed `radius` m.
    pub fn blast(peak_speed: f32, front_speed: f32, radius: f32) -> Self {
        Self::new(SourceShape::Blast {
            peak_speed,
            front_speed,
            radius,
        })
    }

    /// A gust front sweeping across a field: a slab `width` m thick and `range` m across,
    /// square to the entity's forward direction (local −Z, so point the entity downwind), that
    /// starts at the entity when the component is added (the start of the next fixed step) and travels
    /// forward at `front_speed` m/s for `range` m, adding up to `strength` m/s along forward as
    /// it passes (fading across its thickness and toward its sides). Like a blast it is one-shot
    /// and then inert.
    pub fn gust(strength: f32, front_speed: f32, width: f32, range: f32) -> Self {
        Self::new(SourceShape::Gust {
            strength,
            front_speed,
            width,
            range,
        })
    }

    /// How far from its origin the source can blow, m (0: nowhere, and for sizes that
    /// [`Self::validate`] refuses).
    pub fn reach(&self) -> f32 {
        let reach = match self.shape {
            SourceShape::Sphere { radius, .. }
            | SourceShape::Vortex { radius, .. }
            | SourceShape::Blast { radius, .. } => radius,
            SourceShape::Fan { range, .. } => range,
            // The far corners of the slab at the end of its travel.
            SourceShape::Gust { width, range, .. } => {
                (range + width).hypot(range * std::f32::consts::FRAC_1_SQRT_2)
            }
        };
        if reach.is_finite() && reach >= 0.0 {
            reach
        } else {
            0.0
        }
    }

    /// True for a blast whose front (and the band behind it) has passed its radius, or a gust
    /// that has crossed its range, `age` seconds after it started; one that never moves (zero
    /// front speed) is never finished.
    pub fn finished(&self, age: f64) -> bool {
        match self.shape {
            SourceShape::Blast {
                front_speed,
                radius,
                ..
            } => front_speed > 0.0 && age * f64::from(front_speed) > f64::from(radius) * 1.2,
            SourceShape::Gust {
                front_speed,
                width,
                range,
                ..
            } => front_speed > 0.0 && age * f64::from(front_speed) > f64::from(range + width),
            _ => false,
        }
    }
}

mod check;
mod placed;
pub use check::WindSourceInvalid;
pub(crate) use placed::{PlacedSource, turn};
