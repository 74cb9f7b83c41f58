//! What a body flies in and how hard it is pushed: [`AeroCoefficients`], and [`AeroError`], the
//! error every aero body's validation returns.

use crate::error::InvalidValue;
use bevy::reflect::Reflect;
use thiserror::Error;

/// Largest drag or lift coefficient accepted.
pub(crate) const MAX_COEFFICIENT: f32 = 1.0e3;
/// Largest fluid density accepted, kg/m³ (a hundred times water's).
pub(crate) const MAX_FLUID_DENSITY: f32 = 1.0e5;

/// Fluid and coefficients of a body.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct AeroCoefficients {
    /// C_D (≥ 0). A flat plate broadside: about 1.2.
    pub drag: f32,
    /// C_L (≥ 0).
    pub lift: f32,
    /// ρ of the fluid, kg/m³ (> 0).
    pub density: f32,
}

impl Default for AeroCoefficients {
    /// A flat plate in air: C_D = 1.2, C_L = 1.0.
    fn default() -> Self {
        Self {
            drag: 1.2,
            lift: 1.0,
            density: super::force::AIR_DENSITY,
        }
    }
}

/// Why a body was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Error, Reflect)]
pub enum AeroError {
    /// A number outside its valid range.
    #[error(transparent)]
    Invalid(#[from] InvalidValue),
}

impl AeroError {
    /// Name of the offending field.
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) => field,
        }
    }
}

pub(super) fn check(
    field: &'static str,
    value: f32,
    ok: bool,
    reason: &'static str,
) -> Result<(), AeroError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(AeroError::Invalid(InvalidValue {
            field,
            value,
            reason,
        }))
    }
}

impl AeroCoefficients {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), AeroError> {
        check(
            "drag",
            self.drag,
            (0.0..=MAX_COEFFICIENT).contains(&self.drag),
            "must be within 0..1e3",
        )?;
        check(
            "lift",
            self.lift,
            (0.0..=MAX_COEFFICIENT).contains(&self.lift),
            "must be within 0..1e3",
        )?;
        check(
            "density",
            self.density,
            self.density > 0.0 && self.density <= MAX_FLUID_DENSITY,
            "must be > 0 and ≤ 1e5 kg/m³",
        )
    }
}

/// Limits and constants of [`AeroCoefficients`].
impl AeroCoefficients {
    /// Air at about 20 °C, kg/m³.
    pub const AIR_DENSITY: f32 = crate::aero::force::AIR_DENSITY;

    /// Water at 25 °C, kg/m³.
    pub const WATER_DENSITY: f32 = crate::aero::force::WATER_DENSITY;

    /// Largest drag or lift coefficient accepted.
    pub const MAX_COEFFICIENT: f32 = MAX_COEFFICIENT;

    /// Largest fluid density accepted, kg/m³ (a hundred times water's).
    pub const MAX_FLUID_DENSITY: f32 = MAX_FLUID_DENSITY;
}
