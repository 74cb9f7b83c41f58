//! The one invalid-value error that every domain's error wraps: the field, the value and what
//! the value must be.

use bevy::reflect::Reflect;
use thiserror::Error;

/// A number outside its valid range: the field it was given for, the value, and what it must
/// be. Every domain error (`WindError`, `FallError`, `ClothError`, `AeroError`) has an
/// `Invalid(InvalidValue)` variant, so one `match` arm reads all of them; `LodInvalid` holds one
/// directly.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::InvalidValue;
/// use bevy_windfall::prelude::*;
///
/// let error = WindConfig { roughness: -1.0, ..default() }.validate().unwrap_err();
/// let WindError::Invalid(InvalidValue { field, value, .. }) = error else { panic!() };
/// assert_eq!((field, value), ("roughness", -1.0));
/// ```
#[derive(Clone, Copy, Debug, Error, Reflect)]
#[reflect(Debug, PartialEq)]
#[error("`{field}` = {value}: {reason}")]
pub struct InvalidValue {
    /// The field's name, as written in the type that holds it (`"roughness"`, `"grid.x"`,
    /// `"release.position"`).
    pub field: &'static str,
    /// The rejected value (the offending component of a vector, NaN for a NaN).
    pub value: f32,
    /// What the value must be.
    pub reason: &'static str,
}

/// Equal when they name the same field for the same reason with the same value, a NaN equal to
/// a NaN: the same refusal is not logged twice.
impl PartialEq for InvalidValue {
    fn eq(&self, other: &Self) -> bool {
        self.field == other.field
            && self.reason == other.reason
            && (self.value == other.value || (self.value.is_nan() && other.value.is_nan()))
    }
}

/// A refusal's reason with its limits formatted from their constants (`reason!("must be ≤ {}",
/// LeafCloud::MAX_LEAVES)`), made once on first use and kept for the program's life, so that
/// [`InvalidValue::reason`] stays a `&'static str` and the error `Copy`: no limit is written twice.
macro_rules! reason {
    ($($format:tt)+) => {{
        static REASON: std::sync::LazyLock<String> =
            std::sync::LazyLock::new(|| format!($($format)+));
        REASON.as_str()
    }};
}
pub(crate) use reason;

impl InvalidValue {
    /// The error naming `field`, its `value` and what it must be: the one way every domain's
    /// error is made (each domain's error converts from it with `?` or `.into()`).
    pub(crate) fn new(field: &'static str, value: f32, reason: &'static str) -> Self {
        Self {
            field,
            value,
            reason,
        }
    }

    /// `Ok` when `ok`, otherwise the error naming `field`.
    pub(crate) fn check(
        ok: bool,
        field: &'static str,
        value: f32,
        reason: &'static str,
    ) -> Result<(), Self> {
        if ok {
            Ok(())
        } else {
            Err(Self::new(field, value, reason))
        }
    }
}
