//! Spectrum slope error against grid size (and so run time), against bare rustfft.

use std::hint::black_box;

use bevy_windfall::spectrum::fbm;
#[path = "../../tests/it/common/measure.rs"]
mod measure;
use measure::{fit_slope, line_spectrum};
use rustfft::{FftPlannerScalar, num_complex::Complex};

use super::plot::{Plot, Series};
use super::{Report, sci, seconds_per};

pub fn report(r: &mut Report) {
    r.section(
        "Spectrum: slope error against grid size",
        "2-D fields n × n by `fbm` (inverse FFT of 1/f^β noise, `spectrum` module). The slope of \
         the line spectrum along x, fitted on log-spaced bins over k = 2..n/4 and averaged over 4 \
         to 64 seeds, against the target −β (slope error = |slope + β|). Time: one `fbm` call (planning included) with \
         the crate's default portable FFT; baseline: one bare rustfft complex 2-D inverse FFT of \
         the same size with its scalar planner (the same FFT code), rows then columns. The \
         difference is the rest of the synthesis: a portable normal draw and a spectral weight \
         per node.",
    );
    let sizes: &[usize] = if r.quick {
        &[16, 32, 64]
    } else {
        &[16, 32, 64, 128, 256, 512]
    };
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for beta in [5.0f32 / 3.0, 3.0] {
        let mut points = Vec::new();
        for &n in sizes {
            let dims = [n, n];
            // Enough seeds that the fit's scatter is below its bias on small grids too.
            let seeds = (65_536 / (n * n)).clamp(4, 64) as u64;
            let mut power = vec![0.0; n / 2 + 1];
            for seed in 0..seeds {
                let field = fbm(&dims, beta, 7 + seed).expect("a valid grid and beta");
                for (p, q) in power.iter_mut().zip(line_spectrum(&field, &dims, 0)) {
                    *p += q;
                }
            }
            let slope = fit_slope(&power, 2, (n / 4).max(3));
            let error = (slope + f64::from(beta)).abs();
            let repeats = if r.quick { 1 } else { (1 << 18) / (n * n) + 1 };
            let ours = seconds_per(repeats, || {
                black_box(fbm(black_box(&dims), beta, 1).expect("a valid grid and beta"));
            });
            let bare = bare_fft_2d(n, repeats);
            points.push((ours * 1e6, error));
            rows.push(vec![
                format!("{beta:.2}"),
                format!("{n}×{n}"),
                seeds.to_string(),
                format!("{slope:.3}"),
                sci(error),
                format!("{:.1}", ours * 1e6),
                format!("{:.1}", bare * 1e6),
                format!("{:.2}", ours / bare),
            ]);
        }
        series.push(Series::new(format!("β = {beta:.2}"), points));
    }
    r.table(
        &[
            "β",
            "grid",
            "seeds",
            "fitted slope",
            "slope error",
            "µs per field",
            "bare rustfft µs",
            "ratio",
        ],
        &rows,
    );
    r.figure(
        "spectrum_slope",
        &Plot {
            title: "Spectrum slope error against synthesis time (16² … 512²)",
            x_label: "µs per field",
            y_label: "|fitted slope + β|",
            series,
        },
    );
}

/// Seconds for one complex n × n inverse FFT by rustfft's scalar planner, rows then columns.
fn bare_fft_2d(n: usize, repeats: usize) -> f64 {
    let fft = FftPlannerScalar::<f32>::new().plan_fft_inverse(n);
    let mut data = vec![Complex::new(1.0f32, 0.5); n * n];
    let mut column = vec![Complex::new(0.0f32, 0.0); n];
    seconds_per(repeats, || {
        for row in data.chunks_mut(n) {
            fft.process(row);
        }
        for j in 0..n {
            for i in 0..n {
                column[i] = data[i * n + j];
            }
            fft.process(&mut column);
            for i in 0..n {
                data[i * n + j] = column[i];
            }
        }
        black_box(&mut data);
    })
}
