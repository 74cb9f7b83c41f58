//! [`PhysicalCloth`]: a [`ParticleCloth`] flag or curtain placed by its entity, its runtime
//! state and marker, its lifecycle, and the systems that step it and write its mesh.

use bevy::asset::Assets;
use bevy::diagnostic::FrameCount;
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::mesh::{Mesh, Mesh3d};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};
use bevy::transform::components::{GlobalTransform, Transform};

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use super::particles::{ParticleCloth, Pinning};
use crate::cloth::{ClothGrid, mesh};
use crate::lifecycle::Described;
use crate::wind::WindField;

/// A physically simulated flag or curtain: a [`ParticleCloth`] in the entity's local frame
/// (x along the yarns, y up, pinned at x = 0 or y = 0), with gravity and lift and drag from the
/// [`WindField`]. [`AeroPlugin`](super::plugin::AeroPlugin) adds a [`PhysicalClothState`] and a [`Mesh3d`] (when the app has
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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
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
pub(super) struct PreviousPositions(Vec<Vec3>);

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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let weightless = PhysicalCloth { areal_density: 0.0, ..default() };
/// let cloth = app.world_mut().spawn(weightless).id();
/// app.update();
/// let invalid = app.world().get::<PhysicalClothInvalid>(cloth).unwrap();
/// assert_eq!(invalid.0.field(), "areal_density");
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct PhysicalClothInvalid(pub AeroError);

crate::lifecycle::invalid_marker!(PhysicalClothInvalid, AeroError);

impl Described for PhysicalCloth {
    type Invalid = PhysicalClothInvalid;
    type Key = PhysicalCloth;
    type Data = ();
    type Context = Option<ResMut<'static, Assets<Mesh>>>;
    const SUBJECT: &'static str = "PhysicalCloth";
    const CONSEQUENCE: &'static str = "it is not simulated";
    /// The transform is checked every step ([`AeroPlugin`](super::AeroPlugin)).
    const SET_UP_CHECKS_TRANSFORM: bool = false;

    fn key(&self) -> PhysicalCloth {
        *self
    }

    /// Builds the particles and, with `Assets<Mesh>`, a mesh.
    fn set_up(
        &self,
        entity: Entity,
        _: (),
        meshes: &mut Option<ResMut<Assets<Mesh>>>,
        commands: &mut Commands,
    ) -> Option<Result<(), AeroError>> {
        let mut e = commands.entity(entity);
        Some(
            match ParticleCloth::new(
                self.grid,
                self.areal_density,
                self.coefficients,
                self.pinning,
            ) {
                Ok(sim) => {
                    if let Some(meshes) = meshes {
                        let mesh = mesh::build(self.grid.rows, self.grid.columns, sim.positions());
                        e.try_insert(Mesh3d(meshes.add(mesh)));
                    }
                    e.try_insert((
                        PreviousPositions(sim.positions().to_vec()),
                        PhysicalClothState(sim),
                    ));
                    Ok(())
                }
                Err(error) => {
                    e.try_remove::<PhysicalClothState>();
                    Err(error)
                }
            },
        )
    }
}

pub(super) fn step_cloths(
    mut commands: Commands,
    mut cloths: Query<(
        Entity,
        &mut PhysicalClothState,
        &mut PreviousPositions,
        &GlobalTransform,
        Option<&PhysicalClothInvalid>,
    )>,
    wind: Option<Res<WindField>>,
    time: Res<Time>,
    frame: Option<Res<FrameCount>>,
    mut budget: Local<FrameBudget>,
    mut world: Local<Vec<Vec3>>,
) {
    let dt = budget.take(frame.map(|f| f.0), time.delta_secs());
    let wind = wind.as_deref();
    for (entity, mut state, mut previous, transform, invalid) in &mut cloths {
        previous.0.clear();
        previous.0.extend_from_slice(state.0.positions());
        let affine = transform.affine();
        // A transform that cannot place the cloth: it holds still, reported once.
        let placed = crate::guard::check_affine(&affine).map_err(AeroError::from);
        let bad = placed.is_err();
        crate::lifecycle::mark_on_change(
            &mut commands,
            entity,
            placed,
            invalid,
            "PhysicalCloth",
            "it holds still",
        );
        if bad {
            continue;
        }
        let inverse = affine.inverse();
        let gravity = inverse.transform_vector3(Vec3::new(0.0, -9.81, 0.0));
        // Read at the nodes' world positions all at once, turned into the local frame.
        let local_wind = |points: &[Vec3], velocities: &mut Vec<Vec3>| match wind {
            Some(w) => {
                world.clear();
                world.extend(points.iter().map(|p| affine.transform_point3(*p)));
                w.velocities(&world, velocities);
                for v in velocities.iter_mut() {
                    *v = inverse.transform_vector3(*v);
                }
            }
            None => {
                velocities.clear();
                velocities.resize(points.len(), Vec3::ZERO);
            }
        };
        if dt > 0.0 {
            state.0.step_batched(dt, gravity, local_wind);
        }
    }
}

/// What one rendered frame may simulate of the cloths: [`ParticleCloth::MAX_STEP`] over all
/// its fixed steps. After a hitch Bevy runs many fixed steps in one frame (up to its
/// `Time<Virtual>` maximum of 0.25 s: 62 ticks of 4 ms); the cloths take the first
/// 50 ms of them and hold still through the rest (the time is dropped, not owed), so a hitch
/// costs at most three frames' worth of cloth. The same rule holds every frame: a game running
/// below 20 frames a second sees its physical cloths in slow motion (at 15 fps, 75 % speed).
#[derive(Default)]
pub(super) struct FrameBudget {
    frame: Option<u32>,
    spent: f32,
}

impl FrameBudget {
    /// The part of a fixed step of `dt` seconds in frame `frame` that the budget allows.
    fn take(&mut self, frame: Option<u32>, dt: f32) -> f32 {
        if frame.is_none() || frame != self.frame {
            *self = Self { frame, spent: 0.0 };
        }
        if !(dt.is_finite() && dt > 0.0) {
            return dt;
        }
        let allowed = dt.min((ParticleCloth::MAX_STEP - self.spent).max(0.0));
        self.spent += allowed;
        allowed
    }
}

/// Writes each cloth's mesh between its last two fixed steps (by how far the frame is into the
/// next step), so it moves smoothly at any frame rate.
pub(super) fn write_cloth_meshes(
    cloths: Query<(
        &PhysicalCloth,
        &PhysicalClothState,
        &PreviousPositions,
        &Mesh3d,
    )>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    mut shown: Local<Vec<Vec3>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    let s = crate::schedule::overstep(schedule.as_deref(), time.as_deref());
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
            mesh::write(&mut mesh, g.rows, g.columns, &shown);
        }
    }
}
