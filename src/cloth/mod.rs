//! Cloth: flags, banners and curtains whose shape comes from P-type Fourier-descriptor yarns
//! driven by 1/f^β noise angles (Tynystanova and Chiba, *Fourier Descriptor Animation of Cloth Flapping in Wind*).
//!
//! | step | what | source |
//! |---|---|---|
//! | noise | 2-D (frozen) or 3-D (evolving: the paper's non-frozen) 1/f^β matrix, band-limited along its lines, scaled to [−θ, θ] | §3.1, §4 |
//! | descriptor | per noise line: ω(j) = exp(iθ(j)), DFT, mean and band, inverse, mean along the stream | eq. 2–6 |
//! | shift | the lines move |v| cells along and |u| across the yarns per frame; evolving: one slice per frame | §4.1–4.2 |
//! | yarns | equal segments along the directions, held at the pole, scaled by the wind: length kept | eq. 2 |
//! | pole edge | arcs of the fixed edge, W1 and W2, both ends on the pole | eq. 8 |
//! | constraint | neighbouring yarns at most L apart, from the leading yarn | eq. 7 |
//! | wind strength | waves grow with the wind, a flag hangs in calm air, a curtain leans downwind | ours |
//! | levels of detail | far cloths traced on a grid 2 or 4 times coarser, cross-faded | ours: [`ClothLod`] |
//!
//! The math lives in plain types ([`ClothSim`], [`DescriptorFilter`]); [`ClothPlugin`] moves
//! every [`Cloth`] on the fixed timestep and rewrites its mesh once per rendered frame.

mod component;
mod constraints;
pub mod descriptor;
mod directions;
#[cfg(feature = "gizmos")]
mod gizmos;
mod measure;
// The cloths' mesh: the crate's plugins build and write it; the report times it. Not API.
#[doc(hidden)]
pub mod mesh;
mod noise;
mod params;
mod plugin;
mod presets;
mod sim;

pub use descriptor::{DescriptorFilter, HarmonicFilter};

#[cfg(feature = "gizmos")]
pub use gizmos::ClothGizmos;
#[cfg(feature = "gizmos")]
pub(crate) use gizmos::ClothGizmosPlugin;
pub use measure::{FlapRecorder, FlapStats};

pub use component::{Cloth, ClothInvalid, ClothLod, ClothState};
pub use params::{ClothError, ClothGrid, ClothParams, ClothWindModel, LeadingYarn};
pub use plugin::ClothPlugin;
pub use presets::{ClothKind, ClothPreset};
pub use sim::{ClothAttachment, ClothSim};
