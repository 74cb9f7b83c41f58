//! Free fall: leaves, paper and coins falling through still or moving air and water
//! (Xie and Miyata, *Realistic Motion Simulations of Objects in Free Fall*).
//!
//! | step | what | source |
//! |---|---|---|
//! | regime | Re = U L / ν, I*, U = √((ρ_s/ρ_f − 1) g b) | eq. 1–3 |
//! | phase diagram | (Re, I*) → main motion L1..L6 ([`PrimitiveMotion::classify`]) | §2.1, Fig. 3 |
//! | database | swings of eq. 5 cut at turning points, k-means on feature vectors, angles from eq. 4 by RK4 | §2.2 |
//! | search tree | glide left / right: fluttering, chaotic (r ∈ [1/10, 10]), tumbling | §2.3.1, Fig. 7 |
//! | unified function | steady descent, helix (eight-petal rose), spiral (radius A₀) | eq. 6 |
//! | amplitudes | A₀ = D U / (h Ω), Gaussian spread per motion | eq. 7–8, §2.3.2 |
//! | Markov chain | L_i → L_j, j ≥ i, bounded by the main motion, per object | §3, eq. 9 |
//! | wind | p ← p + v dt + Δf, v relaxing to u(p) over a response time; tilt θ = W N(t) | §4.2, eq. 15 |
//! | presets | coin, paper, leaves, card, samara with their chains | [`FallPreset`] |
//! | clouds | 100 000 leaves in one entity, levels of detail | [`LeafCloud`] ([`cloud`]) |
//! | levels of detail | far objects stepped every 2nd / 4th step, shown smoothly | [`FallLod`], [`crate::lod`] |
//!
//! | quantity | unit |
//! |---|---|
//! | sizes L, a, b | m |
//! | densities ρ_s, ρ_f | kg/m³ |
//! | ν | m²/s |
//! | U | m/s |
//! | Ω | rad/s |
//!
//! The paper's models are plain types in `model/` ([`Regime::new`], [`TrajectoryDatabase`],
//! [`MarkovChain`], [`FallPath`], [`ode`]); beside them the ECS glue: the components
//! ([`FallingObject`], [`FallState`]), [`FallPlugin`] that moves every object on the fixed
//! timestep, [`FallPreset`]s, the default looks, levels of detail ([`FallLod`]) and [`cloud`].

pub mod cloud;
mod fall_lod;
mod fall_store;
#[cfg(feature = "gizmos")]
mod gizmos;
mod look;
mod model;
mod object;
mod plugin;
mod store;

pub use cloud::{CloudRegion, LeafCloud, LeafCloudInvalid, LeafCloudPlugin, LeafCloudState};
pub use fall_lod::FallLod;
pub use fall_store::FallStore;
#[cfg(feature = "gizmos")]
pub use gizmos::FallGizmos;
#[cfg(feature = "gizmos")]
pub(crate) use gizmos::FallGizmosPlugin;
#[cfg(feature = "render")]
pub(crate) use look::{CLOUD_POINTS, mix, outline};
pub use model::FallModel;
pub use model::body::{Fluid, Shape};
pub use model::database::{DatabaseConfig, TrajectoryDatabase};
pub use model::error::FallError;
pub use model::markov::{MarkovChain, MarkovError};
pub use model::motion::FallScales;
pub use model::ode;
pub use model::regime::{PrimitiveMotion, Regime};
pub use model::release::FallRelease;
pub use model::tilt::WindTilt;

pub use object::{
    FallPreset, FallSettings, FallState, FallingObject, FallingObjectInvalid, Landed,
};
pub use plugin::FallPlugin;
pub use store::path::FallPath;
pub use store::slot::StepOutcome;
pub use store::view::FallView;
