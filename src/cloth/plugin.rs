//! ECS glue: the [`Cloth`] component, its runtime [`ClothState`], and the [`ClothPlugin`].

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::math::{Quat, Vec3};
use bevy::mesh::{Mesh, Mesh3d};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::{Fixed, Time};
use bevy::transform::components::{GlobalTransform, Transform};

use super::mesh::{cloth_mesh, write_cloth_mesh};
use super::params::{ClothError, ClothGrid, ClothParams};
use super::sim::{ClothAttachment, ClothSim};
use crate::WindfallSystems;
use crate::lod::{LodFocus, LodTiers};
use crate::wind::WindField;

/// A flag, banner or curtain. Its node grid is in the entity's local frame (see
/// [`ClothAttachment`]); [`ClothPlugin`] adds a [`ClothState`] and a [`Mesh3d`] (when the app has
/// `Assets<Mesh>`). Give the entity a material to see it. Changing the component rebuilds the
/// cloth; an invalid one gets a [`ClothInvalid`] instead of a state.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// // A 1.5 × 1 m flag on a pole whose top is 6 m up, in the wind of the field.
/// let flag = app
///     .world_mut()
///     .spawn((
///         Cloth {
///             grid: ClothGrid { rows: 16, columns: 24, width: 1.5, height: 1.0 },
///             params: ClothPreset::FlagGentleFrozen.params(),
///             ..default()
///         },
///         Transform::from_xyz(0.0, 6.0, 0.0),
///     ))
///     .id();
/// app.update();
/// let state = app.world().get::<ClothState>(flag).unwrap();
/// assert_eq!(state.sim.positions().len(), 16 * 24);
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
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
/// Reflected (yaw, |v|) for inspectors; the simulation itself is not.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // The free edge's mid node, in the cloth's frame (yarns are stored row by row).
/// fn tip(cloths: Query<(&Cloth, &ClothState)>) {
///     for (cloth, state) in &cloths {
///         let row = cloth.grid.rows / 2;
///         let p = state.sim.positions()[row * cloth.grid.columns + cloth.grid.columns - 1];
///         info!("free edge at {p}");
///     }
/// }
/// # let _ = tip;
/// ```
#[derive(Component, Clone, Default, Reflect)]
#[reflect(Component, Default, Debug, from_reflect = false)]
pub struct ClothState {
    /// The shape over time.
    #[reflect(ignore)]
    pub sim: ClothSim,
    /// Rotation about the pole (local Y), radians: the cloth turns to stream downwind.
    pub yaw: f32,
    /// Noise steps per paper frame used in the last step (|v|).
    pub wind_speed: f32,
    /// The grid's coarseness now and the cross-fade from the last one ([`ClothLod`]).
    #[reflect(ignore)]
    detail: Detail,
}

/// Levels of detail for a [`Cloth`]: with a [`LodFocus`] on the camera, the cloth's shape is
/// traced on the full grid within `near` m of it, on a grid twice as coarse to `far` and four
/// times as coarse beyond ([`ClothSim::rebuild_at_stride`]). The mesh keeps every node (the
/// nodes between are interpolated), and a change of tier cross-fades over
/// [`CLOTH_LOD_FADE`] seconds, so nothing pops. Without this component a cloth is always
/// traced on its full grid.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::cloth::ClothLod;
/// use bevy_windfall::lod::LodTiers;
/// use bevy_windfall::prelude::*;
///
/// fn setup(mut commands: Commands) {
///     // On the camera (here an entity with only a transform).
///     commands.spawn((LodFocus, Transform::from_xyz(0.0, 2.0, 10.0)));
///     // Banners along a castle wall: the far ones cost a sixteenth.
///     for i in 0..40 {
///         commands.spawn((
///             Cloth::default(),
///             ClothLod(LodTiers { near: 15.0, far: 40.0 }),
///             Transform::from_xyz(i as f32 * 4.0, 8.0, 0.0),
///         ));
///     }
/// }
/// # let _ = setup;
/// ```
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct ClothLod(pub LodTiers);

impl crate::lod::HasLodTiers for ClothLod {
    fn tiers(&self) -> LodTiers {
        self.0
    }
}

/// Seconds over which a cloth cross-fades from one grid coarseness to another.
pub const CLOTH_LOD_FADE: f32 = 0.5;

/// A cloth's grid coarseness: the stride it is traced at, the one it fades from, and how far
/// the fade has gone (1: done).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Detail {
    stride: usize,
    from: usize,
    fade: f32,
}

impl Default for Detail {
    fn default() -> Self {
        Self {
            stride: 1,
            from: 1,
            fade: 1.0,
        }
    }
}

impl Detail {
    /// Moves to `target` (a fade that is turned back runs back from where it is) and on by
    /// `dt` seconds.
    fn update(&mut self, target: usize, dt: f32) {
        if target != self.stride {
            if target == self.from && self.fade < 1.0 {
                self.fade = 1.0 - self.fade;
            } else {
                self.fade = 0.0;
            }
            self.from = self.stride;
            self.stride = target;
        }
        let dt = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        self.fade = (self.fade + dt / CLOTH_LOD_FADE).min(1.0);
    }
}

/// Why a [`Cloth`] has no [`ClothState`] (logged once as a warning when it appears), or, with
/// field `transform`, why it does not feel the [`WindField`]: a cloth that follows the wind but
/// whose global transform is not finite, not invertible or beyond
/// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) flaps at its own `params.wind_speed` until the
/// transform is fixed (then this goes).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::cloth::ClothInvalid;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins));
/// let bad = ClothGrid { columns: 1, ..default() };
/// let cloth = app.world_mut().spawn(Cloth { grid: bad, ..default() }).id();
/// app.update();
/// assert_eq!(app.world().get::<ClothInvalid>(cloth).unwrap().0.field(), "grid.columns");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct ClothInvalid(pub ClothError);

impl std::fmt::Debug for ClothState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ClothState")
            .field("grid", self.sim.grid())
            .field("yaw", &self.yaw)
            .field("wind_speed", &self.wind_speed)
            .finish_non_exhaustive()
    }
}

/// Moves every [`Cloth`] on the fixed timestep and rewrites its mesh once per frame.
pub struct ClothPlugin;

impl Plugin for ClothPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        let schedule = crate::simulation_schedule(app);
        app.register_type::<Cloth>()
            .register_type::<ClothState>()
            .register_type::<ClothLod>()
            .register_type::<LodFocus>()
            .register_type::<crate::lod::LodView>()
            .register_type::<LodTiers>()
            .register_type::<ClothInvalid>()
            .register_type::<crate::lod::LodInvalid>()
            .add_observer(init_on_insert)
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
                (init_cloths, write_cloth_meshes)
                    .chain()
                    .run_if(any_with_component::<Cloth>)
                    .in_set(WindfallSystems::WriteBack),
            )
            .add_systems(
                schedule,
                step_cloths
                    .run_if(any_with_component::<Cloth>)
                    .in_set(WindfallSystems::Simulate),
            );
    }
}

/// The shift |v| (noise cells per paper frame) for wind of `speed` m/s on a cloth whose yarns are
/// `length` m long: the waves run at the wind's speed ([`air_speed`](super::air_speed)); capped
/// at 50 cells per frame.
pub fn wind_steps_per_frame(speed: f32, length: f32) -> f32 {
    super::sim::steps_for_speed(speed, length).clamp(0.0, 50.0)
}

/// A cloth, its mesh and what was made of it so far.
type ClothParts<'a> = (
    Entity,
    &'a Cloth,
    Option<&'a Mesh3d>,
    Option<&'a ClothState>,
    Option<&'a ClothInvalid>,
);

/// Sets up every cloth added or changed this frame (a change of grid, parameters or attachment
/// rebuilds it; `follow_wind` alone does not).
fn init_cloths(
    mut commands: Commands,
    cloths: Query<ClothParts, Changed<Cloth>>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    for (entity, cloth, mesh, state, invalid) in &cloths {
        // Refused already (at insertion) for the same reason: not again.
        let refused = invalid.is_some_and(|i| {
            cloth
                .grid
                .validate()
                .and(cloth.params.validate())
                .err()
                .as_ref()
                == Some(&i.0)
        });
        if !refused && state.is_none_or(|s| !built_for(s, cloth)) {
            init_cloth(&mut commands, entity, cloth, mesh, meshes.as_deref_mut());
        }
    }
}

/// Sets a [`Cloth`] up the moment it is inserted: its [`ClothState`] and mesh exist in the
/// frame it was spawned.
fn init_on_insert(
    event: On<Insert, Cloth>,
    mut commands: Commands,
    cloths: Query<(&Cloth, Option<&Mesh3d>, Option<&ClothState>)>,
    mut meshes: Option<ResMut<Assets<Mesh>>>,
) {
    if let Ok((cloth, mesh, state)) = cloths.get(event.entity)
        && state.is_none_or(|s| !built_for(s, cloth))
    {
        init_cloth(
            &mut commands,
            event.entity,
            cloth,
            mesh,
            meshes.as_deref_mut(),
        );
    }
}

/// Whether `state` was built for `cloth`'s shape.
fn built_for(state: &ClothState, cloth: &Cloth) -> bool {
    let sim = &state.sim;
    *sim.grid() == cloth.grid
        && *sim.params() == cloth.params
        && sim.attachment() == cloth.attachment
}

fn init_cloth(
    commands: &mut Commands,
    entity: Entity,
    cloth: &Cloth,
    mesh: Option<&Mesh3d>,
    meshes: Option<&mut Assets<Mesh>>,
) {
    let mut e = commands.entity(entity);
    match ClothSim::new(cloth.grid, cloth.params, cloth.attachment) {
        Ok(sim) => {
            if let Some(meshes) = meshes {
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
                detail: Detail::default(),
            });
        }
        Err(error) => {
            bevy::log::warn!("Cloth {entity}: {error}; it is not shown");
            e.remove::<ClothState>().insert(ClothInvalid(error));
        }
    }
}

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
        Has<ClothInvalid>,
    )>,
) {
    let dt = time.delta_secs();
    for (entity, cloth, mut state, transform, flagged) in &mut cloths {
        let mut speed = cloth.params.wind_speed;
        let wind = wind.as_deref().filter(|_| cloth.follow_wind);
        let bad = wind.and_then(|_| crate::guard::bad_affine(&transform.affine()));
        if bad.is_some() != flagged {
            let mut e = commands.entity(entity);
            match bad {
                Some(value) => {
                    let error = ClothError::Invalid {
                        field: "transform",
                        value,
                        reason: "the global transform must be finite, invertible and within \
                                 ±1e7 m to sample the wind",
                    };
                    bevy::log::warn!("Cloth {entity}: {error}; it flaps at its own wind_speed");
                    e.insert(ClothInvalid(error));
                }
                None => {
                    e.remove::<ClothInvalid>();
                }
            }
        }
        if let Some(wind) = wind.filter(|_| bad.is_none()) {
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
    schedule: Option<Res<crate::WindfallSchedule>>,
    time: Option<Res<Time<Fixed>>>,
    frame: Option<Res<Time>>,
    mut rotated: Local<Vec<Vec3>>,
    mut faded: Local<Vec<Vec3>>,
) {
    let Some(meshes) = meshes.as_deref_mut() else {
        return;
    };
    let s = crate::overstep(schedule.as_deref(), time.as_deref());
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
        write_cloth_mesh(&mut mesh, cloth.grid.rows, cloth.grid.columns, &rotated);
    }
}
