//! [`WindError`]: a bad wind setting, naming its field.

use bevy::reflect::Reflect;
use thiserror::Error;

use crate::error::InvalidValue;

/// A [`WindConfig`](super::config::WindConfig) field that is out of range. [`WindError::field`] names it.
#[derive(Clone, Debug, Error, PartialEq, Reflect)]
pub enum WindError {
    /// A number outside its valid range.
    #[error(transparent)]
    Invalid(#[from] InvalidValue),
    /// A grid axis with fewer than two nodes.
    #[error("`{field}` = {len}: a grid axis needs at least 2 nodes")]
    GridAxis {
        /// The field's name.
        field: &'static str,
        /// The rejected node count.
        len: usize,
    },
    /// More nodes than [`WindConfig::MAX_NODES`](crate::wind::WindConfig::MAX_NODES).
    #[error(
        "`{field}`: {nodes} nodes in all, more than the limit of {max} (`WindConfig::MAX_NODES`)", max = crate::spectrum::Synthesizer::MAX_NODES
    )]
    TooManyNodes {
        /// The field's name.
        field: &'static str,
        /// The node count asked for.
        nodes: usize,
    },
}

impl WindError {
    /// Name of the offending [`WindConfig`](super::config::WindConfig) field (`"roughness"`, `"grid.x"`, ...).
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) | Self::GridAxis { field, .. } => field,
            Self::TooManyNodes { field, .. } => field,
        }
    }
}
