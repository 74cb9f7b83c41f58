//! How a [`RigidPlate`] moves: the per-face load of eq. 3.1 summed into a force and a torque,
//! and the six-degree-of-freedom step with implicit drag that never gains energy from still air.

use bevy::math::{Mat3, Quat, Vec3};

use super::super::force::{drag_rate, face_force};
use super::{LIFT_STEP, PlateState, RigidPlate};

impl RigidPlate {
    /// Kinetic plus potential energy, J (potential measured from the origin against
    /// `gravity`).
    pub fn energy(&self, s: &PlateState, gravity: Vec3) -> f32 {
        let (kinetic, potential) = self.energy_terms(s, gravity);
        kinetic + potential
    }

    /// Kinetic (translation and rotation) and potential energy, J.
    pub fn energy_terms(&self, s: &PlateState, gravity: Vec3) -> (f32, f32) {
        let inertia = self.world_inertia(s.rotation);
        (
            0.5 * self.mass * s.velocity.length_squared()
                + 0.5 * s.angular_velocity.dot(inertia * s.angular_velocity),
            -self.mass * gravity.dot(s.position),
        )
    }

    fn world_inertia(&self, rotation: Quat) -> Mat3 {
        let r = Mat3::from_quat(rotation);
        r * Mat3::from_diagonal(self.inertia) * r.transpose()
    }

    /// Total aerodynamic force and torque (about the centre of mass) in `s`, with `wind(p)` the
    /// fluid velocity at a world point.
    pub fn aero_load(&self, s: &PlateState, wind: &impl Fn(Vec3) -> Vec3) -> (Vec3, Vec3) {
        let c = &self.coefficients;
        let mut force = Vec3::ZERO;
        let mut torque = Vec3::ZERO;
        for face in &self.faces {
            let r = s.rotation * face.center;
            let v = s.velocity + s.angular_velocity.cross(r);
            let f = face_force(
                v - wind(s.position + r),
                s.rotation * face.normal,
                face.area,
                c.drag,
                c.lift,
                c.density,
            );
            force += f;
            torque += r.cross(f);
        }
        (force, torque)
    }

    /// Advances `s` by `dt` under `gravity` and the fluid moving at `wind(p)`.
    ///
    /// Each substep solves the drag implicitly (a 6×6 linear system in the new linear and angular
    /// velocity with each face's drag coefficient frozen: unconditionally stable, and in a
    /// uniform wind it relaxes toward the wind without overshoot) and takes the lift explicitly,
    /// with substeps so that h × lift rate ≤ 0.25. Aerodynamic forces without wind only
    /// remove energy (drag opposes each face's motion, lift is perpendicular to it); when
    /// `wind_is_still` is true, or the wind is the same at every face, a substep that would add
    /// energy (in the wind's frame) through rounding or the explicit lift has its velocities
    /// relative to the wind scaled back so that this energy does not grow.
    ///
    /// A non-finite or non-positive `dt`, a non-finite `gravity` or a state that fails
    /// [`PlateState::validate`] leaves `s` as it is (the plugin reports such a body with
    /// [`AeroBodyInvalid`](crate::aero::AeroBodyInvalid)).
    pub fn step(
        &self,
        s: &mut PlateState,
        dt: f32,
        gravity: Vec3,
        wind: &impl Fn(Vec3) -> Vec3,
        wind_is_still: bool,
    ) {
        if !(dt.is_finite() && dt > 0.0 && gravity.is_finite()) || s.validate().is_err() {
            return;
        }
        if let Some(rotation) = crate::guard::unit_quat(s.rotation) {
            s.rotation = rotation;
        }
        let mut remaining = dt;
        for i in 0..RigidPlate::MAX_SUBSTEPS {
            let rate = self.lift_rate(s, wind);
            // The last substep takes what is left, with the lift scaled down so that it still
            // turns v_rel by at most LIFT_STEP (a limiter that acts only on bodies whose lift
            // rate exceeds RigidPlate::MAX_SUBSTEPS × LIFT_STEP / dt, e.g. a 2 mm foil in water).
            let (h, lift_scale) = if i + 1 == RigidPlate::MAX_SUBSTEPS {
                let h = remaining;
                (h, (LIFT_STEP / (h * rate).max(1e-30)).min(1.0))
            } else {
                (remaining.min(LIFT_STEP / rate.max(1e-12)), 1.0)
            };
            let previous = *s;
            let frame = if wind_is_still {
                Some(Vec3::ZERO)
            } else {
                self.uniform_wind(s, wind)
            };
            self.substep(s, h, gravity, wind, lift_scale);
            if let Some(frame) = frame {
                self.no_energy_gain(s, &previous, gravity, frame);
            }
            remaining -= h;
            if remaining <= 0.0 {
                break;
            }
        }
    }

    /// The baseline the implicit [`RigidPlate::step`] is measured against: one semi-implicit
    /// (symplectic) Euler step with every force explicit, no substeps, no safeguard. Unstable
    /// once dt × ρ C_D A |v_rel| / m exceeds about 2.
    pub fn step_explicit(
        &self,
        s: &mut PlateState,
        dt: f32,
        gravity: Vec3,
        wind: &impl Fn(Vec3) -> Vec3,
    ) {
        let (force, torque) = self.aero_load(s, wind);
        let inertia = self.world_inertia(s.rotation);
        let spin = inertia * s.angular_velocity;
        s.velocity += dt * (force / self.mass + gravity);
        let inverse = inertia.inverse();
        s.angular_velocity += dt * (inverse * (torque - s.angular_velocity.cross(spin)));
        s.position += dt * s.velocity;
        s.rotation = (Quat::from_scaled_axis(dt * s.angular_velocity) * s.rotation).normalize();
    }

    /// The largest rate at which lift turns a face's relative velocity, 1/s, with the lever arm
    /// over the radius of gyration for the rotational part.
    fn lift_rate(&self, s: &PlateState, wind: &impl Fn(Vec3) -> Vec3) -> f32 {
        let c = &self.coefficients;
        let min_inertia = self.inertia.min_element();
        let mut rate = 0.0f32;
        for face in &self.faces {
            let r = s.rotation * face.center;
            let v = s.velocity + s.angular_velocity.cross(r) - wind(s.position + r);
            let k = drag_rate(v.length(), face.area, c.lift, c.density, self.mass);
            let lever = 1.0 + self.mass * r.length_squared() / min_inertia;
            rate = rate.max(k * lever * self.faces.len() as f32);
        }
        if rate.is_finite() { rate } else { f32::MAX }
    }

    fn substep(
        &self,
        s: &mut PlateState,
        h: f32,
        gravity: Vec3,
        wind: &impl Fn(Vec3) -> Vec3,
        lift_scale: f32,
    ) {
        let c = &self.coefficients;
        let inertia = self.world_inertia(s.rotation);
        // A (6×6, symmetric positive definite) [v'; ω'] = b.
        let mut a = [[0.0f64; 6]; 6];
        let mut b = [0.0f64; 6];
        let m = f64::from(self.mass);
        for i in 0..3 {
            a[i][i] = m;
            for j in 0..3 {
                a[3 + i][3 + j] = f64::from(inertia.col(j)[i]);
            }
        }
        let momentum = self.mass * s.velocity + h * self.mass * gravity;
        let spin = inertia * s.angular_velocity
            - h * s.angular_velocity.cross(inertia * s.angular_velocity);
        let mut rhs = [momentum, spin];
        for face in &self.faces {
            let r = s.rotation * face.center;
            let u = wind(s.position + r);
            let v = s.velocity + s.angular_velocity.cross(r);
            let rel = v - u;
            let speed = rel.length();
            let normal = s.rotation * face.normal;
            // Lift alone (explicit) and the drag coefficient K (F_D = −K v_rel).
            let lift = face_force(rel, normal, face.area, 0.0, c.lift * lift_scale, c.density);
            let k = if speed > 0.0 && speed.is_finite() {
                let drag = face_force(rel, normal, face.area, c.drag, 0.0, c.density);
                drag.length() / speed
            } else {
                0.0
            };
            rhs[0] += h * (lift + k * u);
            rhs[1] += h * r.cross(lift + k * u);
            // −h K J^T J with J [v; ω] = v − [r]× ω.
            let x = cross_matrix(r);
            let hk = f64::from(h * k);
            for i in 0..3 {
                a[i][i] += hk;
                for j in 0..3 {
                    let xij = f64::from(x.col(j)[i]);
                    a[i][3 + j] -= hk * xij;
                    a[3 + i][j] += hk * xij;
                    // −X X = Xᵀ X.
                    let xtx: f64 = (0..3)
                        .map(|l| f64::from(x.col(i)[l]) * f64::from(x.col(j)[l]))
                        .sum();
                    a[3 + i][3 + j] += hk * xtx;
                }
            }
        }
        for i in 0..3 {
            b[i] = f64::from(rhs[0][i]);
            b[3 + i] = f64::from(rhs[1][i]);
        }
        let Some(x) = solve6(a, b) else {
            return;
        };
        let v = Vec3::new(x[0] as f32, x[1] as f32, x[2] as f32);
        let w = Vec3::new(x[3] as f32, x[4] as f32, x[5] as f32);
        if !(v.is_finite() && w.is_finite()) {
            return;
        }
        s.velocity = v;
        s.angular_velocity = w;
        s.position += h * v;
        s.rotation = (Quat::from_scaled_axis(h * w) * s.rotation).normalize();
    }

    /// The wind at the faces if it is the same at all of them (to 1e-6 relative), else `None`.
    fn uniform_wind(&self, s: &PlateState, wind: &impl Fn(Vec3) -> Vec3) -> Option<Vec3> {
        let u = wind(s.position);
        let tolerance = 1e-6 * u.length() + 1e-9;
        self.faces
            .iter()
            .all(|f| wind(s.position + s.rotation * f.center).distance(u) <= tolerance)
            .then_some(u)
    }

    /// In a uniform wind `frame` (still air is `frame` = 0) aerodynamic forces only remove
    /// energy measured in the wind's frame. If a substep added some (rounding, or the explicit
    /// lift's turn of v_rel), the velocities relative to the wind are scaled so the energy is
    /// that of `previous`; if even zero relative velocity would leave more (the substep climbed
    /// higher than its energy allows, at an apex), the body stays where it was, moving with the
    /// wind.
    fn no_energy_gain(
        &self,
        s: &mut PlateState,
        previous: &PlateState,
        gravity: Vec3,
        frame: Vec3,
    ) {
        let relative = |p: &PlateState| PlateState {
            velocity: p.velocity - frame,
            ..*p
        };
        let mut rel = relative(s);
        self.no_energy_gain_still(&mut rel, &relative(previous), gravity);
        *s = PlateState {
            velocity: rel.velocity + frame,
            ..rel
        };
    }

    /// [`Self::no_energy_gain`] in the frame where the air is still.
    fn no_energy_gain_still(&self, s: &mut PlateState, previous: &PlateState, gravity: Vec3) {
        let before = self.energy(previous, gravity);
        let after = self.energy(s, gravity);
        if after <= before || !before.is_finite() {
            return;
        }
        let inertia = self.world_inertia(s.rotation);
        let kinetic = 0.5 * self.mass * s.velocity.length_squared()
            + 0.5 * s.angular_velocity.dot(inertia * s.angular_velocity);
        let allowed = kinetic - (after - before);
        if allowed > 0.0 && kinetic > 0.0 {
            let k = (allowed / kinetic).sqrt();
            s.velocity *= k;
            s.angular_velocity *= k;
        } else {
            *s = PlateState {
                velocity: Vec3::ZERO,
                angular_velocity: Vec3::ZERO,
                ..*previous
            };
        }
    }
}

fn cross_matrix(r: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, r.z, -r.y),
        Vec3::new(-r.z, 0.0, r.x),
        Vec3::new(r.y, -r.x, 0.0),
    )
}

/// Gaussian elimination with partial pivoting; `None` if singular.
fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> Option<[f64; 6]> {
    for col in 0..6 {
        let pivot = (col..6).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 || !a[pivot][col].is_finite() {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        let pivot_row = a[col];
        for row in col + 1..6 {
            let f = a[row][col] / pivot_row[col];
            for (x, p) in a[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let sum: f64 = (row + 1..6).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - sum) / a[row][row];
    }
    Some(x)
}
