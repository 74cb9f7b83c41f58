//! The air's pressure on a particle cloth over a substep, implicit, as the force it puts on each
//! node along its normal: F = √L ∘ S(√L ∘ w') + K ∘ w', with w' the nodes' normal velocities
//! relative to the air where the solve reads them (the substep's midpoint or its end: it is
//! handed the reach c that takes w* there), L ≥ 0 and K ≥ 0 the smoothed and local force
//! rates (pressure rate × area) and S the screened filter of [`Screen`]. A free node's
//! w' = w* − c F (c = 0 where pinned), so w' = g ∘ (w* − c ∘ √L ∘ y) with g = 1 / (1 + c K)
//! and y = S(√L ∘ w'): (T + diag(c g L)) y = √L ∘ g ∘ w*, T = S⁻¹, a symmetric positive
//! definite system solved by conjugate gradients preconditioned with S.
//!
//! Every conjugate-gradient iterate y (from zero) leaves a residual orthogonal to itself, so
//! the force's product with the velocities it was solved at, Fᵀ w' = yᵀ T y + Σ K w'², is
//! never negative, however few iterations are run; with the velocities moved by the full
//! substep's reach from that point on or past it (θ ≥ ½), the air only takes energy out in
//! still air.

use super::screen::Screen;
use crate::portable::dot;

/// Conjugate-gradient iterations per substep, at most: the system is I + h × (the pressure's
/// damping rate) once preconditioned, one or two for a flag in a breeze.
const MOST_ITERATIONS: usize = 6;

/// The iterations stop once rᵀ S r has fallen by this factor.
const TOLERANCE: f64 = 1e-6;

/// Work space of [`smoothed_pressure`].
#[derive(Clone, Debug, Default)]
pub(super) struct PressureScratch {
    g: Vec<f32>,
    y: Vec<f32>,
    r: Vec<f32>,
    z: Vec<f32>,
    p: Vec<f32>,
    q: Vec<f32>,
    line: Vec<f32>,
}

/// The nodes' force rates (smoothed L, local K), their normal velocities relative to the air
/// before the pressure (w*) and their reach (c).
pub(super) struct Loads<'a> {
    pub lift: &'a [f32],
    pub drag: &'a [f32],
    pub relative: &'a [f32],
    pub reach: &'a [f32],
}

/// The pressure's force on every node (N, positive pushing against its normal) into `force`,
/// smoothed by `screen`.
pub(super) fn smoothed_pressure(
    loads: Loads,
    screen: &Screen,
    s: &mut PressureScratch,
    force: &mut [f32],
) {
    let Loads {
        lift,
        drag,
        relative,
        reach,
    } = loads;
    let n = lift.len();
    for v in [&mut s.y, &mut s.r, &mut s.z, &mut s.p, &mut s.q] {
        v.clear();
        v.resize(n, 0.0);
    }
    s.g.clear();
    s.g.extend(reach.iter().zip(drag).map(|(c, k)| 1.0 / (1.0 + c * k)));
    for i in 0..n {
        s.r[i] = lift[i].sqrt() * s.g[i] * relative[i];
    }
    s.z.copy_from_slice(&s.r);
    screen.smooth(&mut s.z, &mut s.line);
    s.p.copy_from_slice(&s.z);
    let first = dot(&s.r, &s.z, f64::from);
    let mut rz = first;
    for _ in 0..MOST_ITERATIONS {
        if !(rz > TOLERANCE * first && rz.is_finite()) {
            break;
        }
        s.q.copy_from_slice(&s.p);
        screen.unsmooth(&mut s.q, &mut s.line);
        for i in 0..n {
            s.q[i] += reach[i] * s.g[i] * lift[i] * s.p[i];
        }
        let pq = dot(&s.p, &s.q, f64::from);
        if !(pq > 0.0 && pq.is_finite()) {
            break;
        }
        let alpha = (rz / pq) as f32;
        for i in 0..n {
            s.y[i] += alpha * s.p[i];
            s.r[i] -= alpha * s.q[i];
        }
        s.z.copy_from_slice(&s.r);
        screen.smooth(&mut s.z, &mut s.line);
        let next = dot(&s.r, &s.z, f64::from);
        let beta = (next / rz) as f32;
        rz = next;
        for i in 0..n {
            s.p[i] = s.z[i] + beta * s.p[i];
        }
    }
    for i in 0..n {
        let smoothed = lift[i].sqrt() * s.y[i];
        let after = s.g[i] * (relative[i] - reach[i] * smoothed);
        let value = smoothed + drag[i] * after;
        force[i] = if value.is_finite() { value } else { 0.0 };
    }
}
