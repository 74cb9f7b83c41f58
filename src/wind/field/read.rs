//! Reading the [`WindField`]: the log law, Taylor's travel, the periodic grid, shelters and local
//! sources, at one point or many.

use bevy::math::Vec3;
use wide::f32x4;

use super::WindField;
use super::profile;
use crate::portable::geometry::V3;
use crate::portable::lane::{Lane, MAX_WIDTH, each, per_lane};
use crate::portable::transcendental::{clamp, floor};
use crate::spectrum::periodic_lerp;
use crate::wind::config::{SpatialMode, TemporalMode};
use crate::wind::mover::MoverFlow;

impl WindField {
    /// The global field's velocity at `position` and `time` (sheltered), without the local
    /// sources.
    pub fn global_velocity_at(&self, position: Vec3, time: f32) -> Vec3 {
        self.sheltered(position, f64::from(time))
    }

    /// Wind velocity at `position` at the field's own clock.
    pub fn velocity(&self, position: Vec3) -> Vec3 {
        self.sample(position, self.time)
    }

    /// Wind velocity at `position` and `time`, m/s. Finite for every input.
    pub fn velocity_at(&self, position: Vec3, time: f32) -> Vec3 {
        self.sample(position, f64::from(time))
    }

    /// [`Self::velocity`] for many points, at the field's own clock: `out` is cleared and
    /// filled in order, four points at a time in SIMD lanes, with the bits
    /// [`Self::velocity`] gives each point.
    pub fn velocities(&self, positions: &[Vec3], out: &mut Vec<Vec3>) {
        self.read_many(positions, self.time, out);
    }

    /// [`Self::velocity_at`] for many points: `out` is cleared and filled in order, four
    /// points at a time in SIMD lanes (the log law, the interpolation and the mean wind), with
    /// the bits [`Self::velocity_at`] gives each point.
    pub fn velocities_at(&self, positions: &[Vec3], time: f32, out: &mut Vec<Vec3>) {
        self.read_many(positions, f64::from(time), out);
    }

    /// What every read at `time` shares (see [`Moment`]): taken once for a batch of reads.
    pub(crate) fn moment(&self, time: f64) -> Moment {
        let time = if time.is_finite() { time } else { 0.0 };
        let dims = self.shape.dims();
        let (nt, nx, nz) = match *dims {
            [nt, nx, nz] => (nt, nx, nz),
            [nx, nz] => (1, nx, nz),
            _ => (1, 1, 1),
        };
        let cell = f64::from(self.config.cell_size);
        let travel = self.drift_at(time);
        let shift = |d: f64, n: usize| {
            let period = n as f64 * cell;
            let r = d - (d / period).floor() * period;
            if r.is_finite() { r as f32 } else { 0.0 }
        };
        let slice = match self.config.temporal {
            TemporalMode::Evolving { samples, period } if nt > 1 => {
                let c = time / f64::from(period) * samples as f64;
                let c = c - (c / nt as f64).floor() * nt as f64;
                let c = if c.is_finite() {
                    c.clamp(0.0, nt as f64)
                } else {
                    0.0
                };
                let t0 = (c as usize).min(nt - 1);
                let t1 = if t0 + 1 == nt { 0 } else { t0 + 1 };
                (t0, t1, (c - t0 as f64).clamp(0.0, 1.0) as f32)
            }
            _ => (0, 0, 0.0),
        };
        let pulse = if self.config.pulse.is_active() {
            self.config.pulse.factor(time)
        } else {
            1.0
        };
        Moment {
            time,
            shift: (shift(travel.x, nx), shift(travel.y, nz)),
            slice,
            pulse,
        }
    }

    /// The wind at `L::WIDTH` points given in lanes at `moment` (from [`Self::moment`]): what
    /// a fall store reads for a block.
    #[inline(always)]
    pub(crate) fn velocity_lanes<L: Lane>(&self, moment: &Moment, points: V3<L>) -> V3<L> {
        self.read_lanes(moment, points, &self.movers)
    }

    /// [`Self::velocity_lanes`] for points that all lie within the box of [`Self::movers_near`]
    /// `movers` came from: the same bits, the far movers skipped.
    #[inline(always)]
    pub(crate) fn velocity_lanes_among<L: Lane>(
        &self,
        moment: &Moment,
        points: V3<L>,
        movers: &[MoverFlow],
    ) -> V3<L> {
        self.read_lanes(moment, points, movers)
    }

    /// The movers whose flow reaches into the box from `low` to `high` (in the order they are
    /// summed): reading points inside the box among them alone gives the same bits as among
    /// all (the others add exact zeros there).
    pub(crate) fn movers_near(&self, low: Vec3, high: Vec3) -> Vec<MoverFlow> {
        self.movers
            .iter()
            .filter(|m| {
                let nearest = m.centre.clamp(low, high);
                m.centre.distance_squared(nearest) < m.reach2
            })
            .copied()
            .collect()
    }

    fn read_many(&self, positions: &[Vec3], time: f64, out: &mut Vec<Vec3>) {
        let moment = self.moment(time);
        out.clear();
        out.reserve(positions.len());
        // A few hundred points at a time, each batch among the movers that reach its box.
        for batch in positions.chunks(256) {
            let near;
            let movers = if self.movers.is_empty() {
                &self.movers[..]
            } else {
                let (low, high) = batch.iter().fold(
                    (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                    |(low, high), p| (low.min(*p), high.max(*p)),
                );
                // An infinite point (or a batch of NaNs): every mover, as an unculled read.
                near = if low.is_finite() && high.is_finite() {
                    self.movers_near(low, high)
                } else {
                    self.movers.clone()
                };
                &near[..]
            };
            let mut quads = batch.chunks_exact(4);
            for quad in &mut quads {
                let lane = |axis: usize| f32x4::from(std::array::from_fn(|k| quad[k][axis]));
                let v = self.read_lanes(&moment, V3::new(lane(0), lane(1), lane(2)), movers);
                out.extend((0..4).map(|k| Vec3::new(v.x.get(k), v.y.get(k), v.z.get(k))));
            }
            out.extend(
                quads
                    .remainder()
                    .iter()
                    .map(|&p| self.read_lanes(&moment, V3::of(p), movers).vec3()),
            );
        }
    }

    /// The global field, calmed by every shelter.
    fn sheltered(&self, position: Vec3, time: f64) -> Vec3 {
        self.shelter(position, self.global(position, time))
    }

    /// `global` at `position` calmed by every shelter.
    fn shelter(&self, position: Vec3, global: Vec3) -> Vec3 {
        if self.shelters.is_empty() {
            return global;
        }
        let p = position.into();
        let share: f32 = self
            .shelters
            .iter()
            .map(|s| s.factor(p, self.along))
            .product();
        global * share
    }

    /// The global field (sheltered) plus every local source.
    fn sample(&self, position: Vec3, time: f64) -> Vec3 {
        self.read_lanes(&self.moment(time), V3::of(position), &self.movers)
            .vec3()
    }

    /// The global field (sheltered) plus every local source and the flows of `movers` at
    /// `L::WIDTH` points: the lanes take the log law, the interpolation and the mean wind;
    /// shelters, sources and movers are added point by point (sources, then movers, in one sum).
    #[inline(always)]
    fn read_lanes<L: Lane>(&self, moment: &Moment, points: V3<L>, movers: &[MoverFlow]) -> V3<L> {
        let global = self.global_lanes::<L>(moment, points);
        if self.shelters.is_empty() && self.sources.is_empty() && movers.is_empty() {
            return global;
        }
        let local_time = moment.time;
        let each = |k: usize| {
            let g = Vec3::new(global.x.get(k), global.y.get(k), global.z.get(k));
            let point = Vec3::new(points.x.get(k), points.y.get(k), points.z.get(k));
            let g = self.shelter(point, g);
            if self.sources.is_empty() && movers.is_empty() {
                return g;
            }
            let p = point.into();
            let local = self
                .sources
                .iter()
                .fold(Vec3::ZERO, |sum, s| sum + s.velocity(p, local_time));
            let local = movers.iter().fold(local, |sum, m| sum + m.velocity(point));
            let total = g + local;
            if total.is_finite() { total } else { g }
        };
        let v: [Vec3; MAX_WIDTH] = per_lane(|k| if k < L::WIDTH { each(k) } else { Vec3::ZERO });
        V3::new(
            L::from_fn(|k| v[k].x),
            L::from_fn(|k| v[k].y),
            L::from_fn(|k| v[k].z),
        )
    }

    /// The log-law mean wind plus turbulence (no sources).
    fn global(&self, position: Vec3, time: f64) -> Vec3 {
        self.global_lanes(&self.moment(time), V3::of(position))
            .vec3()
    }

    /// The log-law mean wind plus turbulence (no shelters or sources) at `L::WIDTH` points.
    #[inline(always)]
    fn global_lanes<L: Lane>(&self, moment: &Moment, points: V3<L>) -> V3<L> {
        let c = &self.config;
        let time = moment.time;
        // max(0, ln(h/z0)): the read's one logarithm.
        let h = points.y;
        let above = h.gt(L::splat(c.roughness));
        let height = L::select(h.lt(L::splat(f32::MAX)), h, L::splat(f32::MAX));
        let ratio = profile::ln_lanes(height) - L::splat(self.log_roughness);
        let ratio = L::select(ratio.gt(L::splat(0.0)), ratio, L::splat(0.0));
        let log_ratio = L::select(above, ratio, L::splat(0.0));
        // Mean speed, turbulence scale and advection speed at this height.
        let g = log_ratio * L::splat(self.inv_log_reference); // eq. 14
        let reference = L::splat(c.reference_speed);
        let mean = reference * g;
        let (n, scale) = match c.spatial {
            // One plane carried to every height (eq. 14): the pattern travels the same
            // everywhere, so its travel is reduced to the plane's period once and the rest is
            // single precision in lanes.
            SpatialMode::Plane => (self.plane_lanes(moment, points), g),
            SpatialMode::Volume { .. } => {
                let one = L::splat(1.0);
                // The pattern travels at the local mean wind (eq. 10): per point, in f64.
                (
                    self.volume_lanes(points, time, mean, g),
                    L::select(g.lt(one), g, one),
                )
            }
        };
        let sigma = self.sigma();
        let n = V3::new(
            n.x * scale * L::splat(sigma.x),
            n.y * scale * L::splat(sigma.y),
            n.z * scale * L::splat(sigma.z),
        );
        let (along, across) = (self.along, self.across);
        let u = mean + n.x;
        let wind = V3::new(
            (L::splat(along.x) * u + L::splat(across.x) * n.y) + L::splat(0.0) * n.z,
            (L::splat(along.y) * u + L::splat(across.y) * n.y) + L::splat(1.0) * n.z,
            (L::splat(along.z) * u + L::splat(across.z) * n.y) + L::splat(0.0) * n.z,
        );
        if c.pulse.is_active() {
            wind.scale(L::splat(moment.pulse))
        } else {
            wind
        }
    }

    /// The turbulence of a plane (frozen: a 2-D grid; evolving: 3-D, time first) at each
    /// lane's point: Taylor's travel ∫ U dt reduced to the grid's period in f64 once, then the
    /// node coordinates, branch-free floors and periodic wraps and the bilinear (trilinear in
    /// time) weights in f32 lanes; only the node loads go lane by lane.
    #[inline(always)]
    fn plane_lanes<L: Lane>(&self, moment: &Moment, points: V3<L>) -> V3<L> {
        let dims = self.shape.dims();
        let (nx, nz) = match *dims {
            [_, nx, nz] | [nx, nz] => (nx, nz),
            _ => return V3::splat(Vec3::ZERO),
        };
        let per_cell = L::splat(self.per_cell as f32);
        let x = (points.x - L::splat(moment.shift.0)) * per_cell;
        let z = (points.z - L::splat(moment.shift.1)) * per_cell;
        let x = wrap_lanes(x, nx);
        let z = wrap_lanes(z, nz);
        let (t0, t1, ft) = moment.slice;
        let slice = |t: usize| &self.nodes[t * nx * nz..(t + 1) * nx * nz];
        if t0 == t1 {
            return bilinear(slice(t0), nz, &x, &z);
        }
        let ft = L::splat(ft);
        bilinear(slice(t0), nz, &x, &z)
            .scale(L::splat(1.0) - ft)
            .add(bilinear(slice(t1), nz, &x, &z).scale(ft))
    }

    /// The turbulence of a volume at each lane's point (the pattern's travel scaled by each
    /// height's log-law ratio `travel`, advected at its mean speed `mean`): point by point, in
    /// f64 coordinates.
    #[inline(always)]
    fn volume_lanes<L: Lane>(&self, points: V3<L>, time: f64, mean: L, travel: L) -> V3<L> {
        let noise: [Vec3; MAX_WIDTH] = per_lane(|k| {
            if k >= L::WIDTH {
                return Vec3::ZERO;
            }
            let shift = f64::from(mean.get(k)) * (time - self.drift_since);
            let base = self.drift_base * f64::from(travel.get(k));
            let p = Vec3::new(points.x.get(k), points.y.get(k), points.z.get(k));
            let x = (f64::from(p.x) - (base.x + f64::from(self.along.x) * shift)) * self.per_cell;
            let z = (f64::from(p.z) - (base.y + f64::from(self.along.z) * shift)) * self.per_cell;
            self.sample_nd(p, time, x, z)
        });
        V3::new(
            L::from_fn(|k| noise[k].x),
            L::from_fn(|k| noise[k].y),
            L::from_fn(|k| noise[k].z),
        )
    }

    /// The turbulence read on a 3- or 4-D grid.
    fn sample_nd(&self, position: Vec3, time: f64, x: f64, z: f64) -> Vec3 {
        let c = &self.config;
        let per_cell = self.per_cell;
        let mut coords = [0.0f64; 4];
        let mut axes = 0;
        if let TemporalMode::Evolving { samples, period } = c.temporal {
            coords[axes] = time / f64::from(period) * samples as f64;
            axes += 1;
        }
        coords[axes] = x;
        axes += 1;
        if let SpatialMode::Volume { .. } = c.spatial {
            coords[axes] = f64::from(position.y) * per_cell;
            axes += 1;
        }
        coords[axes] = z;
        periodic_lerp(&self.shape, &self.nodes, &coords[..self.shape.dims().len()])
    }
}

/// The bilinear read of a plane of `nodes` (rows of `nz`) at each lane's wrapped coordinates
/// `x` and `z` (from [`wrap_lanes`]).
#[inline(always)]
fn bilinear<L: Lane>(nodes: &[Vec3], nz: usize, x: &Wrapped<L>, z: &Wrapped<L>) -> V3<L> {
    let node = |i: &[usize; MAX_WIDTH], j: &[usize; MAX_WIDTH]| {
        let [a, b, c, _] = L::columns(|k| {
            let v = nodes[i[k] * nz + j[k]];
            [v.x, v.y, v.z, 0.0]
        });
        V3::new(a, b, c)
    };
    let (i0, i1, fx) = x;
    let (j0, j1, fz) = z;
    let (gx, gz) = (L::splat(1.0) - *fx, L::splat(1.0) - *fz);
    let low = node(i0, j0).scale(gz).add(node(i0, j1).scale(*fz));
    let high = node(i1, j0).scale(gz).add(node(i1, j1).scale(*fz));
    low.scale(gx).add(high.scale(*fx))
}

/// A coordinate wrapped onto a periodic axis, lane by lane: the node below, the next, and the
/// weight of the next.
type Wrapped<L> = ([usize; MAX_WIDTH], [usize; MAX_WIDTH], L);

/// A grid coordinate `c` in lanes wrapped onto an axis of `n` nodes: the node below and the
/// next (periodic), and the weight of the next. Branch-free: c − n ⌊c / n⌋ with the portable
/// floor, held to [0, n) against rounding; a non-finite coordinate reads node 0.
#[inline(always)]
fn wrap_lanes<L: Lane>(c: L, n: usize) -> Wrapped<L> {
    let len = L::splat(n as f32);
    let w = c - len * floor(c * L::splat(1.0 / n as f32));
    let w = L::select(w.lt(L::splat(0.0)), w + len, w);
    let w = L::select(w.ge(len), w - len, w);
    let finite = L::and(w.ge(L::splat(0.0)), w.lt(len));
    let w = L::select(finite, w, L::splat(0.0));
    let i = floor(w);
    let f = clamp(w - i, L::splat(0.0), L::splat(1.0));
    let below = each(L::to_i32s(i), |i| (i.max(0) as usize).min(n - 1));
    let above = each(below, |i| if i + 1 == n { 0 } else { i + 1 });
    (below, above, f)
}

/// What every read of a field at one time shares: the time, the plane pattern's travel
/// reduced to its period (m; single precision from here on), the evolving grid's two time
/// slices and the weight of the second, the pulse's factor.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Moment {
    time: f64,
    shift: (f32, f32),
    slice: (usize, usize, f32),
    pulse: f32,
}
