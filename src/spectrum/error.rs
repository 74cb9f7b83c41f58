//! [`SpectrumError`] and the size limits a synthesis checks before it allocates.

use thiserror::Error;

/// [`Synthesizer::MAX_AXES`](super::Synthesizer::MAX_AXES), here so that the error that quotes it
/// needs no import of the synthesizer (which imports the error).
pub(super) const MAX_AXES: usize = 4;

/// [`Synthesizer::MAX_NODES`](super::Synthesizer::MAX_NODES), here for the same reason.
pub(super) const MAX_NODES: usize = 1 << 26;

/// Why a noise field could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SpectrumError {
    /// No axis was given.
    #[error("`dims` is empty: a field needs at least one axis")]
    NoAxis,
    /// More axes than [`Synthesizer::MAX_AXES`](crate::spectrum::Synthesizer::MAX_AXES).
    #[error("`dims` has {axes} axes, more than the limit of {max} (`Synthesizer::MAX_AXES`)", max = MAX_AXES)]
    TooManyAxes {
        /// How many were given.
        axes: usize,
    },
    /// An axis has fewer than two nodes.
    #[error("`dims[{axis}]` = {len}: every axis needs at least 2 nodes")]
    AxisTooShort {
        /// Which axis.
        axis: usize,
        /// Its node count.
        len: usize,
    },
    /// β is negative or not finite.
    #[error("`beta` = {0}: the spectral exponent must be finite and ≥ 0")]
    Beta(f32),
    /// More nodes than [`Synthesizer::MAX_NODES`](crate::spectrum::Synthesizer::MAX_NODES) (the product saturates at `usize::MAX`).
    #[error(
        "`dims`: {nodes} nodes in all, more than the limit of {max} (`Synthesizer::MAX_NODES`)", max = MAX_NODES
    )]
    TooManyNodes {
        /// The product of `dims`, saturated.
        nodes: usize,
    },
}

impl SpectrumError {
    /// The argument at fault: `"dims"` or `"beta"`.
    pub fn field(&self) -> &'static str {
        match self {
            Self::Beta(_) => "beta",
            _ => "dims",
        }
    }
}
