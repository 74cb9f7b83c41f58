//! A rigid plate with six degrees of freedom driven by per-face lift and drag: a physically
//! falling leaf, card or coin.

use bevy::math::{Quat, Vec3};
use bevy::reflect::Reflect;

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use crate::error::InvalidValue;
use crate::freefall::Shape;

mod step;

/// One face of a body, in the body's frame.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Face {
    /// Centre, m.
    pub center: Vec3,
    /// Unit normal (either side).
    pub normal: Vec3,
    /// Area, m².
    pub area: f32,
}

/// A rigid plate: faces, mass, principal moments of inertia (body axes), coefficients.
#[derive(Clone, Debug, PartialEq, Reflect)]
pub struct RigidPlate {
    faces: Vec<Face>,
    mass: f32,
    inertia: Vec3,
    coefficients: AeroCoefficients,
}

/// Position, velocity, orientation and angular velocity (world frame).
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct PlateState {
    /// Centre of mass, m.
    pub position: Vec3,
    /// m/s.
    pub velocity: Vec3,
    /// Body to world.
    pub rotation: Quat,
    /// rad/s, world frame.
    pub angular_velocity: Vec3,
}

impl Default for PlateState {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            velocity: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            angular_velocity: Vec3::ZERO,
        }
    }
}

impl PlateState {
    /// Checks that the state can be simulated: a finite position within
    /// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE), a rotation that is finite and not zero (any
    /// length: it is normalised), and finite velocities within [`PlateState::MAX_SPEED`](crate::aero::PlateState::MAX_SPEED). The field
    /// names start with `state.`.
    pub fn validate(&self) -> Result<(), AeroError> {
        if let Some(value) = crate::guard::bad_position(self.position) {
            InvalidValue::check(
                false,
                "state.position",
                value,
                crate::guard::position_reason(),
            )?;
        }
        InvalidValue::check(
            crate::guard::unit_quat(self.rotation).is_some(),
            "state.rotation",
            self.rotation.length(),
            "must be a finite, non-zero quaternion",
        )?;
        for (field, v) in [
            ("state.velocity", self.velocity),
            ("state.angular_velocity", self.angular_velocity),
        ] {
            let largest = crate::guard::largest_component(v);
            InvalidValue::check(
                largest.abs() <= PlateState::MAX_SPEED,
                field,
                largest,
                crate::error::reason!("must be finite and within ±{:e}", PlateState::MAX_SPEED),
            )?;
        }
        Ok(())
    }
}

/// Largest h × (lift rate) a substep may take.
pub(crate) const LIFT_STEP: f32 = 0.25;

impl RigidPlate {
    /// A `length` × `width` × `thickness` plate of `density` (kg/m³), lying in its local XZ plane
    /// (normal +Y, length along Z), split into `cells` × `cells` faces.
    pub fn rectangle(
        length: f32,
        width: f32,
        thickness: f32,
        density: f32,
        coefficients: AeroCoefficients,
        cells: usize,
    ) -> Result<Self, AeroError> {
        for (field, value) in [
            ("length", length),
            ("width", width),
            ("thickness", thickness),
        ] {
            InvalidValue::check(
                (Shape::MIN_SIZE..=Shape::MAX_SIZE).contains(&value) && value.is_finite(),
                field,
                value,
                crate::error::reason!(
                    "must be within {:e}..{:e} m",
                    Shape::MIN_SIZE,
                    Shape::MAX_SIZE
                ),
            )?;
        }
        InvalidValue::check(
            density > 0.0 && density <= 1e7 && density.is_finite(),
            "density",
            density,
            "must be > 0 and ≤ 1e7 kg/m³",
        )?;
        // Checked on what the solver divides by: the mass, in f64.
        let mass = f64::from(density) * f64::from(length) * f64::from(width) * f64::from(thickness);
        InvalidValue::check(
            mass >= 1e-30,
            "density",
            density,
            "the plate's mass (density × length × width × thickness) must be ≥ 1e-30 kg",
        )?;
        coefficients.validate()?;
        let cells = cells.clamp(1, 64);
        let area = length * width / (cells * cells) as f32;
        let mut faces = Vec::with_capacity(cells * cells);
        for i in 0..cells {
            for j in 0..cells {
                let x = width * ((i as f32 + 0.5) / cells as f32 - 0.5);
                let z = length * ((j as f32 + 0.5) / cells as f32 - 0.5);
                faces.push(Face {
                    center: Vec3::new(x, 0.0, z),
                    normal: Vec3::Y,
                    area,
                });
            }
        }
        let mass = density * length * width * thickness;
        // Thin box: I_x = m (t² + L²)/12, I_y = m (w² + L²)/12, I_z = m (w² + t²)/12.
        let inertia = mass / 12.0
            * Vec3::new(
                thickness * thickness + length * length,
                width * width + length * length,
                width * width + thickness * thickness,
            );
        Self::new(faces, mass, inertia, coefficients)
    }

    /// A body from its faces (body frame), mass (kg), principal moments (kg m²) and
    /// coefficients. Faces with zero area or a zero or non-finite normal exert no force; a
    /// finite normal of any length (subnormal to `f32::MAX`) is normalised.
    pub fn new(
        faces: Vec<Face>,
        mass: f32,
        inertia: Vec3,
        coefficients: AeroCoefficients,
    ) -> Result<Self, AeroError> {
        InvalidValue::check(
            mass > 0.0 && mass.is_finite(),
            "mass",
            mass,
            "must be finite and > 0",
        )?;
        for (field, value) in [
            ("inertia.x", inertia.x),
            ("inertia.y", inertia.y),
            ("inertia.z", inertia.z),
        ] {
            InvalidValue::check(
                value > 0.0 && value.is_finite(),
                field,
                value,
                "must be finite and > 0",
            )?;
        }
        coefficients.validate()?;
        // Faces that can exert no force are dropped, so no NaN can reach the solver; the rest
        // get unit normals.
        let faces = faces
            .into_iter()
            .filter(|f| f.center.is_finite() && f.area.is_finite() && f.area > 0.0)
            .filter_map(|f| {
                let normal = crate::guard::unit_vec3(f.normal)?;
                Some(Face { normal, ..f })
            })
            .collect();
        Ok(Self {
            faces,
            mass,
            inertia,
            coefficients,
        })
    }

    /// Mass, kg.
    pub fn mass(&self) -> f32 {
        self.mass
    }

    /// Total face area, m².
    pub fn area(&self) -> f32 {
        self.faces.iter().map(|f| f.area.max(0.0)).sum()
    }

    /// The faces, body frame.
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// Coefficients.
    pub fn coefficients(&self) -> &AeroCoefficients {
        &self.coefficients
    }

    /// Replaces the coefficients (live tuning); a bad value is refused by name and nothing
    /// changes.
    pub fn set_coefficients(&mut self, coefficients: AeroCoefficients) -> Result<(), AeroError> {
        coefficients.validate()?;
        self.coefficients = coefficients;
        Ok(())
    }
}

/// Limits and constants of [`PlateState`].
impl PlateState {
    /// Largest speed (m/s) or spin (rad/s) a [`PlateState`] may start from.
    pub const MAX_SPEED: f32 = 1.0e6;
}

/// Limits and constants of [`RigidPlate`].
impl RigidPlate {
    /// Largest substeps per step; past it the step's substeps grow (the drag stays implicit).
    pub const MAX_SUBSTEPS: u32 = 256;
}
