//! What a plugin checks of a [`WindSource`] before it places it (every number finite, sizes
//! within the world), and the marker of one that fails, [`WindSourceInvalid`].

use bevy::ecs::component::Component;
use bevy::ecs::reflect::ReflectComponent;
use bevy::reflect::Reflect;

use super::super::error::WindError;
use super::{SourceShape, WindSource};
use crate::error::InvalidValue;
use crate::guard::MAX_COORDINATE;
use std::f32::consts::FRAC_PI_2;

impl WindSource {
    /// Checks what a plugin would place: every number of the shape finite, sizes (and a blast's
    /// speeds) within 0..=[`MAX_COORDINATE`], a fan's half angle within [0, π/2], the strength
    /// finite. What fails here blows nothing, and the entity gets a
    /// [`WindSourceInvalid`] naming the field.
    ///
    /// # Errors
    /// The first field that fails, named (`shape.radius`, `shape.velocity`, `shape.speed`,
    /// `shape.peak_speed`, `shape.updraft`, `shape.strength`, `strength`, …).
    pub fn validate(&self) -> Result<(), WindError> {
        let finite = |field, v: f32| InvalidValue::check(v.is_finite(), field, v, "must be finite");
        let sized = |field, v: f32| {
            let ok = (0.0..=MAX_COORDINATE).contains(&v);
            InvalidValue::check(
                ok && v.is_finite(),
                field,
                v,
                "must be finite, ≥ 0 and ≤ MAX_COORDINATE",
            )
        };
        match self.shape {
            SourceShape::Sphere { radius, velocity } => {
                sized("shape.radius", radius)?;
                finite("shape.velocity", crate::guard::largest_component(velocity))?;
            }
            SourceShape::Fan {
                range,
                half_angle,
                speed,
            } => {
                sized("shape.range", range)?;
                InvalidValue::check(
                    (0.0..=FRAC_PI_2).contains(&half_angle),
                    "shape.half_angle",
                    half_angle,
                    "must be in [0, π/2]",
                )?;
                finite("shape.speed", speed)?;
            }
            SourceShape::Vortex {
                radius,
                peak_speed,
                updraft,
            } => {
                sized("shape.radius", radius)?;
                finite("shape.peak_speed", peak_speed)?;
                finite("shape.updraft", updraft)?;
            }
            SourceShape::Blast {
                peak_speed,
                front_speed,
                radius,
            } => {
                sized("shape.peak_speed", peak_speed)?;
                sized("shape.front_speed", front_speed)?;
                sized("shape.radius", radius)?;
            }
            SourceShape::Gust {
                strength,
                front_speed,
                width,
                range,
            } => {
                finite("shape.strength", strength)?;
                sized("shape.front_speed", front_speed)?;
                sized("shape.width", width)?;
                sized("shape.range", range)?;
            }
        }
        Ok(finite("strength", self.strength)?)
    }
}

/// Why a [`WindSource`] (or a [`WindShelter`](crate::wind::WindShelter)) adds nothing: a number
/// of its shape that [`WindSource::validate`] refuses, or, with field `transform`, a transform that places it nowhere (not finite, or beyond
/// ±[`MAX_COORDINATE`]). Inserted when the problem appears (logged once with `warn!`), removed
/// once it is gone; the other sources and shelters blow as before.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::wind::{SourceShape, WindSourceInvalid};
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let shape = SourceShape::Fan { range: 5.0, half_angle: 0.5, speed: f32::NAN };
/// let fan = app.world_mut().spawn(WindSource { shape, ..default() }).id();
/// app.update();
/// let invalid = app.world().get::<WindSourceInvalid>(fan).unwrap();
/// assert_eq!(invalid.0.field(), "shape.speed");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct WindSourceInvalid(pub WindError);

crate::lifecycle::invalid_marker!(WindSourceInvalid, WindError);
