//! A particle cloth's compliant constraints and attachments, each projected with the nodes'
//! inverse inertia W = M⁻¹ = (1/m) (I − β n nᵀ), β = m_a / (m + m_a): shear and bending by
//! XPBD (Macklin, Müller & Chentanez 2016), and the long-range attachments (the yarns are in
//! [`super::yarns`]).

use bevy::math::Vec3;

/// The nodes' inverse inertia W = (1/m)(I − β n nᵀ): 1/m (0 if pinned), n and β per node.
#[derive(Clone, Copy)]
pub(super) struct Inertia<'a> {
    pub inverse_mass: &'a [f32],
    pub normals: &'a [Vec3],
    pub beta: &'a [f32],
}

impl Inertia<'_> {
    /// W_i e.
    #[inline]
    pub(super) fn apply(&self, i: usize, e: Vec3) -> Vec3 {
        let n = self.normals[i];
        self.inverse_mass[i] * (e - self.beta[i] * n.dot(e) * n)
    }

    /// eᵀ W_i f.
    #[inline]
    pub(super) fn product(&self, i: usize, e: Vec3, f: Vec3) -> f32 {
        let n = self.normals[i];
        self.inverse_mass[i] * (e.dot(f) - self.beta[i] * n.dot(e) * n.dot(f))
    }
}

/// One XPBD pass over distance constraints (a, b, rest, compliance) with multipliers
/// `lambdas`, at substep `h`: Δλ = (−C − α̃ λ) / (∇C W ∇Cᵀ + α̃), α̃ = compliance / h².
pub(super) fn project_distances(
    x: &mut [Vec3],
    inertia: Inertia,
    constraints: &[(u32, u32, f32, f32)],
    lambdas: &mut [f32],
    h: f32,
) {
    for (lambda, &(a, b, rest, compliance)) in lambdas.iter_mut().zip(constraints) {
        let (a, b) = (a as usize, b as usize);
        let delta = x[a] - x[b];
        let length = delta.length();
        if !(length > 0.0 && length.is_finite()) {
            continue;
        }
        let e = delta * (1.0 / length);
        let w = inertia.product(a, e, e) + inertia.product(b, e, e);
        let alpha = compliance / (h * h);
        if w + alpha <= 0.0 || (w + alpha).is_nan() {
            continue;
        }
        let dl = (rest - length - alpha * *lambda) / (w + alpha);
        *lambda += dl;
        x[a] += inertia.apply(a, e * dl);
        x[b] -= inertia.apply(b, e * dl);
    }
}

/// One XPBD pass over the bending constraints C = x_a − 2 x_b + x_c = 0 (vector-valued) of
/// `bends` (a, b, c, compliance) with multipliers `lambdas`, at substep `h`:
/// Δλ = (W_a + 4 W_b + W_c + α̃ I)⁻¹ (−C − α̃ λ).
pub(super) fn project_bending(
    x: &mut [Vec3],
    inertia: Inertia,
    bends: &[(u32, u32, u32, f32)],
    lambdas: &mut [Vec3],
    h: f32,
) {
    for (&(a, b, c, compliance), lambda) in bends.iter().zip(lambdas.iter_mut()) {
        let (a, b, c) = (a as usize, b as usize, c as usize);
        let alpha = compliance / (h * h);
        // K = W_a + 4 W_b + W_c + α̃ I, symmetric: its six entries, then K⁻¹ by cofactors.
        let mut diagonal = alpha;
        let [mut xx, mut yy, mut zz, mut xy, mut xz, mut yz] = [0.0f32; 6];
        for (node, weight) in [(a, 1.0), (b, 4.0), (c, 1.0)] {
            let w = weight * inertia.inverse_mass[node];
            let (n, s) = (inertia.normals[node], w * inertia.beta[node]);
            diagonal += w;
            xx -= s * n.x * n.x;
            yy -= s * n.y * n.y;
            zz -= s * n.z * n.z;
            xy -= s * n.x * n.y;
            xz -= s * n.x * n.z;
            yz -= s * n.y * n.z;
        }
        let (xx, yy, zz) = (xx + diagonal, yy + diagonal, zz + diagonal);
        let (cxx, cyy, czz) = (yy * zz - yz * yz, xx * zz - xz * xz, xx * yy - xy * xy);
        let (cxy, cxz, cyz) = (xz * yz - xy * zz, xy * yz - xz * yy, xy * xz - xx * yz);
        let determinant = xx * cxx + xy * cxy + xz * cxz;
        if !(determinant > 0.0 && determinant.is_finite()) {
            continue;
        }
        let r = -(x[a] - 2.0 * x[b] + x[c]) - alpha * *lambda;
        let dl = Vec3::new(
            cxx * r.x + cxy * r.y + cxz * r.z,
            cxy * r.x + cyy * r.y + cyz * r.z,
            cxz * r.x + cyz * r.y + czz * r.z,
        ) * (1.0 / determinant);
        if !dl.is_finite() {
            continue;
        }
        *lambda += dl;
        x[a] += inertia.apply(a, dl);
        x[b] -= 2.0 * inertia.apply(b, dl);
        x[c] += inertia.apply(c, dl);
    }
}

/// Long-range attachments (node, pin, rest; Kim, Chentanez & Müller 2012): a node further from
/// its pin than `rest` is moved along W e (e from the pin to the node) until it is exactly
/// `rest` away, or straight toward the pin where that line misses the sphere.
pub(super) fn project_tethers(x: &mut [Vec3], inertia: Inertia, tethers: &[(u32, u32, f32)]) {
    for &(node, pin, rest) in tethers {
        let (node, pin) = (node as usize, pin as usize);
        let d = x[node] - x[pin];
        let length2 = d.length_squared();
        if !(length2 > rest * rest && length2.is_finite()) {
            continue;
        }
        // |d + t w|² = rest², w = W d: the root nearest zero (both are negative).
        let w = inertia.apply(node, d);
        let (a, b, c) = (w.length_squared(), d.dot(w), length2 - rest * rest);
        let discriminant = b * b - a * c;
        let t = (-b + discriminant.max(0.0).sqrt()) / a;
        let moved = d + t * w;
        x[node] = if discriminant >= 0.0 && a > 0.0 && moved.is_finite() {
            x[pin] + moved
        } else {
            x[pin] + d * (rest / length2.sqrt())
        };
    }
}
