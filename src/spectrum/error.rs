//! [`SpectrumError`] and the size limits a synthesis checks before it allocates.

use thiserror::Error;

/// Why a noise field could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SpectrumError {
    /// No axis was given.
    #[error("`dims` is empty: a field needs at least one axis")]
    NoAxis,
    /// More axes than [`Synthesizer::MAX_AXES`](crate::spectrum::Synthesizer::MAX_AXES).
    #[error("`dims` has {axes} axes, more than the limit of {MAX_AXES}")]
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
    #[error("`dims`: {nodes} nodes in all, more than the limit of {MAX_NODES}")]
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

/// Most axes a field may have: 4 (space and time). The amplitude table sums the power of
/// `2^n` alias images per bin, so without a bound a valid node count spread over many short
/// axes (`[2; 26]`) would take 2^52 steps to tabulate; with it, the table costs at most 16 steps
/// per node.
pub(crate) const MAX_AXES: usize = 4;

/// Largest field (product of `dims`) any synthesis may make: 2^26 nodes. It is checked before
/// anything is allocated; at the limit a field takes 512 MiB of spectrum while it is made and
/// 256 MiB of output (twice that for a pair). Every grid derived from user input (wind fields,
/// cloth noise) is bounded by it or by a smaller limit of its own.
pub(crate) const MAX_NODES: usize = 1 << 26;
