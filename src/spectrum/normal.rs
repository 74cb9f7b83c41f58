//! Portable standard normal numbers.

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;
use rustfft::num_complex::Complex;

/// Standard complex normals `X + iY` (X, Y independent standard normal) from a PCG stream by
/// Marsaglia's polar method in f32, with the `libm` crate's pure-Rust `logf` and `sqrtf`, so the numbers
/// are the same on every platform (std's `ln` calls the platform's C library).
pub(crate) struct NormalPairs(Pcg64);

impl NormalPairs {
    pub(crate) fn new(seed: u64) -> Self {
        Self(Pcg64::seed_from_u64(seed))
    }

    pub(crate) fn next_pair(&mut self) -> Complex<f32> {
        const SCALE: f32 = 1.0 / (1u32 << 23) as f32;
        loop {
            // Two uniforms in [−1, 1) with 24 bits each, from one 64-bit draw.
            let bits = self.0.random::<u64>();
            let x = ((bits >> 40) as u32 as f32) * SCALE - 1.0;
            let y = (((bits >> 8) & 0xFF_FFFF) as u32 as f32) * SCALE - 1.0;
            let s = x * x + y * y;
            if s > 0.0 && s < 1.0 {
                let scale = libm::sqrtf(-2.0 * libm::logf(s) / s);
                return Complex::new(x * scale, y * scale);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_are_standard_normal() {
        let mut normals = NormalPairs::new(3);
        let n = 200_000;
        let (mut sum, mut sq, mut cross, mut fourth) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for _ in 0..n {
            let c = normals.next_pair();
            let (x, y) = (f64::from(c.re), f64::from(c.im));
            sum += x + y;
            sq += x * x + y * y;
            cross += x * y;
            fourth += x.powi(4);
        }
        let n = n as f64;
        assert!((sum / (2.0 * n)).abs() < 0.01);
        assert!((sq / (2.0 * n) - 1.0).abs() < 0.01);
        assert!((cross / n).abs() < 0.01);
        assert!((fourth / n - 3.0).abs() < 0.05, "kurtosis {}", fourth / n);
    }
}
