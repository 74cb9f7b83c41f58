//! A particle cloth (XPBD distance constraints, pinned nodes, gravity) whose triangles receive
//! lift and drag: a physically simulated flag.

use crate::error::InvalidValue;

mod loads;
mod screen;
mod substep;
use bevy::math::Vec3;

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use crate::cloth::{ClothError, ClothGrid};

/// Which nodes hold still.
#[derive(Clone, Copy, Debug, PartialEq, Eq, bevy::reflect::Reflect)]
pub enum Pinning {
    /// The first column (a flag on a pole).
    PoleColumn,
    /// The top row (a curtain on a rod).
    TopRow,
}

/// The air a cloth carries with it when it moves across itself, as a fraction of a flat
/// plate's added mass ρ π c / 4 per area (c the smaller side). The whole figure (about what
/// potential flow gives a wave of the flag's length, 2ρ/|k| per area) overdoes it here, since
/// the face law's lift already carries part of the air's reaction: a flag's drag comes out
/// 2.5–3.8 times the free-flag drag of AS/NZS 1170.2 Appendix F and its tip swings 0.9–1.3 L.
/// An eighth is fitted to the measurements: drag 0.72–1.07 of the code's at 4–12 m/s, waves
/// 1.7–1.8 flag lengths long where gravity is small (1.87 measured by Raynaud & Mulleners 2026).
const ADDED_MASS_SHARE: f32 = 0.125;

/// Relative stretch of a stretch edge (seen at the start of a sweep) above which the solver
/// sweeps again past [`ParticleCloth::iterations`].
const STRETCH_TOLERANCE: f32 = 0.05;
/// Node masses a particle cloth accepts, kg: lighter nodes (a gram's hundredth) are driven by
/// their drag and the constraints' rates past what an f32 substep resolves (1e-6 kg went NaN in
/// still air within 5 steps), heavier ones lose every force to rounding.
const MIN_NODE_MASS: f64 = 1e-5;
const MAX_NODE_MASS: f64 = 1e9;

/// A `rows × columns` grid of particles laid out like [`ClothSim`](crate::cloth::ClothSim)'s
/// (x along the yarns from the pole, y up, top row at y = 0), in the body's local frame.
///
/// Each substep: per triangle, the face law with the triangle's mean velocity and wind, its lift
/// and drag shared by its three nodes; per node, the velocity update with the drag implicit
/// (stable at any step, no overshoot of the wind); then XPBD projection of stretch, shear and
/// bend constraints, and velocities from the moved positions.
///
/// Four readings make a thin sheet flap as flags do (waves about 1.8 flag lengths long running
/// to the free edge at 0.74–0.99 of the wind's speed, the tip swinging 0.36–0.67 of the length,
/// f A / U 0.15–0.28, the drag of the wind code's free flag; see the report's "against
/// measurements"), where the face law alone gives a stiff, buzzing sheet:
/// - **Pressure acts along the normal.** The face law's drag, ½ C_D ρ A |n·v_rel| |v_rel|,
///   pushes each node along its normal only (the mean of its faces' normals):
///   (m + m_a + h K) v_n' = (m + m_a) v_n + h F_n + h K u_n, F_n the other forces' normal share
///   and m_a the added mass below. Along −v_rel, as for a rigid plate, its share along
///   the sheet would be a pressure pulling the cloth taut from its free edge, which damps every
///   wave.
/// - **Along the sheet, skin friction**, ½ ρ C_f |v_t| v_t on each side, C_f = 0.005
///   (Prandtl's turbulent flat plate at Re ≈ 10⁶), also implicit.
/// - **Lift is smoothed** over half the cloth's smaller side (a screened filter,
///   (1 − ℓ²∇²) L̃ = L, along rows and columns): the face law reacts to each face's own
///   incidence, while in potential flow the pressure on a wave falls as 1/|k| (Argentina &
///   Mahadevan 2005) and round a finite sheet's edges it falls further, so waves shorter than
///   the sheet are driven less.
/// - **The air moves with the sheet.** Across itself a node accelerates its added mass of air
///   too (an eighth of a plate's ρ π c / 4 per area): m + m_a in the normal update
///   above. The constraints still move nodes with their own mass, and
///   [`ParticleCloth::aerodynamic_force`] leaves out the added mass's reaction (zero on
///   average).
///
/// At least [`ParticleCloth::min_substeps`] substeps per step, more (up to
/// [`ParticleCloth::MAX_SUBSTEPS`]) to keep h × lift rate ≤ 1/4; past that cap the lift is limited to
/// turning a node's relative velocity by 1/4 rad per substep.
#[derive(Clone, Debug)]
pub struct ParticleCloth {
    grid: ClothGrid,
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    inverse_mass: Vec<f32>,
    /// (node a, node b, rest length, compliance).
    constraints: Vec<(u32, u32, f32, f32)>,
    /// Long-range attachments (node, its pin, rest distance): a node may not be further from
    /// the pin of its row (pole) or column (rod) than at rest, which keeps a cloth in a gale
    /// from stretching however few iterations the constraints get.
    tethers: Vec<(u32, u32, f32)>,
    node_mass: f32,
    /// The air moved with a node across the sheet, kg ([`ADDED_MASS_SHARE`]).
    added_mass: f32,
    coefficients: AeroCoefficients,
    /// Fewest constraint iterations per substep, used within
    /// 1..=[`ParticleCloth::MAX_ITERATIONS`](crate::aero::ParticleCloth::MAX_ITERATIONS); more
    /// are swept while a stretch edge is more than 5 % off its length (gales).
    pub iterations: usize,
    /// Fewest substeps per step (XPBD converges by substeps more than by iterations), used
    /// within 1..=[`ParticleCloth::MAX_SUBSTEPS`].
    pub min_substeps: u32,
    lift: Vec<Vec3>,
    drag: Vec<f32>,
    /// Each node's normal (the mean of its faces') and skin-friction rate (kg/s).
    normals: Vec<Vec3>,
    friction: Vec<f32>,
    scratch: Vec<f32>,
    /// The air's force on the cloth over the last step (mean), N.
    force: Vec3,
    /// Time of steps shorter than [`ParticleCloth::MIN_STEP`] not simulated yet, s.
    owed: f32,
    lambdas: Vec<f32>,
    wind: Vec<Vec3>,
    previous: Vec<Vec3>,
}

impl ParticleCloth {
    /// A cloth of `areal_density` kg/m² hanging flat from its pins in the local XY plane.
    pub fn new(
        grid: ClothGrid,
        areal_density: f32,
        coefficients: AeroCoefficients,
        pinning: Pinning,
    ) -> Result<Self, AeroError> {
        let invalid = |field, value, reason| {
            AeroError::Invalid(InvalidValue {
                field,
                value,
                reason,
            })
        };
        // The grid's own error, field and all.
        grid.validate().map_err(|e| match e {
            ClothError::Invalid(InvalidValue {
                field,
                value,
                reason,
            }) => invalid(field, value, reason),
            ClothError::Count {
                field,
                value,
                reason,
            } => invalid(field, value as f32, reason),
        })?;
        if grid.rows < 2 {
            return Err(invalid("grid.rows", grid.rows as f32, "must be ≥ 2"));
        }
        if grid.height <= 0.0 {
            return Err(invalid("grid.height", grid.height, "must be > 0"));
        }
        if !(areal_density.is_finite() && areal_density > 0.0) {
            return Err(invalid(
                "areal_density",
                areal_density,
                "must be finite and > 0",
            ));
        }
        coefficients.validate()?;
        let (rows, columns) = (grid.rows, grid.columns);
        let (dx, dy) = (grid.segment(), grid.row_spacing());
        // A millimetre ripple out of the plane, so that the sheet can fold rather than hang in its
        // own plane like a board (a real flag is never exactly flat).
        let positions: Vec<Vec3> = (0..rows)
            .flat_map(|k| {
                (0..columns).map(move |j| {
                    let ripple = 1e-3 * ((j as f32 * 0.9).sin() + (k as f32 * 1.3).cos());
                    Vec3::new(j as f32 * dx, -(k as f32) * dy, ripple)
                })
            })
            .collect();
        // Checked on what the solver divides by: the node mass, in f64 so no product overflows.
        let node_mass = f64::from(areal_density) * f64::from(grid.width) * f64::from(grid.height)
            / (rows * columns) as f64;
        if !(MIN_NODE_MASS..=MAX_NODE_MASS).contains(&node_mass) {
            return Err(invalid(
                "areal_density",
                areal_density,
                "each node's mass (areal_density × width × height / nodes) must be within 1e-5..1e9 kg",
            ));
        }
        let node_mass = node_mass as f32;
        let added_mass = ADDED_MASS_SHARE
            * coefficients.density
            * std::f32::consts::FRAC_PI_4
            * grid.width.min(grid.height)
            * (grid.width * grid.height / (rows * columns) as f32);
        let inverse_mass = (0..rows * columns)
            .map(|i| {
                let (k, j) = (i / columns, i % columns);
                let pinned = match pinning {
                    Pinning::PoleColumn => j == 0,
                    Pinning::TopRow => k == 0,
                };
                if pinned { 0.0 } else { 1.0 / node_mass }
            })
            .collect();
        let mut constraints = Vec::new();
        let index = |k: usize, j: usize| (k * columns + j) as u32;
        let mut link = |a: u32, b: u32, compliance: f32| {
            let rest = positions[a as usize].distance(positions[b as usize]);
            constraints.push((a, b, rest, compliance));
        };
        for k in 0..rows {
            for j in 0..columns {
                if j + 1 < columns {
                    link(index(k, j), index(k, j + 1), 0.0);
                }
                if k + 1 < rows {
                    link(index(k, j), index(k + 1, j), 0.0);
                }
                if k + 1 < rows && j + 1 < columns {
                    link(index(k, j), index(k + 1, j + 1), 1e-4);
                    link(index(k + 1, j), index(k, j + 1), 1e-4);
                }
                if j + 2 < columns {
                    link(index(k, j), index(k, j + 2), 1e-2);
                }
                if k + 2 < rows {
                    link(index(k, j), index(k + 2, j), 1e-2);
                }
            }
        }
        let tethers = (0..rows * columns)
            .filter_map(|i| {
                let (k, j) = (i / columns, i % columns);
                let pin = match pinning {
                    Pinning::PoleColumn if j > 0 => index(k, 0),
                    Pinning::TopRow if k > 0 => index(0, j),
                    _ => return None,
                };
                let rest = positions[i].distance(positions[pin as usize]);
                Some((i as u32, pin, rest))
            })
            .collect();
        let n = rows * columns;
        Ok(Self {
            tethers,
            grid,
            velocities: vec![Vec3::ZERO; n],
            previous: positions.clone(),
            owed: 0.0,
            positions,
            inverse_mass,
            constraints,
            node_mass,
            added_mass: if added_mass.is_finite() {
                added_mass
            } else {
                0.0
            },
            coefficients,
            iterations: 4,
            min_substeps: 8,
            lift: vec![Vec3::ZERO; n],
            drag: vec![0.0; n],
            normals: vec![Vec3::ZERO; n],
            friction: vec![0.0; n],
            scratch: Vec::new(),
            force: Vec3::ZERO,
            lambdas: Vec::new(),
            wind: vec![Vec3::ZERO; n],
        })
    }

    /// Node positions, row-major (local frame).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Node velocities.
    pub fn velocities(&self) -> &[Vec3] {
        &self.velocities
    }

    /// The grid.
    pub fn grid(&self) -> &ClothGrid {
        &self.grid
    }

    /// Mass of one node, kg.
    pub fn node_mass(&self) -> f32 {
        self.node_mass
    }

    /// Largest |length / rest − 1| over the stretch (row and column) constraints.
    pub fn max_strain(&self) -> f32 {
        self.constraints
            .iter()
            .filter(|c| c.3 == 0.0)
            .map(|&(a, b, rest, _)| {
                (self.positions[a as usize].distance(self.positions[b as usize]) / rest - 1.0).abs()
            })
            .fold(0.0, f32::max)
    }

    /// The mean force of the air on the whole cloth over the last [`Self::step`], N (local
    /// frame): lift, pressure drag and skin friction, as they were applied. Its component along
    /// the wind is the cloth's drag.
    pub fn aerodynamic_force(&self) -> Vec3 {
        self.force
    }

    /// Kinetic plus potential energy of the free nodes, J.
    pub fn energy(&self, gravity: Vec3) -> f32 {
        self.positions
            .iter()
            .zip(&self.velocities)
            .zip(&self.inverse_mass)
            .filter(|(_, w)| **w > 0.0)
            .map(|((p, v), _)| self.node_mass * (0.5 * v.length_squared() - gravity.dot(*p)))
            .sum()
    }

    /// Advances by `dt` under `gravity` in the fluid velocity `wind(p)` (local frame). A
    /// non-finite or non-positive `dt` or a non-finite `gravity` leaves the cloth as it is
    /// (the plugin reports such a cloth with [`PhysicalClothInvalid`](super::physical_cloth::PhysicalClothInvalid)).
    /// Steps shorter than [`ParticleCloth::MIN_STEP`] are added to the next one.
    pub fn step(&mut self, dt: f32, gravity: Vec3, wind: &impl Fn(Vec3) -> Vec3) {
        if !(dt.is_finite() && dt > 0.0 && gravity.is_finite()) {
            return;
        }
        // Velocities come from (x − x₀) / h: a sliver of a step would turn the constraints'
        // small residual into a huge velocity (1e-9 s sent a settled flag's node to 2e6 m/s).
        // Slivers are owed and simulated with the next step that makes them long enough.
        let dt = dt + self.owed;
        if dt < ParticleCloth::MIN_STEP {
            self.owed = dt;
            return;
        }
        self.owed = 0.0;
        let mut remaining = dt;
        self.force = Vec3::ZERO;
        // A long frame (a hitch) in substeps no longer than MAX_SUBSTEP: one of a tenth of a
        // second turned a still cloth's constraint corrections into a fifth of its energy.
        let longest = (dt / self.min_substeps.clamp(1, ParticleCloth::MAX_SUBSTEPS) as f32)
            .min(ParticleCloth::MAX_SUBSTEP);
        for i in 0..ParticleCloth::MAX_SUBSTEPS {
            for (u, p) in self.wind.iter_mut().zip(&self.positions) {
                let w = wind(*p);
                *u = if w.is_finite() { w } else { Vec3::ZERO };
            }
            let rate = self.loads();
            let mut h = if i + 1 == ParticleCloth::MAX_SUBSTEPS {
                remaining
            } else {
                remaining.min(longest).min(0.25 / rate.max(1e-12))
            };
            // Velocities come from (x − x₀) / h: never leave a sliver of a substep for later.
            if remaining - h < 0.01 * h {
                h = remaining;
            }
            self.substep(h, gravity);
            remaining -= h;
            if remaining <= 0.0 {
                break;
            }
        }
        self.force /= dt;
        if !self.force.is_finite() {
            self.force = Vec3::ZERO;
        }
    }
}

/// Limits and constants of [`ParticleCloth`].
impl ParticleCloth {
    /// Most constraint iterations per substep: [`ParticleCloth::iterations`] is clamped to it.
    pub const MAX_ITERATIONS: usize = 64;

    /// Most substeps per step.
    pub const MAX_SUBSTEPS: u32 = 64;

    /// Shortest step simulated, s: a shorter one is added to the next ([`ParticleCloth::step`]).
    pub const MIN_STEP: f32 = 1e-3;

    /// Longest substep, s (while the substeps last: a step of more than
    /// `MAX_SUBSTEPS × MAX_SUBSTEP` = 0.32 s has longer ones). The default 8 substeps of a
    /// frame up to 1/25 s are shorter.
    pub const MAX_SUBSTEP: f32 = 5e-3;
}
