//! Portable standard normal numbers: a 128-layer ziggurat (Marsaglia & Tsang 2000) in f32.
//!
//! Hand-written rather than `rand_distr::StandardNormal` because that one samples its tail and
//! wedges with std's `ln`/`exp`, which call the platform's C library: the fields must be the
//! same bits on every platform. Here the tables are built once with the `libm` crate (pure
//! Rust) and the rare slow paths use `libm` too.
//!
//! Each 32-bit half of a PCG64 draw gives one attempt: 7 bits pick the layer, 1 bit the sign,
//! 24 bits the position in the layer (independent bits, unlike the original RNOR, whose layer
//! index was the low bits of its uniform). 97.2 % of attempts end in an integer compare and a
//! multiply (98.8 % are accepted in all, the rest after a wedge test), against a `logf`, a `sqrtf`, a division and a 21 % rejection per pair for
//! Marsaglia's polar method used before.

use std::sync::LazyLock;

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rustfft::num_complex::Complex;

/// Layers of the ziggurat.
const LAYERS: usize = 128;
/// Right edge of the base layer: where the tail starts (for 128 layers).
const TAIL_START: f64 = 3.442_619_855_899;
/// Area of each layer under the unnormalised density `exp(−x²/2)` (for 128 layers).
const LAYER_AREA: f64 = 9.912_563_035_262_17e-3;
/// 2^24: the positions are 24-bit fractions.
const POSITION_ONE: f64 = 16_777_216.0;

/// The ziggurat's tables: layer `i` is `[0, x_i) × [f(x_i), f(x_{i+1}))` with `f(x) = exp(−x²/2)`,
/// `x_1 = TAIL_START` and `x_0 = LAYER_AREA / f(x_1)` (the base, whose rectangle stands for the
/// tail too).
struct Tables {
    /// `x_i / 2^24`: a 24-bit position times this is the abscissa.
    scale: [f32; LAYERS],
    /// `⌊2^24 · x_{i+1} / x_i⌋`: positions below it lie under the curve for sure.
    inside: [u32; LAYERS],
    /// `f(x_i)`, with `f(x_128) = 1` appended.
    height: [f32; LAYERS + 1],
}

static TABLES: LazyLock<Tables> = LazyLock::new(|| {
    let f = |x: f64| libm::exp(-0.5 * x * x);
    let mut x = [0.0f64; LAYERS + 1];
    x[0] = LAYER_AREA / f(TAIL_START);
    x[1] = TAIL_START;
    for i in 1..LAYERS - 1 {
        // The next edge up: the layer above has the same area, x_i · (f(x_{i+1}) − f(x_i)).
        x[i + 1] = libm::sqrt(-2.0 * libm::log(LAYER_AREA / x[i] + f(x[i])));
    }
    x[LAYERS] = 0.0;
    let mut tables = Tables {
        scale: [0.0; LAYERS],
        inside: [0; LAYERS],
        height: [0.0; LAYERS + 1],
    };
    for i in 0..LAYERS {
        tables.scale[i] = (x[i] / POSITION_ONE) as f32;
        tables.inside[i] = (POSITION_ONE * x[i + 1] / x[i]) as u32;
        tables.height[i] = f(x[i]) as f32;
    }
    tables.height[LAYERS] = 1.0;
    tables
});

/// Standard complex normals `X + iY` (X, Y independent standard normal) from a PCG stream.
pub(crate) struct NormalPairs {
    rng: Pcg64,
    tables: &'static Tables,
}

impl NormalPairs {
    pub(crate) fn new(seed: u64) -> Self {
        Self {
            rng: Pcg64::seed_from_u64(seed),
            tables: &TABLES,
        }
    }

    pub(crate) fn next_pair(&mut self) -> Complex<f32> {
        let bits = self.rng.next_u64();
        let re = from_tables(self.tables, (bits >> 32) as u32, &mut self.rng);
        let im = from_tables(self.tables, bits as u32, &mut self.rng);
        Complex::new(re, im)
    }
}

/// One standard normal: a first attempt from the 32 bits `bits`, drawing more from `rng` only
/// on the slow path. The crate's one normal sampler: the spectra's pairs (from PCG64) and the
/// falls' Gaussian spreads (from `FallRng`, PCG32) both use it.
pub(crate) fn standard_normal<R: Rng>(bits: u32, rng: &mut R) -> f32 {
    from_tables(&TABLES, bits, rng)
}

/// [`standard_normal`] with the tables at hand (the spectra's hot loop keeps them).
#[inline]
fn from_tables<R: Rng>(t: &Tables, bits: u32, rng: &mut R) -> f32 {
    let layer = (bits & 0x7F) as usize;
    let position = bits >> 8;
    if position < t.inside[layer] {
        let x = position as f32 * t.scale[layer];
        return if bits & 0x80 != 0 { -x } else { x };
    }
    slow(t, bits, rng)
}

#[cold]
fn slow<R: Rng>(t: &Tables, mut bits: u32, rng: &mut R) -> f32 {
    loop {
        let layer = (bits & 0x7F) as usize;
        let position = bits >> 8;
        let negative = bits & 0x80 != 0;
        let x = if position < t.inside[layer] {
            position as f32 * t.scale[layer]
        } else if layer == 0 {
            tail(rng)
        } else {
            // In the wedge between x_{i+1} and x_i: accept under the curve.
            let x = position as f32 * t.scale[layer];
            let y = t.height[layer] + uniform(rng) * (t.height[layer + 1] - t.height[layer]);
            if y >= libm::expf(-0.5 * x * x) {
                bits = rng.next_u32();
                continue;
            }
            x
        };
        return if negative { -x } else { x };
    }
}

/// Marsaglia's tail beyond `TAIL_START`.
fn tail<R: Rng>(rng: &mut R) -> f32 {
    let r = TAIL_START as f32;
    loop {
        let a = -libm::logf(open_uniform(rng)) / r;
        let b = -libm::logf(open_uniform(rng));
        if b + b >= a * a {
            return r + a;
        }
    }
}

/// Uniform in [0, 1) with 24 bits.
fn uniform<R: Rng>(rng: &mut R) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / POSITION_ONE as f32)
}

/// Uniform in (0, 1] with 24 bits.
fn open_uniform<R: Rng>(rng: &mut R) -> f32 {
    ((rng.next_u32() >> 8) + 1) as f32 * (1.0 / POSITION_ONE as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_are_standard_normal() {
        let mut normals = NormalPairs::new(3);
        let n = 400_000;
        let (mut sum, mut sq, mut cross, mut fourth) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for _ in 0..n {
            let c = normals.next_pair();
            let (x, y) = (f64::from(c.re), f64::from(c.im));
            sum += x + y;
            sq += x * x + y * y;
            cross += x * y;
            fourth += x.powi(4) + y.powi(4);
        }
        let n = n as f64;
        assert!((sum / (2.0 * n)).abs() < 0.01);
        assert!((sq / (2.0 * n) - 1.0).abs() < 0.01);
        assert!((cross / n).abs() < 0.01);
        assert!(
            (fourth / (2.0 * n) - 3.0).abs() < 0.05,
            "kurtosis {}",
            fourth / (2.0 * n)
        );
    }

    /// The table is a ziggurat: the top edge reaches 0 with equal areas (so the recurrence
    /// closed), and the distribution matches Φ in the body, the wedges and the tail.
    #[test]
    fn table_closes_and_the_histogram_is_gaussian() {
        let t = &*TABLES;
        // The last recurrence step lands near 0: x_127 · (1 − f(x_127)) is one layer's area.
        let x127 = f64::from(t.scale[LAYERS - 1]) * POSITION_ONE;
        let top = x127 * (1.0 - libm::exp(-0.5 * x127 * x127));
        assert!(
            (top / LAYER_AREA - 1.0).abs() < 1e-3,
            "top layer area {top}"
        );

        let mut normals = NormalPairs::new(11);
        let n = 2_000_000usize;
        // P(|X| > t) for t = 0.5, 1, 2, 3, 3.4426 (tail start), 4.
        let edges = [0.5f32, 1.0, 2.0, 3.0, TAIL_START as f32, 4.0];
        let expected = [
            0.617_075, 0.317_311, 0.045_500, 0.002_700, 0.000_576, 0.000_063,
        ];
        let mut beyond = [0usize; 6];
        for _ in 0..n / 2 {
            let c = normals.next_pair();
            for v in [c.re, c.im] {
                assert!(v.is_finite());
                for (k, &edge) in edges.iter().enumerate() {
                    beyond[k] += usize::from(v.abs() > edge);
                }
            }
        }
        for k in 0..edges.len() {
            let p = beyond[k] as f64 / n as f64;
            let sigma = (expected[k] * (1.0 - expected[k]) / n as f64).sqrt();
            assert!(
                (p - expected[k]).abs() < 5.0 * sigma,
                "P(|X| > {}) = {p}, expected {}",
                edges[k],
                expected[k]
            );
        }
    }
}
