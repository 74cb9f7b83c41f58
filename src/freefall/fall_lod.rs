//! Levels of detail for a single falling object: [`FallLod`]. The store keeps falls of each tier
//! together and runs them on its clock (`freefall::store`, `store/clock.rs`).
//!
//! A fall in tier n (see [`LodTiers`](crate::lod::LodTiers)) is advanced every n-th fixed step
//! over the whole time since its last step, so it follows the same path (pieces are sampled by
//! time) and lands at the same time, reading the wind less often. What is shown runs along the
//! path's Bézier between its last two control points at the share of the last step's span that
//! has passed, so a fall stepped every fourth step moves as smoothly as one stepped every step.
//! When the steps grow further apart (a coarser tier) that span is shown over the longer wait.
//! When a step comes before the last span was shown (a change to a finer tier), what was shown
//! then is eased out over two old spans, so the shown pose never jumps.

use bevy::ecs::prelude::*;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use crate::lod::LodTiers;

/// Levels of detail for a single [`FallingObject`](super::object::FallingObject): with a
/// [`LodFocus`](crate::lod::LodFocus) on the camera, the object is stepped every fixed step
/// within `near` m of it, every second step to `far`, every fourth beyond, over the whole time
/// since its last step, exactly as a [`LeafCloud`](super::cloud::LeafCloud)'s leaves are. It follows
/// the same path (its pieces are sampled by time), reads the wind less often, moves smoothly
/// between its steps, and eases back without a jump when it comes nearer. Without this
/// component an object is stepped every fixed step.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::FallLod;
/// use bevy_windfall::prelude::*;
///
/// fn setup(mut commands: Commands) {
///     // On the camera (here an entity with only a transform).
///     commands.spawn((LodFocus, Transform::from_xyz(0.0, 2.0, 10.0)));
///     for i in 0..1000 {
///         commands.spawn((
///             FallingObject { seed: i, ..default() },
///             FallLod::default(),
///             Transform::from_xyz(i as f32 * 0.5, 10.0, 0.0),
///         ));
///     }
/// }
/// # let _ = setup;
/// ```
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct FallLod(pub LodTiers);

impl crate::lod::HasLodTiers for FallLod {
    fn tiers(&self) -> LodTiers {
        self.0
    }
}
