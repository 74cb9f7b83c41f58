//! One number, or several in SIMD lanes: the [`Lane`] trait the step arithmetic is written
//! against once, implemented for `f32` (one lane), `wide::f32x4` (four) and, on x86-64 with
//! AVX2, [`F8`](super::avx::F8) (eight). Every operation is a
//! plain IEEE-754 one, the same in every lane and on every machine (no fused multiply-add, no
//! approximate reciprocal, selects instead of branches), so a value computed in a lane has the
//! bits the scalar code gives it.

use std::ops::{Add, Div, Mul, Neg, Sub};

use wide::{f32x4, i32x4, u32x4};

/// The most lanes any [`Lane`] has: the size of arrays that hold one thing a lane.
pub(crate) const MAX_WIDTH: usize = 8;

/// `f` of each of a lane array's entries, in a plain loop: inlined with the caller in any build
/// (an array's `map` can stay a call where the crate is split into codegen units, and the
/// eight lanes' pass must inline whole into its AVX2 function).
#[inline(always)]
pub(crate) fn each<T: Copy, U: Copy + Default>(
    a: [T; MAX_WIDTH],
    mut f: impl FnMut(T) -> U,
) -> [U; MAX_WIDTH] {
    let mut out = [U::default(); MAX_WIDTH];
    for (o, &v) in out.iter_mut().zip(&a) {
        *o = f(v);
    }
    out
}

/// One entry a lane from `f(k)`, in a plain loop (as [`each`]: `std::array::from_fn` can stay a
/// call in a build split into codegen units).
#[inline(always)]
pub(crate) fn per_lane<T: Copy + Default>(mut f: impl FnMut(usize) -> T) -> [T; MAX_WIDTH] {
    let mut out = [T::default(); MAX_WIDTH];
    for (k, o) in out.iter_mut().enumerate() {
        *o = f(k);
    }
    out
}

/// A number or a few in lanes, with the operations the step needs.
pub(crate) trait Lane:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A comparison's answer per lane.
    type Mask: Copy;
    /// Numbers side by side.
    const WIDTH: usize;

    /// `v` in every lane.
    fn splat(v: f32) -> Self;
    /// `a` where `mask`, else `b`.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    /// `self < other` (false for NaN).
    fn lt(self, other: Self) -> Self::Mask;
    /// `self <= other` (false for NaN).
    fn le(self, other: Self) -> Self::Mask;
    /// `self == other` (false for NaN).
    fn eq(self, other: Self) -> Self::Mask;
    /// Both.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Either.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Whether any lane is set.
    fn any(mask: Self::Mask) -> bool;
    /// Whether every lane is set.
    fn all(mask: Self::Mask) -> bool;
    /// |self|.
    fn abs(self) -> Self;
    /// √self, correctly rounded (IEEE).
    fn sqrt(self) -> Self;
    /// The mantissa in [0.5, 1) and the exponent (as a number) of a positive finite `self`:
    /// `self = m · 2^e`; subnormals included.
    fn frexp(self) -> (Self, Self);
    /// Lane `k`.
    fn get(self, k: usize) -> f32;
    /// Lane by lane from `f(k)`.
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self;
    /// Whether lane `k` of `mask` is set.
    fn mask_get(mask: Self::Mask, k: usize) -> bool;
    /// The [`Lane::WIDTH`] numbers of `column` from `k` on.
    fn load(column: &[f32], k: usize) -> Self;
    /// Writes the lanes where `mask` is set into `column` from `k` on, keeping the others.
    fn store_where(self, mask: Self::Mask, column: &mut [f32], k: usize);
    /// Writes every lane into `column` from `k` on.
    fn store(self, column: &mut [f32], k: usize);
    /// Not `mask`.
    fn not(mask: Self::Mask) -> Self::Mask;
    /// A mask with lane `k` set where `f(k)`.
    fn mask_from_fn(f: impl FnMut(usize) -> bool) -> Self::Mask;
    /// The lanes truncated toward zero to integers (the first [`Lane::WIDTH`] of
    /// [`MAX_WIDTH`]), for indices: NaN gives 0, out of range the nearest end.
    fn to_i32s(self) -> [i32; MAX_WIDTH];
    /// Four columns from one row of four numbers a lane (`row(k)` for lane `k`): a transpose.
    fn columns(row: impl FnMut(usize) -> [f32; 4]) -> [Self; 4];

    /// `self > other`.
    fn gt(self, other: Self) -> Self::Mask {
        other.lt(self)
    }

    /// `self >= other`.
    fn ge(self, other: Self) -> Self::Mask {
        other.le(self)
    }
}

impl Lane for f32 {
    type Mask = bool;
    const WIDTH: usize = 1;

    #[inline]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline]
    fn select(mask: bool, a: Self, b: Self) -> Self {
        if mask { a } else { b }
    }
    #[inline]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline]
    fn eq(self, other: Self) -> bool {
        self == other
    }
    #[inline]
    fn and(a: bool, b: bool) -> bool {
        a & b
    }
    #[inline]
    fn or(a: bool, b: bool) -> bool {
        a | b
    }
    #[inline]
    fn any(mask: bool) -> bool {
        mask
    }
    #[inline]
    fn all(mask: bool) -> bool {
        mask
    }
    #[inline]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline]
    fn frexp(self) -> (Self, Self) {
        // Subnormals are first scaled into the normal range (exactly, by 2^25).
        let sub = self < f32::MIN_POSITIVE;
        let x = if sub { self * 33_554_432.0 } else { self };
        let bits = x.to_bits();
        let e = ((bits >> 23) & 0xff) as i32 - 126 - if sub { 25 } else { 0 };
        (f32::from_bits((bits & 0x007f_ffff) | 0x3f00_0000), e as f32)
    }
    #[inline]
    fn get(self, _: usize) -> f32 {
        self
    }
    #[inline]
    fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        f(0)
    }
    #[inline]
    fn mask_get(mask: bool, _: usize) -> bool {
        mask
    }
    #[inline]
    fn load(column: &[f32], k: usize) -> Self {
        column[k]
    }
    #[inline]
    fn store_where(self, mask: bool, column: &mut [f32], k: usize) {
        if mask {
            column[k] = self;
        }
    }
    #[inline]
    fn store(self, column: &mut [f32], k: usize) {
        column[k] = self;
    }
    #[inline]
    fn not(mask: bool) -> bool {
        !mask
    }
    #[inline]
    fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> bool {
        f(0)
    }
    #[inline]
    fn columns(mut row: impl FnMut(usize) -> [f32; 4]) -> [Self; 4] {
        row(0)
    }
    #[inline]
    fn to_i32s(self) -> [i32; MAX_WIDTH] {
        [self as i32; MAX_WIDTH]
    }
}

impl Lane for f32x4 {
    type Mask = f32x4;
    const WIDTH: usize = 4;

    #[inline]
    fn splat(v: f32) -> Self {
        f32x4::splat(v)
    }
    #[inline]
    fn select(mask: f32x4, a: Self, b: Self) -> Self {
        mask.select(a, b)
    }
    #[inline]
    fn lt(self, other: Self) -> f32x4 {
        self.simd_lt(other)
    }
    #[inline]
    fn le(self, other: Self) -> f32x4 {
        self.simd_le(other)
    }
    #[inline]
    fn eq(self, other: Self) -> f32x4 {
        self.simd_eq(other)
    }
    #[inline]
    fn and(a: f32x4, b: f32x4) -> f32x4 {
        a & b
    }
    #[inline]
    fn or(a: f32x4, b: f32x4) -> f32x4 {
        a | b
    }
    #[inline]
    fn any(mask: f32x4) -> bool {
        mask.any()
    }
    #[inline]
    fn all(mask: f32x4) -> bool {
        mask.all()
    }
    #[inline]
    fn abs(self) -> Self {
        f32x4::abs(self)
    }
    #[inline]
    fn sqrt(self) -> Self {
        f32x4::sqrt(self)
    }
    #[inline]
    fn frexp(self) -> (Self, Self) {
        let sub = self.simd_lt(f32x4::splat(f32::MIN_POSITIVE));
        let x = sub.select(self * f32x4::splat(33_554_432.0), self);
        let bits: u32x4 = bytemuck::cast(x);
        let exponent: i32x4 = bytemuck::cast((bits >> 23u32) & u32x4::splat(0xff));
        let e = exponent.round_float() - f32x4::splat(126.0);
        let e = e - sub.select(f32x4::splat(25.0), f32x4::splat(0.0));
        let m = (bits & u32x4::splat(0x007f_ffff)) | u32x4::splat(0x3f00_0000);
        (bytemuck::cast(m), e)
    }
    #[inline]
    fn get(self, k: usize) -> f32 {
        self.to_array()[k]
    }
    #[inline]
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        f32x4::from(std::array::from_fn::<f32, 4, _>(f))
    }
    #[inline]
    fn mask_get(mask: f32x4, k: usize) -> bool {
        mask.to_bitmask() & (1 << k) != 0
    }
    #[inline]
    fn load(column: &[f32], k: usize) -> Self {
        let four: [f32; 4] = column[k..k + 4].try_into().expect("four lanes");
        f32x4::from(four)
    }
    #[inline]
    fn store_where(self, mask: f32x4, column: &mut [f32], k: usize) {
        let old = Self::load(column, k);
        column[k..k + 4].copy_from_slice(&mask.select(self, old).to_array());
    }
    #[inline]
    fn store(self, column: &mut [f32], k: usize) {
        column[k..k + 4].copy_from_slice(&self.to_array());
    }
    #[inline]
    fn not(mask: f32x4) -> f32x4 {
        mask ^ bytemuck::cast::<[u32; 4], f32x4>([u32::MAX; 4])
    }
    #[inline]
    fn mask_from_fn(mut f: impl FnMut(usize) -> bool) -> f32x4 {
        let bits: [u32; 4] = std::array::from_fn(|k| if f(k) { u32::MAX } else { 0 });
        bytemuck::cast(bits)
    }
    #[inline]
    fn columns(mut row: impl FnMut(usize) -> [f32; 4]) -> [Self; 4] {
        f32x4::transpose([row(0), row(1), row(2), row(3)].map(f32x4::from))
    }
    #[inline]
    fn to_i32s(self) -> [i32; MAX_WIDTH] {
        let four = self.trunc_int().to_array();
        std::array::from_fn(|k| if k < 4 { four[k] } else { 0 })
    }
}
