//! ECS glue: the [`WindPlugin`] and the system that advances the wind clock.

use bevy::app::{App, Plugin, RunFixedMainLoop};
use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::math::{Affine3A, Quat};
use bevy::time::Time;
use bevy::transform::components::Transform;

use super::config::WindConfig;
use super::error::WindError;
use super::field::WindField;
use super::placement;
use super::rebuild::WindRebuild;
use super::rebuild::WindRebuilt;
use super::settings::WindSettings;
use super::shelter::{PlacedShelter, ShelterKind, WindShelter};
use super::source::{PlacedSource, SourceShape, WindSource, WindSourceInvalid};
use super::sync::{apply_wind_settings, land_wind_rebuild};
use crate::lifecycle::{mark, mark_on_change};
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
            .register_type::<WindSourceInvalid>()
            .register_type::<SourceShape>()
            .register_type::<WindShelter>()
            .register_type::<ShelterKind>()
            .add_observer(restart_source)
            .add_observer(check_shelter)
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

/// The transforms of the entities that hold sources and shelters, and of their ancestors.
type Hierarchy<'w, 's> = Query<'w, 's, (&'static Transform, Option<&'static ChildOf>)>;

/// Most ancestors followed up from a source or shelter (a deeper chain places nothing).
const MAX_DEPTH: usize = 256;

/// Where `entity` stands this step, from the `Transform`s of it and its ancestors (current even
/// in the frame it was spawned or moved, before Bevy propagates them): its origin is where its
/// parents' transforms, scales included, put it; its rotation is its own and its ancestors'
/// rotations composed, whatever their scales (a zero, negative or huge scale neither removes nor
/// turns a source: sizes are in metres). A transform that places it nowhere is an error naming
/// `transform`.
fn world_place(entity: Entity, hierarchy: &Hierarchy) -> Result<placement::Placement, WindError> {
    let nowhere = |value| {
        WindError::Invalid(crate::error::InvalidValue {
            field: "transform",
            value,
            reason: "must place it at a finite point within ±MAX_COORDINATE (1e7 m), turned by a \
                     finite rotation",
        })
    };
    let (mut affine, mut rotation) = (Affine3A::IDENTITY, Quat::IDENTITY);
    let mut at = Some(entity);
    for _ in 0..MAX_DEPTH {
        let Some(e) = at else {
            let origin = affine.translation;
            return placement::Placement::new(origin, rotation)
                .ok_or_else(|| nowhere(origin.abs().max_element()));
        };
        let Ok((transform, parent)) = hierarchy.get(e) else {
            // An ancestor without a transform places its children at its origin.
            at = None;
            continue;
        };
        affine = transform.compute_affine() * affine;
        rotation = transform.rotation * rotation;
        at = parent.map(ChildOf::parent);
    }
    Err(nowhere(MAX_DEPTH as f32))
}

/// The items in entity order, so sums over them are the same on every run.
fn in_entity_order<T>(mut items: Vec<(Entity, T)>) -> Vec<T> {
    items.sort_by_key(|(entity, _)| *entity);
    items.into_iter().map(|(_, t)| t).collect()
}

/// What placing a shelter reads.
type ShelterParts = (
    Entity,
    &'static WindShelter,
    Option<&'static WindSourceInvalid>,
);

/// What placing a source reads.
type SourceParts = (
    Entity,
    &'static WindSource,
    Option<&'static SourceStart>,
    Option<&'static WindSourceInvalid>,
);

/// The wind time a [`WindSource`] started at (what a blast's age counts from), and whether a
/// one-shot has finished: then it stays finished, even if the wind's clock is set back (a
/// [`WindField`] inserted by hand), until the component is inserted again.
#[derive(Component, Clone, Copy, Debug)]
struct SourceStart {
    at: f64,
    finished: bool,
}

/// A source inserted (again) starts again: a blast fires anew. Its numbers are checked at once
/// (the transform when it is placed).
fn restart_source(
    event: On<Insert, WindSource>,
    mut commands: Commands,
    sources: Query<(&WindSource, Option<&WindSourceInvalid>)>,
) {
    if let Ok(mut e) = commands.get_entity(event.entity) {
        e.remove::<SourceStart>();
    }
    if let Ok((source, invalid)) = sources.get(event.entity) {
        let outcome = source.validate();
        mark(
            &mut commands,
            event.entity,
            outcome,
            invalid,
            "WindSource",
            NOTHING,
        );
    }
}

/// A shelter's numbers are checked when it is inserted (the transform when it is placed).
fn check_shelter(
    event: On<Insert, WindShelter>,
    mut commands: Commands,
    shelters: Query<(&WindShelter, Option<&WindSourceInvalid>)>,
) {
    if let Ok((shelter, invalid)) = shelters.get(event.entity) {
        let outcome = shelter.validate();
        mark(
            &mut commands,
            event.entity,
            outcome,
            invalid,
            "WindShelter",
            NOTHING,
        );
    }
}

/// Places every [`WindSource`] and [`WindShelter`] in the [`WindField`] for this fixed step, in
/// entity order (so the sum is the same on every run), each by [`world_place`]. One that cannot
/// be placed (a number that is not finite, a transform that places it nowhere) adds nothing and
/// gets a [`WindSourceInvalid`].
fn place_wind_sources(
    mut commands: Commands,
    mut wind: ResMut<WindField>,
    sources: Query<SourceParts>,
    shelters: Query<ShelterParts>,
    hierarchy: Hierarchy,
) {
    let mut sheltering: Vec<(Entity, PlacedShelter)> = Vec::new();
    for (entity, shelter, invalid) in &shelters {
        let place = shelter
            .validate()
            .and_then(|()| world_place(entity, &hierarchy));
        let placed = place
            .as_ref()
            .ok()
            .and_then(|p| PlacedShelter::new(shelter, p));
        mark_on_change(
            &mut commands,
            entity,
            place.map(|_| ()),
            invalid,
            "WindShelter",
            NOTHING,
        );
        sheltering.extend(placed.map(|p| (entity, p)));
    }
    if !(sheltering.is_empty() && wind.shelter_count() == 0) {
        wind.set_shelters(in_entity_order(sheltering));
    }
    let now = wind.time_f64();
    // A source added before this step has blown since the step began.
    let started = wind.step_start();
    let mut placed: Vec<(Entity, PlacedSource)> = Vec::new();
    for (entity, source, start, invalid) in &sources {
        let start = match start {
            Some(s) if s.finished => continue,
            Some(s) => s.at,
            None => {
                commands.entity(entity).insert(SourceStart {
                    at: started,
                    finished: false,
                });
                started
            }
        };
        let place = source
            .validate()
            .and_then(|()| world_place(entity, &hierarchy));
        let here = place.as_ref().ok().copied();
        mark_on_change(
            &mut commands,
            entity,
            place.map(|_| ()),
            invalid,
            "WindSource",
            NOTHING,
        );
        if source.finished(now - start) {
            commands.entity(entity).insert(SourceStart {
                at: start,
                finished: true,
            });
            continue;
        }
        if let Some(p) = here.and_then(|here| PlacedSource::new(source, &here, start)) {
            placed.push((entity, p));
        }
    }
    if placed.is_empty() && wind.source_count() == 0 {
        return;
    }
    wind.set_sources(in_entity_order(placed));
}

/// What an invalid source or shelter does.
const NOTHING: &str = "it adds nothing to the wind";
