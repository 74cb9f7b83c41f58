//! Aerodynamics: lift and drag per face on physically driven bodies
//! (`aerodynamic-lift-and-drag.txt`).
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
mod cloth;
mod coefficients;
mod force;
mod plate;
mod plugin;

#[cfg(feature = "avian")]
pub use avian::{AvianAero, AvianAeroPlugin};
pub use cloth::{CLOTH_MAX_ITERATIONS, CLOTH_MAX_SUBSTEPS, ParticleCloth, Pinning};
pub use force::{AIR_DENSITY, WATER_DENSITY, face_force};
pub use plate::{
    AeroCoefficients, AeroError, Face, LIFT_STEP, MAX_COEFFICIENT, MAX_FLUID_DENSITY,
    MAX_STATE_SPEED, MAX_SUBSTEPS, PlateState, RigidPlate,
};
pub use plugin::{
    AeroBody, AeroBodyInvalid, AeroPlugin, AeroState, PhysicalCloth, PhysicalClothInvalid,
    PhysicalClothState,
};
