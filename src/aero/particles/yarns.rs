//! Inextensible yarns: every edge along the rows and the columns kept at its rest length at once.
//!
//! Linearised at the predicted positions, the edges' multipliers solve (J W Jᵀ) Δλ = −C, J the
//! edges' gradients and W the nodes' inverse inertia, then Δx = W Jᵀ Δλ. The system is solved
//! by conjugate gradients preconditioned with its own grid lines (each row's and each column's
//! edges form a tridiagonal block, factorised once by Thomas' algorithm): exact for an unsheared
//! grid, whose rows and columns do not couple, and a few iterations where shear couples them.

use bevy::math::Vec3;

use super::constraints::{Inertia, finite, gather};
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
    /// The last solve's residual relative to its start, in the preconditioned norm.
    pub last_residual: f32,
}

/// What [`Yarns::gather`] spreads to the nodes.
#[derive(Clone, Copy)]
enum Source {
    P,
    Lambda,
}

/// Σ a b, in f64 sums of f32 products taken eight at a time.
fn dot(a: &[f32], b: &[f32]) -> f64 {
    let mut sums = [0.0f32; 8];
    let (chunks_a, chunks_b) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = chunks_a
        .remainder()
        .iter()
        .zip(chunks_b.remainder())
        .map(|(x, y)| f64::from(x * y))
        .sum();
    for (x, y) in chunks_a.zip(chunks_b) {
        for k in 0..8 {
            sums[k] += x[k] * y[k];
        }
    }
    tail + sums.iter().map(|s| f64::from(*s)).sum::<f64>()
}

/// Conjugate-gradient iterations per projection, at most.
const MOST_ITERATIONS: usize = 12;
/// The iterations stop once the residual has fallen by this factor (in the preconditioned
/// norm): the part of the constraints left unsolved turns into velocity at the next substep,
/// so it is made small against the substep's own correction, not against the edge.
const TOLERANCE: f64 = 1e-2;

/// The edges of a `rows × columns` grid: along each row (row by row), then along each column
/// (column by column), with their rest lengths and the solver's work space.
#[derive(Clone, Debug, Default)]
pub(super) struct Yarns {
    rows: usize,
    columns: usize,
    /// Each edge's nodes, and the two families of equal lines lying one after another (the
    /// rows, the columns) as (first edge, edges per line, lines).
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
    pub(super) solves: YarnSolves,
}

impl Yarns {
    /// The yarns of a `rows × columns` grid at `positions`, their rest lengths.
    pub(super) fn new(rows: usize, columns: usize, positions: &[Vec3]) -> Self {
        let mut ends = Vec::new();
        for (count, stride, lanes, step) in
            [(columns, 1, rows, columns), (rows, columns, columns, 1)]
        {
            for lane in 0..lanes {
                let first = lane * step;
                ends.extend((0..count - 1).map(|j| {
                    let a = first + j * stride;
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
            solves: YarnSolves::default(),
        }
    }

    /// Largest |length / rest − 1| over the edges.
    pub(super) fn max_strain(&self, x: &[Vec3]) -> f32 {
        self.ends
            .iter()
            .zip(&self.rest)
            .map(|(&(a, b), rest)| (x[a as usize].distance(x[b as usize]) / rest - 1.0).abs())
            .fold(0.0, f32::max)
    }

    /// Projects `x` onto the yarns' rest lengths (one linearisation).
    pub(super) fn project(&mut self, x: &mut [Vec3], inertia: Inertia) {
        let count = self.rest.len();
        let lanes = count - count % 4;
        for first in (0..lanes).step_by(4) {
            self.linearise::<wide::f32x4>(x, inertia, first);
        }
        for e in lanes..count {
            self.linearise::<f32>(x, inertia, e);
        }
        // The lines' blocks (a line's last edge couples to nothing) and their factors.
        for &(first, length, count) in &self.families {
            let (first, length) = (first as usize, length as usize);
            for line in 0..count as usize {
                let last = first + (line + 1) * length - 1;
                for j in first + line * length..last {
                    let shared = self.ends[j].1 as usize;
                    self.off[j] =
                        -inertia.product(shared, self.direction[j], self.direction[j + 1]);
                }
                self.off[last] = 0.0;
            }
        }
        for &(first, length, count) in &self.families {
            let (first, length, count) = (first as usize, length as usize, count as usize);
            for j in 0..length {
                for line in 0..count {
                    let i = first + line * length + j;
                    let below = if j > 0 {
                        self.off[i - 1] * self.upper[i - 1]
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
        self.solve(inertia);
        // Δx = W Jᵀ λ.
        self.gather(inertia, Source::Lambda);
        for (x, dx) in x.iter_mut().zip(&self.push) {
            if dx.is_finite() {
                *x += *dx;
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

    /// λ ≈ A⁻¹ r, A = J W Jᵀ, by conjugate gradients from zero (r is overwritten; see
    /// [`TOLERANCE`]).
    fn solve(&mut self, inertia: Inertia) {
        let count = self.rest.len();
        self.lambda.fill(0.0);
        self.precondition();
        self.p.copy_from_slice(&self.z);
        let mut rz = dot(&self.r, &self.z);
        let first = rz;
        let enough = rz * TOLERANCE * TOLERANCE;
        let mut iterations = 0;
        for _ in 0..MOST_ITERATIONS {
            if !(rz > enough && rz.is_finite()) {
                break;
            }
            iterations += 1;
            self.multiply(inertia);
            let pq = dot(&self.p, &self.q);
            if !(pq > 0.0 && pq.is_finite()) {
                break;
            }
            let alpha = (rz / pq) as f32;
            for e in 0..count {
                self.lambda[e] += alpha * self.p[e];
                self.r[e] -= alpha * self.q[e];
            }
            self.precondition();
            let next = dot(&self.r, &self.z);
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
    /// side, so that their recurrences run at once.
    fn precondition(&mut self) {
        for &(first, length, count) in &self.families {
            let (first, length, count) = (first as usize, length as usize, count as usize);
            let at = |line: usize, j: usize| first + line * length + j;
            for line in 0..count {
                let i = at(line, 0);
                self.z[i] = self.r[i] * self.inverse_pivot[i];
            }
            for j in 1..length {
                for line in 0..count {
                    let i = at(line, j);
                    self.z[i] =
                        (self.r[i] - self.off[i - 1] * self.z[i - 1]) * self.inverse_pivot[i];
                }
            }
            for j in (0..length - 1).rev() {
                for line in 0..count {
                    let i = at(line, j);
                    self.z[i] -= self.upper[i] * self.z[i + 1];
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
                let row = k * (columns - 1) + j;
                if j > 0 {
                    f += d[row - 1] * values[row - 1];
                }
                if j + 1 < columns {
                    f -= d[row] * values[row];
                }
                let column = row_edges + j * (rows - 1) + k;
                if k > 0 {
                    f += d[column - 1] * values[column - 1];
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

    #[test]
    fn edges_linearised_in_lanes_have_the_bits_of_one_at_a_time() {
        let (rows, columns) = (5, 7);
        let n = rows * columns;
        let rest: Vec<Vec3> = (0..n)
            .map(|i| {
                Vec3::new(
                    (i % columns) as f32 * 0.1,
                    -((i / columns) as f32) * 0.1,
                    0.0,
                )
            })
            .collect();
        for seed in 0..20u64 {
            let r = |i: u64| unit(seed * 7_919 + i);
            let mut x: Vec<Vec3> = rest
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    *p + Vec3::new(r(3 * i as u64), r(3 * i as u64 + 1), r(3 * i as u64 + 2)) * 0.03
                })
                .collect();
            // Extremes: an edge of zero length (the 8th, from node 8 to 9), a NaN, a node far
            // off.
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
            let pole = rows * (columns - 1);
            assert_eq!((one.direction[pole], one.diagonal[pole]), (Vec3::ZERO, 1.0));
            assert_eq!((one.direction[7], one.diagonal[7]), (Vec3::ZERO, 1.0));
            assert!(one.diagonal[1] > 0.0 && one.direction[1].is_normalized());
        }
    }
}
