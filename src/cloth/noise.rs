//! The noise matrix that drives the yarn angles (cloth paper §3.1, §4).

use crate::error::InvalidValue;
use crate::spectrum::{GridShape, fbm};

use super::params::ClothError;

/// 1/f^β noise scaled into [−1, 1]: rows × columns for frozen wind (a 2-D matrix, §4.1), or
/// frames × rows × columns for evolving wind (a 3-D matrix, §4.2). Read between nodes by
/// periodic linear interpolation, so shifts need not be whole steps.
#[derive(Clone, Debug)]
pub(crate) struct NoiseSheet {
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
        let mut values = fbm(&dims, beta, seed)
            .map_err(|_| InvalidValue::new("beta", beta, "must be finite and ≥ 0"))?;
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

    /// (frames, rows, columns); frames is 1 for a frozen sheet.
    pub fn size(&self) -> (usize, usize, usize) {
        let d = self.shape.dims();
        match d.len() {
            3 => (d[0], d[1], d[2]),
            _ => (1, d[0], d[1]),
        }
    }

    /// Line `index` (frame × rows + row) of the sheet, `columns` long.
    pub fn line(&self, index: usize) -> &[f32] {
        let (_, _, columns) = self.size();
        &self.values[index * columns..(index + 1) * columns]
    }
}
