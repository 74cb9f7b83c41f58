//! The noise matrix that drives the yarn angles (cloth paper §3.1, §4).

use crate::spectrum::{GridShape, periodic_lerp, try_fbm};

use super::ClothError;

/// 1/f^β noise scaled into [−1, 1]: rows × columns for frozen wind (a 2-D matrix, §4.1), or
/// frames × rows × columns for non-frozen wind (a 3-D matrix, §4.2). Read between nodes by
/// periodic linear interpolation, so shifts need not be whole steps.
#[derive(Clone, Debug)]
pub struct NoiseSheet {
    shape: GridShape,
    values: Vec<f32>,
}

impl NoiseSheet {
    /// A sheet of `rows × columns` (and `frames` deep if `frames > 1`), spectral exponent `beta`.
    pub fn new(
        frames: usize,
        rows: usize,
        columns: usize,
        beta: f32,
        seed: u64,
    ) -> Result<Self, ClothError> {
        let mut dims = Vec::with_capacity(3);
        if frames > 1 {
            dims.push(frames);
        }
        dims.extend([rows.max(2), columns.max(2)]);
        let mut values = try_fbm(&dims, beta, seed).map_err(|_| ClothError::Invalid {
            field: "beta",
            value: beta,
            reason: "must be finite and ≥ 0",
        })?;
        // Scale into [−1, 1]: the angles then span exactly the amplitude range [−θ, θ].
        let peak = values.iter().fold(0.0f32, |m, v| m.max(v.abs()));
        if peak > 0.0 {
            values.iter_mut().for_each(|v| *v /= peak);
        }
        Ok(Self {
            shape: GridShape::new(&dims),
            values,
        })
    }

    /// Whether the sheet has a time axis (non-frozen wind).
    pub fn evolving(&self) -> bool {
        self.shape.dims().len() == 3
    }

    /// (frames, rows, columns); frames is 1 for a frozen sheet.
    pub fn size(&self) -> (usize, usize, usize) {
        let d = self.shape.dims();
        match d.len() {
            3 => (d[0], d[1], d[2]),
            _ => (1, d[0], d[1]),
        }
    }

    /// Fills `out[j]` with `scale` times the value at (frame, row, first_column + j) for every j: one line of
    /// the sheet read at a fractional offset. The interpolation weights are the same for the
    /// whole line, so this is much cheaper than [`Self::sample`] per node.
    pub fn sample_line(
        &self,
        frame: f64,
        row: f64,
        first_column: f64,
        scale: f32,
        out: &mut [f32],
    ) {
        let (frames, rows, columns) = self.size();
        let split = |x: f64, n: usize| -> (usize, usize, f32) {
            let len = n as f64;
            let c = x - (x / len).floor() * len;
            let c = if c.is_finite() {
                c.clamp(0.0, len)
            } else {
                0.0
            };
            let i = (c as usize).min(n - 1);
            (i, (i + 1) % n, (c - i as f64).clamp(0.0, 1.0) as f32)
        };
        let (f0, f1, tf) = if frames > 1 {
            split(frame, frames)
        } else {
            (0, 0, 0.0)
        };
        let (r0, r1, tr) = split(row, rows);
        let (c0, _, tc) = split(first_column, columns);
        // The four (frame, row) lines to blend, with their weights.
        let lines = [
            ((f0 * rows + r0) * columns, (1.0 - tf) * (1.0 - tr)),
            ((f0 * rows + r1) * columns, (1.0 - tf) * tr),
            ((f1 * rows + r0) * columns, tf * (1.0 - tr)),
            ((f1 * rows + r1) * columns, tf * tr),
        ];
        let used = if frames > 1 { 4 } else { 2 };
        out.fill(0.0);
        for &(base, weight) in &lines[..used] {
            let line = &self.values[base..base + columns];
            let (a, b) = (scale * weight * (1.0 - tc), scale * weight * tc);
            let mut c = c0;
            for value in out.iter_mut() {
                let next = if c + 1 == columns { 0 } else { c + 1 };
                *value += a * line[c] + b * line[next];
                c = next;
            }
        }
    }

    /// Value at fractional (frame, row, column), wrapping every axis; in [−1, 1].
    pub fn sample(&self, frame: f64, row: f64, column: f64) -> f32 {
        if self.evolving() {
            periodic_lerp(&self.shape, &self.values, &[frame, row, column])
        } else {
            periodic_lerp(&self.shape, &self.values, &[row, column])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_reads_match_point_reads() {
        for frames in [1, 5] {
            let sheet = NoiseSheet::new(frames, 6, 10, 2.0, 3).unwrap();
            let mut line = vec![0.0; 23];
            for (frame, row, start) in [(0.0, 0.0, 0.0), (1.3, 2.7, -4.25), (7.9, -1.5, 13.6)] {
                sheet.sample_line(frame, row, start, 1.0, &mut line);
                for (j, v) in line.iter().enumerate() {
                    let p = sheet.sample(frame, row, start + j as f64);
                    assert!((v - p).abs() < 1e-5, "{frames} {j}: {v} vs {p}");
                }
            }
        }
    }
}
