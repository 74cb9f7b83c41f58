//! From a physical object to its main primitive motion: Re (eq. 1, 3), I* (eq. 2) and the
//! (Re, I*) phase diagram of §2.1.

use bevy::reflect::Reflect;

use super::body::{Fluid, Shape};
use super::error::FallError;
use crate::error::InvalidValue;

/// The six primitive motions L1..L6 of §2.1, in the order of the paper's hypothesis (§3.1): a
/// fall only ever moves to the same or a higher-numbered motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Reflect)]
pub enum PrimitiveMotion {
    /// L1, SD: drops straight down.
    #[default]
    SteadyDescent,
    /// L2, PF: oscillates from side to side with a well-defined period.
    Fluttering,
    /// L3, TC: oscillates with growing amplitude and turns into tumbling, irregularly.
    Chaotic,
    /// L4, PT: turns end over end and drifts to one side.
    Tumbling,
    /// L5, TH: a helical path, a rose curve seen from above.
    Helix,
    /// L6, PS: falls down a circle.
    Spiral,
}

impl PrimitiveMotion {
    /// The main motion of an object with Reynolds number `reynolds` and dimensionless moment of
    /// inertia `inertia`: the region of the phase diagram (Fig. 2 of the free-fall paper,
    /// its table of regions) they fall in. NaN or negative values count as 0.
    pub fn classify(reynolds: f32, inertia: f32) -> Self {
        let re = if reynolds > 0.0 { reynolds } else { 0.0 };
        let i = if inertia > 0.0 { inertia } else { 0.0 };
        PHASE_DIAGRAM
            .iter()
            .find(|r| re >= r.re_min && re < r.re_max && i >= r.inertia_min && i < r.inertia_max)
            .map_or(PrimitiveMotion::Fluttering, |r| r.motion)
    }

    /// All six, L1 to L6.
    pub const ALL: [Self; 6] = [
        Self::SteadyDescent,
        Self::Fluttering,
        Self::Chaotic,
        Self::Tumbling,
        Self::Helix,
        Self::Spiral,
    ];

    /// 0-based index: L1 → 0, ..., L6 → 5.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The motion with this 0-based index (clamped to L6).
    pub fn from_index(index: usize) -> Self {
        Self::ALL[index.min(5)]
    }

    /// The paper's label, `"L1"`..`"L6"`.
    pub fn label(self) -> &'static str {
        ["L1", "L2", "L3", "L4", "L5", "L6"][self.index()]
    }

    /// Planar motions (fluttering, chaotic, tumbling) are built from database segments by the
    /// search tree; the others from the unified function of eq. 6.
    pub fn is_planar(self) -> bool {
        matches!(self, Self::Fluttering | Self::Chaotic | Self::Tumbling)
    }
}

/// One region of the phase diagram: `motion` where `re_min ≤ Re < re_max` and
/// `inertia_min ≤ I* < inertia_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PhaseRegion {
    /// The motion of this region.
    pub motion: PrimitiveMotion,
    /// Lowest Reynolds number (inclusive).
    pub re_min: f32,
    /// Highest Reynolds number (exclusive).
    pub re_max: f32,
    /// Lowest I* (inclusive).
    pub inertia_min: f32,
    /// Highest I* (exclusive).
    pub inertia_max: f32,
    /// Where the boundary comes from.
    pub source: &'static str,
}

/// The phase diagram (the paper's Fig. 3 is not in its text), first match wins; a point that
/// matches no region is [`PrimitiveMotion::Fluttering`], the periodic regime of Field et al.
///
/// The boundaries are rounded values of the regions the literature reports, placed so that the
/// paper's three objects of §5 (Fig. 15) fall where the paper says: coin (3.55e3, 1e-2)
/// fluttering, paper ellipse (6.8e3, 2.2e-3) spiral, leaf (1.2e4, 6.3e-3) helix.
pub(crate) const PHASE_DIAGRAM: [PhaseRegion; 5] = [
    PhaseRegion {
        motion: PrimitiveMotion::SteadyDescent,
        re_min: 0.0,
        re_max: 100.0,
        inertia_min: 0.0,
        inertia_max: f32::INFINITY,
        source: "Field et al. 1997, Willmarth et al. 1964: steady fall below Re ≈ 100 at any I*",
    },
    PhaseRegion {
        motion: PrimitiveMotion::Tumbling,
        re_min: 100.0,
        re_max: f32::INFINITY,
        inertia_min: 4.0e-2,
        inertia_max: f32::INFINITY,
        source: "Field et al. 1997: tumbling above I* ≈ 4e-2",
    },
    PhaseRegion {
        motion: PrimitiveMotion::Chaotic,
        re_min: 100.0,
        re_max: f32::INFINITY,
        inertia_min: 1.5e-2,
        inertia_max: 4.0e-2,
        source: "Field et al. 1997: chaotic band between periodic and tumbling",
    },
    PhaseRegion {
        motion: PrimitiveMotion::Spiral,
        re_min: 3.0e3,
        re_max: f32::INFINITY,
        inertia_min: 0.0,
        inertia_max: 4.0e-3,
        source: "Zhong et al. 2011: spiral for the lightest thin disks at high Re",
    },
    PhaseRegion {
        motion: PrimitiveMotion::Helix,
        re_min: 3.0e3,
        re_max: f32::INFINITY,
        inertia_min: 4.0e-3,
        inertia_max: 8.0e-3,
        source: "Zhong et al. 2011: transitional helix between zigzag and spiral",
    },
];

/// Everything §2.1 derives from the inputs. Computed in f64, stored in f32.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Regime {
    /// Re = U L / ν (eq. 1).
    pub reynolds: f32,
    /// I* (eq. 2).
    pub inertia: f32,
    /// U, the mean descent speed of eq. 3, m/s.
    pub descent_speed: f32,
    /// Mass, kg.
    pub mass: f32,
    /// The phase diagram's motion for (Re, I*).
    pub main: PrimitiveMotion,
}

fn invalid(field: &'static str, value: f32, reason: &'static str) -> FallError {
    InvalidValue::new(field, value, reason).into()
}

fn positive(field: &'static str, value: f32, max: f32) -> Result<(), FallError> {
    if value.is_finite() && value > 0.0 && value <= max {
        Ok(())
    } else {
        Err(invalid(
            field,
            value,
            "must be finite, > 0 and within the documented maximum",
        ))
    }
}

impl Regime {
    /// Re, I*, U and the main motion of `shape` with density `density` (kg/m³) in `fluid` under
    /// gravity `gravity` (m/s²).
    ///
    /// I* is eq. 2 for rotation about the long axis (the axis a falling plate turns about),
    /// normalised by ρ_f a⁵, in the thin-plate limit b ≪ a the paper uses:
    /// - disk (paper): I* = π ρ_s b / (64 ρ_f a);
    /// - rectangle (paper): I* = 8 ρ_s (a² + b²) b / (3π ρ_f a³);
    /// - ellipse (derived): ∫ρ (y² + z²) dV over an elliptic plate of axes L, a is
    ///   ρ_s π L a b · a²/64, so I* = π ρ_s b L / (64 ρ_f a²), which is the disk's at L = a.
    ///
    /// U = √((ρ_s/ρ_f − 1) g b) (eq. 3) and Re = U L / ν (eq. 1).
    ///
    /// # Errors
    /// A size, density, viscosity or gravity out of range, named; a plate no denser than the
    /// fluid.
    pub fn new(
        shape: &Shape,
        density: f32,
        fluid: &Fluid,
        gravity: f32,
    ) -> Result<Self, FallError> {
        let (l, a, b) = shape.lengths();
        let (names, what) = match shape {
            Shape::Disk { .. } => (
                ["shape.diameter", "shape.diameter", "shape.thickness"],
                "disk",
            ),
            Shape::Rectangle { .. } => (["shape.length", "shape.width", "shape.thickness"], "rect"),
            Shape::Ellipse { .. } => (["shape.major", "shape.minor", "shape.thickness"], "ellipse"),
        };
        for (name, value) in names.iter().zip([l, a, b]) {
            positive(name, value, Shape::MAX_SIZE)?;
            if value < Shape::MIN_SIZE {
                return Err(invalid(
                    name,
                    value,
                    crate::error::reason!("must be ≥ {:e} m", Shape::MIN_SIZE),
                ));
            }
        }
        if b > a {
            return Err(invalid(
                names[2],
                b,
                "a thin plate: thickness ≤ the other sizes",
            ));
        }
        if a > l {
            return Err(invalid(
                names[1],
                a,
                "the cross-section may not exceed the length",
            ));
        }
        positive("fluid.density", fluid.density, 1.0e5)?;
        positive(
            "fluid.kinematic_viscosity",
            fluid.kinematic_viscosity,
            1.0e3,
        )?;
        // Superfluid helium, the thinnest known fluid, is about 1e-8 m²/s; much less and Re
        // overflows f32 and the phase diagram has nothing to say.
        if fluid.kinematic_viscosity < Fluid::MIN_VISCOSITY {
            return Err(invalid(
                "fluid.kinematic_viscosity",
                fluid.kinematic_viscosity,
                crate::error::reason!("must be ≥ {:e} m²/s", Fluid::MIN_VISCOSITY),
            ));
        }
        positive("gravity", gravity, 1.0e4)?;
        positive("density", density, 1.0e7)?;
        let ratio = f64::from(density) / f64::from(fluid.density);
        if ratio <= 1.0 {
            return Err(FallError::LighterThanFluid {
                density,
                fluid_density: fluid.density,
            });
        }
        if ratio > f64::from(Fluid::MAX_DENSITY_RATIO) {
            return Err(invalid(
                "density",
                density,
                crate::error::reason!("ρ_s/ρ_f must be ≤ {:e}", Fluid::MAX_DENSITY_RATIO),
            ));
        }
        let (l, a, b) = (f64::from(l), f64::from(a), f64::from(b));
        let pi = std::f64::consts::PI;
        let inertia = match what {
            "disk" => pi * ratio * b / (64.0 * a),
            "rect" => 8.0 * ratio * (a * a + b * b) * b / (3.0 * pi * a.powi(3)),
            _ => pi * ratio * b * l / (64.0 * a * a),
        };
        let descent_speed = ((ratio - 1.0) * f64::from(gravity) * b).sqrt();
        let reynolds = descent_speed * l / f64::from(fluid.kinematic_viscosity);
        let mass = f64::from(density) * f64::from(shape.area()) * b;
        let (reynolds, inertia) = (reynolds as f32, inertia as f32);
        Ok(Regime {
            reynolds,
            inertia,
            descent_speed: descent_speed as f32,
            mass: mass as f32,
            main: PrimitiveMotion::classify(reynolds, inertia),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_region_is_reachable_and_first_match_wins() {
        for region in PHASE_DIAGRAM {
            let re = if region.re_max.is_finite() {
                (region.re_min + region.re_max) / 2.0
            } else {
                region.re_min * 2.0 + 1.0
            };
            let i = if region.inertia_max.is_finite() {
                (region.inertia_min + region.inertia_max) / 2.0
            } else {
                region.inertia_min * 2.0
            };
            assert_eq!(
                PrimitiveMotion::classify(re, i),
                region.motion,
                "{region:?}"
            );
        }
        assert_eq!(
            PrimitiveMotion::classify(500.0, 1e-3),
            PrimitiveMotion::Fluttering
        );
    }
}
