//! One fall through time: the Markov chain picks primitive motions, pieces give the still-fluid
//! path f(t), the wind carries it (§4.2), Bézier curves smooth what is shown.

use std::f32::consts::{PI, TAU};

use bevy::math::cubic_splines::CubicSegment;
use bevy::math::{Quat, Vec3};

use super::database::TrajectoryDatabase;
use super::model::FallModel;
use super::motion::{FallScales, Glide, Piece, next_glide};
use super::random::FallRng;
use super::regime::PrimitiveMotion;

/// Most pieces one step may cross; the rest of a huge step falls straight at U.
const MAX_PIECES_PER_STEP: u32 = 64;
/// Motion changes blend position increments and orientation over this share of a swing.
const BLEND_SWINGS: f32 = 0.35;

/// How the wind turns the object (eq. 15): θ = W N(t), leaning downwind. The paper's N(t) is
/// the fBm wind speed |u|; as an angle factor it must be bounded, so N = x / (1 + x) with
/// x = |u| / U_ref: linear in light wind, 1/2 at the reference speed, approaching the designer's
/// maximum W in a gale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WindTilt {
    /// W, the largest tilt, rad (|W| ≤ π).
    pub max_angle: f32,
    /// U_ref, m/s.
    pub reference_speed: f32,
}

impl WindTilt {
    /// The rotation that leans the object downwind.
    pub fn rotation(&self, wind: Vec3) -> Quat {
        let (x, z) = (wind.x, wind.z);
        let horizontal = (x * x + z * z).sqrt();
        let speed = wind.length();
        if !(horizontal > 1e-6 && speed.is_finite() && self.max_angle.is_finite()) {
            return Quat::IDENTITY;
        }
        let ratio = speed / self.reference_speed.max(1e-3);
        let half = 0.5 * self.max_angle.clamp(-PI, PI) * (ratio / (1.0 + ratio));
        // Axis Y × horizontal = (z, 0, −x) / |horizontal|.
        let (sin, cos) = sin_cos_quarter_turn(half);
        let k = sin / horizontal;
        Quat::from_xyzw(z * k, 0.0, -x * k, cos)
    }
}

/// sin and cos of |x| ≤ π/2 by their Taylor series to x¹⁰ (error < 4e-6): no range reduction
/// and no library call on the per-object hot path.
fn sin_cos_quarter_turn(x: f32) -> (f32, f32) {
    // Horner form with the factorials' reciprocals as constants (multiplications, no divisions).
    const S: [f32; 4] = [1.0 / 6.0, 1.0 / 120.0, 1.0 / 5040.0, 1.0 / 362_880.0];
    const C: [f32; 5] = [
        1.0 / 2.0,
        1.0 / 24.0,
        1.0 / 720.0,
        1.0 / 40_320.0,
        1.0 / 3_628_800.0,
    ];
    let x2 = x * x;
    let sin = x * (1.0 - x2 * (S[0] - x2 * (S[1] - x2 * (S[2] - x2 * S[3]))));
    let cos = 1.0 - x2 * (C[0] - x2 * (C[1] - x2 * (C[2] - x2 * (C[3] - x2 * C[4]))));
    (sin, cos)
}

/// The piece a motion change blends away from: its time and offset run on past its end.
#[derive(Clone, Copy, Debug)]
struct Blend {
    piece: Piece,
    time: f32,
    offset: Vec3,
    elapsed: f32,
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
    main: PrimitiveMotion,
    rng: FallRng,
    motion: PrimitiveMotion,
    yaw: Quat,
    glide: Glide,
    piece: Piece,
    piece_time: f32,
    /// `piece.sample(piece_time)`, kept so each step evaluates the piece once.
    piece_offset: Vec3,
    piece_tilt: Quat,
    /// The database cluster of the current planar motion's swings.
    cluster: u16,
    /// The piece before a motion change, while the change blends (boxed: rare, and a small
    /// path keeps ten thousand of them in cache).
    previous: Option<Box<Blend>>,
    still: Vec3,
    /// Control points p_{i−2}, p_{i−1}, p_i.
    points: [Vec3; 3],
    /// Orientation at p_{i−1} and p_i.
    orientations: [Quat; 2],
    ground: f32,
    landed: bool,
    time: f32,
    markov_steps: u32,
}

impl FallPath {
    /// A fall with main motion `main` released at `position` that lands at height `ground`.
    pub fn new(
        model: &FallModel,
        scales: FallScales,
        main: PrimitiveMotion,
        seed: u64,
        position: Vec3,
        ground: f32,
    ) -> Self {
        let db = model.database();
        let mut rng = FallRng::new(seed);
        let motion = model.bounded(main).start(&mut rng);
        let yaw = Quat::from_rotation_y(rng.uniform() * TAU);
        let glide = if rng.coin() {
            Glide::Left
        } else {
            Glide::Right
        };
        let mut path = Self {
            scales,
            main,
            rng,
            motion,
            yaw,
            glide,
            piece: Piece::curve(&scales, PrimitiveMotion::SteadyDescent, 0.0),
            piece_time: 0.0,
            piece_offset: Vec3::ZERO,
            piece_tilt: Quat::IDENTITY,
            cluster: 0,
            previous: None,
            still: Vec3::ZERO,
            points: [position; 3],
            orientations: [yaw; 2],
            ground,
            landed: false,
            time: 0.0,
            markov_steps: 0,
        };
        path.cluster = db.nearest_cluster(scales.swing_feature(motion)) as u16;
        path.piece = path.build_piece(db, None);
        path.piece_tilt = path.piece.tilt(db, 0.0);
        path.orientations = [path.yaw * path.piece_tilt; 2];
        path
    }

    /// Markov steps taken (one per finished piece).
    pub fn markov_steps(&self) -> u32 {
        self.markov_steps
    }

    /// Advances by `dt` seconds: p ← p + u dt + Δf (§4.2), with `wind` the velocity at the
    /// current position (zero in still fluid), and `tilt` the wind's turn of eq. 15.
    pub fn advance(
        &mut self,
        model: &FallModel,
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
        let delta = self.still_step(model, dt);
        self.time += dt;
        self.still += delta;
        let mut next = self.points[2] + wind * dt + delta;
        let landed = next.y <= self.ground;
        if landed {
            next.y = self.ground;
        }
        let orientation =
            (tilt.rotation(wind) * self.orientation_now(model.database())).normalize();
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
    fn still_step(&mut self, model: &FallModel, dt: f32) -> Vec3 {
        let db = model.database();
        // The usual step: inside one piece, no blend.
        if self.previous.is_none() && self.piece_time + dt < self.piece.duration() {
            self.piece_time += dt;
            let (end, tilt) = self.piece.sample(db, self.piece_time);
            let inc = end - self.piece_offset;
            self.piece_offset = end;
            self.piece_tilt = tilt;
            return self.yaw * inc;
        }
        let mut remaining = dt;
        let mut delta = Vec3::ZERO;
        let blend = BLEND_SWINGS * self.scales.swing_time();
        let mut crossed = 0;
        while remaining > 0.0 && crossed < MAX_PIECES_PER_STEP {
            let left = (self.piece.duration() - self.piece_time).max(0.0);
            let h = remaining.min(left);
            let (end, tilt) = self.piece.sample(db, self.piece_time + h);
            let mut inc = end - self.piece_offset;
            self.piece_offset = end;
            self.piece_tilt = tilt;
            if let Some(old) = self.previous.as_mut() {
                let w = smoothstep((old.elapsed + 0.5 * h) / blend);
                let old_end = old.piece.offset(db, old.time + h);
                inc = (old_end - old.offset).lerp(inc, w);
                old.offset = old_end;
                old.time += h;
                old.elapsed += h;
                if old.elapsed >= blend {
                    self.previous = None;
                }
            }
            delta += self.yaw * inc;
            self.piece_time += h;
            remaining -= h;
            if self.piece_time >= self.piece.duration() {
                self.next_piece(model);
                crossed += 1;
            }
        }
        if remaining > 0.0 {
            delta.y -= self.scales.descent_speed * remaining;
        }
        delta
    }

    fn next_piece(&mut self, model: &FallModel) {
        let db = model.database();
        let next = model.bounded(self.main).next(self.motion, &mut self.rng);
        self.markov_steps += 1;
        let old = self.piece;
        if next != self.motion {
            self.previous = Some(Box::new(Blend {
                piece: old,
                time: self.piece_time,
                offset: self.piece_offset,
                elapsed: 0.0,
            }));
        }
        if next != self.motion {
            self.cluster = db.nearest_cluster(self.scales.swing_feature(next)) as u16;
        }
        self.motion = next;
        self.piece = self.build_piece(db, Some(old));
        self.piece_time = 0.0;
        self.piece_offset = Vec3::ZERO;
        self.piece_tilt = self.piece.tilt(db, 0.0);
    }

    fn build_piece(&mut self, db: &TrajectoryDatabase, old: Option<Piece>) -> Piece {
        let theta0 = old.map_or(0.0, |p| p.end_angle(db));
        if self.motion.is_planar() {
            let (glide, r) = next_glide(self.motion, self.glide, &mut self.rng);
            self.glide = glide;
            return Piece::swing(
                db,
                usize::from(self.cluster),
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
        let tilt = self.piece_tilt;
        let tilt = match &self.previous {
            Some(old) => {
                let blend = BLEND_SWINGS * self.scales.swing_time();
                old.piece
                    .tilt(db, old.time)
                    .slerp(tilt, smoothstep(old.elapsed / blend))
            }
            None => tilt,
        };
        self.yaw * tilt
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
        // Consecutive orientations are a step apart: nlerp (glam's lerp takes the short way
        // and normalises) is slerp to well under a degree.
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
        self.main
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turn_series_is_accurate() {
        for i in 0..=1000 {
            let x = -PI / 2.0 + PI * i as f32 / 1000.0;
            let (s, c) = sin_cos_quarter_turn(x);
            assert!(
                (s - x.sin()).abs() < 4e-6 && (c - x.cos()).abs() < 4e-6,
                "{x}"
            );
        }
    }

    #[test]
    fn wind_tilt_leans_downwind_by_w_n() {
        let tilt = WindTilt {
            max_angle: 0.8,
            reference_speed: 4.0,
        };
        let q = tilt.rotation(Vec3::new(4.0, 0.0, 0.0));
        // Up leans toward +x by W/2 at the reference speed.
        let up = q * Vec3::Y;
        assert!((up.x.atan2(up.y) - 0.4).abs() < 1e-5, "{up:?}");
        assert!((q.length() - 1.0).abs() < 1e-5);
        assert_eq!(tilt.rotation(Vec3::ZERO), Quat::IDENTITY);
        assert_eq!(tilt.rotation(Vec3::NAN), Quat::IDENTITY);
    }
}
