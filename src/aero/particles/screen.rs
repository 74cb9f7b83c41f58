//! Smoothing a load over a sheet: the screened filter (1 − ℓ²∇²) L̃ = L along each grid line.
//!
//! A quasi-steady face law answers each face's own incidence. In potential flow the pressure on
//! a wave of wavenumber k along a sheet carries a factor 1/|k| (Argentina & Mahadevan, "Fluid-flow
//! -induced flutter of a flag", PNAS 102, 2005): a wave a few nodes long is pushed far less
//! than the face law says, a wave the size of the sheet about as much. The filter keeps a load's
//! total and its long waves and takes out the short ones (a wave of wavenumber k keeps
//! 1 / (1 + ℓ²k²) of itself). Hand-written: a tridiagonal solve per grid line (Thomas'
//! algorithm), which no maintained crate offers for strided `Vec3` data.

use bevy::math::Vec3;

/// Filters `count` values of `values` starting at `start`, `stride` apart, in place:
/// (1 − a δ²) out = in with a = (ℓ / spacing)², δ² the second difference, and zero flux past
/// both ends (so the sum is kept). `scratch` holds at least `count` values.
pub(crate) fn screen_line(
    values: &mut [Vec3],
    start: usize,
    stride: usize,
    count: usize,
    a: f32,
    scratch: &mut [f32],
) {
    if count < 2 || !(a.is_finite() && a > 0.0) {
        return;
    }
    let diagonal = |j: usize| {
        if j == 0 || j + 1 == count {
            1.0 + a
        } else {
            1.0 + 2.0 * a
        }
    };
    let at = |j: usize| start + j * stride;
    // Forward sweep: the matrix is diagonally dominant, every pivot ≥ 1.
    let mut pivot = diagonal(0);
    scratch[0] = -a / pivot;
    values[at(0)] /= pivot;
    for j in 1..count {
        pivot = diagonal(j) + a * scratch[j - 1];
        scratch[j] = -a / pivot;
        values[at(j)] = (values[at(j)] + a * values[at(j - 1)]) / pivot;
    }
    for j in (0..count - 1).rev() {
        values[at(j)] = values[at(j)] - scratch[j] * values[at(j + 1)];
    }
}

/// [`screen_line`] along every row of a `rows × columns` row-major grid (spacing `dx`), then
/// along every column (spacing `dy`), with smoothing length `length` m.
pub(crate) fn screen_grid(
    values: &mut [Vec3],
    rows: usize,
    columns: usize,
    (dx, dy): (f32, f32),
    length: f32,
    scratch: &mut Vec<f32>,
) {
    scratch.resize(rows.max(columns), 0.0);
    let (ax, ay) = ((length / dx).powi(2), (length / dy).powi(2));
    for k in 0..rows {
        screen_line(values, k * columns, 1, columns, ax, scratch);
    }
    for j in 0..columns {
        screen_line(values, j, columns, rows, ay, scratch);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(values: &[f32], a: f32) -> Vec<f32> {
        let mut v: Vec<Vec3> = values.iter().map(|&x| Vec3::new(x, -x, 0.0)).collect();
        let mut scratch = vec![0.0; v.len()];
        screen_line(&mut v, 0, 1, values.len(), a, &mut scratch);
        assert!(v.iter().all(|p| p.y == -p.x), "components filtered alike");
        v.iter().map(|p| p.x).collect()
    }

    #[test]
    fn keeps_totals_and_long_waves_and_takes_out_short_ones() {
        let n = 40;
        let a = 4.0;
        // A constant stays, to rounding.
        assert!(
            line(&vec![2.5; n], a)
                .iter()
                .all(|x| (x - 2.5).abs() < 1e-5)
        );
        // A grid-scale ripple (+1, −1, …) keeps about 1 / (1 + 4a) of itself in the middle.
        let ripple: Vec<f32> = (0..n)
            .map(|j| if j % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let out = line(&ripple, a);
        let kept = out[n / 2].abs();
        assert!((kept - 1.0 / (1.0 + 4.0 * a)).abs() < 1e-3, "{kept}");
        // A wave as long as the line keeps nearly all: 1 / (1 + a (2 sin(k/2))²), k = 2π/n.
        let k = std::f32::consts::TAU / n as f32;
        let wave: Vec<f32> = (0..n).map(|j| (k * j as f32).cos()).collect();
        let out = line(&wave, a);
        let expected = 1.0 / (1.0 + a * (2.0 * (k / 2.0).sin()).powi(2));
        assert!(expected > 0.9);
        assert!(
            (out[n / 2] / wave[n / 2] - expected).abs() < 0.05,
            "{}",
            out[n / 2]
        );
        // Any load keeps its total (the ends pass nothing on).
        let load: Vec<f32> = (0..n).map(|j| ((j * 7919) % 13) as f32 - 6.0).collect();
        let (before, after) = (load.iter().sum::<f32>(), line(&load, a).iter().sum::<f32>());
        assert!((before - after).abs() < 1e-3, "{before} vs {after}");
    }

    #[test]
    fn a_grid_is_filtered_along_rows_and_columns() {
        let (rows, columns) = (6, 9);
        // One node pushed: the push spreads to both neighbours in both directions, total kept.
        let mut v = vec![Vec3::ZERO; rows * columns];
        v[3 * columns + 4] = Vec3::Z;
        let mut scratch = Vec::new();
        screen_grid(&mut v, rows, columns, (0.1, 0.1), 0.1, &mut scratch);
        let total: Vec3 = v.iter().sum();
        assert!((total - Vec3::Z).length() < 1e-5, "{total}");
        assert!(v[3 * columns + 4].z < 0.5);
        assert!(v[3 * columns + 5].z > 0.0 && v[4 * columns + 4].z > 0.0);
    }
}
