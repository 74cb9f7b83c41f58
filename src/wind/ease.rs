//! Smooth changes of the mean wind ([`WindField::ease_to`](super::field::WindField::ease_to)): weather
//! that builds up or dies down, and a wind that veers, instead of a jump.

use bevy::math::Vec2;
use bevy::reflect::Reflect;

use super::config::WindConfig;
use super::error::WindError;
use crate::error::InvalidValue;

/// Where [`WindField::ease_to`](super::field::WindField::ease_to) is taking the mean wind and how fast
/// it gets there ([`WindField::easing`](super::field::WindField::easing)), and how far it has come:
/// the speed and direction it started from and the wind time since, so that each step is
/// computed from the start in f64 (a step too small for an f32 speed is never lost: an easing of
/// any τ arrives) and a [`WindSnapshot`](super::WindSnapshot) resumes it to the bit.
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
    /// The speed it started from, m/s.
    #[cfg_attr(feature = "serde", serde(default))]
    from_speed: f32,
    /// The unit direction it started from (x, z).
    #[cfg_attr(feature = "serde", serde(default))]
    from_direction: Vec2,
    /// Wind time since it started, s.
    #[cfg_attr(feature = "serde", serde(default))]
    elapsed: f64,
}

impl WindEasing {
    /// An easing toward `speed` and the unit `direction` with time constant τ, starting now from
    /// `from_speed` and the unit `from_direction`.
    pub(super) fn new(
        speed: f32,
        direction: Vec2,
        time_constant: f32,
        from_speed: f32,
        from_direction: Vec2,
    ) -> Self {
        Self {
            speed,
            direction,
            time_constant,
            from_speed,
            from_direction,
            elapsed: 0.0,
        }
    }

    /// Takes `saved`'s τ and, if they are sound (a unit direction, a time ≥ 0), where it started
    /// and how long ago; otherwise (an older snapshot without them) this easing starts now.
    ///
    /// # Errors
    /// A start speed the wind may not have (not finite, negative, or above
    /// [`WindConfig::MAX_REFERENCE_SPEED`]): it would be the reference speed after a step.
    pub(super) fn resume_from(&mut self, saved: &WindEasing) -> Result<(), WindError> {
        InvalidValue::check(
            saved.from_speed.is_finite()
                && (0.0..=WindConfig::MAX_REFERENCE_SPEED).contains(&saved.from_speed),
            "easing.from_speed",
            saved.from_speed,
            crate::error::reason!(
                "must be finite, ≥ 0 and ≤ {:e} m/s",
                WindConfig::MAX_REFERENCE_SPEED
            ),
        )?;
        self.time_constant = saved.time_constant;
        let unit = (saved.from_direction.length_squared() - 1.0).abs() < 1e-3;
        if unit && saved.elapsed.is_finite() && saved.elapsed >= 0.0 {
            self.from_speed = saved.from_speed;
            self.from_direction = saved.from_direction;
            self.elapsed = saved.elapsed;
        }
        Ok(())
    }

    /// Advances the easing by `dt` wind seconds: speed and direction are the fraction
    /// 1 − e^(−t/τ) of the way from where they started (the direction by that fraction of the
    /// angle between, turning the short way), t the time since the start, so the speed follows a
    /// first-order lag and never jumps. Returns the new speed, the new direction and whether the
    /// target is reached (then exactly).
    pub(super) fn step(&mut self, dt: f32) -> (f32, Vec2, bool) {
        self.elapsed += f64::from(dt.max(0.0));
        let decay = if self.time_constant > 0.0 {
            libm::exp(-self.elapsed / f64::from(self.time_constant))
        } else {
            0.0
        };
        let gap = f64::from(self.from_speed) - f64::from(self.speed);
        let next_speed = (f64::from(self.speed) + gap * decay) as f32;
        let angle = f64::from(self.from_direction.angle_to(self.direction));
        let next_direction =
            Vec2::from_angle((angle * (1.0 - decay)) as f32).rotate(self.from_direction);
        let close = (self.speed - next_speed).abs() <= 1e-4 * self.speed.max(1.0)
            && (angle * decay).abs() <= 1e-5;
        if close || decay <= 0.0 {
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
