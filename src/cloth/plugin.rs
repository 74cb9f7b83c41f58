//! The [`ClothPlugin`]: steps every [`Cloth`] on the fixed timestep and rewrites its mesh once
//! per frame.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::mesh::{Mesh, Mesh3d};
use bevy::time::{Fixed, Time};
use bevy::transform::components::GlobalTransform;

use super::component::{Cloth, ClothInvalid, ClothLod, ClothState, Detail};
use super::mesh;
use super::params::ClothError;
use super::sim::{ClothAttachment, ClothSim};
use crate::lifecycle::set_up_changed;
use crate::schedule::{SimulateSystems, WindfallSystems};
use crate::wind::WindField;

crate::schedule::simulation_plugin!(
    /// Moves every [`Cloth`] on the fixed timestep and rewrites its mesh once per frame.
    ClothPlugin
);

impl Plugin for ClothPlugin {
    fn build(&self, app: &mut App) {
        let schedule = self.configure(app);
        crate::lifecycle::observe::<Cloth>(app);
        crate::lod::register_types(app);
        app.register_type::<Cloth>()
            .register_type::<ClothState>()
            .register_type::<ClothLod>()
            .register_type::<ClothInvalid>()
            .add_systems(
                PostUpdate,
                crate::lod::check_tiers::<ClothLod>
                    .run_if(crate::lod::any_tiers::<ClothLod>)
                    .in_set(WindfallSystems::WriteBack),
            )
            // Set up in the frame the cloth is added (or changed), before its mesh is written.
            // Only with a cloth (a system with nothing to do still costs a wake-up).
            .add_systems(
                PostUpdate,
                (set_up_changed::<Cloth>, write_cloth_meshes)
                    .chain()
                    .run_if(any_with_component::<Cloth>)
                    .in_set(WindfallSystems::WriteBack),
            )
            .add_systems(
                schedule,
                step_cloths
                    .run_if(any_with_component::<Cloth>)
                    .in_set(SimulateSystems::Cloth),
            );
    }
}

/// The fastest shift the wind gives a cloth, noise steps per paper frame.
const MAX_STEPS_PER_FRAME: f32 = 50.0;

/// Seconds over which a cloth turns to a new wind direction.
const TURN_TIME: f32 = 0.6;

fn step_cloths(
    mut commands: Commands,
    time: Res<Time>,
    wind: Option<Res<WindField>>,
    mut cloths: Query<(
        Entity,
        &Cloth,
        &mut ClothState,
        &GlobalTransform,
        Option<&ClothInvalid>,
    )>,
) {
    let dt = time.delta_secs();
    for (entity, cloth, mut state, transform, invalid) in &mut cloths {
        let mut speed = cloth.params.wind_steps_per_frame;
        let wind = wind.as_deref().filter(|_| cloth.follow_wind);
        let placed = match wind {
            Some(_) => crate::guard::check_affine(&transform.affine()).map_err(ClothError::from),
            None => Ok(()),
        };
        let bad = placed.is_err();
        crate::lifecycle::mark_on_change(
            &mut commands,
            entity,
            placed,
            invalid,
            "Cloth",
            "it flaps at its own wind_steps_per_frame",
        );
        if let Some(wind) = wind.filter(|_| !bad) {
            let v = wind.velocity(transform.translation());
            let local = transform.affine().inverse().transform_vector3(v);
            let horizontal = Vec3::new(local.x, 0.0, local.z);
            speed = ClothSim::steps_for_speed(horizontal.length(), cloth.grid.width)
                .clamp(0.0, MAX_STEPS_PER_FRAME);
            if cloth.attachment == ClothAttachment::Pole && horizontal.length() > 1e-3 {
                let target = (-horizontal.z).atan2(horizontal.x);
                let turn = (target - state.yaw + std::f32::consts::PI)
                    .rem_euclid(std::f32::consts::TAU)
                    - std::f32::consts::PI;
                state.yaw += turn * (1.0 - (-dt / TURN_TIME).exp());
            }
        }
        state.wind_steps_per_frame = speed;
        state.sim.advance(dt, speed);
    }
}

/// Rebuilds each cloth between its last two fixed steps (by how far the frame is into the next
/// step), on the grid its [`ClothLod`] picks, and rewrites its mesh in place.
#[allow(clippy::too_many_arguments)]
fn write_cloth_meshes(
    mut cloths: Query<(
        &Cloth,
        &mut ClothState,
        &Mesh3d,
        &GlobalTransform,
        Option<&ClothLod>,
    )>,
    foci: crate::lod::Foci,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
    schedule: Option<Res<crate::schedule::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    frame: Option<Res<Time>>,
    mut rotated: Local<Vec<Vec3>>,
    mut faded: Local<Vec<Vec3>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    let s = crate::schedule::overstep(schedule.as_deref(), time.as_deref());
    let dt = frame.map_or(0.0, |t| t.delta_secs());
    let focus = crate::lod::focus(&foci);
    for (cloth, mut state, mesh, transform, lod) in &mut cloths {
        let state = &mut *state;
        let target =
            lod.zip(focus)
                .map_or(1, |(l, f)| f.tier(&l.0, transform.translation())) as usize;
        state.detail.update(target, dt);
        let Detail { stride, from, fade } = state.detail;
        if fade < 1.0 {
            state.sim.rebuild_at_stride(s, from);
            faded.clear();
            faded.extend_from_slice(state.sim.positions());
            state.sim.rebuild_at_stride(s, stride);
            state
                .sim
                .fade_from(&faded, fade * fade * (3.0 - 2.0 * fade));
        } else {
            state.sim.rebuild_at_stride(s, stride);
        }
        let Some(mut mesh) = meshes.get_mut(&mesh.0) else {
            continue;
        };
        let turn = Quat::from_rotation_y(state.yaw);
        rotated.clear();
        rotated.extend(state.sim.positions().iter().map(|&p| turn * p));
        mesh::write(&mut mesh, cloth.grid.rows, cloth.grid.columns, &rotated);
    }
}
