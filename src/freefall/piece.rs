//! Pieces of still-fluid motion (§2.3): a swing along a database segment (the search tree's
//! child) or a stretch of the unified trajectory function (eq. 6), each sampled by time relative
//! to its start, with the plate's tilt.
//!
//! **Plate angle.** Every swing turns the plate from the angle it has when the swing starts to
//! an end angle, along the database's eq. 4 profile, so the orientation is continuous across
//! swings, whichever child the search tree picks. A plate is symmetric under a half-turn about
//! its long axis, so angles are read modulo π: a swing that reverses the glide (fluttering) ends
//! at ±Θ about the current half-turn; a swing that keeps the side (tumbling, and a chaotic swing
//! that repeats its side) turns on by a half-turn, as a tumbling card does.

use std::f32::consts::PI;

use bevy::math::{Quat, Vec2, Vec3};

use super::database::{SEGMENT_SAMPLES, TrajectoryDatabase};
use super::motion::{CHAOTIC_MIN_TIME, CHAOTIC_SCALE, FallScales, Glide, MOTION_SHAPES};
use super::regime::PrimitiveMotion;

/// A stretch of still-fluid motion, evaluated relative to its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Piece {
    /// A database segment along the heading.
    Swing {
        /// Database index.
        segment: u32,
        /// +1 right, −1 left.
        sign: f32,
        /// Metres per database unit (U/Ω times the chaotic scale r).
        scale: f32,
        /// Sideways factor (1; less for a tumble in strong wind or a small chaotic swing).
        sideways: f32,
        /// s.
        duration: f32,
        /// The plate turns along the tumbling profile (a half-turn) rather than the swing's.
        tumble: bool,
        /// Plate angle at the start, rad.
        theta0: f32,
        /// Angle turned over the swing, rad.
        turn: f32,
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
        /// The half-turns the plate carries from earlier tumbles (a multiple of π), rad.
        flip: f32,
    },
}

/// What a swing needs besides its database segment: the search tree's choice and the plate's
/// state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SwingChoice {
    /// The child of the search tree: which way it glides.
    pub glide: Glide,
    /// Whether the glide keeps the previous swing's side (a half-turn) rather than reversing.
    pub same_side: bool,
    /// The chaotic scale r (1 otherwise): the swing lasts r swing times, but at least
    /// [`CHAOTIC_MIN_TIME`] (a plate cannot turn through its range in a blink) and at least one
    /// for a half-turn.
    pub r: f32,
    /// The plate angle when the swing starts, rad.
    pub theta: f32,
    /// [`FallScales::tumble_survival`] in the current wind (1 in still fluid).
    pub survival: f32,
}

impl SwingChoice {
    /// How many swing times the swing lasts.
    pub fn swings(&self, half_turn: bool) -> f32 {
        let r = if self.r.is_finite() { self.r } else { 1.0 };
        let least = if half_turn { 1.0 } else { CHAOTIC_MIN_TIME };
        r.clamp(least, CHAOTIC_SCALE.1)
    }
}

impl Piece {
    /// A swing along database segment `segment` (the search tree's pick), with the segment's
    /// own glide, modulation and angle range, scaled in size and duration by the time the swing
    /// lasts ([`SwingChoice::swings`]). The plate turns from its current angle to the segment's ±Θ about
    /// its current half-turn, or by a half-turn when the glide keeps its side.
    pub fn swing(
        db: &TrajectoryDatabase,
        scales: &FallScales,
        segment: u32,
        choice: SwingChoice,
    ) -> Self {
        let unit = scales.descent_speed / scales.swing_rate;
        let range = db.segment(segment).angle_range;
        let sign = choice.glide.sign();
        let theta = if choice.theta.is_finite() {
            choice.theta
        } else {
            0.0
        };
        // The half-turn the plate is in, and where the swing ends.
        let base = PI * (theta / PI).round();
        let (tumble, end) = if choice.same_side {
            let survival = choice.survival.clamp(0.0, 1.0);
            let full = base + sign * (PI + range) - theta;
            (true, theta + survival * full)
        } else {
            // A quick swing turns the plate no faster than the widest swing of the database
            // does over a whole swing time: the angle follows the swing's size.
            let most = 2.0 * db.widest_angle_range() * choice.swings(false);
            (
                false,
                theta + (base + sign * range - theta).clamp(-most, most),
            )
        };
        let (sin, cos) = (0.5 * theta).sin_cos();
        let sideways = if tumble { choice.survival } else { 1.0 };
        let swings = choice.swings(tumble);
        Self::Swing {
            segment,
            sign,
            scale: swings * unit,
            sideways,
            duration: (swings * scales.swing_time()).max(MIN_PIECE),
            tumble,
            theta0: theta,
            turn: end - theta,
            start_half: Vec2::new(cos, sin),
        }
    }

    /// Eq. 6 for steady descent, helix or spiral, with radius `amplitude` (A₀, m): for the helix
    /// A_e = A₀ / (1 + ε_e), so its outer petals reach A₀.
    pub fn curve(
        scales: &FallScales,
        motion: PrimitiveMotion,
        amplitude: f32,
        start: f32,
        flip: f32,
    ) -> Self {
        let shape = MOTION_SHAPES[motion.index()];
        Self::Curve {
            amplitude: amplitude / (1.0 + shape.eccentricity),
            eccentricity: shape.eccentricity,
            lobes: shape.lobes,
            rate: shape.rate * scales.swing_rate,
            descent: scales.descent_speed,
            start,
            duration: scales.swing_time().max(MIN_PIECE),
            flip,
        }
    }

    /// Length, s.
    pub fn duration(&self) -> f32 {
        match *self {
            Self::Swing { duration, .. } | Self::Curve { duration, .. } => duration,
        }
    }

    /// Displacement since the start and the plate's tilt at piece time `t`, in the frame where
    /// x is the heading, y up and z the heading × up. Beyond its end a swing continues in a
    /// straight line at its final velocity and keeps its final angle; a curve continues eq. 6.
    pub fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        match *self {
            Self::Swing {
                segment,
                sign,
                scale,
                sideways,
                duration,
                tumble,
                turn,
                start_half,
                ..
            } => {
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
                let shape = if tumble {
                    db.tumble_shape()
                } else {
                    &seg.angle_shape
                };
                let progress = shape[i] + (shape[i + 1] - shape[i]) * f;
                let offset = Vec3::new(sign * p.x * scale * sideways, p.y * scale, 0.0);
                (offset, rotation_z(start_half, turn * progress))
            }
            Self::Curve { start, .. } => {
                let (position, velocity) = self.curve_motion(start + t);
                (
                    position - self.curve_motion(start).0,
                    self.curve_tilt(velocity),
                )
            }
        }
    }

    /// [`Piece::sample`]'s displacement alone.
    pub fn offset(&self, db: &TrajectoryDatabase, t: f32) -> Vec3 {
        self.sample(db, t).0
    }

    /// [`Piece::sample`]'s tilt alone.
    pub fn tilt(&self, db: &TrajectoryDatabase, t: f32) -> Quat {
        self.sample(db, t).1
    }

    /// Eq. 6 at curve time `time` and its time derivative, from one `sin_cos` of the phase and
    /// one of the lobes' phase: r = A(1 + ε sin kφ), φ = Ω t, p = (r cos φ, −U t, r sin φ), so
    /// ṗ = (ṙ cos φ − r Ω sin φ, −U, ṙ sin φ + r Ω cos φ) with ṙ = A ε k Ω cos kφ. (A finite
    /// difference in f32 loses its digits as curve time grows: at 100 s a step of 1 ms is
    /// 1 % of the time's last bit.)
    fn curve_motion(&self, time: f32) -> (Vec3, Vec3) {
        let Self::Curve {
            amplitude,
            eccentricity,
            lobes,
            rate,
            descent,
            ..
        } = *self
        else {
            return (Vec3::ZERO, Vec3::ZERO);
        };
        let phase = rate * time;
        let (sl, cl) = (lobes * phase).sin_cos();
        let radius = amplitude * (1.0 + eccentricity * sl);
        let d_radius = amplitude * eccentricity * lobes * rate * cl;
        let (s, c) = phase.sin_cos();
        (
            Vec3::new(radius * c, -descent * time, radius * s),
            Vec3::new(
                d_radius * c - radius * rate * s,
                -descent,
                d_radius * s + radius * rate * c,
            ),
        )
    }

    /// A curve's plate leans into its horizontal velocity `velocity` by half its glide angle
    /// (after the half-turns it carries).
    fn curve_tilt(&self, velocity: Vec3) -> Quat {
        let Self::Curve { descent, flip, .. } = *self else {
            return Quat::IDENTITY;
        };
        let horizontal = Vec2::new(velocity.x, velocity.z);
        let speed = horizontal.length();
        let base = Quat::from_rotation_z(flip);
        if speed > 1e-6 && speed.is_finite() {
            let axis = Vec3::new(-horizontal.y, 0.0, horizontal.x) / speed;
            Quat::from_axis_angle(axis, 0.5 * speed.atan2(descent.max(1e-6))) * base
        } else {
            base
        }
    }

    /// Plate angle at the end, about the heading frame's z (for a curve: its half-turns).
    pub fn end_angle(&self) -> f32 {
        match *self {
            Self::Swing { theta0, turn, .. } => theta0 + turn,
            Self::Curve { flip, .. } => flip,
        }
    }
}

/// Shortest piece, s: keeps the piece loop finite for any input.
pub const MIN_PIECE: f32 = 1e-4;

/// The rotation about z by θ₀ + φ, from (cos θ₀/2, sin θ₀/2) and φ (|φ| ≤ 2π).
fn rotation_z(start_half: Vec2, phi: f32) -> Quat {
    let (s, c) = sin_cos_small(0.5 * phi);
    let (c0, s0) = (start_half.x, start_half.y);
    Quat::from_xyzw(0.0, 0.0, s0 * c + c0 * s, c0 * c - s0 * s)
}

/// sin and cos of |x| ≤ π by their Taylor series to x¹⁴ (error < 3e-5 at π, < 1e-6 below 2):
/// no range reduction and no library call on the per-object hot path. Larger |x| falls back to
/// the library.
pub(crate) fn sin_cos_small(x: f32) -> (f32, f32) {
    if x.is_nan() || x.abs() > PI {
        return x.sin_cos();
    }
    // Horner form with the factorials' reciprocals as constants (multiplications only).
    const S: [f32; 6] = [
        1.0 / 6.0,
        1.0 / 120.0,
        1.0 / 5040.0,
        1.0 / 362_880.0,
        1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
    ];
    const C: [f32; 7] = [
        1.0 / 2.0,
        1.0 / 24.0,
        1.0 / 720.0,
        1.0 / 40_320.0,
        1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        1.0 / 87_178_291_200.0,
    ];
    let x2 = x * x;
    let sin =
        x * (1.0 - x2 * (S[0] - x2 * (S[1] - x2 * (S[2] - x2 * (S[3] - x2 * (S[4] - x2 * S[5]))))));
    let cos = 1.0
        - x2 * (C[0]
            - x2 * (C[1] - x2 * (C[2] - x2 * (C[3] - x2 * (C[4] - x2 * (C[5] - x2 * C[6]))))));
    (sin, cos)
}

#[cfg(test)]
mod tests {
    use std::f32::consts::PI;

    use bevy::math::Vec2;

    use super::*;
    use crate::freefall::database::TrajectoryDatabase;
    use crate::freefall::motion::Glide;
    use crate::freefall::object::FallingObject;
    use crate::freefall::random::FallRng;
    use crate::freefall::regime::PrimitiveMotion;

    #[test]
    fn two_picks_of_the_search_tree_give_different_swings() {
        let db = TrajectoryDatabase::default();
        let object = FallingObject::default();
        let scales = object.scales(&object.regime().unwrap());
        let mut rng = FallRng::new(1);
        let choice = SwingChoice {
            glide: Glide::Right,
            same_side: false,
            r: 1.0,
            theta: 0.0,
            survival: 1.0,
        };
        // What a swing shows: its sideways glide, the plate's turn, and how unevenly it drops.
        let measure = |segment: u32| {
            let piece = Piece::swing(&db, &scales, segment, choice);
            let d = piece.duration();
            let end = piece.offset(&db, d);
            let turn = piece.tilt(&db, 0.0).angle_between(piece.tilt(&db, d));
            let drops: Vec<f32> = (0..8)
                .map(|i| {
                    let (a, b) = (i as f32 * d / 8.0, (i + 1) as f32 * d / 8.0);
                    piece.offset(&db, a).y - piece.offset(&db, b).y
                })
                .collect();
            let unevenness = drops.iter().fold(0.0f32, |m, x| m.max(*x))
                / drops.iter().fold(f32::INFINITY, |m, x| m.min(*x));
            (end.x, turn, unevenness)
        };
        // Narrow and wide keys find different clusters: glides differ severalfold.
        let a0 = scales.amplitude(PrimitiveMotion::Fluttering);
        let narrow = db.find(&scales.swing_key(0.4 * a0, 1.0), &mut rng);
        let wide = db.find(&scales.swing_key(10.0 * a0, 1.0), &mut rng);
        let (a, b) = (measure(narrow), measure(wide));
        assert!(b.0 > 4.0 * a.0, "glides {} and {}", a.0, b.0);
        // Within one cluster, members differ in what P¹ − P⁰ does not show: the plate's turn or
        // the descent's modulation.
        let cluster = db.nearest_cluster(&scales.swing_key(2.0 * a0, 1.0));
        let members: Vec<_> = db.members()[cluster].iter().map(|&s| measure(s)).collect();
        let spread = |f: fn(&(f32, f32, f32)) -> f32| {
            let lo = members.iter().map(f).fold(f32::INFINITY, f32::min);
            let hi = members.iter().map(f).fold(0.0f32, f32::max);
            hi / lo
        };
        assert!(
            spread(|m| m.1) > 1.3 || spread(|m| m.2) > 1.3,
            "turns ×{} unevenness ×{}",
            spread(|m| m.1),
            spread(|m| m.2)
        );
    }

    #[test]
    fn curve_velocity_is_the_derivative_of_eq_6() {
        let piece = |eccentricity| Piece::Curve {
            amplitude: 0.05,
            eccentricity,
            lobes: 3.0,
            rate: 7.0,
            descent: 0.4,
            start: 0.0,
            duration: 1.0,
            flip: 0.0,
        };
        let lobed = piece(0.3);
        for tau in [0.1f32, 0.37, 1.2] {
            let h = 1e-3;
            let (ahead, behind) = (lobed.curve_motion(tau + h).0, lobed.curve_motion(tau - h).0);
            let difference = (ahead - behind) / (2.0 * h);
            let velocity = lobed.curve_motion(tau).1;
            assert!(
                (difference - velocity).length() < 2e-3 * velocity.length(),
                "{tau}: {difference} vs {velocity}"
            );
        }
        // A circle (ε = 0) is swept at A Ω whenever it is, long into a fall too.
        let circle = piece(0.0);
        for tau in [0.2f32, 50.0, 500.0] {
            let v = circle.curve_motion(tau).1;
            let speed = Vec2::new(v.x, v.z).length();
            assert!((speed - 0.05 * 7.0).abs() < 1e-5, "{tau}: {speed}");
            assert_eq!(v.y, -0.4);
        }
    }

    #[test]
    fn small_angle_series_is_accurate() {
        for i in 0..=2000 {
            let x = -PI + std::f32::consts::TAU * i as f32 / 2000.0;
            let (s, c) = sin_cos_small(x);
            assert!(
                (s - x.sin()).abs() < 3e-5 && (c - x.cos()).abs() < 3e-5,
                "{x}"
            );
        }
    }
}
