//! Portable arithmetic: the numbers the fall's step and the wind's read compute, written once
//! for one number or for SIMD lanes ([`lane::Lane`]), in plain IEEE-754 operations in a fixed
//! order: the same bits on every machine, in every lane, on any number of threads and in the
//! browser. What is here: the lane abstraction, the transcendental kernels the step calls
//! ([`transcendental`]) and fixed-order vectors and quaternions ([`geometry`]). Everything else the
//! crate computes rarely (a new swing, a Markov step, the database at start-up) uses the
//! pure-Rust `libm`, which is portable in the same way.

use std::sync::atomic::{AtomicBool, Ordering};

pub(crate) mod geometry;
pub(crate) mod lane;
pub(crate) mod transcendental;

/// Whether the falls' usual steps go several at a time in SIMD lanes (on unless turned off):
/// their bits are the same either way, so this only changes the speed.
static LANES: AtomicBool = AtomicBool::new(true);

/// Turns the lanes off (`false`) or on: for tests and benchmarks that compare the two, which
/// must give the same bits. Not part of the crate's interface.
#[doc(hidden)]
pub fn set_lanes(on: bool) {
    LANES.store(on, Ordering::Relaxed);
}

/// Whether the lanes are on.
pub(crate) fn lanes_enabled() -> bool {
    LANES.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests;
