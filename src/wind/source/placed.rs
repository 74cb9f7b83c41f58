//! A [`WindSource`] placed in the world for one fixed step: what the field samples, the
//! velocity of each shape (sphere, fan, vortex, blast, gust).

use bevy::math::{Quat, Vec3, Vec3A};

use super::super::local::{Placement, fade};
use super::super::pulse::Pulse;
use super::{SourceShape, WindSource};
use crate::portable::geometry::{Q, V3};
use crate::portable::transcendental::acos;

/// 1 up to `inner`, then fading smoothly to 0 at `outer`.
fn plateau(x: f32, inner: f32, outer: f32) -> f32 {
    if x <= inner {
        1.0
    } else {
        fade((x - inner) / (outer - inner).max(f32::MIN_POSITIVE))
    }
}

/// The most any one source adds, m/s per axis: far beyond any wind, and small enough that the
/// sum of any number of sources a game can hold stays finite.
pub(crate) const MAX_SOURCE_SPEED: f32 = 1.0e6;

/// The one guard on what a source adds: a non-finite velocity (a NaN or infinite field set by
/// hand) adds nothing, a huge one is held to ±[`MAX_SOURCE_SPEED`] per axis, so one bad source
/// never cancels the others at a point (the sum stays finite).
fn guarded(v: Vec3) -> Vec3 {
    if v.is_finite() {
        v.clamp(
            Vec3::splat(-MAX_SOURCE_SPEED),
            Vec3::splat(MAX_SOURCE_SPEED),
        )
    } else {
        Vec3::ZERO
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
    /// `source` at `place`, started at wind time `start`.
    /// `None` for a source that blows nothing (zero strength or reach). The plugin places only
    /// sources that pass [`WindSource::validate`]; whatever slips through is caught by the one
    /// guard on what a source adds.
    pub(crate) fn new(source: &WindSource, place: &Placement, start: f64) -> Option<Self> {
        let reach = source.reach();
        let strength = if source.strength.is_finite() {
            source.strength
        } else {
            0.0
        };
        if !(reach > 0.0 && reach.is_finite() && strength != 0.0) {
            return None;
        }
        Some(Self {
            shape: source.shape,
            strength,
            pulse: source.pulse,
            origin: place.origin,
            to_local: place.to_local,
            to_world: place.to_world,
            reach2: reach * reach,
            start,
        })
    }

    /// The velocity this source adds at `p` at wind time `time`, m/s.
    #[inline]
    pub(crate) fn velocity(&self, p: Vec3A, time: f64) -> Vec3 {
        let d = p - self.origin;
        let r2 = Vec3::from(d).length_squared();
        if r2.is_nan() || r2 >= self.reach2 {
            return Vec3::ZERO;
        }
        let mut strength = if self.pulse.is_active() {
            self.strength * self.pulse.factor(time - self.start)
        } else {
            self.strength
        };
        if matches!(self.shape, SourceShape::Blast { .. }) {
            // A blast blows outward, never inward, whatever its strength's sign.
            strength = strength.max(0.0);
        }
        guarded(self.inside(Vec3::from(d), r2, time) * strength)
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
                let forward = turn(self.to_world, Vec3::NEG_Z);
                let along = d.dot(forward);
                if along <= 0.0 || r == 0.0 {
                    return Vec3::ZERO;
                }
                let angle = acos((along / r).min(1.0));
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
                let local = turn(self.to_local, d);
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
                turn(
                    self.to_world,
                    tangent * (peak_speed * swirl) + Vec3::Y * lift,
                ) * envelope
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
                d / r * (peak_speed.max(0.0) * fade(s) * plateau(r, 0.5 * radius, radius))
            }
            SourceShape::Gust {
                strength,
                front_speed,
                width,
                range,
            } => {
                let age = time - self.start;
                let local = turn(self.to_local, d);
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
                let across = (local.x * local.x + local.y * local.y).sqrt() / (0.5 * range);
                turn(self.to_world, Vec3::NEG_Z) * (strength * fade(s) * fade(across))
            }
        }
    }
}

/// `v` turned by the unit quaternion `q`, in portable arithmetic (glam's quaternion product
/// sums its terms in another order with SIMD than without).
pub(crate) fn turn(q: Quat, v: Vec3) -> Vec3 {
    Q::of(q).rotate(V3::of(v)).vec3()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn placed(source: WindSource) -> PlacedSource {
        let here = Placement::new(Vec3A::ZERO, Quat::IDENTITY).unwrap();
        PlacedSource::new(&source, &here, 0.0).unwrap()
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
