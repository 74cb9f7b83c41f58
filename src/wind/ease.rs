//! Smooth changes of the mean wind ([`WindField::ease_to`](super::field::WindField::ease_to)): weather
//! that builds up or dies down, and a wind that veers, instead of a jump.

use bevy::math::Vec2;
use bevy::reflect::Reflect;

/// Where [`WindField::ease_to`](super::field::WindField::ease_to) is taking the mean wind and how fast
/// it gets there ([`WindField::easing`](super::field::WindField::easing)).
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WindEasing {
    /// Target speed at the reference height, m/s.
    pub speed: f32,
    /// Target direction, a unit vector (x, z).
    pub direction: Vec2,
    /// τ, s of wind time.
    pub time_constant: f32,
}

impl WindEasing {
    /// One step of `dt` wind seconds from `speed` and the unit `direction`: both move the
    /// fraction 1 − e^(−dt/τ) of the way (the direction by that fraction of the angle between,
    /// turning the short way), so the speed follows a first-order lag and never jumps. Returns
    /// the new speed, the new direction and whether the target is reached (then exactly).
    pub(super) fn step(&self, speed: f32, direction: Vec2, dt: f32) -> (f32, Vec2, bool) {
        let k = if self.time_constant > 0.0 {
            (1.0 - (-dt / self.time_constant).exp()).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let angle = direction.angle_to(self.direction);
        let next_speed = speed + (self.speed - speed) * k;
        let next_direction = Vec2::from_angle(angle * k).rotate(direction);
        let close = (self.speed - next_speed).abs() <= 1e-4 * self.speed.max(1.0)
            && (angle * (1.0 - k)).abs() <= 1e-5;
        if close || k >= 1.0 {
            (self.speed, self.direction, true)
        } else {
            (
                next_speed,
                next_direction.normalize_or(self.direction),
                false,
            )
        }
    }
}
