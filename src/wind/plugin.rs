//! ECS glue: the [`WindPlugin`] and the system that advances the wind clock.

use bevy::app::{App, FixedUpdate, Plugin, PreUpdate};
use bevy::ecs::prelude::*;
use bevy::time::{Fixed, Time};

use super::{WindConfig, WindField, WindRebuilt, finish_wind_rebuild};
use crate::WindfallSystems;

/// Adds wind to an app: inserts a [`WindField`] built from `config` (unless the app already has
/// one) and advances its clock in [`FixedUpdate`], in [`WindfallSystems::Wind`]. Swaps in a
/// field rebuilt in the background ([`WindRebuild`](super::WindRebuild)) in [`PreUpdate`].
///
/// With `config: None` no field is inserted; insert your own with
/// `app.insert_resource(WindField::new(config)?)`, which reports a bad configuration as a
/// [`WindError`](super::WindError) instead of panicking.
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
    /// # Panics
    /// If `config` is invalid; validate it first with [`WindConfig::validate`] or build the
    /// field yourself with [`WindField::new`].
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        app.register_type::<WindConfig>()
            .add_message::<WindRebuilt>()
            .add_systems(PreUpdate, finish_wind_rebuild)
            .add_systems(
                FixedUpdate,
                advance_wind_clock
                    .run_if(resource_exists::<WindField>)
                    .in_set(WindfallSystems::Wind),
            );
        if let Some(config) = &self.config
            && !app.world().contains_resource::<WindField>()
        {
            let field = WindField::new(config.clone())
                .unwrap_or_else(|e| panic!("WindPlugin: invalid WindConfig: {e}"));
            app.insert_resource(field);
        }
    }
}

/// Advances the [`WindField`] clock by one fixed timestep.
pub fn advance_wind_clock(time: Res<Time<Fixed>>, mut wind: ResMut<WindField>) {
    wind.advance(time.delta_secs());
}
