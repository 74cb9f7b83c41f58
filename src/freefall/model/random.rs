//! A small portable random stream per falling object.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg32;

/// PCG32 with uniform and normal draws made from integer bits and `libm`, so a seed gives the
/// same numbers on every platform.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FallRng(Pcg32);

impl FallRng {
    /// A stream from a seed.
    pub fn new(seed: u64) -> Self {
        Self(Pcg32::seed_from_u64(seed))
    }

    /// Uniform in [0, 1) with 24 bits.
    pub fn uniform(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Standard normal, by the crate's one sampler: the spectra's portable ziggurat
    /// (Marsaglia & Tsang 2000; the paper names Box–Muller, whose distribution it draws).
    pub fn normal(&mut self) -> f32 {
        let bits = self.0.next_u32();
        crate::spectrum::standard_normal(bits, &mut self.0)
    }

    /// 64 uniform bits (a seed for a new stream).
    pub fn bits(&mut self) -> u64 {
        u64::from(self.0.next_u32()) << 32 | u64::from(self.0.next_u32())
    }

    /// True with probability one half.
    pub fn coin(&mut self) -> bool {
        self.0.next_u32() & 1 == 1
    }
}
