//! The wind's turn of a falling object (eq. 15).

use bevy::math::{Quat, Vec3};

use crate::portable::geometry::{Q, V3};
use crate::portable::lane::Lane;
use crate::portable::transcendental::{clamp, sin_cos};
use crate::wind::WindField;

/// How the wind turns the object (eq. 15): θ = W N(t), leaning downwind. The paper's N(t) is
/// the fBm wind speed |u|; as an angle factor it must be bounded, so N = x / (1 + x) with
/// x = |u| / U_ref: linear in light wind, 1/2 at the reference speed, approaching the designer's
/// maximum W in a gale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindTilt {
    /// W, the largest tilt, rad (|W| ≤ π).
    pub max_angle: f32,
    /// U_ref, m/s.
    pub reference_speed: f32,
}

impl WindTilt {
    /// The tilt of largest angle `max_angle` (W, rad) in `wind`: its reference speed is the
    /// wind's own (1 m/s in still air, where nothing tilts).
    pub fn in_wind(max_angle: f32, wind: Option<&WindField>) -> Self {
        Self {
            max_angle,
            reference_speed: wind.map_or(1.0, |w| w.config().reference_speed),
        }
    }

    /// The rotation that leans the object downwind.
    pub fn rotation(&self, wind: Vec3) -> Quat {
        self.scaled_rotation(wind, 1.0)
    }

    /// [`WindTilt::rotation`] with its angle times `factor` ∈ [0, 1].
    pub(crate) fn scaled_rotation(&self, wind: Vec3, factor: f32) -> Quat {
        wind_tilt(self.max_angle, self.reference_speed, V3::of(wind), factor).quat()
    }
}

/// Eq. 15's tilt of the orientation: θ = W N with N = |u| / (U_ref + |u|), leaning downwind,
/// times `factor` (see [`WindTilt`]).
#[inline(always)]
pub(crate) fn wind_tilt<L: Lane>(max_angle: L, reference_speed: L, wind: V3<L>, factor: L) -> Q<L> {
    let horizontal = (wind.x * wind.x + wind.z * wind.z).sqrt();
    let speed = wind.length_squared().sqrt();
    let pi = L::splat(std::f32::consts::PI);
    let finite = |v: L| v.abs().lt(L::splat(f32::INFINITY));
    let leans = L::and(
        horizontal.gt(L::splat(1e-6)),
        L::and(finite(speed), finite(max_angle)),
    );
    let floor = L::splat(1e-3);
    let n = speed / (L::select(reference_speed.gt(floor), reference_speed, floor) + speed);
    let half = L::splat(0.5) * factor * clamp(max_angle, -pi, pi) * n;
    let (sin, cos) = sin_cos(half);
    let k = sin / horizontal;
    let zero = L::splat(0.0);
    let tilt = Q::new(wind.z * k, zero, -(wind.x * k), cos);
    Q::select(leans, tilt, Q::identity())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wind_tilt_leans_downwind_by_w_n() {
        let tilt = WindTilt {
            max_angle: 0.8,
            reference_speed: 4.0,
        };
        let q = tilt.rotation(Vec3::new(4.0, 0.0, 0.0));
        // Up leans toward +x by W/2 at the reference speed.
        let up = q * Vec3::Y;
        assert!((up.x.atan2(up.y) - 0.4).abs() < 1e-5, "{up:?}");
        assert!((q.length() - 1.0).abs() < 1e-5);
        assert_eq!(tilt.rotation(Vec3::ZERO), Quat::IDENTITY);
        assert_eq!(tilt.rotation(Vec3::NAN), Quat::IDENTITY);
    }
}
