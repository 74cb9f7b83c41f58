//! One fall through time: the Markov chain picks primitive motions, pieces give the still-fluid
//! path f(t), the fluid carries it (§4.2) through a response time, Béziers smooth what is shown.

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use bevy::math::cubic_splines::CubicSegment;
use bevy::math::{Quat, Vec3};

use super::database::TrajectoryDatabase;
use super::markov::BoundedChain;
use super::model::FallModel;
use super::motion::{FallScales, Glide, next_glide};
use super::piece::{Piece, SwingChoice};
use super::random::FallRng;
use super::regime::PrimitiveMotion;
use super::release::{FallRelease, LIFT_OFF_FACTOR, LIFT_OFF_HOP, MAX_RELEASE_SPEED, MAX_STEP};
pub use super::tilt::WindTilt;

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
const MIN_DRIFT: f32 = 1e-6;

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
    pub fn release(
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
            None => (Quat::from_rotation_y(random_yaw), 0.0),
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
        let synthesised = path.yaw() * path.piece_tilt;
        let shown = match rotation {
            Some(q) => {
                path.release = Some(Box::new(ReleaseFade {
                    residual: (q * synthesised.inverse()).normalize(),
                    elapsed: 0.0,
                    length: (RELEASE_SWINGS * scales.swing_time()).max(MIN_RELEASE),
                }));
                q
            }
            None => synthesised,
        };
        path.orientations = [shown; 2];
        path
    }

    /// Lets a resting object go again in a wind strong enough to lift it (see
    /// [`LIFT_OFF_FACTOR`]): from where it lies, a hop above the ground, in the orientation it
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
    /// Hostile input is clamped: `dt` to 0..=[`MAX_STEP`] (non-finite: 0), `wind` to
    /// [`MAX_RELEASE_SPEED`] (non-finite: still fluid).
    pub fn advance(
        &mut self,
        model: &FallModel,
        dt: f32,
        wind: Vec3,
        tilt: &WindTilt,
    ) -> StepOutcome {
        let dt = if dt.is_finite() {
            dt.clamp(0.0, MAX_STEP)
        } else {
            0.0
        };
        let wind = crate::guard::clamp_length(wind, MAX_RELEASE_SPEED);
        if self.landed {
            if wind.length() > LIFT_OFF_FACTOR * self.scales.descent_speed {
                self.lift_off(model, wind);
            } else {
                // Let the shown curve settle on the resting point.
                self.points = [self.points[1], self.points[2], self.points[2]];
                self.orientations = [self.orientations[1]; 2];
                return StepOutcome::Resting;
            }
        }
        let delta = self.still_step(model, dt, wind);
        self.time += f64::from(dt);
        self.still += delta;
        // Backward Euler on dv/dt = (u − v) / τ: never past the wind, stable at any step. In
        // still air the decaying drift would stay on subnormals (slow assists): flushed.
        let slip = wind - self.drift;
        let k = dt * self.scales.response_rate(slip.length_squared());
        self.drift += slip * (k / (1.0 + k));
        if self.drift.length_squared() < MIN_DRIFT * MIN_DRIFT {
            self.drift = Vec3::ZERO;
        }
        let mut next = self.points[2] + self.drift * dt + delta;
        let landed = next.y <= self.ground;
        if landed {
            next.y = self.ground;
            self.drift = Vec3::ZERO;
        }
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
            self.lateral += inc.x;
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

    /// The Markov step at the end of a piece (§3.2), then the next piece.
    fn next_piece(&mut self, model: &FallModel, wind: Vec3) {
        let db = model.database();
        let old = self.piece;
        let next = self
            .chain
            .next_after(self.motion, old.duration(), &mut self.rng);
        self.markov_steps += 1;
        let changed = next != self.motion;
        if changed {
            self.enter_motion(next);
        }
        let theta = old.end_angle();
        let survival = self
            .scales
            .tumble_survival((wind.x * wind.x + wind.z * wind.z).sqrt());
        self.piece = self.build_piece(db, theta, survival, Some(old));
        if changed && !(old_is_planar(&old) && self.motion.is_planar()) {
            self.previous = Some(Box::new(Blend {
                piece: old,
                time: self.piece_time,
                offset: self.piece_offset,
                elapsed: 0.0,
                length: (BLEND_SWINGS * self.scales.swing_time()).max(MIN_BLEND),
            }));
        }
        self.piece_time = 0.0;
        self.piece_offset = Vec3::ZERO;
        self.piece_tilt = self.piece.tilt(db, 0.0);
    }

    /// `v` from the heading frame to the world: a turn by ψ about +Y.
    fn turned(&self, v: Vec3) -> Vec3 {
        let (ch, sh) = (self.heading.x, self.heading.y);
        let (c, s) = (ch * ch - sh * sh, 2.0 * ch * sh);
        Vec3::new(v.x * c + v.z * s, v.y, v.z * c - v.x * s)
    }

    /// The heading as a quaternion.
    fn yaw(&self) -> Quat {
        Quat::from_xyzw(0.0, self.heading.y, 0.0, self.heading.x)
    }

    /// A new motion: its amplitude with the Gaussian spread; swings go round where it is.
    fn enter_motion(&mut self, motion: PrimitiveMotion) {
        if !(motion.is_planar() && self.motion.is_planar()) {
            self.centre = self.lateral;
        }
        self.motion = motion;
        self.amplitude = self.scales.spread_amplitude(motion, &mut self.rng);
    }

    fn build_piece(
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
            let key = self.scales.swing_key(glide_to, choice.swings(same_side));
            let segment = db.find(&key, &mut self.rng);
            return Piece::swing(db, &self.scales, segment, choice);
        }
        let flip = PI * (theta / PI).round();
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

    fn orientation_now(
        &mut self,
        db: &TrajectoryDatabase,
        wind: Vec3,
        tilt: &WindTilt,
        dt: f32,
    ) -> Quat {
        let piece = match &self.previous {
            Some(old) => old
                .piece
                .tilt(db, old.time)
                .slerp(self.piece_tilt, smoothstep(old.elapsed / old.length)),
            None => self.piece_tilt,
        };
        let synthesised = self.yaw() * piece;
        // Unit to rounding: each step's orientation is made afresh, and what is shown is
        // normalised (`smoothed`, `orientation`).
        let Some(release) = self.release.as_mut() else {
            return tilt.rotation(wind) * synthesised;
        };
        release.elapsed += dt;
        let w = smoothstep(release.elapsed / release.length);
        let residual = release.residual.slerp(Quat::IDENTITY, w);
        if w >= 1.0 {
            self.release = None;
        }
        (tilt.scaled_rotation(wind, w) * residual * synthesised).normalize()
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

    /// The current piece of the still-fluid path.
    pub fn piece(&self) -> &Piece {
        &self.piece
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

fn old_is_planar(piece: &Piece) -> bool {
    matches!(piece, Piece::Swing { .. })
}

/// The heading (a rotation about +Y) whose frame has the plate's long axis (local Z) as its z,
/// and the plate's pitch about that axis. A long axis pointing straight up or down gives no
/// heading: `fallback` (an angle about Y) is used.
fn heading_and_pitch(rotation: Quat, fallback: f32) -> (Quat, f32) {
    let long = rotation * Vec3::Z;
    let horizontal = bevy::math::Vec2::new(long.x, long.z);
    let yaw = if horizontal.length_squared() > 1e-6 {
        Quat::from_rotation_y(horizontal.x.atan2(horizontal.y))
    } else {
        Quat::from_rotation_y(fallback)
    };
    let chord = yaw.inverse() * (rotation * Vec3::X);
    (yaw, chord.y.atan2(chord.x))
}

fn smoothstep(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
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
