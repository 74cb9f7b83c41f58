//! [`FallView`]: one fall of a store, to read.

use bevy::math::{Quat, Vec3};

use super::Store;
use super::block::ConstantStorage;
use super::block::{Hot, W};
use super::cold::Cold;
use super::pose::smoothed;
use crate::freefall::model::motion::FallScales;
use crate::freefall::model::regime::PrimitiveMotion;

/// One fall as it is after its last step: where it is, how it is turned, what it is doing. A
/// [`FallPath`](crate::freefall::FallPath) reads as one, and so does each leaf of a
/// [`CloudLeaves`](crate::freefall::cloud::CloudLeaves) and each falling object of an app
/// ([`FallStore::fall`](crate::freefall::FallStore::fall)).
#[derive(Clone, Copy)]
pub struct FallView<'a> {
    pub(crate) hot: &'a Hot,
    pub(crate) k: usize,
    pub(crate) cold: &'a Cold,
}

impl std::fmt::Debug for FallView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FallView")
            .field("position", &self.position())
            .field("motion", &self.motion())
            .field("landed", &self.landed())
            .finish()
    }
}

impl<'a> FallView<'a> {
    /// p_i, the latest control point: where the fall is, m.
    pub fn position(&self) -> Vec3 {
        let (h, k) = (self.hot, self.k);
        Vec3::new(h.p2x[k], h.p2y[k], h.p2z[k])
    }

    /// The latest orientation (normalised).
    pub fn orientation(&self) -> Quat {
        let (h, k) = (self.hot, self.k);
        Quat::from_xyzw(h.q1x[k], h.q1y[k], h.q1z[k], h.q1w[k]).normalize()
    }

    /// The velocity of the fluid-following part of the motion, m/s.
    pub fn drift(&self) -> Vec3 {
        let (h, k) = (self.hot, self.k);
        Vec3::new(h.vx[k], h.vy[k], h.vz[k])
    }

    /// f(t): the still-fluid displacement since release, m.
    pub fn still_displacement(&self) -> Vec3 {
        let (h, k) = (self.hot, self.k);
        Vec3::new(h.sx[k], h.sy[k], h.sz[k])
    }

    /// The current primitive motion (Markov state).
    pub fn motion(&self) -> PrimitiveMotion {
        self.cold.motion
    }

    /// The chain's bound: the main motion from the phase diagram.
    pub fn main_motion(&self) -> PrimitiveMotion {
        self.cold.chain.main()
    }

    /// A₀ of the current motion, with its Gaussian draw, m.
    pub fn amplitude(&self) -> f32 {
        self.cold.amplitude
    }

    /// The heading: the rotation about +Y whose local +X the swings glide along.
    pub fn heading(&self) -> Quat {
        let (h, k) = (self.hot, self.k);
        Quat::from_xyzw(0.0, h.hs[k], 0.0, h.hc[k])
    }

    /// Seconds since release.
    pub fn time(&self) -> f32 {
        (self.cold.piece_start + f64::from(self.hot.t[self.k])) as f32
    }

    /// True once on the ground.
    pub fn landed(&self) -> bool {
        self.hot.landed[self.k] > 0.5
    }

    /// Markov steps taken (one per finished piece).
    pub fn markov_steps(&self) -> u32 {
        self.cold.markov_steps
    }

    /// The sizes of this fall.
    pub fn scales(&self) -> &'a FallScales {
        &self.cold.scales
    }

    /// The shown pose a fraction `s` ∈ [0, 1] of a step after the second-to-last control point:
    /// a cubic Bézier from p_{i−1} to p_i with Catmull–Rom tangents, one step behind the
    /// simulation, and a normalised lerp of the orientations (the short way).
    pub fn smoothed(&self, s: f32) -> (Vec3, Quat) {
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let (position, rotation) = smoothed::<f32>(self.hot, self.k, s);
        (position.vec3(), rotation.quat())
    }
}

impl<K: ConstantStorage> Store<K> {
    /// Fall `handle`, to read.
    pub fn view(&self, handle: u32) -> Option<FallView<'_>> {
        let place = self.place(handle)?;
        let band = &self.bands[place.band as usize];
        let s = place.index as usize;
        Some(FallView {
            hot: &band.blocks[s / W].hot,
            k: s % W,
            cold: &band.cold[s],
        })
    }
}
