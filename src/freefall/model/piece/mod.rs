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
use crate::portable::geometry::Q;
use crate::portable::transcendental::sin_cos;

pub(crate) mod sample;

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
        /// Eq. 6 at `start` (what a sample's displacement is counted from).
        start_position: Vec3,
        /// The rotation about z by `flip`.
        flip_rotation: Quat,
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
        // The start angle less whole turns of the half angle (4π: the same quaternion), so a
        // tumbling plate's angle stays a bounded argument however many half-turns it made.
        let theta = if choice.theta.is_finite() {
            let turns = 2.0 * std::f32::consts::TAU;
            choice.theta - turns * crate::portable::transcendental::round(choice.theta / turns)
        } else {
            0.0
        };
        // The half-turn the plate is in, and where the swing ends.
        let base = PI * crate::portable::transcendental::round(theta / PI);
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
        let (sin, cos) = crate::portable::transcendental::sin_cos_bounded(0.5 * theta);
        let sideways = if tumble { choice.survival } else { 1.0 };
        let swings = choice.swings(tumble);
        let duration = (swings * scales.swing_time()).max(MIN_PIECE);
        // The start slope (progress per unit of s) the last piece's rate asks for, against the
        // profile's own, as far as the plate stays within a quarter turn past its start and end
        // angles ([`EaseBounds`](super::database::EaseBounds)).
        let turn = end - theta;
        let wanted = choice.rate * duration / turn;
        let ease = if wanted.is_finite() && turn.abs() > 1e-3 {
            db.ease_bounds(segment, tumble).toward(wanted)
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
        let rate = shape.rate * scales.swing_rate;
        // Eq. 6 repeats every turn (k is whole): the curve time is kept within one, so its
        // phase stays a bounded argument however long the fall.
        let period = std::f32::consts::TAU / rate;
        let start = if start.is_finite() && period.is_finite() && period > 0.0 {
            let turns = libm::floorf(start / period);
            (start - turns * period).clamp(0.0, period)
        } else {
            0.0
        };
        let amplitude = amplitude / (1.0 + shape.eccentricity);
        let mut curve = Self::Curve {
            amplitude,
            eccentricity: shape.eccentricity,
            lobes: shape.lobes,
            rate,
            descent: scales.descent_speed,
            start,
            duration: scales.swing_time().max(MIN_PIECE),
            flip,
            start_position: Vec3::ZERO,
            flip_rotation: Quat::IDENTITY,
        };
        let mut words = [0.0; sample::WORDS];
        {
            use sample::curve_word::*;
            words[AMPLITUDE] = amplitude;
            words[AMPLITUDE_ECCENTRICITY] = amplitude * shape.eccentricity;
            words[LOBES] = shape.lobes;
            words[RATE] = rate;
            words[DESCENT] = scales.descent_speed;
        }
        let at_start = sample::curve_motion::<f32>(&words, start).0.vec3();
        let (sin, cos) = sin_cos(0.5 * flip);
        let turned = Quat::from_xyzw(0.0, 0.0, sin, cos);
        if let Self::Curve {
            start_position,
            flip_rotation,
            ..
        } = &mut curve
        {
            (*start_position, *flip_rotation) = (at_start, turned);
        }
        curve
    }

    /// Length, s.
    pub fn duration(&self) -> f32 {
        match *self {
            Self::Swing { duration, .. } | Self::Curve { duration, .. } => duration,
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

    /// [`Piece::tilt`], except that past a swing's end the plate keeps turning at the rate it
    /// ended with ([`Piece::end_rate`]), the rate falling linearly to zero over τ: what the
    /// plate shows of a swing it leaves for another motion while the change blends (a card that
    /// tumbles into a spiral does not stop dead). τ is `fade` or shorter, so that the plate turns
    /// on by at most [`COAST_ANGLE`]; polynomial, so the same bits everywhere.
    pub fn coasting_tilt(&self, db: &TrajectoryDatabase, t: f32, fade: f32) -> Quat {
        let tilt = self.tilt(db, t);
        let past = t - self.duration();
        let rate = self.end_rate(db);
        if !(past > 0.0 && rate.is_finite() && rate != 0.0 && fade > 0.0) {
            return tilt;
        }
        let tau = fade.min(2.0 * COAST_ANGLE / rate.abs());
        let x = past.min(tau);
        let extra = rate * (x - 0.5 * x * x / tau);
        let (sin, cos) = sin_cos(0.5 * extra);
        // Both turn about the heading frame's z: the order does not matter.
        Q::of(tilt)
            .mul(Q::new(0.0, 0.0, sin, cos))
            .normalize()
            .quat()
    }

    /// Whether this is eq. 6's curve in `motion`'s shape (its eccentricity and lobes, as
    /// [`Piece::curve`] gives them), whatever its radius, phase and flip.
    pub fn is_curve_of(&self, motion: PrimitiveMotion) -> bool {
        let shape = MOTION_SHAPES[motion.index()];
        matches!(*self, Self::Curve { eccentricity, lobes, .. }
            if eccentricity == shape.eccentricity && lobes == shape.lobes)
    }

    /// Plate angle at the end, about the heading frame's z (for a curve: its half-turns).
    pub fn end_angle(&self) -> f32 {
        match *self {
            Self::Swing { theta0, turn, .. } => theta0 + turn,
            Self::Curve { flip, .. } => flip,
        }
    }
}

/// The most a plate turns on past the end of a swing it leaves for another motion, rad
/// ([`Piece::coasting_tilt`]): a bound that keeps what the blend starts from near what it heads
/// for (its slerp takes the shorter way round, which changes side past a half turn apart).
/// Fast swings stop the sooner: τ = 2 · this / |rate|.
pub const COAST_ANGLE: f32 = std::f32::consts::FRAC_PI_4;

/// Shortest piece, s: keeps the piece loop finite for any input.
pub const MIN_PIECE: f32 = 1e-4;

#[cfg(test)]
mod tests;
