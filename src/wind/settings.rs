//! The live wind settings: a resource that [`WindPlugin`](super::plugin::WindPlugin) follows.

use std::ops::{Deref, DerefMut};

use bevy::ecs::prelude::*;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use super::config::WindConfig;

/// The wind's settings, live: edit them (in code, an inspector or a saved scene) and
/// [`WindPlugin`](super::plugin::WindPlugin) follows on the next fixed step. The mean speed, direction
/// and pulse apply at once; anything that changes the turbulence (β, roughness, grid, seed, modes) starts a
/// [`WindRebuild`](super::rebuild::WindRebuild) in the background, which lands a fixed number of steps later, whatever the
/// machine (see [`WindRebuild`](super::rebuild::WindRebuild)); edits made meanwhile are merged into the new field, never lost.
/// A bad value is refused with a warning that names the field; the wind keeps what it had and
/// the settings go back to it.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, WindPlugin::default()));
/// app.update();
/// // A stronger breeze, turned toward +Z: both apply on the next fixed step.
/// let mut settings = app.world_mut().resource_mut::<WindSettings>();
/// settings.reference_speed = 8.0;
/// settings.direction = Vec2::new(0.0, 1.0);
/// ```
#[derive(Resource, Clone, Debug, Default, PartialEq, Reflect)]
#[reflect(Resource, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WindSettings {
    /// The configuration the wind should have.
    pub config: WindConfig,
}

impl WindSettings {
    /// Settings for `config`.
    pub fn new(config: WindConfig) -> Self {
        Self { config }
    }
}

impl Deref for WindSettings {
    type Target = WindConfig;
    fn deref(&self) -> &WindConfig {
        &self.config
    }
}

impl DerefMut for WindSettings {
    fn deref_mut(&mut self) -> &mut WindConfig {
        &mut self.config
    }
}

/// Whether `a` and `b` differ in more than the mean speed and direction (which need no rebuild).
pub(crate) fn needs_rebuild(a: &WindConfig, b: &WindConfig) -> bool {
    let strip = |c: &WindConfig| WindConfig {
        reference_speed: 0.0,
        direction: bevy::math::Vec2::X,
        pulse: super::pulse::Pulse::default(),
        ..c.clone()
    };
    strip(a) != strip(b)
}
