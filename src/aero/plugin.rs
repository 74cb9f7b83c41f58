//! ECS glue: [`AeroBody`] (a rigid plate moved by gravity, lift and drag), its [`AeroState`],
//! and the [`AeroPlugin`].

use bevy::app::{App, FixedUpdate, Plugin, PostUpdate, PreUpdate};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::mesh::{Mesh, Mesh3d};
use bevy::time::{Fixed, Time};
use bevy::transform::components::{GlobalTransform, Transform};

use super::cloth::{ParticleCloth, Pinning};
use super::plate::{AeroCoefficients, AeroError, PlateState, RigidPlate};
use crate::WindfallSystems;
use crate::cloth::{ClothGrid, cloth_mesh, write_cloth_mesh};
use crate::wind::WindField;

/// A physically driven rigid plate (a leaf, card or coin): gravity plus per-face lift and drag
/// in the [`WindField`] (still air without one). It starts from its [`Transform`] at rest;
/// set [`AeroState::state`] for another start. The transform follows the body every fixed step.
#[derive(Component, Clone, Debug)]
#[require(Transform, AeroState)]
pub struct AeroBody {
    /// Faces, mass, inertia and coefficients.
    pub plate: RigidPlate,
    /// m/s².
    pub gravity: Vec3,
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
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct AeroState {
    /// Position, velocity, orientation and spin.
    pub state: PlateState,
    started: bool,
}

impl AeroState {
    /// Starts the body from `state` instead of its transform at rest.
    pub fn new(state: PlateState) -> Self {
        Self {
            state,
            started: true,
        }
    }
}

/// A physically simulated flag or curtain: a [`ParticleCloth`] in the entity's local frame
/// (x along the yarns, y up, pinned at x = 0 or y = 0), with gravity and lift and drag from the
/// [`WindField`]. [`AeroPlugin`] adds a [`PhysicalClothState`] and a [`Mesh3d`] (when the app has
/// `Assets<Mesh>`); give it a material. Changing the component rebuilds the cloth; an invalid
/// one gets a [`PhysicalClothInvalid`].
#[derive(Component, Clone, Copy, Debug, PartialEq)]
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

/// Runtime state of a [`PhysicalCloth`].
#[derive(Component, Clone, Debug)]
pub struct PhysicalClothState(pub ParticleCloth);

/// Why a [`PhysicalCloth`] has no state.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PhysicalClothInvalid(pub AeroError);

/// Moves every [`AeroBody`] and [`PhysicalCloth`] on the fixed timestep.
pub struct AeroPlugin;

impl Plugin for AeroPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        app.add_systems(PreUpdate, init_cloths)
            .add_systems(
                FixedUpdate,
                (step_bodies, step_cloths).in_set(WindfallSystems::Simulate),
            )
            .add_systems(PostUpdate, write_cloth_meshes);
    }
}

fn init_cloths(
    mut commands: Commands,
    cloths: Query<(Entity, &PhysicalCloth), Changed<PhysicalCloth>>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    for (entity, cloth) in &cloths {
        let mut e = commands.entity(entity);
        match ParticleCloth::new(
            cloth.grid,
            cloth.areal_density,
            cloth.coefficients,
            cloth.pinning,
        ) {
            Ok(sim) => {
                if let Some(meshes) = meshes.as_deref_mut() {
                    let mesh = cloth_mesh(cloth.grid.rows, cloth.grid.columns, sim.positions());
                    e.insert(Mesh3d(meshes.add(mesh)));
                }
                e.remove::<PhysicalClothInvalid>()
                    .insert(PhysicalClothState(sim));
            }
            Err(error) => {
                e.remove::<PhysicalClothState>()
                    .insert(PhysicalClothInvalid(error));
            }
        }
    }
}

fn step_cloths(
    mut cloths: Query<(&mut PhysicalClothState, &GlobalTransform)>,
    wind: Option<Res<WindField>>,
    time: Res<Time<Fixed>>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    for (mut state, transform) in &mut cloths {
        let affine = transform.affine();
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

fn write_cloth_meshes(
    cloths: Query<(&PhysicalCloth, &PhysicalClothState, &Mesh3d)>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    for (cloth, state, mesh) in &cloths {
        if let Some(mut mesh) = meshes.get_mut(&mesh.0) {
            let g = cloth.grid;
            write_cloth_mesh(&mut mesh, g.rows, g.columns, state.0.positions());
        }
    }
}

fn step_bodies(
    mut bodies: Query<(&AeroBody, &mut AeroState, &mut Transform)>,
    wind: Option<Res<WindField>>,
    time: Res<Time<Fixed>>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    bodies
        .par_iter_mut()
        .for_each(|(body, mut state, mut transform)| {
            if !state.started {
                state.started = true;
                state.state.position = transform.translation;
                state.state.rotation = transform.rotation;
            }
            let s = &mut state.state;
            match wind {
                Some(w) => body
                    .plate
                    .step(s, dt, body.gravity, &|p| w.velocity(p), false),
                None => body.plate.step(s, dt, body.gravity, &|_| Vec3::ZERO, true),
            }
            transform.translation = s.position;
            transform.rotation = s.rotation;
        });
}
