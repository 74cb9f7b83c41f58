//! The `spectrum` module: slopes, moments, realness, periodicity, sizes, seeds.
use crate::common::measure;
use bevy_windfall::spectrum::{FftBackend, SpectrumError, Synthesizer, fbm};
use measure::{fit_slope, line_spectrum, mean_variance};

const BETAS: [f32; 4] = [1.0, 5.0 / 3.0, 2.0, 3.0];
const TOLERANCE: f64 = 0.1;

/// Mean line spectrum along `axis` over a few seeds.
fn averaged_spectrum(dims: &[usize], beta: f32, axis: usize, seeds: u64) -> Vec<f64> {
    let mut total = vec![0.0; dims[axis] / 2 + 1];
    for seed in 0..seeds {
        let field = fbm(dims, beta, 1000 + seed).unwrap();
        for (t, p) in total.iter_mut().zip(line_spectrum(&field, dims, axis)) {
            *t += p;
        }
    }
    total
}

fn assert_slope(dims: &[usize], axis: usize, seeds: u64, k_lo: usize, k_hi: usize) {
    for beta in BETAS {
        let slope = fit_slope(&averaged_spectrum(dims, beta, axis, seeds), k_lo, k_hi);
        assert!(
            (slope + f64::from(beta)).abs() <= TOLERANCE,
            "{dims:?} axis {axis}: slope {slope:.3}, expected {:.3}",
            -beta
        );
    }
}

#[test]
fn one_dimensional_slope_is_minus_beta() {
    assert_slope(&[4096], 0, 32, 4, 512);
}

#[test]
fn two_dimensional_line_slope_is_minus_beta_on_both_axes() {
    assert_slope(&[256, 256], 0, 4, 4, 64);
    assert_slope(&[256, 256], 1, 4, 4, 64);
}

#[test]
fn three_dimensional_line_slope_is_minus_beta_on_every_axis() {
    for axis in 0..3 {
        assert_slope(&[64, 64, 64], axis, 4, 2, 16);
    }
}

#[test]
fn non_power_of_two_sizes_keep_slope_and_moments() {
    // 1500 = 2²·3·5³ and 3000 along a 2-D line: mixed-radix transforms.
    assert_slope(&[1500], 0, 32, 4, 187);
    assert_slope(&[100, 1200], 1, 4, 4, 300);
    for dims in [&[2usize][..], &[3], &[7, 5], &[3, 5, 7], &[2, 2, 2]] {
        let (mean, var) = mean_variance(&fbm(dims, 5.0 / 3.0, 3).unwrap());
        assert!(
            mean.abs() < 1e-5 && (var - 1.0).abs() < 1e-4,
            "{dims:?}: {mean} {var}"
        );
    }
}

#[test]
fn fields_have_zero_mean_and_unit_variance() {
    for beta in [0.0, 1.0, 5.0 / 3.0, 3.0, 8.0] {
        for dims in [&[1024usize][..], &[64, 48], &[16, 16, 16]] {
            let (mean, var) = mean_variance(&fbm(dims, beta, 11).unwrap());
            assert!(mean.abs() < 1e-5, "{dims:?} β={beta}: mean {mean}");
            assert!(
                (var - 1.0).abs() < 1e-4,
                "{dims:?} β={beta}: variance {var}"
            );
        }
    }
}

#[test]
fn paired_fields_are_real_and_independent() {
    // If the spectrum were not exactly Hermitian, the real and imaginary parts of the transform
    // would mix, and the two fields of a pair would correlate. Correlate second differences
    // (blue for every β ≤ 3, so many independent samples) over a few seeds.
    let dims = [128, 128];
    let increments = |f: &[f32]| -> Vec<f64> {
        f.windows(3)
            .map(|w| f64::from(w[2] - 2.0 * w[1] + w[0]))
            .collect()
    };
    for beta in BETAS {
        let mut corr = 0.0;
        for seed in 0..4 {
            let (a, b) = Synthesizer::new(&dims, beta, FftBackend::Portable)
                .unwrap()
                .pair(seed);
            let (da, db) = (increments(&a), increments(&b));
            let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
            corr += dot(&da, &db) / (dot(&da, &da) * dot(&db, &db)).sqrt() / 4.0;
            let slope = fit_slope(&line_spectrum(&b, &dims, 1), 4, 24);
            assert!(
                (slope + f64::from(beta)).abs() <= 0.15,
                "second field slope {slope}"
            );
        }
        assert!(
            corr.abs() < 0.05,
            "β={beta}: correlation of increments {corr}"
        );
    }
}

#[test]
fn fields_tile_seamlessly() {
    // Differences across the wrap-around seam look like differences between any neighbours.
    // One seam is 128 strongly correlated differences, so its mean square scatters by about
    // ±25 % (0.76–1.47 of the inner ones over 8 seeds); over 16 fields it is within 25 %. A
    // non-periodic field would jump by about √2 σ at the seam: a ratio near 20 here.
    let (n, m) = (128, 128);
    let sq = |a: f32, b: f32| f64::from(a - b).powi(2);
    let (mut seam, mut inner) = (0.0, 0.0);
    for seed in 1..=16 {
        let f = fbm(&[n, m], 5.0 / 3.0, seed).unwrap();
        seam += (0..n).map(|i| sq(f[i * m], f[i * m + m - 1])).sum::<f64>() / n as f64;
        inner += (0..n)
            .flat_map(|i| (1..m).map(move |j| (i, j)))
            .map(|(i, j)| sq(f[i * m + j], f[i * m + j - 1]))
            .sum::<f64>()
            / (n * (m - 1)) as f64;
    }
    assert!(
        (seam / inner - 1.0).abs() < 0.25,
        "seam {seam} inner {inner}"
    );
}

#[test]
fn same_seed_same_bits_other_seed_other_field() {
    let bits = |v: Vec<f32>| v.into_iter().map(f32::to_bits).collect::<Vec<_>>();
    let a = bits(fbm(&[32, 40], 5.0 / 3.0, 77).unwrap());
    assert_eq!(a, bits(fbm(&[32, 40], 5.0 / 3.0, 77).unwrap()));
    assert_ne!(a, bits(fbm(&[32, 40], 5.0 / 3.0, 78).unwrap()));
    // Any thread gives the same bits.
    let handles: Vec<_> = (0..4)
        .map(|_| std::thread::spawn(|| fbm(&[32, 40], 5.0 / 3.0, 77).unwrap()))
        .collect();
    for h in handles {
        assert_eq!(a, bits(h.join().unwrap()));
    }
}

/// FNV-1a over the bit patterns.
fn fingerprint(values: &[f32]) -> u64 {
    values.iter().fold(0xcbf2_9ce4_8422_2325, |h, v| {
        v.to_bits()
            .to_le_bytes()
            .iter()
            .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
    })
}

#[test]
fn output_is_portable_across_machines() {
    // Fingerprints recorded on x86_64 Linux. The scalar FFT planner and PCG stream make them
    // the same on every machine; a change here means a change of the noise every user sees.
    assert_eq!(fingerprint(&fbm(&[256], 5.0 / 3.0, 42).unwrap()), GOLDEN_1D);
    assert_eq!(fingerprint(&fbm(&[12, 10, 9], 1.0, 7).unwrap()), GOLDEN_3D);
}
const GOLDEN_1D: u64 = 12228083372507955431;
const GOLDEN_3D: u64 = 2228581054304297266;

#[test]
fn bad_input_gives_a_named_error() {
    assert_eq!(fbm(&[], 1.0, 0), Err(SpectrumError::NoAxis));
    // Few nodes, but over many axes: 2^26 alias images per bin would hang the table.
    assert_eq!(
        fbm(&[2; 26], 1.0, 0),
        Err(SpectrumError::TooManyAxes { axes: 26 })
    );
    assert_eq!(
        fbm(&[4, 1, 4], 1.0, 0),
        Err(SpectrumError::AxisTooShort { axis: 1, len: 1 })
    );
    for beta in [-1.0, f32::NAN, f32::INFINITY] {
        assert!(matches!(fbm(&[8], beta, 0), Err(SpectrumError::Beta(_))));
    }
}

/// A shared synthesizer (kept across fields of the same grid and β) gives the same bits as a
/// fresh one, for every key it is asked for in turn, more keys than it keeps included.
#[test]
fn shared_synthesizers_give_the_same_bits_as_fresh_ones() {
    let keys: Vec<(Vec<usize>, f32)> = (0..Synthesizer::CACHED + 2)
        .map(|i| (vec![16 + 2 * i, 12], 1.0 + 0.25 * i as f32))
        .collect();
    for round in 0..2u64 {
        for (dims, beta) in &keys {
            let shared = Synthesizer::shared(dims, *beta, FftBackend::Portable).unwrap();
            let fresh = Synthesizer::new(dims, *beta, FftBackend::Portable).unwrap();
            let bits = |v: Vec<f32>| v.into_iter().map(f32::to_bits).collect::<Vec<_>>();
            assert_eq!(
                bits(shared.field(round)),
                bits(fresh.field(round)),
                "{dims:?}"
            );
            let (a, b) = (shared.pair(round + 7), fresh.pair(round + 7));
            assert_eq!((bits(a.0), bits(a.1)), (bits(b.0), bits(b.1)), "{dims:?}");
        }
    }
    // An invalid key is refused, not cached.
    assert!(Synthesizer::shared(&[1], 1.0, FftBackend::Portable).is_err());
}
