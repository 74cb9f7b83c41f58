//! What falls and what it falls through: the object's [`Shape`] and the [`Fluid`] (the inputs of
//! eq. 1–3 of the free-fall paper).

use bevy::reflect::Reflect;

/// A fluid: density and kinematic viscosity.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Fluid {
    /// ρ_f, kg/m³.
    pub density: f32,
    /// ν, m²/s.
    pub kinematic_viscosity: f32,
}

impl Fluid {
    /// Air at about 20 °C, sea level.
    pub const AIR: Self = Self {
        density: 1.204,
        kinematic_viscosity: 1.5e-5,
    };
    /// Water at 25 °C (the viscosity that gives the paper's coin Re = 3.55e3).
    pub const WATER: Self = Self {
        density: 997.0,
        kinematic_viscosity: 0.89e-6,
    };

    /// Largest accepted ρ_s / ρ_f.
    pub const MAX_DENSITY_RATIO: f32 = 1.0e6;

    /// Smallest accepted kinematic viscosity, m²/s.
    pub const MIN_VISCOSITY: f32 = 1.0e-9;
}

/// The object's outline. Thin plates: thickness below the other sizes.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub enum Shape {
    /// A coin: L = a = diameter, b = thickness.
    Disk {
        /// m.
        diameter: f32,
        /// m.
        thickness: f32,
    },
    /// A card: L = length, a = width (the chord it tumbles over), b = thickness.
    Rectangle {
        /// m, ≥ width.
        length: f32,
        /// m.
        width: f32,
        /// m.
        thickness: f32,
    },
    /// A leaf or paper ellipse: L = major axis, a = minor axis, b = thickness.
    Ellipse {
        /// m, ≥ minor.
        major: f32,
        /// m.
        minor: f32,
        /// m.
        thickness: f32,
    },
}

impl Shape {
    /// (L, a, b) of §2.1: length, cross-section length, cross-section width (thickness).
    pub fn lengths(&self) -> (f32, f32, f32) {
        match *self {
            Self::Disk {
                diameter,
                thickness,
            } => (diameter, diameter, thickness),
            Self::Rectangle {
                length,
                width,
                thickness,
            } => (length, width, thickness),
            Self::Ellipse {
                major,
                minor,
                thickness,
            } => (major, minor, thickness),
        }
    }

    /// Largest accepted size, m: far beyond any use, small enough that every derived number stays
    /// finite in f32.
    pub const MAX_SIZE: f32 = 1.0e3;

    /// Smallest accepted size, m (0.1 µm).
    pub const MIN_SIZE: f32 = 1.0e-7;

    /// Face area, m².
    pub fn area(&self) -> f32 {
        let (l, a, _) = self.lengths();
        match self {
            Self::Rectangle { .. } => l * a,
            _ => std::f32::consts::FRAC_PI_4 * l * a,
        }
    }
}
