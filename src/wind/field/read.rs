//! Reading the [`WindField`]: the log law, Taylor's travel, the periodic grid, shelters and local
//! sources, at one point or many.

use bevy::math::Vec3;
use wide::f32x4;

use super::WindField;
use super::profile;
use crate::math::geometry::V3;
use crate::math::lane::Lane;
use crate::spectrum::{periodic_lerp, wrap};
use crate::wind::config::{SpatialMode, TemporalMode};

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

    /// [`Self::velocity_at`] for many points: `out` is cleared and filled in order, four
    /// points at a time in SIMD lanes (the log law, the interpolation and the mean wind), with
    /// the bits [`Self::velocity_at`] gives each point.
    pub fn velocities_at(&self, positions: &[Vec3], time: f32, out: &mut Vec<Vec3>) {
        self.read_many(positions, f64::from(time), out);
    }

    /// The wind at the field's own clock at `L::WIDTH` points given in lanes.
    pub(crate) fn velocity_lanes<L: Lane>(&self, points: V3<L>) -> V3<L> {
        let p: [Vec3; 4] = std::array::from_fn(|k| {
            let k = k.min(L::WIDTH - 1);
            Vec3::new(points.x.get(k), points.y.get(k), points.z.get(k))
        });
        self.sample_lanes::<L>(&p[..L::WIDTH], self.time)
    }

    fn read_many(&self, positions: &[Vec3], time: f64, out: &mut Vec<Vec3>) {
        out.clear();
        out.reserve(positions.len());
        let mut quads = positions.chunks_exact(4);
        for quad in &mut quads {
            let v = self.sample_lanes::<f32x4>(quad, time);
            out.extend((0..4).map(|k| Vec3::new(v.x.get(k), v.y.get(k), v.z.get(k))));
        }
        out.extend(quads.remainder().iter().map(|&p| self.sample(p, time)));
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
        let v = self.sample_lanes::<f32>(&[position], time);
        Vec3::new(v.x, v.y, v.z)
    }

    /// The global field (sheltered) plus every local source at `L::WIDTH` points: the lanes
    /// take the log law, the interpolation and the mean wind; shelters and sources are added
    /// point by point.
    fn sample_lanes<L: Lane>(&self, points: &[Vec3], time: f64) -> V3<L> {
        let global = self.global_lanes::<L>(points, time);
        if self.shelters.is_empty() && self.sources.is_empty() {
            return global;
        }
        let local_time = if time.is_finite() { time } else { self.time };
        let each = |k: usize| {
            let g = Vec3::new(global.x.get(k), global.y.get(k), global.z.get(k));
            let g = self.shelter(points[k], g);
            if self.sources.is_empty() {
                return g;
            }
            let p = points[k].into();
            let local = self
                .sources
                .iter()
                .fold(Vec3::ZERO, |sum, s| sum + s.velocity(p, local_time));
            let total = g + local;
            if total.is_finite() { total } else { g }
        };
        let v: [Vec3; 4] = std::array::from_fn(|k| if k < L::WIDTH { each(k) } else { Vec3::ZERO });
        V3::new(
            L::from_fn(|k| v[k].x),
            L::from_fn(|k| v[k].y),
            L::from_fn(|k| v[k].z),
        )
    }

    /// The log-law mean wind plus turbulence (no sources).
    fn global(&self, position: Vec3, time: f64) -> Vec3 {
        let v = self.global_lanes::<f32>(&[position], time);
        Vec3::new(v.x, v.y, v.z)
    }

    /// The log-law mean wind plus turbulence (no shelters or sources) at `L::WIDTH` points.
    fn global_lanes<L: Lane>(&self, points: &[Vec3], time: f64) -> V3<L> {
        let c = &self.config;
        // max(0, ln(h/z0)): the read's one logarithm.
        let h = L::from_fn(|k| points[k].y);
        let above = h.gt(L::splat(c.roughness));
        let height = L::select(h.lt(L::splat(f32::MAX)), h, L::splat(f32::MAX));
        let ratio = profile::ln_lanes(height) - L::splat(self.log_roughness);
        let ratio = L::select(ratio.gt(L::splat(0.0)), ratio, L::splat(0.0));
        let log_ratio = L::select(above, ratio, L::splat(0.0));
        // Mean speed, turbulence scale and advection speed at this height.
        let g = log_ratio * L::splat(self.inv_log_reference); // eq. 14
        let reference = L::splat(c.reference_speed);
        let mean = reference * g;
        // `travel`: how the pattern's travel at this height compares with the reference's.
        let (scale, advection, travel) = match c.spatial {
            SpatialMode::Plane => (g, reference, L::splat(1.0)),
            SpatialMode::Volume { .. } => {
                let one = L::splat(1.0);
                (L::select(g.lt(one), g, one), mean, g) // mean = (u*/κ) ln(h/z0), eq. 10
            }
        };
        let time = if time.is_finite() { time } else { 0.0 };
        // Taylor's hypothesis: the pattern translates with the mean wind, by ∫ U dt (the travel
        // booked before the last change of speed or direction, plus U × the time since).
        let coordinates = |k: usize| {
            let shift = f64::from(advection.get(k)) * (time - self.drift_since);
            let base = self.drift_base * f64::from(travel.get(k));
            let p = points[k];
            let x = (f64::from(p.x) - (base.x + f64::from(self.along.x) * shift)) * self.per_cell;
            let z = (f64::from(p.z) - (base.y + f64::from(self.along.z) * shift)) * self.per_cell;
            (x, z)
        };
        let n = if self.shape.dims().len() == 2 {
            self.plane_lanes::<L>(&coordinates)
        } else {
            let noise: [Vec3; 4] = std::array::from_fn(|k| {
                if k < L::WIDTH {
                    let (x, z) = coordinates(k);
                    self.sample_nd(points[k], time, x, z)
                } else {
                    Vec3::ZERO
                }
            });
            V3::new(
                L::from_fn(|k| noise[k].x),
                L::from_fn(|k| noise[k].y),
                L::from_fn(|k| noise[k].z),
            )
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
            wind.scale(L::splat(c.pulse.factor(time)))
        } else {
            wind
        }
    }

    /// The turbulence of a 2-D grid at each lane's node coordinates: the periodic wraps and the
    /// four nodes point by point, the bilinear weights in lanes.
    fn plane_lanes<L: Lane>(&self, coordinates: &dyn Fn(usize) -> (f64, f64)) -> V3<L> {
        let dims = self.shape.dims();
        let corners: [([usize; 4], f32, f32); 4] = std::array::from_fn(|k| {
            if k >= L::WIDTH {
                return ([0; 4], 0.0, 0.0);
            }
            let (x, z) = coordinates(k);
            let (i0, i1, fx) = wrap(x, dims[0]);
            let (j0, j1, fy) = wrap(z, dims[1]);
            let (r0, r1) = (i0 * dims[1], i1 * dims[1]);
            ([r0 + j0, r0 + j1, r1 + j0, r1 + j1], fx, fy)
        });
        let node = |corner: usize| {
            let v = |axis: usize| L::from_fn(|k| self.nodes[corners[k].0[corner]][axis]);
            V3::new(v(0), v(1), v(2))
        };
        let fx = L::from_fn(|k| corners[k].1);
        let fy = L::from_fn(|k| corners[k].2);
        let (gx, gy) = (L::splat(1.0) - fx, L::splat(1.0) - fy);
        let low = node(0).scale(gy).add(node(1).scale(fy));
        let high = node(2).scale(gy).add(node(3).scale(fy));
        low.scale(gx).add(high.scale(fx))
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
