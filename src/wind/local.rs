//! What local wind pieces (a [`WindSource`](super::source::WindSource) or a
//! [`WindShelter`](super::shelter::WindShelter)) share: where one stands for a fixed step
//! ([`Placement`]), the sizes their constructors accept, and the fade at their edges.

use bevy::math::{Quat, Vec3A};

use super::error::WindError;
use crate::error::InvalidValue;
use crate::guard::MAX_COORDINATE;

/// An origin and a rotation in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Placement {
    /// Where it stands.
    pub(crate) origin: Vec3A,
    /// Local to world rotation.
    pub(crate) to_world: Quat,
    /// World to local rotation (the inverse of `to_world`).
    pub(crate) to_local: Quat,
}

impl Placement {
    /// At `origin`, turned by `rotation` (normalised), or `None` when either is not finite (or
    /// the rotation has no length) or the origin lies beyond ±[`MAX_COORDINATE`].
    pub(crate) fn new(origin: Vec3A, rotation: Quat) -> Option<Self> {
        let rotation = crate::guard::unit_quat(rotation)?;
        (origin.is_finite() && origin.abs().max_element() <= MAX_COORDINATE).then(|| Self {
            origin,
            to_world: rotation,
            to_local: rotation.inverse(),
        })
    }
}

/// `Ok` for a size in [0, `MAX_COORDINATE`], otherwise an error naming `field`: what the `try_`
/// constructors of sources and shelters refuse.
pub(crate) fn check_size(field: &'static str, value: f32) -> Result<(), WindError> {
    let ok = (0.0..=MAX_COORDINATE).contains(&value) && value.is_finite();
    Ok(InvalidValue::check(
        ok,
        field,
        value,
        "must be finite, ≥ 0 and ≤ MAX_COORDINATE",
    )?)
}

/// The fade (1 − s²)², 1 at s = 0, 0 with zero slope at |s| ≥ 1: how a source's velocity and a
/// shelter's calm end at their edges.
pub(crate) fn fade(s: f32) -> f32 {
    let t = (1.0 - s * s).max(0.0);
    t * t
}

/// A size as given, held to [`MAX_COORDINATE`] (nothing reaches farther than the world goes),
/// or 0 for a negative or NaN one (which then places nothing).
pub(crate) fn size(v: f32) -> f32 {
    if v.is_finite() {
        v.clamp(0.0, MAX_COORDINATE)
    } else {
        0.0
    }
}
