//! Debug drawing of falls (feature `gizmos`): each falling object's recent path as shown (its
//! global position, so falls inside scaled or moved parents draw where they are seen), each
//! stretch coloured by the primitive motion it was in.

use std::collections::VecDeque;

use bevy::app::{App, Plugin, PostUpdate};
use bevy::color::Color;
use bevy::ecs::prelude::*;
use bevy::gizmos::AppGizmoBuilder;
use bevy::gizmos::config::{GizmoConfig, GizmoConfigGroup};
use bevy::gizmos::gizmos::Gizmos;
use bevy::math::Vec3;
use bevy::reflect::Reflect;
use bevy::transform::TransformSystems;
use bevy::transform::components::GlobalTransform;

use super::fall_store::FallStore;
use super::model::regime::PrimitiveMotion;
use super::object::FallState;
use super::object::FallingObject;

/// Draws falling objects' trails when the [`FallGizmos`] gizmo group is enabled (off by
/// default; part of [`WindfallDebugPlugin`](crate::WindfallDebugPlugin)). Costs nothing while
/// disabled.
pub(crate) struct FallGizmosPlugin;

impl Plugin for FallGizmosPlugin {
    fn build(&self, app: &mut App) {
        let config = GizmoConfig {
            enabled: false,
            ..Default::default()
        };
        app.insert_gizmo_config(FallGizmos::default(), config)
            .add_systems(
                PostUpdate,
                draw_fall_paths.after(TransformSystems::Propagate).run_if(
                    |store: Res<bevy::gizmos::config::GizmoConfigStore>| {
                        store.config::<FallGizmos>().0.enabled
                    },
                ),
            );
    }
}

/// The gizmo group of the fall trails: how long and how many.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::FallGizmos;
///
/// fn show_trails(mut store: ResMut<GizmoConfigStore>) {
///     store.config_mut::<FallGizmos>().0.enabled = true;
/// }
/// # let _ = show_trails;
/// ```
#[derive(Clone, Debug, Reflect, GizmoConfigGroup)]
pub struct FallGizmos {
    /// Frames of path kept per object.
    pub trail_frames: usize,
    /// Draw at most this many objects' trails (the first ones found).
    pub max_objects: usize,
}

impl Default for FallGizmos {
    fn default() -> Self {
        Self {
            trail_frames: 90,
            max_objects: 60,
        }
    }
}

/// The recent positions of a falling object and the motion at each, kept while its path is
/// drawn, and the fall time of the last one (a smaller time means a new fall: the trail starts
/// afresh).
#[derive(Component, Default, Debug)]
pub(crate) struct FallTrail {
    points: VecDeque<(Vec3, Color)>,
    time: f32,
}

/// A colour per primitive motion (L1..L6), for paths and panels.
pub(crate) fn motion_color(motion: PrimitiveMotion) -> Color {
    match motion {
        PrimitiveMotion::SteadyDescent => Color::srgb(0.2, 0.2, 0.9),
        PrimitiveMotion::Fluttering => Color::srgb(0.1, 0.7, 0.2),
        PrimitiveMotion::Chaotic => Color::srgb(0.9, 0.5, 0.0),
        PrimitiveMotion::Tumbling => Color::srgb(0.85, 0.1, 0.1),
        PrimitiveMotion::Spiral => Color::srgb(0.6, 0.1, 0.8),
        PrimitiveMotion::Helix => Color::srgb(0.0, 0.6, 0.7),
    }
}

fn draw_fall_paths(
    mut commands: Commands,
    mut objects: Query<
        (Entity, &FallState, &GlobalTransform, Option<&mut FallTrail>),
        With<FallingObject>,
    >,
    store: Option<Res<FallStore>>,
    mut gizmos: Gizmos<FallGizmos>,
) {
    let Some(store) = store else {
        return;
    };
    let config = gizmos.config_ext.clone();
    for (entity, state, transform, trail) in objects.iter_mut().take(config.max_objects) {
        let Some(mut trail) = trail else {
            commands.entity(entity).try_insert(FallTrail::default());
            continue;
        };
        let Some(path) = store.fall(entity).filter(|p| !p.landed()) else {
            trail.points.clear();
            continue;
        };
        if path.time() < trail.time {
            trail.points.clear();
        }
        trail.time = path.time();
        let color = state.motion().map_or(Color::WHITE, motion_color);
        trail.points.push_back((transform.translation(), color));
        while trail.points.len() > config.trail_frames.max(2) {
            trail.points.pop_front();
        }
        gizmos.linestrip_gradient(trail.points.iter().copied());
    }
}

impl FallGizmos {
    /// The colour of each primitive motion (L1..L6) in trails and panels.
    pub fn motion_color(motion: PrimitiveMotion) -> Color {
        motion_color(motion)
    }
}
