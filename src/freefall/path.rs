//! One fall through time: the Markov chain picks primitive motions, pieces give the still-fluid
//! path f(t), the wind carries it (§4.2), Bézier curves smooth what is shown.

use std::f32::consts::TAU;

use bevy::math::cubic_splines::CubicSegment;
use bevy::math::{Quat, Vec3};

use super::database::TrajectoryDatabase;
use super::markov::BoundedChain;
use super::motion::{FallScales, Glide, Piece, next_glide};
use super::random::FallRng;
use super::regime::PrimitiveMotion;

/// Most pieces one step may cross; the rest of a huge step falls straight at U.
const MAX_PIECES_PER_STEP: u32 = 64;
/// Motion changes blend position increments and orientation over this share of a swing.
const BLEND_SWINGS: f32 = 0.35;

/// How the wind turns the object (eq. 15): θ = W N(t) with N(t) = tanh(|u| / U_ref), so the
/// tilt grows linearly in light wind and saturates at the designer's maximum W in a gale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindTilt {
    /// W, the largest tilt, rad.
    pub max_angle: f32,
    /// U_ref, m/s: the speed that gives tanh(1) ≈ 0.76 W.
    pub reference_speed: f32,
}

impl WindTilt {
    /// The rotation that leans the object downwind.
    pub fn rotation(&self, wind: Vec3) -> Quat {
        let horizontal = Vec3::new(wind.x, 0.0, wind.z);
        let speed = wind.length();
        let Some(axis) = Vec3::Y.cross(horizontal).try_normalize() else {
            return Quat::IDENTITY;
        };
        if !(speed.is_finite() && self.max_angle.is_finite()) {
            return Quat::IDENTITY;
        }
        let angle = self.max_angle * (speed / self.reference_speed.max(1e-3)).tanh();
        Quat::from_axis_angle(axis, angle)
    }
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
    chain: BoundedChain,
    rng: FallRng,
    motion: PrimitiveMotion,
    yaw: Quat,
    glide: Glide,
    piece: Piece,
    piece_time: f32,
    /// The piece before a motion change and its time, while the change blends.
    previous: Option<(Piece, f32)>,
    blend_time: f32,
    still: Vec3,
    /// Control points p_{i−2}, p_{i−1}, p_i.
    points: [Vec3; 3],
    /// Orientation at p_{i−1} and p_i.
    orientations: [Quat; 2],
    ground: f32,
    landed: bool,
    time: f32,
    transitions: Vec<(PrimitiveMotion, PrimitiveMotion)>,
    record_transitions: bool,
}

impl FallPath {
    /// A fall released at `position` that lands at height `ground`.
    pub fn new(
        db: &TrajectoryDatabase,
        scales: FallScales,
        chain: BoundedChain,
        seed: u64,
        position: Vec3,
        ground: f32,
    ) -> Self {
        let mut rng = FallRng::new(seed);
        let motion = chain.start(&mut rng);
        let yaw = Quat::from_rotation_y(rng.uniform() * TAU);
        let glide = if rng.coin() {
            Glide::Left
        } else {
            Glide::Right
        };
        let mut path = Self {
            scales,
            chain,
            rng,
            motion,
            yaw,
            glide,
            piece: Piece::curve(&scales, PrimitiveMotion::SteadyDescent, 0.0),
            piece_time: 0.0,
            previous: None,
            blend_time: 0.0,
            still: Vec3::ZERO,
            points: [position; 3],
            orientations: [yaw; 2],
            ground,
            landed: false,
            time: 0.0,
            transitions: Vec::new(),
            record_transitions: false,
        };
        path.piece = path.build_piece(db, None);
        let tilt = path.yaw * path.piece.tilt(db, 0.0);
        path.orientations = [tilt; 2];
        path
    }

    /// Keep every Markov step as (from, to) in [`FallPath::transitions`] (for tests and tools).
    pub fn record_transitions(&mut self, on: bool) {
        self.record_transitions = on;
    }

    /// The recorded Markov steps.
    pub fn transitions(&self) -> &[(PrimitiveMotion, PrimitiveMotion)] {
        &self.transitions
    }

    /// Advances by `dt` seconds: p ← p + u dt + Δf (§4.2), with `wind` the velocity at the
    /// current position (zero in still fluid), and `tilt` the wind's turn of eq. 15.
    pub fn advance(
        &mut self,
        db: &TrajectoryDatabase,
        dt: f32,
        wind: Vec3,
        tilt: &WindTilt,
    ) -> StepOutcome {
        if self.landed {
            // Let the shown curve settle on the resting point.
            self.points = [self.points[1], self.points[2], self.points[2]];
            self.orientations = [self.orientations[1]; 2];
            return StepOutcome::Resting;
        }
        let dt = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        let wind = if wind.is_finite() { wind } else { Vec3::ZERO };
        let delta = self.still_step(db, dt);
        self.time += dt;
        self.still += delta;
        let mut next = self.points[2] + wind * dt + delta;
        let landed = next.y <= self.ground;
        if landed {
            next.y = self.ground;
        }
        let orientation = tilt.rotation(wind) * self.orientation_now(db);
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
    fn still_step(&mut self, db: &TrajectoryDatabase, dt: f32) -> Vec3 {
        let mut remaining = dt;
        let mut delta = Vec3::ZERO;
        let blend = BLEND_SWINGS * self.scales.swing_time();
        let mut crossed = 0;
        while remaining > 0.0 && crossed < MAX_PIECES_PER_STEP {
            let left = (self.piece.duration() - self.piece_time).max(0.0);
            let h = remaining.min(left);
            let t0 = self.piece_time;
            let mut inc = self.piece.offset(db, t0 + h) - self.piece.offset(db, t0);
            if let Some((old, old_time)) = self.previous.as_mut() {
                let w = smoothstep((self.blend_time + 0.5 * h) / blend);
                let old_inc = old.offset(db, *old_time + h) - old.offset(db, *old_time);
                inc = old_inc.lerp(inc, w);
                *old_time += h;
                self.blend_time += h;
                if self.blend_time >= blend {
                    self.previous = None;
                }
            }
            delta += self.yaw * inc;
            self.piece_time += h;
            remaining -= h;
            if self.piece_time >= self.piece.duration() {
                self.next_piece(db);
                crossed += 1;
            }
        }
        if remaining > 0.0 {
            delta.y -= self.scales.descent_speed * remaining;
        }
        delta
    }

    fn next_piece(&mut self, db: &TrajectoryDatabase) {
        let next = self.chain.next(self.motion, &mut self.rng);
        if self.record_transitions {
            self.transitions.push((self.motion, next));
        }
        let old = self.piece;
        if next != self.motion {
            self.previous = Some((old, old.duration()));
            self.blend_time = 0.0;
        }
        self.motion = next;
        self.piece = self.build_piece(db, Some(old));
        self.piece_time = 0.0;
    }

    fn build_piece(&mut self, db: &TrajectoryDatabase, old: Option<Piece>) -> Piece {
        let theta0 = old.map_or(0.0, |p| p.end_angle(db));
        if self.motion.is_planar() {
            let (glide, r) = next_glide(self.motion, self.glide, &mut self.rng);
            self.glide = glide;
            return Piece::swing(
                db,
                &self.scales,
                self.motion,
                glide,
                r,
                theta0,
                &mut self.rng,
            );
        }
        match old {
            // The same curve carries on from where it was.
            Some(Piece::Curve {
                start, duration, ..
            }) if self.previous.is_none() => {
                Piece::curve(&self.scales, self.motion, start + duration)
            }
            _ => {
                let phase = self.rng.uniform() * TAU / (self.scales.swing_rate * 0.5).max(1e-6);
                Piece::curve(&self.scales, self.motion, phase)
            }
        }
    }

    fn orientation_now(&self, db: &TrajectoryDatabase) -> Quat {
        let tilt = self.piece.tilt(db, self.piece_time);
        let tilt = match self.previous {
            Some((old, old_time)) => {
                let blend = BLEND_SWINGS * self.scales.swing_time();
                old.tilt(db, old_time)
                    .slerp(tilt, smoothstep(self.blend_time / blend))
            }
            None => tilt,
        };
        (self.yaw * tilt).normalize()
    }

    /// The shown pose a fraction `s` ∈ [0, 1] of a step after the second-to-last control point:
    /// a cubic Bézier from p_{i−1} to p_i with Catmull–Rom tangents (bevy_math's
    /// [`CubicSegment::new_bezier`]), one step behind the simulation, and a slerp of the
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
        (curve.position(s), q0.slerp(q1, s))
    }

    /// p_i, the latest control point.
    pub fn position(&self) -> Vec3 {
        self.points[2]
    }

    /// The latest orientation.
    pub fn orientation(&self) -> Quat {
        self.orientations[1]
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

    /// Seconds since release.
    pub fn time(&self) -> f32 {
        self.time
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

fn smoothstep(x: f32) -> f32 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}
