//! ECS glue: the [`Cloth`] component, its runtime [`ClothState`], and the [`ClothPlugin`].

use bevy::app::{App, FixedUpdate, Plugin, PostUpdate, PreUpdate};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::mesh::{Mesh, Mesh3d};
use bevy::time::{Fixed, Time};
use bevy::transform::components::{GlobalTransform, Transform};

use super::mesh::{cloth_mesh, write_cloth_mesh};
use super::params::{ClothError, ClothGrid, ClothParams};
use super::sim::{ClothAttachment, ClothSim};
use crate::WindfallSystems;
use crate::wind::WindField;

/// A flag, banner or curtain. Its node grid is in the entity's local frame (see
/// [`ClothAttachment`]); [`ClothPlugin`] adds a [`ClothState`] and a [`Mesh3d`] (when the app has
/// `Assets<Mesh>`). Give the entity a material to see it. Changing the component rebuilds the
/// cloth; an invalid one gets a [`ClothInvalid`] instead of a state.
#[derive(Component, Clone, Debug, PartialEq)]
#[require(Transform)]
pub struct Cloth {
    /// Size and resolution.
    pub grid: ClothGrid,
    /// Motion parameters (see [`ClothPreset`](super::ClothPreset)).
    pub params: ClothParams,
    /// Pole (flag, banner) or rod (curtain).
    pub attachment: ClothAttachment,
    /// With a [`WindField`], take speed (and, on a pole, direction) from the wind at the
    /// entity's origin instead of `params.wind_speed`.
    pub follow_wind: bool,
}

impl Default for Cloth {
    fn default() -> Self {
        Self {
            grid: ClothGrid::default(),
            params: ClothParams::default(),
            attachment: ClothAttachment::Pole,
            follow_wind: true,
        }
    }
}

/// Runtime state of a [`Cloth`]: the simulation and the direction the cloth streams in.
#[derive(Component, Clone)]
pub struct ClothState {
    /// The shape over time.
    pub sim: ClothSim,
    /// Rotation about the pole (local Y), radians: the cloth turns to stream downwind.
    pub yaw: f32,
    /// Noise steps per paper frame used in the last step (|v|).
    pub wind_speed: f32,
}

/// Why a [`Cloth`] has no [`ClothState`].
#[derive(Component, Clone, Debug, PartialEq)]
pub struct ClothInvalid(pub ClothError);

/// Moves every [`Cloth`] on the fixed timestep and rewrites its mesh once per frame.
pub struct ClothPlugin;

impl Plugin for ClothPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        app.add_systems(PreUpdate, init_cloths)
            .add_systems(FixedUpdate, step_cloths.in_set(WindfallSystems::Simulate))
            .add_systems(PostUpdate, write_cloth_meshes);
    }
}

/// The shift |v| (noise cells per paper frame) for wind of `speed` m/s on a cloth whose yarns are
/// `length` m long: the waves run at the wind's speed ([`air_speed`](super::air_speed)); capped
/// at 50 cells per frame.
pub fn wind_steps_per_frame(speed: f32, length: f32) -> f32 {
    super::sim::steps_for_speed(speed, length).clamp(0.0, 50.0)
}

fn init_cloths(
    mut commands: Commands,
    cloths: Query<(Entity, &Cloth, Option<&Mesh3d>), Changed<Cloth>>,
    meshes: Option<ResMut<Assets<Mesh>>>,
) {
    let mut meshes = meshes;
    for (entity, cloth, mesh) in &cloths {
        let mut e = commands.entity(entity);
        match ClothSim::new(cloth.grid, cloth.params, cloth.attachment) {
            Ok(sim) => {
                if let Some(meshes) = meshes.as_deref_mut() {
                    let (rows, columns) = (cloth.grid.rows, cloth.grid.columns);
                    let fresh = cloth_mesh(rows, columns, sim.positions());
                    let existing = mesh.filter(|m| meshes.contains(&m.0));
                    match existing {
                        Some(m) => {
                            if let Some(mut slot) = meshes.get_mut(&m.0) {
                                *slot = fresh;
                            }
                        }
                        None => {
                            e.insert(Mesh3d(meshes.add(fresh)));
                        }
                    }
                }
                e.remove::<ClothInvalid>().insert(ClothState {
                    wind_speed: cloth.params.wind_speed,
                    sim,
                    yaw: 0.0,
                });
            }
            Err(error) => {
                e.remove::<ClothState>().insert(ClothInvalid(error));
            }
        }
    }
}

/// Seconds over which a cloth turns to a new wind direction.
const TURN_TIME: f32 = 0.6;

fn step_cloths(
    time: Res<Time<Fixed>>,
    wind: Option<Res<WindField>>,
    mut cloths: Query<(&Cloth, &mut ClothState, &GlobalTransform)>,
) {
    let dt = time.delta_secs();
    for (cloth, mut state, transform) in &mut cloths {
        let mut speed = cloth.params.wind_speed;
        if let Some(wind) = wind.as_deref().filter(|_| cloth.follow_wind) {
            let v = wind.velocity(transform.translation());
            let local = transform.affine().inverse().transform_vector3(v);
            let horizontal = Vec3::new(local.x, 0.0, local.z);
            speed = wind_steps_per_frame(horizontal.length(), cloth.grid.width);
            if cloth.attachment == ClothAttachment::Pole && horizontal.length() > 1e-3 {
                let target = (-horizontal.z).atan2(horizontal.x);
                let turn = (target - state.yaw + std::f32::consts::PI)
                    .rem_euclid(std::f32::consts::TAU)
                    - std::f32::consts::PI;
                state.yaw += turn * (1.0 - (-dt / TURN_TIME).exp());
            }
        }
        state.wind_speed = speed;
        state.sim.advance(dt, speed);
    }
}

fn write_cloth_meshes(
    mut cloths: Query<(&Cloth, &mut ClothState, &Mesh3d)>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
    mut rotated: Local<Vec<Vec3>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    for (cloth, mut state, mesh) in &mut cloths {
        state.sim.rebuild();
        let Some(mut mesh) = meshes.get_mut(&mesh.0) else {
            continue;
        };
        let turn = Quat::from_rotation_y(state.yaw);
        rotated.clear();
        rotated.extend(state.sim.positions().iter().map(|&p| turn * p));
        write_cloth_mesh(&mut mesh, cloth.grid.rows, cloth.grid.columns, &rotated);
    }
}
