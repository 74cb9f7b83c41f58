//! The arithmetic of a fall's step, written once for one fall or for a block's lanes
//! ([`Lane`]): §4.2's p ← p + v dt + Δf with the drift relaxing toward the wind, the
//! compensated move and the landing ([`fall_on`]), eq. 15's orientation ([`orient`]), and the
//! usual step inside one piece ([`usual`]), which a block takes for all its lanes whose piece
//! goes on. Every fall takes these through the same code whichever lane or block it is in, so
//! its path has the same bits with lanes or without, on any number of threads, on any machine.

use bevy::math::Vec3;

use super::block::{Block, ConstantStorage, Hot, LaneConstants, W};
use crate::freefall::model::database::TrajectoryDatabase;
use crate::freefall::model::piece::sample::{WORDS, sample};
use crate::freefall::model::tilt::wind_tilt;
use crate::portable::geometry::{Q, V3};
use crate::portable::lane::{Lane, per_lane};

/// Drift speeds below this, m/s, are still air (flushed to zero: never subnormal).
pub(crate) const MIN_DRIFT: f32 = 1e-6;

/// The part of a fall's state §4.2's move reads and writes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Motion<L> {
    /// p_i, m.
    pub point: V3<L>,
    pub drift: V3<L>,
    pub still: V3<L>,
    pub carry: V3<L>,
}

/// `v` turned from the heading frame to the world: by ψ about +Y, from (cos ψ, sin ψ).
#[inline(always)]
pub(crate) fn turned<L: Lane>(turn: (L, L), v: V3<L>) -> V3<L> {
    let (c, s) = turn;
    V3::new(v.x * c + v.z * s, v.y, v.z * c - v.x * s)
}

/// §4.2's p ← p + v dt + Δf for a still-fluid displacement `delta` over `dt`: the drift v
/// relaxes toward `wind` by backward Euler, the move is carried in compensated summation (a
/// step below f32's spacing far from the origin is kept until it adds up), and a fall that
/// reaches the ground stops on it. Returns which lanes landed.
#[inline(always)]
pub(crate) fn fall_on<L: Lane>(
    m: &mut Motion<L>,
    c: &LaneConstants<L>,
    delta: V3<L>,
    dt: L,
    wind: V3<L>,
) -> L::Mask {
    m.still = m.still.add(delta);
    // Backward Euler on dv/dt = (u − v) / τ, 1/τ = √(U² + |u − v|²) / ℓ: never past the wind,
    // stable at any step; in still air a decaying drift is flushed to zero.
    let slip = wind.sub(m.drift);
    let u = c.descent_speed;
    let k = dt * ((u * u + slip.length_squared()).sqrt() * c.inv_drag_length);
    let drift = m.drift.add(slip.scale(k / (L::splat(1.0) + k)));
    let still_air = drift.length_squared().lt(L::splat(MIN_DRIFT * MIN_DRIFT));
    m.drift = V3::select(still_air, V3::splat(Vec3::ZERO), drift);
    let step = m.drift.scale(dt).add(delta).add(m.carry);
    let mut next = m.point.add(step);
    // Exact: `next` and the point are within a factor of two of each other wherever a step is
    // smaller than the position (Sterbenz).
    let carry = step.sub(next.sub(m.point));
    let bounded = |v: L| v.abs().lt(L::splat(f32::INFINITY));
    let finite = L::and(bounded(carry.x), L::and(bounded(carry.y), bounded(carry.z)));
    m.carry = V3::select(finite, carry, V3::splat(Vec3::ZERO));
    let landed = next.y.le(c.ground);
    next.y = L::select(landed, c.ground, next.y);
    m.drift = V3::select(landed, V3::splat(Vec3::ZERO), m.drift);
    m.carry = V3::select(landed, V3::splat(Vec3::ZERO), m.carry);
    m.point = next;
    landed
}

/// The orientation shown at a step: eq. 15's lean downwind (`factor` of it) times the heading
/// `yaw` (a turn about +Y: x = z = 0, as [`yaw`] makes it) times the plate's tilt in the
/// heading frame.
#[inline(always)]
pub(crate) fn orient<L: Lane>(
    max_angle: L,
    reference_speed: L,
    wind: V3<L>,
    factor: L,
    yaw: Q<L>,
    tilt: Q<L>,
) -> Q<L> {
    level_mul(
        wind_tilt(max_angle, reference_speed, wind, factor),
        about_y_mul(yaw, tilt),
    )
}

/// `yaw.mul(q)` for a turn about +Y (`yaw.x = yaw.z = 0`): [`Q::mul`] with the products of
/// those zeros left out (8 multiplications where 16 would be; the same values, at most a zero's
/// sign other).
#[inline(always)]
fn about_y_mul<L: Lane>(yaw: Q<L>, q: Q<L>) -> Q<L> {
    let (y0, w0) = (yaw.y, yaw.w);
    Q::new(
        w0 * q.x + y0 * q.z,
        w0 * q.y + y0 * q.w,
        w0 * q.z - y0 * q.x,
        w0 * q.w - y0 * q.y,
    )
}

/// `lean.mul(q)` for a turn about a level axis (`lean.y = 0`, as eq. 15's lean downwind):
/// [`Q::mul`] with the products of that zero left out, in its order of operations.
#[inline(always)]
fn level_mul<L: Lane>(lean: Q<L>, q: Q<L>) -> Q<L> {
    let (x0, z0, w0) = (lean.x, lean.z, lean.w);
    Q::new(
        (w0 * q.x + x0 * q.w) - z0 * q.y,
        (w0 * q.y - x0 * q.z) + z0 * q.x,
        (w0 * q.z + x0 * q.y) + z0 * q.w,
        (w0 * q.w - x0 * q.x) - z0 * q.z,
    )
}

/// The heading's rotation about +Y from (cos ψ/2, sin ψ/2).
#[inline(always)]
pub(crate) fn yaw<L: Lane>(half: (L, L)) -> Q<L> {
    let zero = L::splat(0.0);
    Q::new(zero, half.1, zero, half.0)
}

macro_rules! v3 {
    ($h:expr, $x:ident, $y:ident, $z:ident, $k:expr) => {
        V3::new(
            L::load(&$h.$x, $k),
            L::load(&$h.$y, $k),
            L::load(&$h.$z, $k),
        )
    };
}

macro_rules! store_v3 {
    ($v:expr, $mask:expr, $h:expr, $x:ident, $y:ident, $z:ident, $k:expr) => {{
        let v = $v;
        v.x.store_where($mask, &mut $h.$x, $k);
        v.y.store_where($mask, &mut $h.$y, $k);
        v.z.store_where($mask, &mut $h.$z, $k);
    }};
}

/// Writes `q` into the four columns where `mask`.
#[inline(always)]
fn store_q<L: Lane>(q: Q<L>, mask: L::Mask, columns: [&mut [f32; W]; 4], k: usize) {
    let [x, y, z, w] = columns;
    q.x.store_where(mask, x, k);
    q.y.store_where(mask, y, k);
    q.z.store_where(mask, z, k);
    q.w.store_where(mask, w, k);
}

/// A piece's words of lanes `k..`.
#[inline(always)]
pub(crate) fn words<L: Lane>(h: &Hot, k: usize) -> [L; WORDS] {
    [
        L::load(&h.w0, k),
        L::load(&h.w1, k),
        L::load(&h.w2, k),
        L::load(&h.w3, k),
        L::load(&h.w4, k),
        L::load(&h.w5, k),
        L::load(&h.w6, k),
        L::load(&h.w7, k),
        L::load(&h.w8, k),
        L::load(&h.w9, k),
        L::load(&h.w10, k),
    ]
}

/// The motion state of lanes `k..`.
#[inline(always)]
pub(crate) fn motion<L: Lane>(h: &Hot, k: usize) -> Motion<L> {
    Motion {
        point: v3!(h, p2x, p2y, p2z, k),
        drift: v3!(h, vx, vy, vz, k),
        still: v3!(h, sx, sy, sz, k),
        carry: v3!(h, cx, cy, cz, k),
    }
}

/// The piece sampled at piece time `t` for lanes `k..` of `block`: its displacement in the
/// heading frame and the plate's tilt.
#[inline(always)]
pub(crate) fn sample_piece<L: Lane, K: ConstantStorage>(
    block: &Block<K>,
    k: usize,
    db: &TrajectoryDatabase,
    t: L,
) -> (V3<L>, Q<L>) {
    let h = &block.hot;
    let half = L::splat(0.5);
    let rows = per_lane(|j| block.row[(k + j).min(block.row.len() - 1)]);
    sample(
        &words(h, k),
        L::load(&h.inv_duration, k),
        rows,
        L::load(&h.tumble, k).gt(half),
        L::load(&h.curve, k).gt(half),
        db,
        t,
    )
}

/// Where the swing of lane `k` of `block` ends (its segment's last sample, heading frame).
#[inline]
pub(crate) fn swing_end<K: ConstantStorage>(
    block: &Block<K>,
    k: usize,
    db: &TrajectoryDatabase,
) -> V3<f32> {
    use crate::freefall::model::database::SEGMENT_SAMPLES;
    use crate::freefall::model::piece::sample::swing_word::{X_SCALE, Y_SCALE};
    let row = db.row(block.row[k] as usize + SEGMENT_SAMPLES - 1);
    let words = words::<f32>(&block.hot, k);
    V3::new(words[X_SCALE] * row[0], words[Y_SCALE] * row[1], 0.0)
}

/// Writes a step's end for the lanes `k..` where `mask`: the point and orientation appended to
/// the control points, the rest of the motion, the piece's clock and offset, the landing.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn commit<L: Lane>(
    h: &mut Hot,
    k: usize,
    mask: L::Mask,
    m: &Motion<L>,
    orientation: Q<L>,
    t: L,
    offset: V3<L>,
    landed: L::Mask,
) {
    // Every lane (the usual case): plain stores.
    if L::all(mask) {
        write(h, k, m, orientation, t, offset, landed, |v, column| {
            v.store(column, k)
        });
    } else {
        write(h, k, m, orientation, t, offset, landed, |v, column| {
            v.store_where(mask, column, k)
        });
    }
}

/// [`commit`]'s writes, each through `put`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn write<L: Lane>(
    h: &mut Hot,
    k: usize,
    m: &Motion<L>,
    orientation: Q<L>,
    t: L,
    offset: V3<L>,
    landed: L::Mask,
    put: impl Fn(L, &mut [f32; W]),
) {
    // p_{i−2} ← p_{i−1} ← p_i ← the new point; the orientations likewise.
    let p1 = v3!(h, p1x, p1y, p1z, k);
    let p2 = v3!(h, p2x, p2y, p2z, k);
    let q1 = [
        L::load(&h.q1x, k),
        L::load(&h.q1y, k),
        L::load(&h.q1z, k),
        L::load(&h.q1w, k),
    ];
    let was = L::load(&h.landed, k);
    for (v, column) in [
        (p1.x, &mut h.p0x),
        (p1.y, &mut h.p0y),
        (p1.z, &mut h.p0z),
        (p2.x, &mut h.p1x),
        (p2.y, &mut h.p1y),
        (p2.z, &mut h.p1z),
        (m.point.x, &mut h.p2x),
        (m.point.y, &mut h.p2y),
        (m.point.z, &mut h.p2z),
        (q1[0], &mut h.q0x),
        (q1[1], &mut h.q0y),
        (q1[2], &mut h.q0z),
        (q1[3], &mut h.q0w),
        (orientation.x, &mut h.q1x),
        (orientation.y, &mut h.q1y),
        (orientation.z, &mut h.q1z),
        (orientation.w, &mut h.q1w),
        (m.drift.x, &mut h.vx),
        (m.drift.y, &mut h.vy),
        (m.drift.z, &mut h.vz),
        (m.still.x, &mut h.sx),
        (m.still.y, &mut h.sy),
        (m.still.z, &mut h.sz),
        (m.carry.x, &mut h.cx),
        (m.carry.y, &mut h.cy),
        (m.carry.z, &mut h.cz),
        (offset.x, &mut h.ox),
        (offset.y, &mut h.oy),
        (offset.z, &mut h.oz),
        (t, &mut h.t),
        (L::select(landed, L::splat(1.0), was), &mut h.landed),
    ] {
        put(v, column);
    }
}

/// Whether `wind` lifts a resting fall of descent speed `u` again: faster than
/// [`FallRelease::LIFT_OFF_FACTOR`](crate::freefall::model::release::FallRelease::LIFT_OFF_FACTOR) × U.
#[inline(always)]
pub(crate) fn lifts<L: Lane>(wind: V3<L>, u: L) -> L::Mask {
    let least = L::splat(crate::freefall::model::release::FallRelease::LIFT_OFF_FACTOR) * u;
    wind.length_squared().gt(least * least)
}

/// A resting fall's step for lanes `k..` where `mask`: the shown curve settles on the resting
/// point (p_{i−2} ← p_{i−1} ← p_i, the orientations likewise) and `dt` more seconds on the
/// ground.
#[inline(always)]
pub(crate) fn settle<L: Lane>(h: &mut Hot, k: usize, mask: L::Mask, dt: L) {
    let p1 = v3!(h, p1x, p1y, p1z, k);
    let p2 = v3!(h, p2x, p2y, p2z, k);
    store_v3!(p1, mask, h, p0x, p0y, p0z, k);
    store_v3!(p2, mask, h, p1x, p1y, p1z, k);
    let q1 = Q::new(
        L::load(&h.q1x, k),
        L::load(&h.q1y, k),
        L::load(&h.q1z, k),
        L::load(&h.q1w, k),
    );
    store_q(
        q1,
        mask,
        [&mut h.q0x, &mut h.q0y, &mut h.q0z, &mut h.q0w],
        k,
    );
    (L::load(&h.rest, k) + dt).store_where(mask, &mut h.rest, k);
}

/// The rest of a step for lanes `k..` where `mask`, once the still-fluid displacement `delta`
/// (world frame) and the plate's `tilt` are known and the piece's clock `t` and offset are
/// moved on: [`fall_on`] and the orientation. Returns which lanes landed.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish<L: Lane>(
    h: &mut Hot,
    k: usize,
    mask: L::Mask,
    c: &LaneConstants<L>,
    t: L,
    offset: V3<L>,
    delta: V3<L>,
    tilt: Q<L>,
    dt: L,
    wind: V3<L>,
    reference_speed: L,
) -> L::Mask {
    let mut m = motion(h, k);
    let landed = fall_on(&mut m, c, delta, dt, wind);
    let half = (L::load(&h.hc, k), L::load(&h.hs, k));
    let one = L::splat(1.0);
    let orientation = orient(c.max_angle, reference_speed, wind, one, yaw(half), tilt);
    commit(h, k, mask, &m, orientation, t, offset, landed);
    L::and(mask, landed)
}
