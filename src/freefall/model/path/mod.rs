//! One fall through time: the Markov chain picks primitive motions, pieces give the still-fluid
//! path f(t), the fluid carries it (§4.2) through a response time, Béziers smooth what is shown.

use std::f32::consts::TAU;
use std::sync::Arc;

use bevy::math::{Quat, Vec3};

use super::FallModel;
use super::markov::BoundedChain;
use super::motion::{FallScales, Glide};
use super::piece::Piece;
use super::random::FallRng;
use super::regime::PrimitiveMotion;
use super::release::{FallRelease, LIFT_OFF_HOP};
pub use super::tilt::WindTilt;

mod chain;
mod pose;
pub(crate) mod usual;
use crate::math::geometry::{Q, V3};
use pose::{heading_and_pitch, smoothstep};

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
/// Drift speeds below this, m/s, are still air (flushed to zero in `FallPath::advance`).
pub(crate) const MIN_DRIFT: f32 = 1e-6;

/// The piece a motion change blends away from: its time and offset run on past its end.
#[derive(Clone, Copy, Debug)]
struct Blend {
    piece: Piece,
    time: f32,
    offset: Vec3,
    elapsed: f32,
    length: f32,
}

/// The part of the release orientation the synthesis does not reproduce, fading out.
#[derive(Clone, Copy, Debug)]
struct ReleaseFade {
    residual: Quat,
    elapsed: f32,
    length: f32,
}

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

/// The state of one falling object.
#[derive(Clone, Debug)]
pub struct FallPath {
    scales: FallScales,
    chain: Arc<BoundedChain>,
    rng: FallRng,
    motion: PrimitiveMotion,
    /// A₀ of the current motion with its Gaussian draw (§2.3.2), m.
    amplitude: f32,
    /// (cos ψ/2, sin ψ/2) of the heading ψ, a rotation about +Y.
    heading: bevy::math::Vec2,
    glide: Glide,
    /// No swing yet: the first one reverses nothing.
    fresh: bool,
    piece: Piece,
    piece_time: f32,
    /// `piece.sample(piece_time)`, kept so each step evaluates the piece once.
    piece_offset: Vec3,
    piece_tilt: Quat,
    /// Sideways position along the heading, m, and the centre the swings go round (moved on by
    /// half-turns, which drift).
    lateral: f32,
    centre: f32,
    /// The piece before a motion change, while the change blends (boxed: rare, and a small
    /// path keeps ten thousand of them in cache).
    previous: Option<Box<Blend>>,
    release: Option<Box<ReleaseFade>>,
    /// Velocity of the fluid-following part, m/s.
    drift: Vec3,
    still: Vec3,
    /// Control points p_{i−2}, p_{i−1}, p_i.
    points: [Vec3; 3],
    /// What rounding left out of p_i so far (compensated summation): far from the origin a
    /// step's move can be below f32's spacing, and is carried until it adds up to one, so a
    /// fall let go 1e6 m up still moves at its speed on average.
    carry: Vec3,
    /// Orientation at p_{i−1} and p_i.
    orientations: [Quat; 2],
    ground: f32,
    landed: bool,
    time: f64,
    markov_steps: u32,
}

impl FallPath {
    /// A fall with main motion `main` and the model's chain, let go at rest at `position`,
    /// flat, with a heading from the seed, landing at height `ground`.
    pub fn new(
        model: &FallModel,
        scales: FallScales,
        main: PrimitiveMotion,
        seed: u64,
        position: Vec3,
        ground: f32,
    ) -> Self {
        Self::release(
            model,
            scales,
            model.bounded_shared(main),
            seed,
            FallRelease::at(position, ground),
        )
    }

    /// A fall following `chain` (bounded by its main motion), let go as `release` says.
    ///
    /// The release orientation is kept: the plate's long axis sets the heading (it glides
    /// across it), its pitch about that axis is the first swing's start angle, and whatever
    /// else it has (a roll, a tilt the first motion does not have) fades out over a swing.
    pub(crate) fn release(
        model: &FallModel,
        scales: FallScales,
        chain: Arc<BoundedChain>,
        seed: u64,
        release: FallRelease,
    ) -> Self {
        let db = model.database();
        let mut rng = FallRng::new(seed);
        let motion = chain.start(&mut rng);
        let random_yaw = rng.uniform() * TAU;
        let glide = if rng.coin() {
            Glide::Left
        } else {
            Glide::Right
        };
        let rotation = release.rotation.and_then(crate::guard::unit_quat);
        let (yaw, theta) = match rotation {
            Some(q) => heading_and_pitch(q, random_yaw),
            None => (Q::from_rotation_y(random_yaw).quat(), 0.0),
        };
        let position = if release.position.is_finite() {
            release.position
        } else {
            Vec3::ZERO
        };
        let drift = if release.velocity.is_finite() {
            release.velocity
        } else {
            Vec3::ZERO
        };
        let mut path = Self {
            scales,
            chain,
            rng,
            motion,
            amplitude: 0.0,
            heading: bevy::math::Vec2::new(yaw.w, yaw.y),
            glide,
            fresh: true,
            piece: Piece::curve(&scales, PrimitiveMotion::SteadyDescent, 0.0, 0.0, 0.0),
            piece_time: 0.0,
            piece_offset: Vec3::ZERO,
            piece_tilt: Quat::IDENTITY,
            lateral: 0.0,
            centre: 0.0,
            previous: None,
            release: None,
            drift,
            still: Vec3::ZERO,
            points: [position; 3],
            carry: Vec3::ZERO,
            orientations: [yaw; 2],
            ground: release.ground,
            landed: false,
            time: 0.0,
            markov_steps: 0,
        };
        path.motion = PrimitiveMotion::SteadyDescent;
        path.enter_motion(motion);
        path.piece = path.build_piece(db, theta, 1.0, None);
        path.piece_tilt = path.piece.tilt(db, 0.0);
        let synthesised = Q::of(path.yaw()).mul(Q::of(path.piece_tilt));
        let shown = match rotation {
            Some(q) => {
                path.release = Some(Box::new(ReleaseFade {
                    residual: Q::of(q).mul(synthesised.conjugate()).normalize().quat(),
                    elapsed: 0.0,
                    length: (RELEASE_SWINGS * scales.swing_time()).max(MIN_RELEASE),
                }));
                q
            }
            None => synthesised.quat(),
        };
        path.orientations = [shown; 2];
        path
    }

    /// Lets a resting object go again in a wind strong enough to lift it (see
    /// [`FallRelease::LIFT_OFF_FACTOR`](crate::freefall::FallRelease::LIFT_OFF_FACTOR)): from where it lies, a hop above the ground, in the orientation it
    /// lies in, at the wind's velocity plus half the wind's speed upward, with a new seed from
    /// its own stream (so the same run lifts it the same way). Its clock and Markov count go on.
    fn lift_off(&mut self, model: &FallModel, wind: Vec3) {
        let release = FallRelease {
            position: self.points[2] + Vec3::Y * LIFT_OFF_HOP,
            rotation: Some(self.orientations[1]),
            velocity: wind + Vec3::Y * (0.5 * wind.length()),
            ground: self.ground,
        };
        let seed = self.rng.bits();
        let (time, markov_steps) = (self.time, self.markov_steps);
        *self = Self::release(model, self.scales, Arc::clone(&self.chain), seed, release);
        self.time = time;
        self.markov_steps = markov_steps;
    }

    /// Markov steps taken (one per finished piece).
    pub fn markov_steps(&self) -> u32 {
        self.markov_steps
    }

    /// Advances by `dt` seconds: p ← p + v dt + Δf (§4.2), where v, the velocity of the part of
    /// the motion the fluid carries, relaxes toward `wind` (the fluid's velocity at the current
    /// position; zero in still fluid) over [`FallScales::response_time`], and Δf is the still-fluid
    /// path's increment; `tilt` is the wind's turn of eq. 15.
    ///
    /// Hostile input is clamped: `dt` to 0..=[`FallRelease::MAX_STEP`](crate::freefall::FallRelease::MAX_STEP) (non-finite: 0), `wind` to
    /// [`FallRelease::MAX_SPEED`](crate::freefall::FallRelease::MAX_SPEED) (non-finite: still fluid).
    pub fn advance(
        &mut self,
        model: &FallModel,
        dt: f32,
        wind: Vec3,
        tilt: &WindTilt,
    ) -> StepOutcome {
        let dt = if dt.is_finite() {
            dt.clamp(0.0, FallRelease::MAX_STEP)
        } else {
            0.0
        };
        let wind = crate::guard::clamp_length(wind, FallRelease::MAX_SPEED);
        if self.landed {
            if wind.length() > FallRelease::LIFT_OFF_FACTOR * self.scales.descent_speed {
                self.lift_off(model, wind);
            } else {
                // Let the shown curve settle on the resting point.
                self.points = [self.points[1], self.points[2], self.points[2]];
                self.orientations = [self.orientations[1]; 2];
                return StepOutcome::Resting;
            }
        }
        if self.usual(dt) {
            // Inside one piece: the step lanes take too, through the same code.
            let mut hot = self.hot(tilt);
            hot.piece_time += dt;
            let (end, turn) = self.piece.sample(model.database(), hot.piece_time);
            let made = usual::advance(&mut hot, V3::of(end), Q::of(turn), dt, V3::of(wind));
            return if self.take_usual(&hot, &made, 0, dt) {
                StepOutcome::Landed
            } else {
                StepOutcome::Falling
            };
        }
        let delta = self.still_step(model, dt, wind);
        self.time += f64::from(dt);
        let mut hot = self.hot(tilt);
        let (next, landed) = usual::fall_on(&mut hot, V3::of(delta), dt, V3::of(wind));
        (self.drift, self.still, self.carry) =
            (hot.drift.vec3(), hot.still.vec3(), hot.carry.vec3());
        let next = next.vec3();
        let orientation = self.orientation_now(model.database(), wind, tilt, dt);
        self.points = [self.points[1], self.points[2], next];
        self.orientations = [self.orientations[1], orientation];
        if landed {
            self.landed = true;
            StepOutcome::Landed
        } else {
            StepOutcome::Falling
        }
    }

    /// Still-fluid displacement over `dt`, crossing pieces as needed.
    fn still_step(&mut self, model: &FallModel, dt: f32, wind: Vec3) -> Vec3 {
        let db = model.database();
        // The usual step: inside one piece, no blend.
        if self.previous.is_none() && self.piece_time + dt < self.piece.duration() {
            self.piece_time += dt;
            let (end, tilt) = self.piece.sample(db, self.piece_time);
            let inc = end - self.piece_offset;
            self.piece_offset = end;
            self.piece_tilt = tilt;
            self.lateral += inc.x;
            return self.turned(inc);
        }
        let mut remaining = dt;
        let mut delta = Vec3::ZERO;
        let mut crossed = 0;
        while remaining > 0.0 && crossed < MAX_PIECES_PER_STEP {
            let left = (self.piece.duration() - self.piece_time).max(0.0);
            let h = remaining.min(left);
            let (end, tilt) = self.piece.sample(db, self.piece_time + h);
            let mut inc = end - self.piece_offset;
            self.piece_offset = end;
            self.piece_tilt = tilt;
            // The swings go round the synthesis' own sideways position, not the blended one:
            // the pieces then do not depend on the step (a leaf stepped every fourth step
            // picks the same swings).
            self.lateral += inc.x;
            if let Some(old) = self.previous.as_mut() {
                let w = smoothstep((old.elapsed + 0.5 * h) / old.length);
                let old_end = old.piece.offset(db, old.time + h);
                inc = (old_end - old.offset).lerp(inc, w);
                old.offset = old_end;
                old.time += h;
                old.elapsed += h;
                if old.elapsed >= old.length {
                    self.previous = None;
                }
            }
            delta += self.turned(inc);
            self.piece_time += h;
            remaining -= h;
            if self.piece_time >= self.piece.duration() {
                self.next_piece(model, wind);
                crossed += 1;
            }
        }
        if remaining > 0.0 {
            delta.y -= self.scales.descent_speed * remaining;
        }
        delta
    }

    /// `v` from the heading frame to the world: a turn by ψ about +Y.
    fn turned(&self, v: Vec3) -> Vec3 {
        usual::turned((self.heading.x, self.heading.y), V3::of(v)).vec3()
    }

    /// The heading as a quaternion.
    fn yaw(&self) -> Quat {
        Quat::from_xyzw(0.0, self.heading.y, 0.0, self.heading.x)
    }
}
