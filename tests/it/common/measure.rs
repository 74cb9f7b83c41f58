//! Measuring what a synthesis made: power spectra along grid lines, the slope of a spectrum
//! on log-log axes, mean and variance. The tests and the `report` example check the 1/f^β
//! law with these (`common::measure` here; the `report` example includes it by `#[path]`).
#![allow(dead_code)] // each user takes what it needs

use rustfft::{FftPlanner, num_complex::Complex};

/// Mean power |X(k)|² over every line of a row-major field along `axis`, for k in 0..=n/2.
pub fn line_spectrum(field: &[f32], dims: &[usize], axis: usize) -> Vec<f64> {
    let n = dims[axis];
    let stride: usize = dims[axis + 1..].iter().product();
    let fft = FftPlanner::<f64>::new().plan_fft_forward(n);
    let mut power = vec![0.0; n / 2 + 1];
    let mut line = vec![Complex::new(0.0, 0.0); n];
    let mut lines = 0usize;
    for start in 0..field.len() {
        if !(start / stride).is_multiple_of(n) {
            continue; // not the first node of a line along `axis`
        }
        for (i, c) in line.iter_mut().enumerate() {
            *c = Complex::new(f64::from(field[start + i * stride]), 0.0);
        }
        fft.process(&mut line);
        for (k, p) in power.iter_mut().enumerate() {
            *p += line[k].norm_sqr();
        }
        lines += 1;
    }
    power.iter().map(|p| p / lines as f64).collect()
}

/// Power spectrum of one real series, k in 0..=n/2.
pub fn series_spectrum(series: &[f32]) -> Vec<f64> {
    line_spectrum(series, &[series.len()], 0)
}

/// Least-squares slope of log power against log k over `k_lo..=k_hi`, on logarithmically spaced
/// bins (each the mean of its k's), each bin weighted by how many k's it averages (the inverse
/// of its variance), so that the sparse, noisy low-k bins do not dominate.
pub fn fit_slope(power: &[f64], k_lo: usize, k_hi: usize) -> f64 {
    let bins = 12;
    let (l0, l1) = ((k_lo as f64).ln(), ((k_hi + 1) as f64).ln());
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    let mut ws = Vec::new();
    for b in 0..bins {
        let lo = (l0 + (l1 - l0) * b as f64 / bins as f64).exp().ceil() as usize;
        let hi = (l0 + (l1 - l0) * (b + 1) as f64 / bins as f64).exp().ceil() as usize;
        let ks: Vec<usize> = (lo.max(k_lo)..hi.min(k_hi + 1)).collect();
        if ks.is_empty() {
            continue;
        }
        let k_mean = ks.iter().map(|&k| (k as f64).ln()).sum::<f64>() / ks.len() as f64;
        let p_mean = ks.iter().map(|&k| power[k]).sum::<f64>() / ks.len() as f64;
        xs.push(k_mean);
        ys.push(p_mean.ln());
        ws.push(ks.len() as f64);
    }
    let w: f64 = ws.iter().sum();
    let mx = xs.iter().zip(&ws).map(|(x, w)| x * w).sum::<f64>() / w;
    let my = ys.iter().zip(&ws).map(|(y, w)| y * w).sum::<f64>() / w;
    let sxy: f64 = (0..xs.len())
        .map(|i| ws[i] * (xs[i] - mx) * (ys[i] - my))
        .sum();
    let sxx: f64 = (0..xs.len()).map(|i| ws[i] * (xs[i] - mx).powi(2)).sum();
    sxy / sxx
}

/// Mean and variance (in f64).
pub fn mean_variance(values: &[f32]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
    let var = values
        .iter()
        .map(|&v| (f64::from(v) - mean).powi(2))
        .sum::<f64>()
        / n;
    (mean, var)
}
