//! The one step driver of a fall store, for a cloud's leaves and an app's falling objects
//! alike. On each fixed step it takes the bands due (see [`store`](super)), in parallel chunks
//! of blocks, and for each block:
//! 1. the wind where its falls are, read in one batch of lanes;
//! 2. one branch-free lane pass over the falls whose piece goes on ([`kernel::usual`]);
//! 3. the others (a piece ends and the chain steps, a swing is searched, a blend, a release
//!    fading, an easing, a landing, a fall at rest) one at a time, in lane order, through the
//!    same kernels ([`Slot::prepare`]); a fall whose step ends in a piece it crossed into
//!    leaves the new piece's sample to the lanes, which take it with the falls whose piece
//!    goes on;
//! 4. for each fall stepped, its tier measured again and the span its pose is shown over.
//!
//! Bands changed, landings and motion changes are reported, and applied after the parallel
//! part in handle order.

use bevy::math::Vec3;
use bevy::tasks::TaskPool;
use wide::f32x4;

use super::air::Reading;
use super::block::{Block, ConstantStorage, W};
use super::clock::FallClock;
use super::cold::Cold;
use super::kernel;
use super::slot::{Part, Slot, StepOutcome};
use super::step::Step;
use super::{Store, band_of, due_bands};
use crate::freefall::model::release::FallRelease;
use crate::portable::geometry::{Q, V3};
use crate::portable::lane::Lane;

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

impl<K: ConstantStorage> Store<K> {
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
        // What every read of the wind on this step shares, taken once.
        let air = &Reading::of(step.air);
        let mut reports = Vec::new();
        let due = due_bands(clock.steps);
        for (b, band) in self.bands.iter_mut().enumerate() {
            if !due.contains(&b) || band.len() == 0 {
                continue;
            }
            let run = |blocks: &mut [Block<K>], cold: &mut [Cold]| {
                step_blocks(kind, blocks, cold, b, step, air, &clock)
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
fn step_blocks<K: ConstantStorage>(
    kind: &K,
    blocks: &mut [Block<K>],
    cold: &mut [Cold],
    band: usize,
    step: &Step,
    air: &Reading,
    clock: &FallClock,
) -> ChunkReport {
    let mut report = ChunkReport::default();
    // Only the movers that reach this chunk's falls.
    let near = air.around(blocks, cold.len());
    let air = near.as_ref().unwrap_or(air);
    for b in 0..blocks.len() {
        let first = b * W;
        if first >= cold.len() {
            break;
        }
        let live = (cold.len() - first).min(W);
        // Cache lines on their way while this block is stepped: a cloud of 100 000 leaves
        // streams more bytes a step than the caches hold (docs/performance.md). The block two
        // ahead; and the cold state of the next block's falls that will go one at a time (its
        // block, asked for one block ago, is here to say which), over the time each waited (a
        // tier's span, as `step_block` steps it).
        #[cfg(target_arch = "x86_64")]
        {
            if b == 0
                && let Some(next) = blocks.get(1)
            {
                crate::portable::avx::prefetch(next);
            }
            if let Some(ahead) = blocks.get(b + 2) {
                crate::portable::avx::prefetch(ahead);
            }
            if let Some(next) = blocks.get(b + 1) {
                let h = &next.hot;
                for (j, cold) in cold.iter().skip(first + W).take(W).enumerate() {
                    let waited = (clock.seconds - next.updated[j]) as f32;
                    if h.plain[j] < 0.5 || h.t[j] + waited >= h.duration[j] {
                        crate::portable::avx::prefetch(cold);
                    }
                }
            }
        }
        step_block(
            kind,
            &mut blocks[b],
            &mut cold[first..first + live],
            band,
            step,
            air,
            clock,
            &mut report,
        );
    }
    report
}

/// Steps the `cold.len()` falls of `block`.
#[allow(clippy::too_many_arguments)]
fn step_block<K: ConstantStorage>(
    kind: &K,
    block: &mut Block<K>,
    cold: &mut [Cold],
    band: usize,
    step: &Step,
    air: &Reading,
    clock: &FallClock,
    report: &mut ChunkReport,
) {
    // The time since each fall's last step (its tier's span; a fall just let go: one step).
    let waited: [f32; W] = std::array::from_fn(|j| {
        let w = (clock.seconds - block.updated[j]) as f32;
        if w.is_finite() {
            w.clamp(0.0, FallRelease::MAX_STEP)
        } else {
            0.0
        }
    });
    let mut outcomes = [StepOutcome::Falling; W];
    // Which falls went one at a time (only their cold state is read again).
    let mut alone = [false; W];
    if step.width > 1 {
        let mut lanes = Lanes {
            kind,
            block,
            cold,
            step,
            air,
            clock,
            waited: &waited,
            outcomes: &mut outcomes,
            alone: &mut alone,
        };
        #[cfg(target_arch = "x86_64")]
        if step.width == 8 && crate::portable::avx::has_avx2() {
            // SAFETY: this CPU has AVX2 (checked just above).
            #[allow(unsafe_code)]
            unsafe {
                lanes.eight()
            };
        } else {
            lanes.four();
        }
        #[cfg(not(target_arch = "x86_64"))]
        lanes.four();
    } else {
        for (j, cold) in cold.iter_mut().enumerate() {
            let wind = air.lanes::<f32, K>(block, j).vec3();
            let mut slot = Slot { block, k: j, cold };
            let before = slot.easing_before(clock, waited[j]);
            outcomes[j] = slot.advance(kind, step, waited[j], wind);
            slot.easing_after(before, clock);
            alone[j] = true;
        }
    }
    let live = cold.len();
    for (j, cold) in cold.iter_mut().enumerate() {
        let handle = block.handle[j];
        let h = &mut block.hot;
        match outcomes[j] {
            StepOutcome::Landed => {
                report.landed.push(handle);
                h.rest[j] = 0.0;
            }
            StepOutcome::Resting => {
                if step.recycle_after.is_some_and(|t| h.rest[j] >= t) {
                    report.recycle.push(handle);
                }
            }
            StepOutcome::Falling => {}
        }
        if alone[j] {
            if std::mem::take(&mut cold.changed) {
                report.changed.push(handle);
            }
            if std::mem::take(&mut cold.lifted) {
                report.lifted += 1;
            }
        }
        block.updated[j] = clock.seconds;
    }
    report.advanced += live;
    // Each fall's tier from where it is now, and the span its pose is shown over: until its
    // next step on that tier, or the step just taken if longer.
    let Some(focus) = step.focus else {
        // No focus: every fall at full detail, every step.
        for (j, span) in block.hot.span.iter_mut().enumerate().take(live) {
            *span = if clock.last_dt > waited[j] {
                clock.last_dt
            } else {
                waited[j]
            };
        }
        if band != 0 {
            report
                .moves
                .extend(block.handle[..live].iter().map(|&handle| (handle, 0)));
        }
        return;
    };
    for (j, &waited) in waited.iter().enumerate().take(live) {
        let handle = block.handle[j];
        let next_tier = match kind.lod(&block.consts, j) {
            Some(lod) => {
                let h = &block.hot;
                focus.tier(&lod, Vec3::new(h.p2x[j], h.p2y[j], h.p2z[j]))
            }
            None => 1,
        };
        let next = clock.steps_to_next(next_tier, handle) as f32 * clock.last_dt;
        block.hot.span[j] = if next > waited { next } else { waited };
        let to = band_of(next_tier, handle);
        if to != band {
            report.moves.push((handle, to));
        }
    }
}

/// What [`step_block`]'s lane pass reads and writes: the block, its live falls' cold state
/// (`cold`), the step and the time since each fall's last step; each fall's outcome and whether
/// it went one at a time.
struct Lanes<'a, 'b, K: ConstantStorage> {
    kind: &'a K,
    block: &'a mut Block<K>,
    cold: &'a mut [Cold],
    step: &'a Step<'b>,
    air: &'a Reading<'b>,
    clock: &'a FallClock,
    waited: &'a [f32; W],
    outcomes: &'a mut [StepOutcome; W],
    alone: &'a mut [bool; W],
}

impl<K: ConstantStorage> Lanes<'_, '_, K> {
    /// The block in passes of four lanes (two where a block holds eight).
    #[inline(never)]
    fn four(&mut self) {
        // Each pass with its offset a constant (no bounds checks in the pass).
        self.pass::<f32x4>(0);
        if W > 4 && self.cold.len() > 4 {
            self.pass::<f32x4>(4);
        }
    }

    /// The block in one pass of eight lanes, compiled for AVX2: the pass's generic arithmetic
    /// (its lane kernels are `#[inline(always)]`) is inlined into this function and takes its
    /// instructions.
    #[cfg(target_arch = "x86_64")]
    #[inline(never)]
    #[target_feature(enable = "avx2")]
    fn eight(&mut self) {
        self.pass::<crate::portable::avx::F8>(0);
    }

    /// The falls in lanes `k..k + L::WIDTH`: the wind read for them at once; the falls whose
    /// piece goes on and those at rest in lanes; the others one at a time
    /// ([`Slot::prepare`]), their move and orientation finished in lanes with the usual ones
    /// (and the new piece sampled in lanes where a step ended in a piece it crossed into).
    #[inline(always)]
    fn pass<L: Lane>(&mut self, k: usize) {
        let Lanes {
            kind,
            ref mut block,
            ref mut cold,
            step,
            air,
            clock,
            waited,
            ref mut outcomes,
            ref mut alone,
        } = *self;
        pass::<L, K>(
            kind, block, k, cold, step, air, clock, waited, outcomes, alone,
        );
    }
}

/// [`Lanes::pass`], with what it reads and writes spelled out.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn pass<L: Lane, K: ConstantStorage>(
    kind: &K,
    block: &mut Block<K>,
    k: usize,
    cold: &mut [Cold],
    step: &Step,
    air: &Reading,
    clock: &FallClock,
    waited: &[f32; W],
    outcomes: &mut [StepOutcome; W],
    alone: &mut [bool; W],
) {
    let live = cold.len();
    let lanes = k..(k + L::WIDTH).min(live);
    let db = step.model.database();
    let wind = air.lanes::<L, K>(block, k);
    let c = kind.load::<L>(&block.consts, k);
    let half = L::splat(0.5);
    let dt = L::load(waited, k);
    let h = &block.hot;
    let span = L::load(&h.span, k);
    let on_time = L::or(span.le(L::splat(0.0)), dt.ge(span * L::splat(1.0 - 1e-3)));
    let plain = L::and(
        L::and(L::mask_from_fn(|j| k + j < live), on_time),
        L::load(&h.plain, k).gt(half),
    );
    let landed = L::load(&h.landed, k).gt(half);
    let t = L::load(&h.t, k) + dt;
    let go = L::and(L::and(plain, L::not(landed)), t.lt(L::load(&h.duration, k)));
    // Resting where the wind does not lift: the shown curve settles.
    let resting = L::and(
        L::and(plain, landed),
        L::not(kernel::lifts(wind, c.descent_speed)),
    );
    if L::any(resting) {
        kernel::settle(&mut block.hot, k, resting, dt);
    }
    // The others, one at a time: what lanes cannot share.
    let mut moves: [Option<(Vec3, Q<f32>)>; W] = [None; W];
    let mut crossings: [Option<(V3<f32>, f32)>; W] = [None; W];
    let mut easings = [None; W];
    for j in lanes.clone() {
        if L::mask_get(go, j - k) {
            continue;
        }
        if L::mask_get(resting, j - k) {
            outcomes[j] = StepOutcome::Resting;
            continue;
        }
        let w = Vec3::new(wind.x.get(j - k), wind.y.get(j - k), wind.z.get(j - k));
        let mut slot = Slot {
            block,
            k: j,
            cold: &mut cold[j],
        };
        alone[j] = true;
        easings[j] = Some(slot.easing_before(clock, waited[j]));
        match slot.prepare(kind, step, waited[j], w, true) {
            Part::Done(outcome) => outcomes[j] = outcome,
            Part::Move { delta, tilt } => moves[j] = Some((delta, tilt)),
            Part::Crossed { delta, t } => crossings[j] = Some((delta, t)),
        }
    }
    // The piece sampled in lanes: where it goes on, and where a new one began (a step across
    // one piece end: the move up to it added in).
    let crossed = L::mask_from_fn(|j| k + j < W && crossings[k + j].is_some());
    let sampled = L::or(go, crossed);
    let t = if L::any(crossed) {
        L::select(crossed, gather(&crossings, k, 0.0, |c| c.1), t)
    } else {
        t
    };
    let (end, tilt) = if L::any(sampled) {
        kernel::sample_piece(block, k, db, t)
    } else {
        (V3::splat(Vec3::ZERO), Q::identity())
    };
    let h = &block.hot;
    let offset = V3::new(L::load(&h.ox, k), L::load(&h.oy, k), L::load(&h.oz, k));
    let delta = kernel::turned((L::load(&h.tc, k), L::load(&h.ts, k)), end.sub(offset));
    let delta = if L::any(crossed) {
        let before = V3::new(
            gather(&crossings, k, 0.0, |c| c.0.x),
            gather(&crossings, k, 0.0, |c| c.0.y),
            gather(&crossings, k, 0.0, |c| c.0.z),
        );
        V3::select(crossed, before.add(delta), delta)
    } else {
        delta
    };
    // The move and the orientation, in lanes, for all that move.
    let alone_moves = L::mask_from_fn(|j| k + j < W && moves[k + j].is_some());
    let moving = L::or(sampled, alone_moves);
    if L::any(moving) {
        let go = sampled;
        let h = &block.hot;
        let t = L::select(go, t, L::load(&h.t, k));
        let offset = V3::select(
            go,
            end,
            V3::new(L::load(&h.ox, k), L::load(&h.oy, k), L::load(&h.oz, k)),
        );
        // The moves of the falls that went one at a time, gathered into lanes only where
        // there are some (most blocks have none).
        let (delta, tilt) = if L::any(alone_moves) {
            let part = |f: fn(&(Vec3, Q<f32>)) -> f32, none| gather(&moves, k, none, f);
            let their_delta = V3::new(
                part(|m| m.0.x, 0.0),
                part(|m| m.0.y, 0.0),
                part(|m| m.0.z, 0.0),
            );
            let their_tilt = Q::new(
                part(|m| m.1.x, 0.0),
                part(|m| m.1.y, 0.0),
                part(|m| m.1.z, 0.0),
                part(|m| m.1.w, 1.0),
            );
            (
                V3::select(go, delta, their_delta),
                Q::select(go, tilt, their_tilt),
            )
        } else {
            (delta, tilt)
        };
        let landed = kernel::finish(
            &mut block.hot,
            k,
            moving,
            &c,
            t,
            offset,
            delta,
            tilt,
            dt,
            wind,
            L::splat(step.air.reference_speed()),
        );
        for j in lanes.clone() {
            if L::mask_get(moving, j - k) {
                outcomes[j] = if L::mask_get(landed, j - k) {
                    StepOutcome::Landed
                } else {
                    StepOutcome::Falling
                };
            }
        }
    }
    for j in lanes {
        if let Some(before) = easings[j] {
            Slot {
                block,
                k: j,
                cold: &mut cold[j],
            }
            .easing_after(before, clock);
        }
    }
}

/// Lanes of `f` of the items `k..k + L::WIDTH` (`none` where a lane has no item).
#[inline(always)]
fn gather<L: Lane, T>(items: &[Option<T>; W], k: usize, none: f32, f: impl Fn(&T) -> f32) -> L {
    L::from_fn(|j| items.get(k + j).and_then(Option::as_ref).map_or(none, &f))
}
