//! The live wind settings, the one writer of the wind: a resource that
//! [`WindPlugin`](super::plugin::WindPlugin) takes in, field by field.

use std::ops::{Deref, DerefMut};

use bevy::ecs::prelude::*;
use bevy::log::warn;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use super::config::{MeanWind, WindConfig};
use super::field::WindField;
use super::rebuild::WindRebuild;

/// The wind's settings, live: the one place an app sets its wind (in code, an inspector or a
/// saved scene); [`WindField`] is what blows now, computed from them, for systems to read.
/// [`WindPlugin`](super::plugin::WindPlugin) takes in what you changed, field by field, before
/// the next fixed step ([`WindfallSystems::Prepare`](crate::WindfallSystems::Prepare)): the mean
/// speed, direction and pulse apply at once; anything that changes the turbulence (β,
/// roughness, grid, seed, modes) starts a [`WindRebuild`](super::rebuild::WindRebuild) in the
/// background, which lands a fixed number of steps later, whatever the machine. Nothing writes
/// into the settings: they hold what you set. A bad value is refused with a warning that names
/// the field; the wind keeps what it had and the settings keep your value until you change it.
/// The rules for a frame with several writers are in the crate's docs/live.md.
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

/// Takes in what changed in [`WindSettings`] since the field last took them in
/// (`WindField::taken_in`), field by field: the mean wind's fields at once (each one valid on
/// its own), the turbulence by a [`WindRebuild`] (unless the field, or the rebuild in flight,
/// already has it; set back to the field's, the rebuild in flight is dropped). A bad value is
/// warned about by name and not taken; the settings are never written.
pub(super) fn take_in_wind_settings(
    mut commands: Commands,
    settings: Res<WindSettings>,
    field: Option<ResMut<WindField>>,
    rebuild: Option<Res<WindRebuild>>,
) {
    let Some(mut field) = field else {
        return;
    };
    let now = &settings.config;
    let last = field
        .taken_in
        .clone()
        .unwrap_or_else(|| field.config().clone());
    if *now == last {
        return;
    }
    // Each changed field of the mean wind on its own, so one bad value holds back no other.
    let (was, wants) = (last.mean(), now.mean());
    let mut apply = |edit: &dyn Fn(&mut MeanWind)| {
        let mut mean = field.config().mean();
        edit(&mut mean);
        if let Err(e) = field.set_mean(mean) {
            warn!("WindSettings: {e}; the wind keeps what it had");
        }
    };
    if was.reference_speed != wants.reference_speed {
        apply(&|m| m.reference_speed = wants.reference_speed);
    }
    if was.direction != wants.direction {
        apply(&|m| m.direction = wants.direction);
    }
    if was.pulse != wants.pulse {
        apply(&|m| m.pulse = wants.pulse);
    }
    if !now.same_turbulence(&last) {
        if now.same_turbulence(field.config()) {
            commands.remove_resource::<WindRebuild>();
        } else if !rebuild.is_some_and(|r| !r.superseded && r.config().same_turbulence(now)) {
            match WindRebuild::start(now.clone()) {
                Ok(job) => commands.insert_resource(job),
                Err(e) => warn!("WindSettings: {e}; the wind keeps what it had"),
            }
        }
    }
    field.taken_in = Some(now.clone());
}

/// A [`WindField`] was inserted (resources are components; this observes the insertion): a
/// rebuild in flight is superseded by it, and the field takes in the app's settings as they
/// are, if it has taken in none (a new field; a clone or a snapshot's keeps its own).
pub(super) fn field_inserted(
    _: On<Insert<WindField>>,
    rebuild: Option<ResMut<WindRebuild>>,
    settings: Option<Res<WindSettings>>,
    field: Option<ResMut<WindField>>,
) {
    if let Some(mut rebuild) = rebuild {
        rebuild.superseded = true;
    }
    if let (Some(mut field), Some(settings)) = (field, settings)
        && field.taken_in.is_none()
    {
        field.taken_in = Some(settings.config.clone());
    }
}
