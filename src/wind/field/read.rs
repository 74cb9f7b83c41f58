//! Reading the [`WindField`]: the log law, Taylor's travel, the periodic grid, shelters and local
//! sources, at one point or many.

use bevy::math::Vec3;

use super::WindField;
use super::profile;
use crate::spectrum::{periodic_lerp, periodic_lerp_2d};
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

    /// [`Self::velocity_at`] for many points: `out` is cleared and filled in order.
    pub fn velocities_at(&self, positions: &[Vec3], time: f32, out: &mut Vec<Vec3>) {
        out.clear();
        out.extend(positions.iter().map(|&p| self.sample(p, f64::from(time))));
    }

    /// The global field, calmed by every shelter.
    fn sheltered(&self, position: Vec3, time: f64) -> Vec3 {
        let global = self.global(position, time);
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
        let global = self.sheltered(position, time);
        if self.sources.is_empty() {
            return global;
        }
        let time = if time.is_finite() { time } else { self.time };
        let p = position.into();
        let local = self
            .sources
            .iter()
            .fold(Vec3::ZERO, |sum, s| sum + s.velocity(p, time));
        let total = global + local;
        if total.is_finite() { total } else { global }
    }

    /// The log-law mean wind plus turbulence (no sources).
    fn global(&self, position: Vec3, time: f64) -> Vec3 {
        self.global_with(position, self.log_ratio(position.y), time)
    }

    /// max(0, ln(h/z0)) at `height`: the one logarithm of a read.
    #[inline]
    fn log_ratio(&self, height: f32) -> f32 {
        if height > self.config.roughness {
            (profile::ln(height.min(f32::MAX)) - self.log_roughness).max(0.0)
        } else {
            0.0
        }
    }

    /// [`Self::global`] with the read's [`Self::log_ratio`] already taken. Kept out of line, the
    /// logarithm's library call made by the small caller: compiled as one function with it,
    /// 10 000 plane reads took 415 µs instead of 315 µs (`cargo bench --bench freefall --
    /// wind_sampling_only`, the machine of `docs/performance.md`; the arithmetic is the same,
    /// the compiler's register allocation is not).
    #[inline(never)]
    fn global_with(&self, position: Vec3, log_ratio: f32, time: f64) -> Vec3 {
        let c = &self.config;
        // Mean speed, turbulence scale and advection speed at this height.
        let g = log_ratio * self.inv_log_reference; // eq. 14
        // `travel`: how the pattern's travel at this height compares with the reference's.
        let (mean, scale, advection, travel) = match c.spatial {
            SpatialMode::Plane => (c.reference_speed * g, g, c.reference_speed, 1.0),
            SpatialMode::Volume { .. } => {
                let mean = c.reference_speed * g; // = (u*/κ) ln(h/z0), eq. 10
                (mean, g.min(1.0), mean, g)
            }
        };
        let time = if time.is_finite() { time } else { 0.0 };
        // Taylor's hypothesis: the pattern translates with the mean wind, by ∫ U dt (the travel
        // booked before the last change of speed or direction, plus U × the time since).
        let shift = f64::from(advection) * (time - self.drift_since);
        let base = self.drift_base * f64::from(travel);
        let per_cell = self.per_cell;
        let x = (f64::from(position.x) - (base.x + f64::from(self.along.x) * shift)) * per_cell;
        let z = (f64::from(position.z) - (base.y + f64::from(self.along.z) * shift)) * per_cell;
        let n = if self.shape.dims().len() == 2 {
            periodic_lerp_2d(&self.shape, &self.nodes, x, z)
        } else {
            self.sample_nd(position, time, x, z)
        } * scale
            * self.sigma();
        let wind = self.along * (mean + n.x) + self.across * n.y + Vec3::Y * n.z;
        if c.pulse.is_active() {
            wind * c.pulse.factor(time)
        } else {
            wind
        }
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
