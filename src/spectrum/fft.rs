//! n-dimensional inverse FFT with rustfft, one axis at a time.

use std::sync::Arc;

use rustfft::{Fft, FftPlanner, FftPlannerScalar, num_complex::Complex};

use super::grid::GridShape;

/// Which rustfft planner transforms the spectrum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum FftBackend {
    /// rustfft's scalar algorithms: the same bits on every machine. The default.
    #[default]
    Portable,
    /// rustfft's SIMD algorithms (AVX, SSE, NEON), chosen at run time: faster, and the same bits
    /// on machines with the same instruction set, but not across instruction sets.
    Simd,
}

/// Planned transforms for one grid shape.
pub(crate) struct InverseFftNd {
    ffts: Vec<Arc<dyn Fft<f32>>>,
}

impl InverseFftNd {
    pub(crate) fn new(shape: &GridShape, backend: FftBackend) -> Self {
        let ffts = match backend {
            FftBackend::Portable => {
                let mut planner = FftPlannerScalar::new();
                shape
                    .dims()
                    .iter()
                    .map(|&n| planner.plan_fft_inverse(n))
                    .collect()
            }
            FftBackend::Simd => {
                let mut planner = FftPlanner::new();
                shape
                    .dims()
                    .iter()
                    .map(|&n| planner.plan_fft_inverse(n))
                    .collect()
            }
        };
        Self { ffts }
    }

    /// In-place inverse transform (unnormalised). Lines along an axis are gathered into a
    /// contiguous buffer so that rustfft transforms them as one batch.
    pub(crate) fn process(&self, data: &mut [Complex<f32>], shape: &GridShape) {
        let zero = Complex::new(0.0, 0.0);
        let mut lines = Vec::new();
        let mut scratch = Vec::new();
        for ((&n, &stride), fft) in shape.dims().iter().zip(shape.strides()).zip(&self.ffts) {
            scratch.resize(fft.get_inplace_scratch_len(), zero);
            if stride == 1 {
                fft.process_with_scratch(data, &mut scratch);
                continue;
            }
            let block_len = n * stride;
            lines.resize(block_len, zero);
            for block in data.chunks_exact_mut(block_len) {
                for (i, row) in block.chunks_exact(stride).enumerate() {
                    for (j, &value) in row.iter().enumerate() {
                        lines[j * n + i] = value;
                    }
                }
                fft.process_with_scratch(&mut lines, &mut scratch);
                for (i, row) in block.chunks_exact_mut(stride).enumerate() {
                    for (j, value) in row.iter_mut().enumerate() {
                        *value = lines[j * n + i];
                    }
                }
            }
        }
    }
}
