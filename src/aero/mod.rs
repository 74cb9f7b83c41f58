//! Aerodynamics: lift and drag per face on physically driven bodies
//! (the lift-and-drag paper's *Aerodynamics* section).
//!
//! | quantity | unit |
//! |---|---|
//! | velocities v_face, u, v_rel | m/s |
//! | area A | m² |
//! | density ρ | kg/m³ |
//! | C_D, C_L | 1 |
//! | force | N |
//!
//! [`face_force`] is the per-face law (eq. 3.1 and the drag and lift formulas); [`RigidPlate`]
//! sums it over a plate's faces into a force and a torque and integrates six degrees of freedom
//! with implicit drag; [`AeroPlugin`] moves every [`AeroBody`] on the fixed timestep.

#[cfg(feature = "avian")]
mod avian;
mod body;
mod coefficients;
mod error;
mod force;
mod particles;
mod physical_cloth;
mod plate;
mod plugin;

#[cfg(feature = "avian")]
pub use avian::{AvianAero, AvianAeroPlugin};
pub use body::{AeroBody, AeroBodyInvalid, AeroState};
pub use coefficients::AeroCoefficients;
pub use error::AeroError;
pub use force::face_force;
pub use particles::{ParticleCloth, Pinning, YarnSolves};
pub use physical_cloth::{PhysicalCloth, PhysicalClothInvalid, PhysicalClothState};
pub use plate::{Face, PlateState, RigidPlate};
pub use plugin::AeroPlugin;
