//! One fall of the store, one at a time: the step the lanes do not take (a piece ends and the
//! Markov chain steps, a swing is searched, a motion change blends, the release orientation
//! fades, a resting fall settles).
//! Whatever part of such a step the lanes also take goes through the same kernels
//! ([`kernel`](super::kernel)), one lane wide.

use bevy::math::Vec3;

pub(crate) mod release;

use super::block::{Block, ConstantStorage};
use super::clock::FallClock;
use super::cold::{Blend, Cold, Easing, smoothstep};
use super::kernel::{self, Motion, commit, fall_on, motion, orient, sample_piece, turned, yaw};
use super::pose::{LeafPose, shown, smoothed};
use super::step::Step;
use crate::freefall::model::FallModel;
use crate::freefall::model::piece::Piece;
use crate::portable::geometry::{Q, V3};

/// Most pieces one step may cross; the rest of a huge step falls straight at U.
const MAX_PIECES_PER_STEP: u32 = 64;
/// Motion changes that switch between swings and eq. 6 blend position increments and
/// orientation over this share of a swing ...
const BLEND_SWINGS: f32 = 0.35;
/// ... and at least this long, s, so a blend spans several frames of any frame rate.
const MIN_BLEND: f32 = 0.15;
/// A blend is summed in parts of at most this long, s (a step that spans more is cut into
/// equal parts): its increments are weighted at each part's middle, so a distant leaf's
/// longer steps sum it at the points a full-detail leaf's frames do.
const BLEND_PART: f32 = 1.0 / 60.0;

/// What a step did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepOutcome {
    /// Still in the air.
    Falling,
    /// Reached the ground in this step.
    Landed,
    /// Already on the ground; nothing moved.
    Resting,
}

/// What [`Slot::prepare`] leaves to finish.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Part {
    /// Nothing: the step is done, and did this.
    Done(StepOutcome),
    /// The move (the still-fluid displacement `delta`, world frame, m) and the orientation
    /// (the plate's `tilt` in the heading frame): the piece's clock and offset are written.
    Move { delta: Vec3, tilt: Q<f32> },
    /// A piece ended and the next began (compiled in the block, its clock and offset at 0):
    /// left to sample is the new piece at piece time `t`, inside it, whose displacement (turned
    /// by the heading) adds to `delta`, the move up to its start. Only where the lanes take
    /// it ([`Slot::prepare`]'s `lanes`), when the step ends inside the piece its last crossing
    /// began (under the cap on pieces a step crosses) and no blend or release fade runs: the
    /// arithmetic the one-at-a-time loop would do, in lanes.
    Crossed { delta: V3<f32>, t: f32 },
}

/// What [`Slot::still_step`] leaves: the whole step, or a crossing for the lanes to finish.
enum Still {
    Whole(Vec3, Q<f32>),
    Crossed(V3<f32>, f32),
}

/// One fall of a store: lane `k` of `block` and its cold state.
pub(crate) struct Slot<'a, K: ConstantStorage> {
    pub block: &'a mut Block<K>,
    pub k: usize,
    pub cold: &'a mut Cold,
}

impl<K: ConstantStorage> Slot<'_, K> {
    /// What a step at `clock` after `waited` seconds must ease the shown pose from: the pose
    /// shown now, if the step comes before the last span was shown (a change to a finer tier)
    /// or an easing is under way, and when the easing will end.
    pub fn easing_before(&self, clock: &FallClock, waited: f32) -> Option<(LeafPose, f64)> {
        let k = self.k;
        let now = clock.seconds;
        let span = self.block.hot.span[k];
        let running = self
            .cold
            .easing
            .as_ref()
            .map(|e| e.end)
            .filter(|&end| end > now);
        // (The share is a ratio of clock differences rounded to f32: a step of the same span
        // can come out a rounding short of the whole, which is no lag worth easing.)
        let lagging = span > 0.0 && waited < span * (1.0 - 1e-3);
        // A new easing lasts two of the spans before (it catches up at most half a step per
        // step); one under way keeps its end.
        let end = running.unwrap_or(now + 2.0 * f64::from(span.max(waited)));
        (running.is_some() || lagging).then(|| (shown(self.block, k, self.cold, now), end))
    }

    /// Eases the shown pose after a step from `before` ([`Slot::easing_before`]): the offset
    /// and turn from the pose the step shows at its start, fading out by the easing's end.
    pub fn easing_after(&mut self, before: Option<(LeafPose, f64)>, clock: &FallClock) {
        let k = self.k;
        self.cold.easing = before.map(|(pose, end)| {
            let (p, q) = smoothed::<f32>(&self.block.hot, k, 0.0);
            let (position, rotation) = (p.vec3(), q.quat());
            Box::new(Easing {
                offset: pose.position - position,
                turn: (pose.rotation * rotation.inverse()).normalize(),
                start: clock.seconds,
                end,
            })
        });
        self.set_plain();
    }

    /// Seconds since release.
    pub fn time(&self) -> f64 {
        self.cold.piece_start + f64::from(self.block.hot.t[self.k])
    }

    /// Whether the fall is on the ground.
    pub fn landed(&self) -> bool {
        self.block.hot.landed[self.k] > 0.5
    }

    /// Marks whether a usual step is possible (no blend, no release fading, no easing).
    pub fn set_plain(&mut self) {
        let plain = self.cold.previous.is_none()
            && self.cold.release.is_none()
            && self.cold.easing.is_none();
        self.block.hot.plain[self.k] = if plain { 1.0 } else { 0.0 };
    }

    /// Advances the fall by `dt` seconds (0..=[`FallRelease::MAX_STEP`]) in `wind` (held to
    /// [`FallRelease::MAX_SPEED`]): §4.2's p ← p + v dt + Δf, the drift relaxing toward the wind
    /// over [`FallScales::response_time`], Δf the still-fluid path's increment across as many
    /// pieces as the step crosses, and the orientation with eq. 15's tilt. A resting fall
    /// settles, or is lifted by a strong enough wind. ([`Slot::prepare`], then the move the
    /// lanes finish, one lane wide.)
    pub fn advance(&mut self, kind: &K, step: &Step, dt: f32, wind: Vec3) -> StepOutcome {
        match self.prepare(kind, step, dt, wind, false) {
            Part::Done(outcome) => outcome,
            Part::Crossed { .. } => unreachable!("a crossing is left only to lanes"),
            Part::Move { delta, tilt } => {
                let k = self.k;
                let c = kind.load::<f32>(&self.block.consts, k);
                let h = &mut self.block.hot;
                let (t, offset) = (h.t[k], V3::new(h.ox[k], h.oy[k], h.oz[k]));
                let landed = kernel::finish::<f32>(
                    h,
                    k,
                    true,
                    &c,
                    t,
                    offset,
                    V3::of(delta),
                    tilt,
                    dt,
                    V3::of(wind),
                    step.air.reference_speed(),
                );
                if landed {
                    StepOutcome::Landed
                } else {
                    StepOutcome::Falling
                }
            }
        }
    }

    /// The part of a step taken one fall at a time: a resting fall settles or is lifted; the
    /// piece is sampled at its new time, or crossed into the next ones (the Markov step, the
    /// swing search), blended from the last motion's; a fall whose release orientation is still
    /// fading is stepped whole. What is left, the move and the orientation of [`Part::Move`],
    /// the lanes finish ([`kernel::finish`]) for many falls at once; with `lanes`, a step that
    /// crosses into a piece it ends in leaves the new piece's sample to them too
    /// ([`Part::Crossed`]).
    pub fn prepare(&mut self, kind: &K, step: &Step, dt: f32, wind: Vec3, lanes: bool) -> Part {
        let (k, model) = (self.k, step.model);
        if self.landed() {
            let c = kind.get(&self.block.consts, k);
            if kernel::lifts::<f32>(V3::of(wind), c.descent_speed) {
                self.lift_off(kind, model, wind);
            } else {
                kernel::settle::<f32>(&mut self.block.hot, k, true, dt);
                return Part::Done(StepOutcome::Resting);
            }
        }
        let db = model.database();
        let plain = self.cold.previous.is_none() && self.cold.release.is_none();
        let h = &self.block.hot;
        if plain && h.t[k] + dt < h.duration[k] {
            // Inside one piece: the lanes' usual sample, one lane wide.
            let t = h.t[k] + dt;
            let (end, tilt) = sample_piece::<f32, K>(self.block, k, db, t);
            let h = &mut self.block.hot;
            let inc = end.sub(V3::new(h.ox[k], h.oy[k], h.oz[k]));
            h.t[k] = t;
            (h.ox[k], h.oy[k], h.oz[k]) = (end.x, end.y, end.z);
            let delta = turned((h.tc[k], h.ts[k]), inc).vec3();
            return Part::Move { delta, tilt };
        }
        let (delta, tilt) = match self.still_step(model, dt, wind, lanes) {
            Still::Whole(delta, tilt) => (delta, tilt),
            Still::Crossed(delta, t) => {
                self.set_plain();
                return Part::Crossed { delta, t };
            }
        };
        let tilt = match &self.cold.previous {
            Some(old) => old.shown(db, tilt),
            None => tilt,
        };
        if self.cold.release.is_none() {
            self.set_plain();
            return Part::Move { delta, tilt };
        }
        // The release orientation fading: this fall's orientation is its own.
        let c = kind.load::<f32>(&self.block.consts, k);
        let mut m: Motion<f32> = motion(&self.block.hot, k);
        let landed = fall_on(&mut m, &c, V3::of(delta), dt, V3::of(wind));
        let orientation = self.fading(c.max_angle, step.air.reference_speed(), wind, tilt, dt);
        let h = &mut self.block.hot;
        let (t, offset) = (h.t[k], V3::new(h.ox[k], h.oy[k], h.oz[k]));
        commit::<f32>(h, k, true, &m, orientation, t, offset, landed);
        self.set_plain();
        Part::Done(if landed {
            StepOutcome::Landed
        } else {
            StepOutcome::Falling
        })
    }

    /// Still-fluid displacement over `dt` (world frame), crossing pieces as needed, and the
    /// plate's tilt at the end; with `lanes`, a step that ends inside the piece a crossing
    /// began, with no blend or release fade and under [`MAX_PIECES_PER_STEP`], stops at that
    /// crossing ([`Still::Crossed`]: the lanes sample the new piece as the loop's next turn
    /// would).
    fn still_step(&mut self, model: &FallModel, dt: f32, wind: Vec3, lanes: bool) -> Still {
        let db = model.database();
        let k = self.k;
        let turn = (self.block.hot.tc[k], self.block.hot.ts[k]);
        let mut remaining = dt;
        let mut delta = V3::of(Vec3::ZERO);
        let mut crossed = 0;
        let mut tilt = None;
        while remaining > 0.0 && crossed < MAX_PIECES_PER_STEP {
            let h = &self.block.hot;
            let (t, duration) = (h.t[k], h.duration[k]);
            let left = (duration - t).max(0.0);
            let mut step = remaining.min(left);
            if self.cold.previous.is_some() {
                // Within a thousandth of a part counts as one (f32 frame times).
                let parts = (step / BLEND_PART - 1e-3).ceil().max(1.0);
                step /= parts;
            }
            // To a swing's end: its last sample (the next piece's tilt follows); elsewhere the
            // piece sampled.
            let crossing = step >= left;
            let end = if crossing && h.curve[k] < 0.5 {
                tilt = None;
                kernel::swing_end(self.block, k, db)
            } else {
                let (end, piece_tilt) = sample_piece::<f32, K>(self.block, k, db, t + step);
                tilt = Some(piece_tilt);
                end
            };
            let h = &mut self.block.hot;
            let offset = V3::new(h.ox[k], h.oy[k], h.oz[k]);
            let mut inc = end.sub(offset);
            (h.ox[k], h.oy[k], h.oz[k]) = (end.x, end.y, end.z);
            h.t[k] = t + step;
            if let Some(old) = self.cold.previous.as_mut() {
                let w = smoothstep((old.elapsed + 0.5 * step) / old.length);
                let old_end = old.piece.offset(db, old.time + step);
                inc = V3::of((old_end - old.offset).lerp(inc.vec3(), w));
                old.offset = old_end;
                old.time += step;
                old.elapsed += step;
                if old.elapsed >= old.length {
                    self.cold.previous = None;
                }
            }
            delta = delta.add(turned(turn, inc));
            remaining -= step;
            if t + step >= duration {
                // The new piece's tilt at its start is sampled only if the step ends there.
                self.next_piece(model, wind);
                tilt = None;
                crossed += 1;
                // The loop's next turn would sample the new piece at `remaining` (its clock
                // and offset at 0) and end: the lanes do that for many falls at once.
                if lanes
                    && crossed < MAX_PIECES_PER_STEP
                    && remaining > 0.0
                    && remaining < self.block.hot.duration[k]
                    && self.cold.previous.is_none()
                    && self.cold.release.is_none()
                {
                    return Still::Crossed(delta, 0.0 + remaining);
                }
            }
        }
        if remaining > 0.0 {
            delta.y -= self.cold.scales.descent_speed * remaining;
            self.cold.piece_start += f64::from(remaining);
        }
        let tilt = tilt.unwrap_or_else(|| {
            let t = self.block.hot.t[k];
            sample_piece::<f32, K>(self.block, k, db, t).1
        });
        Still::Whole(delta.vec3(), tilt)
    }

    /// The Markov step at the end of a piece (§3.2: the motion changes when its sojourn is
    /// over), then the next piece.
    fn next_piece(&mut self, model: &FallModel, wind: Vec3) {
        let db = model.database();
        let k = self.k;
        let cold = &mut *self.cold;
        let old = cold.piece;
        cold.markov_steps += 1;
        cold.piece_start += f64::from(old.duration());
        cold.lateral += self.block.hot.ox[k];
        cold.sojourn -= old.duration();
        let mut next = cold.motion;
        if cold.sojourn <= 0.0 {
            next = cold.chain.leave(cold.motion, &mut cold.rng);
            if next == cold.motion {
                cold.sojourn = cold.chain.sojourn(next, &mut cold.rng);
            }
        }
        let changed = next != cold.motion;
        if changed {
            cold.enter_motion(next);
            cold.changed = true;
        }
        let theta = old.end_angle();
        let survival = cold
            .scales
            .tumble_survival((wind.x * wind.x + wind.z * wind.z).sqrt());
        cold.piece = cold.build_piece(db, theta, survival, Some(old));
        if changed && !(matches!(old, Piece::Swing { .. }) && cold.motion.is_planar()) {
            let h = &self.block.hot;
            let time = h.t[k];
            // A change while another blends starts from what that blend shows now.
            let residual = match cold.previous.as_deref() {
                Some(running) => {
                    let own = Q::of(old.tilt(db, time));
                    running.shown(db, own).mul(own.conjugate()).normalize()
                }
                None => Q::identity(),
            };
            cold.previous = Some(Box::new(Blend {
                piece: old,
                time,
                offset: Vec3::new(h.ox[k], h.oy[k], h.oz[k]),
                elapsed: 0.0,
                length: (BLEND_SWINGS * cold.scales.swing_time()).max(MIN_BLEND),
                residual,
            }));
        }
        let piece = cold.piece;
        let h = &mut self.block.hot;
        h.t[k] = 0.0;
        (h.ox[k], h.oy[k], h.oz[k]) = (0.0, 0.0, 0.0);
        self.block.write_piece(k, &piece, db);
    }

    /// The orientation while the release orientation fades (see [`orient`] for the others):
    /// the residual of the release slerped away, eq. 15's lean growing with it.
    fn fading(
        &mut self,
        max_angle: f32,
        reference_speed: f32,
        wind: Vec3,
        piece: Q<f32>,
        dt: f32,
    ) -> Q<f32> {
        let k = self.k;
        let heading = yaw((self.block.hot.hc[k], self.block.hot.hs[k]));
        let release = self.cold.release.as_mut().expect("a release fading");
        release.elapsed += dt;
        let w = smoothstep(release.elapsed / release.length);
        let residual = Q::of(release.residual).slerp(Q::identity(), w);
        if w >= 1.0 {
            self.cold.release = None;
        }
        let lean = orient(
            max_angle,
            reference_speed,
            V3::of(wind),
            w,
            Q::identity(),
            Q::identity(),
        );
        lean.mul(residual).mul(heading.mul(piece)).normalize()
    }
}
