//! The shown poses of a store's falls: each on the Bézier between its last two control points
//! at the share of its last step's span that has passed, plus what is left of an easing (a
//! change to a finer tier), in lanes, block by block.

use bevy::math::{Quat, Vec3};
use bevy::tasks::TaskPool;

use super::block::{Block, ConstantStorage, Hot, W};
use super::cold::Cold;
use super::{BANDS, Store};
use crate::portable::geometry::{Q, V3};
use crate::portable::lane::Lane;

/// A shown pose: position and orientation, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeafPose {
    /// Where the leaf is, m.
    pub position: Vec3,
    /// How it is turned (the plate in its local XZ plane, long axis local Z).
    pub rotation: Quat,
}

impl Default for LeafPose {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
        }
    }
}

/// The pose of lanes `k..` a fraction `s` ∈ [0, 1] of a step after p_{i−1}: the cubic Bézier
/// from p_{i−1} to p_i with Catmull–Rom tangents ((p_i − p_{i−2}) / 2 at its start, p_i − p_{i−1}
/// at its end), one step behind the simulation, and the orientations' normalised lerp the short
/// way (a step apart, within a degree of the slerp).
#[inline]
pub(crate) fn smoothed<L: Lane>(h: &Hot, k: usize, s: L) -> (V3<L>, Q<L>) {
    let point = |x: &[f32; W], y: &[f32; W], z: &[f32; W]| {
        V3::new(L::load(x, k), L::load(y, k), L::load(z, k))
    };
    let p0 = point(&h.p0x, &h.p0y, &h.p0z);
    let p1 = point(&h.p1x, &h.p1y, &h.p1z);
    let p2 = point(&h.p2x, &h.p2y, &h.p2z);
    let third = L::splat(1.0 / 3.0);
    let c1 = p1.add(p2.sub(p0).scale(L::splat(0.5) * third));
    let c2 = p2.sub(p2.sub(p1).scale(third));
    let r = L::splat(1.0) - s;
    let (b0, b1) = (r * r * r, L::splat(3.0) * r * r * s);
    let (b2, b3) = (L::splat(3.0) * r * s * s, s * s * s);
    let position = p1
        .scale(b0)
        .add(c1.scale(b1))
        .add(c2.scale(b2))
        .add(p2.scale(b3));
    let q0 = Q::new(
        L::load(&h.q0x, k),
        L::load(&h.q0y, k),
        L::load(&h.q0z, k),
        L::load(&h.q0w, k),
    );
    let q1 = Q::new(
        L::load(&h.q1x, k),
        L::load(&h.q1y, k),
        L::load(&h.q1z, k),
        L::load(&h.q1w, k),
    );
    let dot = ((q0.x * q1.x + q0.y * q1.y) + q0.z * q1.z) + q0.w * q1.w;
    let sign = L::select(dot.lt(L::splat(0.0)), L::splat(-1.0), L::splat(1.0));
    let lerp = |a: L, b: L| a + (b * sign - a) * s;
    let rotation = Q::new(
        lerp(q0.x, q1.x),
        lerp(q0.y, q1.y),
        lerp(q0.z, q1.z),
        lerp(q0.w, q1.w),
    )
    .normalize();
    (position, rotation)
}

/// The share of lanes `k..`'s last span passed at `now`, in [0, 1] (1 before the first step).
#[inline]
fn share<L: Lane, K: ConstantStorage>(block: &Block<K>, k: usize, now: f64) -> L {
    let span = L::load(&block.hot.span, k);
    let since = L::from_fn(|j| (now - block.updated[(k + j).min(W - 1)]) as f32);
    let s = since / span;
    let s = L::select(s.lt(L::splat(0.0)), L::splat(0.0), s);
    let s = L::select(s.gt(L::splat(1.0)), L::splat(1.0), s);
    // No span yet, or a NaN: the last point.
    L::select(
        span.gt(L::splat(0.0)),
        L::select(s.eq(s), s, L::splat(1.0)),
        L::splat(1.0),
    )
}

/// The pose shown at `now` of lane `k` of `block`, with what is left of its easing.
pub(crate) fn shown<K: ConstantStorage>(
    block: &Block<K>,
    k: usize,
    cold: &Cold,
    now: f64,
) -> LeafPose {
    let s = share::<f32, K>(block, k, now);
    let (position, rotation) = smoothed::<f32>(&block.hot, k, s);
    if block.hot.plain[k] > 0.5 {
        // No easing (nor blend, nor release fade): the cold state is not read.
        LeafPose {
            position: position.vec3(),
            rotation: rotation.quat(),
        }
    } else {
        eased(position.vec3(), rotation.quat(), cold, now)
    }
}

/// `position` and `rotation` with what is left at `now` of `cold`'s easing.
fn eased(position: Vec3, rotation: Quat, cold: &Cold, now: f64) -> LeafPose {
    match cold.easing.as_deref() {
        Some(e) if e.end > now => {
            let length = (e.end - e.start).max(1e-9);
            let left = ((e.end - now) / length).clamp(0.0, 1.0) as f32;
            LeafPose {
                position: position + e.offset * left,
                rotation: (Quat::IDENTITY.lerp(e.turn, left) * rotation).normalize(),
            }
        }
        _ => LeafPose { position, rotation },
    }
}

/// Blocks a parallel task poses together.
const POSE_CHUNK: usize = 128;

impl<K: ConstantStorage> Store<K> {
    /// Fall `handle`'s shown pose at `now` (s on the store's clock), one lane wide: the bits
    /// [`Store::poses`] gives it (lane-wise IEEE arithmetic in the same order).
    pub fn pose(&self, handle: u32, now: f64) -> Option<LeafPose> {
        let place = self.place(handle)?;
        let band = &self.bands[place.band as usize];
        let s = place.index as usize;
        Some(shown(&band.blocks[s / W], s % W, &band.cold[s], now))
    }

    /// Every fall's shown pose at `now` (s on the store's clock), `out[handle]`: `out` is
    /// resized to [`Store::handles`]. Posed in lanes, chunks on `pool`'s threads (the same bits
    /// on any number).
    pub fn poses(&self, now: f64, pool: Option<&TaskPool>, out: &mut Vec<LeafPose>) {
        out.resize(self.handles(), LeafPose::default());
        let lanes = crate::portable::lane_width() > 1;
        for band in &self.bands[..BANDS] {
            let n = band.len();
            let pose_chunk = |c: usize, blocks: &[Block<K>]| {
                let mut poses = Vec::with_capacity(blocks.len() * W);
                for (b, block) in blocks.iter().enumerate() {
                    // The next block's lines on their way while this one is posed (a hint:
                    // 10 % off posing 10 000 falls on this machine).
                    #[cfg(target_arch = "x86_64")]
                    if let Some(next) = blocks.get(b + 1) {
                        crate::portable::avx::prefetch(&next.hot);
                        crate::portable::avx::prefetch(&next.updated);
                        crate::portable::avx::prefetch(&next.handle);
                    }
                    let first = (c * POSE_CHUNK + b) * W;
                    let live = (n - first).min(W);
                    block_poses(
                        block,
                        &band.cold[first..first + live],
                        now,
                        lanes,
                        &mut poses,
                    );
                }
                poses
            };
            let chunks: Vec<Vec<(u32, LeafPose)>> = match pool {
                Some(pool) if band.blocks.len() > POSE_CHUNK => pool.scope(|scope| {
                    for (c, blocks) in band.blocks.chunks(POSE_CHUNK).enumerate() {
                        scope.spawn(async move { pose_chunk(c, blocks) });
                    }
                }),
                _ => band
                    .blocks
                    .chunks(POSE_CHUNK)
                    .enumerate()
                    .map(|(c, blocks)| pose_chunk(c, blocks))
                    .collect(),
            };
            for (handle, pose) in chunks.into_iter().flatten() {
                out[handle as usize] = pose;
            }
        }
    }
}

/// The poses of the `cold.len()` falls of `block` at `now`, appended with their handles.
fn block_poses<K: ConstantStorage>(
    block: &Block<K>,
    cold: &[Cold],
    now: f64,
    lanes: bool,
    out: &mut Vec<(u32, LeafPose)>,
) {
    let mut poses = [LeafPose::default(); W];
    if lanes {
        for (k, four) in poses.chunks_mut(4).enumerate().take(cold.len().div_ceil(4)) {
            let s = share::<wide::f32x4, K>(block, 4 * k, now);
            let (p, q) = smoothed::<wide::f32x4>(&block.hot, 4 * k, s);
            for (j, pose) in four.iter_mut().enumerate() {
                *pose = LeafPose {
                    position: Vec3::new(p.x.get(j), p.y.get(j), p.z.get(j)),
                    rotation: Quat::from_xyzw(q.x.get(j), q.y.get(j), q.z.get(j), q.w.get(j)),
                };
            }
        }
    } else {
        for (j, pose) in poses.iter_mut().enumerate().take(cold.len()) {
            let s = share::<f32, K>(block, j, now);
            let (p, q) = smoothed::<f32>(&block.hot, j, s);
            *pose = LeafPose {
                position: p.vec3(),
                rotation: q.quat(),
            };
        }
    }
    for (j, cold) in cold.iter().enumerate() {
        let pose = if block.hot.plain[j] > 0.5 {
            poses[j]
        } else {
            eased(poses[j].position, poses[j].rotation, cold, now)
        };
        out.push((block.handle[j], pose));
    }
}
