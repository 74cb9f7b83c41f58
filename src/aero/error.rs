//! Why an aero body was rejected: [`AeroError`], the error every aero body's validation returns.

use bevy::reflect::Reflect;
use thiserror::Error;

use crate::error::InvalidValue;

/// Why a body was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Error, Reflect)]
pub enum AeroError {
    /// A number outside its valid range.
    #[error(transparent)]
    Invalid(#[from] InvalidValue),
}

/// A cloth's grid refused inside an aero body (a particle cloth's): the same field and value.
impl From<crate::cloth::ClothError> for AeroError {
    fn from(error: crate::cloth::ClothError) -> Self {
        match error {
            crate::cloth::ClothError::Invalid(invalid) => invalid.into(),
            crate::cloth::ClothError::Count {
                field,
                value,
                reason,
            } => InvalidValue::new(field, value as f32, reason).into(),
        }
    }
}

impl AeroError {
    /// Name of the offending field.
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) => field,
        }
    }
}
