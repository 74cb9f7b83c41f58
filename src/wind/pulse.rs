//! A periodic swell of the wind's strength, like Unity's WindZone pulse (its magnitude and
//! frequency): the wind breathes without changing its mean.

use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use std::f64::consts::TAU;

use super::error::WindError;
use crate::error::InvalidValue;

/// The wind's strength swells and eases periodically: it is multiplied by
/// `1 + magnitude · sin(2π · frequency · t)` at wind time `t`. The factor averages to 1 over a
/// period (the mean wind is unchanged), peaks at `1 + magnitude` and never drops below
/// `1 − magnitude ≥ 0`, so the wind never turns round. The default (magnitude 0) does nothing.
///
/// On [`WindConfig::pulse`](super::config::WindConfig::pulse) it scales the whole global wind (mean
/// and turbulence; the turbulence pattern still travels at the mean speed); on
/// [`WindSource::pulse`](super::source::WindSource::pulse) it scales that source.
///
/// # Example
///
/// ```
/// use bevy_windfall::wind::{Pulse, WindConfig};
///
/// // A breeze that swells by ±40 % every 8 s.
/// let config = WindConfig { pulse: Pulse::new(0.4, 0.125), ..WindConfig::default() };
/// assert!(config.validate().is_ok());
/// assert!((config.pulse.factor(2.0) - 1.4).abs() < 1e-6); // a quarter period in: the peak
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[reflect(Default, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pulse {
    /// Relative swing of the strength, in [0, 1].
    pub magnitude: f32,
    /// Swells per second, Hz, in [0, [`Pulse::MAX_FREQUENCY`](crate::wind::Pulse::MAX_FREQUENCY)].
    pub frequency: f32,
}

impl Pulse {
    /// A pulse of `magnitude` (relative, [0, 1]) and `frequency` (Hz). Unchecked: see
    /// [`Self::validate`]; [`Self::factor`] clamps.
    pub fn new(magnitude: f32, frequency: f32) -> Self {
        Self {
            magnitude,
            frequency,
        }
    }

    /// Checks both numbers; the error names `pulse.magnitude` or `pulse.frequency`.
    pub fn validate(&self) -> Result<(), WindError> {
        let m = self.magnitude;
        InvalidValue::check(
            m.is_finite() && (0.0..=1.0).contains(&m),
            "pulse.magnitude",
            m,
            "must lie in [0, 1]",
        )?;
        let f = self.frequency;
        InvalidValue::check(
            f.is_finite() && (0.0..=Pulse::MAX_FREQUENCY).contains(&f),
            "pulse.frequency",
            f,
            crate::error::reason!("must lie in [0, {}] Hz", Pulse::MAX_FREQUENCY),
        )?;
        Ok(())
    }

    /// Whether it changes anything.
    pub fn is_active(&self) -> bool {
        self.magnitude > 0.0 && self.frequency > 0.0
    }

    /// This pulse with its magnitude clamped to [0, 1] and its frequency to
    /// [0, [`Pulse::MAX_FREQUENCY`](crate::wind::Pulse::MAX_FREQUENCY)] (a non-finite value counts as 0): what [`Self::factor`] uses.
    pub fn clamped(&self) -> Self {
        let clamp = |v: f32, hi: f32| if v.is_finite() { v.clamp(0.0, hi) } else { 0.0 };
        Self::new(
            clamp(self.magnitude, 1.0),
            clamp(self.frequency, Pulse::MAX_FREQUENCY),
        )
    }

    /// The strength factor at wind time `time` s: `1 + m sin(2π f t)` of [`Self::clamped`], so it
    /// is finite and ≥ 0 for every input.
    pub fn factor(&self, time: f64) -> f32 {
        let Self {
            magnitude: m,
            frequency: f,
        } = self.clamped();
        if m == 0.0 || f == 0.0 || !time.is_finite() {
            return 1.0;
        }
        // The phase modulo one period first, so a long clock keeps its precision.
        let cycles = (time * f64::from(f)).rem_euclid(1.0);
        (1.0 + f64::from(m) * libm::sin(TAU * cycles)).max(0.0) as f32
    }
}

/// Limits and constants of [`Pulse`].
impl Pulse {
    /// Largest pulse frequency, Hz: faster than any wind gust; it keeps the phase 2πft finite and
    /// exact enough in f64 over the whole clock.
    pub const MAX_FREQUENCY: f32 = 100.0;
}
