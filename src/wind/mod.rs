//! Wind: a [`WindField`] resource that every other part of the crate samples.
//!
//! The model follows §4.1–4.2 of *Realistic Motion Simulations of Objects in Free Fall* (Xie and Miyata):
//!
//! | quantity | symbol | unit | source |
//! |---|---|---|---|
//! | mean speed at height h | U(h) = (u*/κ) ln(h/z0) | m/s | eq. 10 |
//! | friction velocity | u* | m/s | eq. 10, from U at the reference height |
//! | roughness length | z0 | m | eq. 10 |
//! | turbulence spectrum | S ∝ 1/f^β along a line, β = 5/3 | – | eq. 11, 13 |
//! | amplitudes | σ_u = I·U(h_ref), σ_v = 0.88 σ_u, σ_w = 0.55 σ_u | m/s | eq. 12 ([`WindField::sigma`]) |
//! | plane-to-height scaling | ln(h/z0) / ln(h0/z0) | – | eq. 14 |
//!
//! [`WindPlugin`] inserts the field and advances its clock on the fixed timestep.

mod config;
mod ease;
mod error;
mod field;
#[cfg(feature = "gizmos")]
mod gizmos;
mod local;
mod mover;
mod placement;
mod plugin;

mod pulse;
mod rebuild;
mod settings;
mod shelter;
mod snapshot;
mod source;

pub use config::{SpatialMode, TemporalMode, WindConfig};
pub use ease::WindEasing;
pub use error::WindError;
pub(crate) use field::Moment;
pub use field::WindField;
#[cfg(feature = "gizmos")]
pub use gizmos::WindGizmos;
#[cfg(feature = "gizmos")]
pub(crate) use gizmos::WindGizmosPlugin;
pub(crate) use mover::MoverFlow;
pub use mover::{WindMover, WindMoverInvalid};
pub use plugin::WindPlugin;
pub use pulse::Pulse;
pub use rebuild::{WindRebuild, WindRebuilt};
pub use settings::WindSettings;
pub use shelter::{ShelterKind, WindShelter, WindShelterInvalid};
pub use snapshot::WindSnapshot;
pub use source::{SourceShape, WindSource, WindSourceInvalid};
