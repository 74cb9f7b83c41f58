//! The air's load on a particle cloth each substep: the face law per triangle (lift, smoothed
//! over the sheet; pressure drag along each node's normal) and skin friction along the sheet.

use bevy::math::Vec3;

use super::super::force::face_force;
use super::ParticleCloth;
use super::screen::screen_grid;

/// Skin friction coefficient of each side of the cloth: Prandtl's turbulent flat plate,
/// 0.074 Re^−1/5, at the Re ≈ 10⁶ of a flag a metre or two long in a breeze.
const SKIN_FRICTION: f32 = 0.005;
/// The face law's lift is smoothed over this fraction of the cloth's smaller side (see
/// [`screen_grid`]): waves shorter than about the span are driven less, as the air flows round
/// a finite sheet's edges. Half the span puts a flag's waves at about 1.8 of its length where
/// flags' are 1.87 (Raynaud & Mulleners 2026, 48 paper flags of several aspect ratios).
const LIFT_SMOOTHING: f32 = 0.5;

impl ParticleCloth {
    /// Lift per node (smoothed), pressure-drag rate and normal per node from every triangle, and
    /// skin-friction rate per node; returns the largest lift rate (1/s).
    pub(super) fn loads(&mut self) -> f32 {
        let c = self.coefficients;
        let columns = self.grid.columns;
        self.lift.fill(Vec3::ZERO);
        self.drag.fill(0.0);
        self.normals.fill(Vec3::ZERO);
        let mut rate = 0.0f32;
        for k in 0..self.grid.rows - 1 {
            for j in 0..columns - 1 {
                let a = k * columns + j;
                let (b, cc, d) = (a + columns, a + 1, a + columns + 1);
                for [p, q, r] in [[a, b, cc], [cc, b, d]] {
                    let (xp, xq, xr) = (self.positions[p], self.positions[q], self.positions[r]);
                    let cross = (xq - xp).cross(xr - xp);
                    let area = 0.5 * cross.length();
                    let v = (self.velocities[p] + self.velocities[q] + self.velocities[r]) / 3.0;
                    let u = (self.wind[p] + self.wind[q] + self.wind[r]) / 3.0;
                    let rel = v - u;
                    let lift = face_force(rel, cross, area, 0.0, c.lift, c.density);
                    let speed = rel.length();
                    let k_drag = if speed > 0.0 {
                        face_force(rel, cross, area, c.drag, 0.0, c.density).length() / speed
                    } else {
                        0.0
                    };
                    // Area-weighted, and the same side for all: the grid's winding.
                    let normal = if cross.is_finite() { cross } else { Vec3::ZERO };
                    for node in [p, q, r] {
                        self.lift[node] += lift / 3.0;
                        self.drag[node] += k_drag / 3.0;
                        self.normals[node] += normal;
                    }
                    let r = c.density * c.lift * area * speed / self.node_mass;
                    if r.is_finite() {
                        rate = rate.max(r);
                    }
                }
            }
        }
        let node_area = self.grid.width * self.grid.height / self.positions.len() as f32;
        let per_speed = c.density * SKIN_FRICTION * node_area;
        for i in 0..self.positions.len() {
            let n = self.normals[i].normalize_or_zero();
            self.normals[i] = n;
            let rel = self.velocities[i] - self.wind[i];
            let along = (rel - n * rel.dot(n)).length();
            let f = per_speed * along;
            self.friction[i] = if f.is_finite() { f } else { 0.0 };
        }
        let spacing = (self.grid.segment(), self.grid.row_spacing());
        let length = LIFT_SMOOTHING * self.grid.width.min(self.grid.height);
        screen_grid(
            &mut self.lift,
            self.grid.rows,
            columns,
            spacing,
            length,
            &mut self.scratch,
        );
        rate
    }
}
