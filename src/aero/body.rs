//! [`AeroBody`]: a rigid plate moved by gravity, lift and drag, its runtime [`AeroState`] and
//! its [`AeroBodyInvalid`] marker, and the systems that step and pose it.

use std::sync::{Mutex, PoisonError};

use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use super::plate::{PlateState, RigidPlate};
use crate::error::InvalidValue;
use crate::wind::WindField;

/// A physically driven rigid plate (a leaf, card or coin): gravity plus per-face lift and drag
/// in the [`WindField`] (still air without one). It starts from its [`Transform`] at rest;
/// set [`AeroState::state`] for another start. The transform is posed between its last two fixed
/// steps every frame.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// # use bevy::time::TimeUpdateStrategy;
/// # app.insert_resource(TimeUpdateStrategy::ManualDuration(std::time::Duration::from_millis(17)));
/// // A business card dropped from 3 m.
/// let plate =
///     RigidPlate::rectangle(0.085, 0.055, 3e-4, 700.0, AeroCoefficients::default(), 2)?;
/// let card = app
///     .world_mut()
///     .spawn((AeroBody::new(plate), Transform::from_xyz(0.0, 3.0, 0.0)))
///     .id();
/// for _ in 0..10 {
///     app.update();
/// }
/// assert!(app.world().get::<Transform>(card).unwrap().translation.y < 3.0);
/// # Ok::<(), bevy_windfall::aero::AeroError>(())
/// ```
#[derive(Component, Clone, Debug, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform, AeroState)]
pub struct AeroBody {
    /// Faces, mass, inertia and coefficients.
    pub plate: RigidPlate,
    /// m/s².
    pub gravity: Vec3,
}

impl Default for AeroBody {
    /// A 7.3 × 4.2 cm leaf, 0.3 mm thick, 500 kg/m³, 2 × 2 faces, in air.
    fn default() -> Self {
        Self::new(
            RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2)
                .expect("a valid leaf"),
        )
    }
}

impl AeroBody {
    /// A body under standard gravity.
    pub fn new(plate: RigidPlate) -> Self {
        Self {
            plate,
            gravity: Vec3::new(0.0, -9.81, 0.0),
        }
    }
}

/// Runtime state of an [`AeroBody`] (required component).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::aero::PlateState;
///
/// // A leaf thrown sideways at 3 m/s instead of starting at rest.
/// let start = PlateState {
///     position: Vec3::new(0.0, 2.0, 0.0),
///     velocity: Vec3::new(3.0, 0.0, 0.0),
///     ..default()
/// };
/// let leaf = (AeroBody::default(), AeroState::new(start));
/// # let _ = leaf;
/// ```
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct AeroState {
    /// Position, velocity, orientation and spin.
    pub state: PlateState,
    started: bool,
    /// Position and orientation one fixed step ago: the pose between steps is interpolated.
    previous: (Vec3, Quat),
}

impl AeroState {
    /// Starts the body from `state` instead of its transform at rest.
    pub fn new(state: PlateState) -> Self {
        Self {
            state,
            started: true,
            previous: (state.position, state.rotation),
        }
    }

    /// The pose a fraction `s` ∈ [0, 1] of the way from the last fixed step to the current one.
    pub fn interpolated(&self, s: f32) -> (Vec3, Quat) {
        let s = if s.is_finite() {
            s.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let (p0, q0) = self.previous;
        (
            p0.lerp(self.state.position, s),
            q0.slerp(self.state.rotation, s).normalize(),
        )
    }
}

/// Why an [`AeroBody`] holds still (logged once as a warning, removed when it can move again):
/// a start [`Transform`] or an [`AeroState`] that is not finite or lies beyond
/// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) (field `state.position`), a zero quaternion
/// (`state.rotation`), velocities beyond [`PlateState::MAX_SPEED`](crate::aero::PlateState::MAX_SPEED), or a
/// non-finite or huge [`AeroBody::gravity`] (`gravity`).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::aero::AeroBodyInvalid;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let lost = app
///     .world_mut()
///     .spawn((AeroBody::default(), Transform::from_xyz(f32::NAN, 2.0, 0.0)))
///     .id();
/// app.world_mut().run_schedule(FixedUpdate);
/// let invalid = app.world().get::<AeroBodyInvalid>(lost).unwrap();
/// assert_eq!(invalid.0.field(), "state.position");
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct AeroBodyInvalid(pub AeroError);

/// Largest |gravity| an [`AeroBody`] accepts, m/s².
const MAX_GRAVITY: f32 = 1.0e4;

impl AeroBody {
    /// Checks what a step needs: `gravity` and the state the body is in (or starts from).
    fn check(&self, state: &PlateState) -> Result<(), AeroError> {
        let g = crate::guard::largest_component(self.gravity);
        InvalidValue::check(
            g.abs() <= MAX_GRAVITY,
            "gravity",
            g,
            crate::error::reason!("must be finite and within ±{MAX_GRAVITY:e} m/s²"),
        )?;
        state.validate()
    }
}

crate::lifecycle::invalid_marker!(AeroBodyInvalid, AeroError);

pub(super) fn step_bodies(
    mut commands: Commands,
    mut bodies: Query<(
        Entity,
        &AeroBody,
        &mut AeroState,
        &Transform,
        Has<AeroBodyInvalid>,
    )>,
    wind: Option<Res<WindField>>,
    time: Res<Time>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    let verdicts = Mutex::new(Vec::new());
    bodies
        .par_iter_mut()
        .for_each(|(entity, body, mut state, transform, flagged)| {
            if !state.started {
                // Started from the transform; a bad one waits (reported) until it is fixed.
                state.state.position = transform.translation;
                state.state.rotation = transform.rotation;
            }
            let verdict = body.check(&state.state);
            if verdict.is_err() != flagged {
                verdicts
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .push((entity, verdict.err()));
            }
            let Some(rotation) = crate::guard::unit_quat(state.state.rotation) else {
                return;
            };
            if verdict.is_err() {
                return;
            }
            state.state.rotation = rotation;
            state.started = true;
            state.previous = (state.state.position, state.state.rotation);
            let s = &mut state.state;
            match wind {
                Some(w) => body
                    .plate
                    .step(s, dt, body.gravity, &|p| w.velocity(p), false),
                None => body.plate.step(s, dt, body.gravity, &|_| Vec3::ZERO, true),
            }
            if !state.state.position.is_finite() || !state.state.rotation.is_finite() {
                // The plate's step keeps a valid state finite; should it not, hold still.
                state.state = PlateState {
                    position: state.previous.0,
                    rotation: state.previous.1,
                    ..PlateState::default()
                };
            }
        });
    let mut verdicts = verdicts
        .into_inner()
        .unwrap_or_else(PoisonError::into_inner);
    verdicts.sort_by_key(|v| v.0);
    for (entity, verdict) in verdicts {
        match verdict {
            // Only the entities whose verdict changed were collected: a new error is logged once.
            Some(error) => crate::lifecycle::mark::<AeroBodyInvalid>(
                &mut commands,
                entity,
                Err(error),
                None,
                "AeroBody",
                "it holds still",
            ),
            None => {
                commands.entity(entity).try_remove::<AeroBodyInvalid>();
            }
        }
    }
}

/// Poses every started [`AeroBody`] between its last two fixed steps, by how far the frame is
/// into the next step: motion looks smooth at any frame rate.
pub(super) fn pose_bodies(
    mut bodies: Query<(&AeroState, &mut Transform)>,
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
) {
    let s = crate::schedule::overstep(schedule.as_deref(), time.as_deref());
    bodies.par_iter_mut().for_each(|(state, mut transform)| {
        if state.started {
            let (position, rotation) = state.interpolated(s);
            transform.translation = position;
            transform.rotation = rotation;
        }
    });
}
