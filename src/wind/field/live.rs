//! What changes a built [`WindField`] live: its mean speed, direction and pulse, at once or eased
//! ([`WindField::ease_to`]), and its clock.

use bevy::math::{DVec2, Vec2};

use super::super::config::MeanWind;
use super::super::ease::WindEasing;
use super::super::error::WindError;
use super::super::pulse::Pulse;
use super::WindField;
use crate::error::InvalidValue;

/// The field's own setters: for a field used without ECS (a server's, a tool's, a test's). In an
/// app, edit [`WindSettings`](crate::wind::WindSettings) instead: the plugin applies it.
impl WindField {
    /// Changes the mean speed at the reference height at once, keeping the turbulence pattern
    /// (and ending any [`Self::ease_to`]).
    pub fn set_reference_speed(&mut self, speed: f32) -> Result<(), WindError> {
        self.set_mean(MeanWind {
            reference_speed: speed,
            ..self.config.mean()
        })?;
        self.ease = None;
        Ok(())
    }

    /// Changes the horizontal direction (x, z) of the mean wind at once, keeping the pattern
    /// (and ending any [`Self::ease_to`]).
    pub fn set_direction(&mut self, direction: Vec2) -> Result<(), WindError> {
        self.set_mean(MeanWind {
            direction,
            ..self.config.mean()
        })?;
        self.ease = None;
        Ok(())
    }

    /// Sets the periodic swell of the wind's strength ([`Pulse`]) at once.
    ///
    /// # Errors
    /// A magnitude outside [0, 1] or a frequency outside [0, 100] Hz, named.
    pub fn set_pulse(&mut self, pulse: Pulse) -> Result<(), WindError> {
        self.set_mean(MeanWind {
            pulse,
            ..self.config.mean()
        })
    }

    /// Sets the mean wind if it is valid: a new speed or direction books the pattern's travel so
    /// far at the old ones and ends any easing; a new pulse alone changes only the pulse.
    pub(in crate::wind) fn set_mean(&mut self, mean: MeanWind) -> Result<(), WindError> {
        let now = self.config.mean();
        if mean == now {
            return Ok(());
        }
        let config = self.config.with_mean(mean);
        config.validate()?;
        if (mean.reference_speed, mean.direction) != (now.reference_speed, now.direction) {
            self.rebase_drift();
            self.ease = None;
        }
        self.config = config;
        self.derive();
        Ok(())
    }

    /// Goes on from `old` with this field's turbulence: `old`'s clock, its pattern's travel,
    /// easing, mean wind and the settings it took in (what a [`WindRebuild`] does when it lands).
    ///
    /// [`WindRebuild`]: crate::wind::WindRebuild
    pub(in crate::wind) fn carry_on_from(&mut self, old: &WindField) {
        self.continue_clock_of(old);
        self.config = self.config.with_mean(old.config.mean());
        self.taken_in.clone_from(&old.taken_in);
        self.derive();
    }

    /// Books the pattern's travel so far at the current speed and direction, before they change.
    fn rebase_drift(&mut self) {
        self.drift_base = self.drift_at(self.time);
        self.drift_since = self.time;
    }

    /// How far the pattern has travelled at the reference speed by wind time `time`, m (x, z):
    /// the travel booked so far plus the current mean wind times the time since.
    pub(crate) fn drift_at(&self, time: f64) -> DVec2 {
        let span = f64::from(self.config.reference_speed) * (time - self.drift_since);
        self.drift_base + DVec2::new(f64::from(self.along.x), f64::from(self.along.z)) * span
    }

    /// Eases the mean wind toward `speed` (m/s at the reference height) and `direction` (x, z)
    /// with time constant `time_constant` (s of wind time): as the clock advances, both move the
    /// fraction 1 − e^(−dt/τ) of the way each step (the direction turning the short way), so a
    /// storm builds up and a wind veers without a jump; τ = 0 sets them at once. The turbulence
    /// pattern is kept. [`Self::set_reference_speed`] or [`Self::set_direction`] end it.
    ///
    /// # Errors
    /// A speed or direction [`Self::set_reference_speed`] / [`Self::set_direction`] would
    /// refuse, or a negative or non-finite `time_constant`.
    pub fn ease_to(
        &mut self,
        speed: f32,
        direction: Vec2,
        time_constant: f32,
    ) -> Result<(), WindError> {
        let mut target = self.config.clone();
        target.reference_speed = speed;
        target.direction = direction;
        target.validate()?;
        check_time_constant(time_constant)?;
        let direction = crate::guard::unit_vec2(direction).unwrap_or(Vec2::X);
        let now = Vec2::new(self.along.x, self.along.z);
        self.ease = Some(WindEasing::new(
            speed,
            direction,
            time_constant,
            self.config.reference_speed,
            now,
        ));
        if time_constant == 0.0 {
            self.ease_step(0.0);
        }
        Ok(())
    }

    /// Restores an easing (from a [`WindSnapshot`](super::WindSnapshot)) without stepping it:
    /// its target as [`Self::ease_to`] checks it, its τ as well (a NaN or negative τ is refused,
    /// named), and how far it had come (a snapshot without that starts it from now).
    pub(in crate::wind) fn resume_easing(&mut self, saved: &WindEasing) -> Result<(), WindError> {
        let (speed_now, direction_now) = (self.config.reference_speed, self.config.direction);
        check_time_constant(saved.time_constant)?;
        self.ease_to(
            saved.speed,
            saved.direction,
            saved.time_constant.max(f32::MIN_POSITIVE),
        )?;
        // ease_to with τ > 0 changes nothing yet; keep the exact τ and the progress.
        if let Some(ease) = self.ease.as_mut() {
            ease.resume_from(saved)?;
        }
        debug_assert_eq!(
            (speed_now, direction_now),
            (self.config.reference_speed, self.config.direction)
        );
        Ok(())
    }

    /// Where [`Self::ease_to`] is taking the mean wind, if it is.
    pub fn easing(&self) -> Option<WindEasing> {
        self.ease
    }

    fn ease_step(&mut self, dt: f32) {
        let Some(ease) = self.ease.as_mut() else {
            return;
        };
        let (speed, direction, arrived) = ease.step(dt);
        self.rebase_drift();
        self.config.reference_speed = speed;
        self.config.direction = direction;
        if arrived {
            self.ease = None;
        }
        self.derive();
    }

    /// Wind time, s, as f32 (as Bevy's `Time::elapsed_secs`); in full: [`Self::time_f64`].
    pub fn time(&self) -> f32 {
        self.time as f32
    }

    /// Wind time, s, in full, as Bevy's `Time::elapsed_secs_f64` (the clock runs in f64 so that
    /// long sessions keep their precision).
    pub fn time_f64(&self) -> f64 {
        self.time
    }

    /// Sets the wind clock to `time` seconds, clamped to ±[`WindField::MAX_CLOCK`](crate::wind::WindField::MAX_CLOCK) (a non-finite time is
    /// ignored).
    pub fn set_clock(&mut self, time: f64) {
        if time.is_finite() {
            self.time = time.clamp(-WindField::MAX_CLOCK, WindField::MAX_CLOCK);
            self.step_start = self.time;
        }
    }

    /// Advances the wind clock by `dt` seconds times [`Self::time_scale`], unless paused.
    /// A non-finite step is ignored; the clock stays within ±[`WindField::MAX_CLOCK`](crate::wind::WindField::MAX_CLOCK), so even a
    /// `time_scale` of `f32::MAX` leaves [`Self::time`] finite.
    pub fn advance(&mut self, dt: f32) {
        let step = f64::from(dt) * f64::from(self.time_scale);
        self.step_start = self.time;
        if !self.paused && step.is_finite() {
            self.time = (self.time + step).clamp(-WindField::MAX_CLOCK, WindField::MAX_CLOCK);
            self.ease_step(step.abs().min(f64::from(f32::MAX)) as f32);
        }
    }

    /// Takes over `old`'s clock (time, time scale, pause), its [`Self::ease_to`] in progress and
    /// how far its pattern has travelled, so a rebuilt field continues where the old one was.
    pub fn continue_clock_of(&mut self, old: &WindField) {
        self.time = old.time;
        self.time_scale = old.time_scale;
        self.paused = old.paused;
        self.ease = old.ease;
        self.step_start = old.step_start;
        // The pattern's travel so far, booked at the old field's own speed and direction: it
        // goes on from where it is, whatever this field's mean wind.
        self.drift_base = old.drift_at(old.time);
        self.drift_since = old.time;
    }
}

/// An easing's τ: finite and ≥ 0.
fn check_time_constant(time_constant: f32) -> Result<(), WindError> {
    Ok(InvalidValue::check(
        time_constant.is_finite() && time_constant >= 0.0,
        "time_constant",
        time_constant,
        "must be finite and ≥ 0",
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wind::WindConfig;

    #[test]
    fn a_rebuilt_field_goes_on_from_where_the_pattern_was() {
        // The old field blew 5 m/s along +X for 10 s; the new one blows 9 m/s along +Z. At the
        // hand-over the pattern has travelled 50 m along X, and goes on from there.
        let mut old = WindField::new(WindConfig {
            reference_speed: 5.0,
            grid: [16, 16],
            ..WindConfig::default()
        })
        .unwrap();
        for _ in 0..600 {
            old.advance(1.0 / 60.0);
        }
        let mut new = WindField::new(WindConfig {
            reference_speed: 9.0,
            direction: Vec2::Y,
            grid: [16, 16],
            ..WindConfig::default()
        })
        .unwrap();
        new.continue_clock_of(&old);
        let at = old.drift_at(old.time);
        assert!((at - DVec2::new(50.0, 0.0)).length() < 1e-4, "{at}");
        assert_eq!(new.drift_at(new.time), at);
        // One more second: 9 m along +Z from there.
        let later = new.drift_at(new.time + 1.0);
        assert!(
            (later - at - DVec2::new(0.0, 9.0)).length() < 1e-9,
            "{later}"
        );
    }
}
