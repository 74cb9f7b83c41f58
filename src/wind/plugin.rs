//! ECS glue: the [`WindPlugin`] and the system that advances the wind clock.

use bevy::app::{App, Plugin, RunFixedMainLoop};
use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::time::Time;

use super::rebuild::land_wind_rebuild;
use super::{WindConfig, WindField, WindRebuilt, WindSettings, apply_wind_settings};
use crate::WindfallSystems;

/// Adds wind to an app: inserts a [`WindField`] built from `config` (unless the app already has
/// one) and its live [`WindSettings`]; takes in the settings before the fixed loop
/// ([`WindfallSystems::Prepare`]); in the simulation schedule (`FixedUpdate`), in
/// [`WindfallSystems::Wind`], lands a field rebuilt in the background
/// ([`WindRebuild`](super::WindRebuild)) at its step and advances the wind clock.
///
/// With `config: None` no field is inserted; insert your own with
/// `app.insert_resource(WindField::new(config)?)`. An invalid `config` is logged as an error
/// naming the field and no field is inserted (the app goes on in still air).
#[derive(Clone, Debug)]
pub struct WindPlugin {
    /// Configuration of the field to insert, if any.
    pub config: Option<WindConfig>,
}

impl Default for WindPlugin {
    fn default() -> Self {
        Self {
            config: Some(WindConfig::default()),
        }
    }
}

impl WindPlugin {
    /// A plugin that inserts a field built from `config`.
    pub fn new(config: WindConfig) -> Self {
        Self {
            config: Some(config),
        }
    }
}

impl Plugin for WindPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        let schedule = crate::simulation_schedule(app);
        app.register_type::<WindConfig>()
            .register_type::<WindSettings>()
            .register_type::<WindField>()
            .register_type::<super::WindSnapshot>()
            .add_message::<WindRebuilt>()
            .add_systems(
                RunFixedMainLoop,
                apply_wind_settings.in_set(WindfallSystems::Prepare),
            )
            .add_systems(
                schedule,
                (
                    land_wind_rebuild,
                    advance_wind_clock.run_if(resource_exists::<WindField>),
                )
                    .chain()
                    .in_set(WindfallSystems::Wind),
            );
        if let Some(config) = &self.config
            && !app.world().contains_resource::<WindField>()
        {
            match WindField::new(config.clone()) {
                Ok(field) => {
                    app.insert_resource(field);
                }
                Err(e) => error!("WindPlugin: invalid WindConfig ({e}); no wind is inserted"),
            }
        }
        let live = app
            .world()
            .get_resource::<WindField>()
            .map(|f| f.config().clone());
        if let Some(config) = live
            && !app.world().contains_resource::<WindSettings>()
        {
            app.insert_resource(WindSettings::new(config));
        }
    }
}

/// Advances the [`WindField`] clock by one step of the schedule's clock (the fixed step in
/// [`FixedUpdate`]).
pub fn advance_wind_clock(time: Res<Time>, mut wind: ResMut<WindField>) {
    wind.advance(time.delta_secs());
}
