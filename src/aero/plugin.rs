//! ECS glue: [`AeroBody`] (a rigid plate moved by gravity, lift and drag), its [`AeroState`],
//! and the [`AeroPlugin`].

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use std::sync::{Mutex, PoisonError};

use bevy::math::{Quat, Vec3};
use bevy::mesh::{Mesh, Mesh3d};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};
use bevy::transform::components::{GlobalTransform, Transform};

use super::cloth::{ParticleCloth, Pinning};
use super::plate::{AeroCoefficients, AeroError, PlateState, RigidPlate};
use crate::WindfallSystems;
use crate::cloth::{ClothGrid, cloth_mesh, write_cloth_mesh};
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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
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

/// A physically simulated flag or curtain: a [`ParticleCloth`] in the entity's local frame
/// (x along the yarns, y up, pinned at x = 0 or y = 0), with gravity and lift and drag from the
/// [`WindField`]. [`AeroPlugin`] adds a [`PhysicalClothState`] and a [`Mesh3d`] (when the app has
/// `Assets<Mesh>`); give it a material. Changing the component rebuilds the cloth; an invalid
/// one gets a [`PhysicalClothInvalid`].
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::aero::{PhysicalCloth, PhysicalClothState};
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// let flag = app
///     .world_mut()
///     .spawn((PhysicalCloth::default(), Transform::from_xyz(0.0, 5.0, 0.0)))
///     .id();
/// app.update();
/// let cloth = &app.world().get::<PhysicalClothState>(flag).unwrap().0;
/// assert!(cloth.max_strain() < 0.05);
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform)]
pub struct PhysicalCloth {
    /// Size and resolution (the procedural [`Cloth`](crate::cloth::Cloth)'s grid).
    pub grid: ClothGrid,
    /// kg/m² (flag fabric: about 0.1–0.2).
    pub areal_density: f32,
    /// Coefficients and fluid.
    pub coefficients: AeroCoefficients,
    /// Pole column or top row.
    pub pinning: Pinning,
}

impl Default for PhysicalCloth {
    fn default() -> Self {
        Self {
            grid: ClothGrid::default(),
            areal_density: 0.15,
            coefficients: AeroCoefficients::default(),
            pinning: Pinning::PoleColumn,
        }
    }
}

/// Runtime state of a [`PhysicalCloth`] (not reflected: the particles are the simulation's).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::aero::PhysicalClothState;
///
/// // How much the particle cloths stretch (XPBD keeps it small).
/// fn strain(cloths: Query<&PhysicalClothState>) -> f32 {
///     cloths.iter().map(|c| c.0.max_strain()).fold(0.0, f32::max)
/// }
/// # let _ = strain;
/// ```
#[derive(Component, Clone, Debug)]
pub struct PhysicalClothState(pub ParticleCloth);

/// The node positions one fixed step ago, so the mesh is drawn between steps.
#[derive(Component, Clone, Debug, Default)]
struct PreviousPositions(Vec<Vec3>);

/// Why a [`PhysicalCloth`] has no state (logged once as a warning when it appears), or, with
/// field `transform`, why it holds still: its global transform is not finite, not invertible
/// or beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) (removed once it is).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::aero::{PhysicalCloth, PhysicalClothInvalid};
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// let weightless = PhysicalCloth { areal_density: 0.0, ..default() };
/// let cloth = app.world_mut().spawn(weightless).id();
/// app.update();
/// let invalid = app.world().get::<PhysicalClothInvalid>(cloth).unwrap();
/// assert_eq!(invalid.0.field(), "areal_density");
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct PhysicalClothInvalid(pub AeroError);

/// Why an [`AeroBody`] holds still (logged once as a warning, removed when it can move again):
/// a start [`Transform`] or an [`AeroState`] that is not finite or lies beyond
/// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) (field `state.position`), a zero quaternion
/// (`state.rotation`), velocities beyond [`MAX_STATE_SPEED`](super::MAX_STATE_SPEED), or a
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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
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
        let g = self.gravity.abs().max_element();
        if g.is_nan() || g > MAX_GRAVITY {
            return Err(AeroError::Invalid {
                field: "gravity",
                value: g,
                reason: "must be finite and within ±1e4 m/s²",
            });
        }
        state.validate()
    }
}

/// Moves every [`AeroBody`] and [`PhysicalCloth`] on the fixed timestep.
pub struct AeroPlugin;

impl Plugin for AeroPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        let schedule = crate::simulation_schedule(app);
        app.register_type::<AeroBody>()
            .register_type::<AeroState>()
            .register_type::<AeroBodyInvalid>()
            .register_type::<PhysicalCloth>()
            .register_type::<PhysicalClothInvalid>()
            .add_observer(init_on_insert)
            // Each only with something to move (a system with nothing to do still costs a
            // wake-up).
            .add_systems(
                schedule,
                (
                    step_bodies.run_if(any_with_component::<AeroState>),
                    step_cloths.run_if(any_with_component::<PhysicalClothState>),
                )
                    .in_set(WindfallSystems::Simulate),
            )
            // Set up in the frame the cloth is added (or changed), before its mesh is written.
            .add_systems(
                PostUpdate,
                (
                    (init_cloths, write_cloth_meshes)
                        .chain()
                        .run_if(any_with_component::<PhysicalCloth>),
                    pose_bodies.run_if(any_with_component::<AeroState>),
                )
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}

/// The [`PhysicalCloth`] a state (or refusal) was made for.
#[derive(Component, Clone, Copy, Debug)]
struct BuiltFor(PhysicalCloth);

/// Sets up every physical cloth added or changed this frame.
fn init_cloths(
    mut commands: Commands,
    cloths: Query<(Entity, &PhysicalCloth, Option<&BuiltFor>), Changed<PhysicalCloth>>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    for (entity, cloth, built) in &cloths {
        if built.is_none_or(|b| b.0 != *cloth) {
            init_cloth(&mut commands, entity, cloth, meshes.as_deref_mut());
        }
    }
}

/// Sets a [`PhysicalCloth`] up the moment it is inserted: its state and mesh exist in the
/// frame it was spawned.
fn init_on_insert(
    event: On<Insert, PhysicalCloth>,
    mut commands: Commands,
    cloths: Query<(&PhysicalCloth, Option<&BuiltFor>)>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    if let Ok((cloth, built)) = cloths.get(event.entity)
        && built.is_none_or(|b| b.0 != *cloth)
    {
        init_cloth(&mut commands, event.entity, cloth, meshes.as_deref_mut());
    }
}

fn init_cloth(
    commands: &mut Commands,
    entity: Entity,
    cloth: &PhysicalCloth,
    meshes: Option<&mut Assets<Mesh>>,
) {
    let mut e = commands.entity(entity);
    e.insert(BuiltFor(*cloth));
    match ParticleCloth::new(
        cloth.grid,
        cloth.areal_density,
        cloth.coefficients,
        cloth.pinning,
    ) {
        Ok(sim) => {
            if let Some(meshes) = meshes {
                let mesh = cloth_mesh(cloth.grid.rows, cloth.grid.columns, sim.positions());
                e.insert(Mesh3d(meshes.add(mesh)));
            }
            e.remove::<PhysicalClothInvalid>().insert((
                PreviousPositions(sim.positions().to_vec()),
                PhysicalClothState(sim),
            ));
        }
        Err(error) => {
            bevy::log::warn!("PhysicalCloth {entity}: {error}; it is not simulated");
            e.remove::<PhysicalClothState>()
                .insert(PhysicalClothInvalid(error));
        }
    }
}

fn step_cloths(
    mut commands: Commands,
    mut cloths: Query<(
        Entity,
        &mut PhysicalClothState,
        &mut PreviousPositions,
        &GlobalTransform,
        Has<PhysicalClothInvalid>,
    )>,
    wind: Option<Res<WindField>>,
    time: Res<Time>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    for (entity, mut state, mut previous, transform, flagged) in &mut cloths {
        previous.0.clear();
        previous.0.extend_from_slice(state.0.positions());
        let affine = transform.affine();
        // A transform that cannot place the cloth: it holds still, reported once.
        let bad = crate::guard::bad_affine(&affine);
        if bad.is_some() != flagged {
            let mut e = commands.entity(entity);
            match bad {
                Some(value) => {
                    let error = AeroError::Invalid {
                        field: "transform",
                        value,
                        reason: "the global transform must be finite, invertible and within ±1e7 m",
                    };
                    bevy::log::warn!("PhysicalCloth {entity}: {error}; it holds still");
                    e.insert(PhysicalClothInvalid(error));
                }
                None => {
                    e.remove::<PhysicalClothInvalid>();
                }
            }
        }
        if bad.is_some() {
            continue;
        }
        let inverse = affine.inverse();
        let gravity = inverse.transform_vector3(Vec3::new(0.0, -9.81, 0.0));
        // Sampled at the node's world position, turned into the local frame.
        let local_wind = |p: Vec3| match wind {
            Some(w) => inverse.transform_vector3(w.velocity(affine.transform_point3(p))),
            None => Vec3::ZERO,
        };
        state.0.step(dt, gravity, &local_wind);
    }
}

/// Writes each cloth's mesh between its last two fixed steps (by how far the frame is into the
/// next step), so it moves smoothly at any frame rate.
fn write_cloth_meshes(
    cloths: Query<(
        &PhysicalCloth,
        &PhysicalClothState,
        &PreviousPositions,
        &Mesh3d,
    )>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
    schedule: Option<Res<crate::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    mut shown: Local<Vec<Vec3>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    let s = crate::overstep(schedule.as_deref(), time.as_deref());
    for (cloth, state, previous, mesh) in &cloths {
        if let Some(mut mesh) = meshes.get_mut(&mesh.0) {
            let g = cloth.grid;
            let now = state.0.positions();
            shown.clear();
            if previous.0.len() == now.len() {
                shown.extend(previous.0.iter().zip(now).map(|(a, b)| a.lerp(*b, s)));
            } else {
                shown.extend_from_slice(now);
            }
            write_cloth_mesh(&mut mesh, g.rows, g.columns, &shown);
        }
    }
}

fn step_bodies(
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
            Some(error) => {
                bevy::log::warn!("AeroBody {entity}: {error}; it holds still");
                commands.entity(entity).insert(AeroBodyInvalid(error));
            }
            None => {
                commands.entity(entity).remove::<AeroBodyInvalid>();
            }
        }
    }
}

/// Poses every started [`AeroBody`] between its last two fixed steps, by how far the frame is
/// into the next step: motion looks smooth at any frame rate.
fn pose_bodies(
    mut bodies: Query<(&AeroState, &mut Transform)>,
    schedule: Option<Res<crate::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
) {
    let s = crate::overstep(schedule.as_deref(), time.as_deref());
    bodies.par_iter_mut().for_each(|(state, mut transform)| {
        if state.started {
            let (position, rotation) = state.interpolated(s);
            transform.translation = position;
            transform.rotation = rotation;
        }
    });
}
