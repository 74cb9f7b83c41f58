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

use super::{Cloth, ClothState};

/// Draws every [`Cloth`]'s yarns while [`ClothGizmos::enabled`].
pub struct ClothGizmosPlugin;

impl Plugin for ClothGizmosPlugin {
    fn build(&self, app: &mut App) {
        // The yarns lie on the cloth's surface: drawn slightly in front so it does not hide them.
        let config = GizmoConfig {
            depth_bias: -0.01,
            ..Default::default()
        };
        app.insert_gizmo_config(YarnGizmos, config);
        app.init_resource::<ClothGizmos>().add_systems(
            PostUpdate,
            draw_yarns
                .after(TransformSystems::Propagate)
                .run_if(|g: Res<ClothGizmos>| g.enabled),
        );
    }
}

/// The gizmo group of the yarns (its own depth bias).
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct YarnGizmos;

/// How [`ClothGizmosPlugin`] draws.
#[derive(Resource, Clone, Debug)]
pub struct ClothGizmos {
    /// Draw at all (off by default).
    pub enabled: bool,
    /// Draw every n-th yarn (≥ 1).
    pub every: usize,
    /// Yarn colour; the pole edge is drawn in black.
    pub color: Color,
}

impl Default for ClothGizmos {
    fn default() -> Self {
        Self {
            enabled: false,
            every: 2,
            color: Color::srgb(1.0, 0.9, 0.1),
        }
    }
}

fn draw_yarns(
    config: Res<ClothGizmos>,
    cloths: Query<(&ClothState, &GlobalTransform), With<Cloth>>,
    mut gizmos: Gizmos<YarnGizmos>,
) {
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
