//! The portable kernels against a correctly rounded result (the f64 function rounded to f32)
//! and against the platform's f32 function, in ulps, over their whole input range sampled at a
//! stride of bit patterns; and four lanes against one, bit for bit.

use wide::f32x4;

use super::transcendental::{acos, atan2, floor, ln, round, sin_cos};

/// Distance in ulps between two f32 of the same sign class (0 for equal bits or two NaNs).
fn ulps(a: f32, b: f32) -> u64 {
    if a.is_nan() && b.is_nan() {
        return 0;
    }
    let key = |v: f32| {
        let i = v.to_bits() as i32;
        if i < 0 {
            i64::from(i32::MIN) - i64::from(i)
        } else {
            i64::from(i)
        }
    };
    (key(a) - key(b)).unsigned_abs()
}

/// Every `stride`-th f32 bit pattern from `from` to `to` (both finite, ordered), both signs
/// when `signed`.
fn sweep(from: f32, to: f32, stride: u32) -> impl Iterator<Item = f32> {
    (from.to_bits()..=to.to_bits())
        .step_by(stride as usize)
        .map(f32::from_bits)
}

/// The largest error of `ours` against `reference` (rounded f64) and against `platform`.
fn worst(
    inputs: impl Iterator<Item = f32>,
    ours: impl Fn(f32) -> f32,
    reference: impl Fn(f64) -> f64,
    platform: impl Fn(f32) -> f32,
) -> (u64, u64, f32) {
    let (mut against_exact, mut against_platform, mut at) = (0, 0, 0.0);
    for x in inputs {
        let v = ours(x);
        let exact = ulps(v, reference(f64::from(x)) as f32);
        if exact > against_exact {
            (against_exact, at) = (exact, x);
        }
        against_platform = against_platform.max(ulps(v, platform(x)));
    }
    (against_exact, against_platform, at)
}

#[test]
fn sin_and_cos_are_within_two_ulps_up_to_ten_thousand() {
    for sign in [1.0f32, -1.0] {
        let inputs = || sweep(0.0, 1.0e4, 1009).map(move |x| sign * x);
        let (s, sp, at) = worst(inputs(), |x| sin_cos(x).0, f64::sin, f32::sin);
        assert!(s <= 2, "sin: {s} ulps at {at}");
        let (c, cp, at) = worst(inputs(), |x| sin_cos(x).1, f64::cos, f32::cos);
        assert!(c <= 2, "cos: {c} ulps at {at}");
        println!("sin: {s} ulps ({sp} from the platform's), cos: {c} ({cp})");
    }
    // Far out (libm's exact reduction): as accurate; NaN and infinities give NaN.
    let far = || sweep(1.0e4, f32::MAX, 409_999);
    let (s, _, at) = worst(far(), |x| sin_cos(x).0, f64::sin, f32::sin);
    assert!(s <= 2, "sin far out: {s} ulps at {at}");
    for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let (s, c) = sin_cos(x);
        assert!(s.is_nan() && c.is_nan(), "{x}");
    }
    assert_eq!(sin_cos(0.0f32), (0.0, 1.0));
}

#[test]
fn ln_is_within_one_ulp_of_every_positive_number() {
    let (e, p, at) = worst(
        sweep(f32::from_bits(1), f32::MAX, 1013),
        ln,
        f64::ln,
        f32::ln,
    );
    assert!(e <= 1, "ln: {e} ulps at {at}");
    println!("ln: {e} ulps ({p} from the platform's)");
    assert_eq!(ln(1.0f32), 0.0);
    assert_eq!(ln(0.0f32), f32::NEG_INFINITY);
    assert_eq!(ln(f32::INFINITY), f32::INFINITY);
    assert!(ln(-1.0f32).is_nan() && ln(f32::NAN).is_nan());
}

#[test]
fn atan2_is_within_three_ulps_everywhere() {
    let values: Vec<f32> = sweep(0.0, f32::MAX, 1_600_009)
        .flat_map(|v| [v, -v])
        .collect();
    let (mut worst_exact, mut worst_platform) = (0, 0);
    for &y in &values {
        for &x in &values {
            let ours = atan2(y, x);
            let exact = f64::from(y).atan2(f64::from(x)) as f32;
            let e = ulps(ours, exact);
            assert!(e <= 3, "atan2({y}, {x}) = {ours}, {exact}: {e} ulps");
            worst_exact = worst_exact.max(e);
            worst_platform = worst_platform.max(ulps(ours, y.atan2(x)));
        }
    }
    println!("atan2: {worst_exact} ulps ({worst_platform} from the platform's)");
    assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
    assert_eq!(
        atan2(f32::INFINITY, f32::INFINITY),
        std::f32::consts::FRAC_PI_4
    );
}

#[test]
fn acos_is_within_two_ulps_on_its_domain() {
    for sign in [1.0f32, -1.0] {
        let inputs = sweep(0.0, 1.0, 97).map(move |x| sign * x);
        let (e, p, at) = worst(inputs, acos, f64::acos, f32::acos);
        assert!(e <= 2, "acos: {e} ulps at {at}");
        println!("acos: {e} ulps ({p} from the platform's)");
    }
    assert!(acos(1.5f32).is_nan() && acos(f32::NAN).is_nan());
}

#[test]
fn floor_and_round_are_exact() {
    for x in sweep(0.0, 3.0e7, 997).flat_map(|v| [v, -v]) {
        assert_eq!(floor(x), x.floor(), "{x}");
        assert_eq!(round(x), x.round_ties_even(), "{x}");
    }
}

/// What lane tests feed the kernels, eight a step of the sweep: signs, reciprocals, NaN,
/// infinity, square roots, subnormals and values past the reduction's range.
fn lane_inputs() -> Vec<f32> {
    sweep(0.0, 3.0e4, 7919)
        .flat_map(|v| {
            [
                v,
                -v,
                1.0 / (v + 0.5),
                f32::NAN,
                f32::INFINITY,
                0.5 * v.sqrt(),
                v * 1e-40,
                -v * 3.0e9,
            ]
        })
        .collect()
}

/// Lanes of `L` over `x` (`L::WIDTH` values) give each lane the bits one lane gives it, for
/// the kernels every width shares: `sin_cos`, `ln`, `floor`.
fn kernels_give_the_bits_of_one<L: super::lane::Lane>(x: &[f32]) {
    let lanes = L::from_fn(|k| x[k]);
    let bits = |v: L| {
        (0..L::WIDTH)
            .map(|k| v.get(k).to_bits())
            .collect::<Vec<_>>()
    };
    let one = |f: &dyn Fn(f32) -> f32| x.iter().map(|&v| f(v).to_bits()).collect::<Vec<_>>();
    let (s, c) = sin_cos(lanes);
    assert_eq!(bits(s), one(&|v| sin_cos(v).0), "{x:?}");
    assert_eq!(bits(c), one(&|v| sin_cos(v).1), "{x:?}");
    assert_eq!(bits(ln(lanes)), one(&ln), "{x:?}");
    assert_eq!(bits(floor(lanes)), one(&floor), "{x:?}");
}

/// Four lanes give each lane the bits one lane gives it, for every kernel.
#[test]
fn lanes_give_the_bits_of_one() {
    let inputs = lane_inputs();
    for chunk in inputs.chunks_exact(4) {
        let x: [f32; 4] = chunk.try_into().unwrap();
        let y = x.map(|v| 0.37 - v);
        let lanes = f32x4::from(x);
        kernels_give_the_bits_of_one::<f32x4>(chunk);
        let a = atan2(f32x4::from(y), lanes).to_array().map(f32::to_bits);
        let b: Vec<u32> = y
            .iter()
            .zip(&x)
            .map(|(&y, &x)| atan2(y, x).to_bits())
            .collect();
        assert_eq!(a.to_vec(), b, "{x:?}");
        let clamped = x.map(|v| (v * 1e-4).clamp(-1.0, 1.0));
        let a = acos(f32x4::from(clamped)).to_array().map(f32::to_bits);
        assert_eq!(a, clamped.map(|v| acos(v).to_bits()), "{x:?}");
    }
}

/// Eight AVX2 lanes give each lane the bits of one (where this CPU has AVX2): the kernels, the
/// square root and division, `frexp`, the truncation to indices (NaN, infinities and
/// out-of-range values included) and a comparison's select.
#[cfg(target_arch = "x86_64")]
#[test]
fn eight_lanes_give_the_bits_of_one() {
    use super::avx::{F8, has_avx2};
    use super::lane::Lane;
    if !has_avx2() {
        eprintln!("no AVX2 on this CPU: eight lanes are not used here");
        return;
    }
    let inputs = lane_inputs();
    for chunk in inputs.chunks_exact(8) {
        let x: [f32; 8] = chunk.try_into().unwrap();
        let lanes = F8::from_fn(|k| x[k]);
        let bits = |v: F8| std::array::from_fn::<u32, 8, _>(|k| v.get(k).to_bits());
        let one = |f: &dyn Fn(f32) -> f32| x.map(|v| f(v).to_bits());
        kernels_give_the_bits_of_one::<F8>(chunk);
        assert_eq!(bits(round(lanes)), one(&round), "{x:?}");
        assert_eq!(bits(lanes.sqrt()), one(&f32::sqrt), "{x:?}");
        assert_eq!(bits(-lanes), one(&|v| -v), "{x:?}");
        assert_eq!(bits(lanes.abs()), one(&f32::abs), "{x:?}");
        let y = x.map(|v| 0.37 - v);
        let ys = F8::from_fn(|k| y[k]);
        assert_eq!(
            bits(ys / lanes),
            std::array::from_fn(|k| (y[k] / x[k]).to_bits()),
            "{x:?}"
        );
        let a = bits(atan2(ys, lanes));
        assert_eq!(a, std::array::from_fn(|k| atan2(y[k], x[k]).to_bits()));
        let clamped = x.map(|v| (v * 1e-4).clamp(-1.0, 1.0));
        let a = bits(acos(F8::from_fn(|k| clamped[k])));
        assert_eq!(a, clamped.map(|v| acos(v).to_bits()), "{x:?}");
        let positive = x.map(|v| v.abs().max(f32::from_bits(1)).min(f32::MAX));
        let (m, e) = F8::from_fn(|k| positive[k]).frexp();
        for (k, v) in positive.iter().enumerate() {
            let (m1, e1) = v.frexp();
            assert_eq!(
                (m.get(k).to_bits(), e.get(k).to_bits()),
                (m1.to_bits(), e1.to_bits())
            );
        }
        let four: [i32; 8] = std::array::from_fn(|k| {
            let half = f32x4::from(std::array::from_fn::<f32, 4, _>(|j| x[k / 4 * 4 + j]));
            half.to_i32s()[k % 4]
        });
        assert_eq!(lanes.to_i32s(), four, "{x:?}");
        assert_eq!(lanes.to_i32s(), x.map(|v| v as i32), "{x:?}");
        let picked = F8::select(lanes.lt(ys), lanes, ys);
        assert_eq!(
            bits(picked),
            std::array::from_fn(|k| if x[k] < y[k] { x[k] } else { y[k] }.to_bits())
        );
    }
}
