//! Sampling a piece at a piece time, written once for one piece or for several in SIMD lanes
//! ([`Lane`]): a database swing's displacement along its segment and the plate's turn along its
//! angle profile, or eq. 6's curve and the plate's lean into its velocity. Both read a piece in
//! its compiled form, [`PieceWords`]: the numbers a step needs, fixed while the piece lasts,
//! written once when it begins (a reciprocal for the duration, products taken once).

use bevy::math::{Quat, Vec3};

use super::Piece;
use crate::freefall::model::database::{SEGMENT_SAMPLES, TrajectoryDatabase};
use crate::portable::geometry::{Q, V3};
use crate::portable::lane::{Lane, MAX_WIDTH, each};
use crate::portable::transcendental::{atan2, clamp, sin_cos_bounded};

/// How many numbers a compiled piece holds (see [`PieceWords`]).
pub(crate) const WORDS: usize = 11;

/// A swing's words: sign × scale × sideways, scale (m per database unit), the angle turned,
/// (cos θ₀/2, sin θ₀/2), the ease.
pub(crate) mod swing_word {
    pub const X_SCALE: usize = 0;
    pub const Y_SCALE: usize = 1;
    pub const TURN: usize = 2;
    pub const HALF_COS: usize = 3;
    pub const HALF_SIN: usize = 4;
    pub const EASE: usize = 5;
}

/// A curve's words: A_e, A_e ε_e, k, Ω, U, the curve time at the start (one turn at most), eq. 6
/// at that time (x, y, z), the plate's half-turns as a rotation about z (z, w).
pub(crate) mod curve_word {
    pub const AMPLITUDE: usize = 0;
    pub const AMPLITUDE_ECCENTRICITY: usize = 1;
    pub const LOBES: usize = 2;
    pub const RATE: usize = 3;
    pub const DESCENT: usize = 4;
    pub const START: usize = 5;
    pub const START_X: usize = 6;
    pub const START_Y: usize = 7;
    pub const START_Z: usize = 8;
    pub const FLIP_Z: usize = 9;
    pub const FLIP_W: usize = 10;
}

/// A piece compiled for the step: what stays fixed while it lasts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PieceWords {
    /// The swing's or the curve's numbers ([`swing_word`], [`curve_word`]).
    pub words: [f32; WORDS],
    /// T and 1/T, s and 1/s.
    pub duration: f32,
    pub inv_duration: f32,
    /// A swing's first database row ([`TrajectoryDatabase::row_base`]).
    pub row: u32,
    /// An eq. 6 curve (else a swing).
    pub curve: bool,
    /// A swing that turns along the tumbling profile.
    pub tumble: bool,
}

impl Piece {
    /// The piece compiled for the step.
    pub(crate) fn words(&self, db: &TrajectoryDatabase) -> PieceWords {
        let duration = self.duration();
        let mut words = [0.0; WORDS];
        let (row, curve, tumble) = match *self {
            Piece::Swing {
                segment,
                sign,
                scale,
                sideways,
                tumble,
                turn,
                start_half,
                ease,
                ..
            } => {
                use swing_word::*;
                words[X_SCALE] = sign * scale * sideways;
                words[Y_SCALE] = scale;
                words[TURN] = turn;
                words[HALF_COS] = start_half.x;
                words[HALF_SIN] = start_half.y;
                words[EASE] = ease;
                (db.row_base(segment), false, tumble)
            }
            Piece::Curve {
                amplitude,
                eccentricity,
                lobes,
                rate,
                descent,
                start,
                start_position,
                flip_rotation,
                ..
            } => {
                use curve_word::*;
                words[AMPLITUDE] = amplitude;
                words[AMPLITUDE_ECCENTRICITY] = amplitude * eccentricity;
                words[LOBES] = lobes;
                words[RATE] = rate;
                words[DESCENT] = descent;
                words[START] = start;
                words[START_X] = start_position.x;
                words[START_Y] = start_position.y;
                words[START_Z] = start_position.z;
                words[FLIP_Z] = flip_rotation.z;
                words[FLIP_W] = flip_rotation.w;
                (0, true, false)
            }
        };
        PieceWords {
            words,
            duration,
            inv_duration: 1.0 / duration,
            row,
            curve,
            tumble,
        }
    }
}

impl PieceWords {
    /// Displacement since the start and the plate's tilt at piece time `t` (see
    /// [`Piece::sample`]), one lane of [`sample`].
    pub(crate) fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        let (offset, tilt) = sample::<f32>(
            &self.words,
            self.inv_duration,
            [self.row; MAX_WIDTH],
            self.tumble,
            self.curve,
            db,
            t,
        );
        (offset.vec3(), tilt.quat())
    }
}

/// The rotation about z by θ₀ + φ from (cos θ₀/2, sin θ₀/2) and φ (|φ| bounded: a turn).
#[inline(always)]
pub(crate) fn rotation_z<L: Lane>(start_half: (L, L), phi: L) -> Q<L> {
    let (s, c) = sin_cos_bounded(L::splat(0.5) * phi);
    let (c0, s0) = start_half;
    let zero = L::splat(0.0);
    Q::new(zero, zero, s0 * c + c0 * s, c0 * c - s0 * s)
}

/// Pieces of either kind at piece time `t`, lane by lane (`curve` says which): the swing's
/// sample where a lane is a swing, the curve's where it is a curve; each kind is computed only
/// when a lane has it.
#[inline(always)]
pub(crate) fn sample<L: Lane>(
    words: &[L; WORDS],
    inv_duration: L,
    rows: [u32; MAX_WIDTH],
    tumble: L::Mask,
    curve: L::Mask,
    db: &TrajectoryDatabase,
    t: L,
) -> (V3<L>, Q<L>) {
    let any_curve = L::any(curve);
    let any_swing = L::any(L::not(curve));
    match (any_swing, any_curve) {
        (true, false) => swing_sample(words, inv_duration, rows, tumble, db, t),
        (false, true) => curve_sample(words, t),
        _ => {
            let (a, p) = swing_sample(words, inv_duration, rows, tumble, db, t);
            let (b, q) = curve_sample(words, t);
            (V3::select(curve, b, a), Q::select(curve, q, p))
        }
    }
}

/// A swing at piece time `t`: its displacement and the plate's tilt. The segment's samples are
/// interpolated linearly; beyond its end a swing goes on at its last velocity (the last pair of
/// samples extrapolated) and keeps its final angle.
#[inline(always)]
pub(crate) fn swing_sample<L: Lane>(
    words: &[L; WORDS],
    inv_duration: L,
    rows: [u32; MAX_WIDTH],
    tumble: L::Mask,
    db: &TrajectoryDatabase,
    t: L,
) -> (V3<L>, Q<L>) {
    use swing_word::*;
    let last = (SEGMENT_SAMPLES - 1) as f32;
    let s = t * inv_duration;
    let u = clamp(s, L::splat(0.0), L::splat(1.0));
    let x = u * L::splat(last);
    // The sample below x (NaN: the first), and the rows of it and the next, one load a lane.
    let index = each(L::to_i32s(x), |i| i.clamp(0, last as i32 - 1) as usize);
    let i = L::from_fn(|k| index[k] as f32);
    let base = |k: usize| rows[k] as usize + index[k];
    let [x0, y0, a0, b0] = L::columns(|k| db.row(base(k)));
    let [x1, y1, a1, b1] = L::columns(|k| db.row(base(k) + 1));
    // Position: linear in the unclamped sample coordinate (past the end it extrapolates).
    let f = s * L::splat(last) - i;
    let (px, py) = (x0 + (x1 - x0) * f, y0 + (y1 - y0) * f);
    // Angle: held at the end.
    let g = x - i;
    let (a0, a1) = (L::select(tumble, b0, a0), L::select(tumble, b1, a1));
    let rest = L::splat(1.0) - u;
    let progress = (a0 + (a1 - a0) * g) + words[EASE] * u * (rest * rest);
    let offset = V3::new(words[X_SCALE] * px, words[Y_SCALE] * py, L::splat(0.0));
    let half = (words[HALF_COS], words[HALF_SIN]);
    (offset, rotation_z(half, words[TURN] * progress))
}

/// Eq. 6 at curve time `time` and its time derivative.
#[inline(always)]
pub(crate) fn curve_motion<L: Lane>(words: &[L; WORDS], time: L) -> (V3<L>, V3<L>) {
    use curve_word::*;
    let (rate, lobes) = (words[RATE], words[LOBES]);
    let phase = rate * time;
    let (sl, cl) = sin_cos_bounded(lobes * phase);
    let radius = words[AMPLITUDE] + words[AMPLITUDE_ECCENTRICITY] * sl;
    let d_radius = words[AMPLITUDE_ECCENTRICITY] * lobes * rate * cl;
    let (s, c) = sin_cos_bounded(phase);
    let descent = words[DESCENT];
    (
        V3::new(radius * c, -(descent * time), radius * s),
        V3::new(
            d_radius * c - radius * rate * s,
            -descent,
            d_radius * s + radius * rate * c,
        ),
    )
}

/// A curve at piece time `t`: its displacement since its start and the plate leaning into its
/// horizontal velocity by half its glide angle.
#[inline(always)]
pub(crate) fn curve_sample<L: Lane>(words: &[L; WORDS], t: L) -> (V3<L>, Q<L>) {
    use curve_word::*;
    let (position, velocity) = curve_motion(words, words[START] + t);
    let speed = (velocity.x * velocity.x + velocity.z * velocity.z).sqrt();
    let axis = V3::new(-velocity.z / speed, L::splat(0.0), velocity.x / speed);
    let descent = words[DESCENT];
    let descent = L::select(descent.gt(L::splat(1e-6)), descent, L::splat(1e-6));
    let zero = L::splat(0.0);
    let flip = Q::new(zero, zero, words[FLIP_Z], words[FLIP_W]);
    let (s, c) = sin_cos_bounded(L::splat(0.25) * atan2(speed, descent));
    let lean = Q::new(axis.x * s, axis.y * s, axis.z * s, c).mul(flip);
    let moving = L::and(speed.gt(L::splat(1e-6)), speed.lt(L::splat(f32::INFINITY)));
    let start = V3::new(words[START_X], words[START_Y], words[START_Z]);
    (position.sub(start), Q::select(moving, lean, flip))
}

impl Piece {
    /// Displacement since the start and the plate's tilt at piece time `t`, in the frame where
    /// x is the heading, y up and z the heading × up. Beyond its end a swing continues in a
    /// straight line at its final velocity and keeps its final angle; a curve continues eq. 6.
    pub fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        self.words(db).sample(db, t)
    }

    /// [`Piece::sample`]'s displacement alone.
    pub fn offset(&self, db: &TrajectoryDatabase, t: f32) -> Vec3 {
        self.sample(db, t).0
    }

    /// [`Piece::sample`]'s tilt alone.
    pub fn tilt(&self, db: &TrajectoryDatabase, t: f32) -> Quat {
        self.sample(db, t).1
    }
}
