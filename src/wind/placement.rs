//! Placing the local wind each fixed step: the systems that check every [`WindSource`] and
//! [`WindShelter`], find where it stands from its entity's world transform (its scale ignored)
//! and put it in the [`WindField`], in entity order.

use bevy::ecs::prelude::*;
use bevy::math::{Affine3A, Quat};
use bevy::transform::components::Transform;

use super::error::WindError;
use super::field::WindField;
use super::local::Placement;
use super::shelter::{PlacedShelter, WindShelter, WindShelterInvalid};
use super::source::{PlacedSource, WindSource, WindSourceInvalid};
use crate::error::InvalidValue;
use crate::lifecycle::{mark_description, mark_on_change};

/// Whether [`place_wind_sources`] has work: a field, and a source or shelter to place or placed
/// ones to clear.
pub(super) fn anything_to_place(
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

/// The transforms of the entities that hold sources and shelters, and of their ancestors.
pub(super) type Hierarchy<'w, 's> = Query<'w, 's, (&'static Transform, Option<&'static ChildOf>)>;

/// Most ancestors followed up from a source or shelter (a deeper chain places nothing).
const MAX_DEPTH: usize = 256;

/// Where `entity` stands this step, from the `Transform`s of it and its ancestors (current even
/// in the frame it was spawned or moved, before Bevy propagates them): its origin is where its
/// parents' transforms, scales included, put it; its rotation is its own and its ancestors'
/// rotations composed, whatever their scales (a zero, negative or huge scale neither removes nor
/// turns a source: sizes are in metres). A transform that places it nowhere is an error naming
/// `transform`.
pub(super) fn world_place(entity: Entity, hierarchy: &Hierarchy) -> Result<Placement, WindError> {
    let nowhere = |value| {
        WindError::from(InvalidValue::new(
            "transform",
            value,
            crate::error::reason!(
                "must place it at a finite point within ±MAX_COORDINATE ({:e} m), turned by a \
                 finite rotation",
                crate::guard::MAX_COORDINATE
            ),
        ))
    };
    let (mut affine, mut rotation) = (Affine3A::IDENTITY, Quat::IDENTITY);
    let mut at = Some(entity);
    for _ in 0..MAX_DEPTH {
        let Some(e) = at else {
            let origin = affine.translation;
            return Placement::new(origin, rotation)
                .ok_or_else(|| nowhere(crate::guard::largest_component(origin.into())));
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
pub(super) fn in_entity_order<T>(mut items: Vec<(Entity, T)>) -> Vec<T> {
    items.sort_by_key(|(entity, _)| *entity);
    items.into_iter().map(|(_, t)| t).collect()
}

/// What placing a shelter reads.
type ShelterParts = (
    Entity,
    &'static WindShelter,
    Option<&'static WindShelterInvalid>,
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
pub(super) struct SourceStart {
    at: f64,
    finished: bool,
}

/// A source inserted (again) starts again: a blast fires anew. Its numbers are checked at once
/// (the transform when it is placed).
pub(super) fn restart_source(
    event: On<Insert<WindSource>>,
    mut commands: Commands,
    sources: Query<(&WindSource, Option<&WindSourceInvalid>)>,
) {
    if let Ok(mut e) = commands.get_entity(event.entity) {
        e.try_remove::<SourceStart>();
    }
    if let Ok((source, invalid)) = sources.get(event.entity) {
        let outcome = source.validate();
        mark_description(
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
pub(super) fn check_shelter(
    event: On<Insert<WindShelter>>,
    mut commands: Commands,
    shelters: Query<(&WindShelter, Option<&WindShelterInvalid>)>,
) {
    if let Ok((shelter, invalid)) = shelters.get(event.entity) {
        let outcome = shelter.validate();
        mark_description(
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
/// gets a [`WindSourceInvalid`] (a shelter a [`WindShelterInvalid`]).
pub(super) fn place_wind_sources(
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
                commands.entity(entity).try_insert(SourceStart {
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
        if here.is_some() && source.finished(now - start) {
            commands.entity(entity).try_insert(SourceStart {
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
