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
use super::series::sin_cos_small;

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
        /// Added to the profile's progress as `ease` s (1 − s)²: the swing starts turning at
        /// the rate the last piece ended with (C¹ joins), ends as its profile does.
        ease: f32,
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
    /// The rate the plate turns at when the swing starts ([`Piece::end_rate`] of the last),
    /// rad/s.
    pub rate: f32,
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
        let duration = (swings * scales.swing_time()).max(MIN_PIECE);
        // The start slope (progress per unit of s) the last piece's rate asks for, against the
        // profile's own, as far as the plate stays between its start and end angles.
        let shape = if tumble {
            db.tumble_shape()
        } else {
            &db.segment(segment).angle_shape
        };
        let turn = end - theta;
        let wanted = choice.rate * duration / turn;
        let ease = if wanted.is_finite() && turn.abs() > 1e-3 {
            ease_toward(shape, wanted)
        } else {
            0.0
        };
        Self::Swing {
            segment,
            sign,
            scale: swings * unit,
            sideways,
            duration,
            tumble,
            theta0: theta,
            turn,
            start_half: Vec2::new(cos, sin),
            ease,
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
                ease,
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
                let u = s.clamp(0.0, 1.0);
                let progress =
                    shape[i] + (shape[i + 1] - shape[i]) * f + ease * u * (1.0 - u).powi(2);
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

    /// The rate the plate turns at when the piece ends, rad/s about the heading frame's z (a
    /// curve only leans: 0).
    pub fn end_rate(&self, db: &TrajectoryDatabase) -> f32 {
        let Self::Swing {
            segment,
            tumble,
            turn,
            duration,
            ..
        } = *self
        else {
            return 0.0;
        };
        let shape = if tumble {
            db.tumble_shape()
        } else {
            &db.segment(segment).angle_shape
        };
        let last = SEGMENT_SAMPLES - 1;
        turn * (shape[last] - shape[last - 1]) * last as f32 / duration
    }

    /// Plate angle at the end, about the heading frame's z (for a curve: its half-turns).
    pub fn end_angle(&self) -> f32 {
        match *self {
            Self::Swing { theta0, turn, .. } => theta0 + turn,
            Self::Curve { flip, .. } => flip,
        }
    }
}

/// The `ease` of [`Piece::Swing`] that starts `shape` (progress 0 → 1 over s ∈ [0, 1]) at slope
/// `wanted`, limited so that shape(s) + ease s (1 − s)² stays within [−¼, 1¼] at every sample:
/// the swing takes up the last piece's rate, turning past its start angle (a plate still turning
/// the other way, slowing before it reverses) or its end angle by at most a quarter of its turn.
fn ease_toward(shape: &[f32; SEGMENT_SAMPLES], wanted: f32) -> f32 {
    const OVERSHOOT: f32 = 0.25;
    let last = (SEGMENT_SAMPLES - 1) as f32;
    let (mut low, mut high) = (f32::NEG_INFINITY, f32::INFINITY);
    for (i, p) in shape.iter().enumerate().take(SEGMENT_SAMPLES - 1).skip(1) {
        let s = i as f32 / last;
        let bump = s * (1.0 - s) * (1.0 - s);
        low = low.max((-OVERSHOOT - p) / bump);
        high = high.min((1.0 + OVERSHOOT - p) / bump);
    }
    (wanted - (shape[1] - shape[0]) * last).clamp(low.min(0.0), high.max(0.0))
}

/// Shortest piece, s: keeps the piece loop finite for any input.
pub const MIN_PIECE: f32 = 1e-4;

/// The rotation about z by θ₀ + φ, from (cos θ₀/2, sin θ₀/2) and φ (a swing's turn times its
/// progress, which the ease lets run from −¼ to 1¼; beyond |φ| = 2π the series hands over to
/// the library).
fn rotation_z(start_half: Vec2, phi: f32) -> Quat {
    let (s, c) = sin_cos_small(0.5 * phi);
    let (c0, s0) = (start_half.x, start_half.y);
    Quat::from_xyzw(0.0, 0.0, s0 * c + c0 * s, c0 * c - s0 * s)
}

#[cfg(test)]
#[path = "piece_tests.rs"]
mod tests;
