//! [`FallStore`]: the falls of an app's [`FallingObject`](super::FallingObject)s, one fall
//! store (`freefall::store`) for all of them.

use bevy::ecs::entity::EntityHashMap;
use bevy::ecs::prelude::*;

use super::model::FallModel;
use super::store::Store;
use super::store::block::{ConstantStorage, FallConstants, PerFallConstants};
use super::store::cold::FallStart;
use super::store::view::FallView;
use crate::lod::LodTiers;

/// The falls of every [`FallingObject`](super::FallingObject) of the app (a resource of the
/// [`FallPlugin`](super::FallPlugin)): each object's fall is a slot of one structure of arrays,
/// stepped by the same driver as a [`LeafCloud`](super::LeafCloud)'s leaves. An object keeps
/// its components ([`FallState`](super::FallState) tells its regime and what it is doing);
/// read its whole fall here.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let leaf = app
///     .world_mut()
///     .spawn((FallingObject::default(), Transform::from_xyz(0.0, 3.0, 0.0)))
///     .id();
/// app.update();
/// let fall = app.world().resource::<FallStore>().fall(leaf).unwrap();
/// assert_eq!(fall.position(), Vec3::new(0.0, 3.0, 0.0));
/// ```
#[derive(Resource, Clone, Debug)]
pub struct FallStore {
    pub(crate) falls: Store<PerFallConstants>,
    /// The entity of each handle.
    entities: Vec<Option<Entity>>,
    handles: EntityHashMap<u32>,
}

impl Default for FallStore {
    fn default() -> Self {
        Self {
            falls: Store::new(PerFallConstants),
            entities: Vec::new(),
            handles: EntityHashMap::default(),
        }
    }
}

impl FallStore {
    /// `entity`'s fall, if it has one.
    pub fn fall(&self, entity: Entity) -> Option<FallView<'_>> {
        self.falls.view(*self.handles.get(&entity)?)
    }

    /// How many objects fall (or rest).
    pub fn len(&self) -> usize {
        self.falls.len()
    }

    /// True with no falling object.
    pub fn is_empty(&self) -> bool {
        self.falls.len() == 0
    }

    /// Every object's fall, with its entity.
    pub fn falls(&self) -> impl Iterator<Item = (Entity, FallView<'_>)> {
        self.handles
            .iter()
            .filter_map(|(&e, &h)| Some((e, self.falls.view(h)?)))
    }

    /// Bytes the falls take.
    pub fn memory_bytes(&self) -> usize {
        self.falls.memory_bytes()
    }

    /// Lets `entity`'s fall go as `start` says (again, in its slot, if it had one); returns
    /// its handle.
    pub(crate) fn set_up(&mut self, entity: Entity, model: &FallModel, start: &FallStart) -> u32 {
        if let Some(&handle) = self.handles.get(&entity) {
            self.falls.replace(handle, model, start);
            return handle;
        }
        let handle = self.falls.insert(model, start);
        let h = handle as usize;
        if self.entities.len() <= h {
            self.entities.resize(h + 1, None);
        }
        self.entities[h] = Some(entity);
        self.handles.insert(entity, handle);
        handle
    }

    /// Removes `entity`'s fall.
    pub(crate) fn remove(&mut self, entity: Entity) {
        if let Some(handle) = self.handles.remove(&entity) {
            self.falls.remove(handle);
            self.entities[handle as usize] = None;
        }
    }

    /// The entity of fall `handle`.
    pub(crate) fn entity(&self, handle: u32) -> Option<Entity> {
        self.entities.get(handle as usize).copied().flatten()
    }

    /// Sets `entity`'s levels of detail (taken up at its next step).
    pub(crate) fn set_lod(&mut self, entity: Entity, lod: Option<LodTiers>) {
        let Some(&handle) = self.handles.get(&entity) else {
            return;
        };
        let kind = self.falls.kind;
        if let Some(slot) = self.falls.slot(handle) {
            let c = kind.get(&slot.block.consts, slot.k);
            PerFallConstants::set(&mut slot.block.consts, slot.k, &FallConstants { lod, ..c });
        }
    }
}
