//! Local wind: [`WindSource`] components (spheres, fans, vortices, blasts) whose velocities add to
//! the [`WindField`](super::WindField) where they are.
//!
//! Each profile is compact (exactly zero beyond its extent, so a sample far away costs one
//! distance test) and smooth (no jump at its edge), built from the fade `(1 − s²)²`, which is 1 at
//! s = 0, falls monotonically and reaches 0 with zero slope at s = 1.

use bevy::ecs::component::Component;
use bevy::ecs::reflect::ReflectComponent;
use bevy::math::{Affine3A, Quat, Vec3, Vec3A};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;
use std::f32::consts::FRAC_PI_2;

use super::config::WindError;
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
/// The plain constructors never fail: a non-finite number becomes 0, a negative size 0 and an
/// angle is clamped to its range, so a bad argument gives a source that blows nothing rather than
/// NaN. The `try_` constructors return a [`WindError`] naming the argument instead.
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
///     .add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins))
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

/// A finite value or 0.
fn finite(v: f32) -> f32 {
    if v.is_finite() { v } else { 0.0 }
}

/// A finite size ≥ 0.
fn size(v: f32) -> f32 {
    finite(v).max(0.0)
}

/// `Ok` for a finite `value` that is `ok`, otherwise an error naming `field`.
fn check(field: &'static str, value: f32, ok: bool, reason: &'static str) -> Result<(), WindError> {
    super::config::check(ok && value.is_finite(), field, value, reason)
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
        let velocity = if velocity.is_finite() {
            velocity
        } else {
            Vec3::ZERO
        };
        Self::new(SourceShape::Sphere {
            radius: size(radius),
            velocity,
        })
    }

    /// [`Self::sphere`], refusing a negative or non-finite `radius` or a non-finite `velocity`.
    pub fn try_sphere(radius: f32, velocity: Vec3) -> Result<Self, WindError> {
        check("radius", radius, radius >= 0.0, "must be finite and ≥ 0")?;
        let largest = velocity.abs().max_element();
        check("velocity", largest, true, "must be finite")?;
        Ok(Self::sphere(radius, velocity))
    }

    /// A jet along the entity's forward direction ([`Transform::forward`], local −Z): inside a
    /// cone of `half_angle` rad (clamped to [0, π/2]), up to `range` m, blowing outward from the
    /// fan at `speed` m/s on the axis, fading to zero at the cone's edge and at `range`. Nothing
    /// behind the fan or outside the cone.
    pub fn fan(range: f32, half_angle: f32, speed: f32) -> Self {
        Self::new(SourceShape::Fan {
            range: size(range),
            half_angle: size(half_angle).min(FRAC_PI_2),
            speed: finite(speed),
        })
    }

    /// [`Self::fan`], refusing a negative or non-finite `range`, a `half_angle` outside
    /// [0, π/2] or a non-finite `speed`.
    pub fn try_fan(range: f32, half_angle: f32, speed: f32) -> Result<Self, WindError> {
        check("range", range, range >= 0.0, "must be finite and ≥ 0")?;
        check(
            "half_angle",
            half_angle,
            (0.0..=FRAC_PI_2).contains(&half_angle),
            "must be in [0, π/2]",
        )?;
        check("speed", speed, true, "must be finite")?;
        Ok(Self::fan(range, half_angle, speed))
    }

    /// A horizontal swirl about the entity's local +Y axis, right-handed (at local +X the wind
    /// blows toward local −Z; a negative `peak_speed` reverses it): zero on the axis, rising
    /// linearly to `peak_speed` at the core's edge (radius / 5) as a Rankine vortex, falling as
    /// 1/r outside it, and fading to nothing at `radius` m from the centre (measured in 3-D, so
    /// the whirl is a ball, flat within radius / 2 of the centre's height).
    pub fn vortex(radius: f32, peak_speed: f32) -> Self {
        Self::new(SourceShape::Vortex {
            radius: size(radius),
            peak_speed: finite(peak_speed),
            updraft: 0.0,
        })
    }

    /// [`Self::vortex`], refusing a negative or non-finite `radius` or a non-finite
    /// `peak_speed`.
    pub fn try_vortex(radius: f32, peak_speed: f32) -> Result<Self, WindError> {
        check("radius", radius, radius >= 0.0, "must be finite and ≥ 0")?;
        check("peak_speed", peak_speed, true, "must be finite")?;
        Ok(Self::vortex(radius, peak_speed))
    }

    /// A vortex that also lifts: `updraft` m/s upward on its axis, fading outward like the swirl
    /// (a dust devil). Ignored by other shapes.
    pub fn with_updraft(mut self, updraft: f32) -> Self {
        if let SourceShape::Vortex { updraft: u, .. } = &mut self.shape {
            *u = finite(updraft);
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
            peak_speed: size(peak_speed),
            front_speed: size(front_speed),
            radius: size(radius),
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
            strength: finite(strength),
            front_speed: size(front_speed),
            width: size(width),
            range: size(range),
        })
    }

    /// [`Self::gust`], refusing a non-finite `strength` or negative or non-finite sizes.
    pub fn try_gust(
        strength: f32,
        front_speed: f32,
        width: f32,
        range: f32,
    ) -> Result<Self, WindError> {
        let reason = "must be finite and ≥ 0";
        check("strength", strength, true, "must be finite")?;
        check("front_speed", front_speed, front_speed >= 0.0, reason)?;
        check("width", width, width >= 0.0, reason)?;
        check("range", range, range >= 0.0, reason)?;
        Ok(Self::gust(strength, front_speed, width, range))
    }

    /// [`Self::blast`], refusing negative or non-finite arguments.
    pub fn try_blast(peak_speed: f32, front_speed: f32, radius: f32) -> Result<Self, WindError> {
        let reason = "must be finite and ≥ 0";
        check("peak_speed", peak_speed, peak_speed >= 0.0, reason)?;
        check("front_speed", front_speed, front_speed >= 0.0, reason)?;
        check("radius", radius, radius >= 0.0, reason)?;
        Ok(Self::blast(peak_speed, front_speed, radius))
    }

    /// How far from its origin the source can blow, m (0: nowhere).
    pub fn reach(&self) -> f32 {
        match self.shape {
            SourceShape::Sphere { radius, .. }
            | SourceShape::Vortex { radius, .. }
            | SourceShape::Blast { radius, .. } => radius,
            SourceShape::Fan { range, .. } => range,
            // The far corners of the slab at the end of its travel.
            SourceShape::Gust { width, range, .. } => {
                (range + width).hypot(range * std::f32::consts::FRAC_1_SQRT_2)
            }
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

/// The fade (1 − s²)², 1 at s = 0, 0 with zero slope at |s| ≥ 1.
fn fade(s: f32) -> f32 {
    let t = (1.0 - s * s).max(0.0);
    t * t
}

/// 1 up to `inner`, then fading smoothly to 0 at `outer`.
fn plateau(x: f32, inner: f32, outer: f32) -> f32 {
    if x <= inner {
        1.0
    } else {
        fade((x - inner) / (outer - inner).max(f32::MIN_POSITIVE))
    }
}

/// A source placed in the world for one fixed step: what the field samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlacedSource {
    pub(crate) shape: SourceShape,
    pub(crate) strength: f32,
    pub(crate) pulse: Pulse,
    pub(crate) origin: Vec3A,
    /// World to local rotation (the inverse of the entity's).
    pub(crate) to_local: Quat,
    /// Local to world rotation.
    pub(crate) to_world: Quat,
    /// reach².
    pub(crate) reach2: f32,
    /// Wind time the source started at (blasts).
    pub(crate) start: f64,
}

impl PlacedSource {
    /// `source` at the position and rotation of `affine`, started at wind time `start`.
    /// `None` for a source that blows nothing (zero strength or reach, a non-finite place).
    pub(crate) fn new(source: &WindSource, affine: &Affine3A, start: f64) -> Option<Self> {
        let (_, rotation, origin) = affine.to_scale_rotation_translation();
        let rotation = crate::guard::unit_quat(rotation)?;
        let reach = source.reach();
        let strength = finite(source.strength);
        if !(origin.is_finite() && reach > 0.0 && strength != 0.0) {
            return None;
        }
        Some(Self {
            shape: source.shape,
            strength,
            pulse: source.pulse,
            origin: origin.into(),
            to_local: rotation.inverse(),
            to_world: rotation,
            reach2: reach * reach,
            start,
        })
    }

    /// The velocity this source adds at `p` at wind time `time`, m/s.
    #[inline]
    pub(crate) fn velocity(&self, p: Vec3A, time: f64) -> Vec3 {
        let d = p - self.origin;
        let r2 = d.length_squared();
        if r2.is_nan() || r2 >= self.reach2 {
            return Vec3::ZERO;
        }
        let strength = if self.pulse.is_active() {
            self.strength * self.pulse.factor(time - self.start)
        } else {
            self.strength
        };
        self.inside(Vec3::from(d), r2, time) * strength
    }

    fn inside(&self, d: Vec3, r2: f32, time: f64) -> Vec3 {
        let r = r2.sqrt();
        match self.shape {
            SourceShape::Sphere { radius, velocity } => velocity * fade(r / radius),
            SourceShape::Fan {
                range,
                half_angle,
                speed,
            } => {
                let forward = self.to_world * Vec3::NEG_Z;
                let along = d.dot(forward);
                if along <= 0.0 || r == 0.0 {
                    return Vec3::ZERO;
                }
                let angle = (along / r).min(1.0).acos();
                if angle >= half_angle {
                    return Vec3::ZERO;
                }
                // Outward from the fan (a spreading jet), fading across the cone and along it.
                d / r * (speed * fade(angle / half_angle) * fade(along / range))
            }
            SourceShape::Vortex {
                radius,
                peak_speed,
                updraft,
            } => {
                let local = self.to_local * d;
                let horizontal = (local.x * local.x + local.z * local.z).sqrt();
                let envelope = plateau(r, 0.5 * radius, radius);
                let core = 0.2 * radius;
                // Rankine: solid-body rotation inside the core, 1/r outside.
                let swirl = if horizontal <= core {
                    horizontal / core
                } else {
                    core / horizontal
                };
                let tangent = if horizontal > 0.0 {
                    // +Y × (x, 0, z) / |..| = (z, 0, −x) / |..|: at +X toward −Z.
                    Vec3::new(local.z, 0.0, -local.x) / horizontal
                } else {
                    Vec3::ZERO
                };
                let lift = updraft * fade(horizontal / radius.max(f32::MIN_POSITIVE));
                self.to_world * (tangent * (peak_speed * swirl) + Vec3::Y * lift) * envelope
            }
            SourceShape::Blast {
                peak_speed,
                front_speed,
                radius,
            } => {
                let age = time - self.start;
                if age < 0.0 || r == 0.0 {
                    return Vec3::ZERO;
                }
                let front = (age * f64::from(front_speed)) as f32;
                let width = 0.2 * radius;
                // A shock: the full speed at the front, easing to nothing a band behind it.
                let behind = front - r;
                if behind < 0.0 || behind > width {
                    return Vec3::ZERO;
                }
                let s = behind / width.max(f32::MIN_POSITIVE);
                d / r * (peak_speed * fade(s) * plateau(r, 0.5 * radius, radius))
            }
            SourceShape::Gust {
                strength,
                front_speed,
                width,
                range,
            } => {
                let age = time - self.start;
                let local = self.to_local * d;
                let along = -local.z;
                if age < 0.0 || along < 0.0 || along > range {
                    return Vec3::ZERO;
                }
                let front = (age * f64::from(front_speed)) as f32;
                let behind = front - along;
                if !(0.0..=width).contains(&behind) {
                    return Vec3::ZERO;
                }
                let s = 2.0 * behind / width.max(f32::MIN_POSITIVE) - 1.0;
                let across = local.x.hypot(local.y) / (0.5 * range);
                self.to_world * Vec3::NEG_Z * (strength * fade(s) * fade(across))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn placed(source: WindSource) -> PlacedSource {
        PlacedSource::new(&source, &Affine3A::IDENTITY, 0.0).unwrap()
    }

    #[test]
    fn fades_are_monotone_and_smooth() {
        let mut last = fade(0.0);
        assert_eq!(last, 1.0);
        for i in 1..=100 {
            let v = fade(i as f32 / 100.0);
            assert!(v <= last);
            last = v;
        }
        assert_eq!(fade(1.0), 0.0);
        // Zero slope at the edge: the step into the last 1 % is tiny.
        assert!(fade(0.99) < 5e-4);
    }

    #[test]
    fn a_vortex_turns_right_handed_about_its_axis() {
        let v = placed(WindSource::vortex(5.0, 8.0));
        let at_x = v.velocity(Vec3A::new(1.0, 0.0, 0.0), 0.0);
        assert!(at_x.z < 0.0 && at_x.x.abs() < 1e-6, "{at_x}");
        assert!((at_x.length() - 8.0).abs() < 1e-4, "core edge: {at_x}");
        assert_eq!(v.velocity(Vec3A::ZERO, 0.0), Vec3::ZERO);
        assert_eq!(v.velocity(Vec3A::new(0.0, 0.0, 5.01), 0.0), Vec3::ZERO);
    }
}
