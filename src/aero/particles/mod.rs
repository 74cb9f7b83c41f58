//! A particle cloth (pinned nodes, gravity, inextensible yarns, shear and bending in physical
//! units) pushed by the air's pressure along its normal: a physically simulated flag.

use crate::error::InvalidValue;
use crate::portable::transcendental::sin_cos;

mod constraints;
mod loads;
mod pressure;
mod reactive;
mod screen;
mod substep;
mod yarns;
use bevy::math::Vec3;

pub use yarns::YarnSolves;

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use crate::cloth::ClothGrid;

/// Which nodes hold still.
#[derive(Clone, Copy, Debug, PartialEq, Eq, bevy::reflect::Reflect)]
pub enum Pinning {
    /// The first column (a flag on a pole).
    PoleColumn,
    /// The top row (a curtain on a rod).
    TopRow,
}

/// The air a node carries when it moves across the sheet, as a fraction of a flat plate's
/// added mass ρ π c / 4 per area (c the cloth's smaller side): fitted with the pressure's
/// smoothing length to the flapping flag's drag and waves (docs/aero.md).
const ADDED_MASS_SHARE: f32 = 0.3;

/// In-plane shear stiffness G t, N/m per radian: a loosely woven fabric's at small shear
/// (Kawabata's G, about 1–50 N/m); low enough that a flag hangs from its pole by shearing.
const SHEAR_STIFFNESS: f32 = 1.5;

/// Bending stiffness B, N·m: a flag cloth's (Kawabata: 0.05–0.2 gf·cm²/cm, 5e-6–2e-5 N·m).
const BENDING_STIFFNESS: f32 = 2e-5;

/// Relative stretch of a yarn edge above which a substep's yarns are linearised again, and
/// past which the next tick is cut into twice the substeps.
const STRETCH_TOLERANCE: f32 = 0.02;

/// The most a yarn edge may be stretched, relative: a substep that leaves one stretched further
/// (or anything not finite), which only loads far beyond any weather do (winds of 1e3–1e30 m/s,
/// gravity of 1e6 m/s² and more on the lightest nodes), is undone: the nodes stay where the
/// substep found them and stop. A clamp, counted by [`ParticleCloth::undone_substeps`].
const STRETCH_LIMIT: f32 = 0.5;

/// Relative stretch of a yarn edge past which a tick is simulated again in twice the substeps
/// (up to [`ParticleCloth::MAX_SUBSTEPS`]): the substeps are otherwise cut finer only from the
/// next tick, and a whipping edge in a storm on a fine grid could be left stretched by 5–7 %.
const RETRY_STRAIN: f32 = 2.0 * STRETCH_TOLERANCE;

/// The state a tick starts from, kept while it may be simulated again ([`RETRY_STRAIN`]).
#[derive(Clone, Debug, Default)]
struct TickStart {
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    normals: Vec<Vec3>,
    force: Vec3,
    undone: u64,
}

/// Node masses a particle cloth accepts, kg: lighter nodes are driven by their drag past what
/// an f32 substep resolves, heavier ones lose every force to rounding.
const MIN_NODE_MASS: f64 = 1e-5;
const MAX_NODE_MASS: f64 = 1e9;

/// A `rows × columns` grid of particles laid out like [`ClothSim`](crate::cloth::ClothSim)'s
/// (x along the yarns from the pole, y up, top row at y = 0), in the body's local frame.
///
/// Each node has the mass m of its share of the cloth and, across the sheet, carries air: its
/// inertia is M = m I + m_a n nᵀ (n its unit normal, from its neighbours; m_a a fraction of a
/// flat plate's added mass for the node's area). Time advances in ticks of 4 ms
/// ([`ParticleCloth::tick`], Macklin et al., "Small steps in physics simulation", 2019: ticks
/// of 1, 2 and 4 ms give the same frequency, swing and drag within 5 % over 180 s, so the
/// default is the longest, at about half the cost of 2 ms),
/// each tick one substep (or 2, 4 … [`ParticleCloth::MAX_SUBSTEPS`] while the yarns could not be
/// held within 2 % of their lengths; a tick that leaves an edge more than 4 % long is simulated
/// again in twice the substeps), each substep:
/// 1. **Pressure along the normal, implicit.** p = ½ ρ |v_rel|² C_N(α) sgn(v_rel · n),
///    v_rel = v − u, α the incidence, C_N = C_D sin²α + C_L sin α cos²α (the face law's share
///    along the normal), written p = (l + k) w with w = v_rel · n and the rates
///    l = ½ ρ |v_rel| C_L cos²α (smoothed over the sheet) and k = ½ ρ |v_rel| C_D sin α (local),
///    frozen over the substep: with L = A l and K = A k (A the node's area) the node's force is
///    A p = √L S(√L w') + K w', w' the velocity at the substep's midpoint (Crank–Nicolson) and
///    S a screened filter over a quarter of the smaller side (in potential flow the pressure on
///    a wave of wavenumber k falls as 1/|k|; past the sides across the yarns from the pins it
///    falls to zero); the wind's share u · n is read along the normal halfway through the
///    substep's turn. Both shares only take energy out of the motion relative to the air.
/// 2. **Skin friction** ½ ρ C_f |v_t − u_t| (v_t − u_t) on each side, along the sheet, implicit.
/// 3. **Velocities**: M (v' − v) = h (m g − A p n − c (v'_t − u_t)).
/// 4. **Constraints** on x + h v', each projected with the same inverse inertia W = M⁻¹:
///    bending (x_a − 2 x_b + x_c = 0 along rows and columns, compliance s³ / (B w)) and shear
///    (both diagonals of every cell, compliance from G t) by XPBD; the yarns (every row and
///    column edge) inextensible, solved together by conjugate gradients preconditioned with each
///    grid line's tridiagonal block; a long-range attachment per node to the pin of its yarn,
///    which it may never be further from than at rest.
/// 5. v = (x − x₀) / h; each node's normal is then brought up to date, its velocity along the
///    new normal set so that ½ m |v|² + ½ m_a (v · n)² is what it was.
///
/// [`ParticleCloth::energy`] counts the carried air's kinetic energy ½ m_a (v · n)².
#[derive(Clone, Debug)]
pub struct ParticleCloth {
    grid: ClothGrid,
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    /// 1 / m, 0 for a pinned node.
    inverse_mass: Vec<f32>,
    node_mass: f32,
    /// Each node's share of the sheet, m² (a quarter of each cell it is a corner of), the air
    /// it carries across the sheet, kg, and β = m_a / (m + m_a).
    areas: Vec<f32>,
    added_mass: Vec<f32>,
    beta: Vec<f32>,
    yarns: yarns::Yarns,
    /// Shear: (node a, node b, rest length, compliance), both diagonals of every cell.
    shear: Vec<(u32, u32, f32, f32)>,
    /// Runs of shear constraints and of bending constraints that share no node
    /// ([`constraints::disjoint_runs`]).
    shear_runs: Vec<(u32, u32)>,
    bend_runs: Vec<(u32, u32)>,
    /// Bending: three consecutive nodes (a, b, c) along a row or a column and the compliance of
    /// x_a − 2 x_b + x_c = 0, m/N.
    bends: Vec<(u32, u32, u32, f32)>,
    /// Long-range attachments (node, its pin, rest distance).
    tethers: Vec<(u32, u32, f32)>,
    pinning: Pinning,
    coefficients: AeroCoefficients,
    /// Constraint sweeps per substep, used within 1..=[`ParticleCloth::MAX_ITERATIONS`].
    pub iterations: usize,
    /// Fewest substeps per tick, used within 1..=[`ParticleCloth::MAX_SUBSTEPS`].
    pub min_substeps: u32,
    /// How long one tick of the simulation is, s: each is one substep or more (while the yarns
    /// could not be held). [`ParticleCloth::SUBSTEP`] (4 ms) by default, used within
    /// [`ParticleCloth::SHORTEST_TICK`]..=[`ParticleCloth::LONGEST_TICK`]; a frame is simulated
    /// in whole ticks.
    pub tick: f32,
    /// Each node's unit normal (zero where the sheet is degenerate): the one its inertia and
    /// velocity are expressed with.
    normals: Vec<Vec3>,
    fresh_normals: Vec<Vec3>,
    /// The nodes' normals where their velocities would take them over the substep, x + h v.
    ahead_normals: Vec<Vec3>,
    /// Per node: the pressure's smoothed and local force rates and the skin-friction rate
    /// (kg/s), the normal velocity relative to the air before the pressure (m/s), the reach
    /// h / (m + m_a), the reach the pressure's solve reads (the midpoint's θ h / (m + m_a))
    /// and the pressure's force of the substep (N).
    lift_rate: Vec<f32>,
    drag_rate: Vec<f32>,
    friction: Vec<f32>,
    relative: Vec<f32>,
    reach: Vec<f32>,
    midpoint_reach: Vec<f32>,
    pressure: Vec<f32>,
    pressure_scratch: pressure::PressureScratch,
    wind: Vec<Vec3>,
    /// The last batch of wind read (see [`ParticleCloth::step_batched`]).
    wind_read: Vec<Vec3>,
    /// Milliseconds since the wind was last sampled.
    wind_age: u32,
    shear_lambdas: Vec<f32>,
    bend_lambdas: Vec<Vec3>,
    /// The air's force on the cloth over the last step (mean), N.
    force: Vec3,
    /// Time not simulated yet (less than a tick), s.
    owed: f32,
    tick_start: TickStart,
    /// Substeps undone since the cloth was made (see [`STRETCH_LIMIT`]).
    undone: u64,
    /// Substeps the next tick is cut into.
    parts: u32,
    previous: Vec<Vec3>,
    /// The air as Lighthill's reactive force along the chordwise yarns instead of the pressure
    /// (opt-in, [`ParticleCloth::with_reactive_air`]).
    reactive: Option<reactive::ReactiveAir>,
}

impl ParticleCloth {
    /// A cloth of `areal_density` kg/m² hanging flat from its pins in the local XY plane.
    pub fn new(
        grid: ClothGrid,
        areal_density: f32,
        coefficients: AeroCoefficients,
        pinning: Pinning,
    ) -> Result<Self, AeroError> {
        // The grid's own error, field and all.
        grid.validate()?;
        InvalidValue::check(grid.rows >= 2, "grid.rows", grid.rows as f32, "must be ≥ 2")?;
        InvalidValue::check(grid.height > 0.0, "grid.height", grid.height, "must be > 0")?;
        InvalidValue::check(
            areal_density.is_finite() && areal_density > 0.0,
            "areal_density",
            areal_density,
            "must be finite and > 0",
        )?;
        coefficients.validate()?;
        let (rows, columns) = (grid.rows, grid.columns);
        let n = rows * columns;
        // Checked on what the solver divides by: the node mass, in f64 so no product overflows.
        let node_mass =
            f64::from(areal_density) * f64::from(grid.width) * f64::from(grid.height) / n as f64;
        InvalidValue::check(
            (MIN_NODE_MASS..=MAX_NODE_MASS).contains(&node_mass),
            "areal_density",
            areal_density,
            crate::error::reason!(
                "each node's mass (areal_density × width × height / nodes) must be within {MIN_NODE_MASS:e}..{MAX_NODE_MASS:e} kg"
            ),
        )?;
        let node_mass = node_mass as f32;
        let (dx, dy) = (grid.segment(), grid.row_spacing());
        // A ripple out of the plane of a thousandth of the smaller side, so that the sheet can
        // fold rather than hang in its own plane like a board (a real flag is never exactly
        // flat): waves of a fixed share of the sheet (W / 1.9 along the yarns, H / 1.1 across),
        // so every grid starts from the same shape; portable sines, the same bits everywhere.
        let size = grid.width.min(grid.height);
        let positions: Vec<Vec3> = (0..rows)
            .flat_map(|k| {
                (0..columns).map(move |j| {
                    let (x, y) = (j as f32 * dx, k as f32 * dy);
                    let (sine, _) = sin_cos(std::f32::consts::TAU * 1.9 * x / grid.width);
                    let (_, cosine) = sin_cos(std::f32::consts::TAU * 1.1 * y / grid.height);
                    Vec3::new(x, -y, 1e-3 * size * (sine + cosine))
                })
            })
            .collect();
        let edge = |at: usize, count: usize| if at == 0 || at + 1 == count { 0.5 } else { 1.0 };
        let areas: Vec<f32> = (0..n)
            .map(|i| dx * dy * edge(i / columns, rows) * edge(i % columns, columns))
            .collect();
        let per_area = ADDED_MASS_SHARE
            * coefficients.density
            * std::f32::consts::FRAC_PI_4
            * grid.width.min(grid.height);
        let added_mass: Vec<f32> = areas
            .iter()
            .map(|a| Some(per_area * a).filter(|m| m.is_finite()).unwrap_or(0.0))
            .collect();
        let beta = added_mass
            .iter()
            .map(|m_a| m_a / (node_mass + m_a))
            .collect();
        let pinned = |i: usize| match pinning {
            Pinning::PoleColumn => i.is_multiple_of(columns),
            Pinning::TopRow => i < columns,
        };
        let inverse_mass = (0..n)
            .map(|i| if pinned(i) { 0.0 } else { 1.0 / node_mass })
            .collect();
        let distance = |a: usize, b: usize| positions[a].distance(positions[b]);
        // Two diagonals of stiffness G t d² / (2 dx dy) store a cell's shear energy
        // ½ G t γ² dx dy. Listed so that consecutive constraints mostly share no node (they are
        // projected four at a time where four in a row share none: `disjoint_runs`).
        let diagonal = dx * dx + dy * dy;
        let shear_compliance = 2.0 * dx * dy / (SHEAR_STIFFNESS * diagonal);
        let mut shear = Vec::with_capacity(2 * (rows - 1) * (columns - 1));
        for (from, to) in [(0, columns + 1), (1, columns)] {
            for parity in 0..2 {
                for k in 0..rows - 1 {
                    for j in (parity..columns - 1).step_by(2) {
                        let (p, q) = (k * columns + j + from, k * columns + j + to);
                        shear.push((p as u32, q as u32, distance(p, q), shear_compliance));
                    }
                }
            }
        }
        // Bending energy ½ B κ² per area, κ = |x_a − 2 x_b + x_c| / s² (flat at rest): a
        // compliance of s³ / (B w) per three nodes s apart on a strip w wide (Bergou et al.'s
        // quadratic bending, the same stiffness on any grid).
        let stride_bends = |stride: usize, first: &dyn Fn(usize, usize) -> Option<usize>| {
            let compliance = if stride == 1 {
                dx.powi(3) / (BENDING_STIFFNESS * dy)
            } else {
                dy.powi(3) / (BENDING_STIFFNESS * dx)
            };
            // By phase along the line, so that consecutive constraints mostly share no node.
            (0..3)
                .flat_map(move |phase| (0..n).map(move |i| (phase, i)))
                .filter_map(|(phase, i)| first(phase, i))
                .map(|a| {
                    let a = a as u32;
                    let s = stride as u32;
                    (a, a + s, a + 2 * s, compliance)
                })
                .collect::<Vec<_>>()
        };
        let mut bends = stride_bends(1, &|phase, i| {
            let j = i % columns;
            (j + 2 < columns && j % 3 == phase).then_some(i)
        });
        bends.extend(stride_bends(columns, &|phase, i| {
            let k = i / columns;
            (k + 2 < rows && k % 3 == phase).then_some(i)
        }));
        let tethers = (0..n)
            .filter(|&i| !pinned(i))
            .map(|i| {
                let pin = match pinning {
                    Pinning::PoleColumn => i - i % columns,
                    Pinning::TopRow => i % columns,
                };
                (i as u32, pin as u32, distance(i, pin))
            })
            .collect();
        let yarns = yarns::Yarns::new(rows, columns, &positions);
        let mut cloth = Self {
            grid,
            velocities: vec![Vec3::ZERO; n],
            previous: positions.clone(),
            positions,
            inverse_mass,
            node_mass,
            areas,
            added_mass,
            beta,
            yarns,
            shear_lambdas: vec![0.0; shear.len()],
            shear_runs: constraints::disjoint_runs(
                &shear.iter().map(|s| [s.0, s.1]).collect::<Vec<_>>(),
            ),
            bend_runs: constraints::disjoint_runs(
                &bends.iter().map(|b| [b.0, b.1, b.2]).collect::<Vec<_>>(),
            ),
            shear,
            bend_lambdas: vec![Vec3::ZERO; bends.len()],
            bends,
            tethers,
            pinning,
            coefficients,
            iterations: 1,
            min_substeps: 1,
            tick: ParticleCloth::SUBSTEP,
            normals: Vec::with_capacity(n),
            fresh_normals: Vec::with_capacity(n),
            ahead_normals: Vec::with_capacity(n),
            lift_rate: vec![0.0; n],
            drag_rate: vec![0.0; n],
            friction: vec![0.0; n],
            relative: vec![0.0; n],
            reach: vec![0.0; n],
            midpoint_reach: vec![0.0; n],
            pressure: vec![0.0; n],
            pressure_scratch: pressure::PressureScratch::default(),
            wind: vec![Vec3::ZERO; n],
            wind_read: Vec::with_capacity(n),
            wind_age: u32::MAX,
            force: Vec3::ZERO,
            owed: 0.0,
            tick_start: TickStart::default(),
            undone: 0,
            parts: 1,
            reactive: None,
        };
        let mut normals = std::mem::take(&mut cloth.normals);
        cloth.normals_into(&mut normals);
        cloth.normals = normals;
        Ok(cloth)
    }

    /// The same cloth with the air as Lighthill's reactive force along its chordwise yarns
    /// (the yarns from the pins to the free edge) and the resistive drag, instead of the
    /// smoothed pressure: each node carries its strip's share of a flat plate's added mass,
    /// elliptic over the span. Experimental and not yet the default: it gives a held sheet
    /// Jones' slender-wing lift slope on any grid and a flag in a breeze waves at Lighthill's
    /// speed, but the flag swings too wide, drags too much and does not hang in light air (the
    /// module `reactive` and docs/aero.md say what is measured and what is missing). Hidden
    /// from the docs until it does.
    #[doc(hidden)]
    pub fn with_reactive_air(mut self) -> Self {
        let (air, added_mass) = reactive::ReactiveAir::new(&self);
        self.beta = added_mass
            .iter()
            .map(|m_a| m_a / (self.node_mass + m_a))
            .collect();
        self.added_mass = added_mass;
        self.reactive = Some(air);
        let mut normals = std::mem::take(&mut self.normals);
        self.normals_into(&mut normals);
        self.normals = normals;
        self
    }

    /// Pivots of the reactive air's solves that were not positive and finite (0 without it).
    #[doc(hidden)]
    pub fn reactive_guarded_pivots(&self) -> u64 {
        self.reactive
            .as_ref()
            .map_or(0, reactive::ReactiveAir::guarded_pivots)
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

    /// How the yarns' linear solves have gone since the cloth was made: how many, their
    /// iterations, those stopped at the limit before the tolerance, guarded pivots and the last
    /// residual.
    pub fn yarn_solves(&self) -> YarnSolves {
        self.yarns.solves
    }

    /// Substeps undone since the cloth was made: a substep that would leave a yarn edge
    /// stretched by more than half its length, or a node not finite, is undone and the cloth
    /// stopped where it was (only under loads far beyond weather: see the module's docs).
    pub fn undone_substeps(&self) -> u64 {
        self.undone
    }

    /// Largest |length / rest − 1| over the edges along the rows and the columns.
    pub fn max_strain(&self) -> f32 {
        self.yarns.max_strain(&self.positions)
    }

    /// The mean force of the air on the whole cloth over the last [`Self::step`] that advanced
    /// it, N (local frame): pressure and skin friction, as they were applied (the carried air's
    /// inertia is the nodes' own, not a force). Its component along the wind is the cloth's drag.
    pub fn aerodynamic_force(&self) -> Vec3 {
        self.force
    }

    /// Kinetic plus potential energy of the free nodes, J, with the kinetic energy of the air
    /// they carry across the sheet: Σ ½ m |v|² + ½ m_a (v · n)² − m g · x.
    pub fn energy(&self, gravity: Vec3) -> f32 {
        let m = self.node_mass;
        self.positions
            .iter()
            .zip(&self.velocities)
            .zip(&self.normals)
            .zip(self.inverse_mass.iter().zip(&self.added_mass))
            .filter(|(_, (w, _))| **w > 0.0)
            .map(|(((p, v), n), (_, m_a))| {
                0.5 * m * v.length_squared() + 0.5 * m_a * v.dot(*n).powi(2) - m * gravity.dot(*p)
            })
            .sum()
    }

    /// Advances by `dt` under `gravity` in the fluid velocity `wind(p)` (local frame), in whole
    /// ticks ([`ParticleCloth::tick`], 4 ms by default): what is left of `dt` (less than
    /// one) is simulated with the next step, and a step longer than [`ParticleCloth::MAX_STEP`] is
    /// simulated as that long. The wind is sampled every [`ParticleCloth::WIND_INTERVAL`]
    /// milliseconds (rounded to whole ticks). A substep that would stretch a yarn by more than half is undone
    /// ([`ParticleCloth::undone_substeps`]). A non-finite or non-positive `dt` or a non-finite `gravity` leaves the cloth
    /// as it is (the plugin reports such a cloth with
    /// [`PhysicalClothInvalid`](super::physical_cloth::PhysicalClothInvalid)).
    pub fn step(&mut self, dt: f32, gravity: Vec3, wind: &impl Fn(Vec3) -> Vec3) {
        self.step_batched(dt, gravity, |points, velocities| {
            velocities.clear();
            velocities.extend(points.iter().map(|p| wind(*p)));
        });
    }

    /// [`ParticleCloth::step`] with the wind read for every node at once: `wind(points,
    /// velocities)` fills `velocities` with the fluid's velocity at each of `points` (local
    /// frame), in order (it is handed over empty); a velocity missing or not finite counts as
    /// still air. A batch lets a
    /// field read its points side by side, as
    /// [`WindField::velocities`](crate::wind::WindField::velocities) does with the bits of its
    /// point read (the [`PhysicalCloth`](super::physical_cloth::PhysicalCloth) plugin reads so).
    pub fn step_batched(
        &mut self,
        dt: f32,
        gravity: Vec3,
        mut wind: impl FnMut(&[Vec3], &mut Vec<Vec3>),
    ) {
        if !(dt.is_finite() && dt > 0.0 && gravity.is_finite()) {
            return;
        }
        let tick = if self.tick.is_finite() {
            self.tick
                .clamp(ParticleCloth::SHORTEST_TICK, ParticleCloth::LONGEST_TICK)
        } else {
            ParticleCloth::SUBSTEP
        };
        // The wind is sampled every WIND_INTERVAL milliseconds, rounded to whole ticks.
        let interval = ((ParticleCloth::WIND_INTERVAL as f32 * 1e-3 / tick).round() as u32).max(1);
        let total = (dt + self.owed).min(ParticleCloth::MAX_STEP);
        // Whole ticks; within a thousandth of one counts as whole (f32 frame times).
        let count = (total / tick + 1e-3).floor();
        self.owed = (total - count * tick).max(0.0);
        if count < 1.0 {
            return;
        }
        self.force = Vec3::ZERO;
        for _ in 0..count as u32 {
            if self.wind_age >= interval {
                self.wind_read.clear();
                wind(&self.positions, &mut self.wind_read);
                for (i, u) in self.wind.iter_mut().enumerate() {
                    let w = self.wind_read.get(i).copied().unwrap_or(Vec3::ZERO);
                    *u = if w.is_finite() { w } else { Vec3::ZERO };
                }
                self.wind_age = 0;
            }
            self.wind_age += 1;
            // More substeps while the yarns could not be held within STRETCH_TOLERANCE (gales,
            // huge gravity), fewer again once they are well within it; a tick that left an
            // edge stretched past RETRY_STRAIN is simulated again in twice the substeps.
            let most = ParticleCloth::MAX_SUBSTEPS;
            let mut parts = self.parts.max(self.min_substeps).clamp(1, most);
            let worst = loop {
                if parts < most {
                    self.save_tick();
                }
                let worst = self.substeps(tick / parts as f32, parts, gravity);
                if (worst > RETRY_STRAIN || worst.is_nan()) && parts < most {
                    self.restore_tick();
                    parts = (parts * 2).min(most);
                } else {
                    break worst;
                }
            };
            if worst > STRETCH_TOLERANCE || worst.is_nan() {
                self.parts = (parts * 2).min(most);
            } else if worst < 0.25 * STRETCH_TOLERANCE {
                self.parts = (parts / 2).max(1);
            } else {
                self.parts = parts;
            }
        }
        self.force /= count * tick;
        if !self.force.is_finite() {
            self.force = Vec3::ZERO;
        }
    }
}

impl ParticleCloth {
    /// `parts` substeps of `h`; returns the largest relative stretch of a yarn edge they left.
    fn substeps(&mut self, h: f32, parts: u32, gravity: Vec3) -> f32 {
        let mut worst = 0.0f32;
        for _ in 0..parts {
            self.loads();
            let force = self.force;
            let strain = self.substep(h, gravity);
            if !(strain <= STRETCH_LIMIT && self.positions.iter().all(|p| p.is_finite())) {
                // The undone substep's loads are not reported either.
                self.undo();
                self.force = force;
            }
            // A NaN strain counts as the worst (f32::max would skip it).
            if strain.is_nan() || strain > worst {
                worst = strain;
            }
        }
        worst
    }

    /// Keeps the state a tick starts from, to simulate it again.
    fn save_tick(&mut self) {
        let start = &mut self.tick_start;
        for (kept, now) in [
            (&mut start.positions, &self.positions),
            (&mut start.velocities, &self.velocities),
            (&mut start.normals, &self.normals),
        ] {
            kept.clear();
            kept.extend_from_slice(now);
        }
        (start.force, start.undone) = (self.force, self.undone);
    }

    /// Puts the cloth back as [`Self::save_tick`] kept it; the yarns' next solve starts from
    /// zero.
    fn restore_tick(&mut self) {
        let start = &self.tick_start;
        self.positions.copy_from_slice(&start.positions);
        self.velocities.copy_from_slice(&start.velocities);
        self.normals.copy_from_slice(&start.normals);
        (self.force, self.undone) = (start.force, start.undone);
        self.yarns.forget();
    }

    /// Puts the nodes back where the last substep found them, at rest (see [`STRETCH_LIMIT`]).
    fn undo(&mut self) {
        self.positions.copy_from_slice(&self.previous);
        self.velocities.fill(Vec3::ZERO);
        let mut normals = std::mem::take(&mut self.normals);
        self.normals_into(&mut normals);
        self.normals = normals;
        self.yarns.forget();
        self.undone += 1;
    }
}

/// Limits and constants of [`ParticleCloth`].
impl ParticleCloth {
    /// Most constraint sweeps per substep: [`ParticleCloth::iterations`] is clamped to it.
    pub const MAX_ITERATIONS: usize = 8;

    /// Most substeps per tick: [`ParticleCloth::min_substeps`] is clamped to it.
    pub const MAX_SUBSTEPS: u32 = 16;

    /// The default tick ([`ParticleCloth::tick`]), s: the longest substep of a new cloth.
    pub const SUBSTEP: f32 = 4e-3;

    /// The shortest tick a cloth takes, s.
    pub const SHORTEST_TICK: f32 = 2.5e-4;

    /// The longest tick a cloth takes, s.
    pub const LONGEST_TICK: f32 = 4e-3;

    /// Longest step simulated, s: a longer one (a hitch) is simulated as this long, so a frame
    /// costs at most three 60 Hz frames' worth of ticks (12 of the default 4 ms), however long
    /// it took. The
    /// [`PhysicalCloth`](super::physical_cloth::PhysicalCloth) plugin holds each rendered frame to
    /// the same budget over all its fixed steps.
    pub const MAX_STEP: f32 = 0.05;

    /// Milliseconds between two samples of the wind.
    pub const WIND_INTERVAL: u32 = 4;
}
