//! Spectral 1/f^β noise (fractional Brownian motion) in any number of dimensions.
//!
//! A random spectrum is shaped so that the power spectral density of an n-dimensional field falls
//! as `1/|f|^(β+n−1)` (eq. 13 of *Realistic Motion Simulations of Objects in Free Fall* (Xie and Miyata); eq. 1 and §3.1 of
//! *Fourier Descriptor Animation of Cloth Flapping in Wind* (Tynystanova and Chiba), where the text notes that the exponent must be
//! `β+n−1` for n-dimensional noise), then brought to real space by an inverse FFT.
//! Along any straight line through the field the power spectrum then falls as `1/f^β`, which is
//! what the tests measure.
//!
//! | quantity | meaning |
//! |---|---|
//! | `dims` | grid nodes per axis, row-major (last index fastest), each ≥ 2, at most [`Synthesizer::MAX_AXES`](crate::spectrum::Synthesizer::MAX_AXES) axes and [`Synthesizer::MAX_NODES`](crate::spectrum::Synthesizer::MAX_NODES) nodes in all |
//! | `beta` | spectral exponent β ≥ 0: 0 white, 1 pink, 5/3 Kolmogorov, 2 Brownian |
//! | `seed` | 64-bit seed of a PCG stream: same seed, same field, bit for bit |
//!
//! The fields are periodic along every axis (they tile), have zero mean and unit variance.
//!
//! # Portability
//! Randomness comes from [`rand_pcg::Pcg64`] and the inverse FFT from rustfft's *scalar*
//! planner, so no CPU-feature detection changes the order of floating-point operations: the
//! output is the same bit for bit on every machine and any thread count. The SIMD planners of
//! rustfft are faster but pick different algorithms on different CPUs; [`FftBackend::Simd`]
//! selects them for a [`Synthesizer`] where speed matters more than cross-machine bits.

mod amplitude;
mod error;
mod fft;
mod grid;
mod normal;

pub(crate) use normal::standard_normal;
mod sample;
mod synth;
pub use error::SpectrumError;
pub use fft::FftBackend;
pub(crate) use grid::GridShape;
pub(crate) use sample::periodic_lerp;
pub use synth::{Synthesizer, fbm};
