//! The falling-paper ODE of eq. 4 (Tanabe & Kaneko 1994) and its integrators.
//!
//! State: position (x, y) with y up, angle θ, velocities (u, v) and ω. With α = arctan(u/v),
//! β = α + θ, V² = u² + v², k = ±1 by the sign of sign(v)·sin β:
//!
//! ```text
//! u̇ = −(A⊥ sin²θ + A∥ cos²θ) u + (A⊥ − A∥) sinθ cosθ v + k K V² cosβ cosα
//! v̇ = −(A⊥ cos²θ + A∥ sin²θ) v + (A⊥ − A∥) sinθ cosθ u − k K V² cosβ sinα − g
//! ω̇ = −A⊥ ω − R V² cosβ sinβ
//! ```
//!
//! K stands for the paper's πρ_f L / m and R for its 3πρ_f (the printed text drops the lengths
//! and the mass). The printed equations have no gravity and, with y up and v < 0 while
//! falling, the opposite sign on the lift term; with that sign no parameter gives the
//! fluttering of the paper's Fig. 4a, with this one the model flutters (K small) or tumbles (K
//! large) as Tanabe and Kaneko report. The lift is perpendicular to (u, v), so only the damping
//! and gravity do work: the speed stays below max(V₀, g / A∥).

use super::error::FallError;
use crate::error::InvalidValue;

/// Parameters of eq. 4 (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TanabeKaneko {
    /// A⊥, damping across the plate, 1/s.
    pub a_perp: f64,
    /// A∥, damping along the plate, 1/s.
    pub a_par: f64,
    /// K, lift, 1/m.
    pub lift: f64,
    /// R, aerodynamic torque, 1/m².
    pub torque: f64,
    /// g, m/s².
    pub gravity: f64,
}

impl TanabeKaneko {
    /// Periodic fluttering with the damping of the paper's Fig. 4a (A⊥ = 4.1, A∥ = 0.9);
    /// swings of about ±0.9 rad every 0.45 s.
    pub const FLUTTER: Self = Self {
        a_perp: 4.1,
        a_par: 0.9,
        lift: 0.4,
        torque: 30.0,
        gravity: 9.81,
    };
    /// Tumbling: the same damping with twice the lift; θ grows without bound.
    pub const TUMBLE: Self = Self {
        a_perp: 4.1,
        a_par: 0.9,
        lift: 0.8,
        torque: 30.0,
        gravity: 9.81,
    };

    /// d/dt of `s`.
    pub fn derivative(&self, s: &OdeState) -> OdeState {
        let (sin_t, cos_t) = libm::sincos(s.theta);
        let (ap, aa) = (self.a_perp, self.a_par);
        let cross = (ap - aa) * sin_t * cos_t;
        let (lift_u, lift_v, torque) = self.lift_and_torque(s, sin_t, cos_t);
        OdeState {
            x: s.u,
            y: s.v,
            theta: s.omega,
            u: -(ap * sin_t * sin_t + aa * cos_t * cos_t) * s.u + cross * s.v + lift_u,
            v: -(ap * cos_t * cos_t + aa * sin_t * sin_t) * s.v + cross * s.u + lift_v
                - self.gravity,
            omega: -ap * s.omega + torque,
        }
    }

    /// The lift acceleration (perpendicular to (u, v)) and the aerodynamic angular acceleration.
    fn lift_and_torque(&self, s: &OdeState, sin_t: f64, cos_t: f64) -> (f64, f64, f64) {
        let (u, v) = (s.u, s.v);
        let v2 = u * u + v * v;
        let speed = v2.sqrt();
        // α = arctan(u/v) as a direction: (sin α, cos α) = ±(u, v)/V with the sign of v
        // (arctan's branch); (0, 1) at rest.
        let (sin_a, cos_a) = if speed > 0.0 {
            let sign = if v >= 0.0 { 1.0 } else { -1.0 };
            (sign * u / speed, sign * v / speed)
        } else {
            (0.0, 1.0)
        };
        // β = α + θ; k = ±1 by sign(v) sin β.
        let sin_b = sin_a * cos_t + cos_a * sin_t;
        let cos_b = cos_a * cos_t - sin_a * sin_t;
        let k = if (if v >= 0.0 { sin_b } else { -sin_b }) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        let lift = k * self.lift * v2 * cos_b;
        (
            lift * cos_a,
            -lift * sin_a,
            -self.torque * v2 * cos_b * sin_b,
        )
    }

    /// Fastest rate in the linearised system, 1/s: the damping and the lift and torque
    /// frequencies at speed `speed`. Explicit steps are stable for dt × rate below about 2.
    pub fn stiffness(&self, speed: f64) -> f64 {
        self.a_perp.abs().max(self.a_par.abs())
            + 2.0 * self.lift.abs() * speed
            + speed * self.torque.abs().sqrt()
    }
}

/// State of eq. 4.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OdeState {
    /// Horizontal position, m.
    pub x: f64,
    /// Height, m.
    pub y: f64,
    /// Angle of the plate from horizontal, rad.
    pub theta: f64,
    /// ẋ, m/s.
    pub u: f64,
    /// ẏ, m/s.
    pub v: f64,
    /// θ̇, rad/s.
    pub omega: f64,
}

impl OdeState {
    fn axpy(&self, h: f64, d: &Self) -> Self {
        Self {
            x: self.x + h * d.x,
            y: self.y + h * d.y,
            theta: self.theta + h * d.theta,
            u: self.u + h * d.u,
            v: self.v + h * d.v,
            omega: self.omega + h * d.omega,
        }
    }

    /// Speed √(u² + v²).
    pub fn speed(&self) -> f64 {
        (self.u * self.u + self.v * self.v).sqrt()
    }

    /// Every component finite.
    pub fn is_finite(&self) -> bool {
        [self.x, self.y, self.theta, self.u, self.v, self.omega]
            .iter()
            .all(|c| c.is_finite())
    }
}

/// How one step of eq. 4 is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Forward Euler, first order.
    Euler,
    /// Explicit midpoint (RK2), second order.
    Midpoint,
    /// Classical fourth-order Runge–Kutta (the paper's choice, §2.2).
    Rk4,
    /// Linearly implicit Euler: damping implicit (exact 2×2 solve), lift, torque and gravity
    /// explicit, then positions from the new velocities. First order; stable for any damping.
    SemiImplicit,
}

/// Largest dt × [`TanabeKaneko::stiffness`] an explicit substep may take.
pub(crate) const STABLE_RATE_STEP: f64 = 1.0;

/// Largest magnitude of a parameter [`step`] uses (1/s, 1/m, 1/m², m/s²): a million times any
/// plate's; beyond it the products of eq. 4 could overflow to NaN.
pub(crate) const MAX_PARAMETER: f64 = 1.0e6;

/// `params` with every value held to ±[`MAX_PARAMETER`] (NaN: 0).
fn bounded(params: &TanabeKaneko) -> TanabeKaneko {
    let b = |v: f64| {
        if v.is_nan() {
            0.0
        } else {
            v.clamp(-MAX_PARAMETER, MAX_PARAMETER)
        }
    };
    TanabeKaneko {
        a_perp: b(params.a_perp),
        a_par: b(params.a_par),
        lift: b(params.lift),
        torque: b(params.torque),
        gravity: b(params.gravity),
    }
}

/// Advances `state` by `dt` with `method` in substeps sized so that h × stiffness ≤
/// [`STABLE_RATE_STEP`] at the state each substep starts from (the speed, and so the lift and
/// torque rates, change within a step). After [`TanabeKaneko::MAX_SUBSTEPS`](crate::freefall::ode::TanabeKaneko::MAX_SUBSTEPS) the rest of the step is taken in
/// one [`Integrator::SemiImplicit`] substep, which is stable for any damping. Non-finite `dt` or
/// `dt ≤ 0` leaves the state unchanged; a longer `dt` than [`FallRelease::MAX_STEP`] is taken
/// as that (as [`FallPath::advance`] does), and parameters are held to ±1e6, so hostile input
/// never gives NaN.
///
/// [`FallRelease::MAX_STEP`]: FallRelease::MAX_STEP
/// [`FallPath::advance`]: super::FallPath::advance
///
/// Every substep then passes [`speed_limit`]: the lift switches sign where sin β crosses zero,
/// and explicit stages that straddle the switch add energy the ODE cannot (its lift is
/// perpendicular to the velocity); weakly damped, strongly lifted plates would otherwise speed
/// up without bound. The limit never binds on an accurate solution.
pub(crate) fn step(
    params: &TanabeKaneko,
    state: OdeState,
    dt: f64,
    method: Integrator,
) -> OdeState {
    if !(dt.is_finite() && dt > 0.0) {
        return state;
    }
    let params = &bounded(params);
    let mut s = state;
    let mut remaining = dt.min(f64::from(super::release::FallRelease::MAX_STEP));
    for i in 0..=TanabeKaneko::MAX_SUBSTEPS {
        let rate = params.stiffness(s.speed()).max(1e-12);
        let (h, method) = if i < TanabeKaneko::MAX_SUBSTEPS {
            (remaining.min(STABLE_RATE_STEP / rate), method)
        } else {
            (remaining, Integrator::SemiImplicit)
        };
        let next = single_step(params, &s, h, method);
        s = speed_limit(params, &s, next, h);
        remaining -= h;
        if remaining <= 0.0 {
            break;
        }
    }
    s
}

/// Caps the speed of `next` at what eq. 4 allows after `h` from `previous`: only damping
/// (≥ A_min = min(A⊥, A∥)) and gravity do work, so |v| ≤ g/A + (|v₀| − g/A) e^(−A h) above the
/// terminal speed g/A, ≤ g/A below it, and ≤ |v₀| + g h in any case.
pub(crate) fn speed_limit(
    params: &TanabeKaneko,
    previous: &OdeState,
    next: OdeState,
    h: f64,
) -> OdeState {
    let v0 = previous.speed();
    let g = params.gravity.abs();
    let damping = params.a_perp.min(params.a_par).max(0.0);
    let mut limit = v0 + g * h;
    if damping > 0.0 {
        let terminal = g / damping;
        let relaxed = if v0 > terminal {
            terminal + (v0 - terminal) * libm::exp(-damping * h)
        } else {
            terminal
        };
        limit = limit.min(relaxed);
    }
    let speed = next.speed();
    if speed > limit && speed.is_finite() {
        let k = limit / speed;
        OdeState {
            u: next.u * k,
            v: next.v * k,
            ..next
        }
    } else {
        next
    }
}

/// One step of size `h`, no splitting.
pub(crate) fn single_step(
    params: &TanabeKaneko,
    s: &OdeState,
    h: f64,
    method: Integrator,
) -> OdeState {
    match method {
        Integrator::Euler => s.axpy(h, &params.derivative(s)),
        Integrator::Midpoint => {
            let k1 = params.derivative(s);
            s.axpy(h, &params.derivative(&s.axpy(h / 2.0, &k1)))
        }
        Integrator::Rk4 => {
            let k1 = params.derivative(s);
            let k2 = params.derivative(&s.axpy(h / 2.0, &k1));
            let k3 = params.derivative(&s.axpy(h / 2.0, &k2));
            let k4 = params.derivative(&s.axpy(h, &k3));
            let mut out = *s;
            for (o, (a, (b, (c, d)))) in out.fields_mut().into_iter().zip(
                k1.fields().into_iter().zip(
                    k2.fields()
                        .into_iter()
                        .zip(k3.fields().into_iter().zip(k4.fields())),
                ),
            ) {
                *o += h / 6.0 * (a + 2.0 * b + 2.0 * c + d);
            }
            out
        }
        Integrator::SemiImplicit => semi_implicit(params, s, h),
    }
}

impl OdeState {
    fn fields(&self) -> [f64; 6] {
        [self.x, self.y, self.theta, self.u, self.v, self.omega]
    }

    fn fields_mut(&mut self) -> [&mut f64; 6] {
        [
            &mut self.x,
            &mut self.y,
            &mut self.theta,
            &mut self.u,
            &mut self.v,
            &mut self.omega,
        ]
    }
}

/// Linearly implicit step: the damping matrix D (eigenvalues A⊥, A∥ ≥ 0) is solved exactly,
/// the lift turns the velocity by the angle it would turn it in `h` (so it does no work, as in
/// the ODE), torque and gravity are explicit, and positions use the new velocities.
fn semi_implicit(params: &TanabeKaneko, s: &OdeState, h: f64) -> OdeState {
    let (sin_t, cos_t) = libm::sincos(s.theta);
    let (ap, aa) = (params.a_perp.max(0.0), params.a_par.max(0.0));
    let (lift_u, lift_v, torque) = params.lift_and_torque(s, sin_t, cos_t);
    // Rotate (u, v) by h × (angular rate of the lift): (v × L) / V².
    let v2 = s.u * s.u + s.v * s.v;
    let turn = if v2 > 0.0 {
        h * (s.u * lift_v - s.v * lift_u) / v2
    } else {
        0.0
    };
    let (sin_p, cos_p) = libm::sincos(turn);
    let bu = cos_p * s.u - sin_p * s.v;
    let bv = sin_p * s.u + cos_p * s.v - h * params.gravity;
    // Solve (I + hD) (u', v') = (bu, bv).
    let cross = (ap - aa) * sin_t * cos_t;
    let a11 = 1.0 + h * (ap * sin_t * sin_t + aa * cos_t * cos_t);
    let a22 = 1.0 + h * (ap * cos_t * cos_t + aa * sin_t * sin_t);
    let a12 = -h * cross;
    let det = a11 * a22 - a12 * a12;
    let u = (a22 * bu - a12 * bv) / det;
    let v = (a11 * bv - a12 * bu) / det;
    let omega = (s.omega + h * torque) / (1.0 + h * ap);
    OdeState {
        x: s.x + h * u,
        y: s.y + h * v,
        theta: s.theta + h * omega,
        u,
        v,
        omega,
    }
}

/// Integrates from `state` for `duration` in steps of `dt` and returns every state, the
/// first included.
///
/// # Errors
/// `dt` not finite and > 0, `duration` not finite and ≥ 0, or more than
/// [`TanabeKaneko::MAX_TRAJECTORY_STEPS`](crate::freefall::ode::TanabeKaneko::MAX_TRAJECTORY_STEPS) steps (checked before anything is allocated; the field named is
/// `dt`).
pub(crate) fn trajectory(
    params: &TanabeKaneko,
    state: OdeState,
    dt: f64,
    duration: f64,
    method: Integrator,
) -> Result<Vec<OdeState>, FallError> {
    InvalidValue::check(
        dt.is_finite() && dt > 0.0,
        "dt",
        dt as f32,
        "must be finite and > 0",
    )?;
    InvalidValue::check(
        duration.is_finite() && duration >= 0.0,
        "duration",
        duration as f32,
        "must be finite and ≥ 0",
    )?;
    let steps = (duration / dt).round();
    InvalidValue::check(
        steps <= TanabeKaneko::MAX_TRAJECTORY_STEPS as f64,
        "dt",
        dt as f32,
        "duration / dt exceeds 2^22 steps",
    )?;
    let n = steps as usize;
    let mut out = Vec::with_capacity(n + 1);
    let mut s = state;
    out.push(s);
    for _ in 0..n {
        s = step(params, s, dt, method);
        out.push(s);
    }
    Ok(out)
}

/// Limits and constants of [`TanabeKaneko`].
impl TanabeKaneko {
    /// Most substeps [`TanabeKaneko::step`] takes before it switches to [`Integrator::SemiImplicit`].
    pub const MAX_SUBSTEPS: u32 = 256;

    /// Most steps [`TanabeKaneko::trajectory`] takes: 2^22 states, 192 MiB.
    pub const MAX_TRAJECTORY_STEPS: usize = 1 << 22;
}

/// Integrating the model.
impl TanabeKaneko {
    /// One step of `h` by `method` (no sub-steps, no limits): what [`Self::step`] divides
    /// its step into.
    pub fn single_step(&self, state: &OdeState, h: f64, method: Integrator) -> OdeState {
        single_step(self, state, h, method)
    }

    /// `state` advanced by `dt`, in sub-steps the method keeps stable.
    pub fn step(&self, state: OdeState, dt: f64, method: Integrator) -> OdeState {
        step(self, state, dt, method)
    }

    /// Every state from `state` on, `dt` apart, for `duration`.
    ///
    /// # Errors
    /// `dt` not finite and > 0, `duration` not finite and ≥ 0, or too many steps (named).
    pub fn trajectory(
        &self,
        state: OdeState,
        dt: f64,
        duration: f64,
        method: Integrator,
    ) -> Result<Vec<OdeState>, FallError> {
        trajectory(self, state, dt, duration, method)
    }
}
