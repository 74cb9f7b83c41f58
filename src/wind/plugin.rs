//! ECS glue: the [`WindPlugin`] and the system that advances the wind clock.

use bevy::app::{App, Plugin, RunFixedMainLoop};
use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::math::Affine3A;
use bevy::time::Time;
use bevy::transform::components::{GlobalTransform, Transform};

use super::config::WindConfig;
use super::field::WindField;
use super::rebuild::WindRebuild;
use super::rebuild::WindRebuilt;
use super::settings::WindSettings;
use super::shelter::{PlacedShelter, ShelterKind, WindShelter};
use super::source::{PlacedSource, SourceShape, WindSource};
use super::sync::{apply_wind_settings, land_wind_rebuild};
use crate::schedule::WindfallSystems;
use bevy::ecs::schedule::{InternedScheduleLabel, ScheduleLabel};

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
            .register_type::<SourceShape>()
            .register_type::<WindShelter>()
            .register_type::<ShelterKind>()
            .add_observer(restart_source)
            .add_message::<WindRebuilt>()
            .add_systems(
                RunFixedMainLoop,
                apply_wind_settings.in_set(WindfallSystems::Prepare),
            )
            .add_systems(
                schedule,
                (
                    land_wind_rebuild.run_if(resource_exists::<WindRebuild>),
                    advance_wind_clock.run_if(resource_exists::<WindField>),
                    // Only with a source or shelter to place, or placed ones to clear (a system
                    // with nothing to do still costs a wake-up).
                    place_wind_sources.run_if(anything_to_place),
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

/// Whether [`place_wind_sources`] has work: a field, and a source or shelter to place or placed
/// ones to clear.
fn anything_to_place(
    sources: Query<(), With<WindSource>>,
    shelters: Query<(), With<WindShelter>>,
    wind: Option<Res<WindField>>,
) -> bool {
    wind.is_some_and(|w| {
        !(sources.is_empty()
            && shelters.is_empty()
            && w.source_count() == 0
            && w.shelter_count() == 0)
    })
}

/// Advances the [`WindField`] clock by one step of the schedule's clock (the fixed step in
/// [`FixedUpdate`]).
pub fn advance_wind_clock(time: Res<Time>, mut wind: ResMut<WindField>) {
    wind.advance(time.delta_secs());
}

/// Where a source or shelter is: its `Transform`, its `GlobalTransform`, whether it has a parent.
type Placement = (
    &'static Transform,
    Option<&'static GlobalTransform>,
    Has<ChildOf>,
);

/// The world placement of an entity: an unparented one by its `Transform` (current even in the
/// frame it was spawned), a parented one by its `GlobalTransform` (propagated last frame).
fn world_affine(
    (transform, global, parented): (&Transform, Option<&GlobalTransform>, bool),
) -> Affine3A {
    match global {
        Some(g) if parented => g.affine(),
        _ => transform.compute_affine(),
    }
}

/// The items in entity order, so sums over them are the same on every run.
fn in_entity_order<T>(mut items: Vec<(Entity, T)>) -> Vec<T> {
    items.sort_by_key(|(entity, _)| *entity);
    items.into_iter().map(|(_, t)| t).collect()
}

/// What placing a shelter reads.
type ShelterParts = (Entity, &'static WindShelter, Placement);

/// What placing a source reads.
type SourceParts = (
    Entity,
    &'static WindSource,
    Placement,
    Option<&'static SourceStart>,
);

/// The wind time a [`WindSource`] started at (what a blast's age counts from).
#[derive(Component, Clone, Copy, Debug)]
struct SourceStart(f64);

/// A source inserted (again) starts again: a blast fires anew.
fn restart_source(event: On<Insert, WindSource>, mut commands: Commands) {
    if let Ok(mut e) = commands.get_entity(event.entity) {
        e.remove::<SourceStart>();
    }
}

/// Places every [`WindSource`] and [`WindShelter`] in the [`WindField`] for this fixed step, in
/// entity order (so the sum is the same on every run), each by [`world_affine`].
fn place_wind_sources(
    mut commands: Commands,
    mut wind: ResMut<WindField>,
    sources: Query<SourceParts>,
    shelters: Query<ShelterParts>,
) {
    let sheltering: Vec<(Entity, PlacedShelter)> = shelters
        .iter()
        .filter_map(|(entity, shelter, place)| {
            PlacedShelter::new(shelter, &world_affine(place)).map(|p| (entity, p))
        })
        .collect();
    if !(sheltering.is_empty() && wind.shelter_count() == 0) {
        wind.set_shelters(in_entity_order(sheltering));
    }
    let now = wind.time_seconds();
    // A source added before this step has blown since the step began.
    let started = wind.step_start();
    let mut placed: Vec<(Entity, PlacedSource)> = Vec::new();
    for (entity, source, place, start) in &sources {
        let start = match start {
            Some(s) => s.0,
            None => {
                commands.entity(entity).insert(SourceStart(started));
                started
            }
        };
        if source.finished(now - start) {
            continue;
        }
        if let Some(p) = PlacedSource::new(source, &world_affine(place), start) {
            placed.push((entity, p));
        }
    }
    if placed.is_empty() && wind.source_count() == 0 {
        return;
    }
    wind.set_sources(in_entity_order(placed));
}
