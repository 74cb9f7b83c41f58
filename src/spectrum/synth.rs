//! Synthesis of 1/f^β fields: shaped Hermitian spectrum, inverse FFT, normalisation.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rustfft::{FftPlannerScalar, num_complex::Complex};
use thiserror::Error;

use super::grid::GridShape;

/// Why a noise field could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SpectrumError {
    /// No axis was given.
    #[error("`dims` is empty: a field needs at least one axis")]
    NoAxis,
    /// An axis has fewer than two nodes.
    #[error("`dims[{axis}]` = {len}: every axis needs at least 2 nodes")]
    AxisTooShort {
        /// Which axis.
        axis: usize,
        /// Its node count.
        len: usize,
    },
    /// β is negative or not finite.
    #[error("`beta` = {0}: the spectral exponent must be finite and ≥ 0")]
    Beta(f32),
}

/// A real, periodic, zero-mean, unit-variance 1/f^β field on a row-major grid.
///
/// Power spectral density `S(f) ∝ 1/|f|^(β+n−1)` (free-fall paper eq. 13, cloth paper eq. 1), so
/// along any line the spectrum falls as `1/f^β`.
///
/// # Panics
/// On the inputs [`try_fbm`] rejects: an empty `dims`, an axis shorter than 2, or a negative or
/// non-finite `beta`.
pub fn fbm(dims: &[usize], beta: f32, seed: u64) -> Vec<f32> {
    try_fbm(dims, beta, seed).unwrap_or_else(|e| panic!("fbm: {e}"))
}

/// [`fbm`] with a typed error instead of a panic.
pub fn try_fbm(dims: &[usize], beta: f32, seed: u64) -> Result<Vec<f32>, SpectrumError> {
    let (a, _) = synthesize(dims, beta, seed, false)?;
    Ok(a)
}

/// Two independent fields from one complex inverse FFT (the real parts of one spectrum's
/// transform are the first field, the imaginary parts the second), at the cost of one field.
///
/// # Panics
/// On the inputs [`try_fbm_pair`] rejects.
pub fn fbm_pair(dims: &[usize], beta: f32, seed: u64) -> (Vec<f32>, Vec<f32>) {
    try_fbm_pair(dims, beta, seed).unwrap_or_else(|e| panic!("fbm_pair: {e}"))
}

/// [`fbm_pair`] with a typed error instead of a panic.
pub fn try_fbm_pair(
    dims: &[usize],
    beta: f32,
    seed: u64,
) -> Result<(Vec<f32>, Vec<f32>), SpectrumError> {
    synthesize(dims, beta, seed, true)
}

fn validate(dims: &[usize], beta: f32) -> Result<(), SpectrumError> {
    if dims.is_empty() {
        return Err(SpectrumError::NoAxis);
    }
    if let Some((axis, &len)) = dims.iter().enumerate().find(|&(_, &n)| n < 2) {
        return Err(SpectrumError::AxisTooShort { axis, len });
    }
    if !beta.is_finite() || beta < 0.0 {
        return Err(SpectrumError::Beta(beta));
    }
    Ok(())
}

fn synthesize(
    dims: &[usize],
    beta: f32,
    seed: u64,
    pair: bool,
) -> Result<(Vec<f32>, Vec<f32>), SpectrumError> {
    validate(dims, beta)?;
    let shape = GridShape::new(dims);
    let mut spectrum = hermitian_spectrum(&shape, beta, seed, pair);
    inverse_fft_nd(&mut spectrum, &shape);
    let first = normalized(spectrum.iter().map(|c| c.re));
    let second = if pair {
        normalized(spectrum.iter().map(|c| c.im))
    } else {
        Vec::new()
    };
    Ok((first, second))
}

/// Fourier coefficients `F(k) = A(k) · (X + iY)`, X, Y standard normal (the cloth paper's
/// `C · Nrand` with a random phase, eq. 1), with `F(−k) = F(k)*` exactly, so the inverse transform
/// is real. Bins that are their own mirror (DC, Nyquist) get a real value of the same expected
/// power; DC is zero, so the mean is zero. `A(k)` is [`AmplitudeTable`]'s.
///
/// With `pair`, a second independent Hermitian spectrum `G` is folded in as `F + iG`, whose
/// inverse transform is `f + i g` with `f`, `g` both real.
fn hermitian_spectrum(shape: &GridShape, beta: f32, seed: u64, pair: bool) -> Vec<Complex<f32>> {
    let table = AmplitudeTable::new(shape.dims(), beta);
    let mut normals = NormalPairs(Pcg64::seed_from_u64(seed));
    let zero = Complex::new(0.0f32, 0.0);
    let i = Complex::new(0.0f32, 1.0);
    let mut out = vec![zero; shape.len()];
    for flat in 1..shape.len() {
        let mirror = shape.mirror(flat);
        if mirror < flat {
            continue; // set together with its partner
        }
        let amplitude = table.at(shape, flat);
        let a = normals.next();
        let b = if pair { normals.next() } else { zero };
        if mirror == flat {
            // Real, with the power of a complex bin: √2 · X.
            let s = std::f32::consts::SQRT_2;
            out[flat] = Complex::new(a.re * s, b.re * s) * amplitude;
        } else {
            out[flat] = (a + i * b) * amplitude;
            out[mirror] = (a.conj() + i * b.conj()) * amplitude;
        }
    }
    out
}

/// Spectral amplitude `A(f) = √S(f)` of eq. 13 (free-fall paper), `S(f) = |f|^−(β+n−1)`, with
/// `f` in cycles per node, for a continuous field sampled at the nodes: each bin also receives
/// the power of its nearest alias along every axis, `S_grid(f) = Σ_{m ∈ {0,1}ⁿ} S(|f| − m)`.
///
/// Without the aliases, a line through an n-D field misses the power of the transverse
/// frequencies beyond Nyquist and its spectrum steepens (slope −1.13 instead of −1 for β = 1 on a
/// 128³ grid); with them, the line spectra follow `f^−β` within 0.04 up to a quarter of Nyquist.
/// `S` depends only on `|f_i|`, so it is tabulated on one octant. Powers use the `libm` crate
/// (pure Rust) so the table is the same on every platform; they are taken relative to the
/// lowest frequency's, which only rescales the field before normalisation and never overflows.
struct AmplitudeTable {
    half: Vec<usize>,
    values: Vec<f32>,
}

impl AmplitudeTable {
    fn new(dims: &[usize], beta: f32) -> Self {
        let half: Vec<usize> = dims.iter().map(|&n| n / 2 + 1).collect();
        let octant = GridShape::new(&half);
        let exponent = -(f64::from(beta) + dims.len() as f64 - 1.0) / 2.0;
        // Powers relative to the lowest frequency's, in log space: no overflow for any β.
        let f2_min = dims.iter().map(|&n| 1.0 / (n * n) as f64).fold(f64::MAX, f64::min);
        let log_f2_min = libm::log(f2_min);
        let mut index = vec![0usize; dims.len()];
        let values = (0..octant.len())
            .map(|flat| {
                let mut rest = flat;
                for (axis, &stride) in octant.strides().iter().enumerate() {
                    index[axis] = rest / stride;
                    rest %= stride;
                }
                let mut power = 0.0;
                for images in 0..(1usize << dims.len()) {
                    let f2: f64 = (0..dims.len())
                        .map(|a| {
                            let f = index[a] as f64 / dims[a] as f64;
                            let f = if images >> a & 1 == 1 { 1.0 - f } else { f };
                            f * f
                        })
                        .sum();
                    if f2 > 0.0 {
                        power += libm::exp(exponent * (libm::log(f2) - log_f2_min));
                    }
                }
                libm::sqrt(power) as f32
            })
            .collect();
        Self { half, values }
    }

    /// Amplitude of the bin at `flat` in the full grid `shape`.
    fn at(&self, shape: &GridShape, flat: usize) -> f32 {
        let mut rest = flat;
        let mut index = 0;
        for ((&n, &stride), &h) in shape.dims().iter().zip(shape.strides()).zip(&self.half) {
            let i = rest / stride;
            rest %= stride;
            index = index * h + i.min(n - i);
        }
        self.values[index]
    }
}

/// Standard complex normals `X + iY` from a PCG stream by the Box–Muller transform, with the
/// `libm` crate's pure-Rust `log` and `sincos`, so the numbers are the same on every platform.
struct NormalPairs(Pcg64);

impl NormalPairs {
    fn next(&mut self) -> Complex<f32> {
        // u1 in (0, 1]: never ln(0).
        let u1 = 1.0 - self.0.random::<f64>();
        let u2 = self.0.random::<f64>();
        let r = libm::sqrt(-2.0 * libm::log(u1));
        let (sin, cos) = libm::sincos(std::f64::consts::TAU * u2);
        Complex::new((r * cos) as f32, (r * sin) as f32)
    }
}

/// In-place n-dimensional inverse FFT, one axis at a time, with rustfft's scalar planner
/// (portable: see the module docs). Lines along an axis are gathered into a contiguous buffer
/// so that rustfft transforms them as one batch.
pub(crate) fn inverse_fft_nd(data: &mut [Complex<f32>], shape: &GridShape) {
    let mut planner = FftPlannerScalar::<f32>::new();
    let mut lines = Vec::new();
    let mut scratch = Vec::new();
    let zero = Complex::new(0.0, 0.0);
    for (&n, &stride) in shape.dims().iter().zip(shape.strides()) {
        let fft = planner.plan_fft_inverse(n);
        scratch.resize(fft.get_inplace_scratch_len(), zero);
        if stride == 1 {
            fft.process_with_scratch(data, &mut scratch);
            continue;
        }
        let block_len = n * stride;
        lines.resize(block_len, zero);
        for block in data.chunks_exact_mut(block_len) {
            for (i, row) in block.chunks_exact(stride).enumerate() {
                for (j, &value) in row.iter().enumerate() {
                    lines[j * n + i] = value;
                }
            }
            fft.process_with_scratch(&mut lines, &mut scratch);
            for (i, row) in block.chunks_exact_mut(stride).enumerate() {
                for (j, value) in row.iter_mut().enumerate() {
                    *value = lines[j * n + i];
                }
            }
        }
    }
}

/// Shift to zero mean and scale to unit variance (sums in f64, in index order).
fn normalized(values: impl Iterator<Item = f32> + Clone) -> Vec<f32> {
    let (mut count, mut sum) = (0usize, 0.0f64);
    for v in values.clone() {
        count += 1;
        sum += f64::from(v);
    }
    let mean = sum / count as f64;
    let variance = values
        .clone()
        .map(|v| (f64::from(v) - mean).powi(2))
        .sum::<f64>()
        / count as f64;
    let scale = if variance > 0.0 {
        1.0 / variance.sqrt()
    } else {
        0.0
    };
    values
        .map(|v| ((f64::from(v) - mean) * scale) as f32)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectrum_is_exactly_hermitian() {
        for dims in [&[6usize][..], &[5, 4], &[3, 4, 5]] {
            let shape = GridShape::new(dims);
            let s = hermitian_spectrum(&shape, 5.0 / 3.0, 9, false);
            for flat in 0..shape.len() {
                assert_eq!(s[flat], s[shape.mirror(flat)].conj(), "{dims:?} bin {flat}");
            }
            assert_eq!(s[0], Complex::new(0.0, 0.0));
        }
    }

    #[test]
    fn transform_of_the_spectrum_is_real() {
        for dims in [&[64usize][..], &[15, 16], &[8, 9, 10]] {
            let shape = GridShape::new(dims);
            let mut field = hermitian_spectrum(&shape, 5.0 / 3.0, 1, false);
            inverse_fft_nd(&mut field, &shape);
            let max_re = field.iter().map(|c| c.re.abs()).fold(0.0, f32::max);
            let max_im = field.iter().map(|c| c.im.abs()).fold(0.0, f32::max);
            assert!(max_im <= 1e-5 * max_re, "{dims:?}: imaginary {max_im} real {max_re}");
        }
    }

    #[test]
    fn inverse_fft_matches_direct_sum() {
        let shape = GridShape::new(&[3, 4]);
        let spectrum = hermitian_spectrum(&shape, 1.0, 4, true);
        let mut fast = spectrum.clone();
        inverse_fft_nd(&mut fast, &shape);
        for (x, y) in [(0usize, 0usize), (1, 2), (2, 3)] {
            let mut direct = Complex::new(0.0f64, 0.0);
            for k in 0..3 {
                for l in 0..4 {
                    let phase = std::f64::consts::TAU * ((k * x) as f64 / 3.0 + (l * y) as f64 / 4.0);
                    let c = spectrum[k * 4 + l];
                    let c = Complex::new(f64::from(c.re), f64::from(c.im));
                    direct += c * Complex::new(phase.cos(), phase.sin());
                }
            }
            let got = fast[x * 4 + y];
            assert!((f64::from(got.re) - direct.re).abs() < 1e-4);
            assert!((f64::from(got.im) - direct.im).abs() < 1e-4);
        }
    }

    #[test]
    fn bad_input_is_named() {
        assert_eq!(try_fbm(&[], 1.0, 0), Err(SpectrumError::NoAxis));
        assert_eq!(
            try_fbm(&[8, 1], 1.0, 0),
            Err(SpectrumError::AxisTooShort { axis: 1, len: 1 })
        );
        assert_eq!(try_fbm(&[8], -0.5, 0), Err(SpectrumError::Beta(-0.5)));
        assert!(matches!(try_fbm(&[8], f32::NAN, 0), Err(SpectrumError::Beta(_))));
    }
}
