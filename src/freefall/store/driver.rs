//! The one step driver of a fall store, for a cloud's leaves and an app's falling objects
//! alike. On each fixed step it takes the bands due (see [`store`](super)), in parallel chunks
//! of blocks, and for each block:
//! 1. the wind where its falls are, read in one batch of lanes;
//! 2. one branch-free lane pass over the falls whose piece goes on ([`kernel::usual`]);
//! 3. the others (a piece ends and the chain steps, a swing is searched, a blend, a release
//!    fading, an easing, a landing, a fall at rest) one at a time, in lane order, through the
//!    same kernels ([`Slot::advance`]);
//! 4. for each fall stepped, its tier measured again and the span its pose is shown over.
//!
//! Bands changed, landings and motion changes are reported, and applied after the parallel
//! part in handle order.

use bevy::math::{Quat, Vec3};
use bevy::tasks::TaskPool;
use wide::f32x4;

use super::block::{Block, Cold, Constants, Easing, W};
use super::kernel;
use super::pose::shown;
use super::slot::{Slot, StepOutcome};
use super::{Store, band_of, due_bands};
use crate::freefall::lod::FallClock;
use crate::freefall::model::FallModel;
use crate::freefall::model::release::FallRelease;
use crate::lod::Focus;
use crate::math::geometry::V3;
use crate::math::lane::Lane;
use crate::wind::WindField;

/// The air the falls move in.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Air<'a> {
    /// Still air.
    Still,
    /// The wind field, read where each fall is at its own clock.
    Field(&'a WindField),
    /// The same velocity everywhere, m/s.
    Uniform(Vec3),
}

/// Everything one step reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step<'a> {
    pub model: &'a FallModel,
    pub air: Air<'a>,
    /// Eq. 15's U_ref, m/s.
    pub reference_speed: f32,
    /// Where levels of detail are measured from (`None`: every fall at full detail).
    pub focus: Option<Focus>,
    /// Whether falls go several at a time in SIMD lanes (the same bits either way).
    pub lanes: bool,
    /// Falls resting this long, s, are reported ([`StepReport::recycle`]).
    pub recycle_after: Option<f32>,
}

/// What one step did.
#[derive(Clone, Debug, Default)]
pub(crate) struct StepReport {
    /// Falls advanced.
    pub advanced: usize,
    /// Handles of the falls that reached the ground, in order.
    pub landed: Vec<u32>,
    /// Handles of the falls whose motion changed or that left the ground, in order.
    pub changed: Vec<u32>,
    /// Handles of the falls resting at least [`Step::recycle_after`], in order.
    pub recycle: Vec<u32>,
}

/// What the chunks of one band report.
#[derive(Default)]
struct ChunkReport {
    advanced: usize,
    landed: Vec<u32>,
    lifted: usize,
    changed: Vec<u32>,
    recycle: Vec<u32>,
    /// (handle, band) of falls whose tier changed.
    moves: Vec<(u32, usize)>,
}

/// Blocks a parallel task steps together (512 falls: big enough that the task costs little
/// beside its work, small enough that two threads share a few thousand falls).
const CHUNK_BLOCKS: usize = 128;

impl<K: Constants> Store<K> {
    /// One fixed step of `dt` seconds (held to 0..=[`FallRelease::MAX_STEP`]): the clock moves
    /// on and every fall due advances over the time since its own last step.
    pub fn step(&mut self, dt: f32, step: &Step, pool: Option<&TaskPool>) -> StepReport {
        let dt = if dt.is_finite() {
            dt.clamp(0.0, FallRelease::MAX_STEP)
        } else {
            0.0
        };
        self.clock.tick(dt);
        let clock = self.clock;
        let kind = &self.kind;
        let mut reports = Vec::new();
        let due = due_bands(clock.steps);
        for (b, band) in self.bands.iter_mut().enumerate() {
            if !due.contains(&b) || band.len() == 0 {
                continue;
            }
            let run = |blocks: &mut [Block<K>], cold: &mut [Cold]| {
                step_blocks(kind, blocks, cold, b, step, &clock)
            };
            let blocks = band.blocks.len();
            let chunks = band
                .blocks
                .chunks_mut(CHUNK_BLOCKS)
                .zip(band.cold.chunks_mut(CHUNK_BLOCKS * W));
            match pool {
                Some(pool) if blocks > CHUNK_BLOCKS => {
                    reports.extend(pool.scope(|scope| {
                        for (blocks, cold) in chunks {
                            scope.spawn(async move { run(blocks, cold) });
                        }
                    }));
                }
                _ => reports.extend(chunks.map(|(blocks, cold)| run(blocks, cold))),
            }
        }
        let mut report = StepReport::default();
        let mut moves = Vec::new();
        for r in reports {
            report.advanced += r.advanced;
            self.resting = self.resting + r.landed.len() - r.lifted;
            report.landed.extend(r.landed);
            report.changed.extend(r.changed);
            report.recycle.extend(r.recycle);
            moves.extend(r.moves);
        }
        report.landed.sort_unstable();
        report.changed.sort_unstable();
        report.recycle.sort_unstable();
        moves.sort_unstable();
        for (handle, band) in moves {
            self.move_to(handle, band);
        }
        report
    }
}

/// Steps `blocks` (the falls `cold` of band `band`).
fn step_blocks<K: Constants>(
    kind: &K,
    blocks: &mut [Block<K>],
    cold: &mut [Cold],
    band: usize,
    step: &Step,
    clock: &FallClock,
) -> ChunkReport {
    let mut report = ChunkReport::default();
    for (b, block) in blocks.iter_mut().enumerate() {
        let first = b * W;
        if first >= cold.len() {
            break;
        }
        let live = (cold.len() - first).min(W);
        step_block(
            kind,
            block,
            &mut cold[first..first + live],
            band,
            step,
            clock,
            &mut report,
        );
    }
    report
}

/// Steps the `cold.len()` falls of `block`.
#[allow(clippy::too_many_arguments)]
fn step_block<K: Constants>(
    kind: &K,
    block: &mut Block<K>,
    cold: &mut [Cold],
    band: usize,
    step: &Step,
    clock: &FallClock,
    report: &mut ChunkReport,
) {
    let live = cold.len();
    // The time since each fall's last step (its tier's span; a fall just let go: one step).
    let waited: [f32; W] = std::array::from_fn(|j| {
        let w = (clock.seconds - block.updated[j]) as f32;
        if w.is_finite() {
            w.clamp(0.0, FallRelease::MAX_STEP)
        } else {
            0.0
        }
    });
    let db = step.model.database();
    let reference_speed = step.reference_speed;
    let mut usual = [false; W];
    let mut landed = [false; W];
    let mut winds = [Vec3::ZERO; W];
    if step.lanes {
        let wind = air_lanes::<f32x4, K>(block, 0, &step.air);
        for (j, w) in winds.iter_mut().enumerate() {
            *w = Vec3::new(wind.x.get(j), wind.y.get(j), wind.z.get(j));
        }
        let h = &block.hot;
        let half = f32x4::splat(0.5);
        let dt = f32x4::from(waited);
        let span = f32x4::load(&h.span, 0);
        let on_time = f32x4::or(
            span.le(f32x4::splat(0.0)),
            dt.ge(span * f32x4::splat(1.0 - 1e-3)),
        );
        let inside = (f32x4::load(&h.t, 0) + dt).lt(f32x4::load(&h.duration, 0));
        let go = f32x4::and(
            f32x4::and(f32x4::mask_from_fn(|j| j < live), inside),
            f32x4::and(
                f32x4::and(f32x4::load(&h.plain, 0).gt(half), on_time),
                f32x4::load(&h.landed, 0).lt(half),
            ),
        );
        if f32x4::any(go) {
            let c = kind.load::<f32x4>(&block.consts, 0);
            let now_landed = kernel::usual(
                block,
                0,
                &c,
                go,
                dt,
                wind,
                f32x4::splat(reference_speed),
                db,
            );
            for j in 0..live {
                usual[j] = f32x4::mask_get(go, j);
                landed[j] = f32x4::mask_get(now_landed, j);
            }
        }
    } else {
        for (j, w) in winds.iter_mut().enumerate().take(live) {
            *w = air_lanes::<f32, K>(block, j, &step.air).vec3();
        }
    }
    for (j, cold) in cold.iter_mut().enumerate() {
        let handle = block.handle[j];
        if !usual[j] {
            let mut slot = Slot { block, k: j, cold };
            let before = (slot.cold.motion, slot.landed());
            let outcome = step_slot(&mut slot, kind, step, clock, waited[j], winds[j]);
            landed[j] = outcome == StepOutcome::Landed;
            let after = (slot.cold.motion, slot.landed());
            if before.0 != after.0 || (before.1 && !after.1) {
                report.changed.push(handle);
            }
            if before.1 && !after.1 {
                report.lifted += 1;
            }
            if outcome == StepOutcome::Resting
                && step.recycle_after.is_some_and(|t| block.hot.rest[j] >= t)
            {
                report.recycle.push(handle);
            }
        } else {
            block.updated[j] = clock.seconds;
        }
        if landed[j] {
            report.landed.push(handle);
            block.hot.rest[j] = 0.0;
        }
        report.advanced += 1;
        // Its tier from where it is now, and the span its pose is shown over: until its next
        // step on that tier, or the step just taken if longer.
        let position = Vec3::new(block.hot.p2x[j], block.hot.p2y[j], block.hot.p2z[j]);
        let next_tier = match (kind.lod(&block.consts, j), step.focus) {
            (Some(lod), Some(focus)) => focus.tier(&lod, position),
            _ => 1,
        };
        let next = clock.steps_to_next(next_tier, handle) as f32 * clock.last_dt;
        block.hot.span[j] = if next > waited[j] { next } else { waited[j] };
        let to = band_of(next_tier, handle);
        if to != band {
            report.moves.push((handle, to));
        }
    }
}

/// Advances one fall that the lanes did not (see the module docs), with the bookkeeping of its
/// tier: a step that comes before its last span was shown (a change to a finer tier), or one
/// taken while an easing is under way, eases what is shown from where it was.
fn step_slot<K: Constants>(
    slot: &mut Slot<'_, K>,
    kind: &K,
    step: &Step,
    clock: &FallClock,
    waited: f32,
    wind: Vec3,
) -> StepOutcome {
    let k = slot.k;
    let now = clock.seconds;
    let span = slot.block.hot.span[k];
    let running = slot
        .cold
        .easing
        .as_ref()
        .map(|e| e.end)
        .filter(|&end| end > now);
    // (The share is a ratio of clock differences rounded to f32: a step of the same span can
    // come out a rounding short of the whole, which is no lag worth easing.)
    let lagging = span > 0.0 && waited < span * (1.0 - 1e-3);
    let before = (running.is_some() || lagging).then(|| shown(slot.block, k, slot.cold, now));
    // A new easing lasts two of the spans before (it catches up at most half a step per step);
    // one under way keeps its end.
    let end = running.unwrap_or(now + 2.0 * f64::from(span.max(waited)));
    let outcome = slot.advance(kind, step.model, waited, wind, step.reference_speed);
    slot.cold.easing = before.map(|pose| {
        let (position, rotation) = smoothed_start(slot);
        Box::new(Easing {
            offset: pose.position - position,
            turn: (pose.rotation * rotation.inverse()).normalize(),
            start: now,
            end,
        })
    });
    slot.block.updated[k] = now;
    slot.set_plain();
    outcome
}

/// The pose shown right after a step (at the start of its span).
fn smoothed_start<K: Constants>(slot: &Slot<'_, K>) -> (Vec3, Quat) {
    let (p, q) = super::pose::smoothed::<f32>(&slot.block.hot, slot.k, 0.0);
    (p.vec3(), q.quat())
}

/// The air's velocity at lanes `k..` of `block` (where each fall is), held to
/// [`FallRelease::MAX_SPEED`].
fn air_lanes<L: Lane, K: Constants>(block: &Block<K>, k: usize, air: &Air) -> V3<L> {
    let h = &block.hot;
    let wind = match air {
        Air::Still => return V3::splat(Vec3::ZERO),
        Air::Uniform(u) => V3::splat(*u),
        Air::Field(field) => {
            let p = V3::new(L::load(&h.p2x, k), L::load(&h.p2y, k), L::load(&h.p2z, k));
            field.velocity_lanes(p)
        }
    };
    clamp_speed(wind, FallRelease::MAX_SPEED)
}

/// `v` held to `max` long (a non-finite vector: zero), lane by lane: the usual case with no
/// division, the rest one lane at a time (overflow-safe).
fn clamp_speed<L: Lane>(v: V3<L>, max: f32) -> V3<L> {
    let squared = v.length_squared();
    let ok = L::and(squared.gt(L::splat(0.0)), squared.le(L::splat(max * max)));
    let zero = squared.eq(L::splat(0.0));
    if L::all(L::or(ok, zero)) {
        return v;
    }
    let each = |j: usize| {
        if L::mask_get(ok, j) {
            Vec3::new(v.x.get(j), v.y.get(j), v.z.get(j))
        } else {
            crate::guard::clamp_length(Vec3::new(v.x.get(j), v.y.get(j), v.z.get(j)), max)
        }
    };
    let lanes: [Vec3; 4] = std::array::from_fn(|j| if j < L::WIDTH { each(j) } else { Vec3::ZERO });
    V3::new(
        L::from_fn(|j| lanes[j].x),
        L::from_fn(|j| lanes[j].y),
        L::from_fn(|j| lanes[j].z),
    )
}
