//! One substep of a particle cloth: velocities with the air implicit and the nodes' inertia
//! m I + m_a n nᵀ, the constraints on the predicted positions with the same inertia, velocities
//! from the moved positions, and the normals brought up to date with the carried air's energy
//! kept.
//!
//! Under the pressure (the default air) the air's two stiff terms are taken at the substep's
//! midpoint, so ticks of 1 to 4 ms give the same flapping within 5 %: each free node's wind
//! share along the normal, u · n, is read along the normal halfway to where the velocities take
//! the nodes (normalize(n + n̂), n̂ the normals of x + h v; the wind's load follows the sheet as
//! it turns; a held node, or one whose normal would turn past a right angle, reads its own
//! normal), and the pressure's solve is Crank–Nicolson,
//! θ = ½ (see [`midpoint_share`]).

use bevy::math::Vec3;

use super::constraints::{Inertia, project_bending, project_distances, project_tethers};
use super::pressure::{Loads, smoothed_pressure};
use super::screen::Screen;
use super::{ParticleCloth, Pinning, STRETCH_TOLERANCE, reactive};

/// The pressure is smoothed over this fraction of the cloth's smaller side (see [`Screen`]):
/// fitted with the added mass to the flapping flag's drag and waves (docs/aero.md).
const PRESSURE_SMOOTHING: f32 = 0.25;

/// Most linearisations of the yarns per sweep.
const MOST_LINEARISATIONS: usize = 4;

/// The share θ of the substep's reach the pressure's solve reads: ½, the midpoint
/// (Crank–Nicolson, second order), raised to 1 − 1/x once x = h (L + K) / (m + m_a) passes 2
/// so a node's normal velocity relative to the air, w* (1 − (1 − θ)x) / (1 + θx) under the
/// local rate alone, never reverses (past x = 2 stiff air stops it: w′ = 0). The
/// velocity update keeps the full reach: the power of the force, −F · (w* + w′) / 2 over the
/// substep, is never positive, so still air still only takes energy out.
fn midpoint_share(x: f32) -> f32 {
    if x > 2.0 { 1.0 - 1.0 / x } else { 0.5 }
}

impl ParticleCloth {
    /// One substep of `h` (after [`ParticleCloth::loads`]); returns the largest relative
    /// stretch of a yarn edge it left.
    pub(super) fn substep(&mut self, h: f32, gravity: Vec3) -> f32 {
        let m = self.node_mass;
        let by_pressure = self.reactive.is_none();
        if by_pressure {
            // The normals where the velocities take the nodes (`previous` as scratch).
            for ((ahead, x), v) in self
                .previous
                .iter_mut()
                .zip(&self.positions)
                .zip(&self.velocities)
            {
                *ahead = *x + h * *v;
            }
            let mut ahead = std::mem::take(&mut self.ahead_normals);
            self.normals_at(&self.previous, &mut ahead);
            self.ahead_normals = ahead;
        }
        self.previous.copy_from_slice(&self.positions);
        // Gravity (its share along n moving m + m_a) and skin friction (implicit, along the
        // sheet); the normal velocity relative to the air before the pressure, the wind's
        // share read at the midpoint's normal under the pressure.
        for i in 0..self.positions.len() {
            let (n, u) = (self.normals[i], self.wind[i]);
            if self.inverse_mass[i] == 0.0 {
                self.relative[i] = -u.dot(n);
                self.reach[i] = 0.0;
                continue;
            }
            let (c, m_a) = (self.friction[i], self.added_mass[i]);
            let v = self.velocities[i];
            let (v_n, g_n, u_n) = (v.dot(n), gravity.dot(n), u.dot(n));
            let (v_t, g_t, u_t) = (v - n * v_n, gravity - n * g_n, u - n * u_n);
            let along = (m * (v_t + h * g_t) + h * c * u_t) / (m + h * c);
            let normal = v_n + h * g_n * m / (m + m_a);
            self.velocities[i] = along + n * normal;
            // Halfway through a turn of less than a right angle; past it (a whipping edge's
            // normal flipping within a substep) the start's normal.
            let ahead = if by_pressure {
                self.ahead_normals[i]
            } else {
                Vec3::ZERO
            };
            let wind_n = if n.dot(ahead) > 0.0 {
                u.dot((n + ahead).normalize_or(n))
            } else {
                u_n
            };
            self.relative[i] = normal - wind_n;
            self.reach[i] = h / (m + m_a);
        }
        if let Some(air) = &mut self.reactive {
            air.solve(h, &self.drag_rate, &self.relative, &mut self.pressure);
        } else {
            for (((midpoint, c), l), k) in self
                .midpoint_reach
                .iter_mut()
                .zip(&self.reach)
                .zip(&self.lift_rate)
                .zip(&self.drag_rate)
            {
                *midpoint = midpoint_share(c * (l + k)) * c;
            }
            let loads = Loads {
                lift: &self.lift_rate,
                drag: &self.drag_rate,
                relative: &self.relative,
                reach: &self.midpoint_reach,
            };
            let screen = self.screen();
            smoothed_pressure(
                loads,
                &screen,
                &mut self.pressure_scratch,
                &mut self.pressure,
            );
        }
        for i in 0..self.positions.len() {
            let (n, u, p) = (self.normals[i], self.wind[i], self.pressure[i]);
            let c = self.friction[i];
            let u_t = u - n * u.dot(n);
            let v = match &self.reactive {
                Some(air) => self.velocities[i] + n * (air.after()[i] - self.relative[i]),
                None => self.velocities[i] - n * (self.reach[i] * p),
            };
            let pinned = self.inverse_mass[i] == 0.0;
            // A held node's push goes into the pin (and into the force).
            let v_t = if pinned { Vec3::ZERO } else { v - n * v.dot(n) };
            let force = -n * p + c * (u_t - v_t);
            if force.is_finite() {
                self.force += h * force;
            }
            self.velocities[i] = if pinned || !v.is_finite() {
                Vec3::ZERO
            } else {
                v
            };
            self.positions[i] += h * self.velocities[i];
        }
        let strain = self.project(h);
        for ((v, p), q) in self
            .velocities
            .iter_mut()
            .zip(&self.positions)
            .zip(&self.previous)
        {
            *v = (*p - *q) / h;
        }
        self.turn_normals();
        strain
    }

    /// The pressure's filter over [`PRESSURE_SMOOTHING`] of the smaller side: no flux past the
    /// ends of the yarns from the pins, falling to zero past the sheet's sides.
    fn screen(&self) -> Screen {
        let length = PRESSURE_SMOOTHING * self.grid.width.min(self.grid.height);
        let (free_rows, free_columns) = match self.pinning {
            Pinning::PoleColumn => ((false, false), (true, true)),
            Pinning::TopRow => ((true, true), (false, false)),
        };
        Screen {
            rows: self.grid.rows,
            columns: self.grid.columns,
            along_rows: (length / self.grid.segment()).powi(2),
            along_columns: (length / self.grid.row_spacing()).powi(2),
            free_rows,
            free_columns,
        }
    }

    /// The constraints, [`ParticleCloth::iterations`] sweeps: bending, shear, then the yarns and
    /// the attachments, linearised again while an edge is more than [`STRETCH_TOLERANCE`] off
    /// its length. Returns the largest relative stretch left.
    fn project(&mut self, h: f32) -> f32 {
        let inertia = Inertia {
            inverse_mass: &self.inverse_mass,
            normals: &self.normals,
            beta: &self.beta,
        };
        let x = &mut self.positions;
        self.shear_lambdas.fill(0.0);
        self.bend_lambdas.fill(Vec3::ZERO);
        let mut strain = 0.0;
        for sweep in 0..self.iterations.clamp(1, ParticleCloth::MAX_ITERATIONS) {
            project_bending(
                x,
                inertia,
                &self.bends,
                &mut self.bend_lambdas,
                &self.bend_runs,
                h,
            );
            project_distances(
                x,
                inertia,
                &self.shear,
                &mut self.shear_lambdas,
                &self.shear_runs,
                h,
            );
            for linearisation in 0..MOST_LINEARISATIONS {
                let warm = (sweep == 0 && linearisation == 0).then_some(h);
                self.yarns.project(x, inertia, warm);
                project_tethers(x, inertia, &self.tethers);
                strain = self.yarns.max_strain(x);
                if strain <= STRETCH_TOLERANCE {
                    break;
                }
            }
        }
        strain
    }

    /// Each node's normal from the moved positions, its velocity along the new normal set so
    /// that ½ m |v|² + ½ m_a (v · n)² is what it was with the normal its substep used. With the
    /// reactive air, the carried air's momentum relative to the wind, m_a (v − u) · n, also
    /// answers the normal's turn in the wind: Δ(v · n) (m + m_a) gains m_a S(u · Δn), the share
    /// of Lighthill's −∂ₜ(m_a w) that the nodes' inertia along n does not hold, screened along
    /// the yarns as the flux is (in linear theory the two make the air's Coriolis-like force
    /// −2 m_a U ∂ₓ∂ₜy on a wave, each half kept by the same share 1 / (1 + k²ℓ²)).
    fn turn_normals(&mut self) {
        let mut fresh = std::mem::take(&mut self.fresh_normals);
        self.normals_into(&mut fresh);
        let m = self.node_mass;
        if let Some(air) = &mut self.reactive {
            air.turn(&self.wind, &self.normals, &fresh);
        }
        let turned = self.reactive.as_ref().map(reactive::ReactiveAir::turned);
        for (i, ((v, (old, new)), (w, m_a))) in self
            .velocities
            .iter_mut()
            .zip(self.normals.iter().zip(&fresh))
            .zip(self.inverse_mass.iter().zip(&self.added_mass))
            .enumerate()
        {
            if *w == 0.0 || *m_a == 0.0 {
                continue;
            }
            let (was, is) = (v.dot(*old), v.dot(*new));
            let size = ((m * is * is + m_a * was * was) / (m + m_a)).sqrt();
            let sign = if is != 0.0 { is.signum() } else { was.signum() };
            let moved = match turned {
                Some(turned) => {
                    let carried = m_a * turned[i] / (m + m_a);
                    *v + *new * (sign * size - is + carried)
                }
                None => *v + *new * (sign * size - is),
            };
            if moved.is_finite() {
                *v = moved;
            }
        }
        self.fresh_normals = std::mem::replace(&mut self.normals, fresh);
    }
}
