//! Inextensible yarns: every edge along the rows and the columns kept at its rest length at once.
//!
//! Linearised at the predicted positions, the edges' multipliers solve (J W Jᵀ) Δλ = −C, J the
//! edges' gradients and W the nodes' inverse inertia, then Δx = W Jᵀ Δλ. The system is solved
//! by conjugate gradients preconditioned with its own grid lines (each row's and each column's
//! edges form a tridiagonal block, factorised once by Thomas' algorithm): exact for an unsheared
//! grid, whose rows and columns do not couple, and a few iterations where shear couples them.
//! Each substep's first solve starts from the last one's multipliers (a flag's tension changes
//! little from one substep to the next), or from zero where that start is worse: a hanging
//! flag's solve takes two fifths of the iterations of one from zero, a flapping flag's two
//! thirds (and one product and preconditioning more to start), to the same bound, a share of the
//! residual from zero.

use bevy::math::Vec3;

use super::constraints::{Inertia, finite, gather};
use crate::portable::dot;
use crate::portable::geometry::V3;
use crate::portable::lane::Lane;

/// How the yarns' solves have gone since the cloth was made: [`ParticleCloth::yarn_solves`](super::ParticleCloth::yarn_solves).
///
/// Each projection of the yarns solves one linear system by conjugate gradients, stopping when
/// the residual has fallen by the tolerance or after a fixed number of iterations; what a
/// stopped solve leaves is made up at the next linearisation and substep. These counters show
/// whether that happens, rather than leaving it unseen.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct YarnSolves {
    /// Projections of the yarns (linearised systems solved).
    pub solves: u64,
    /// Conjugate-gradient iterations over all of them.
    pub iterations: u64,
    /// Solves stopped at the iteration limit before reaching the tolerance.
    pub unconverged: u64,
    /// Pivots of the lines' tridiagonal blocks that were not positive and finite (the edge was
    /// then preconditioned alone): 0 unless rounding breaks the blocks' positive definiteness.
    pub guarded_pivots: u64,
    /// The last solve's residual relative to the residual from zero, in the preconditioned norm.
    pub last_residual: f32,
}

/// What [`Yarns::gather`] spreads to the nodes.
#[derive(Clone, Copy)]
enum Source {
    P,
    Lambda,
}

/// Conjugate-gradient iterations per projection, at most.
const MOST_ITERATIONS: usize = 12;
/// The iterations stop once the residual is this share of the residual from zero (in the
/// preconditioned norm), whichever start they took: the part of the constraints left unsolved turns into velocity at the next substep,
/// so it is made small against the substep's own correction, not against the edge.
const TOLERANCE: f64 = 1e-2;

/// The edges of a `rows × columns` grid, with their rest lengths and the solver's work space:
/// the rows' edges, then the columns', each family's lines side by side (a family's j-th edges
/// of all its lines one after another: a row's j-th edge at j · rows + row, a column's k-th at
/// rows (columns − 1) + k · columns + column), so that the lines' recurrences run over
/// contiguous edges.
#[derive(Clone, Debug, Default)]
pub(super) struct Yarns {
    rows: usize,
    columns: usize,
    /// Each edge's nodes, and the two families of equal lines lying one after another (the
    /// rows, the columns) as (first edge, edges per line, lines): a line's next edge is `lines`
    /// further on.
    ends: Vec<(u32, u32)>,
    families: [(u32, u32, u32); 2],
    rest: Vec<f32>,
    direction: Vec<Vec3>,
    /// Each line's tridiagonal block: the diagonal, the coupling to the line's next edge, and
    /// their Thomas factors (1 / pivot, the upper factor).
    diagonal: Vec<f32>,
    off: Vec<f32>,
    inverse_pivot: Vec<f32>,
    upper: Vec<f32>,
    lambda: Vec<f32>,
    r: Vec<f32>,
    z: Vec<f32>,
    p: Vec<f32>,
    q: Vec<f32>,
    push: Vec<Vec3>,
    /// The multipliers of the last warm-started projection and its substep (0: none yet).
    warm: Vec<f32>,
    warm_step: f32,
    /// The residual from zero, kept while a warm start is tried.
    start: Vec<f32>,
    pub(super) solves: YarnSolves,
}

impl Yarns {
    /// The yarns of a `rows × columns` grid at `positions`, their rest lengths.
    pub(super) fn new(rows: usize, columns: usize, positions: &[Vec3]) -> Self {
        let mut ends = Vec::new();
        // (edges a line, lines, a line's first node, the step along a line).
        for (length, lines, line_step, stride) in [
            (columns - 1, rows, columns, 1),
            (rows - 1, columns, 1, columns),
        ] {
            for j in 0..length {
                ends.extend((0..lines).map(|line| {
                    let a = line * line_step + j * stride;
                    (a as u32, (a + stride) as u32)
                }));
            }
        }
        let rest: Vec<f32> = ends
            .iter()
            .map(|&(a, b)| positions[a as usize].distance(positions[b as usize]))
            .collect();
        let count = ends.len();
        let families = [
            (0, (columns - 1) as u32, rows as u32),
            (
                (rows * (columns - 1)) as u32,
                (rows - 1) as u32,
                columns as u32,
            ),
        ];
        Self {
            rows,
            columns,
            ends,
            families,
            rest,
            direction: vec![Vec3::ZERO; count],
            diagonal: vec![0.0; count],
            off: vec![0.0; count],
            inverse_pivot: vec![0.0; count],
            upper: vec![0.0; count],
            lambda: vec![0.0; count],
            r: vec![0.0; count],
            z: vec![0.0; count],
            p: vec![0.0; count],
            q: vec![0.0; count],
            push: vec![Vec3::ZERO; rows * columns],
            warm: vec![0.0; count],
            warm_step: 0.0,
            start: vec![0.0; count],
            solves: YarnSolves::default(),
        }
    }

    /// The next solve starts from zero (the kept multipliers belong to a substep undone).
    pub(super) fn forget(&mut self) {
        self.warm_step = 0.0;
    }

    /// Largest |length / rest − 1| over the edges.
    pub(super) fn max_strain(&self, x: &[Vec3]) -> f32 {
        self.ends
            .iter()
            .zip(&self.rest)
            .map(|(&(a, b), rest)| (x[a as usize].distance(x[b as usize]) / rest - 1.0).abs())
            .fold(0.0, f32::max)
    }

    /// Projects `x` onto the yarns' rest lengths (one linearisation). With `warm`, the
    /// substep's length, the solve starts from the multipliers of the last warm-started
    /// projection scaled by (h / h_then)² (a steady tension T gives λ = h² T), and those it
    /// finds are kept for the next: the first projection of a substep; later ones (what is left
    /// of the constraints) start from zero.
    pub(super) fn project(&mut self, x: &mut [Vec3], inertia: Inertia, warm: Option<f32>) {
        let count = self.rest.len();
        let lanes = count - count % 4;
        for first in (0..lanes).step_by(4) {
            self.linearise::<wide::f32x4>(x, inertia, first);
        }
        for e in lanes..count {
            self.linearise::<f32>(x, inertia, e);
        }
        self.factorise(inertia);
        let scale = match warm {
            Some(h) if self.warm_step > 0.0 => (h / self.warm_step).powi(2),
            _ => 0.0,
        };
        self.solve(inertia, scale);
        if let Some(h) = warm {
            self.warm.copy_from_slice(&self.lambda);
            self.warm_step = h;
        }
        // Δx = W Jᵀ λ.
        self.gather(inertia, Source::Lambda);
        for (x, dx) in x.iter_mut().zip(&self.push) {
            if dx.is_finite() {
                *x += *dx;
            }
        }
    }

    /// The lines' tridiagonal blocks at the linearised edges (a line's last edge couples to
    /// nothing) and their Thomas factors; a pivot that is not positive and finite leaves its
    /// edge preconditioned alone.
    fn factorise(&mut self, inertia: Inertia) {
        for &(first, length, count) in &self.families {
            let (first, length, count) = (first as usize, length as usize, count as usize);
            let last = first + (length - 1) * count;
            for i in first..last {
                let shared = self.ends[i].1 as usize;
                self.off[i] =
                    -inertia.product(shared, self.direction[i], self.direction[i + count]);
            }
            self.off[last..last + count].fill(0.0);
        }
        for &(first, length, count) in &self.families {
            let (first, length, count) = (first as usize, length as usize, count as usize);
            for j in 0..length {
                for i in first + j * count..first + (j + 1) * count {
                    let below = if j > 0 {
                        self.off[i - count] * self.upper[i - count]
                    } else {
                        0.0
                    };
                    let pivot = self.diagonal[i] - below;
                    if pivot > 0.0 && pivot.is_finite() {
                        self.inverse_pivot[i] = 1.0 / pivot;
                        self.upper[i] = self.off[i] / pivot;
                    } else {
                        // Preconditioned alone: its diagonal is positive (or 1 where the edge
                        // is left as it is).
                        self.solves.guarded_pivots += 1;
                        self.inverse_pivot[i] = 1.0 / self.diagonal[i];
                        self.upper[i] = 0.0;
                    }
                }
            }
        }
    }

    /// Each of `L::WIDTH` edges from `first`: its direction, its diagonal J W Jᵀ and its
    /// constraint's value (rest − length) at `x`; a degenerate edge, or one with both ends
    /// pinned, is left as it is (no direction, diagonal 1, nothing to solve).
    #[inline(always)]
    fn linearise<L: Lane>(&mut self, x: &[Vec3], inertia: Inertia, first: usize) {
        let a = |k: usize| self.ends[first + k].0 as usize;
        let b = |k: usize| self.ends[first + k].1 as usize;
        let delta = gather::<L>(x, b).sub(gather::<L>(x, a));
        let length = delta.length_squared().sqrt();
        let d = delta.scale(L::splat(1.0) / length);
        let diagonal = inertia.lanes::<L>(a).square(d) + inertia.lanes::<L>(b).square(d);
        let zero = L::splat(0.0);
        let valid = L::and(
            L::and(zero.lt(length), zero.lt(diagonal)),
            L::and(
                finite(diagonal),
                L::and(finite(d.x), L::and(finite(d.y), finite(d.z))),
            ),
        );
        let d = V3::select(valid, d, V3::new(zero, zero, zero));
        let diagonal = L::select(valid, diagonal, L::splat(1.0));
        let rest = L::from_fn(|k| self.rest[first + k]);
        let r = L::select(valid, rest - length, zero);
        for k in 0..L::WIDTH {
            self.direction[first + k] = Vec3::new(d.x.get(k), d.y.get(k), d.z.get(k));
            self.diagonal[first + k] = diagonal.get(k);
            self.r[first + k] = r.get(k);
        }
    }

    /// λ ≈ A⁻¹ r, A = J W Jᵀ, by conjugate gradients from `scale` times the kept multipliers,
    /// or from zero where that start leaves a larger residual than zero does (r is overwritten;
    /// see [`TOLERANCE`]: both starts stop at the same bound, the residual from zero's share).
    fn solve(&mut self, inertia: Inertia, scale: f32) {
        let count = self.rest.len();
        self.precondition();
        let first = dot(&self.r, &self.z, |p| p);
        let enough = first * TOLERANCE * TOLERANCE;
        let warm = scale > 0.0 && scale.is_finite();
        if warm {
            // λ₀ on the edges that are solved (a degenerate or held edge has no direction).
            for ((l, w), d) in self.lambda.iter_mut().zip(&self.warm).zip(&self.direction) {
                let l0 = scale * w;
                *l = if *d != Vec3::ZERO && l0.is_finite() {
                    l0
                } else {
                    0.0
                };
            }
            self.start.copy_from_slice(&self.r);
            self.p.copy_from_slice(&self.lambda);
            self.multiply(inertia);
            for (r, q) in self.r.iter_mut().zip(&self.q) {
                *r -= q;
            }
            self.precondition();
        }
        let (mut rz, mut from_zero) = (first, !warm);
        if warm {
            rz = dot(&self.r, &self.z, |p| p);
            if matches!(
                rz.partial_cmp(&first),
                None | Some(std::cmp::Ordering::Greater)
            ) {
                // A start worse than zero (the tension changed, or a NaN): from zero instead.
                self.r.copy_from_slice(&self.start);
                self.precondition();
                (rz, from_zero) = (first, true);
            }
        }
        if from_zero {
            self.lambda.fill(0.0);
        }
        self.p.copy_from_slice(&self.z);
        let mut iterations = 0;
        for _ in 0..MOST_ITERATIONS {
            if !(rz > enough && rz.is_finite()) {
                break;
            }
            iterations += 1;
            self.multiply(inertia);
            let pq = dot(&self.p, &self.q, |p| p);
            if !(pq > 0.0 && pq.is_finite()) {
                break;
            }
            let alpha = (rz / pq) as f32;
            for e in 0..count {
                self.lambda[e] += alpha * self.p[e];
                self.r[e] -= alpha * self.q[e];
            }
            self.precondition();
            let next = dot(&self.r, &self.z, |p| p);
            let beta = (next / rz) as f32;
            rz = next;
            for e in 0..count {
                self.p[e] = self.z[e] + beta * self.p[e];
            }
        }
        let solves = &mut self.solves;
        solves.solves += 1;
        solves.iterations += iterations;
        if iterations == MOST_ITERATIONS as u64 && rz > enough {
            solves.unconverged += 1;
        }
        solves.last_residual = if first > 0.0 && rz.is_finite() {
            (rz / first).sqrt() as f32
        } else {
            0.0
        };
    }

    /// z = P⁻¹ r, P the lines' blocks: each family's lines (the rows, the columns) swept side by
    /// side, their j-th edges contiguous, so that their recurrences run at once in SIMD lanes.
    fn precondition(&mut self) {
        for &(first, length, count) in &self.families {
            let (first, length, count) = (first as usize, length as usize, count as usize);
            let edges = first..first + length * count;
            let (r, z) = (&self.r[edges.clone()], &mut self.z[edges.clone()]);
            let (off, inverse_pivot) =
                (&self.off[edges.clone()], &self.inverse_pivot[edges.clone()]);
            let upper = &self.upper[edges];
            for ((z, r), d) in z[..count]
                .iter_mut()
                .zip(&r[..count])
                .zip(&inverse_pivot[..count])
            {
                *z = r * d;
            }
            for j in 1..length {
                let (before, after) = z.split_at_mut(j * count);
                let (below, z) = (&before[(j - 1) * count..], &mut after[..count]);
                let at = j * count..(j + 1) * count;
                let coupling = &off[(j - 1) * count..j * count];
                for (((z, r), (o, below)), d) in z
                    .iter_mut()
                    .zip(&r[at.clone()])
                    .zip(coupling.iter().zip(below))
                    .zip(&inverse_pivot[at])
                {
                    *z = (r - o * below) * d;
                }
            }
            for j in (0..length - 1).rev() {
                let (before, after) = z.split_at_mut((j + 1) * count);
                let (z, above) = (&mut before[j * count..], &after[..count]);
                for ((z, u), above) in z
                    .iter_mut()
                    .zip(&upper[j * count..(j + 1) * count])
                    .zip(above)
                {
                    *z -= u * above;
                }
            }
        }
    }

    /// q = J W Jᵀ p.
    fn multiply(&mut self, inertia: Inertia) {
        self.gather(inertia, Source::P);
        for (e, &(a, b)) in self.ends.iter().enumerate() {
            self.q[e] = self.direction[e].dot(self.push[b as usize] - self.push[a as usize]);
        }
    }

    /// push = W Jᵀ p (or λ): each node's impulses from its (at most four) edges, gathered.
    fn gather(&mut self, inertia: Inertia, source: Source) {
        let (rows, columns) = (self.rows, self.columns);
        let row_edges = rows * (columns - 1);
        let values = match source {
            Source::P => &self.p,
            Source::Lambda => &self.lambda,
        };
        let d = &self.direction;
        for k in 0..rows {
            for j in 0..columns {
                let mut f = Vec3::ZERO;
                // The row's edges before and after node (k, j), then the column's.
                let row = j * rows + k;
                if j > 0 {
                    f += d[row - rows] * values[row - rows];
                }
                if j + 1 < columns {
                    f -= d[row] * values[row];
                }
                let column = row_edges + k * columns + j;
                if k > 0 {
                    f += d[column - columns] * values[column - columns];
                }
                if k + 1 < rows {
                    f -= d[column] * values[column];
                }
                let i = k * columns + j;
                self.push[i] = inertia.apply(i, f);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aero::particles::constraints::tests::{normals_and_betas, unit};

    /// A flat `rows × columns` grid of 0.1 m cells, row-major, hanging down from y = 0.
    fn flat_grid(rows: usize, columns: usize) -> Vec<Vec3> {
        (0..rows * columns)
            .map(|i| {
                Vec3::new(
                    (i % columns) as f32 * 0.1,
                    -((i / columns) as f32) * 0.1,
                    0.0,
                )
            })
            .collect()
    }

    /// The preconditioner solves each line's tridiagonal block: P z = r, with P's diagonal and
    /// its coupling between a line's consecutive edges, on grids whose lines are one edge long
    /// (2 × N, N × 2) and longer.
    #[test]
    fn the_lines_preconditioner_inverts_their_blocks() {
        for (seed, (rows, columns)) in [(2, 5), (5, 2), (4, 6), (3, 3), (7, 4)]
            .into_iter()
            .enumerate()
        {
            let r = |i: usize| unit(seed as u64 * 104_729 + i as u64);
            let n = rows * columns;
            let rest = flat_grid(rows, columns);
            let x: Vec<Vec3> = rest
                .iter()
                .enumerate()
                .map(|(i, p)| *p + Vec3::new(r(3 * i), r(3 * i + 1), r(3 * i + 2)) * 0.02)
                .collect();
            let (normals, beta) = normals_and_betas(n, |i| unit(seed as u64 * 31 + i));
            let inverse_mass: Vec<f32> = (0..n)
                .map(|i| {
                    if i % columns == 0 {
                        0.0
                    } else {
                        10.0 + 10.0 * r(7 * n + i).abs()
                    }
                })
                .collect();
            let inertia = Inertia {
                inverse_mass: &inverse_mass,
                normals: &normals,
                beta: &beta,
            };
            let mut yarns = Yarns::new(rows, columns, &rest);
            let count = yarns.rest.len();
            for e in 0..count {
                yarns.linearise::<f32>(&x, inertia, e);
            }
            yarns.factorise(inertia);
            assert_eq!(yarns.solves.guarded_pivots, 0);
            for e in 0..count {
                yarns.r[e] = r(11 * n + e);
            }
            yarns.precondition();
            for &(first, length, lines) in &yarns.families {
                let (first, length, lines) = (first as usize, length as usize, lines as usize);
                for j in 0..length {
                    for line in 0..lines {
                        let i = first + j * lines + line;
                        let mut pz = yarns.diagonal[i] * yarns.z[i];
                        if j > 0 {
                            pz += yarns.off[i - lines] * yarns.z[i - lines];
                        }
                        if j + 1 < length {
                            pz += yarns.off[i] * yarns.z[i + lines];
                            // The coupling is between the edges sharing a node.
                            assert_eq!(yarns.ends[i].1, yarns.ends[i + lines].0);
                        }
                        // |r| < 1: an absolute bound.
                        assert!(
                            (pz - yarns.r[i]).abs() <= 1e-4,
                            "{rows} x {columns}, edge {i}: {pz} against {}",
                            yarns.r[i]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn edges_linearised_in_lanes_have_the_bits_of_one_at_a_time() {
        let (rows, columns) = (5, 7);
        let n = rows * columns;
        let rest = flat_grid(rows, columns);
        for seed in 0..20u64 {
            let r = |i: u64| unit(seed * 7_919 + i);
            let mut x: Vec<Vec3> = rest
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    *p + Vec3::new(r(3 * i as u64), r(3 * i as u64 + 1), r(3 * i as u64 + 2)) * 0.03
                })
                .collect();
            // Extremes: an edge of zero length (from node 8 to 9), a NaN, a node far off.
            x[9] = x[8];
            if seed % 2 == 0 {
                x[20].z = f32::NAN;
            }
            x[30] *= 1e25;
            let (normals, beta) = normals_and_betas(n, r);
            let inverse_mass: Vec<f32> = (0..n)
                .map(|i| if i % columns == 0 { 0.0 } else { 20.0 })
                .collect();
            let inertia = Inertia {
                inverse_mass: &inverse_mass,
                normals: &normals,
                beta: &beta,
            };
            let mut lanes = Yarns::new(rows, columns, &rest);
            let mut one = lanes.clone();
            let count = lanes.rest.len();
            assert!(count >= 8 && !count.is_multiple_of(4));
            for first in (0..count - count % 4).step_by(4) {
                lanes.linearise::<wide::f32x4>(&x, inertia, first);
            }
            for e in 0..count {
                if e >= count - count % 4 {
                    lanes.linearise::<f32>(&x, inertia, e);
                }
                one.linearise::<f32>(&x, inertia, e);
            }
            let bits = |y: &Yarns| {
                y.direction
                    .iter()
                    .flat_map(|d| [d.x, d.y, d.z])
                    .chain(y.diagonal.iter().copied())
                    .chain(y.r.iter().copied())
                    .map(f32::to_bits)
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&lanes), bits(&one), "seed {seed}");
            // Both ends pinned (the pole's yarn) or degenerate: left as they are.
            let edge = |a: u32, b: u32| one.ends.iter().position(|e| *e == (a, b)).unwrap();
            let pole = edge(0, columns as u32);
            assert_eq!((one.direction[pole], one.diagonal[pole]), (Vec3::ZERO, 1.0));
            let short = edge(8, 9);
            assert_eq!(
                (one.direction[short], one.diagonal[short]),
                (Vec3::ZERO, 1.0)
            );
            let free = edge(1, 2);
            assert!(one.diagonal[free] > 0.0 && one.direction[free].is_normalized());
        }
    }
}
