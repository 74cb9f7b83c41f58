//! Where and how a fall starts ([`FallRelease`]) and the bounds a fall keeps to.

use crate::error::InvalidValue;
use bevy::math::{Quat, Vec3};

use super::error::FallError;

/// Where and how an object is let go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FallRelease {
    /// Position, m.
    pub position: Vec3,
    /// Orientation: the plate in the local XZ plane with its long axis along local Z (the axis
    /// it tumbles about). `None`: flat, with a heading drawn from the seed.
    pub rotation: Option<Quat>,
    /// Velocity of the part of the motion that follows the fluid, m/s (0 from a hand; a fall
    /// released again in mid-air keeps its own).
    pub velocity: Vec3,
    /// Height of the ground, m.
    pub ground: f32,
}

/// How far above the ground a lifted object starts, m.
pub(crate) const LIFT_OFF_HOP: f32 = 0.01;

impl FallRelease {
    /// Let go at rest at `position`, flat, with a heading from the seed.
    pub fn at(position: Vec3, ground: f32) -> Self {
        Self {
            position,
            rotation: None,
            velocity: Vec3::ZERO,
            ground,
        }
    }

    /// Checks that a fall can start here: `position` and `ground` finite and within
    /// ±[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE) (or `ground` = −∞: no ground), `rotation`
    /// (if any) finite and not zero
    /// (any length: it is normalised), `velocity` finite and within [`FallRelease::MAX_SPEED`](crate::freefall::FallRelease::MAX_SPEED).
    /// The fields are named `release.position`, ... ; the [`FallPlugin`] releases from the
    /// entity's `Transform` and [`FallSettings::ground_height`].
    ///
    /// [`FallPlugin`]: crate::freefall::FallPlugin
    /// [`FallSettings::ground_height`]: crate::freefall::FallSettings::ground_height
    pub fn validate(&self) -> Result<(), FallError> {
        if let Some(value) = crate::guard::bad_position(self.position) {
            InvalidValue::check(
                false,
                "release.position",
                value,
                crate::guard::position_reason(),
            )?;
        }
        check_ground(self.ground, true)?;
        if let Some(q) = self.rotation {
            InvalidValue::check(
                crate::guard::unit_quat(q).is_some(),
                "release.rotation",
                q.length(),
                "must be a finite, non-zero quaternion",
            )?;
        }
        let speed = crate::guard::largest_component(self.velocity);
        InvalidValue::check(
            speed.abs() <= FallRelease::MAX_SPEED,
            "release.velocity",
            speed,
            crate::error::reason!(
                "must be finite and within ±{:e} m/s",
                FallRelease::MAX_SPEED
            ),
        )?;
        Ok(())
    }
}

/// Limits and constants of [`FallRelease`].
impl FallRelease {
    /// A resting object is lifted again when the wind where it lies is faster than this many times
    /// its descent speed U (eq. 3). A flat plate on the ground meets the flow at a small angle
    /// (C_L ≈ 0.2); its lift ½ ρ_f C_L A |w|² beats its weight ρ_s A b g when
    /// |w|² > 2 ρ_s b g / (ρ_f C_L) ≈ 10 U², so |w| > 3.2 U. A leaf (U ≈ 1 m/s) needs a strong gust
    /// or a blast; the paper's coin in air (U ≈ 5.7 m/s) a gale. Near the ground the log law's mean
    /// wind is small (zero below the roughness length), so it is mostly gusts and local sources
    /// ([`WindSource`](crate::wind::WindSource)) that lift things.
    pub const LIFT_OFF_FACTOR: f32 = 3.0;

    /// Largest speed, m/s, a fall may be released with (and the largest wind it feels).
    pub const MAX_SPEED: f32 = 1.0e4;

    /// Longest step [`FallPath::advance`](crate::freefall::FallPath::advance) takes, s; a
    /// longer one is cut to it.
    pub const MAX_STEP: f32 = 60.0;
}

/// The one check of a ground height, a single object's and a cloud's (`release.ground`): within
/// ±[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE), or −∞ (no ground: the fall never ends)
/// where `endless` allows it.
pub(crate) fn check_ground(ground: f32, endless: bool) -> Result<(), FallError> {
    let within = ground.abs() <= crate::guard::MAX_COORDINATE;
    if within || (endless && ground == f32::NEG_INFINITY) {
        return Ok(());
    }
    let reason = if endless {
        crate::guard::ground_reason()
    } else {
        crate::guard::position_reason()
    };
    Err(InvalidValue::new("release.ground", ground, reason).into())
}
