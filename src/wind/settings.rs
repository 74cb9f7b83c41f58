//! The live wind settings: a resource that [`WindPlugin`](super::WindPlugin) follows.

use std::ops::{Deref, DerefMut};

use bevy::ecs::prelude::*;
use bevy::log::warn;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use super::rebuild::start_rebuild;
use super::{WindConfig, WindField, WindRebuild};

/// The wind's settings, live: edit them (in code, an inspector or a saved scene) and
/// [`WindPlugin`](super::WindPlugin) follows on the next fixed step. The mean speed, direction
/// and pulse apply at once; anything that changes the turbulence (β, roughness, grid, seed, modes) starts a
/// [`WindRebuild`] in the background, which lands a fixed number of steps later, whatever the
/// machine (see [`WindRebuild`]); edits made meanwhile are merged into the new field, never lost.
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
        pulse: super::Pulse::default(),
        ..c.clone()
    };
    strip(a) != strip(b)
}

/// Follows [`WindSettings`]: what changed in them since the last step applies, speed and
/// direction (and pulse) at once, the rest by a background rebuild. A field changed directly
/// ([`WindField::set_reference_speed`], [`WindField::set_direction`],
/// [`WindField::set_pulse`], a newly inserted field) is
/// reflected back into the settings, so neither kind of edit overwrites the other.
pub fn apply_wind_settings(
    mut commands: Commands,
    settings: Option<ResMut<WindSettings>>,
    field: Option<ResMut<WindField>>,
    rebuild: Option<Res<WindRebuild>>,
    mut seen: Local<Option<WindConfig>>,
) {
    let (Some(mut settings), Some(mut field)) = (settings, field) else {
        return;
    };
    let seen = seen.get_or_insert_with(|| settings.config.clone());
    if settings.is_changed() && settings.config != *seen {
        let target = settings.config.clone();
        let mut refused = None;
        if target.reference_speed != seen.reference_speed
            && let Err(e) = field.set_reference_speed(target.reference_speed)
        {
            refused = Some(e);
        }
        if target.direction != seen.direction
            && let Err(e) = field.set_direction(target.direction)
        {
            refused = Some(e);
        }
        if target.pulse != seen.pulse
            && let Err(e) = field.set_pulse(target.pulse)
        {
            refused = Some(e);
        }
        if needs_rebuild(seen, &target) {
            match start_rebuild(target.clone(), Some(field.generation())) {
                Ok(job) => {
                    commands.insert_resource(job);
                }
                Err(e) => refused = Some(e),
            }
        }
        if let Some(e) = refused {
            warn!("WindSettings: {e}; the wind keeps what it had");
        }
        *seen = target;
    }
    // The field leads where it was changed directly: its speed and direction always, the rest
    // when nothing is building (a field inserted by hand).
    let live = field.config();
    let mut synced = settings.config.clone();
    synced.reference_speed = live.reference_speed;
    synced.direction = live.direction;
    synced.pulse = live.pulse;
    if rebuild.is_none() && !settings.is_changed() {
        synced = live.clone();
    }
    if synced != settings.config {
        seen.reference_speed = synced.reference_speed;
        seen.direction = synced.direction;
        seen.pulse = synced.pulse;
        if rebuild.is_none() && !settings.is_changed() {
            *seen = synced.clone();
        }
        settings.bypass_change_detection().config = synced;
    }
}
