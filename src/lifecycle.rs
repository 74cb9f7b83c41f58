//! The one lifecycle every described component follows ([`FallingObject`], [`LeafCloud`],
//! [`Cloth`], [`PhysicalCloth`]): it is set up the moment it is inserted (an observer) and again
//! whenever its description changes (change detection, in [`WindfallSystems::WriteBack`]); a
//! description that cannot be set up gets its `…Invalid` marker holding the typed error, logged
//! once with `warn!`, and the marker goes once the description is fixed.
//!
//! [`FallingObject`]: crate::freefall::FallingObject
//! [`LeafCloud`]: crate::freefall::LeafCloud
//! [`Cloth`]: crate::cloth::Cloth
//! [`PhysicalCloth`]: crate::aero::PhysicalCloth
//! [`WindfallSystems::WriteBack`]: crate::schedule::WindfallSystems::WriteBack

use std::fmt::Display;

use bevy::ecs::component::Mutable;
use bevy::ecs::prelude::*;
use bevy::ecs::query::{IterQueryData, QueryData, QueryItem};
use bevy::ecs::system::{StaticSystemParam, SystemParam, SystemParamItem};

/// An `…Invalid` marker: a component holding why its entity is not simulated.
pub(crate) trait InvalidMarker: Component<Mutability = Mutable> + Sized {
    /// The typed error it holds.
    type Error: Display + PartialEq + Clone + Send + Sync + 'static;
    /// The marker for `error`.
    fn new(error: Self::Error) -> Self;
    /// The error it holds.
    fn error(&self) -> &Self::Error;
    /// The field its error names (`"transform"` for a transform that cannot place the entity).
    fn field(&self) -> &'static str;
}

/// Implements [`InvalidMarker`] for a tuple struct `Marker(pub Error)`.
macro_rules! invalid_marker {
    ($marker:ty, $error:ty) => {
        $crate::lifecycle::invalid_marker!($marker, $error, |e: &$error| e.field());
    };
    ($marker:ty, $error:ty, $field:expr) => {
        impl $crate::lifecycle::InvalidMarker for $marker {
            type Error = $error;
            fn new(error: $error) -> Self {
                Self(error)
            }
            fn error(&self) -> &$error {
                &self.0
            }
            fn field(&self) -> &'static str {
                ($field)(&self.0)
            }
        }
    };
}
pub(crate) use invalid_marker;

/// Inserts or removes `entity`'s marker `I` after a check: an error that differs from the one it
/// holds is logged once (`"{subject} {entity}: {error}; {consequence}"`) and inserted; `Ok`
/// removes a marker it has.
pub(crate) fn mark<I: InvalidMarker>(
    commands: &mut Commands,
    entity: Entity,
    outcome: Result<(), I::Error>,
    current: Option<&I>,
    subject: &str,
    consequence: &str,
) {
    match outcome {
        Ok(()) => {
            if current.is_some() {
                commands.entity(entity).try_remove::<I>();
            }
        }
        Err(error) => {
            if current.is_none_or(|c| *c.error() != error) {
                bevy::log::warn!("{subject} {entity}: {error}; {consequence}");
                commands.entity(entity).try_insert(I::new(error));
            }
        }
    }
}

/// [`mark`] for a check of the description alone: a marker for the transform (which a check
/// made every step, [`mark_on_change`], put on and takes off) stays while the description is
/// fine, so that an edit does not clear a marker whose cause is still there.
pub(crate) fn mark_description<I: InvalidMarker>(
    commands: &mut Commands,
    entity: Entity,
    outcome: Result<(), I::Error>,
    current: Option<&I>,
    subject: &str,
    consequence: &str,
) {
    let placement = current.filter(|c| c.field() == TRANSFORM_FIELD);
    if !(outcome.is_ok() && placement.is_some()) {
        mark(commands, entity, outcome, current, subject, consequence);
    }
}

/// The field a transform's error names ([`crate::guard::check_affine`]).
const TRANSFORM_FIELD: &str = "transform";

/// [`mark`] for a check made every step (a transform that cannot place the entity): the marker
/// goes on when the check turns bad and off when it turns good, once each, however the error's
/// value (a coordinate, a determinant) changes meanwhile. `current` must be a marker only this
/// check puts on (an entity with a state had no set-up error).
pub(crate) fn mark_on_change<I: InvalidMarker>(
    commands: &mut Commands,
    entity: Entity,
    outcome: Result<(), I::Error>,
    current: Option<&I>,
    subject: &str,
    consequence: &str,
) {
    if outcome.is_err() != current.is_some() {
        mark(commands, entity, outcome, current, subject, consequence);
    }
}

/// A component whose description is set up into a simulation (a fall, a cloud, a cloth), or
/// refused with a typed error. Its plugin adds the observers ([`observe`]) and the system
/// [`set_up_changed`] (in `WriteBack`, before anything reads its state).
pub(crate) trait Described: Component + Sized {
    /// Its marker.
    type Invalid: InvalidMarker;
    /// What of the description, when it changes, sets it up again (`follow_wind` alone does not
    /// rebuild a cloth).
    type Key: PartialEq + Send + Sync + 'static;
    /// What the set-up reads or writes on the entity (its state, its transform, its mesh).
    type Data: QueryData + IterQueryData;
    /// The resources the set-up reads.
    type Context: SystemParam;
    /// Its name in the log.
    const SUBJECT: &'static str;
    /// What happens to an invalid one, for the log ("it does not fall").
    const CONSEQUENCE: &'static str;
    /// Whether [`Self::set_up`] checks the entity's transform too; if not, a check made every
    /// step does ([`mark_on_change`]) and a set-up leaves its marker alone.
    const SET_UP_CHECKS_TRANSFORM: bool = true;

    /// The key of this description.
    fn key(&self) -> Self::Key;

    /// Sets the entity up; `None` when it cannot be tried now (a resource it needs is gone),
    /// which leaves everything as it is.
    fn set_up(
        &self,
        entity: Entity,
        data: QueryItem<'_, '_, Self::Data>,
        context: &mut SystemParamItem<Self::Context>,
        commands: &mut Commands,
    ) -> Option<Result<(), <Self::Invalid as InvalidMarker>::Error>>;
}

/// The key a component was last set up for (so that touching it without a change, or a change
/// of a field outside the key, does nothing).
#[derive(Component)]
pub(crate) struct SetUpFor<C: Described>(C::Key);

/// What the set-up reads of an entity: its description, the key it was set up for, its marker
/// and what [`Described::Data`] names.
type Parts<'a, C> = (
    &'a C,
    Option<&'a SetUpFor<C>>,
    Option<&'a <C as Described>::Invalid>,
    <C as Described>::Data,
);

/// [`Parts`] with the description's change ticks, to tell a new one from a replaced one.
type Inserted<'a, C> = (
    Ref<'a, C>,
    Option<&'a SetUpFor<C>>,
    Option<&'a <C as Described>::Invalid>,
    <C as Described>::Data,
);

/// The system that sets up every `C` changed this frame.
pub(crate) fn set_up_changed<C: Described>(
    mut commands: Commands,
    mut described: Query<(Entity, Parts<C>), Changed<C>>,
    context: StaticSystemParam<C::Context>,
) {
    let mut context = context.into_inner();
    for (entity, (c, memo, invalid, data)) in described.iter_mut() {
        set_up(&mut commands, entity, c, memo, invalid, data, &mut context);
    }
}

/// The system that sets up every `C` that has not been (one spawned while a resource its set-up
/// needs was gone, such as the `FallModel`): its plugin runs it when that resource returns, so
/// nothing is left idle without a marker. One refused before is checked again (and logged only
/// if its error changed).
pub(crate) fn set_up_pending<C: Described>(
    mut commands: Commands,
    mut described: Query<(Entity, Parts<C>), Without<SetUpFor<C>>>,
    context: StaticSystemParam<C::Context>,
) {
    let mut context = context.into_inner();
    for (entity, (c, memo, invalid, data)) in described.iter_mut() {
        set_up(&mut commands, entity, c, memo, invalid, data, &mut context);
    }
}

/// Adds `C`'s observer: set up on insertion. The plugin adds [`set_up_changed`] to its
/// write-back systems.
pub(crate) fn observe<C: Described>(app: &mut bevy::app::App) {
    app.add_observer(set_up_on_insert::<C>)
        .add_observer(forget_on_remove::<C>);
}

/// The observer that takes `C`'s marker and memo with it when `C` is removed: a marker stands
/// for the description it refused, so it goes with the description (as [`LodInvalid`] does).
///
/// [`LodInvalid`]: crate::lod::LodInvalid
fn forget_on_remove<C: Described>(event: On<Remove<C>>, mut commands: Commands) {
    commands
        .entity(event.entity)
        .try_remove::<(C::Invalid, SetUpFor<C>)>();
}

/// The observer that sets `C` up the moment it is inserted (in the frame it was spawned).
fn set_up_on_insert<C: Described>(
    event: On<Insert<C>>,
    mut commands: Commands,
    mut described: Query<Inserted<C>>,
    context: StaticSystemParam<C::Context>,
) {
    let mut context = context.into_inner();
    if let Ok((c, memo, invalid, data)) = described.get_mut(event.entity) {
        // Newly added (spawned, or inserted again after a removal): the memo of an earlier
        // life does not count. Replaced: set up only if the description changed.
        let memo = memo.filter(|_| !c.is_added());
        let c = c.into_inner();
        set_up(
            &mut commands,
            event.entity,
            c,
            memo,
            invalid,
            data,
            &mut context,
        );
    }
}

fn set_up<C: Described>(
    commands: &mut Commands,
    entity: Entity,
    c: &C,
    memo: Option<&SetUpFor<C>>,
    invalid: Option<&C::Invalid>,
    data: QueryItem<'_, '_, C::Data>,
    context: &mut SystemParamItem<C::Context>,
) {
    let key = c.key();
    // Set up already for this description (and valid, or refused for the same reason below).
    if memo.is_some_and(|m| m.0 == key) {
        return;
    }
    if let Some(outcome) = c.set_up(entity, data, context, commands) {
        // A refused description keeps no memo, so it is checked again whenever it is written
        // to (one refused for its transform or a resource starts once they are fixed); the
        // marker's error comparison (NaN-safe) keeps the log to one line.
        match &outcome {
            Ok(()) => {
                commands.entity(entity).try_insert(SetUpFor::<C>(key));
            }
            Err(_) => {
                commands.entity(entity).try_remove::<SetUpFor<C>>();
            }
        }
        let mark = if C::SET_UP_CHECKS_TRANSFORM {
            mark::<C::Invalid>
        } else {
            mark_description::<C::Invalid>
        };
        mark(
            commands,
            entity,
            outcome,
            invalid,
            C::SUBJECT,
            C::CONSEQUENCE,
        );
    }
}
