//! Debug drawing of cloth (feature `gizmos`): the yarns (rows of the P-type descriptor) and the
//! pole edge.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::color::Color;
use bevy::ecs::prelude::*;
use bevy::gizmos::AppGizmoBuilder;
use bevy::gizmos::config::{GizmoConfig, GizmoConfigGroup};
use bevy::gizmos::gizmos::Gizmos;
use bevy::reflect::Reflect;
use bevy::transform::TransformSystems;
use bevy::transform::components::GlobalTransform;

use super::component::Cloth;
use super::component::ClothState;

/// Draws every [`Cloth`]'s yarns when the [`ClothGizmos`] gizmo group is enabled (off by
/// default; part of [`WindfallDebugPlugin`](crate::WindfallDebugPlugin)).
pub(crate) struct ClothGizmosPlugin;

impl Plugin for ClothGizmosPlugin {
    fn build(&self, app: &mut App) {
        // The yarns lie on the cloth's surface: drawn slightly in front so it does not hide them.
        let config = GizmoConfig {
            enabled: false,
            depth_bias: -0.01,
            ..Default::default()
        };
        app.insert_gizmo_config(ClothGizmos::default(), config)
            .add_systems(PostUpdate, draw_yarns.after(TransformSystems::Propagate));
    }
}

/// The gizmo group of the yarns: which are drawn and in what colour.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::cloth::ClothGizmos;
///
/// fn show_yarns(mut store: ResMut<GizmoConfigStore>) {
///     store.config_mut::<ClothGizmos>().0.enabled = true;
/// }
/// # let _ = show_yarns;
/// ```
#[derive(Clone, Debug, Reflect, GizmoConfigGroup)]
pub struct ClothGizmos {
    /// Draw every n-th yarn (≥ 1).
    pub every: usize,
    /// Yarn colour; the pole edge is drawn in black.
    pub color: Color,
}

impl Default for ClothGizmos {
    fn default() -> Self {
        Self {
            every: 2,
            color: Color::srgb(1.0, 0.9, 0.1),
        }
    }
}

fn draw_yarns(
    cloths: Query<(&ClothState, &GlobalTransform), With<Cloth>>,
    mut gizmos: Gizmos<ClothGizmos>,
) {
    if !gizmos.config.enabled {
        return;
    }
    let config = gizmos.config_ext.clone();
    for (state, at) in &cloths {
        let columns = state.sim.grid().columns;
        let points = state.sim.positions();
        let world = |p| at.transform_point(p);
        for yarn in points.chunks(columns).step_by(config.every.max(1)) {
            gizmos.linestrip(yarn.iter().copied().map(world), config.color);
        }
        let edge = points.iter().step_by(columns).copied().map(world);
        gizmos.linestrip(edge, Color::BLACK);
    }
}
