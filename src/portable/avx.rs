//! Eight lanes where an x86-64 CPU has AVX2: [`F8`], a [`Lane`] over `std::arch`'s 256-bit
//! vectors, and [`has_avx2`], the run-time check that lets code use it.
//!
//! Hand-written over `std::arch` rather than taken from a crate: `wide`'s `f32x8` picks its
//! instructions when the crate is compiled (two SSE halves unless the whole build targets AVX),
//! and `fearless_simd`'s vectors carry a capability token that [`Lane::splat`] and the other
//! token-free constructors the step is written against cannot supply. Each operation here is
//! the one `wide::f32x4` uses on SSE, twice as wide (IEEE add, subtract, multiply, divide and
//! square root; comparisons false on NaN; the same truncation rule), so eight lanes give each
//! fall the bits four lanes and one give it. One difference in kind: a select here blends by
//! each mask lane's sign bit (`vblendvps`) where `wide` on SSE2 blends bit by bit; the two agree
//! because every mask the step makes (comparisons, `and`, `or`, `not`, `mask_from_fn`) is all
//! ones or all zeros in each lane.
//!
//! **Where it may run.** The methods are `#[inline(always)]`, most over an AVX or AVX2
//! intrinsic (the array conversions are plain bit copies). An [`F8`] may only be made in code
//! entered after [`has_avx2`] said yes: the store's driver does so in one
//! `#[target_feature(enable = "avx2")]` function, the only place in the crate that names
//! `F8` outside this file and its tests. That is a rule of this crate's code, not one the
//! type enforces (`Lane::splat` and the other constructors are safe functions); the `unsafe`
//! blocks that run an intrinsic rely on it. The step's lane kernels are `#[inline(always)]` so
//! that they inline into that function and take its instructions; one left out of line would
//! still be correct, only slower.

#![allow(unsafe_code)]

use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::lane::{Lane, MAX_WIDTH};

/// Whether this CPU has AVX2 (the check is cached by the standard library).
pub(crate) fn has_avx2() -> bool {
    is_x86_feature_detected!("avx2")
}

/// Eight `f32` lanes in one AVX register. Only made where [`has_avx2`] holds.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct F8(__m256);

/// Runs `f` on the intrinsics: sound because an [`F8`] only exists where AVX2 does (module doc).
macro_rules! avx {
    ($e:expr) => {
        // SAFETY: F8 is only made after `has_avx2()` (see the module doc).
        unsafe { $e }
    };
}

/// Asks the CPU to bring the cache lines of `value` in ahead of use (a hint: no effect on
/// what any code computes).
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    let start = (value as *const T).cast::<i8>();
    for line in (0..std::mem::size_of::<T>()).step_by(64) {
        // SAFETY: a prefetch is a hint that never faults (SSE, on every x86-64), and the
        // address lies within `value`.
        avx!(_mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(line)));
    }
}

impl F8 {
    #[inline(always)]
    fn bits(self) -> __m256i {
        avx!(_mm256_castps_si256(self.0))
    }

    #[inline(always)]
    fn of_bits(bits: __m256i) -> Self {
        F8(avx!(_mm256_castsi256_ps(bits)))
    }

    /// The lanes as an array: a plain copy of the bits (no instruction that needs AVX, so it
    /// inlines anywhere, closures included).
    #[inline(always)]
    fn array(self) -> [f32; 8] {
        // SAFETY: __m256 and [f32; 8] are 32 plain bytes with every bit pattern valid.
        avx!(std::mem::transmute::<__m256, [f32; 8]>(self.0))
    }

    #[inline(always)]
    fn of_array(a: [f32; 8]) -> Self {
        // SAFETY: as in `array`.
        F8(avx!(std::mem::transmute::<[f32; 8], __m256>(a)))
    }

    /// Lane by lane from `f(k)`, in a loop that inlines where the caller is.
    #[inline(always)]
    fn build<T: Copy>(zero: T, mut f: impl FnMut(usize) -> T) -> [T; 8] {
        let mut out = [zero; 8];
        for (k, o) in out.iter_mut().enumerate() {
            *o = f(k);
        }
        out
    }
}

impl Add for F8 {
    type Output = F8;
    #[inline(always)]
    fn add(self, o: F8) -> F8 {
        F8(avx!(_mm256_add_ps(self.0, o.0)))
    }
}

impl Sub for F8 {
    type Output = F8;
    #[inline(always)]
    fn sub(self, o: F8) -> F8 {
        F8(avx!(_mm256_sub_ps(self.0, o.0)))
    }
}

impl Mul for F8 {
    type Output = F8;
    #[inline(always)]
    fn mul(self, o: F8) -> F8 {
        F8(avx!(_mm256_mul_ps(self.0, o.0)))
    }
}

impl Div for F8 {
    type Output = F8;
    #[inline(always)]
    fn div(self, o: F8) -> F8 {
        F8(avx!(_mm256_div_ps(self.0, o.0)))
    }
}

impl Neg for F8 {
    type Output = F8;
    /// The sign bit flipped (as `wide` and scalar `-x` do: −0 from 0).
    #[inline(always)]
    fn neg(self) -> F8 {
        F8(avx!(_mm256_xor_ps(self.0, _mm256_set1_ps(-0.0))))
    }
}

impl Lane for F8 {
    type Mask = F8;
    const WIDTH: usize = 8;

    #[inline(always)]
    fn splat(v: f32) -> Self {
        F8(avx!(_mm256_set1_ps(v)))
    }
    #[inline(always)]
    fn select(mask: F8, a: Self, b: Self) -> Self {
        F8(avx!(_mm256_blendv_ps(b.0, a.0, mask.0)))
    }
    #[inline(always)]
    fn lt(self, other: Self) -> F8 {
        F8(avx!(_mm256_cmp_ps::<_CMP_LT_OQ>(self.0, other.0)))
    }
    #[inline(always)]
    fn le(self, other: Self) -> F8 {
        F8(avx!(_mm256_cmp_ps::<_CMP_LE_OQ>(self.0, other.0)))
    }
    #[inline(always)]
    fn eq(self, other: Self) -> F8 {
        F8(avx!(_mm256_cmp_ps::<_CMP_EQ_OQ>(self.0, other.0)))
    }
    #[inline(always)]
    fn and(a: F8, b: F8) -> F8 {
        F8(avx!(_mm256_and_ps(a.0, b.0)))
    }
    #[inline(always)]
    fn or(a: F8, b: F8) -> F8 {
        F8(avx!(_mm256_or_ps(a.0, b.0)))
    }
    #[inline(always)]
    fn any(mask: F8) -> bool {
        avx!(_mm256_movemask_ps(mask.0)) != 0
    }
    #[inline(always)]
    fn all(mask: F8) -> bool {
        avx!(_mm256_movemask_ps(mask.0)) == 0xff
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F8(avx!(_mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0)))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F8(avx!(_mm256_sqrt_ps(self.0)))
    }
    #[inline(always)]
    fn frexp(self) -> (Self, Self) {
        // As the four-lane version: subnormals scaled by 2^25 first, exactly.
        let sub = self.lt(F8::splat(f32::MIN_POSITIVE));
        let x = F8::select(sub, self * F8::splat(33_554_432.0), self);
        let bits = x.bits();
        avx!({
            let exponent = _mm256_and_si256(_mm256_srli_epi32::<23>(bits), _mm256_set1_epi32(0xff));
            let e = F8(_mm256_cvtepi32_ps(exponent)) - F8::splat(126.0);
            let e = e - F8::select(sub, F8::splat(25.0), F8::splat(0.0));
            let m = _mm256_or_si256(
                _mm256_and_si256(bits, _mm256_set1_epi32(0x007f_ffff)),
                _mm256_set1_epi32(0x3f00_0000),
            );
            (F8::of_bits(m), e)
        })
    }
    #[inline(always)]
    fn get(self, k: usize) -> f32 {
        self.array()[k]
    }
    #[inline(always)]
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        F8::of_array(F8::build(0.0, f))
    }
    #[inline(always)]
    fn mask_get(mask: F8, k: usize) -> bool {
        avx!(_mm256_movemask_ps(mask.0)) & (1 << k) != 0
    }
    #[inline(always)]
    fn load(column: &[f32], k: usize) -> Self {
        let eight: &[f32; 8] = column[k..k + 8].try_into().expect("eight lanes");
        F8(avx!(_mm256_loadu_ps(eight.as_ptr())))
    }
    #[inline(always)]
    fn store_where(self, mask: F8, column: &mut [f32], k: usize) {
        let old = Self::load(column, k);
        F8::select(mask, self, old).store(column, k);
    }
    #[inline(always)]
    fn store(self, column: &mut [f32], k: usize) {
        let eight: &mut [f32; 8] = (&mut column[k..k + 8]).try_into().expect("eight lanes");
        avx!(_mm256_storeu_ps(eight.as_mut_ptr(), self.0));
    }
    #[inline(always)]
    fn not(mask: F8) -> F8 {
        F8::of_bits(avx!(_mm256_xor_si256(mask.bits(), _mm256_set1_epi32(-1))))
    }
    #[inline(always)]
    fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> F8 {
        let bits = F8::build(0u32, |k| if f(k) { u32::MAX } else { 0 });
        F8::of_array(F8::build(0.0, |k| f32::from_bits(bits[k])))
    }
    #[inline(always)]
    fn to_i32s(self) -> [i32; MAX_WIDTH] {
        // `wide`'s rule: NaN → 0, ≥ 2^31 → i32::MAX, the rest truncated (below −2^31: i32::MIN).
        avx!({
            let non_nan = _mm256_and_ps(self.0, _mm256_cmp_ps::<_CMP_EQ_OQ>(self.0, self.0));
            let over = _mm256_castps_si256(_mm256_cmp_ps::<_CMP_GE_OQ>(
                self.0,
                _mm256_set1_ps(2_147_483_648.0),
            ));
            let int = _mm256_xor_si256(over, _mm256_cvttps_epi32(non_nan));
            std::mem::transmute::<__m256i, [i32; 8]>(int)
        })
    }
    #[inline(always)]
    fn columns(mut row: impl FnMut(usize) -> [f32; 4]) -> [Self; 4] {
        let rows = F8::build([0.0; 4], &mut row);
        let column = |c: usize| F8::of_array(F8::build(0.0, |k| rows[k][c]));
        [column(0), column(1), column(2), column(3)]
    }
}
