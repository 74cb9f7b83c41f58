//! Configuration of a [`WindField`](super::field::WindField) and its validation.

use bevy::math::Vec2;

use super::pulse::Pulse;
use crate::spectrum::FftBackend;
use bevy::reflect::Reflect;

use super::error::WindError;
use crate::error::InvalidValue;

/// Where the turbulence lives in space.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SpatialMode {
    /// One horizontal 2-D field at the reference height, carried to other heights by the log-law
    /// ratio of eq. 14 (free-fall paper). Cheap: the paper's choice for real time.
    Plane,
    /// A full 3-D volume of `vertical_nodes` layers from the ground up, periodic vertically too.
    Volume {
        /// Grid nodes along Y.
        vertical_nodes: usize,
    },
}

/// How the turbulence changes in time.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TemporalMode {
    /// Taylor's frozen turbulence: the pattern only translates with the mean wind.
    Frozen,
    /// The pattern translates and also evolves, read from a noise field with one more (time)
    /// dimension that is periodic, so it never runs out.
    Evolving {
        /// Grid nodes along the time axis.
        samples: usize,
        /// Seconds after which the evolution repeats.
        period: f32,
    },
}

/// Everything that defines a [`WindField`](super::field::WindField). Y is up.
///
/// | field | unit | default | meaning |
/// |---|---|---|---|
/// | `reference_speed` | m/s | 4.0 | mean wind speed U(h_ref) (a gentle breeze) |
/// | `reference_height` | m | 10.0 | h_ref, where `reference_speed` holds (standard 10 m); ≥ e^0.1 z0 ([`WindConfig::MIN_LOG_RATIO`](crate::wind::WindConfig::MIN_LOG_RATIO)) |
/// | `roughness` | m | 0.3 | z0 of the log law (0.3: scattered trees, the paper's value) |
/// | `direction` | – | (1, 0) | horizontal direction (x, z) the wind blows toward |
/// | `beta` | – | 5/3 | spectral exponent (Kolmogorov) |
/// | `turbulence_intensity` | – | `None` | σ_u / U(h_ref); `None` is 1/ln(h_ref/z0), i.e. σ_u = u*/κ ≈ 2.5 u* |
/// | `spatial` | – | `Plane` | [`SpatialMode`] |
/// | `temporal` | – | `Frozen` | [`TemporalMode`] |
/// | `grid` | nodes | [128, 128] | horizontal nodes along x and z |
/// | `cell_size` | m | 1.0 | distance between grid nodes |
/// | `seed` | – | 0 | seed of the turbulence |
/// | `fft` | – | `Portable` | [`FftBackend`]: same bits on every machine, or SIMD speed |
/// | `pulse` | – | none | [`Pulse`]: a periodic swell of the whole wind (Unity's pulse magnitude and frequency) |
#[derive(Clone, Debug, PartialEq, Reflect)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WindConfig {
    /// Mean wind speed at `reference_height`, m/s.
    pub reference_speed: f32,
    /// Height where `reference_speed` is given, m.
    pub reference_height: f32,
    /// Roughness length z0, m.
    pub roughness: f32,
    /// Horizontal direction (x, z) the wind blows toward; need not be normalised.
    pub direction: Vec2,
    /// Spectral exponent β of the turbulence.
    pub beta: f32,
    /// σ_u / U(h_ref); `None` for the surface-layer value 1/ln(h_ref/z0).
    pub turbulence_intensity: Option<f32>,
    /// 2-D plane or 3-D volume.
    pub spatial: SpatialMode,
    /// Frozen or evolving.
    pub temporal: TemporalMode,
    /// Horizontal grid nodes along x and z.
    pub grid: [usize; 2],
    /// Distance between neighbouring grid nodes, m.
    pub cell_size: f32,
    /// Seed of the turbulence.
    pub seed: u64,
    /// Planner of the inverse FFT: `Portable` (same bits everywhere) or `Simd` (faster).
    #[reflect(ignore)]
    pub fft: FftBackend,
    /// A periodic swell of the wind's strength; applies at once, without a rebuild.
    #[cfg_attr(feature = "serde", serde(default))]
    pub pulse: Pulse,
}

impl Default for WindConfig {
    fn default() -> Self {
        Self {
            reference_speed: 4.0,
            reference_height: 10.0,
            roughness: 0.3,
            direction: Vec2::X,
            beta: 5.0 / 3.0,
            turbulence_intensity: None,
            spatial: SpatialMode::Plane,
            temporal: TemporalMode::Frozen,
            grid: [128, 128],
            cell_size: 1.0,
            seed: 0,
            fft: FftBackend::Portable,
            pulse: Pulse::default(),
        }
    }
}

impl WindConfig {
    /// The default wind (over scattered trees, z0 = 0.3 m) at Beaufort force `force` (clamped
    /// to 12): [`WindConfig::BEAUFORT_SPEEDS`](crate::wind::WindConfig::BEAUFORT_SPEEDS) at a reference height of 10 m, where the scale is defined.
    pub fn beaufort(force: u8) -> Self {
        Self {
            reference_speed: Self::BEAUFORT_SPEEDS[usize::from(force.min(12))],
            reference_height: 10.0,
            ..Self::default()
        }
    }
}

fn check_axis(field: &'static str, len: usize) -> Result<(), WindError> {
    if len >= 2 {
        Ok(())
    } else {
        Err(WindError::GridAxis { field, len })
    }
}

impl WindConfig {
    /// Checks every field; the first bad one is returned.
    pub fn validate(&self) -> Result<(), WindError> {
        let z0 = self.roughness;
        InvalidValue::check(
            z0.is_finite() && z0 > 0.0,
            "roughness",
            z0,
            "must be finite and > 0",
        )?;
        let h = self.reference_height;
        // Checked on what is used, ln(h/z0) (eq. 10's denominator), not on h > z0 alone: one
        // f32 step above z0 would round the logarithm to 0 and every sample to NaN.
        InvalidValue::check(
            h.is_finite()
                && h > z0
                && crate::portable::transcendental::ln(h) - crate::portable::transcendental::ln(z0)
                    >= WindConfig::MIN_LOG_RATIO,
            "reference_height",
            h,
            "must be finite and at least 1.105 × `roughness` (ln(h/z0) ≥ 0.1)",
        )?;
        let u = self.reference_speed;
        InvalidValue::check(
            u.is_finite() && (0.0..=Self::MAX_REFERENCE_SPEED).contains(&u),
            "reference_speed",
            u,
            crate::error::reason!(
                "must be finite, ≥ 0 and ≤ {:e} m/s",
                WindConfig::MAX_REFERENCE_SPEED
            ),
        )?;
        let d = self.direction;
        InvalidValue::check(
            crate::guard::unit_vec2(d).is_some(),
            "direction",
            crate::guard::largest_component(d.extend(0.0)),
            "must be finite and non-zero",
        )?;
        InvalidValue::check(
            self.beta.is_finite() && self.beta >= 0.0,
            "beta",
            self.beta,
            "must be finite and ≥ 0",
        )?;
        if let Some(i) = self.turbulence_intensity {
            InvalidValue::check(
                i.is_finite() && (0.0..=Self::MAX_TURBULENCE_INTENSITY).contains(&i),
                "turbulence_intensity",
                i,
                crate::error::reason!(
                    "must be finite, ≥ 0 and ≤ {}",
                    WindConfig::MAX_TURBULENCE_INTENSITY
                ),
            )?;
        }
        check_axis("grid.x", self.grid[0])?;
        check_axis("grid.z", self.grid[1])?;
        InvalidValue::check(
            self.cell_size.is_finite() && self.cell_size > 0.0,
            "cell_size",
            self.cell_size,
            "must be finite and > 0",
        )?;
        let mut nodes = self.grid[0].saturating_mul(self.grid[1]);
        if let SpatialMode::Volume { vertical_nodes } = self.spatial {
            check_axis("spatial.vertical_nodes", vertical_nodes)?;
            nodes = nodes.saturating_mul(vertical_nodes);
        }
        if let TemporalMode::Evolving { samples, period } = self.temporal {
            check_axis("temporal.samples", samples)?;
            InvalidValue::check(
                period.is_finite() && period > 0.0,
                "temporal.period",
                period,
                "must be finite and > 0",
            )?;
            nodes = nodes.saturating_mul(samples);
        }
        if nodes > crate::spectrum::Synthesizer::MAX_NODES {
            return Err(WindError::TooManyNodes {
                field: "grid",
                nodes,
            });
        }
        self.pulse.validate()
    }
}

/// Limits and constants of [`WindConfig`].
impl WindConfig {
    /// Largest grid (including the time axis) a field may have: the spectral synthesis' budget,
    /// [`WindConfig::MAX_NODES`](crate::wind::WindConfig::MAX_NODES) = 2^26 nodes (768 MiB of samples).
    pub const MAX_NODES: usize = crate::spectrum::Synthesizer::MAX_NODES;

    /// Mean wind speed at 10 m, m/s, for each Beaufort force 0–12: the middle of the WMO range of
    /// the force (force 0: calm, below 0.3 m/s; force 12: the lower bound of hurricane force,
    /// 32.7 m/s).
    pub const BEAUFORT_SPEEDS: [f32; 13] = [
        0.1, 0.9, 2.45, 4.4, 6.7, 9.35, 12.3, 15.5, 18.95, 22.6, 26.45, 30.55, 32.7,
    ];

    /// Highest accepted `reference_speed`, m/s (ten times a hurricane's, far past any use).
    pub const MAX_REFERENCE_SPEED: f32 = 1.0e4;

    /// Highest accepted `turbulence_intensity`.
    pub const MAX_TURBULENCE_INTENSITY: f32 = 10.0;

    /// Least accepted ln(h_ref/z0): the reference height is at least e^0.1 ≈ 1.105 times the
    /// roughness length. It keeps eq. 10's u* = κU/ln(h/z0) finite and the default turbulence
    /// intensity 1/ln(h/z0) within [`WindConfig::MAX_TURBULENCE_INTENSITY`](crate::wind::WindConfig::MAX_TURBULENCE_INTENSITY).
    pub const MIN_LOG_RATIO: f32 = 0.1;
}

/// The mean wind: the fields of [`WindConfig`] that apply at once, without a rebuild (speed,
/// direction, pulse). They are listed here only; everything else is the turbulence, which a
/// change rebuilds ([`WindRebuild`](super::rebuild::WindRebuild)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MeanWind {
    pub(crate) reference_speed: f32,
    pub(crate) direction: Vec2,
    pub(crate) pulse: Pulse,
}

impl WindConfig {
    /// Its mean wind.
    pub(crate) fn mean(&self) -> MeanWind {
        MeanWind {
            reference_speed: self.reference_speed,
            direction: self.direction,
            pulse: self.pulse,
        }
    }

    /// The same configuration with the mean wind `mean`.
    pub(crate) fn with_mean(&self, mean: MeanWind) -> Self {
        Self {
            reference_speed: mean.reference_speed,
            direction: mean.direction,
            pulse: mean.pulse,
            ..self.clone()
        }
    }

    /// Whether `self` and `other` have the same turbulence (everything but the mean wind): the
    /// same field, up to its mean wind.
    pub(crate) fn same_turbulence(&self, other: &Self) -> bool {
        *self == other.with_mean(self.mean())
    }
}
