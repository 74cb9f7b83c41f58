//! The usual step of a fall (§4.2 inside one piece: no piece ends, no blend from a motion
//! change, no release fading, not landed), written once for one fall or for several in SIMD
//! lanes ([`Lane`]): sampling the piece (a database swing or eq. 6's curve), the fluid's drift
//! relaxing toward the wind, the compensated move, landing, and the orientation with eq. 15's
//! tilt. Every fall takes this step through the same code whatever lane or chunk it lands in,
//! so its path has the same bits with lanes or without, on any number of threads, on any
//! machine. What lanes cannot share (a new piece, the Markov step, a swing search, a blend, a
//! release fading) is [`FallPath::advance`]'s own, one fall at a time.

use bevy::math::{Quat, Vec3};

use super::super::FallModel;
use super::super::database::TrajectoryDatabase;
use super::super::piece::Piece;
use super::super::piece::sample::{CurveLanes, SwingLanes, curve_sample, swing_sample};
use super::super::release::FallRelease;
use super::super::tilt::{WindTilt, wind_tilt};
use super::{FallPath, MIN_DRIFT, StepOutcome};
use crate::math::geometry::{Q, V3};
use crate::math::lane::Lane;
use crate::wind::WindField;

/// What the usual step reads and writes of each fall, lane by lane.
#[derive(Clone, Copy)]
pub(crate) struct Hot<L> {
    pub piece_time: L,
    pub piece_offset: V3<L>,
    pub lateral: L,
    pub drift: V3<L>,
    pub still: V3<L>,
    pub carry: V3<L>,
    /// The last control point, p_i.
    pub point: V3<L>,
    /// (cos ψ/2, sin ψ/2) of the heading.
    pub heading: (L, L),
    /// The fall's sizes: U (m/s) and the drag length (m), and the ground's height.
    pub descent_speed: L,
    pub drag_length: L,
    pub ground: L,
    /// Eq. 15's tilt: W (rad) and U_ref (m/s).
    pub max_angle: L,
    pub reference_speed: L,
}

/// What the usual step makes: the next control point and orientation, the piece's tilt, and
/// which falls landed.
pub(crate) struct Made<L: Lane> {
    pub next: V3<L>,
    pub orientation: Q<L>,
    pub piece_tilt: Q<L>,
    pub landed: L::Mask,
}

/// `v` turned from the heading frame to the world: by ψ about +Y.
pub(crate) fn turned<L: Lane>(heading: (L, L), v: V3<L>) -> V3<L> {
    let (ch, sh) = heading;
    let (c, s) = (ch * ch - sh * sh, L::splat(2.0) * ch * sh);
    V3::new(v.x * c + v.z * s, v.y, v.z * c - v.x * s)
}

/// The usual step of `dt` seconds in `wind` (already held to the largest speed), the piece
/// sampled at the new piece time (`hot.piece_time`, already moved on) as `end` and `tilt`:
/// the piece's increment turned to the world, then [`fall_on`], and the orientation yaw ·
/// piece tilt under eq. 15's tilt.
pub(crate) fn advance<L: Lane>(
    hot: &mut Hot<L>,
    end: V3<L>,
    tilt: Q<L>,
    dt: L,
    wind: V3<L>,
) -> Made<L> {
    let inc = end.sub(hot.piece_offset);
    hot.piece_offset = end;
    hot.lateral = hot.lateral + inc.x;
    let delta = turned(hot.heading, inc);
    let (next, landed) = fall_on(hot, delta, dt, wind);
    let zero = L::splat(0.0);
    let yaw = Q::new(zero, hot.heading.1, zero, hot.heading.0);
    let lean = wind_tilt(hot.max_angle, hot.reference_speed, wind, L::splat(1.0));
    Made {
        next,
        orientation: lean.mul(yaw.mul(tilt)),
        piece_tilt: tilt,
        landed,
    }
}

/// §4.2's p ← p + v dt + Δf for a still-fluid displacement `delta` over `dt`: the drift v
/// relaxes toward `wind` by backward Euler, the move is carried in compensated summation (a
/// step below f32's spacing far from the origin is kept until it adds up), and a fall that
/// reaches the ground stops on it. Returns the new point and whether it landed.
pub(crate) fn fall_on<L: Lane>(
    hot: &mut Hot<L>,
    delta: V3<L>,
    dt: L,
    wind: V3<L>,
) -> (V3<L>, L::Mask) {
    hot.still = hot.still.add(delta);
    // Backward Euler on dv/dt = (u − v) / τ, 1/τ = √(U² + |u − v|²) / drag length: never past
    // the wind, stable at any step; in still air a decaying drift is flushed to zero.
    let slip = wind.sub(hot.drift);
    let u = hot.descent_speed;
    let length = L::select(
        hot.drag_length.gt(L::splat(1e-12)),
        hot.drag_length,
        L::splat(1e-12),
    );
    let k = dt * ((u * u + slip.length_squared()).sqrt() / length);
    let drift = hot.drift.add(slip.scale(k / (L::splat(1.0) + k)));
    let still_air = drift.length_squared().lt(L::splat(MIN_DRIFT * MIN_DRIFT));
    hot.drift = V3::select(still_air, V3::splat(Vec3::ZERO), drift);
    let step = hot.drift.scale(dt).add(delta).add(hot.carry);
    let mut next = hot.point.add(step);
    // Exact: `next` and the point are within a factor of two of each other wherever a step is
    // smaller than the position (Sterbenz).
    let carry = step.sub(next.sub(hot.point));
    let bounded = |v: L| v.abs().lt(L::splat(f32::INFINITY));
    let finite = L::and(bounded(carry.x), L::and(bounded(carry.y), bounded(carry.z)));
    hot.carry = V3::select(finite, carry, V3::splat(Vec3::ZERO));
    let landed = next.y.le(hot.ground);
    next.y = L::select(landed, hot.ground, next.y);
    hot.drift = V3::select(landed, V3::splat(Vec3::ZERO), hot.drift);
    hot.carry = V3::select(landed, V3::splat(Vec3::ZERO), hot.carry);
    hot.point = next;
    (next, landed)
}

impl FallPath {
    /// Whether the next step of `dt` is a usual one (see the module's docs).
    pub(crate) fn usual(&self, dt: f32) -> bool {
        !self.landed
            && self.previous.is_none()
            && self.release.is_none()
            && self.piece_time + dt < self.piece.duration()
    }

    /// What the usual step reads of this fall (one lane).
    pub(crate) fn hot(&self, tilt: &WindTilt) -> Hot<f32> {
        Hot {
            piece_time: self.piece_time,
            piece_offset: V3::of(self.piece_offset),
            lateral: self.lateral,
            drift: V3::of(self.drift),
            still: V3::of(self.still),
            carry: V3::of(self.carry),
            point: V3::of(self.points[2]),
            heading: (self.heading.x, self.heading.y),
            descent_speed: self.scales.descent_speed,
            drag_length: self.scales.drag_length,
            ground: self.ground,
            max_angle: tilt.max_angle,
            reference_speed: tilt.reference_speed,
        }
    }

    /// The piece under way.
    pub(crate) fn piece(&self) -> &Piece {
        &self.piece
    }

    /// Takes back what a usual step of `dt` made of lane `k` of `hot` and `made`.
    pub(crate) fn take_usual<L: Lane>(
        &mut self,
        hot: &Hot<L>,
        made: &Made<L>,
        k: usize,
        dt: f32,
    ) -> bool {
        let v = |v: V3<L>| Vec3::new(v.x.get(k), v.y.get(k), v.z.get(k));
        let q = |q: Q<L>| Quat::from_xyzw(q.x.get(k), q.y.get(k), q.z.get(k), q.w.get(k));
        self.piece_time = hot.piece_time.get(k);
        self.piece_offset = v(hot.piece_offset);
        self.piece_tilt = q(made.piece_tilt);
        self.lateral = hot.lateral.get(k);
        self.drift = v(hot.drift);
        self.still = v(hot.still);
        self.carry = v(hot.carry);
        self.time += f64::from(dt);
        self.points = [self.points[1], self.points[2], v(made.next)];
        self.orientations = [self.orientations[1], q(made.orientation)];
        let landed = L::mask_get(made.landed, k);
        self.landed = landed;
        landed
    }
}

/// A fall's usual step waiting for the lanes: which item it is, its wind and step as
/// [`FallPath::advance`] holds them, its tilt, and what its owner keeps for afterwards.
pub(crate) struct UsualJob {
    pub index: usize,
    pub wind: Vec3,
    pub dt: f32,
    pub tilt: WindTilt,
    /// The seconds since the last step and until the next (a cloud leaf's tier clock).
    pub waited: f32,
    pub next: f32,
}

impl UsualJob {
    /// Item `index`'s step of `dt` in `wind`, held as [`FallPath::advance`] holds them.
    pub(crate) fn new(index: usize, wind: Vec3, dt: f32, tilt: WindTilt) -> Self {
        Self {
            index,
            wind: crate::guard::clamp_length(wind, FallRelease::MAX_SPEED),
            dt: if dt.is_finite() {
                dt.clamp(0.0, FallRelease::MAX_STEP)
            } else {
                0.0
            },
            tilt,
            waited: dt,
            next: 0.0,
        }
    }
}

/// Takes `jobs` (usual steps of `items`, all swings or all curves) four at a time in SIMD
/// lanes and the rest one at a time through the same code; `done` is told which landed.
pub(crate) fn run_usual<T>(
    items: &mut [T],
    jobs: &[UsualJob],
    path_of: impl Fn(&mut T) -> &mut FallPath,
    db: &TrajectoryDatabase,
    mut done: impl FnMut(&mut T, &UsualJob, bool),
) {
    let (quads, rest) = jobs.split_at(jobs.len() / 4 * 4);
    for group in quads.chunks_exact(4) {
        let group = [&group[0], &group[1], &group[2], &group[3]];
        let Ok([a, b, c, d]) = items.get_disjoint_mut(group.map(|j| j.index)) else {
            continue;
        };
        let landed = {
            let mut paths = [path_of(a), path_of(b), path_of(c), path_of(d)];
            step_usual::<wide::f32x4, 4>(&mut paths, group, db)
        };
        for (k, item) in [a, b, c, d].into_iter().enumerate() {
            done(item, group[k], landed[k]);
        }
    }
    for job in rest {
        let item = &mut items[job.index];
        let landed = step_usual::<f32, 1>(&mut [path_of(item)], [job], db)[0];
        done(item, job, landed);
    }
}

/// One usual step of `paths` (all swings or all curves), lane by lane, each with its job.
fn step_usual<L: Lane, const N: usize>(
    paths: &mut [&mut FallPath; N],
    jobs: [&UsualJob; N],
    db: &TrajectoryDatabase,
) -> [bool; 4] {
    debug_assert!(N == L::WIDTH);
    let dts = jobs.map(|j| j.dt);
    let winds = jobs.map(|j| j.wind);
    let number = |read: &dyn Fn(&FallPath) -> f32| L::from_fn(|k| read(paths[k]));
    let vector = |read: &dyn Fn(&FallPath) -> Vec3| {
        V3::new(
            number(&|p| read(p).x),
            number(&|p| read(p).y),
            number(&|p| read(p).z),
        )
    };
    let dt = L::from_fn(|k| dts[k]);
    let mut hot = Hot {
        piece_time: number(&|p| p.piece_time) + dt,
        piece_offset: vector(&|p| p.piece_offset),
        lateral: number(&|p| p.lateral),
        drift: vector(&|p| p.drift),
        still: vector(&|p| p.still),
        carry: vector(&|p| p.carry),
        point: vector(&|p| p.points[2]),
        heading: (number(&|p| p.heading.x), number(&|p| p.heading.y)),
        descent_speed: number(&|p| p.scales.descent_speed),
        drag_length: number(&|p| p.scales.drag_length),
        ground: number(&|p| p.ground),
        max_angle: L::from_fn(|k| jobs[k].tilt.max_angle),
        reference_speed: L::from_fn(|k| jobs[k].tilt.reference_speed),
    };
    let pieces: [&Piece; 4] = std::array::from_fn(|k| &paths[k.min(L::WIDTH - 1)].piece);
    let pieces = &pieces[..L::WIDTH];
    let (end, turn) = match pieces[0] {
        Piece::Swing { .. } => swing_sample(&SwingLanes::of(pieces), db, hot.piece_time),
        Piece::Curve { .. } => curve_sample(&CurveLanes::of(pieces), hot.piece_time),
    };
    let wind = V3::new(
        L::from_fn(|k| winds[k].x),
        L::from_fn(|k| winds[k].y),
        L::from_fn(|k| winds[k].z),
    );
    let made = advance(&mut hot, end, turn, dt, wind);
    let mut landed = [false; 4];
    for (k, path) in paths.iter_mut().enumerate() {
        landed[k] = path.take_usual(&hot, &made, k, dts[k]);
    }
    landed
}

impl FallPath {
    /// Advances every fall of `paths` by `dt` seconds in `wind` (`None`: still fluid) at the
    /// field's own clock, as [`FallPath::advance`] advances one (the same bits for each fall),
    /// but four at a time: the wind is read in SIMD lanes ([`WindField::velocities_at`]'s
    /// batched read) and the usual steps (inside a piece) are taken in lanes; what lanes cannot
    /// share (a new piece, the Markov step, a swing search) one fall at a time. `outcomes` is
    /// cleared and filled in order.
    pub fn advance_all(
        paths: &mut [FallPath],
        model: &FallModel,
        dt: f32,
        wind: Option<&WindField>,
        tilt: &WindTilt,
        outcomes: &mut Vec<StepOutcome>,
    ) {
        let positions: Vec<Vec3> = paths.iter().map(FallPath::position).collect();
        let mut winds = Vec::new();
        match wind {
            Some(w) => w.velocities(&positions, &mut winds),
            None => winds.resize(paths.len(), Vec3::ZERO),
        }
        outcomes.clear();
        outcomes.resize(paths.len(), StepOutcome::Falling);
        let (mut swings, mut curves) = (Vec::new(), Vec::new());
        let lanes = crate::math::lanes_enabled();
        for (i, (path, wind)) in paths.iter_mut().zip(winds).enumerate() {
            let job = UsualJob::new(i, wind, dt, *tilt);
            if lanes && path.usual(job.dt) {
                match path.piece {
                    Piece::Swing { .. } => swings.push(job),
                    Piece::Curve { .. } => curves.push(job),
                }
            } else {
                outcomes[i] = path.advance(model, dt, wind, tilt);
            }
        }
        for jobs in [&swings, &curves] {
            run_usual(
                paths,
                jobs,
                |p| p,
                model.database(),
                |_, job, landed| {
                    if landed {
                        outcomes[job.index] = StepOutcome::Landed;
                    }
                },
            );
        }
    }
}
