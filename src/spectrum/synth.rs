//! Synthesis of 1/f^β fields: shaped Hermitian spectrum, inverse FFT, normalisation.

use std::sync::{Arc, Mutex};

use rustfft::num_complex::Complex;

use super::amplitude::AmplitudeTable;
use super::error::SpectrumError;
use super::fft::{FftBackend, InverseFftNd};
use super::grid::GridShape;
use super::normal::NormalPairs;

/// A real, periodic, zero-mean, unit-variance 1/f^β field on a row-major grid.
///
/// Power spectral density `S(f) ∝ 1/|f|^(β+n−1)` (free-fall paper eq. 13, cloth paper eq. 1), so
/// along any line the spectrum falls as `1/f^β`.
///
/// # Errors
/// An empty `dims`, more axes than [`Synthesizer::MAX_AXES`], an axis shorter than 2, more
/// nodes than [`Synthesizer::MAX_NODES`], or a negative or non-finite `beta`: a
/// [`SpectrumError`] naming which.
pub fn fbm(dims: &[usize], beta: f32, seed: u64) -> Result<Vec<f32>, SpectrumError> {
    Ok(Synthesizer::new(dims, beta, FftBackend::Portable)?.field(seed))
}

fn validate(dims: &[usize], beta: f32) -> Result<(), SpectrumError> {
    if dims.is_empty() {
        return Err(SpectrumError::NoAxis);
    }
    if dims.len() > Synthesizer::MAX_AXES {
        return Err(SpectrumError::TooManyAxes { axes: dims.len() });
    }
    if let Some((axis, &len)) = dims.iter().enumerate().find(|&(_, &n)| n < 2) {
        return Err(SpectrumError::AxisTooShort { axis, len });
    }
    if !beta.is_finite() || beta < 0.0 {
        return Err(SpectrumError::Beta(beta));
    }
    let nodes = dims.iter().fold(1usize, |p, &n| p.saturating_mul(n));
    if nodes > Synthesizer::MAX_NODES {
        return Err(SpectrumError::TooManyNodes { nodes });
    }
    Ok(())
}

/// The key of a shared synthesizer: dims, β's bits, backend.
type SharedKey = (Vec<usize>, u32, FftBackend);

static SHARED: Mutex<Vec<(SharedKey, Arc<Synthesizer>)>> = Mutex::new(Vec::new());

/// Makes real, periodic, zero-mean, unit-variance 1/f^β fields of one shape and β. Building it
/// tabulates the spectral amplitudes and plans the transforms once; reuse it for many seeds.
pub struct Synthesizer {
    shape: GridShape,
    table: AmplitudeTable,
    fft: InverseFftNd,
    /// Per axis and index: flat-index offset of the mirrored (negated) index.
    mirror_offsets: Vec<Vec<usize>>,
    /// Per axis and index: offset into the amplitude table.
    table_offsets: Vec<Vec<usize>>,
}

impl Synthesizer {
    /// Validates the input, tabulates amplitudes and plans the inverse FFT.
    pub fn new(dims: &[usize], beta: f32, backend: FftBackend) -> Result<Self, SpectrumError> {
        validate(dims, beta)?;
        let shape = GridShape::new(dims);
        let table = AmplitudeTable::new(dims, beta);
        let mirror_offsets = dims
            .iter()
            .zip(shape.strides())
            .map(|(&n, &stride)| (0..n).map(|i| (n - i) % n * stride).collect())
            .collect();
        Ok(Self {
            table_offsets: table.offsets(dims),
            fft: InverseFftNd::new(&shape, backend),
            shape,
            table,
            mirror_offsets,
        })
    }

    /// A shared synthesizer for `dims`, `beta` and `backend`: the last [`Synthesizer::CACHED`](crate::spectrum::Synthesizer::CACHED)
    /// made this way (of at most [`Synthesizer::MAX_CACHED_NODES`](crate::spectrum::Synthesizer::MAX_CACHED_NODES) nodes) are kept, so rebuilding a field of the same grid and β (a new seed, a new
    /// speed, a rebuilt wind) skips the amplitude table and the FFT planning, which are most of
    /// a small field's cost. The table and plans depend only on the key: the fields are the same
    /// bits either way.
    ///
    /// # Errors
    /// As [`Synthesizer::new`].
    pub fn shared(
        dims: &[usize],
        beta: f32,
        backend: FftBackend,
    ) -> Result<Arc<Self>, SpectrumError> {
        validate(dims, beta)?;
        let key = (dims.to_vec(), beta.to_bits(), backend);
        let mut cache = SHARED
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(i) = cache.iter().position(|(k, _)| *k == key) {
            let hit = cache.remove(i);
            let synth = Arc::clone(&hit.1);
            cache.insert(0, hit);
            return Ok(synth);
        }
        let nodes: usize = dims.iter().product();
        if nodes > Synthesizer::MAX_CACHED_NODES {
            // Too big to keep for the process's life: built, used, dropped.
            drop(cache);
            return Ok(Arc::new(Self::new(dims, beta, backend)?));
        }
        // Built under the lock: two threads asking for the same key build it once.
        let synth = Arc::new(Self::new(dims, beta, backend)?);
        cache.insert(0, (key, Arc::clone(&synth)));
        cache.truncate(Synthesizer::CACHED);
        Ok(synth)
    }

    /// Nodes per axis.
    pub fn dims(&self) -> &[usize] {
        self.shape.dims()
    }

    /// One field.
    pub fn field(&self, seed: u64) -> Vec<f32> {
        let (mut spectrum, power) = self.spectrum(seed, false);
        self.fft.process(&mut spectrum, &self.shape);
        normalized(&spectrum, |c| c.re, power[0])
    }

    /// Two independent fields from one complex inverse FFT: the real parts of the transform are
    /// the first field, the imaginary parts the second.
    pub fn pair(&self, seed: u64) -> (Vec<f32>, Vec<f32>) {
        let (mut spectrum, power) = self.spectrum(seed, true);
        self.fft.process(&mut spectrum, &self.shape);
        (
            normalized(&spectrum, |c| c.re, power[0]),
            normalized(&spectrum, |c| c.im, power[1]),
        )
    }

    /// Fourier coefficients `F(k) = A(k) · (X + iY)`, X, Y standard normal (the cloth paper's
    /// `C · Nrand` with a random phase, eq. 1), with `F(−k) = F(k)*` exactly, so the inverse
    /// transform is real. Bins that are their own mirror (DC, Nyquist) get a real value of the
    /// same expected power; DC is zero, so the mean is zero. `A(k)` is [`AmplitudeTable`]'s.
    ///
    /// With `pair`, a second independent Hermitian spectrum `G` is folded in as `F + iG`, whose
    /// inverse transform is `f + i g` with `f`, `g` both real.
    ///
    /// Also returns `Σ_k |F(k)|²` and `Σ_k |G(k)|²` (in f64, in index order): by Parseval,
    /// the variances of `f` and `g` (the unnormalised inverse transform of `F` has
    /// `Σ_x f² = N Σ_k |F|²`), so normalising needs no pass over the fields.
    fn spectrum(&self, seed: u64, pair: bool) -> (Vec<Complex<f32>>, [f64; 2]) {
        if pair {
            self.spectrum_of::<true>(seed)
        } else {
            self.spectrum_of::<false>(seed)
        }
    }

    /// [`Self::spectrum`], with or without `G`. Bins are visited in flat order, each pair of
    /// mirrors once (at the first of the two): a row whose mirror row comes later is visited
    /// whole, one that comes earlier is skipped, and a row that is its own mirror (a handful)
    /// is visited up to its middle.
    fn spectrum_of<const PAIR: bool>(&self, seed: u64) -> (Vec<Complex<f32>>, [f64; 2]) {
        let dims = self.shape.dims();
        let axes = dims.len();
        let last = dims[axes - 1];
        let zero = Complex::new(0.0f32, 0.0);
        let mut normals = NormalPairs::new(seed);
        let mut out = vec![zero; self.shape.len()];
        let mut power = [0.0f64; 2];
        let (row_mirrors, row_table) = (
            &self.mirror_offsets[axes - 1],
            &self.table_offsets[axes - 1],
        );
        // Odometer over every axis but the last; the last is the inner loop.
        let mut index = vec![0usize; axes - 1];
        for row in (0..out.len()).step_by(last) {
            let mut mirror_row = 0;
            let mut table_row = 0;
            for (axis, &i) in index.iter().enumerate() {
                mirror_row += self.mirror_offsets[axis][i];
                table_row += self.table_offsets[axis][i];
            }
            let columns = match mirror_row.cmp(&row) {
                std::cmp::Ordering::Greater => last,
                std::cmp::Ordering::Equal => last / 2 + 1,
                std::cmp::Ordering::Less => 0, // set with its mirror row
            };
            for j in 0..columns {
                let flat = row + j;
                let mirror = mirror_row + row_mirrors[j];
                if mirror < flat || flat == 0 {
                    continue; // DC stays zero; a partner was set with its mirror
                }
                let amplitude = self.table.at(table_row + row_table[j]);
                let a = normals.next_pair();
                let b = if PAIR { normals.next_pair() } else { zero };
                let a2 = f64::from(amplitude) * f64::from(amplitude);
                if mirror == flat {
                    // Real, with the power of a complex bin: √2 · X.
                    let s = std::f32::consts::SQRT_2 * amplitude;
                    out[flat] = Complex::new(a.re * s, b.re * s);
                    power[0] += 2.0 * a2 * f64::from(a.re * a.re);
                    power[1] += 2.0 * a2 * f64::from(b.re * b.re);
                } else {
                    // F + iG at k and its conjugate partner at −k.
                    out[flat] = Complex::new(a.re - b.im, a.im + b.re) * amplitude;
                    out[mirror] = Complex::new(a.re + b.im, b.re - a.im) * amplitude;
                    power[0] += 2.0 * a2 * f64::from(a.norm_sqr());
                    power[1] += 2.0 * a2 * f64::from(b.norm_sqr());
                }
            }
            for axis in (0..axes - 1).rev() {
                index[axis] += 1;
                if index[axis] < dims[axis] {
                    break;
                }
                index[axis] = 0;
            }
        }
        (out, power)
    }
}

/// One part of a complex field scaled to unit variance, given its variance from the spectrum
/// (its mean is zero: the DC bin is). Rounding in the transform leaves the mean and variance
/// within about 1e-6 of 0 and 1.
fn normalized(
    field: &[Complex<f32>],
    part: impl Fn(&Complex<f32>) -> f32,
    variance: f64,
) -> Vec<f32> {
    let scale = if variance > 0.0 {
        (1.0 / variance.sqrt()) as f32
    } else {
        0.0
    };
    field.iter().map(|c| part(c) * scale).collect()
}

/// Limits and constants of [`Synthesizer`].
impl Synthesizer {
    /// How many synthesizers [`Synthesizer::shared`] keeps (most recently used first).
    pub const CACHED: usize = 4;

    /// Most axes a field may have: 4 (space and time). The amplitude table sums the power of
    /// `2^n` alias images per bin, so without a bound a valid node count spread over many short
    /// axes (`[2; 26]`) would take 2^52 steps to tabulate; with it, the table costs at most 16 steps
    /// per node.
    pub const MAX_AXES: usize = super::error::MAX_AXES;

    /// Grids above this many nodes (2^22: 256³ is above, 128³ below) are not kept: their tables
    /// (a quarter to an eighth of the grid, 4 bytes a bin) would stay for the process's life.
    pub const MAX_CACHED_NODES: usize = 1 << 22;

    /// Largest field (product of `dims`) any synthesis may make: 2^26 nodes. It is checked before
    /// anything is allocated; at the limit a field takes 512 MiB of spectrum while it is made and
    /// 256 MiB of output (twice that for a pair). Every grid derived from user input (wind fields,
    /// cloth noise) is bounded by it or by a smaller limit of its own.
    pub const MAX_NODES: usize = super::error::MAX_NODES;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn synth(dims: &[usize]) -> Synthesizer {
        Synthesizer::new(dims, 5.0 / 3.0, FftBackend::Portable).unwrap()
    }

    #[test]
    fn spectrum_is_exactly_hermitian() {
        for dims in [&[6usize][..], &[5, 4], &[3, 4, 5], &[2, 3, 2, 4]] {
            let s = synth(dims);
            for pair in [false, true] {
                let spectrum = s.spectrum(9, pair).0;
                for flat in 0..spectrum.len() {
                    let (a, m) = (spectrum[flat], spectrum[s.shape.mirror(flat)]);
                    if pair {
                        // F + iG with F, G Hermitian: (F + iG)(−k) = F(k)* + i G(k)*.
                        let f = (a + m.conj()) * 0.5;
                        let g = (a - m.conj()) * Complex::new(0.0, -0.5);
                        let (fm, gm) = (
                            (m + a.conj()) * 0.5,
                            (m - a.conj()) * Complex::new(0.0, -0.5),
                        );
                        assert!((f - fm.conj()).norm() < 1e-6 && (g - gm.conj()).norm() < 1e-6);
                    } else {
                        assert_eq!(a, m.conj(), "{dims:?} bin {flat}");
                    }
                }
                assert_eq!(spectrum[0], Complex::new(0.0, 0.0));
            }
        }
    }

    #[test]
    fn transform_of_the_spectrum_is_real() {
        for dims in [&[64usize][..], &[15, 16], &[8, 9, 10]] {
            let s = synth(dims);
            let mut field = s.spectrum(1, false).0;
            s.fft.process(&mut field, &s.shape);
            let max_re = field.iter().map(|c| c.re.abs()).fold(0.0, f32::max);
            let max_im = field.iter().map(|c| c.im.abs()).fold(0.0, f32::max);
            assert!(
                max_im <= 1e-5 * max_re,
                "{dims:?}: imaginary {max_im} real {max_re}"
            );
        }
    }

    #[test]
    fn inverse_fft_matches_direct_sum() {
        let s = synth(&[3, 4]);
        let spectrum = s.spectrum(4, true).0;
        for backend in [FftBackend::Portable, FftBackend::Simd] {
            let mut fast = spectrum.clone();
            InverseFftNd::new(&s.shape, backend).process(&mut fast, &s.shape);
            for (x, y) in [(0usize, 0usize), (1, 2), (2, 3)] {
                let mut direct = Complex::new(0.0f64, 0.0);
                for k in 0..3 {
                    for l in 0..4 {
                        let phase =
                            std::f64::consts::TAU * ((k * x) as f64 / 3.0 + (l * y) as f64 / 4.0);
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
    }

    #[test]
    fn backends_agree_to_rounding() {
        let portable = synth(&[32, 24]).field(5);
        let simd = Synthesizer::new(&[32, 24], 5.0 / 3.0, FftBackend::Simd)
            .unwrap()
            .field(5);
        for (a, b) in portable.iter().zip(&simd) {
            assert!((a - b).abs() < 1e-4);
        }
    }

    #[test]
    fn bad_input_is_named() {
        assert_eq!(fbm(&[], 1.0, 0), Err(SpectrumError::NoAxis));
        assert_eq!(
            fbm(&[8, 1], 1.0, 0),
            Err(SpectrumError::AxisTooShort { axis: 1, len: 1 })
        );
        assert_eq!(fbm(&[8], -0.5, 0), Err(SpectrumError::Beta(-0.5)));
        assert!(matches!(
            fbm(&[8], f32::NAN, 0),
            Err(SpectrumError::Beta(_))
        ));
    }

    #[test]
    fn sizes_beyond_the_budget_are_refused_before_allocating() {
        for dims in [
            &[1usize << 40][..],
            &[1 << 33, 1 << 33],
            &[1 << 20, 1 << 20],
        ] {
            let error = fbm(dims, 1.0, 0).unwrap_err();
            assert!(
                matches!(error, SpectrumError::TooManyNodes { .. }),
                "{dims:?}"
            );
            assert_eq!(error.field(), "dims");
        }
        // Overflowing products saturate rather than wrap to a small, accepted size.
        let wrap = [1usize << 32, 1 << 32, 4];
        assert_eq!(
            Synthesizer::new(&wrap, 1.0, FftBackend::Portable)
                .map(|_| ())
                .unwrap_err(),
            SpectrumError::TooManyNodes { nodes: usize::MAX }
        );
    }

    #[test]
    fn huge_beta_still_gives_a_unit_variance_field() {
        // Only the lowest frequencies survive an enormous β: the field is a smooth wave, never
        // all zero or NaN, on square and non-square grids alike.
        for dims in [&[64usize][..], &[48, 20], &[7, 12, 5]] {
            for beta in [1.0e9f32, 3.0e20, f32::MAX] {
                let field = fbm(dims, beta, 3).unwrap();
                let n = field.len() as f64;
                let var = field.iter().map(|&v| f64::from(v).powi(2)).sum::<f64>() / n;
                assert!(field.iter().all(|v| v.is_finite()), "{dims:?} β {beta}");
                assert!(
                    (var - 1.0).abs() < 1e-3,
                    "{dims:?} β {beta}: variance {var}"
                );
            }
        }
    }
}
