//! The air's load on a particle cloth each substep: each node's normal, its pressure's force
//! rates (smoothed and local) and its skin-friction rate.

use bevy::math::Vec3;

use super::ParticleCloth;

/// Skin friction coefficient of each side of the cloth: Prandtl's turbulent flat plate,
/// 0.074 Re^−1/5, at the Re ≈ 10⁶ of a flag a metre or two long in a breeze.
const SKIN_FRICTION: f32 = 0.005;

/// Largest force rate, kg/s: keeps every rate, and its product with a finite velocity, finite.
const MOST_RATE: f32 = 1e30;

impl ParticleCloth {
    /// Each node's unit normal from its neighbours along the row and the column (one-sided at
    /// the edges; zero where the sheet is degenerate), on the side +Z is at rest.
    pub(super) fn normals_into(&self, normals: &mut Vec<Vec3>) {
        self.normals_at(&self.positions, normals);
    }

    /// [`ParticleCloth::normals_into`] for the nodes at `p` instead of where they are.
    pub(super) fn normals_at(&self, p: &[Vec3], normals: &mut Vec<Vec3>) {
        let (rows, columns) = (self.grid.rows, self.grid.columns);
        normals.clear();
        normals.extend((0..rows).flat_map(|k| {
            let (above, below) = (
                k.saturating_sub(1) * columns,
                (k + 1).min(rows - 1) * columns,
            );
            let row = k * columns;
            (0..columns).map(move |j| {
                let along = p[row + (j + 1).min(columns - 1)] - p[row + j.saturating_sub(1)];
                let up = p[above + j] - p[below + j];
                let n = along.cross(up).normalize_or_zero();
                if n.is_finite() { n } else { Vec3::ZERO }
            })
        }));
    }

    /// The force rates of the pressure and the skin-friction rate of every node, from the
    /// velocities, normals and wind at the start of the substep. With w = v_rel · n =
    /// |v_rel| sin α the face law's normal share A p = ½ ρ A |v_rel|² (C_D sin²α +
    /// C_L sin α cos²α) sgn w is (L + K) w: L = ½ ρ A |v_rel| C_L cos²α, smoothed over the
    /// sheet, and K = ½ ρ A |v_rel| C_D sin α, local (A the node's area). Skin friction
    /// c = ρ C_f A |v_t − u_t| (both sides).
    pub(super) fn loads(&mut self) {
        let c = self.coefficients;
        for i in 0..self.positions.len() {
            let (n, u) = (self.normals[i], self.wind[i]);
            let rel = self.velocities[i] - u;
            let speed = rel.length();
            let along = rel.dot(n);
            let sine = if speed > 0.0 {
                (along.abs() / speed).min(1.0)
            } else {
                0.0
            };
            let area = self.areas[i];
            let rate = |slope: f32| {
                let d = (0.5 * c.density * area * speed * slope).min(MOST_RATE);
                if d.is_finite() { d } else { 0.0 }
            };
            self.lift_rate[i] = rate(c.lift * (1.0 - sine * sine));
            self.drag_rate[i] = rate(c.drag * sine);
            let f = c.density * SKIN_FRICTION * area * (rel - n * along).length();
            self.friction[i] = if f.is_finite() { f.min(MOST_RATE) } else { 0.0 };
        }
        if let Some(air) = &mut self.reactive {
            air.measure(&self.positions, &self.velocities, &self.wind);
        }
    }
}
