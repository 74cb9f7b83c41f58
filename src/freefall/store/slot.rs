//! One fall of the store, one at a time: how it is let go (and lifted again from the ground),
//! and the step the lanes do not take (a piece ends and the Markov chain steps, a swing is
//! searched, a motion change blends, the release orientation fades, a resting fall settles).
//! Whatever part of such a step the lanes also take goes through the same kernels
//! ([`kernel`](super::kernel)), one lane wide.

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use bevy::math::{Quat, Vec3};

use super::block::{Blend, Block, Cold, Constants, Easing, FallConstants, Hot, ReleaseFade};
use super::kernel::{self, Motion, commit, fall_on, motion, orient, sample_piece, turned, yaw};
use super::pose::{LeafPose, shown, smoothed};
use crate::freefall::lod::FallClock;
use crate::freefall::model::FallModel;
use crate::freefall::model::database::{SearchMemo, TrajectoryDatabase};
use crate::freefall::model::markov::BoundedChain;
use crate::freefall::model::motion::{FallScales, Glide, next_glide};
use crate::freefall::model::piece::{Piece, SwingChoice};
use crate::freefall::model::random::FallRng;
use crate::freefall::model::regime::PrimitiveMotion;
use crate::freefall::model::release::{FallRelease, LIFT_OFF_HOP};
use crate::lod::LodTiers;
use crate::math::geometry::{Q, V3};
use crate::math::kernels::atan2;

/// Most pieces one step may cross; the rest of a huge step falls straight at U.
const MAX_PIECES_PER_STEP: u32 = 64;
/// Motion changes that switch between swings and eq. 6 blend position increments and
/// orientation over this share of a swing ...
const BLEND_SWINGS: f32 = 0.35;
/// ... and at least this long, s, so a blend spans several frames of any frame rate.
const MIN_BLEND: f32 = 0.15;
/// The release orientation fades into the synthesised one over this many swings ...
const RELEASE_SWINGS: f32 = 1.0;
/// ... and at least this long, s.
const MIN_RELEASE: f32 = 0.25;

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

/// Everything that starts a fall.
#[derive(Clone, Debug)]
pub(crate) struct FallStart {
    pub scales: FallScales,
    pub chain: Arc<BoundedChain>,
    pub seed: u64,
    pub release: FallRelease,
    /// Eq. 15's W, rad.
    pub max_angle: f32,
    pub lod: Option<LodTiers>,
}

/// What [`Slot::prepare`] leaves to finish.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Part {
    /// Nothing: the step is done, and did this.
    Done(StepOutcome),
    /// The move (the still-fluid displacement `delta`, world frame, m) and the orientation
    /// (the plate's `tilt` in the heading frame): the piece's clock and offset are written.
    Move { delta: Vec3, tilt: Q<f32> },
}

/// One fall of a store: lane `k` of `block` and its cold state.
pub(crate) struct Slot<'a, K: Constants> {
    pub block: &'a mut Block<K>,
    pub k: usize,
    pub cold: &'a mut Cold,
}

/// The cold state of a fall about to be let go (what [`Slot::release`] fills in).
pub(crate) fn blank_cold(start: &FallStart) -> Cold {
    Cold {
        scales: start.scales,
        chain: Arc::clone(&start.chain),
        rng: FallRng::new(start.seed),
        motion: PrimitiveMotion::SteadyDescent,
        sojourn: f32::INFINITY,
        amplitude: 0.0,
        glide: Glide::Right,
        fresh: true,
        piece: Piece::curve(&start.scales, PrimitiveMotion::SteadyDescent, 0.0, 0.0, 0.0),
        lateral: 0.0,
        centre: 0.0,
        key_angle: start.scales.swing_key_angle(),
        piece_start: 0.0,
        markov_steps: 0,
        previous: None,
        release: None,
        easing: None,
        releases: 1,
        changed: false,
        lifted: false,
        search: SearchMemo::default(),
    }
}

impl<K: Constants> Slot<'_, K> {
    /// Lets the fall go as `start` says, its clock at `clock` (its first step is then taken
    /// at once, over the time since): the chain's first motion, a heading from the seed (or
    /// the release orientation's long axis), the first piece, the release orientation fading
    /// into the synthesised one over a swing.
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
        *self.cold = blank_cold(start);
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
        let piece_tilt = cold.piece.tilt(db, 0.0);
        let synthesised = Q::of(heading).mul(Q::of(piece_tilt));
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
        let (k, piece) = (self.k, cold.piece);
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
            (&mut h.t, 0.0),
            (&mut h.ox, 0.0),
            (&mut h.oy, 0.0),
            (&mut h.oz, 0.0),
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
        write_piece(self.block, k, &piece, db);
        self.set_plain();
    }

    /// Lets a resting fall go again in a wind strong enough to lift it (see
    /// [`FallRelease::LIFT_OFF_FACTOR`]): from where it lies, a hop above the ground, in the
    /// orientation it lies in, at the wind's velocity plus half the wind's speed upward, with a
    /// new seed from its own stream (so the same run lifts it the same way). Its clock and
    /// Markov count go on.
    fn lift_off(&mut self, kind: &K, model: &FallModel, wind: Vec3) {
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
    pub fn advance(
        &mut self,
        kind: &K,
        model: &FallModel,
        dt: f32,
        wind: Vec3,
        reference_speed: f32,
    ) -> StepOutcome {
        match self.prepare(kind, model, dt, wind, reference_speed) {
            Part::Done(outcome) => outcome,
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
                    reference_speed,
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
    /// the lanes finish ([`kernel::finish`]) for many falls at once.
    pub fn prepare(
        &mut self,
        kind: &K,
        model: &FallModel,
        dt: f32,
        wind: Vec3,
        reference_speed: f32,
    ) -> Part {
        let k = self.k;
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
        let (delta, tilt) = self.still_step(model, dt, wind);
        let tilt = match &self.cold.previous {
            Some(old) => Q::of(old.piece.tilt(db, old.time))
                .slerp(tilt, smoothstep(old.elapsed / old.length)),
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
        let orientation = self.fading(c.max_angle, reference_speed, wind, tilt, dt);
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
    /// plate's tilt at the end.
    fn still_step(&mut self, model: &FallModel, dt: f32, wind: Vec3) -> (Vec3, Q<f32>) {
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
            let step = remaining.min(left);
            // To a swing's end: its last sample (the next piece's tilt follows); elsewhere the
            // piece sampled.
            let crossing = remaining >= left;
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
        (delta.vec3(), tilt)
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
            cold.previous = Some(Box::new(Blend {
                piece: old,
                time: h.t[k],
                offset: Vec3::new(h.ox[k], h.oy[k], h.oz[k]),
                elapsed: 0.0,
                length: (BLEND_SWINGS * cold.scales.swing_time()).max(MIN_BLEND),
            }));
        }
        let piece = cold.piece;
        let h = &mut self.block.hot;
        h.t[k] = 0.0;
        (h.ox[k], h.oy[k], h.oz[k]) = (0.0, 0.0, 0.0);
        write_piece(self.block, k, &piece, db);
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

impl Cold {
    /// A new motion: its amplitude with the Gaussian spread and its sojourn; swings go round
    /// where the fall is.
    pub(crate) fn enter_motion(&mut self, motion: PrimitiveMotion) {
        if !(motion.is_planar() && self.motion.is_planar()) {
            self.centre = self.lateral;
        }
        self.motion = motion;
        self.amplitude = self.scales.spread_amplitude(motion, &mut self.rng);
        self.sojourn = self.chain.sojourn(motion, &mut self.rng);
    }

    /// The piece that follows `old` (or the first, `None`) with the plate at angle `theta`: a
    /// swing found by the search tree (§2.3.1) for a planar motion, eq. 6 otherwise (the same
    /// curve carried on where it can be).
    pub(crate) fn build_piece(
        &mut self,
        db: &TrajectoryDatabase,
        theta: f32,
        survival: f32,
        old: Option<Piece>,
    ) -> Piece {
        if self.motion.is_planar() {
            let (glide, r) = next_glide(self.motion, self.glide, &mut self.rng);
            let same_side = !self.fresh && glide == self.glide;
            self.fresh = false;
            self.glide = glide;
            let choice = SwingChoice {
                glide,
                same_side,
                r,
                theta,
                survival,
                rate: old.map_or(0.0, |p| p.end_rate(db)),
            };
            // The search key (§2.3.1): the glide to the next turning point, r A₀ to the other
            // side of the centre (A_e = r A₀), or on by 2 r A₀ for a half-turn, which drifts.
            let reach = r * self.amplitude;
            let glide_to = if same_side {
                self.centre += glide.sign() * 2.0 * reach;
                2.0 * reach
            } else {
                // Past the turning point already (a long previous swing): a short swing back.
                ((self.centre + glide.sign() * reach - self.lateral) * glide.sign()).max(0.0)
            };
            let key =
                self.scales
                    .swing_key_with(self.key_angle, glide_to, choice.swings(same_side));
            let segment = db.find_remembered(&key, &mut self.rng, &mut self.search);
            return Piece::swing(db, &self.scales, segment, choice);
        }
        // The plate's half-turns, less whole turns of the half angle (4π: the same quaternion).
        let turns = 4.0 * PI;
        let flip = PI * crate::math::kernels::round(theta / PI);
        let flip = flip - turns * crate::math::kernels::round(flip / turns);
        match old {
            // The same curve carries on from where it was.
            Some(Piece::Curve {
                start, duration, ..
            }) if old.is_some_and(|p| p.end_angle() == flip) && !self.curve_changed(&old) => {
                Piece::curve(
                    &self.scales,
                    self.motion,
                    self.amplitude,
                    start + duration,
                    flip,
                )
            }
            _ => {
                let phase = self.rng.uniform() * TAU / (self.scales.swing_rate * 0.25).max(1e-6);
                Piece::curve(&self.scales, self.motion, self.amplitude, phase, flip)
            }
        }
    }

    /// Whether the last piece was a curve of another motion.
    fn curve_changed(&self, old: &Option<Piece>) -> bool {
        let Some(Piece::Curve {
            eccentricity,
            lobes,
            ..
        }) = old
        else {
            return true;
        };
        let fresh = Piece::curve(&self.scales, self.motion, self.amplitude, 0.0, 0.0);
        !matches!(fresh, Piece::Curve { eccentricity: e, lobes: l, .. } if e == *eccentricity && l == *lobes)
    }
}

/// Writes `piece`, compiled, into lane `k` of `block`.
pub(crate) fn write_piece<K: Constants>(
    block: &mut Block<K>,
    k: usize,
    piece: &Piece,
    db: &TrajectoryDatabase,
) {
    let words = piece.words(db);
    let h: &mut Hot = &mut block.hot;
    h.duration[k] = words.duration;
    h.inv_duration[k] = words.inv_duration;
    for (column, value) in [
        &mut h.w0, &mut h.w1, &mut h.w2, &mut h.w3, &mut h.w4, &mut h.w5, &mut h.w6, &mut h.w7,
        &mut h.w8, &mut h.w9, &mut h.w10,
    ]
    .into_iter()
    .zip(words.words)
    {
        column[k] = value;
    }
    h.curve[k] = if words.curve { 1.0 } else { 0.0 };
    h.tumble[k] = if words.tumble { 1.0 } else { 0.0 };
    block.row[k] = words.row;
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

/// 3x² − 2x³ on x clamped to [0, 1] (bevy_math's `EaseFunction::SmoothStep`): how a blend and
/// the release's residual fade.
pub(crate) fn smoothstep(x: f32) -> f32 {
    use bevy::math::curve::{Curve, EaseFunction};
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
