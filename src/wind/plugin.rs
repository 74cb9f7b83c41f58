//! The [`WindPlugin`] and the system that advances the wind clock.

use bevy::app::{App, Plugin, RunFixedMainLoop};
use bevy::ecs::prelude::*;
use bevy::ecs::schedule::{InternedScheduleLabel, ScheduleLabel};
use bevy::log::error;
use bevy::time::Time;

use super::config::WindConfig;
use super::field::WindField;
use super::mover::{WindMover, WindMoverInvalid, anything_moving, place_wind_movers};
use super::placement::{anything_to_place, check_shelter, place_wind_sources, restart_source};
use super::rebuild::{WindRebuild, WindRebuilt, land_wind_rebuild};
use super::settings::{WindSettings, field_inserted, take_in_wind_settings};
use super::shelter::{ShelterKind, WindShelter, WindShelterInvalid};
use super::source::{SourceShape, WindSource, WindSourceInvalid};
use crate::schedule::WindfallSystems;

/// Adds wind to an app: inserts a [`WindField`] built from `config` (unless the app already has
/// one) and its live [`WindSettings`]; takes in the settings before the fixed loop
/// ([`WindfallSystems::Prepare`]); in the simulation schedule (`FixedUpdate`), in
/// [`WindfallSystems::Wind`], lands a field rebuilt in the background
/// ([`WindRebuild`](super::rebuild::WindRebuild)) at its step and advances the wind clock.
///
/// With `config: None` no field is inserted; insert your own with
/// `app.insert_resource(WindField::new(config)?)`. An invalid `config` is logged as an error
/// naming the field and no field is inserted (the app goes on in still air).
///
/// The wind clock advances in `FixedUpdate`; [`WindPlugin::in_schedule`] moves it (give every
/// plugin the same schedule, or use `WindfallPlugins::new`).
#[derive(Clone, Debug)]
pub struct WindPlugin {
    /// Configuration of the field to insert, if any.
    pub config: Option<WindConfig>,
    /// Where the clock advances; `None` follows the schedule its group (or an earlier plugin)
    /// recorded, else `FixedUpdate`.
    pub schedule: Option<InternedScheduleLabel>,
}

impl Default for WindPlugin {
    fn default() -> Self {
        Self {
            config: Some(WindConfig::default()),
            schedule: None,
        }
    }
}

impl WindPlugin {
    /// A plugin that inserts a field built from `config`.
    pub fn new(config: WindConfig) -> Self {
        Self {
            config: Some(config),
            schedule: None,
        }
    }

    /// The same plugin, advancing the wind clock in `schedule` instead of `FixedUpdate`.
    pub fn in_schedule(self, schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: Some(schedule.intern()),
            ..self
        }
    }
}

impl Plugin for WindPlugin {
    fn build(&self, app: &mut App) {
        let schedule = crate::schedule::resolve(app, self.schedule);
        crate::schedule::configure_sets(app, schedule);
        app.register_type::<WindConfig>()
            .register_type::<WindSettings>()
            .register_type::<WindField>()
            .register_type::<super::snapshot::WindSnapshot>()
            .register_type::<WindSource>()
            .register_type::<WindSourceInvalid>()
            .register_type::<SourceShape>()
            .register_type::<WindShelter>()
            .register_type::<WindShelterInvalid>()
            .register_type::<ShelterKind>()
            .register_type::<WindMover>()
            .register_type::<WindMoverInvalid>()
            .add_observer(field_inserted)
            .add_observer(restart_source)
            .add_observer(check_shelter)
            .add_message::<WindRebuilt>()
            .add_systems(
                RunFixedMainLoop,
                take_in_wind_settings
                    .run_if(resource_exists_and_changed::<WindSettings>)
                    .in_set(WindfallSystems::Prepare),
            )
            .add_systems(
                schedule,
                (
                    land_wind_rebuild.run_if(resource_exists::<WindRebuild>),
                    advance_wind_clock.run_if(resource_exists::<WindField>),
                    // Only with a source or shelter to place, or placed ones to clear (a system
                    // with nothing to do still costs a wake-up).
                    place_wind_sources.run_if(anything_to_place),
                    place_wind_movers.run_if(anything_moving),
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
            app.insert_resource(WindSettings::new(config.clone()));
            // The field has taken these in: a later edit applies what differs from them.
            if let Some(mut field) = app.world_mut().get_resource_mut::<WindField>() {
                field.taken_in.get_or_insert(config);
            }
        }
    }
}

/// Advances the [`WindField`] clock by one step of the schedule's clock (the fixed step in
/// [`FixedUpdate`]).
pub fn advance_wind_clock(time: Res<Time>, mut wind: ResMut<WindField>) {
    wind.advance(time.delta_secs());
}
