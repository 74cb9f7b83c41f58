//! The [`Cloth`] component (what a game spawns), its runtime [`ClothState`], its levels of detail
//! ([`ClothLod`]) and [`ClothInvalid`] marker, and how a cloth is set up (its lifecycle).

use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::mesh::{Mesh, Mesh3d};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

use super::mesh;
use super::params::{ClothError, ClothGrid, ClothParams};
use super::sim::{ClothAttachment, ClothSim};
use crate::lifecycle::Described;
use crate::lod::LodTiers;

/// A flag, banner or curtain. Its node grid is in the entity's local frame (see
/// [`ClothAttachment`]); [`ClothPlugin`](super::ClothPlugin) adds a [`ClothState`] and a [`Mesh3d`] (when the app has
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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// // A 1.5 × 1 m flag on a pole whose top is 6 m up, in the wind of the field.
/// let flag = app
///     .world_mut()
///     .spawn((
///         Cloth {
///             grid: ClothGrid { rows: 16, columns: 24, width: 1.5, height: 1.0 },
///             params: ClothPreset::FlagFlappingFrozen.params(),
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
    /// Motion parameters (see [`ClothPreset`](super::presets::ClothPreset)).
    pub params: ClothParams,
    /// Pole (flag, banner) or rod (curtain).
    pub attachment: ClothAttachment,
    /// With a [`WindField`](crate::wind::WindField), take speed (and, on a pole, direction) from the wind at the
    /// entity's origin instead of `params.wind_steps_per_frame`.
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
    pub wind_steps_per_frame: f32,
    /// The grid's coarseness now and the cross-fade from the last one ([`ClothLod`]).
    #[reflect(ignore)]
    pub(super) detail: Detail,
}

/// Levels of detail for a [`Cloth`]: with a [`LodFocus`](crate::lod::LodFocus) on the camera, the cloth's shape is
/// traced on the full grid within `near` m of it, on a grid twice as coarse to `far` and four
/// times as coarse beyond ([`ClothSim::rebuild_at_stride`]). The mesh keeps every node (the
/// nodes between are interpolated), and a change of tier cross-fades over
/// [`ClothLod::FADE_SECONDS`] seconds, so nothing pops. Without this component a cloth is always
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

/// A cloth's grid coarseness: the stride it is traced at, the one it fades from, and how far
/// the fade has gone (1: done).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Detail {
    pub(super) stride: usize,
    pub(super) from: usize,
    pub(super) fade: f32,
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
    pub(super) fn update(&mut self, target: usize, dt: f32) {
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
        self.fade = (self.fade + dt / ClothLod::FADE_SECONDS).min(1.0);
    }
}

/// Why a [`Cloth`] has no [`ClothState`] (logged once as a warning when it appears), or, with
/// field `transform`, why it does not feel the [`WindField`](crate::wind::WindField): a cloth that follows the wind but
/// whose global transform is not finite, not invertible or beyond
/// ±[`MAX_COORDINATE`](crate::MAX_COORDINATE) flaps at its own `params.wind_steps_per_frame` until the
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
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let bad = ClothGrid { columns: 1, ..default() };
/// let cloth = app.world_mut().spawn(Cloth { grid: bad, ..default() }).id();
/// app.update();
/// assert_eq!(app.world().get::<ClothInvalid>(cloth).unwrap().0.field(), "grid.columns");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct ClothInvalid(pub ClothError);

crate::lifecycle::invalid_marker!(ClothInvalid, ClothError);

impl std::fmt::Debug for ClothState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ClothState")
            .field("grid", self.sim.grid())
            .field("yaw", &self.yaw)
            .field("wind_steps_per_frame", &self.wind_steps_per_frame)
            .finish_non_exhaustive()
    }
}

impl Described for Cloth {
    type Invalid = ClothInvalid;
    type Key = (ClothGrid, ClothParams, ClothAttachment);
    type Data = Option<&'static Mesh3d>;
    type Context = Option<ResMut<'static, Assets<Mesh>>>;
    const SUBJECT: &'static str = "Cloth";
    const CONSEQUENCE: &'static str = "it is not shown";
    /// The transform is checked every step, with the wind ([`ClothPlugin`](super::ClothPlugin)).
    const SET_UP_CHECKS_TRANSFORM: bool = false;

    /// A change of grid, parameters or attachment rebuilds it; `follow_wind` alone does not.
    fn key(&self) -> Self::Key {
        (self.grid, self.params, self.attachment)
    }

    /// Builds the yarns and writes its mesh (into the entity's own, or a new one).
    fn set_up(
        &self,
        entity: Entity,
        mesh: Option<&Mesh3d>,
        meshes: &mut Option<ResMut<Assets<Mesh>>>,
        commands: &mut Commands,
    ) -> Option<Result<(), ClothError>> {
        let mut e = commands.entity(entity);
        let sim = match ClothSim::new(self.grid, self.params, self.attachment) {
            Ok(sim) => sim,
            Err(error) => {
                e.try_remove::<ClothState>();
                return Some(Err(error));
            }
        };
        if let Some(meshes) = meshes {
            let fresh = mesh::build(self.grid.rows, self.grid.columns, sim.positions());
            match mesh.filter(|m| meshes.contains(&m.0)) {
                Some(m) => {
                    if let Some(mut slot) = meshes.get_mut(&m.0) {
                        *slot = fresh;
                    }
                }
                None => {
                    e.try_insert(Mesh3d(meshes.add(fresh)));
                }
            }
        }
        e.try_insert(ClothState {
            wind_steps_per_frame: self.params.wind_steps_per_frame,
            sim,
            yaw: 0.0,
            detail: Detail::default(),
        });
        Some(Ok(()))
    }
}

/// Limits and constants of [`ClothLod`].
impl ClothLod {
    /// Seconds over which a cloth cross-fades from one grid coarseness to another.
    pub const FADE_SECONDS: f32 = 0.5;
}
