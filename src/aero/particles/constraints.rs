//! A particle cloth's compliant constraints and attachments, each projected with the nodes'
//! inverse inertia W = M⁻¹ = (1/m) (I − β n nᵀ), β = m_a / (m + m_a): shear and bending by
//! XPBD (Macklin, Müller & Chentanez 2016), and the long-range attachments (the yarns are in
//! [`super::yarns`]). Constraints that share no node are projected four at a time in SIMD lanes
//! (the crate's `Lane` over `wide::f32x4`, the same bits as one at a time).

use bevy::math::Vec3;

use crate::portable::geometry::V3;
use crate::portable::lane::Lane;

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

/// Consecutive constraints that share no node, in runs of at most [`RUN`] (start, length):
/// a run of [`RUN`] is projected side by side in SIMD lanes. Gauss–Seidel over constraints that
/// share no node does not depend on their order, and every lane does the scalar code's IEEE
/// operations in the same order, so a run gives each node the bits one constraint at a time
/// would. A constraint's own nodes are distinct (as the grid builds them): its kernel reads them
/// all before it writes any.
pub(super) fn disjoint_runs<const K: usize>(nodes: &[[u32; K]]) -> Vec<(u32, u32)> {
    let mut runs = Vec::new();
    let mut start = 0;
    while start < nodes.len() {
        let mut length = 1;
        while length < RUN
            && start + length < nodes.len()
            && nodes[start..start + length]
                .iter()
                .all(|other| nodes[start + length].iter().all(|n| !other.contains(n)))
        {
            length += 1;
        }
        runs.push((start as u32, length as u32));
        start += length;
    }
    runs
}

/// Constraints projected side by side.
const RUN: usize = 4;

/// `lanes` on each run of [`RUN`] constraints (and their multipliers), `one` on each
/// constraint of a shorter run, in order.
#[inline(always)]
fn in_runs<T, U>(
    runs: &[(u32, u32)],
    x: &mut [Vec3],
    constraints: &[T],
    lambdas: &mut [U],
    lanes: impl Fn(&mut [Vec3], &[T], &mut [U]),
    one: impl Fn(&mut [Vec3], &[T], &mut [U]),
) {
    for &(start, length) in runs {
        let range = start as usize..(start + length) as usize;
        if length as usize == RUN {
            lanes(x, &constraints[range.clone()], &mut lambdas[range]);
        } else {
            for i in range {
                one(x, &constraints[i..=i], &mut lambdas[i..=i]);
            }
        }
    }
}

/// `v` is finite, per lane.
#[inline(always)]
pub(super) fn finite<L: Lane>(v: L) -> L::Mask {
    v.abs().lt(L::splat(f32::INFINITY))
}

/// Each lane's node `node(k)` of an array of vectors.
#[inline(always)]
pub(super) fn gather<L: Lane>(values: &[Vec3], node: impl Fn(usize) -> usize) -> V3<L> {
    V3::new(
        L::from_fn(|k| values[node(k)].x),
        L::from_fn(|k| values[node(k)].y),
        L::from_fn(|k| values[node(k)].z),
    )
}

/// Writes each lane's vector back to node `node(k)` where `mask`.
#[inline(always)]
fn scatter<L: Lane>(values: &mut [Vec3], node: impl Fn(usize) -> usize, v: V3<L>, mask: L::Mask) {
    for k in 0..L::WIDTH {
        if L::mask_get(mask, k) {
            values[node(k)] = Vec3::new(v.x.get(k), v.y.get(k), v.z.get(k));
        }
    }
}

/// The inverse inertia of each lane's node, gathered once: 1/m, n and β.
#[derive(Clone, Copy)]
pub(super) struct LaneInertia<L> {
    inverse_mass: L,
    normal: V3<L>,
    beta: L,
}

impl Inertia<'_> {
    /// The inverse inertia of node `node(k)` in lane k.
    #[inline(always)]
    pub(super) fn lanes<L: Lane>(&self, node: impl Fn(usize) -> usize + Copy) -> LaneInertia<L> {
        LaneInertia {
            inverse_mass: L::from_fn(|k| self.inverse_mass[node(k)]),
            normal: gather::<L>(self.normals, node),
            beta: L::from_fn(|k| self.beta[node(k)]),
        }
    }
}

impl<L: Lane> LaneInertia<L> {
    /// W e, as [`Inertia::apply`] computes it.
    #[inline(always)]
    pub(super) fn apply(&self, e: V3<L>) -> V3<L> {
        let (n, w) = (self.normal, self.inverse_mass);
        let k = self.beta * ((n.x * e.x + n.y * e.y) + n.z * e.z);
        V3::new(
            w * (e.x - k * n.x),
            w * (e.y - k * n.y),
            w * (e.z - k * n.z),
        )
    }

    /// eᵀ W e, as [`Inertia::product`] computes it.
    #[inline(always)]
    pub(super) fn square(&self, e: V3<L>) -> L {
        let n = self.normal;
        let along = (n.x * e.x + n.y * e.y) + n.z * e.z;
        self.inverse_mass * (e.length_squared() - self.beta * along * along)
    }
}

/// One XPBD pass over distance constraints (a, b, rest, compliance) with multipliers
/// `lambdas`, at substep `h`: Δλ = (−C − α̃ λ) / (∇C W ∇Cᵀ + α̃), α̃ = compliance / h²;
/// `runs` from [`disjoint_runs`].
pub(super) fn project_distances(
    x: &mut [Vec3],
    inertia: Inertia,
    constraints: &[(u32, u32, f32, f32)],
    lambdas: &mut [f32],
    runs: &[(u32, u32)],
    h: f32,
) {
    let squared = h * h;
    in_runs(
        runs,
        x,
        constraints,
        lambdas,
        |x, c, l| distances::<wide::f32x4>(x, inertia, c, l, squared),
        |x, c, l| distances::<f32>(x, inertia, c, l, squared),
    );
}

/// [`project_distances`] of `L::WIDTH` constraints that share no node.
#[inline(always)]
fn distances<L: Lane>(
    x: &mut [Vec3],
    inertia: Inertia,
    constraints: &[(u32, u32, f32, f32)],
    lambdas: &mut [f32],
    squared: f32,
) {
    let a = |k: usize| constraints[k].0 as usize;
    let b = |k: usize| constraints[k].1 as usize;
    let (xa, xb) = (gather::<L>(x, a), gather::<L>(x, b));
    let delta = xa.sub(xb);
    let length = delta.length_squared().sqrt();
    let valid = L::and(L::splat(0.0).lt(length), finite(length));
    let e = delta.scale(L::splat(1.0) / length);
    let (ia, ib) = (inertia.lanes::<L>(a), inertia.lanes::<L>(b));
    let w = ia.square(e) + ib.square(e);
    let alpha = L::from_fn(|k| constraints[k].3) / L::splat(squared);
    let valid = L::and(valid, L::splat(0.0).lt(w + alpha));
    let lambda = L::from_fn(|k| lambdas[k]);
    let rest = L::from_fn(|k| constraints[k].2);
    let dl = (rest - length - alpha * lambda) / (w + alpha);
    let e = e.scale(dl);
    let (pa, pb) = (ia.apply(e), ib.apply(e));
    scatter(x, a, xa.add(pa), valid);
    scatter(x, b, xb.sub(pb), valid);
    let lambda = L::select(valid, lambda + dl, lambda);
    for (k, l) in lambdas.iter_mut().enumerate() {
        *l = lambda.get(k);
    }
}

/// One XPBD pass over the bending constraints C = x_a − 2 x_b + x_c = 0 (vector-valued) of
/// `bends` (a, b, c, compliance) with multipliers `lambdas`, at substep `h`:
/// Δλ = (W_a + 4 W_b + W_c + α̃ I)⁻¹ (−C − α̃ λ); `runs` from [`disjoint_runs`].
pub(super) fn project_bending(
    x: &mut [Vec3],
    inertia: Inertia,
    bends: &[(u32, u32, u32, f32)],
    lambdas: &mut [Vec3],
    runs: &[(u32, u32)],
    h: f32,
) {
    let squared = h * h;
    in_runs(
        runs,
        x,
        bends,
        lambdas,
        |x, c, l| bending::<wide::f32x4>(x, inertia, c, l, squared),
        |x, c, l| bending::<f32>(x, inertia, c, l, squared),
    );
}

/// [`project_bending`] of `L::WIDTH` constraints that share no node.
#[inline(always)]
fn bending<L: Lane>(
    x: &mut [Vec3],
    inertia: Inertia,
    bends: &[(u32, u32, u32, f32)],
    lambdas: &mut [Vec3],
    squared: f32,
) {
    let a = |k: usize| bends[k].0 as usize;
    let b = |k: usize| bends[k].1 as usize;
    let c = |k: usize| bends[k].2 as usize;
    let alpha = L::from_fn(|k| bends[k].3) / L::splat(squared);
    // K = W_a + 4 W_b + W_c + α̃ I, symmetric: its six entries, then K⁻¹ by cofactors.
    let mut diagonal = alpha;
    let zero = L::splat(0.0);
    let [mut xx, mut yy, mut zz, mut xy, mut xz, mut yz] = [zero; 6];
    let nodes = [
        inertia.lanes::<L>(a),
        inertia.lanes::<L>(b),
        inertia.lanes::<L>(c),
    ];
    for (node, weight) in nodes.iter().zip([1.0, 4.0, 1.0]) {
        let w = L::splat(weight) * node.inverse_mass;
        let n = node.normal;
        let s = w * node.beta;
        diagonal = diagonal + w;
        xx = xx - s * n.x * n.x;
        yy = yy - s * n.y * n.y;
        zz = zz - s * n.z * n.z;
        xy = xy - s * n.x * n.y;
        xz = xz - s * n.x * n.z;
        yz = yz - s * n.y * n.z;
    }
    let (xx, yy, zz) = (xx + diagonal, yy + diagonal, zz + diagonal);
    let (cxx, cyy, czz) = (yy * zz - yz * yz, xx * zz - xz * xz, xx * yy - xy * xy);
    let (cxy, cxz, cyz) = (xz * yz - xy * zz, xy * yz - xz * yy, xy * xz - xx * yz);
    let determinant = xx * cxx + xy * cxy + xz * cxz;
    let valid = L::and(zero.lt(determinant), finite(determinant));
    let (xa, xb, xc) = (gather::<L>(x, a), gather::<L>(x, b), gather::<L>(x, c));
    let lambda = V3::new(
        L::from_fn(|k| lambdas[k].x),
        L::from_fn(|k| lambdas[k].y),
        L::from_fn(|k| lambdas[k].z),
    );
    let two = L::splat(2.0);
    let bend = xa.sub(xb.scale(two)).add(xc);
    let r = V3::new(
        -bend.x - alpha * lambda.x,
        -bend.y - alpha * lambda.y,
        -bend.z - alpha * lambda.z,
    );
    let inverse = L::splat(1.0) / determinant;
    let dl = V3::new(
        (cxx * r.x + cxy * r.y + cxz * r.z) * inverse,
        (cxy * r.x + cyy * r.y + cyz * r.z) * inverse,
        (cxz * r.x + cyz * r.y + czz * r.z) * inverse,
    );
    let valid = L::and(
        valid,
        L::and(finite(dl.x), L::and(finite(dl.y), finite(dl.z))),
    );
    let [ia, ib, ic] = nodes;
    scatter(x, a, xa.add(ia.apply(dl)), valid);
    scatter(x, b, xb.sub(ib.apply(dl).scale(two)), valid);
    scatter(x, c, xc.add(ic.apply(dl)), valid);
    let lambda = V3::select(valid, lambda.add(dl), lambda);
    for (k, l) in lambdas.iter_mut().enumerate() {
        *l = Vec3::new(lambda.x.get(k), lambda.y.get(k), lambda.z.get(k));
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A number in [−1, 1) from a counter (SplitMix64's finaliser).
    pub(in crate::aero::particles) fn unit(seed: u64) -> f32 {
        let mut z = seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }

    /// Unit normals tilted off +Z and each node's β in (0.1, 0.9), from `r`.
    pub(in crate::aero::particles) fn normals_and_betas(
        nodes: usize,
        r: impl Fn(u64) -> f32,
    ) -> (Vec<Vec3>, Vec<f32>) {
        let normals = (0..nodes as u64)
            .map(|i| Vec3::new(r(500 + i), r(600 + i), 1.0).normalize_or_zero())
            .collect();
        let beta = (0..nodes as u64).map(|i| 0.5 + 0.4 * r(800 + i)).collect();
        (normals, beta)
    }

    #[test]
    fn runs_in_lanes_give_every_node_the_bits_of_one_constraint_at_a_time() {
        let nodes = 60;
        for seed in 0..40u64 {
            let r = |i: u64| unit(seed * 1_000_003 + i);
            let mut x: Vec<Vec3> = (0..nodes as u64)
                .map(|i| Vec3::new(r(3 * i), r(3 * i + 1), r(3 * i + 2) * 1e-2))
                .collect();
            // Extremes: two nodes on one spot, a NaN, a node far off.
            x[7] = x[8];
            if seed % 3 == 0 {
                x[11].y = f32::NAN;
            }
            x[13] *= 1e20;
            let (normals, beta) = normals_and_betas(nodes, r);
            let inverse_mass: Vec<f32> = (0..nodes as u64)
                .map(|i| {
                    if i % 9 == 0 {
                        0.0
                    } else {
                        10.0 + 5.0 * r(700 + i)
                    }
                })
                .collect();
            let inertia = Inertia {
                inverse_mass: &inverse_mass,
                normals: &normals,
                beta: &beta,
            };
            // Random triples of distinct nodes: some runs share nodes, some do not.
            let pick = |i: u64| ((r(900 + i) + 1.0) * 0.5 * nodes as f32) as u32 % nodes as u32;
            let mut bends = Vec::new();
            let mut shear = Vec::new();
            for i in 0..80u64 {
                let (a, b, c) = (pick(3 * i), pick(3 * i + 1), pick(3 * i + 2));
                if a != b && b != c && a != c {
                    bends.push((a, b, c, 1e-3 * (1.0 + r(2000 + i))));
                    shear.push((a, c, 0.5 + 0.2 * r(3000 + i), 1e-4 * (1.0 + r(4000 + i))));
                }
                // Rigid constraints between pinned nodes (every ninth): nothing to move them
                // (w + α = 0, a zero determinant), skipped in their lanes.
                if i % 7 == 0 {
                    let pinned = |k: u64| (9 * ((i / 7 + k) % 7)) as u32;
                    bends.push((pinned(0), pinned(1), pinned(2), 0.0));
                    shear.push((pinned(3), pinned(5), 0.3, 0.0));
                }
            }
            let bend_runs =
                disjoint_runs(&bends.iter().map(|b| [b.0, b.1, b.2]).collect::<Vec<_>>());
            let shear_runs = disjoint_runs(&shear.iter().map(|s| [s.0, s.1]).collect::<Vec<_>>());
            assert!(bend_runs.iter().any(|r| r.1 as usize == RUN));
            assert!(shear_runs.iter().any(|r| r.1 as usize == RUN));
            let single = |count: usize| (0..count as u32).map(|i| (i, 1)).collect::<Vec<_>>();
            let run = |bend_runs: &[(u32, u32)], shear_runs: &[(u32, u32)]| {
                let mut x = x.clone();
                let (bend_start, shear_start) = (Vec3::new(r(1), 0.0, -r(2)) * 1e-3, r(3) * 1e-3);
                let mut bend_lambdas = vec![bend_start; bends.len()];
                let mut shear_lambdas = vec![shear_start; shear.len()];
                for _ in 0..3 {
                    project_bending(&mut x, inertia, &bends, &mut bend_lambdas, bend_runs, 2e-3);
                    project_distances(
                        &mut x,
                        inertia,
                        &shear,
                        &mut shear_lambdas,
                        shear_runs,
                        2e-3,
                    );
                }
                // The rigid constraints between pinned nodes were skipped.
                for (bend, lambda) in bends.iter().zip(&bend_lambdas) {
                    assert!(bend.3 != 0.0 || *lambda == bend_start, "seed {seed}");
                }
                for (shear, lambda) in shear.iter().zip(&shear_lambdas) {
                    assert!(shear.3 != 0.0 || *lambda == shear_start, "seed {seed}");
                }
                let mut bits: Vec<u32> = x
                    .iter()
                    .chain(&bend_lambdas)
                    .flat_map(|v| [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()])
                    .collect();
                bits.extend(shear_lambdas.iter().map(|l| l.to_bits()));
                bits
            };
            let (lanes, one) = (
                run(&bend_runs, &shear_runs),
                run(&single(bends.len()), &single(shear.len())),
            );
            assert_eq!(lanes, one, "seed {seed}");
            // The constraints moved the nodes.
            assert_ne!(lanes, run(&[], &[]), "seed {seed}");
        }
    }

    #[test]
    fn disjoint_runs_share_no_node_and_cover_every_constraint_in_order() {
        let nodes: Vec<[u32; 2]> = (0..200u32)
            .map(|i| [i % 17, (i * 7 + 3) % 23 + 17])
            .collect();
        let runs = disjoint_runs(&nodes);
        let mut next = 0;
        for &(start, length) in &runs {
            assert_eq!(start, next);
            assert!((1..=RUN as u32).contains(&length));
            let run = &nodes[start as usize..(start + length) as usize];
            for (i, p) in run.iter().enumerate() {
                for q in &run[i + 1..] {
                    assert!(p.iter().all(|n| !q.contains(n)), "{p:?} {q:?}");
                }
            }
            next = start + length;
        }
        assert_eq!(next as usize, nodes.len());
    }
}
