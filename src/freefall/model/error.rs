//! Why an object cannot fall by the paper's model: [`FallError`].

use bevy::reflect::Reflect;
use thiserror::Error;

use crate::error::InvalidValue;

/// Why an object cannot fall by the paper's model.
#[derive(Clone, Copy, Debug, PartialEq, Error, Reflect)]
pub enum FallError {
    /// A number outside its valid range.
    #[error(transparent)]
    Invalid(#[from] InvalidValue),
    /// ρ_s ≤ ρ_f: eq. 3 gives no descent velocity (the object floats or hovers).
    #[error(
        "`density` = {density} kg/m³ is not above the fluid's {fluid_density} kg/m³: it does not fall"
    )]
    LighterThanFluid {
        /// The object's density.
        density: f32,
        /// The fluid's density.
        fluid_density: f32,
    },
}

impl FallError {
    /// Name of the offending field (`"shape.thickness"`, `"density"`, ...).
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) => field,
            Self::LighterThanFluid { .. } => "density",
        }
    }
}
