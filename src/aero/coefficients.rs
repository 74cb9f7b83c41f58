//! What a body flies in and how hard it is pushed: [`AeroCoefficients`].

use bevy::reflect::Reflect;

use super::error::AeroError;
use crate::error::InvalidValue;

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
            density: AeroCoefficients::AIR_DENSITY,
        }
    }
}

impl AeroCoefficients {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), AeroError> {
        InvalidValue::check(
            (0.0..=Self::MAX_COEFFICIENT).contains(&self.drag),
            "drag",
            self.drag,
            crate::error::reason!("must be within 0..{:e}", AeroCoefficients::MAX_COEFFICIENT),
        )?;
        InvalidValue::check(
            (0.0..=Self::MAX_COEFFICIENT).contains(&self.lift),
            "lift",
            self.lift,
            crate::error::reason!("must be within 0..{:e}", AeroCoefficients::MAX_COEFFICIENT),
        )?;
        InvalidValue::check(
            self.density > 0.0 && self.density <= Self::MAX_FLUID_DENSITY,
            "density",
            self.density,
            crate::error::reason!(
                "must be > 0 and ≤ {:e} kg/m³",
                AeroCoefficients::MAX_FLUID_DENSITY
            ),
        )?;
        Ok(())
    }
}

/// Limits and constants of [`AeroCoefficients`].
impl AeroCoefficients {
    /// Air at about 20 °C, kg/m³.
    pub const AIR_DENSITY: f32 = 1.204;

    /// Water at 25 °C, kg/m³.
    pub const WATER_DENSITY: f32 = 997.0;

    /// Largest drag or lift coefficient accepted.
    pub const MAX_COEFFICIENT: f32 = 1.0e3;

    /// Largest fluid density accepted, kg/m³ (a hundred times water's).
    pub const MAX_FLUID_DENSITY: f32 = 1.0e5;
}
