//! Sampling a piece at a piece time, written once for one piece or for several in SIMD lanes
//! ([`Lane`]): a database swing's displacement along its segment and the plate's turn along its
//! angle profile, or eq. 6's curve and the plate's lean into its velocity.

use bevy::math::{Quat, Vec3};

use super::Piece;
use crate::freefall::model::database::{SEGMENT_SAMPLES, TrajectoryDatabase};
use crate::math::geometry::{Q, V3};
use crate::math::kernels::{atan2, clamp, sin_cos};
use crate::math::lane::Lane;

/// A swing's numbers, lane by lane, and what its lanes read from the database.
pub(crate) struct SwingLanes<L> {
    pub segment: [u32; 4],
    pub tumble: [bool; 4],
    pub sign: L,
    pub scale: L,
    pub sideways: L,
    pub duration: L,
    pub turn: L,
    pub start_half: (L, L),
    pub ease: L,
}

/// An eq. 6 curve's numbers, lane by lane.
pub(crate) struct CurveLanes<L> {
    pub amplitude: L,
    pub eccentricity: L,
    pub lobes: L,
    pub rate: L,
    pub descent: L,
    pub start: L,
    /// Eq. 6 at the curve's start, and the plate's half-turns as a rotation.
    pub start_position: V3<L>,
    pub flip: Q<L>,
}

/// The rotation about z by θ₀ + φ from (cos θ₀/2, sin θ₀/2) and φ.
pub(crate) fn rotation_z<L: Lane>(start_half: (L, L), phi: L) -> Q<L> {
    let (s, c) = sin_cos(L::splat(0.5) * phi);
    let (c0, s0) = start_half;
    let zero = L::splat(0.0);
    Q::new(zero, zero, s0 * c + c0 * s, c0 * c - s0 * s)
}

/// A swing at piece time `t`: its displacement and the plate's tilt (see [`Piece::sample`]).
pub(crate) fn swing_sample<L: Lane>(
    p: &SwingLanes<L>,
    db: &TrajectoryDatabase,
    t: L,
) -> (V3<L>, Q<L>) {
    let last = (SEGMENT_SAMPLES - 1) as f32;
    let s = t / p.duration;
    let u = clamp(s, L::splat(0.0), L::splat(1.0));
    let x = u * L::splat(last);
    // The database rows of each lane: the sample below x and the one after.
    let index = |k: usize| (x.get(k) as i32).clamp(0, last as i32 - 1) as usize;
    let segment = |k: usize| db.segment(p.segment[k]);
    let shape = |k: usize| {
        if p.tumble[k] {
            db.tumble_shape()
        } else {
            &segment(k).angle_shape
        }
    };
    let i = L::from_fn(|k| index(k) as f32);
    let f = x - i;
    let gather = |read: &dyn Fn(usize, usize) -> f32| L::from_fn(|k| read(k, index(k)));
    let p0 = (
        gather(&|k, i| segment(k).points[i].x),
        gather(&|k, i| segment(k).points[i].y),
    );
    let p1 = (
        gather(&|k, i| segment(k).points[i + 1].x),
        gather(&|k, i| segment(k).points[i + 1].y),
    );
    let (mut px, mut py) = (p0.0 + (p1.0 - p0.0) * f, p0.1 + (p1.1 - p0.1) * f);
    // Beyond its end a swing goes on at its last velocity.
    let beyond = s.gt(L::splat(1.0));
    if L::any(beyond) {
        let tail = |axis: usize| {
            L::from_fn(|k| {
                let points = &segment(k).points;
                let d = points[SEGMENT_SAMPLES - 1] - points[SEGMENT_SAMPLES - 2];
                if axis == 0 { d.x } else { d.y }
            })
        };
        let run = L::splat(last) * (s - L::splat(1.0));
        px = L::select(beyond, px + tail(0) * run, px);
        py = L::select(beyond, py + tail(1) * run, py);
    }
    let (a0, a1) = (gather(&|k, i| shape(k)[i]), gather(&|k, i| shape(k)[i + 1]));
    let rest = L::splat(1.0) - u;
    let progress = (a0 + (a1 - a0) * f) + p.ease * u * (rest * rest);
    let offset = V3::new(
        p.sign * px * p.scale * p.sideways,
        py * p.scale,
        L::splat(0.0),
    );
    (offset, rotation_z(p.start_half, p.turn * progress))
}

/// Eq. 6 at curve time `time` and its time derivative (see [`Piece::sample`]).
pub(crate) fn curve_motion<L: Lane>(p: &CurveLanes<L>, time: L) -> (V3<L>, V3<L>) {
    let phase = p.rate * time;
    let (sl, cl) = sin_cos(p.lobes * phase);
    let radius = p.amplitude * (L::splat(1.0) + p.eccentricity * sl);
    let d_radius = p.amplitude * p.eccentricity * p.lobes * p.rate * cl;
    let (s, c) = sin_cos(phase);
    (
        V3::new(radius * c, -p.descent * time, radius * s),
        V3::new(
            d_radius * c - radius * p.rate * s,
            -p.descent,
            d_radius * s + radius * p.rate * c,
        ),
    )
}

/// A curve at piece time `t`: its displacement since its start and the plate leaning into its
/// horizontal velocity by half its glide angle.
pub(crate) fn curve_sample<L: Lane>(p: &CurveLanes<L>, t: L) -> (V3<L>, Q<L>) {
    let (position, velocity) = curve_motion(p, p.start + t);
    let speed = (velocity.x * velocity.x + velocity.z * velocity.z).sqrt();
    let axis = V3::new(-velocity.z / speed, L::splat(0.0), velocity.x / speed);
    let descent = L::select(p.descent.gt(L::splat(1e-6)), p.descent, L::splat(1e-6));
    let lean = Q::from_axis_angle(axis, L::splat(0.5) * atan2(speed, descent)).mul(p.flip);
    let moving = L::and(speed.gt(L::splat(1e-6)), speed.lt(L::splat(f32::INFINITY)));
    (
        position.sub(p.start_position),
        Q::select(moving, lean, p.flip),
    )
}

impl<L: Lane> SwingLanes<L> {
    /// The numbers of `pieces` (swings, one a lane) side by side.
    pub(crate) fn of(pieces: &[&Piece]) -> Self {
        let mut segment = [0; 4];
        let mut tumble = [false; 4];
        let number = |read: &dyn Fn(&Piece) -> f32| L::from_fn(|k| read(pieces[k]));
        for (k, piece) in pieces.iter().enumerate() {
            if let Piece::Swing {
                segment: s,
                tumble: t,
                ..
            } = **piece
            {
                (segment[k], tumble[k]) = (s, t);
            }
        }
        let field = |pick: fn(&Piece) -> f32| number(&|p| pick(p));
        Self {
            segment,
            tumble,
            sign: field(|p| swing(p).0),
            scale: field(|p| swing(p).1),
            sideways: field(|p| swing(p).2),
            duration: field(Piece::duration),
            turn: field(|p| swing(p).3),
            start_half: (field(|p| swing(p).4), field(|p| swing(p).5)),
            ease: field(|p| swing(p).6),
        }
    }
}

/// A swing's (sign, scale, sideways, turn, cos θ₀/2, sin θ₀/2, ease); zeros for a curve.
fn swing(piece: &Piece) -> (f32, f32, f32, f32, f32, f32, f32) {
    match *piece {
        Piece::Swing {
            sign,
            scale,
            sideways,
            turn,
            start_half,
            ease,
            ..
        } => (
            sign,
            scale,
            sideways,
            turn,
            start_half.x,
            start_half.y,
            ease,
        ),
        Piece::Curve { .. } => (0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0),
    }
}

impl<L: Lane> CurveLanes<L> {
    /// The numbers of `pieces` (curves, one a lane) side by side.
    pub(crate) fn of(pieces: &[&Piece]) -> Self {
        let curve = |k: usize| match *pieces[k] {
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
            } => (
                [amplitude, eccentricity, lobes, rate, descent, start],
                start_position,
                flip_rotation,
            ),
            Piece::Swing { .. } => ([0.0; 6], Vec3::ZERO, Quat::IDENTITY),
        };
        let number = |i: usize| L::from_fn(|k| curve(k).0[i]);
        let position = |axis: usize| L::from_fn(|k| curve(k).1[axis]);
        let flip = |axis: usize| L::from_fn(|k| curve(k).2.to_array()[axis]);
        Self {
            amplitude: number(0),
            eccentricity: number(1),
            lobes: number(2),
            rate: number(3),
            descent: number(4),
            start: number(5),
            start_position: V3::new(position(0), position(1), position(2)),
            flip: Q::new(flip(0), flip(1), flip(2), flip(3)),
        }
    }
}

impl Piece {
    /// Displacement since the start and the plate's tilt at piece time `t`, in the frame where
    /// x is the heading, y up and z the heading × up. Beyond its end a swing continues in a
    /// straight line at its final velocity and keeps its final angle; a curve continues eq. 6.
    pub fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        let (offset, tilt) = match self {
            Self::Swing { .. } => swing_sample(&SwingLanes::<f32>::of(&[self]), db, t),
            Self::Curve { .. } => curve_sample(&CurveLanes::<f32>::of(&[self]), t),
        };
        (offset.vec3(), tilt.quat())
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
