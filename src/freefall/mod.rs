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
//! The math is in plain types ([`Regime::new`], [`TrajectoryDatabase`], [`FallPath`], [`ode`]);
//! [`FallPlugin`] moves every [`FallingObject`] on the fixed timestep.

pub mod cloud;
mod database;
#[cfg(feature = "gizmos")]
mod gizmos;
mod lod;
mod look;
mod markov;
mod model;
mod motion;
mod object;
pub mod ode;
mod path;
mod piece;
mod plugin;
mod presets;
mod random;
mod regime;
mod release;
mod series;
mod tiers;
mod tilt;

pub use cloud::{CloudRegion, LeafCloud, LeafCloudInvalid, LeafCloudPlugin, LeafCloudState};
pub use database::{DatabaseConfig, TrajectoryDatabase};
#[cfg(feature = "gizmos")]
pub use gizmos::FallGizmos;
#[cfg(feature = "gizmos")]
pub(crate) use gizmos::FallGizmosPlugin;
pub use lod::FallLod;
#[cfg(feature = "render")]
pub(crate) use look::{CLOUD_POINTS, mix, outline};
pub use markov::{MarkovChain, MarkovError};
pub use model::FallModel;
pub use motion::FallScales;
pub use path::{FallPath, StepOutcome, WindTilt};

pub use object::{FallSettings, FallState, FallingObject, FallingObjectInvalid, Landed};
pub use plugin::FallPlugin;
pub use presets::FallPreset;
pub use regime::{FallError, Fluid, PrimitiveMotion, Regime, Shape};
pub use release::FallRelease;

/// Renamed to [`FallPlugin`] (one prefix per domain), kept for one release.
#[deprecated(since = "0.2.0", note = "renamed to `FallPlugin`")]
pub type FreeFallPlugin = FallPlugin;
/// Renamed to [`FallSettings`], kept for one release.
#[deprecated(since = "0.2.0", note = "renamed to `FallSettings`")]
pub type FreeFallSettings = FallSettings;
/// Renamed to [`FallError`], kept for one release.
#[deprecated(since = "0.2.0", note = "renamed to `FallError`")]
pub type FreeFallError = FallError;
