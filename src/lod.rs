//! Levels of detail: what is far from the camera is worked on less.
//!
//! Put a [`LodFocus`] on the camera. Each thing that has levels of detail measures its distance
//! d from it and picks a tier of [`LodTiers`]: 1 within `near`, 2 from `near` to `far`, 4
//! beyond. What the tier means depends on the thing:
//!
//! | what | opt in | tier 2 / 4 | shown |
//! |---|---|---|---|
//! | leaves of a [`LeafCloud`](crate::freefall::LeafCloud) | its `lod` field | stepped every 2nd / 4th fixed step | along the path's Bézier over the longer span; a change to a finer tier eases in |
//! | a single [`FallingObject`](crate::freefall::FallingObject) | [`FallLod`](crate::freefall::FallLod) | the same | the same |
//! | a [`Cloth`](crate::cloth::Cloth) | [`ClothLod`](crate::cloth::ClothLod) | every 2nd / 4th yarn and node traced, the rest interpolated | a change of tier cross-fades |
//!
//! Without a focus everything is at full detail. Tiers that fail their check (a NaN or
//! negative `near`, a `far` below `near`) on a `FallLod` or `ClothLod` mean full detail, and the
//! entity gets a [`LodInvalid`] naming the field (logged once with `warn!`) until they are
//! fixed or removed.

use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::GlobalTransform;

/// Where levels of detail are measured from: put it on the camera. With several, the lowest
/// `Entity` (by its ordering) counts; with none, everything is at full detail.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct LodFocus;

/// The distances, m, from the [`LodFocus`] at which the tier goes from 1 to 2 (`near`) and
/// from 2 to 4 (`far`). See the [module](self) for what a tier does.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Default, Debug)]
pub struct LodTiers {
    /// Nearer than this: tier 1 (full detail).
    pub near: f32,
    /// Nearer than this: tier 2; farther: tier 4.
    pub far: f32,
}

impl Default for LodTiers {
    /// Tier 1 within 25 m, 2 to 60 m, 4 beyond.
    fn default() -> Self {
        Self {
            near: 25.0,
            far: 60.0,
        }
    }
}

impl LodTiers {
    /// Tier 1 at any distance.
    pub const FULL: Self = Self {
        near: f32::INFINITY,
        far: f32::INFINITY,
    };

    /// The tier (1, 2 or 4) at `distance` m from the focus (`None`, NaN: 1). Tiers that do not
    /// pass their check (a NaN or negative `near`, a `far` below `near`) give 1 everywhere:
    /// full detail. ([`LeafCloud`](crate::freefall::LeafCloud) refuses them with the field
    /// named; on a [`FallLod`](crate::freefall::FallLod) or [`ClothLod`](crate::cloth::ClothLod)
    /// they turn the levels of detail off and put a [`LodInvalid`] on the entity.)
    pub fn steps_at(&self, distance: Option<f32>) -> u32 {
        self.steps_at_squared(distance.map(|d| d * d.abs()))
    }

    /// [`Self::steps_at`] from the squared distance (no square root per object).
    pub(crate) fn steps_at_squared(&self, squared: Option<f32>) -> u32 {
        if self.check().is_err() {
            return 1;
        }
        // (Checked: 0 ≤ near ≤ far. An infinite distance never reaches an infinite threshold.)
        match squared {
            Some(d2) if self.far < f32::INFINITY && d2 >= self.far * self.far => 4,
            Some(d2) if self.near < f32::INFINITY && d2 >= self.near * self.near => 2,
            _ => 1,
        }
    }

    /// Checks the distances: `near` ≥ 0 and `far` ≥ `near`, neither NaN. On failure, the name
    /// of the bad field (`near` or `far`), its value and why.
    pub(crate) fn check(&self) -> Result<(), (&'static str, f32, &'static str)> {
        if self.near.is_nan() || self.near < 0.0 {
            return Err(("near", self.near, "must be ≥ 0"));
        }
        if self.far.is_nan() || self.far < self.near {
            return Err(("far", self.far, "must be ≥ near"));
        }
        Ok(())
    }
}

/// Why an entity's levels of detail are off: its `FallLod` or `ClothLod` failed the check.
#[derive(Clone, Debug, PartialEq, thiserror::Error, Reflect)]
#[reflect(Debug)]
pub enum LodError {
    /// A distance outside its valid range.
    #[error("`{field}` = {value}: {reason}")]
    Invalid {
        /// The field's name (`near` or `far`).
        field: &'static str,
        /// The rejected value.
        value: f32,
        /// What it must be.
        reason: &'static str,
    },
}

impl LodError {
    /// Name of the offending field.
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid { field, .. } => field,
        }
    }
}

/// On an entity whose `FallLod` or `ClothLod` tiers fail their check: the error. The entity is
/// worked on at full detail meanwhile; the component goes when the tiers are fixed or removed.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::cloth::ClothLod;
/// use bevy_windfall::lod::{LodInvalid, LodTiers};
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, AssetPlugin::default()))
///     .init_asset::<Mesh>()
///     .add_plugins(ClothPlugin);
/// let cloth = app
///     .world_mut()
///     .spawn((Cloth::default(), ClothLod(LodTiers { near: 30.0, far: 10.0 })))
///     .id();
/// app.update();
/// let invalid = app.world().get::<LodInvalid>(cloth).unwrap();
/// assert_eq!(invalid.0.field(), "far");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct LodInvalid(pub LodError);

/// A component that carries [`LodTiers`] (`FallLod`, `ClothLod`).
pub(crate) trait HasLodTiers: Component {
    fn tiers(&self) -> LodTiers;
}

/// Puts a [`LodInvalid`] on entities whose tiers of `C` changed and fail their check (warned
/// once), takes it off when they pass or `C` is removed.
pub(crate) fn check_tiers<C: HasLodTiers>(
    mut commands: Commands,
    changed: Query<(Entity, &C, Option<&LodInvalid>), Changed<C>>,
    mut removed: RemovedComponents<C>,
    marked: Query<(), With<LodInvalid>>,
) {
    for (entity, component, invalid) in &changed {
        match component.tiers().check() {
            Ok(()) => {
                if invalid.is_some() {
                    commands.entity(entity).remove::<LodInvalid>();
                }
            }
            Err((field, value, reason)) => {
                let error = LodError::Invalid {
                    field,
                    value,
                    reason,
                };
                if invalid.is_none_or(|i| i.0 != error) {
                    bevy::log::warn!("levels of detail of {entity}: {error}; full detail instead");
                    commands.entity(entity).insert(LodInvalid(error));
                }
            }
        }
    }
    for entity in removed.read() {
        if marked.contains(entity)
            && let Ok(mut e) = commands.get_entity(entity)
        {
            e.remove::<LodInvalid>();
        }
    }
}

/// The focus: the [`LodFocus`] with the lowest entity, where it is (`None` if there is none or
/// its position is not finite).
pub(crate) fn focus(foci: &Query<(Entity, &GlobalTransform), With<LodFocus>>) -> Option<Vec3> {
    foci.iter()
        .min_by_key(|(entity, _)| *entity)
        .map(|(_, t)| t.translation())
        .filter(|p| p.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiers_by_distance() {
        let tiers = LodTiers::default();
        assert_eq!(tiers.steps_at(None), 1);
        assert_eq!(tiers.steps_at(Some(f32::NAN)), 1);
        assert_eq!(tiers.steps_at(Some(24.9)), 1);
        assert_eq!(tiers.steps_at(Some(25.0)), 2);
        assert_eq!(tiers.steps_at(Some(60.0)), 4);
        assert_eq!(LodTiers::FULL.steps_at(Some(1e30)), 1);
        // Tiers that fail their check are full detail everywhere.
        let upside_down = LodTiers {
            near: 10.0,
            far: -1.0,
        };
        assert_eq!(upside_down.steps_at(Some(100.0)), 1);
        assert_eq!(
            LodTiers {
                near: f32::NAN,
                far: 1.0
            }
            .check()
            .unwrap_err()
            .0,
            "near"
        );
        assert_eq!(
            LodTiers {
                near: 2.0,
                far: 1.0
            }
            .check()
            .unwrap_err()
            .0,
            "far"
        );
    }
}
