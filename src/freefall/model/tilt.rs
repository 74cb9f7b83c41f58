//! The wind's turn of a falling object (eq. 15).

use std::f32::consts::PI;

use bevy::math::{Quat, Vec3};

use super::series::sin_cos_small;
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
        let (x, z) = (wind.x, wind.z);
        let horizontal = (x * x + z * z).sqrt();
        let speed = wind.length();
        if !(horizontal > 1e-6 && speed.is_finite() && self.max_angle.is_finite()) {
            return Quat::IDENTITY;
        }
        // N = x / (1 + x) with x = |u| / U_ref, as |u| / (U_ref + |u|): one division.
        let n = speed / (self.reference_speed.max(1e-3) + speed);
        let half = 0.5 * factor * self.max_angle.clamp(-PI, PI) * n;
        // Axis Y × horizontal = (z, 0, −x) / |horizontal|.
        let (sin, cos) = sin_cos_quarter_turn(half);
        let k = sin / horizontal;
        Quat::from_xyzw(z * k, 0.0, -x * k, cos)
    }
}

/// sin and cos of |x| ≤ π/2 by their Taylor series to x¹⁰ (error < 4e-6): no range reduction
/// and no library call on the per-object hot path.
fn sin_cos_quarter_turn(x: f32) -> (f32, f32) {
    if x.is_nan() || x.abs() > std::f32::consts::FRAC_PI_2 {
        return sin_cos_small(x);
    }
    const S: [f32; 4] = [1.0 / 6.0, 1.0 / 120.0, 1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 5] = [
        1.0 / 2.0,
        1.0 / 24.0,
        1.0 / 720.0,
        1.0 / 40_320.0,
        1.0 / 3_628_800.0,
    ];
    let x2 = x * x;
    let sin = x * (1.0 - x2 * (S[0] - x2 * (S[1] - x2 * (S[2] - x2 * S[3]))));
    let cos = 1.0 - x2 * (C[0] - x2 * (C[1] - x2 * (C[2] - x2 * (C[3] - x2 * C[4]))));
    (sin, cos)
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

    #[test]
    fn quarter_turn_series_is_accurate() {
        for i in 0..=1000 {
            let x = -PI / 2.0 + PI * i as f32 / 1000.0;
            let (s, c) = sin_cos_quarter_turn(x);
            assert!(
                (s - x.sin()).abs() < 4e-6 && (c - x.cos()).abs() < 4e-6,
                "{x}"
            );
        }
    }
}
