//! Smoothing a scalar load over a sheet: the screened filter S = (1 − ℓ²∇²)⁻¹ along each grid
//! line, rows then columns.
//!
//! A quasi-steady face law answers each face's own incidence. In potential flow the pressure on
//! a wave of wavenumber k along a sheet carries a factor 1/|k| (Argentina & Mahadevan, "Fluid-flow
//! -induced flutter of a flag", PNAS 102, 2005): a wave a few nodes long is pushed far less
//! than the face law says, a wave the size of the sheet about as much. The filter keeps a load's
//! long waves and takes out the short ones (a wave of wavenumber k keeps 1 / (1 + ℓ²k²) of
//! itself). Along the yarns from the pins no load leaves the sheet (zero flux at both ends);
//! past the sheet's side edges, round which the air flows, the pressure difference across it
//! falls to zero. Hand-written: a tridiagonal solve per grid line (Thomas' algorithm), which no
//! maintained crate offers for strided data.

/// The filter of a `rows × columns` row-major grid: a = (ℓ / spacing)² along the rows and the
/// columns, and which ends of the lines are free (the load falls to zero one spacing beyond).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Screen {
    pub rows: usize,
    pub columns: usize,
    pub along_rows: f32,
    pub along_columns: f32,
    /// (first, last) end of every row, and of every column, free.
    pub free_rows: (bool, bool),
    pub free_columns: (bool, bool),
}

impl Screen {
    /// values ← S values: every line of a family at once (the factors depend only on the
    /// position along the line).
    pub fn smooth(&self, values: &mut [f32], scratch: &mut Vec<f32>) {
        let (rows, columns) = (self.rows, self.columns);
        scratch.resize(2 * rows.max(columns), 0.0);
        if let Some(a) = Line::new(0, 1, columns, self.along_rows, self.free_rows).factors(scratch)
        {
            // The rows side by side, so that their recurrences overlap.
            let (inverse, upper) = scratch.split_at(columns);
            for line in values.chunks_exact_mut(columns) {
                line[0] *= inverse[0];
            }
            for j in 1..columns {
                for line in values.chunks_exact_mut(columns) {
                    line[j] = (line[j] + a * line[j - 1]) * inverse[j];
                }
            }
            for j in (0..columns - 1).rev() {
                for line in values.chunks_exact_mut(columns) {
                    line[j] -= upper[j] * line[j + 1];
                }
            }
        }
        if let Some(a) =
            Line::new(0, 1, rows, self.along_columns, self.free_columns).factors(scratch)
        {
            let (inverse, upper) = scratch.split_at(rows);
            for v in &mut values[..columns] {
                *v *= inverse[0];
            }
            for k in 1..rows {
                let (done, rest) = values.split_at_mut(k * columns);
                let above = &done[(k - 1) * columns..];
                for (v, w) in rest[..columns].iter_mut().zip(above) {
                    *v = (*v + a * w) * inverse[k];
                }
            }
            for k in (0..rows - 1).rev() {
                let (head, below) = values.split_at_mut((k + 1) * columns);
                let line = &mut head[k * columns..];
                for (v, w) in line.iter_mut().zip(&below[..columns]) {
                    *v -= upper[k] * w;
                }
            }
        }
    }

    /// values ← S⁻¹ values.
    pub fn unsmooth(&self, values: &mut [f32], scratch: &mut Vec<f32>) {
        let (rows, columns) = (self.rows, self.columns);
        scratch.resize(rows.max(columns), 0.0);
        for k in 0..rows {
            let line = Line::new(k * columns, 1, columns, self.along_rows, self.free_rows);
            line.multiply(values, scratch);
        }
        for j in 0..columns {
            let line = Line::new(j, columns, rows, self.along_columns, self.free_columns);
            line.multiply(values, scratch);
        }
    }
}

/// One grid line: `count` values from `start`, `stride` apart, and its operator 1 − a δ².
struct Line {
    start: usize,
    stride: usize,
    count: usize,
    a: f32,
    free: (bool, bool),
}

impl Line {
    fn new(start: usize, stride: usize, count: usize, a: f32, free: (bool, bool)) -> Self {
        Self {
            start,
            stride,
            count,
            a,
            free,
        }
    }

    /// The operator's diagonal at node `j`: 1 + a per neighbour, counting the zero beyond a
    /// free end.
    fn diagonal(&self, j: usize) -> f32 {
        let first = j > 0 || self.free.0;
        let last = j + 1 < self.count || self.free.1;
        1.0 + self.a * (f32::from(u8::from(first)) + f32::from(u8::from(last)))
    }

    fn active(&self) -> bool {
        self.count >= 2 && self.a.is_finite() && self.a > 0.0
    }

    /// Thomas' factors of the line's operator into `scratch` (every pivot ≥ 1: the matrix is
    /// diagonally dominant): 1 / pivot for each node, then the upper factor −a / pivot; returns
    /// a, or None where the line is left as it is.
    fn factors(&self, scratch: &mut [f32]) -> Option<f32> {
        if !self.active() {
            return None;
        }
        let (a, n) = (self.a, self.count);
        let (inverse, upper) = scratch.split_at_mut(n);
        let mut previous = 0.0;
        for j in 0..n {
            let pivot = self.diagonal(j) + a * previous;
            inverse[j] = 1.0 / pivot;
            previous = -a / pivot;
            upper[j] = previous;
        }
        Some(a)
    }

    /// values ← (1 − a δ²) values.
    fn multiply(&self, values: &mut [f32], scratch: &mut [f32]) {
        if !self.active() {
            return;
        }
        let at = |j: usize| self.start + j * self.stride;
        for (j, s) in scratch.iter_mut().enumerate().take(self.count) {
            *s = values[at(j)];
        }
        for j in 0..self.count {
            let left = if j > 0 { scratch[j - 1] } else { 0.0 };
            let right = if j + 1 < self.count {
                scratch[j + 1]
            } else {
                0.0
            };
            values[at(j)] = self.diagonal(j) * scratch[j] - self.a * (left + right);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(values: &[f32], a: f32, free: (bool, bool)) -> Vec<f32> {
        let mut v = values.to_vec();
        let screen = Screen {
            rows: 1,
            columns: values.len(),
            along_rows: a,
            along_columns: 0.0,
            free_rows: free,
            free_columns: (false, false),
        };
        screen.smooth(&mut v, &mut Vec::new());
        v
    }

    #[test]
    fn keeps_long_waves_and_takes_out_short_ones() {
        let n = 40;
        let a = 4.0;
        let held = (false, false);
        // A constant stays, to rounding.
        assert!(
            line(&vec![2.5; n], a, held)
                .iter()
                .all(|x| (x - 2.5).abs() < 1e-5)
        );
        // A grid-scale ripple (+1, −1, …) keeps about 1 / (1 + 4a) of itself in the middle.
        let ripple: Vec<f32> = (0..n)
            .map(|j| if j % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let kept = line(&ripple, a, held)[n / 2].abs();
        assert!((kept - 1.0 / (1.0 + 4.0 * a)).abs() < 1e-3, "{kept}");
        // A wave as long as the line keeps nearly all: 1 / (1 + a (2 sin(k/2))²), k = 2π/n.
        let k = std::f32::consts::TAU / n as f32;
        let wave: Vec<f32> = (0..n).map(|j| (k * j as f32).cos()).collect();
        let out = line(&wave, a, held);
        let expected = 1.0 / (1.0 + a * (2.0 * (k / 2.0).sin()).powi(2));
        assert!(expected > 0.9);
        assert!(
            (out[n / 2] / wave[n / 2] - expected).abs() < 0.05,
            "{}",
            out[n / 2]
        );
        // Between held ends any load keeps its total (the ends pass nothing on).
        let load: Vec<f32> = (0..n).map(|j| ((j * 7919) % 13) as f32 - 6.0).collect();
        let (before, after) = (
            load.iter().sum::<f32>(),
            line(&load, a, held).iter().sum::<f32>(),
        );
        assert!((before - after).abs() < 1e-3, "{before} vs {after}");
        // A free end: a constant load falls toward it, and stays far from it.
        let out = line(&vec![1.0; n], a, (false, true));
        assert!(
            out[n - 1] < 0.5 && out[0] > 0.99,
            "{} {}",
            out[n - 1],
            out[0]
        );
        assert!(out.windows(2).all(|w| w[1] <= w[0] + 1e-6));
    }

    #[test]
    fn smooth_and_unsmooth_undo_each_other() {
        let screen = Screen {
            rows: 6,
            columns: 9,
            along_rows: 2.0,
            along_columns: 3.0,
            free_rows: (false, true),
            free_columns: (true, true),
        };
        let original: Vec<f32> = (0..54).map(|i| ((i * 37) % 11) as f32 - 5.0).collect();
        let mut v = original.clone();
        let mut scratch = Vec::new();
        screen.smooth(&mut v, &mut scratch);
        // One node pushed spreads to both neighbours in both directions.
        let mut one = vec![0.0; 54];
        one[3 * 9 + 4] = 1.0;
        screen.smooth(&mut one, &mut scratch);
        assert!(one[3 * 9 + 4] < 0.5 && one[3 * 9 + 5] > 0.0 && one[4 * 9 + 4] > 0.0);
        screen.unsmooth(&mut v, &mut scratch);
        for (a, b) in v.iter().zip(&original) {
            assert!((a - b).abs() < 1e-4, "{a} vs {b}");
        }
    }
}
