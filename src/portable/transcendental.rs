//! The transcendental functions of the fall's step and of the wind's read, once, for one number
//! or for lanes ([`Lane`]): `sin_cos`, `ln`, `atan2` and `acos` in plain f32 arithmetic in a fixed
//! order (Cody–Waite range reduction and the Cephes library's minimax polynomials, S. L. Moshier,
//! *Methods and Programs for Mathematical Functions*, 1989), never fused into multiply-adds. The
//! same input gives the same bits on every machine, in every lane and in the browser, where the
//! platform's `sinf` or `logf` may differ in the last bit (glibc's use FMA). Their errors against
//! a correctly rounded result and against the platform's are measured in `tests/it/portable_math.rs`.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use super::lane::Lane;

/// The nearest integer to `x` (ties to even, the same in every lane and on every machine),
/// for |x| < 2²³; larger or non-finite values are returned as they are.
#[inline(always)]
pub(crate) fn round<L: Lane>(x: L) -> L {
    let big = L::splat(8_388_608.0);
    let c = L::select(x.lt(L::splat(0.0)), -big, big);
    let r = (x + c) - c;
    L::select(x.abs().lt(big), r, x)
}

/// `value` held to [low, high] (a NaN stays NaN), the same in every lane.
#[inline(always)]
pub(crate) fn clamp<L: Lane>(value: L, low: L, high: L) -> L {
    let v = L::select(value.lt(low), low, value);
    L::select(v.gt(high), high, v)
}

/// The largest integer not above `x` (non-finite values as they are).
#[inline(always)]
pub(crate) fn floor<L: Lane>(x: L) -> L {
    let r = round(x);
    r - L::select(r.gt(x), L::splat(1.0), L::splat(0.0))
}

/// π/2 in four parts, the first three of 8 and 11 significant bits, so that their products
/// with a quadrant count below 2¹³ are exact and the reduction loses nothing where it cancels.
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = 4.837_513e-4;
const PIO2_3: f32 = 7.549_533_6e-8;
const PIO2_4: f32 = 2.563_283e-12;

/// Beyond this |x| the four-part reduction would lose its exactness (2¹³ quadrants).
const REDUCED: f32 = 1.0e4;

/// sin x and cos x: within 2 ulp of the correctly rounded value for |x| ≤ 10⁴ (a curve's phase
/// in any fall of a few minutes); beyond, lane by lane, the pure-Rust `libm::sincosf` (Payne
/// and Hanek's exact reduction), just as portable. NaN and infinities give NaN.
#[inline(always)]
pub(crate) fn sin_cos<L: Lane>(x: L) -> (L, L) {
    let (s, c) = sin_cos_near(x);
    let far = x.abs().gt(L::splat(REDUCED));
    if !L::any(L::and(far, x.abs().lt(L::splat(f32::INFINITY)))) {
        return (s, c);
    }
    let sin = L::from_fn(|k| libm::sincosf(x.get(k)).0);
    let cos = L::from_fn(|k| libm::sincosf(x.get(k)).1);
    let near = L::or(
        x.abs().le(L::splat(REDUCED)),
        x.abs().eq(L::splat(f32::INFINITY)),
    );
    (L::select(near, s, sin), L::select(near, c, cos))
}

/// [`sin_cos`] for |x| ≤ 10⁴ (NaN and infinities give NaN).
#[inline(always)]
fn sin_cos_near<L: Lane>(x: L) -> (L, L) {
    // Within ±0.75 (most calls: half angles of tilts and turns) the reduction below leaves x
    // as it is (k = 0, r = x exactly, no turn or sign): the polynomials alone, the same bits.
    // (Not up to π/4 itself: there x · 2/π may round to ½ and beyond.) NaN goes either way.
    if !L::any(x.abs().gt(L::splat(0.75))) {
        return sin_cos_poly(x);
    }
    sin_cos_bounded(x)
}

/// sin x and cos x for |x| ≤ 10⁴ without a branch (the bits of [`sin_cos`]): what the lanes
/// call where the argument is bounded by construction (half angles, a curve's phase reduced
/// to one turn). Beyond 10⁴ it is not accurate: callers bound their arguments. NaN and
/// infinities give NaN.
#[inline(always)]
pub(crate) fn sin_cos_bounded<L: Lane>(x: L) -> (L, L) {
    let k = round(x * L::splat(2.0 / PI));
    let r = (((x - k * L::splat(PIO2_1)) - k * L::splat(PIO2_2)) - k * L::splat(PIO2_3))
        - k * L::splat(PIO2_4);
    let (s, c) = sin_cos_poly(r);
    // The quadrant k mod 4 turns and signs them.
    let q = k - L::splat(4.0) * floor(k * L::splat(0.25));
    let odd = (q - L::splat(2.0) * floor(q * L::splat(0.5))).eq(L::splat(1.0));
    let (sin, cos) = (L::select(odd, c, s), L::select(odd, s, c));
    let sin = L::select(q.ge(L::splat(2.0)), -sin, sin);
    let flip_cos = L::or(q.eq(L::splat(1.0)), q.eq(L::splat(2.0)));
    (sin, L::select(flip_cos, -cos, cos))
}

/// Cephes sinf and cosf on [−π/4, π/4].
#[inline(always)]
fn sin_cos_poly<L: Lane>(r: L) -> (L, L) {
    let z = r * r;
    let s = ((L::splat(-1.951_529_6e-4) * z + L::splat(8.332_161e-3)) * z
        + L::splat(-1.666_665_5e-1))
        * z
        * r
        + r;
    let c = ((L::splat(2.443_315_7e-5) * z + L::splat(-1.388_731_6e-3)) * z
        + L::splat(4.166_664_6e-2))
        * z
        * z
        - L::splat(0.5) * z
        + L::splat(1.0);
    (s, c)
}

/// ln x: within 1 ulp for every positive finite x (subnormals included); 0 gives −∞, +∞
/// gives +∞, a negative number or NaN gives NaN.
#[inline(always)]
pub(crate) fn ln<L: Lane>(x: L) -> L {
    let positive = L::and(x.gt(L::splat(0.0)), x.lt(L::splat(f32::INFINITY)));
    let (m, e) = L::select(positive, x, L::splat(1.0)).frexp();
    // Cephes logf: m in [√½, √2) around 1.
    let low = m.lt(L::splat(std::f32::consts::FRAC_1_SQRT_2));
    let e = L::select(low, e - L::splat(1.0), e);
    let f = L::select(low, m + m - L::splat(1.0), m - L::splat(1.0));
    let z = f * f;
    let mut p = L::splat(7.037_683_6e-2);
    for c in [
        -1.151_461e-1,
        1.167_699_9e-1,
        -1.242_014_1e-1,
        1.424_932_3e-1,
        -1.666_805_8e-1,
        2.000_071_5e-1,
        -2.499_999_4e-1,
        3.333_333e-1,
    ] {
        p = p * f + L::splat(c);
    }
    let mut y = p * f * z;
    y = y + e * L::splat(-2.121_944_4e-4);
    y = y - L::splat(0.5) * z;
    let result = (f + y) + e * L::splat(0.693_359_4);
    // The edges, as the platform's `ln` gives them.
    let zero = x.eq(L::splat(0.0));
    let result = L::select(zero, L::splat(f32::NEG_INFINITY), result);
    let infinite = x.eq(L::splat(f32::INFINITY));
    let result = L::select(infinite, x, result);
    let finite_or_zero = L::or(positive, L::or(zero, infinite));
    L::select(finite_or_zero, result, L::splat(f32::NAN))
}

/// atan t for t ≥ 0 (Cephes atanf: reduced to |t| ≤ tan π/8 by the identities of π/4 and π/2).
#[inline(always)]
fn atan_positive<L: Lane>(t: L) -> L {
    let big = t.gt(L::splat(2.414_213_5));
    let middle = L::and(t.gt(L::splat(0.414_213_57)), t.le(L::splat(2.414_213_5)));
    let base = L::select(
        big,
        L::splat(FRAC_PI_2),
        L::select(middle, L::splat(FRAC_PI_4), L::splat(0.0)),
    );
    let reduced = L::select(
        big,
        -(L::splat(1.0) / t),
        L::select(middle, (t - L::splat(1.0)) / (t + L::splat(1.0)), t),
    );
    let z = reduced * reduced;
    let p = ((L::splat(8.053_744_5e-2) * z + L::splat(-1.387_768_5e-1)) * z
        + L::splat(1.997_771_1e-1))
        * z
        + L::splat(-3.333_295e-1);
    base + (p * z * reduced + reduced)
}

/// Whether `v` has its sign bit set (−0 included; not NaN).
#[inline(always)]
fn negative<L: Lane>(v: L) -> L::Mask {
    let zero = L::splat(0.0);
    L::or(v.lt(zero), L::and(v.eq(zero), (L::splat(1.0) / v).lt(zero)))
}

/// atan2(y, x), the angle of (x, y) in [−π, π]: within 3 ulp; zeros and infinities as the
/// platform's (IEEE-754's atan2), a NaN gives NaN.
#[inline(always)]
pub(crate) fn atan2<L: Lane>(y: L, x: L) -> L {
    let (ay, ax) = (y.abs(), x.abs());
    let infinite = L::and(
        ay.eq(L::splat(f32::INFINITY)),
        ax.eq(L::splat(f32::INFINITY)),
    );
    let both_zero = L::and(ay.eq(L::splat(0.0)), ax.eq(L::splat(0.0)));
    let fixed = L::select(infinite, L::splat(1.0), L::splat(0.0));
    let t = L::select(L::or(infinite, both_zero), fixed, ay / ax);
    let a = atan_positive(t);
    let a = L::select(negative(x), L::splat(PI) - a, a);
    L::select(negative(y), -a, a)
}

/// asin of 0 ≤ a ≤ 0.5 (Cephes asinf's polynomial).
#[inline(always)]
fn asin_small<L: Lane>(a: L) -> L {
    let z = a * a;
    let p = (((L::splat(4.216_32e-2) * z + L::splat(2.418_131e-2)) * z + L::splat(4.547_002_6e-2))
        * z
        + L::splat(7.495_300_3e-2))
        * z
        + L::splat(1.666_675_2e-1);
    p * z * a + a
}

/// acos x for x in [−1, 1], within 2 ulp (Cephes acosf); outside or NaN, NaN.
#[inline(always)]
pub(crate) fn acos<L: Lane>(x: L) -> L {
    let half = L::splat(0.5);
    let outside = L::or(x.gt(L::splat(1.0)), x.lt(L::splat(-1.0)));
    let a = x.abs();
    // Near ±1: acos x = 2 asin √((1 − |x|)/2), and π minus that below −½.
    let s = (half * (L::splat(1.0) - a)).sqrt();
    let far = L::splat(2.0) * asin_small(L::select(a.gt(half), s, L::splat(0.0)));
    let near = L::splat(FRAC_PI_2) - asin_small(L::select(a.gt(half), L::splat(0.0), x));
    let result = L::select(
        a.gt(half),
        L::select(x.lt(L::splat(0.0)), L::splat(PI) - far, far),
        near,
    );
    L::select(outside, L::splat(f32::NAN), result)
}
