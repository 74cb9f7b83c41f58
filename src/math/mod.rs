//! Portable arithmetic: the numbers the fall's step and the wind's read compute, written once
//! for one number or for SIMD lanes ([`lane::Lane`]), in plain IEEE-754 operations in a fixed
//! order: the same bits on every machine, in every lane, on any number of threads and in the
//! browser. What is here: the lane abstraction, the transcendental kernels the step calls
//! ([`kernels`]) and fixed-order vectors and quaternions ([`geometry`]). Everything else the
//! crate computes rarely (a new swing, a Markov step, the database at start-up) uses the
//! pure-Rust `libm`, which is portable in the same way.

pub(crate) mod geometry;
pub(crate) mod kernels;
pub(crate) mod lane;

#[cfg(test)]
mod tests;
