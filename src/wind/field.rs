//! The [`WindField`] resource: mean log-law wind plus spectral turbulence, sampled anywhere.

use bevy::ecs::reflect::ReflectResource;
use bevy::ecs::resource::Resource;
use bevy::math::{DVec2, Vec2, Vec3};
use bevy::reflect::Reflect;

use super::config::{SpatialMode, TemporalMode, WindConfig, WindError};
use super::ease::Ease;
use super::profile;
use super::pulse::Pulse;
use super::shelter::PlacedShelter;
use super::source::PlacedSource;
use crate::spectrum::{GridShape, SpectrumError, Synthesizer};

/// Highest accepted `reference_speed`, m/s (ten times a hurricane's, far past any use).
pub const MAX_REFERENCE_SPEED: f32 = 1.0e4;
/// Highest accepted `turbulence_intensity`.
pub const MAX_TURBULENCE_INTENSITY: f32 = 10.0;
/// Bound of the wind clock, s (about 31 700 years): [`WindField::advance`] and
/// [`WindField::set_clock`] clamp to ±this, so the clock and [`WindField::time`] stay finite.
pub const MAX_CLOCK: f64 = 1.0e12;

/// Wind velocity anywhere in space and time: a logarithmic mean profile (eq. 10 of
/// `free-fall-motion-synthesis.txt`) plus three independent 1/f^β turbulence components with the
/// per-axis ratios of eq. 12, either on one horizontal plane carried to other heights by eq. 14
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
///     .add_plugins((MinimalPlugins, WindfallPlugins))
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
    /// Where [`WindField::ease_to`] is taking the mean wind.
    ease: Option<Ease>,
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
}

mod read;

/// Numbers the fields made by [`WindField::new`].
static GENERATIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

impl WindField {
    /// Builds the field: validates `config`, then synthesises the three turbulence components
    /// (two in one complex FFT, see [`Synthesizer::pair`]). The amplitude table and FFT plans of
    /// recent grids are kept ([`Synthesizer::shared`]), so a rebuild costs the random spectrum
    /// and the transforms.
    pub fn new(config: WindConfig) -> Result<Self, WindError> {
        validate_extra(&config)?;
        let dims = grid_dims(&config);
        let shape = GridShape::new(&dims);
        let synth = Synthesizer::shared(&dims, config.beta, config.fft).map_err(|e| match e {
            SpectrumError::Beta(beta) => WindError::Invalid {
                field: "beta",
                value: beta,
                reason: "must be finite and ≥ 0",
            },
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
            ease: None,
            shelters: Vec::new(),
            step_start: 0.0,
            drift_base: DVec2::ZERO,
            drift_since: 0.0,
        };
        field.derive();
        Ok(field)
    }

    /// Recomputes the quantities that follow from the configuration.
    fn derive(&mut self) {
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

    /// Changes the mean speed at the reference height at once, keeping the turbulence pattern
    /// (and ending any [`Self::ease_to`]).
    pub fn set_reference_speed(&mut self, speed: f32) -> Result<(), WindError> {
        let mut config = self.config.clone();
        config.reference_speed = speed;
        validate_extra(&config)?;
        self.rebase_drift();
        self.config = config;
        self.ease = None;
        self.derive();
        Ok(())
    }

    /// Changes the horizontal direction (x, z) of the mean wind at once, keeping the pattern
    /// (and ending any [`Self::ease_to`]).
    pub fn set_direction(&mut self, direction: Vec2) -> Result<(), WindError> {
        let mut config = self.config.clone();
        config.direction = direction;
        validate_extra(&config)?;
        self.rebase_drift();
        self.config = config;
        self.ease = None;
        self.derive();
        Ok(())
    }

    /// Sets the periodic swell of the wind's strength ([`Pulse`]) at once.
    ///
    /// # Errors
    /// A magnitude outside [0, 1] or a frequency outside [0, 100] Hz, named.
    pub fn set_pulse(&mut self, pulse: Pulse) -> Result<(), WindError> {
        pulse.validate()?;
        self.config.pulse = pulse;
        Ok(())
    }

    /// Books the pattern's travel so far at the current speed and direction, before they change.
    fn rebase_drift(&mut self) {
        self.drift_base = self.drift_at(self.time);
        self.drift_since = self.time;
    }

    /// How far the pattern has travelled at the reference speed by wind time `time`, m (x, z):
    /// the travel booked so far plus the current mean wind times the time since.
    pub(crate) fn drift_at(&self, time: f64) -> DVec2 {
        let span = f64::from(self.config.reference_speed) * (time - self.drift_since);
        self.drift_base + DVec2::new(f64::from(self.along.x), f64::from(self.along.z)) * span
    }

    /// Eases the mean wind toward `speed` (m/s at the reference height) and `direction` (x, z)
    /// with time constant `time_constant` (s of wind time): as the clock advances, both move the
    /// fraction 1 − e^(−dt/τ) of the way each step (the direction turning the short way), so a
    /// storm builds up and a wind veers without a jump; τ = 0 sets them at once. The turbulence
    /// pattern is kept. [`Self::set_reference_speed`] or [`Self::set_direction`] end it.
    ///
    /// # Errors
    /// A speed or direction [`Self::set_reference_speed`] / [`Self::set_direction`] would
    /// refuse, or a negative or non-finite `time_constant`.
    pub fn ease_to(
        &mut self,
        speed: f32,
        direction: Vec2,
        time_constant: f32,
    ) -> Result<(), WindError> {
        let mut target = self.config.clone();
        target.reference_speed = speed;
        target.direction = direction;
        validate_extra(&target)?;
        if !(time_constant.is_finite() && time_constant >= 0.0) {
            return Err(WindError::Invalid {
                field: "time_constant",
                value: time_constant,
                reason: "must be finite and ≥ 0",
            });
        }
        let direction = crate::guard::unit_vec2(direction).unwrap_or(Vec2::X);
        self.ease = Some(Ease {
            speed,
            direction,
            time_constant,
        });
        if time_constant == 0.0 {
            self.ease_step(0.0);
        }
        Ok(())
    }

    /// Restores an easing (from a [`WindSnapshot`](super::WindSnapshot)) without stepping it.
    pub(super) fn resume_easing(
        &mut self,
        speed: f32,
        direction: Vec2,
        time_constant: f32,
    ) -> Result<(), WindError> {
        let (speed_now, direction_now) = (self.config.reference_speed, self.config.direction);
        self.ease_to(speed, direction, time_constant.max(f32::MIN_POSITIVE))?;
        // ease_to with τ > 0 changes nothing yet; keep the exact τ.
        if let Some(ease) = self.ease.as_mut() {
            ease.time_constant = time_constant;
        }
        debug_assert_eq!(
            (speed_now, direction_now),
            (self.config.reference_speed, self.config.direction)
        );
        Ok(())
    }

    /// Where [`Self::ease_to`] is taking the mean wind: (speed, unit direction, τ).
    pub fn easing(&self) -> Option<(f32, Vec2, f32)> {
        self.ease.map(|e| (e.speed, e.direction, e.time_constant))
    }

    fn ease_step(&mut self, dt: f32) {
        let Some(ease) = self.ease else {
            return;
        };
        let now = Vec2::new(self.along.x, self.along.z);
        let (speed, direction, arrived) = ease.step(self.config.reference_speed, now, dt);
        self.rebase_drift();
        self.config.reference_speed = speed;
        self.config.direction = direction;
        if arrived {
            self.ease = None;
        }
        self.derive();
    }

    /// Wind time, s.
    pub fn time(&self) -> f32 {
        self.time as f32
    }

    /// Wind time, s, in full (the clock runs in f64 so that long sessions keep their precision).
    pub fn time_seconds(&self) -> f64 {
        self.time
    }

    /// Sets the wind clock to `time` seconds, clamped to ±[`MAX_CLOCK`] (a non-finite time is
    /// ignored).
    pub fn set_clock(&mut self, time: f64) {
        if time.is_finite() {
            self.time = time.clamp(-MAX_CLOCK, MAX_CLOCK);
            self.step_start = self.time;
        }
    }

    /// Advances the wind clock by `dt` seconds times [`Self::time_scale`], unless paused.
    /// A non-finite step is ignored; the clock stays within ±[`MAX_CLOCK`], so even a
    /// `time_scale` of `f32::MAX` leaves [`Self::time`] finite.
    pub fn advance(&mut self, dt: f32) {
        let step = f64::from(dt) * f64::from(self.time_scale);
        self.step_start = self.time;
        if !self.paused && step.is_finite() {
            self.time = (self.time + step).clamp(-MAX_CLOCK, MAX_CLOCK);
            self.ease_step(step.abs().min(f64::from(f32::MAX)) as f32);
        }
    }

    /// Takes over `old`'s clock (time, time scale, pause), its [`Self::ease_to`] in progress and
    /// how far its pattern has travelled, so a rebuilt field continues where the old one was.
    pub fn continue_clock_of(&mut self, old: &WindField) {
        self.time = old.time;
        self.time_scale = old.time_scale;
        self.paused = old.paused;
        self.ease = old.ease;
        self.step_start = old.step_start;
        self.drift_base = old.drift_base;
        self.drift_since = old.drift_since;
    }

    /// Replaces the local sources (the [`WindPlugin`](super::WindPlugin) does this every fixed
    /// step from the [`WindSource`](super::WindSource) components).
    pub(crate) fn set_sources(&mut self, sources: Vec<PlacedSource>) {
        self.sources = sources;
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

/// [`WindConfig::validate`] plus the upper bounds that keep every sample finite.
/// Every check [`WindField::new`] makes before synthesising.
pub(super) fn validate_extra(config: &WindConfig) -> Result<(), WindError> {
    config.validate()?;
    if config.reference_speed > MAX_REFERENCE_SPEED {
        return Err(WindError::Invalid {
            field: "reference_speed",
            value: config.reference_speed,
            reason: "must be ≤ 1e4 m/s",
        });
    }
    if let Some(i) = config.turbulence_intensity
        && i > MAX_TURBULENCE_INTENSITY
    {
        return Err(WindError::Invalid {
            field: "turbulence_intensity",
            value: i,
            reason: "must be ≤ 10",
        });
    }
    Ok(())
}
