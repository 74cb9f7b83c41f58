//! Wind interpolation: sampling a coarse grid between its nodes against the fine field, by
//! bilinear interpolation (what `WindField` does) and by the nearest node.

use std::hint::black_box;

use bevy::math::Vec3;
use bevy_windfall::spectrum::fbm;
use bevy_windfall::wind::{WindConfig, WindField};

use super::plot::{Plot, Series};
use super::{Report, sci, seconds_per};

const FINE: usize = 256;

pub fn report(r: &mut Report) {
    r.section(
        "Wind: interpolation error against grid spacing and run time",
        "A 256 × 256 field (β = 5/3) is the truth; a coarse grid keeps every s-th node and is \
         sampled at every fine node, bilinearly (what `WindField` does) or at \
         the nearest node. Error: RMS difference over the RMS of the field. The turbulence \
         between coarse nodes is lost either way: the error measures what a grid spacing of s \
         fine cells costs. Time: ns per sample.",
    );
    let field = fbm(&[FINE, FINE], 5.0 / 3.0, 3).expect("a valid grid and beta");
    let rms = (field.iter().map(|v| f64::from(v * v)).sum::<f64>() / field.len() as f64).sqrt();
    let mut rows = Vec::new();
    let (mut lerp_points, mut near_points) = (Vec::new(), Vec::new());
    for stride in [1usize, 2, 4, 8, 16] {
        let n = FINE / stride;
        let coarse: Vec<f32> = (0..n * n)
            .map(|i| field[(i / n) * stride * FINE + (i % n) * stride])
            .collect();
        let s = stride as f64;
        let lerp = |i: usize| bilinear(&coarse, n, (i / FINE) as f64 / s, (i % FINE) as f64 / s);
        let nearest = |i: usize| {
            let x = (((i / FINE) as f64 / s).round() as usize) % n;
            let y = (((i % FINE) as f64 / s).round() as usize) % n;
            coarse[x * n + y]
        };
        let error = |f: &dyn Fn(usize) -> f32| {
            let sq: f64 = (0..FINE * FINE)
                .map(|i| f64::from(f(i) - field[i]).powi(2))
                .sum();
            (sq / (FINE * FINE) as f64).sqrt() / rms
        };
        let (e_lerp, e_near) = (error(&lerp), error(&nearest));
        let repeats = if r.quick { 1 } else { 20 };
        let per = (FINE * FINE) as f64;
        let t_lerp = seconds_per(repeats, || {
            black_box((0..FINE * FINE).map(lerp).sum::<f32>());
        }) / per;
        let t_near = seconds_per(repeats, || {
            black_box((0..FINE * FINE).map(nearest).sum::<f32>());
        }) / per;
        lerp_points.push((t_lerp * 1e9, e_lerp));
        near_points.push((t_near * 1e9, e_near));
        rows.push(vec![
            format!("{stride}"),
            format!("{n}×{n}"),
            sci(e_lerp),
            format!("{:.1}", t_lerp * 1e9),
            sci(e_near),
            format!("{:.1}", t_near * 1e9),
        ]);
    }
    r.table(
        &[
            "spacing s (fine cells)",
            "coarse grid",
            "bilinear error",
            "bilinear ns",
            "nearest error",
            "nearest ns",
        ],
        &rows,
    );
    r.figure(
        "wind_interpolation",
        &Plot {
            title: "Interpolation error against ns per sample (s = 1 … 16)",
            x_label: "ns per sample",
            y_label: "RMS error / RMS field",
            series: vec![
                Series::new("bilinear", lerp_points),
                Series::new("nearest node", near_points),
            ],
        },
    );
    // The full sampler: log-law mean, three components, height scaling.
    let wind = WindField::new(WindConfig::default()).expect("default wind");
    let points: Vec<Vec3> = (0..4096)
        .map(|i| Vec3::new((i % 64) as f32 * 0.7, 1.5, (i / 64) as f32 * 0.7))
        .collect();
    let mut out = Vec::new();
    let t = seconds_per(if r.quick { 1 } else { 200 }, || {
        wind.velocities_at(black_box(&points), 1.0, &mut out);
    }) / points.len() as f64;
    r.markdown_line(&format!(
        "`WindField::velocities_at` (plane, frozen, 3 components with the log-law mean): \
         {:.1} ns per sample over 4096 points.",
        t * 1e9
    ));
}

/// Periodic bilinear interpolation of an `n` × `n` row-major grid at (x, y) in node units: the
/// same arithmetic as the crate's plane read.
fn bilinear(values: &[f32], n: usize, x: f64, y: f64) -> f32 {
    let wrap = |t: f64| {
        let f = t.floor();
        let i = f.rem_euclid(n as f64) as usize;
        (i, (i + 1) % n, (t - f) as f32)
    };
    let ((i0, i1, fx), (j0, j1, fy)) = (wrap(x), wrap(y));
    let low = values[i0 * n + j0] * (1.0 - fy) + values[i0 * n + j1] * fy;
    let high = values[i1 * n + j0] * (1.0 - fy) + values[i1 * n + j1] * fy;
    low * (1.0 - fx) + high * fx
}
