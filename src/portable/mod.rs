//! Portable arithmetic: the numbers the fall's step and the wind's read compute, written once
//! for one number or for SIMD lanes ([`lane::Lane`]), in plain IEEE-754 operations in a fixed
//! order: the same bits on every machine, in every lane, on any number of threads and in the
//! browser. What is here: the lane abstraction, the transcendental kernels the step calls
//! ([`transcendental`]) and fixed-order vectors and quaternions ([`geometry`]). Everything else the
//! crate computes rarely (a new swing, a Markov step, the database at start-up) uses the
//! pure-Rust `libm`, which is portable in the same way.

use std::sync::atomic::{AtomicUsize, Ordering};

#[cfg(target_arch = "x86_64")]
pub(crate) mod avx;
pub(crate) mod geometry;
pub(crate) mod lane;
pub(crate) mod transcendental;

/// The most falls a step may put side by side in SIMD lanes (8 unless lowered): their bits are
/// the same at every width, so this only changes the speed.
static WIDTH: AtomicUsize = AtomicUsize::new(8);

/// Turns the lanes off (`false`: one fall at a time) or on (the widest this CPU has): for tests
/// and benchmarks that compare the two, which must give the same bits. Not part of the crate's
/// interface.
#[doc(hidden)]
pub fn set_lanes(on: bool) {
    set_lane_width(if on { 8 } else { 1 });
}

/// The most falls a step may put side by side: 1, 4 or 8 (0 counts as 1, 2–7 as 4, more as
/// 8; 8 takes effect only where the CPU has AVX2, else 4). For tests and benchmarks that compare
/// widths, which must give the same bits. Not part of the crate's interface.
#[doc(hidden)]
pub fn set_lane_width(width: usize) {
    WIDTH.store(width, Ordering::Relaxed);
}

/// The lane width the falls' steps use now: 1, 4 or 8 (8 only on x86-64 with AVX2, checked
/// at run time).
pub(crate) fn lane_width() -> usize {
    match WIDTH.load(Ordering::Relaxed) {
        0 | 1 => 1,
        2..=7 => 4,
        _ if widest_lanes() == 8 => 8,
        _ => 4,
    }
}

/// The widest lanes this CPU runs: 8 with AVX2 (x86-64), else 4. Not part of the crate's
/// interface.
#[doc(hidden)]
pub fn widest_lanes() -> usize {
    #[cfg(target_arch = "x86_64")]
    if avx::has_avx2() {
        return 8;
    }
    4
}

#[cfg(test)]
mod tests;

/// Σ a b in a fixed order: the products go eight at a time into eight running sums of type `S`
/// (f32 or f64, given by `widen`: eight chains of additions side by side rather than one), those
/// of the last `a.len() % 8` into an f64 sum, and the eight are added to it in f64.
pub(crate) fn dot<S>(a: &[f32], b: &[f32], widen: impl Fn(f32) -> S) -> f64
where
    S: Copy + Default + std::ops::AddAssign + Into<f64>,
{
    let mut sums = [S::default(); 8];
    let (chunks_a, chunks_b) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = chunks_a
        .remainder()
        .iter()
        .zip(chunks_b.remainder())
        .map(|(x, y)| f64::from(x * y))
        .sum();
    for (x, y) in chunks_a.zip(chunks_b) {
        for k in 0..8 {
            sums[k] += widen(x[k] * y[k]);
        }
    }
    tail + sums.iter().map(|s| (*s).into()).sum::<f64>()
}
