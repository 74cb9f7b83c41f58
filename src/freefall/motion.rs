//! Primitive motions (§2.3): swings assembled by the trajectory search tree for fluttering,
//! chaotic and tumbling motion, and the unified trajectory function (eq. 6) for steady descent,
//! helix and spiral. Amplitudes from eq. 7–8.

use std::f32::consts::PI;

use bevy::math::{Quat, Vec2, Vec3};

use super::database::{SEGMENT_SAMPLES, TrajectoryDatabase};
use super::random::FallRng;
use super::regime::PrimitiveMotion;

/// Per-motion constants of eq. 6–8. `deviation` is B_i of eq. 7 (the deviation coefficient k
/// is [`FallScales::deviation`]); `rate` multiplies the swing rate Ω; `eccentricity` is ε_e and
/// `lobes` is k of eq. 6.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionShape {
    /// B_i: half the sideways excursion per swing (or the circle radius), in object lengths L.
    pub deviation: f32,
    /// Ω of the motion in units of the swing rate.
    pub rate: f32,
    /// ε_e of eq. 6.
    pub eccentricity: f32,
    /// k of eq. 6.
    pub lobes: f32,
}

/// L1..L6. Eq. 6 with ε_e → 0, k = 1 is the spiral; ε_e ≠ 0, k = 4 the helix (an eight-petal
/// rose from above); A_e → 0 steady descent. Values are ours (the paper gives none), chosen so
/// the paths look like Fig. 1 and Fig. 9.
pub const MOTION_SHAPES: [MotionShape; 6] = [
    MotionShape {
        deviation: 0.0,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.6,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.6,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 1.5,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.5,
        rate: 0.5,
        eccentricity: 0.3,
        lobes: 4.0,
    },
    MotionShape {
        deviation: 0.8,
        rate: 0.5,
        eccentricity: 0.0,
        lobes: 1.0,
    },
];

/// Range of the chaotic scale r (§2.3.2).
pub const CHAOTIC_SCALE: (f32, f32) = (0.1, 10.0);

/// The sizes of one fall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FallScales {
    /// U of eq. 3, m/s.
    pub descent_speed: f32,
    /// Ω, rad/s: U / a, eq. 8's Ω ∼ √(b/a) in units of √(g/a) (U/a = √((ρ_s/ρ_f − 1) b/a) √(g/a)).
    pub swing_rate: f32,
    /// L, m.
    pub length: f32,
    /// k of eq. 7 (1 by default).
    pub deviation: f32,
}

impl FallScales {
    /// A₀ of eq. 8 for `motion`. Eq. 7 read with the release height the text says it is linear
    /// in, D_i = k B_i h L / a, gives A₀ = D_i U / (h Ω) = k B_i L U / (a Ω) = k B_i L with
    /// Ω = U / a: the release height cancels.
    pub fn amplitude(&self, motion: PrimitiveMotion) -> f32 {
        self.deviation * MOTION_SHAPES[motion.index()].deviation * self.length
    }

    /// The feature vector a swing of `motion` should have, in database units (length U/Ω):
    /// (2 A₀ Ω / U, −π), the search key of §2.3.1.
    pub fn swing_feature(&self, motion: PrimitiveMotion) -> Vec2 {
        let unit = self.descent_speed / self.swing_rate;
        Vec2::new(2.0 * self.amplitude(motion) / unit.max(1e-12), -PI)
    }

    /// Time of one swing (and one Markov step), s.
    pub fn swing_time(&self) -> f32 {
        PI / self.swing_rate
    }
}

/// Which way a swing glides along the heading (the search tree's two children, Fig. 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Glide {
    /// gl.
    Left,
    /// gr.
    Right,
}

impl Glide {
    /// −1 or +1.
    pub fn sign(self) -> f32 {
        match self {
            Self::Left => -1.0,
            Self::Right => 1.0,
        }
    }

    fn flip(self) -> Self {
        match self {
            Self::Left => Self::Right,
            Self::Right => Self::Left,
        }
    }
}

/// One node of the trajectory search tree (§2.3.1): the child to take after `previous` and its
/// scale r. Fluttering alternates (gl, gr, gl, ...); tumbling keeps one side; chaotic motion
/// takes either side at random with r from a log-normal clamped to [1/10, 10], so it flutters
/// with changing amplitude and tumbles when it repeats a side.
pub fn next_glide(motion: PrimitiveMotion, previous: Glide, rng: &mut FallRng) -> (Glide, f32) {
    match motion {
        PrimitiveMotion::Tumbling => (previous, 1.0),
        PrimitiveMotion::Chaotic => {
            // σ = ln(10)/3: r = 10 is three standard deviations out.
            let r = (rng.normal() * std::f32::consts::LN_10 / 3.0).exp();
            let glide = if rng.coin() {
                previous
            } else {
                previous.flip()
            };
            (glide, r.clamp(CHAOTIC_SCALE.0, CHAOTIC_SCALE.1))
        }
        _ => (previous.flip(), 1.0),
    }
}

/// A stretch of still-fluid motion, evaluated relative to its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Piece {
    /// A database segment along the heading.
    Swing {
        /// Database index.
        segment: u32,
        /// +1 right, −1 left.
        sign: f32,
        /// Metres per database unit, horizontal and vertical.
        scale: Vec2,
        /// s.
        duration: f32,
        /// End over end (tumbling) rather than rocking (fluttering).
        tumble: bool,
        /// Plate angle at the start of a tumbling swing, rad.
        theta0: f32,
        /// (cos θ₀/2, sin θ₀/2).
        start_half: Vec2,
    },
    /// Eq. 6 from curve time `start`.
    Curve {
        /// A_e, m.
        amplitude: f32,
        /// ε_e.
        eccentricity: f32,
        /// k.
        lobes: f32,
        /// Ω, rad/s.
        rate: f32,
        /// U, m/s.
        descent: f32,
        /// Curve time at the piece's start, s.
        start: f32,
        /// s.
        duration: f32,
    },
}

impl Piece {
    /// A swing for `motion` (fluttering, chaotic or tumbling): a random member of database
    /// cluster `cluster` (the one nearest [`FallScales::swing_feature`], found once per motion
    /// by the caller), scaled so its feature vector is r × the wanted one.
    #[allow(clippy::too_many_arguments)]
    pub fn swing(
        db: &TrajectoryDatabase,
        cluster: usize,
        scales: &FallScales,
        motion: PrimitiveMotion,
        glide: Glide,
        r: f32,
        theta0: f32,
        rng: &mut FallRng,
    ) -> Self {
        let unit = scales.descent_speed / scales.swing_rate;
        let sideways = scales.swing_feature(motion).x;
        let segment = db.pick(cluster, rng);
        let seg_x = db.segment(segment).feature().x.max(1e-6);
        let (sin, cos) = (0.5 * theta0).sin_cos();
        Self::Swing {
            segment,
            sign: glide.sign(),
            scale: Vec2::new(r * sideways * unit / seg_x, r * unit),
            duration: (r * scales.swing_time()).max(MIN_PIECE),
            tumble: motion == PrimitiveMotion::Tumbling,
            theta0,
            start_half: Vec2::new(cos, sin),
        }
    }

    /// Eq. 6 for steady descent, helix or spiral.
    pub fn curve(scales: &FallScales, motion: PrimitiveMotion, start: f32) -> Self {
        let shape = MOTION_SHAPES[motion.index()];
        Self::Curve {
            amplitude: scales.amplitude(motion),
            eccentricity: shape.eccentricity,
            lobes: shape.lobes,
            rate: shape.rate * scales.swing_rate,
            descent: scales.descent_speed,
            start,
            duration: scales.swing_time().max(MIN_PIECE),
        }
    }

    /// Length, s.
    pub fn duration(&self) -> f32 {
        match *self {
            Self::Swing { duration, .. } | Self::Curve { duration, .. } => duration,
        }
    }

    /// [`Piece::offset`] and [`Piece::tilt`] at once (one database lookup for swings).
    pub fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        let Self::Swing {
            segment,
            sign,
            scale,
            duration,
            tumble,
            start_half,
            ..
        } = *self
        else {
            return (self.offset(db, t), self.tilt(db, t));
        };
        let seg = db.segment(segment);
        let last = SEGMENT_SAMPLES - 1;
        let s = t / duration;
        let x = s.clamp(0.0, 1.0) * last as f32;
        // x ∈ [0, last]: the i32 conversion is the cheap one.
        let i = (x as i32).clamp(0, last as i32 - 1) as usize;
        let f = x - i as f32;
        let mut p = seg.points[i].lerp(seg.points[i + 1], f);
        if s > 1.0 {
            p += (seg.points[last] - seg.points[last - 1]) * (last as f32 * (s - 1.0));
        }
        let half = if tumble {
            &seg.tumble_half
        } else {
            &seg.flutter_half
        };
        let local = half[i].lerp(half[i + 1], f);
        (
            Vec3::new(sign * p.x * scale.x, p.y * scale.y, 0.0),
            swing_rotation(local, sign, tumble, start_half),
        )
    }

    /// Displacement since the start at piece time `t` (beyond the end a swing continues in a
    /// straight line at its final velocity, a curve continues eq. 6), in the frame where x is
    /// the heading, y up and z the heading × up.
    pub fn offset(&self, db: &TrajectoryDatabase, t: f32) -> Vec3 {
        match *self {
            Self::Swing {
                segment,
                sign,
                scale,
                duration,
                ..
            } => {
                let points = &db.segment(segment).points;
                let (p, velocity_tail) = sample_points(points, t / duration);
                let p = p + velocity_tail;
                Vec3::new(sign * p.x * scale.x, p.y * scale.y, 0.0)
            }
            Self::Curve { start, .. } => self.curve_at(start + t) - self.curve_at(start),
        }
    }

    fn curve_at(&self, time: f32) -> Vec3 {
        let Self::Curve {
            amplitude,
            eccentricity,
            lobes,
            rate,
            descent,
            ..
        } = *self
        else {
            return Vec3::ZERO;
        };
        let phase = rate * time;
        let radius = amplitude * (1.0 + eccentricity * (lobes * phase).sin());
        let (s, c) = phase.sin_cos();
        Vec3::new(radius * c, -descent * time, radius * s)
    }

    /// The plate's tilt at piece time `t` as a rotation in the same frame (applied after the
    /// object's yaw): about z by the ODE angle for swings; for curves, leaning into the
    /// horizontal velocity by half its glide angle.
    pub fn tilt(&self, db: &TrajectoryDatabase, t: f32) -> Quat {
        match *self {
            Self::Swing {
                segment,
                sign,
                duration,
                tumble,
                start_half,
                ..
            } => {
                let seg = db.segment(segment);
                let half = if tumble {
                    &seg.tumble_half
                } else {
                    &seg.flutter_half
                };
                let local = sample_half(half, (t / duration).clamp(0.0, 1.0));
                swing_rotation(local, sign, tumble, start_half)
            }
            Self::Curve { start, descent, .. } => {
                let h = 1e-3;
                let v = (self.curve_at(start + t + h) - self.curve_at(start + t)) / h;
                let horizontal = Vec2::new(v.x, v.z);
                let speed = horizontal.length();
                if speed > 1e-6 && speed.is_finite() {
                    let axis = Vec3::new(-horizontal.y, 0.0, horizontal.x) / speed;
                    Quat::from_axis_angle(axis, 0.5 * speed.atan2(descent.max(1e-6)))
                } else {
                    Quat::IDENTITY
                }
            }
        }
    }

    /// Plate angle at the end (tumbling swings carry it on).
    pub fn end_angle(&self, db: &TrajectoryDatabase) -> f32 {
        match *self {
            Self::Swing {
                segment,
                sign,
                tumble: true,
                theta0,
                ..
            } => theta0 + sign * db.segment(segment).tumble[SEGMENT_SAMPLES - 1],
            Self::Swing { segment, sign, .. } => {
                sign * db.segment(segment).flutter[SEGMENT_SAMPLES - 1]
            }
            Self::Curve { .. } => 0.0,
        }
    }
}

/// Shortest piece, s: keeps the piece loop finite for any input.
pub const MIN_PIECE: f32 = 1e-4;

/// Linear interpolation of the segment at fraction `s`; past 1 the straight continuation.
fn sample_points(points: &[Vec2; SEGMENT_SAMPLES], s: f32) -> (Vec2, Vec2) {
    let last = SEGMENT_SAMPLES - 1;
    let x = s.max(0.0) * last as f32;
    if x >= last as f32 {
        let end_velocity = (points[last] - points[last - 1]) * last as f32;
        return (points[last], end_velocity * (s - 1.0));
    }
    let i = x as usize;
    let f = x - i as f32;
    (points[i].lerp(points[i + 1], f), Vec2::ZERO)
}

/// Lerp of the unit complex numbers (cos θ/2, sin θ/2) at fraction `s` ∈ [0, 1]. Neighbours
/// differ by at most π/64 in θ/2, so the result's norm is within 3e-4 of 1; the path
/// normalises the final orientation once.
fn sample_half(half: &[Vec2; SEGMENT_SAMPLES], s: f32) -> Vec2 {
    let x = s * (SEGMENT_SAMPLES - 1) as f32;
    let i = (x as usize).min(SEGMENT_SAMPLES - 2);
    half[i].lerp(half[i + 1], x - i as f32)
}

/// The rotation about z of a swing: the database's angle (mirrored for a left glide), after
/// the start angle for tumbling. Unit complex numbers (cos θ/2, sin θ/2) multiply as rotations.
fn swing_rotation(local: Vec2, sign: f32, tumble: bool, start_half: Vec2) -> Quat {
    let local = Vec2::new(local.x, sign * local.y);
    let rotation = if tumble {
        let (c0, s0) = (start_half.x, start_half.y);
        Vec2::new(c0 * local.x - s0 * local.y, s0 * local.x + c0 * local.y)
    } else {
        local
    };
    Quat::from_xyzw(0.0, 0.0, rotation.y, rotation.x)
}
