//! ECS glue: [`FallingObject`], its runtime [`FallState`], the [`Landed`] message and the
//! [`FreeFallPlugin`].

use std::sync::{Arc, Mutex, PoisonError};

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

use super::lod::{FallClock, FallLod};
use super::markov::MarkovChain;
use super::model::FallModel;
use super::motion::{FallScales, STROUHAL};
use super::path::{FallPath, StepOutcome, WindTilt};
use super::regime::{Fluid, FreeFallError, PrimitiveMotion, Regime, Shape, regime};
use super::release::FallRelease;
use super::tiers::TierClock;
use crate::WindfallSystems;
use crate::lod::LodFocus;
use crate::wind::WindField;

/// A leaf, a sheet of paper, a coin: anything thin that falls through air or water.
///
/// It falls from where its [`Transform`] is, turned as it is, when the component is added
/// (released in the frame's `PostUpdate`, moved from the next fixed step on). The plate lies in
/// the entity's local XZ plane with its long axis along local Z (the axis it tumbles about).
/// Change it (for example `seed += 1`) to release it again from its current transform; a fall
/// released in mid-air keeps its velocity. An invalid description gets a
/// [`FallingObjectInvalid`] holding the typed error (logged once with `warn!`) and the entity
/// stays still. [`FallPreset`](super::FallPreset) has real
/// objects.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// // A sheet of paper let go 2 m up, turned 30° about its long axis.
/// let sheet = app
///     .world_mut()
///     .spawn((
///         FallingObject {
///             shape: Shape::Rectangle { length: 0.297, width: 0.21, thickness: 1e-4 },
///             density: 800.0,
///             seed: 3,
///             ..default()
///         },
///         Transform::from_xyz(0.0, 2.0, 0.0).with_rotation(Quat::from_rotation_z(0.5)),
///     ))
///     .id();
/// app.update();
/// let regime = *app.world().get::<FallState>(sheet).unwrap().regime().unwrap();
/// assert_eq!(regime.main, PrimitiveMotion::Tumbling);
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform, FallState)]
pub struct FallingObject {
    /// Outline and sizes.
    pub shape: Shape,
    /// ρ_s, kg/m³ (above the fluid's).
    pub density: f32,
    /// The fluid it falls in.
    pub fluid: Fluid,
    /// g, m/s².
    pub gravity: f32,
    /// Seed of this object's random stream (Markov steps, search-tree choices, heading).
    pub seed: u64,
    /// Use this main motion instead of the phase diagram's.
    pub main_motion: Option<PrimitiveMotion>,
    /// k of eq. 7, the deviation coefficient (1 = the paper's amplitudes).
    pub deviation: f32,
    /// W of eq. 15: the largest tilt the wind gives, rad.
    pub wind_tilt: f32,
    /// The Markov chain of its motions (`None`: the [`FallModel`]'s).
    pub markov: Option<MarkovChain>,
}

impl Default for FallingObject {
    /// A 7.3 × 4.2 cm leaf, 0.3 mm thick, density 500 kg/m³, in air.
    fn default() -> Self {
        Self {
            shape: Shape::Ellipse {
                major: 0.073,
                minor: 0.042,
                thickness: 3.0e-4,
            },
            density: 500.0,
            fluid: Fluid::AIR,
            gravity: 9.81,
            seed: 0,
            main_motion: None,
            deviation: 1.0,
            wind_tilt: 0.6,
            markov: None,
        }
    }
}

impl FallingObject {
    /// Re, I*, U and the main motion (the phase diagram's, or [`FallingObject::main_motion`]).
    pub fn regime(&self) -> Result<Regime, FreeFallError> {
        if !(self.deviation.is_finite() && (0.0..=100.0).contains(&self.deviation)) {
            return Err(FreeFallError::Invalid {
                field: "deviation",
                value: self.deviation,
                reason: "must be in [0, 100]",
            });
        }
        if !(self.wind_tilt.is_finite() && self.wind_tilt.abs() <= std::f32::consts::PI) {
            return Err(FreeFallError::Invalid {
                field: "wind_tilt",
                value: self.wind_tilt,
                reason: "must be an angle in [−π, π]",
            });
        }
        let mut r = regime(&self.shape, self.density, &self.fluid, self.gravity)?;
        if let Some(main) = self.main_motion {
            r.main = main;
        }
        Ok(r)
    }

    /// The sizes of its fall (U, Ω = 2π St U / a, L, a, k, ℓ = ρ_s b / ρ_f, I*).
    pub fn scales(&self, regime: &Regime) -> FallScales {
        let (length, chord, thickness) = self.shape.lengths();
        FallScales {
            descent_speed: regime.descent_speed,
            swing_rate: (std::f32::consts::TAU * STROUHAL * regime.descent_speed / chord).max(1e-6),
            length,
            chord,
            deviation: self.deviation,
            drag_length: (f64::from(self.density) * f64::from(thickness)
                / f64::from(self.fluid.density)) as f32,
            inertia: regime.inertia,
        }
    }

    /// Its fall let go as `release` says, with its own chain or the model's.
    ///
    /// # Errors
    /// What [`Self::regime`] or [`FallRelease::validate`] reject.
    pub fn path(&self, model: &FallModel, release: FallRelease) -> Result<FallPath, FreeFallError> {
        let regime = self.regime()?;
        release.validate()?;
        let chain = match &self.markov {
            Some(chain) => Arc::new(chain.bounded(regime.main)),
            None => model.bounded_shared(regime.main),
        };
        Ok(FallPath::release(
            model,
            self.scales(&regime),
            chain,
            self.seed,
            release,
        ))
    }
}

/// Runtime state of a [`FallingObject`] (required component). Reflected (Re, I*, U, the main
/// motion) for inspectors; the path itself is not.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // Count what the falling objects are doing.
/// fn census(objects: Query<&FallState>) -> [usize; 6] {
///     let mut counts = [0; 6];
///     for motion in objects.iter().filter_map(FallState::motion) {
///         counts[motion.index()] += 1;
///     }
///     counts
/// }
/// # let _ = census;
/// ```
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct FallState {
    regime: Option<Regime>,
    #[reflect(ignore)]
    path: Option<FallPath>,
    /// The component this fall was released for (a change of it releases again).
    #[reflect(ignore)]
    released_for: Option<FallingObject>,
    /// When the fall was last stepped, for an object with [`FallLod`] (or one easing back to
    /// full detail after it was removed).
    #[reflect(ignore)]
    tier: Option<TierClock>,
}

impl FallState {
    /// Re, I*, U, mass and main motion, once the object is set up.
    pub fn regime(&self) -> Option<&Regime> {
        self.regime.as_ref()
    }

    /// The fall (Markov state, control points, orientation).
    pub fn path(&self) -> Option<&FallPath> {
        self.path.as_ref()
    }

    /// The current primitive motion.
    pub fn motion(&self) -> Option<PrimitiveMotion> {
        self.path.as_ref().map(FallPath::motion)
    }

    /// True once on the ground.
    pub fn landed(&self) -> bool {
        self.path.as_ref().is_some_and(FallPath::landed)
    }
}

/// Why a [`FallingObject`] does not fall: its description is invalid (the error names the
/// field), or where it was let go is (checked by [`FallRelease::validate`]): a `Transform`
/// whose translation is not finite or beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE)
/// (`release.position`), a zero or non-finite rotation (`release.rotation`), or a
/// [`FreeFallSettings::ground_height`] that is not finite (`release.ground`). Inserted in place
/// of a fall (logged once), removed once the component is changed and valid; the crate's one
/// convention for runtime failures, as [`ClothInvalid`](crate::cloth::ClothInvalid),
/// [`PhysicalClothInvalid`](crate::aero::PhysicalClothInvalid) and
/// [`AeroBodyInvalid`](crate::aero::AeroBodyInvalid).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::freefall::FallingObjectInvalid;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// // Lighter than air: it cannot fall.
/// let balloon = app
///     .world_mut()
///     .spawn(FallingObject { density: 0.5, ..default() })
///     .id();
/// app.update();
/// let invalid = app.world().get::<FallingObjectInvalid>(balloon).unwrap();
/// assert_eq!(invalid.0.field(), "density");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct FallingObjectInvalid(pub FreeFallError);

/// Sent when a [`FallingObject`] reaches the ground.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// fn rustle(mut landed: MessageReader<Landed>) {
///     for l in landed.read() {
///         info!("{} landed at {} after {:.1} s", l.entity, l.position, l.flight_time);
///     }
/// }
/// App::new()
///     .add_plugins((MinimalPlugins, WindfallPlugins))
///     .add_systems(Update, rustle);
/// ```
#[derive(Message, Clone, Copy, Debug, PartialEq)]
pub struct Landed {
    /// The object.
    pub entity: Entity,
    /// Where it came to rest.
    pub position: Vec3,
    /// Seconds since it was released.
    pub flight_time: f32,
}

/// Shared settings of every fall.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // A table top 0.75 m up.
/// App::new()
///     .add_plugins((MinimalPlugins, WindfallPlugins))
///     .insert_resource(FreeFallSettings { ground_height: 0.75 });
/// ```
#[derive(Resource, Clone, Debug, PartialEq, Default, Reflect)]
#[reflect(Resource, Default, Debug)]
pub struct FreeFallSettings {
    /// Height of the ground, m: objects stop there.
    pub ground_height: f32,
}

/// Moves every [`FallingObject`] on the fixed timestep and poses it once per frame.
#[derive(Default)]
pub struct FreeFallPlugin;

impl Plugin for FreeFallPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        let schedule = crate::simulation_schedule(app);
        if !app.world().contains_resource::<FallModel>() {
            app.insert_resource(FallModel::default());
        }
        app.register_type::<FallingObject>()
            .register_type::<FallState>()
            .register_type::<FallingObjectInvalid>()
            .register_type::<FreeFallSettings>()
            .register_type::<FallLod>()
            .register_type::<crate::lod::LodInvalid>()
            .register_type::<LodFocus>()
            .register_type::<crate::lod::LodView>()
            .register_type::<crate::lod::LodTiers>()
            .register_type::<FallModel>()
            .register_type::<super::FallPreset>()
            .init_resource::<FreeFallSettings>()
            .init_resource::<FallClock>()
            .add_message::<Landed>()
            .add_observer(release_on_insert)
            // Every system runs only when there is something for it: a system the executor hands
            // to a worker costs a thread wake-up even when it has nothing to do.
            .add_systems(
                schedule,
                step_objects
                    .in_set(WindfallSystems::Simulate)
                    .run_if(any_with_component::<FallingObject>),
            )
            // Releasing here (not in the simulation) reads the transform the user set this
            // frame before `pose_objects` would overwrite it.
            .add_systems(
                PostUpdate,
                (
                    (release_objects, pose_objects)
                        .chain()
                        .run_if(any_with_component::<FallingObject>),
                    crate::lod::check_tiers::<FallLod>.run_if(crate::lod::any_tiers::<FallLod>),
                )
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}

fn release_objects(
    mut commands: Commands,
    mut objects: Query<
        (Entity, &FallingObject, &Transform, &mut FallState),
        Changed<FallingObject>,
    >,
    settings: Option<Res<FreeFallSettings>>,
    model: Option<Res<FallModel>>,
) {
    // Without a model (removed by the user) nothing can be released; the default ground.
    let Some(model) = model else {
        return;
    };
    let settings = settings.as_deref().cloned().unwrap_or_default();
    for (entity, object, transform, mut state) in &mut objects {
        if state.released_for.as_ref() != Some(object) {
            release(
                &mut commands,
                entity,
                object,
                transform,
                &mut state,
                &settings,
                &model,
            );
        }
    }
}

/// Sets a [`FallingObject`] up the moment it is inserted, so it is falling (and its
/// [`FallState`] filled in) in the frame it was spawned.
fn release_on_insert(
    event: On<Insert, FallingObject>,
    mut commands: Commands,
    mut objects: Query<(&FallingObject, &Transform, &mut FallState)>,
    settings: Option<Res<FreeFallSettings>>,
    model: Option<Res<FallModel>>,
) {
    let Some(model) = model else {
        return;
    };
    let settings = settings.as_deref().cloned().unwrap_or_default();
    if let Ok((object, transform, mut state)) = objects.get_mut(event.entity) {
        release(
            &mut commands,
            event.entity,
            object,
            transform,
            &mut state,
            &settings,
            &model,
        );
    }
}

/// Lets `object` go from `transform`; a fall released again in mid-air keeps the velocity the
/// fluid gave it. An invalid object gets a [`FallingObjectInvalid`] (logged once) and stays
/// where it is.
fn release(
    commands: &mut Commands,
    entity: Entity,
    object: &FallingObject,
    transform: &Transform,
    state: &mut FallState,
    settings: &FreeFallSettings,
    model: &FallModel,
) {
    let velocity = state
        .path
        .as_ref()
        .filter(|p| !p.landed())
        .map_or(Vec3::ZERO, FallPath::drift);
    let release = FallRelease {
        position: transform.translation,
        rotation: Some(transform.rotation),
        velocity,
        ground: settings.ground_height,
    };
    let fall = object
        .regime()
        .and_then(|regime| Ok((regime, object.path(model, release)?)));
    *state = match fall {
        Ok((regime, path)) => {
            commands.entity(entity).remove::<FallingObjectInvalid>();
            FallState {
                regime: Some(regime),
                path: Some(path),
                released_for: Some(object.clone()),
                tier: None,
            }
        }
        Err(error) => {
            bevy::log::warn!("FallingObject {entity}: {error}; it does not fall");
            commands.entity(entity).insert(FallingObjectInvalid(error));
            FallState {
                regime: None,
                path: None,
                released_for: Some(object.clone()),
                tier: None,
            }
        }
    };
}

/// Steps every fall; objects are independent, so they run in parallel (with Bevy's
/// `multi_threaded` feature) and the landings are written sorted by entity, so the messages do
/// not depend on the thread schedule. An object with [`FallLod`] is stepped when its tier is due
/// (see [`crate::lod`]), over the time since its last step.
#[allow(clippy::too_many_arguments)]
fn step_objects(
    mut objects: Query<(Entity, &FallingObject, &mut FallState, Option<&FallLod>)>,
    foci: crate::lod::Foci,
    wind: Option<Res<WindField>>,
    model: Option<Res<FallModel>>,
    time: Res<Time>,
    mut clock: ResMut<FallClock>,
    mut landed: MessageWriter<Landed>,
    mut warned: Local<bool>,
) {
    // The model may have been removed: the falls wait, with one warning, until it is back.
    let Some(model) = model else {
        if !std::mem::replace(&mut *warned, true) {
            bevy::log::warn!("FallModel was removed: falling objects hold still until it is back");
        }
        return;
    };
    *warned = false;
    let dt = time.delta_secs();
    clock.tick(dt);
    let clock = *clock;
    let focus = crate::lod::focus(&foci);
    let wind = wind.as_deref();
    let reference_speed = wind.map_or(1.0, |w| w.config().reference_speed);
    let landings = Mutex::new(Vec::new());
    objects
        .par_iter_mut()
        .for_each(|(entity, object, mut state, lod)| {
            let state = &mut *state;
            let Some(path) = state.path.as_mut() else {
                return;
            };
            // Its first step with levels of detail is taken at once (a fall just let go does
            // not wait for its turn), as if it had been stepped on the step before.
            let first = state.tier.is_none() && lod.is_some();
            if first {
                state.tier = Some(TierClock::stepped_at(clock.seconds - f64::from(dt), dt));
            }
            let tier = lod
                .zip(focus)
                .map_or(1, |(l, f)| f.tier(&l.0, path.position()));
            if !first && !clock.due(tier, entity.index_u32()) {
                return;
            }
            // Resting objects feel the wind too: a strong enough one lifts them again.
            let velocity = wind.map_or(Vec3::ZERO, |w| w.velocity(path.position()));
            let tilt = WindTilt {
                max_angle: object.wind_tilt,
                reference_speed,
            };
            let outcome = match state.tier.as_mut() {
                Some(t) => {
                    let next = clock.steps_to_next(tier, entity.index_u32()) as f32 * dt;
                    let (outcome, _) =
                        t.advance(path, &model, clock.seconds, next, velocity, &tilt);
                    // Back at full detail for good (the component was removed) once eased.
                    if lod.is_none() && !t.easing(clock.seconds) {
                        state.tier = None;
                    }
                    outcome
                }
                None => path.advance(&model, dt, velocity, &tilt),
            };
            if outcome == StepOutcome::Landed {
                let message = Landed {
                    entity,
                    position: path.position(),
                    flight_time: path.time(),
                };
                landings
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .push(message);
            }
        });
    let mut landings = landings
        .into_inner()
        .unwrap_or_else(PoisonError::into_inner);
    landings.sort_by_key(|l| l.entity);
    landed.write_batch(landings);
}

fn pose_objects(
    mut objects: Query<(&FallState, &mut Transform)>,
    schedule: Option<Res<crate::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    clock: Option<Res<FallClock>>,
) {
    let s = crate::overstep(schedule.as_deref(), time.as_deref());
    let clock = clock.as_deref().copied().unwrap_or_default();
    let now = clock.seconds + f64::from(s * clock.last_dt);
    objects.par_iter_mut().for_each(|(state, mut transform)| {
        if let Some(path) = state.path() {
            let (position, rotation): (Vec3, Quat) = match &state.tier {
                Some(tier) => tier.shown(path, now),
                None => path.smoothed(s),
            };
            transform.translation = position;
            transform.rotation = rotation;
        }
    });
}
