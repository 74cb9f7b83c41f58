//! How a fall is posed: the orientation of each step (the blend from the last piece, the
//! release's residual fading out, eq. 15's tilt), the shown pose between steps, and what a fall
//! tells about itself.

use bevy::math::cubic_splines::CubicSegment;
use bevy::math::curve::{Curve, EaseFunction};
use bevy::math::{Quat, Vec3};

use super::super::database::TrajectoryDatabase;
use super::super::motion::FallScales;
use super::super::regime::PrimitiveMotion;
use super::super::tilt::WindTilt;
use super::FallPath;
use crate::math::geometry::{Q, V3};
use crate::math::kernels::atan2;

impl FallPath {
    pub(super) fn orientation_now(
        &mut self,
        db: &TrajectoryDatabase,
        wind: Vec3,
        tilt: &WindTilt,
        dt: f32,
    ) -> Quat {
        // Portable quaternion arithmetic throughout (the same bits on every machine).
        let piece = match &self.previous {
            Some(old) => Q::of(old.piece.tilt(db, old.time))
                .slerp(Q::of(self.piece_tilt), smoothstep(old.elapsed / old.length)),
            None => Q::of(self.piece_tilt),
        };
        let synthesised = Q::of(self.yaw()).mul(piece);
        // Unit to rounding: each step's orientation is made afresh, and what is shown is
        // normalised (`smoothed`, `orientation`).
        let Some(release) = self.release.as_mut() else {
            return Q::of(tilt.rotation(wind)).mul(synthesised).quat();
        };
        release.elapsed += dt;
        let w = smoothstep(release.elapsed / release.length);
        let residual = Q::of(release.residual).slerp(Q::identity(), w);
        if w >= 1.0 {
            self.release = None;
        }
        let lean = Q::of(tilt.scaled_rotation(wind, w));
        lean.mul(residual).mul(synthesised).normalize().quat()
    }

    /// The shown pose a fraction `s` ∈ [0, 1] of a step after the second-to-last control point:
    /// a cubic Bézier from p_{i−1} to p_i with Catmull–Rom tangents (bevy_math's
    /// [`CubicSegment::new_bezier`]), one step behind the simulation, and a normalised lerp of the
    /// orientations.
    pub fn smoothed(&self, s: f32) -> (Vec3, Quat) {
        let [p0, p1, p2] = self.points;
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let start_tangent = (p2 - p0) * 0.5;
        let end_tangent = p2 - p1;
        let curve =
            CubicSegment::new_bezier([p1, p1 + start_tangent / 3.0, p2 - end_tangent / 3.0, p2]);
        let [q0, q1] = self.orientations;
        // A step apart, nlerp (glam's lerp: short way, normalised) is slerp to under a degree.
        (curve.position(s), q0.lerp(q1, s))
    }

    /// p_i, the latest control point.
    pub fn position(&self) -> Vec3 {
        self.points[2]
    }

    /// The latest orientation (normalised).
    pub fn orientation(&self) -> Quat {
        self.orientations[1].normalize()
    }

    /// The velocity of the fluid-following part of the motion, m/s.
    pub fn drift(&self) -> Vec3 {
        self.drift
    }

    /// f(t): the still-fluid displacement since release.
    pub fn still_displacement(&self) -> Vec3 {
        self.still
    }

    /// The current primitive motion (Markov state).
    pub fn motion(&self) -> PrimitiveMotion {
        self.motion
    }

    /// The chain's bound: the main motion from the phase diagram.
    pub fn main_motion(&self) -> PrimitiveMotion {
        self.chain.main()
    }

    /// A₀ of the current motion, with its Gaussian draw, m.
    pub fn amplitude(&self) -> f32 {
        self.amplitude
    }

    /// The heading: the rotation about +Y whose local +X the swings glide along.
    pub fn heading(&self) -> Quat {
        self.yaw()
    }

    /// Seconds since release (summed in f64).
    pub fn time(&self) -> f32 {
        self.time as f32
    }

    /// True once on the ground.
    pub fn landed(&self) -> bool {
        self.landed
    }

    /// The sizes of this fall.
    pub fn scales(&self) -> &FallScales {
        &self.scales
    }
}

/// The heading (a rotation about +Y) whose frame has the plate's long axis (local Z) as its z,
/// and the plate's pitch about that axis. A long axis pointing straight up or down gives no
/// heading: `fallback` (an angle about Y) is used.
pub(super) fn heading_and_pitch(rotation: Quat, fallback: f32) -> (Quat, f32) {
    let rotation = Q::of(rotation);
    let long = rotation.rotate(V3::of(Vec3::Z));
    let horizontal = long.x * long.x + long.z * long.z;
    let yaw = Q::from_rotation_y(if horizontal > 1e-6 {
        atan2(long.x, long.z)
    } else {
        fallback
    });
    let chord = yaw.conjugate().rotate(rotation.rotate(V3::of(Vec3::X)));
    (yaw.quat(), atan2(chord.y, chord.x))
}

/// 3x² − 2x³ on x clamped to [0, 1] (bevy_math's [`EaseFunction::SmoothStep`]): how a blend
/// and the release's residual fade.
pub(super) fn smoothstep(x: f32) -> f32 {
    EaseFunction::SmoothStep.sample_clamped(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heading_follows_the_long_axis() {
        // Long axis (local Z) turned to world +X: the plate glides along ±Z.
        let q = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2) * Quat::from_rotation_z(0.3);
        let (yaw, pitch) = heading_and_pitch(q, 0.0);
        assert!(((yaw * Quat::from_rotation_z(pitch)).dot(q)).abs() > 1.0 - 1e-5);
        assert!((pitch - 0.3).abs() < 1e-5, "{pitch}");
    }
}
