//! Debug drawing of the wind with gizmos (feature `gizmos`).

use bevy::app::{App, Plugin, Update};
use bevy::color::{Color, LinearRgba};
use bevy::ecs::prelude::*;
use bevy::gizmos::AppGizmoBuilder;
use bevy::gizmos::config::{GizmoConfig, GizmoConfigGroup};
use bevy::gizmos::gizmos::Gizmos;
use bevy::math::{Isometry3d, Quat, Vec2, Vec3};
use bevy::reflect::Reflect;
use bevy::transform::components::GlobalTransform;

use super::field::WindField;
use super::source::{SourceShape, WindSource};

/// Draws a grid of wind arrows every frame while a [`WindField`] exists, and the extent of
/// every [`WindSource`] (spheres, a fan's cone, a vortex's core and rim, a blast's reach), when the
/// [`WindGizmos`] gizmo group is enabled (off by default; part of
/// [`WindfallDebugPlugin`](crate::WindfallDebugPlugin)).
pub(crate) struct WindGizmosPlugin;

impl Plugin for WindGizmosPlugin {
    fn build(&self, app: &mut App) {
        let config = GizmoConfig {
            enabled: false,
            ..Default::default()
        };
        app.insert_gizmo_config(WindGizmos::default(), config)
            .add_systems(
                Update,
                (
                    draw_wind_arrows.run_if(resource_exists::<WindField>),
                    draw_wind_sources,
                ),
            );
    }
}

/// The gizmo group of the wind arrows: where and how they are drawn. Switch it on with
/// `GizmoConfigStore::config_mut::<WindGizmos>().0.enabled = true`.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::wind::WindGizmos;
///
/// // Arrows every 2 m over a 20 × 20 m yard, switched on with F1.
/// fn toggle(keys: Res<ButtonInput<KeyCode>>, mut store: ResMut<GizmoConfigStore>) {
///     if keys.just_pressed(KeyCode::F1) {
///         let (config, arrows) = store.config_mut::<WindGizmos>();
///         config.enabled = !config.enabled;
///         arrows.half_extent = Vec2::splat(10.0);
///     }
/// }
/// # let _ = toggle;
/// ```
#[derive(Clone, Debug, Reflect, GizmoConfigGroup)]
pub struct WindGizmos {
    /// Centre of the grid of arrows (x, z), m.
    pub center: Vec2,
    /// Half the sides of the grid along x and z, m.
    pub half_extent: Vec2,
    /// Distance between arrows, m.
    pub spacing: f32,
    /// Height of the arrows' tails, m.
    pub height: f32,
    /// Arrow length per m/s of wind, s.
    pub seconds_per_length: f32,
}

impl Default for WindGizmos {
    fn default() -> Self {
        Self {
            center: Vec2::ZERO,
            half_extent: Vec2::splat(20.0),
            spacing: 2.0,
            height: 1.0,
            seconds_per_length: 0.3,
        }
    }
}

/// Colour classes of the free-fall paper's Fig. 13: speed V against the mean speed U at that
/// height. Red V > 2U, pink U < V ≤ 2U, blue U/2 < V ≤ U, black V ≤ U/2 (drawn dark grey so it
/// shows on dark ground).
pub(crate) fn speed_class_color(speed: f32, mean: f32) -> Color {
    let rgb = if speed > 2.0 * mean {
        LinearRgba::rgb(1.0, 0.05, 0.05)
    } else if speed > mean {
        LinearRgba::rgb(1.0, 0.45, 0.7)
    } else if speed > 0.5 * mean {
        LinearRgba::rgb(0.15, 0.35, 1.0)
    } else {
        LinearRgba::rgb(0.08, 0.08, 0.08)
    };
    rgb.into()
}

fn draw_wind_arrows(wind: Res<WindField>, mut gizmos: Gizmos<WindGizmos>) {
    let spacing = gizmos.config_ext.spacing;
    if !gizmos.config.enabled || spacing.is_nan() || spacing <= 0.0 {
        return;
    }
    let config = gizmos.config_ext.clone();
    let steps = (config.half_extent / config.spacing).floor().as_ivec2();
    let mean = wind.mean_speed_at(config.height);
    for i in -steps.x..=steps.x {
        for k in -steps.y..=steps.y {
            let xz = config.center + Vec2::new(i as f32, k as f32) * config.spacing;
            let tail = Vec3::new(xz.x, config.height, xz.y);
            let v = wind.velocity(tail);
            let color = speed_class_color(v.length(), mean);
            gizmos
                .arrow(tail, tail + v * config.seconds_per_length, color)
                .with_tip_length(0.25 * config.spacing);
        }
    }
}

/// Draws the sources that blow (one refused by its checks blows nothing and is not drawn).
fn draw_wind_sources(
    sources: Query<(&WindSource, &GlobalTransform), Without<super::source::WindSourceInvalid>>,
    mut gizmos: Gizmos<WindGizmos>,
) {
    if !gizmos.config.enabled {
        return;
    }
    let color = LinearRgba::rgb(0.2, 0.9, 1.0);
    let flat = Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    for (source, transform) in &sources {
        let (_, rotation, origin) = transform.to_scale_rotation_translation();
        match source.shape {
            SourceShape::Sphere { radius, velocity } => {
                gizmos.sphere(Isometry3d::from_translation(origin), radius, color);
                gizmos.arrow(origin, origin + velocity * 0.3, color);
            }
            SourceShape::Fan {
                range, half_angle, ..
            } => {
                let forward = rotation * Vec3::NEG_Z;
                let centre = origin + forward * (range * half_angle.cos());
                let rim = range * half_angle.sin();
                let facing = Quat::from_rotation_arc(Vec3::Z, forward);
                gizmos.circle(Isometry3d::new(centre, facing), rim, color);
                for corner in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y] {
                    gizmos.line(origin, centre + facing * corner * rim, color);
                }
            }
            SourceShape::Vortex { radius, .. } => {
                let level = Isometry3d::new(origin, rotation * flat);
                gizmos.circle(level, radius, color);
                gizmos.circle(level, 0.2 * radius, color);
                gizmos.line(
                    origin - rotation * Vec3::Y * radius,
                    origin + rotation * Vec3::Y * radius,
                    color,
                );
            }
            SourceShape::Blast { radius, .. } => {
                gizmos.sphere(Isometry3d::from_translation(origin), radius, color);
            }
            SourceShape::Gust { range, .. } => {
                // Its path: from the entity forward over its range.
                let forward = rotation * Vec3::NEG_Z;
                gizmos.arrow(origin, origin + forward * range, color);
            }
        }
    }
}

impl WindGizmos {
    /// The colour class of Fig. 13 of the free-fall paper for speed V against the mean speed U
    /// at that height: red V > 2U, pink U < V ≤ 2U, blue U/2 < V ≤ U, dark grey V ≤ U/2.
    pub fn speed_class_color(speed: f32, mean: f32) -> Color {
        speed_class_color(speed, mean)
    }
}
