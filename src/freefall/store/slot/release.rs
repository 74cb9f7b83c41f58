//! How a fall of the store is let go, and lifted again from the ground: the chain's first
//! motion, a heading, the first piece, the release orientation fading into the synthesised one.

use std::f32::consts::TAU;
use std::sync::Arc;

use bevy::math::{Quat, Vec3};

use super::Slot;
use crate::freefall::model::FallModel;
use crate::freefall::model::motion::Glide;
use crate::freefall::model::release::{FallRelease, LIFT_OFF_HOP};
use crate::freefall::store::block::{ConstantStorage, FallConstants};
use crate::freefall::store::cold::{Cold, FallStart, ReleaseFade};
use crate::freefall::store::kernel::sample_piece;
use crate::portable::geometry::{Q, V3};
use crate::portable::transcendental::atan2;

/// The release orientation fades into the synthesised one over this many swings ...
const RELEASE_SWINGS: f32 = 1.0;
/// ... and at least this long, s.
const MIN_RELEASE: f32 = 0.25;
/// The latest a fall begins in its first piece, a fraction of it (it begins inside).
const MAX_PHASE: f32 = 0.999;

impl<K: ConstantStorage> Slot<'_, K> {
    /// Lets the fall go as `start` says, its clock at `clock` (its first step is then taken
    /// at once, over the time since): the chain's first motion, a heading from the seed (or
    /// the release orientation's long axis), the first piece (begun `start.phase` into it),
    /// the release orientation fading into the synthesised one over a swing.
    pub fn release(&mut self, model: &FallModel, start: &FallStart, clock: f64) {
        let db = model.database();
        let constants = FallConstants::new(
            &start.scales,
            start.release.ground,
            start.max_angle,
            start.lod,
        );
        K::set(&mut self.block.consts, self.k, &constants);
        let releases = self.cold.releases;
        *self.cold = Cold::blank(start);
        self.cold.releases = releases;
        let cold = &mut *self.cold;
        let motion = cold.chain.start(&mut cold.rng);
        let random_yaw = cold.rng.uniform() * TAU;
        cold.glide = if cold.rng.coin() {
            Glide::Left
        } else {
            Glide::Right
        };
        let release = &start.release;
        let rotation = release.rotation.and_then(crate::guard::unit_quat);
        let (heading, theta) = match rotation {
            Some(q) => heading_and_pitch(q, random_yaw),
            None => (Q::from_rotation_y(random_yaw).quat(), 0.0),
        };
        let finite = |v: Vec3| if v.is_finite() { v } else { Vec3::ZERO };
        let position = finite(release.position);
        let drift = finite(release.velocity);
        cold.enter_motion(motion);
        cold.piece = cold.build_piece(db, theta, 1.0, None);
        // The fall begins `phase` into its first piece: its clock and offset there, the time
        // since release still 0, the motion's sojourn counted from here.
        let k = self.k;
        let phase = if start.phase.is_finite() {
            start.phase.clamp(0.0, MAX_PHASE)
        } else {
            0.0
        };
        let into = phase * cold.piece.duration();
        cold.piece_start = -f64::from(into);
        cold.sojourn += into;
        self.block.write_piece(k, &cold.piece, db);
        let (offset, piece_tilt) = sample_piece::<f32, K>(self.block, k, db, into);
        let synthesised = Q::of(heading).mul(piece_tilt);
        let shown = match rotation {
            Some(q) => {
                cold.release = Some(Box::new(ReleaseFade {
                    residual: Q::of(q).mul(synthesised.conjugate()).normalize().quat(),
                    elapsed: 0.0,
                    length: (RELEASE_SWINGS * start.scales.swing_time()).max(MIN_RELEASE),
                }));
                q
            }
            None => synthesised.quat(),
        };
        let h = &mut self.block.hot;
        for (column, value) in [
            (&mut h.p0x, position.x),
            (&mut h.p0y, position.y),
            (&mut h.p0z, position.z),
            (&mut h.p1x, position.x),
            (&mut h.p1y, position.y),
            (&mut h.p1z, position.z),
            (&mut h.p2x, position.x),
            (&mut h.p2y, position.y),
            (&mut h.p2z, position.z),
            (&mut h.q0x, shown.x),
            (&mut h.q0y, shown.y),
            (&mut h.q0z, shown.z),
            (&mut h.q0w, shown.w),
            (&mut h.q1x, shown.x),
            (&mut h.q1y, shown.y),
            (&mut h.q1z, shown.z),
            (&mut h.q1w, shown.w),
            (&mut h.cx, 0.0),
            (&mut h.cy, 0.0),
            (&mut h.cz, 0.0),
            (&mut h.vx, drift.x),
            (&mut h.vy, drift.y),
            (&mut h.vz, drift.z),
            (&mut h.sx, 0.0),
            (&mut h.sy, 0.0),
            (&mut h.sz, 0.0),
            (&mut h.t, into),
            (&mut h.ox, offset.x),
            (&mut h.oy, offset.y),
            (&mut h.oz, offset.z),
            (&mut h.hc, heading.w),
            (&mut h.hs, heading.y),
            // The heading's full turn, for the increments: cos ψ, sin ψ from the half angle.
            (&mut h.tc, heading.w * heading.w - heading.y * heading.y),
            (&mut h.ts, 2.0 * heading.w * heading.y),
            (&mut h.landed, 0.0),
            (&mut h.rest, 0.0),
            (&mut h.span, 0.0),
        ] {
            column[k] = value;
        }
        self.block.updated[k] = clock;
        self.set_plain();
    }

    /// Lets a resting fall go again in a wind strong enough to lift it (see
    /// [`FallRelease::LIFT_OFF_FACTOR`]): from where it lies, a hop above the ground, in the
    /// orientation it lies in, at the wind's velocity plus half the wind's speed upward, with a
    /// new seed from its own stream (so the same run lifts it the same way). Its clock and
    /// Markov count go on.
    pub(super) fn lift_off(&mut self, kind: &K, model: &FallModel, wind: Vec3) {
        let h = &self.block.hot;
        let k = self.k;
        let position = Vec3::new(h.p2x[k], h.p2y[k], h.p2z[k]);
        let rotation = Quat::from_xyzw(h.q1x[k], h.q1y[k], h.q1z[k], h.q1w[k]);
        let constants = kind.get(&self.block.consts, k);
        let start = FallStart {
            scales: self.cold.scales,
            chain: Arc::clone(&self.cold.chain),
            seed: self.cold.rng.bits(),
            release: FallRelease {
                position: position + Vec3::Y * LIFT_OFF_HOP,
                rotation: Some(rotation),
                velocity: wind + Vec3::Y * (0.5 * wind.length()),
                ground: constants.ground,
            },
            max_angle: constants.max_angle,
            lod: constants.lod,
            phase: 0.0,
        };
        let (time, markov_steps) = (self.time(), self.cold.markov_steps);
        let (updated, span) = (self.block.updated[k], self.block.hot.span[k]);
        let easing = self.cold.easing.take();
        self.release(model, &start, updated);
        self.cold.piece_start = time;
        self.cold.markov_steps = markov_steps;
        self.cold.easing = easing;
        self.block.hot.span[k] = span;
        self.cold.changed = true;
        self.cold.lifted = true;
        self.set_plain();
    }
}

/// The heading (a rotation about +Y) whose frame has the plate's long axis (local Z) as its z,
/// and the plate's pitch about that axis. A long axis pointing straight up or down gives no
/// heading: `fallback` (an angle about Y) is used.
pub(crate) fn heading_and_pitch(rotation: Quat, fallback: f32) -> (Quat, f32) {
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
