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

impl AeroError {
    /// Name of the offending field.
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) => field,
        }
    }
}
