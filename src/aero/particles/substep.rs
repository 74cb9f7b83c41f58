//! One substep of a particle cloth: the velocity update (gravity, lift, implicit pressure drag
//! with the added mass across the sheet, implicit skin friction along it), then XPBD projection
//! of the constraints and the tethers, and velocities from the moved positions.

use bevy::math::Vec3;

use super::{ParticleCloth, STRETCH_TOLERANCE};

impl ParticleCloth {
    pub(super) fn substep(&mut self, h: f32, gravity: Vec3) {
        let m = self.node_mass;
        self.previous.copy_from_slice(&self.positions);
        for i in 0..self.positions.len() {
            if self.inverse_mass[i] == 0.0 {
                // Held: the air's push on it goes into the pin (and into the force).
                let (u, n) = (self.wind[i], self.normals[i]);
                let held = self.lift[i] + n * (self.drag[i] * u.dot(n));
                let held = held + self.friction[i] * (u - n * u.dot(n));
                if held.is_finite() {
                    self.force += h * held;
                }
                self.velocities[i] = Vec3::ZERO;
                continue;
            }
            let (k, f, n) = (self.drag[i], self.friction[i], self.normals[i]);
            // Lift may turn the node's relative velocity by at most 1/4 rad per substep: a
            // limiter that only binds when the substep cap is reached (gales, huge steps).
            let mut lift = self.lift[i] / m;
            let most = 0.25 * (self.velocities[i] - self.wind[i]).length() / h;
            if lift.length() > most {
                lift = lift.normalize_or_zero() * most;
            }
            // Across the sheet a node moves its added mass of air too: every force's share
            // along the normal accelerates m + m_a. Implicit: pressure drag along the normal,
            // skin friction along the sheet.
            let before = self.velocities[i].dot(n);
            let v = self.velocities[i] + h * (gravity + lift);
            let u = self.wind[i];
            let (v_n, u_n) = (v.dot(n), u.dot(n));
            let inertia = m + self.added_mass;
            let carried = before + (v_n - before) * (m / inertia);
            let normal = (carried + h * k * u_n / inertia) / (1.0 + h * k / inertia);
            let (v_t, u_t) = (v - n * v_n, u - n * u_n);
            let along = (v_t + h * f * u_t / m) / (1.0 + h * f / m);
            let v = along + n * normal;
            if v.is_finite() {
                self.velocities[i] = v;
                self.force += h * (m * lift + n * (k * (u_n - normal)) + f * (u_t - along));
            } else {
                self.velocities[i] = Vec3::ZERO;
            }
            self.positions[i] += h * self.velocities[i];
        }
        // XPBD: λ per constraint starts at zero each substep.
        self.lambdas.clear();
        self.lambdas.resize(self.constraints.len(), 0.0);
        // At least `iterations` sweeps, more (to the cap) while a stretch edge is still more
        // than STRETCH_TOLERANCE off its length: a gale's loads need them, a breeze's do not.
        let fewest = self.iterations.clamp(1, ParticleCloth::MAX_ITERATIONS);
        for sweep in 0..ParticleCloth::MAX_ITERATIONS {
            let mut worst = 0.0f32;
            for (lambda, &(a, b, rest, compliance)) in
                self.lambdas.iter_mut().zip(&self.constraints)
            {
                let (a, b) = (a as usize, b as usize);
                let (wa, wb) = (self.inverse_mass[a], self.inverse_mass[b]);
                let delta = self.positions[a] - self.positions[b];
                let length = delta.length();
                if wa + wb == 0.0 || length <= 1e-12 || !length.is_finite() {
                    continue;
                }
                if compliance == 0.0 {
                    worst = worst.max((length - rest).abs() / rest);
                }
                let alpha = compliance / (h * h);
                let dl = (-(length - rest) - alpha * *lambda) / (wa + wb + alpha);
                *lambda += dl;
                let n = delta / length;
                self.positions[a] += wa * dl * n;
                self.positions[b] -= wb * dl * n;
            }
            if sweep + 1 >= fewest && (worst <= STRETCH_TOLERANCE || worst.is_nan()) {
                break;
            }
        }
        for &(node, pin, rest) in &self.tethers {
            let (node, pin) = (node as usize, pin as usize);
            let delta = self.positions[node] - self.positions[pin];
            let length = delta.length();
            if length > rest && length.is_finite() {
                self.positions[node] = self.positions[pin] + delta * (rest / length);
            }
        }
        for ((v, p), q) in self
            .velocities
            .iter_mut()
            .zip(&self.positions)
            .zip(&self.previous)
        {
            *v = (*p - *q) / h;
        }
    }
}
