//! The [`WindField`] resource: mean log-law wind plus spectral turbulence, sampled anywhere.

use crate::error::InvalidValue;
use bevy::ecs::reflect::ReflectResource;
use bevy::ecs::resource::Resource;
use bevy::math::{DVec2, Vec2, Vec3};
use bevy::reflect::Reflect;

use super::config::{SpatialMode, TemporalMode, WindConfig};
use super::ease::WindEasing;
use super::error::WindError;

use super::mover::MoverFlow;
use super::shelter::PlacedShelter;
use super::source::PlacedSource;
use crate::spectrum::{GridShape, SpectrumError, Synthesizer};

/// Wind velocity anywhere in space and time: a logarithmic mean profile (eq. 10 of the
/// free-fall paper, Xie and Miyata, *Realistic Motion Simulations of Objects in Free Fall*) plus
/// three independent 1/f^β turbulence components with the per-axis ratios of eq. 12, either on one horizontal plane carried to other heights by eq. 14
/// or in a full volume, frozen (Taylor) or evolving.
///
/// Sampling interpolates grid nodes linearly and wraps periodically, so every finite position and
/// time gives a finite velocity. The field keeps its own clock, which [`WindPlugin`] advances on
/// the fixed timestep; [`WindField::velocity`] samples at that clock.
///
/// Axes: Y is up; `u` is along the mean wind direction, `v` along `direction × Y`, `w` along Y.
///
/// [`WindPlugin`]: super::WindPlugin
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // A system that pushes smoke particles with the wind where they are.
/// #[derive(Component)]
/// struct Smoke;
///
/// fn drift(wind: Res<WindField>, time: Res<Time>, mut smoke: Query<&mut Transform, With<Smoke>>) {
///     for mut t in &mut smoke {
///         let v = wind.velocity(t.translation);
///         t.translation += v * time.delta_secs();
///     }
/// }
/// App::new()
///     .add_plugins((MinimalPlugins, WindfallPlugins::default()))
///     .add_systems(FixedUpdate, drift.in_set(WindfallSystems::Simulate));
/// ```
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(opaque, Resource, Debug)]
pub struct WindField {
    config: WindConfig,
    shape: GridShape,
    /// Unit-variance turbulence (u, v, w) per node, row-major over `[time?, x, y?, z]`.
    nodes: Vec<Vec3>,
    friction_velocity: f32,
    /// ln(h_ref/z0), the denominator of eq. 14 ...
    log_reference: f32,
    /// ... and its reciprocal (a sample multiplies; a division stalls the read).
    inv_log_reference: f32,
    /// Nodes per metre, 1 / cell size.
    per_cell: f64,
    /// ln(z0).
    log_roughness: f32,
    sigma_u: f32,
    along: Vec3,
    across: Vec3,
    time: f64,
    /// Wind seconds per simulated second; 0 freezes the clock, negative runs it back.
    pub time_scale: f32,
    /// When true the clock does not advance.
    pub paused: bool,
    /// Which field this is: every field made by [`WindField::new`] gets its own number (a clone
    /// keeps it).
    generation: u64,
    /// The [`WindSource`](super::WindSource)s placed at the last fixed step, by entity.
    sources: Vec<PlacedSource>,
    /// The flows of the [`WindMover`](super::WindMover)s that moved at the last fixed step, by
    /// entity.
    movers: Vec<MoverFlow>,
    /// Where [`WindField::ease_to`] is taking the mean wind.
    ease: Option<WindEasing>,
    /// The [`WindShelter`](super::WindShelter)s placed at the last fixed step.
    shelters: Vec<PlacedShelter>,
    /// The clock before the last [`WindField::advance`]: when the step now simulated began.
    step_start: f64,
    /// How far the turbulence pattern had travelled (x, z; m, at the reference speed) when the
    /// mean speed or direction last changed, at wind time `drift_since`: Taylor's hypothesis with
    /// a speed that changes, ∫ U dt, so a change of the mean wind never makes the pattern jump.
    pub(super) drift_base: DVec2,
    /// Wind time of the last change of the mean speed or direction.
    pub(super) drift_since: f64,
    /// The [`WindSettings`](super::WindSettings) as this field last took them in: a settings
    /// edit applies what differs from these, field by field. `None` until the field is
    /// inserted into an app (then the app's settings, if any).
    pub(in crate::wind) taken_in: Option<WindConfig>,
}

mod live;
pub(crate) mod profile;
mod read;
mod snapshot;
pub(crate) use read::Moment;

/// Numbers the fields made by [`WindField::new`].
static GENERATIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl WindField {
    /// Builds the field: validates `config`, then synthesises the three turbulence components
    /// (two in one complex FFT, see [`Synthesizer::pair`]). The amplitude table and FFT plans of
    /// recent grids are kept ([`Synthesizer::shared`]), so a rebuild costs the random spectrum
    /// and the transforms.
    pub fn new(config: WindConfig) -> Result<Self, WindError> {
        config.validate()?;
        let dims = grid_dims(&config);
        let shape = GridShape::new(&dims);
        let synth = Synthesizer::shared(&dims, config.beta, config.fft).map_err(|e| match e {
            SpectrumError::Beta(beta) => {
                InvalidValue::new("beta", beta, "must be finite and ≥ 0").into()
            }
            SpectrumError::NoAxis
            | SpectrumError::TooManyAxes { .. }
            | SpectrumError::AxisTooShort { .. } => WindError::GridAxis {
                field: "grid",
                len: 0,
            },
            SpectrumError::TooManyNodes { nodes } => WindError::TooManyNodes {
                field: "grid",
                nodes,
            },
        })?;
        let (u, v) = synth.pair(config.seed);
        let w = synth.field(config.seed ^ 0x9E37_79B9_7F4A_7C15);
        let nodes = u
            .iter()
            .zip(&v)
            .zip(&w)
            .map(|((&u, &v), &w)| Vec3::new(u, v, w))
            .collect();
        let mut field = Self {
            config,
            shape,
            nodes,
            friction_velocity: 0.0,
            log_reference: 1.0,
            inv_log_reference: 1.0,
            per_cell: 1.0,
            log_roughness: 0.0,
            sigma_u: 0.0,
            along: Vec3::X,
            across: Vec3::Z,
            time: 0.0,
            time_scale: 1.0,
            paused: false,
            generation: GENERATIONS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            sources: Vec::new(),
            movers: Vec::new(),
            ease: None,
            shelters: Vec::new(),
            step_start: 0.0,
            drift_base: DVec2::ZERO,
            drift_since: 0.0,
            taken_in: None,
        };
        field.derive();
        Ok(field)
    }

    /// Recomputes the quantities that follow from the configuration.
    pub(super) fn derive(&mut self) {
        let c = &self.config;
        self.friction_velocity =
            profile::friction_velocity(c.reference_speed, c.reference_height, c.roughness);
        let intensity = c
            .turbulence_intensity
            .unwrap_or_else(|| profile::surface_layer_intensity(c.reference_height, c.roughness));
        self.sigma_u = intensity * c.reference_speed;
        self.log_reference = profile::log_ratio(c.reference_height, c.roughness);
        self.inv_log_reference = 1.0 / self.log_reference;
        self.per_cell = 1.0 / f64::from(c.cell_size);
        self.log_roughness = profile::ln(c.roughness);
        // Validated: the direction has a unit vector, whatever its length.
        let d = crate::guard::unit_vec2(c.direction).unwrap_or(Vec2::X);
        self.along = Vec3::new(d.x, 0.0, d.y);
        self.across = self.along.cross(Vec3::Y);
    }

    /// Which field this is (each [`WindField::new`] makes a new one; clones share it).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The configuration the field was built from (with any later speed or direction change).
    pub fn config(&self) -> &WindConfig {
        &self.config
    }

    /// Friction velocity u* (eq. 10), m/s.
    pub fn friction_velocity(&self) -> f32 {
        self.friction_velocity
    }

    /// Standard deviations (σ_u, σ_v, σ_w) of the turbulence at the reference height, m/s.
    pub fn sigma(&self) -> Vec3 {
        Vec3::new(
            self.sigma_u,
            self.sigma_u * profile::LATERAL_RATIO,
            self.sigma_u * profile::VERTICAL_RATIO,
        )
    }

    /// Unit vector of the mean wind.
    pub fn direction(&self) -> Vec3 {
        self.along
    }

    /// Mean wind speed at `height` by the log law (eq. 10); 0 at or below the roughness length.
    pub fn mean_speed_at(&self, height: f32) -> f32 {
        profile::log_law(self.friction_velocity, self.config.roughness, height)
    }

    /// Replaces the local sources (the [`WindPlugin`](super::WindPlugin) does this every fixed
    /// step from the [`WindSource`](super::WindSource) components).
    pub(crate) fn set_sources(&mut self, sources: Vec<PlacedSource>) {
        self.sources = sources;
    }

    /// Replaces the movers' flows (the [`WindPlugin`](super::WindPlugin) does this every fixed
    /// step from the [`WindMover`](super::WindMover) components).
    pub(crate) fn set_movers(&mut self, movers: Vec<MoverFlow>) {
        self.movers = movers;
    }

    /// Replaces the shelters (the [`WindPlugin`](super::WindPlugin) does this every fixed step
    /// from the [`WindShelter`](super::WindShelter) components).
    pub(crate) fn set_shelters(&mut self, shelters: Vec<PlacedShelter>) {
        self.shelters = shelters;
    }

    /// The wind time the step now simulated began at (the clock before the last advance): a
    /// source added before this step started then.
    pub(crate) fn step_start(&self) -> f64 {
        self.step_start
    }

    /// The unit-variance turbulence per node, row-major over [`Self::grid_dims`].
    #[cfg(feature = "render")]
    pub(crate) fn nodes(&self) -> &[Vec3] {
        &self.nodes
    }

    /// Node counts per axis, row-major: `[time?, x, y?, z]`.
    #[cfg(feature = "render")]
    pub(crate) fn grid_dims(&self) -> &[usize] {
        self.shape.dims()
    }

    /// (ln(h_ref/z0), ln z0): eq. 14's denominator and the log of the roughness.
    #[cfg(feature = "render")]
    pub(crate) fn log_constants(&self) -> (f32, f32) {
        (self.log_reference, self.log_roughness)
    }

    /// The sources placed at the last fixed step, in the order they are summed.
    #[cfg(feature = "render")]
    pub(crate) fn placed_sources(&self) -> &[PlacedSource] {
        &self.sources
    }

    /// The movers' flows placed at the last fixed step, in the order they are summed.
    pub(crate) fn placed_movers(&self) -> &[MoverFlow] {
        &self.movers
    }

    /// The shelters placed at the last fixed step.
    #[cfg(feature = "render")]
    pub(crate) fn placed_shelters(&self) -> &[PlacedShelter] {
        &self.shelters
    }

    /// How many [`WindShelter`](super::WindShelter)s calm the field (as of the last fixed step).
    pub fn shelter_count(&self) -> usize {
        self.shelters.len()
    }

    /// How many [`WindSource`](super::WindSource)s blow into the field (as of the last fixed
    /// step).
    pub fn source_count(&self) -> usize {
        self.sources.len()
    }

    /// How many [`WindMover`](super::WindMover)s push the air (those that moved at the last
    /// fixed step).
    pub fn mover_count(&self) -> usize {
        self.movers.len()
    }
}

/// Node counts per axis, row-major: `[time?, x, y?, z]`.
fn grid_dims(config: &WindConfig) -> Vec<usize> {
    let mut dims = Vec::with_capacity(4);
    if let TemporalMode::Evolving { samples, .. } = config.temporal {
        dims.push(samples);
    }
    dims.push(config.grid[0]);
    if let SpatialMode::Volume { vertical_nodes } = config.spatial {
        dims.push(vertical_nodes);
    }
    dims.push(config.grid[1]);
    dims
}

/// Limits and constants of [`WindField`].
impl WindField {
    /// Bound of the wind clock, s (about 31 700 years): [`WindField::advance`] and
    /// [`WindField::set_clock`] clamp to ±this, so the clock and [`WindField::time`] stay finite.
    pub const MAX_CLOCK: f64 = 1.0e12;

    /// von Kármán's constant κ (eq. 10).
    pub const VON_KARMAN: f32 = 0.40;
}
