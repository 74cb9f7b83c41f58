//! Shelter: [`WindShelter`] boxes that calm the global wind in their lee (a wall, a hedge, a
//! house) or inside them (a room).

use super::local::{Placement, check_size, fade, size};
use super::source::turn;
use bevy::ecs::component::Component;
use bevy::ecs::reflect::ReflectComponent;
use bevy::math::{Quat, Vec3, Vec3A};

use super::error::WindError;
use crate::error::InvalidValue;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

/// What a [`WindShelter`] does.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub enum ShelterKind {
    /// A solid obstacle: no wind inside it, and the wind in its lee (downwind of it, below its
    /// top and within its width) cut by up to `depth` (0..1) right behind it, recovering over
    /// `lee_heights` times its height.
    Wall {
        /// The lee's length in heights of the box.
        lee_heights: f32,
        /// How much of the wind is taken right behind it (0: none, 1: all).
        depth: f32,
    },
    /// A room: no global wind inside the box (a quarter of a metre of transition at its walls).
    Indoor,
}

/// A box (its entity's position and rotation, `half_extents` in metres; scale is ignored) that
/// shelters from the global wind: a wall's lee or a room. Shelters act on the
/// [`WindField`](super::field::WindField)'s log-law wind and turbulence, not on
/// [`WindSource`](super::source::WindSource)s, so a fan indoors still blows. Placed at each fixed step,
/// like sources.
///
/// The lee of a wall: behind a solid fence the wind is reduced most at about one to three
/// heights and recovers by about ten (wind-tunnel and field studies of windbreaks); the profile
/// here is the fade (1 − s²)² of the distance past the downwind face over `lee_heights` × height,
/// full below the top and fading over half a height above it and beside it.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::wind::WindShelter;
///
/// fn setup(mut commands: Commands) {
///     // A 2 m garden wall, 10 m long, and a 4 × 3 × 5 m shed with no wind inside.
///     commands.spawn((WindShelter::wall(Vec3::new(0.1, 1.0, 5.0)), Transform::from_xyz(0.0, 1.0, 0.0)));
///     commands.spawn((WindShelter::indoor(Vec3::new(2.0, 1.5, 2.5)), Transform::from_xyz(8.0, 1.5, 0.0)));
/// }
/// # let _ = setup;
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform)]
pub struct WindShelter {
    /// Wall or room.
    pub kind: ShelterKind,
    /// Half the box's sides along local x, y, z, m.
    pub half_extents: Vec3,
}

impl Default for WindShelter {
    /// A wall 2 m high, 6 m long and 20 cm thick.
    fn default() -> Self {
        Self::wall(Vec3::new(0.1, 1.0, 3.0))
    }
}

impl WindShelter {
    /// A solid wall (or hedge, or house) of `half_extents`: its lee is 8 heights long and loses
    /// up to 85 % of the wind. Sizes a plugin cannot place (see [`Self::validate`]) shelter
    /// nothing and the entity gets a [`WindShelterInvalid`] naming the side.
    pub fn wall(half_extents: Vec3) -> Self {
        Self {
            kind: ShelterKind::Wall {
                lee_heights: 8.0,
                depth: 0.85,
            },
            half_extents,
        }
    }

    /// Checks the numbers a plugin would place: half extents finite and within
    /// 0..=[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE), and for a wall `lee_heights` finite
    /// and ≥ 0 and `depth` in [0, 1]. What fails here shelters nothing and the entity gets a
    /// [`WindShelterInvalid`] naming the field.
    ///
    /// # Errors
    /// The first field that fails, named (`half_extents.x`, `.y`, `.z`, `kind.lee_heights`,
    /// `kind.depth`).
    pub fn validate(&self) -> Result<(), WindError> {
        let h = self.half_extents;
        check_size("half_extents.x", h.x)?;
        check_size("half_extents.y", h.y)?;
        check_size("half_extents.z", h.z)?;
        if let ShelterKind::Wall { lee_heights, depth } = self.kind {
            InvalidValue::check(
                lee_heights.is_finite() && lee_heights >= 0.0,
                "kind.lee_heights",
                lee_heights,
                "must be finite and ≥ 0",
            )?;
            InvalidValue::check(
                (0.0..=1.0).contains(&depth),
                "kind.depth",
                depth,
                "must be in [0, 1]",
            )?;
        }
        Ok(())
    }

    /// A room of `half_extents` with no global wind inside.
    pub fn indoor(half_extents: Vec3) -> Self {
        Self {
            kind: ShelterKind::Indoor,
            half_extents,
        }
    }
}

/// The width of the transition at a room's walls, m.
pub(crate) const ROOM_EDGE: f32 = 0.25;

/// A shelter placed in the world for one fixed step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlacedShelter {
    pub(crate) kind: ShelterKind,
    pub(crate) half: Vec3,
    pub(crate) origin: Vec3A,
    pub(crate) to_local: Quat,
    pub(crate) reach2: f32,
}

impl PlacedShelter {
    /// `shelter` at `place`; `None` if it shelters nothing (a zero size). The plugin places only
    /// shelters that pass [`WindShelter::validate`] (checked once, there).
    pub(crate) fn new(shelter: &WindShelter, place: &Placement) -> Option<Self> {
        let half = shelter.half_extents.map(size);
        if half.min_element() <= 0.0 {
            return None;
        }
        let reach = match shelter.kind {
            ShelterKind::Indoor => half.length() + ROOM_EDGE,
            ShelterKind::Wall { lee_heights, .. } => {
                let height = 2.0 * half.y;
                half.length() + size(lee_heights) * height + height
            }
        };
        Some(Self {
            kind: shelter.kind,
            half,
            origin: place.origin,
            to_local: place.to_local,
            reach2: reach * reach,
        })
    }

    /// The share of the global wind left at `p` (1: none taken) when the mean wind blows along
    /// the unit vector `downwind`.
    pub(crate) fn factor(&self, p: Vec3A, downwind: Vec3) -> f32 {
        let d = p - self.origin;
        let r2 = Vec3::from(d).length_squared();
        if r2.is_nan() || r2 >= self.reach2 {
            return 1.0;
        }
        let local = turn(self.to_local, Vec3::from(d));
        // Distance outside the box (0 inside).
        let outside = (local.abs() - self.half).max(Vec3::ZERO).length();
        match self.kind {
            ShelterKind::Indoor => 1.0 - fade(outside / ROOM_EDGE),
            ShelterKind::Wall { lee_heights, depth } => {
                if outside == 0.0 {
                    return 0.0;
                }
                let height = 2.0 * self.half.y;
                let length = (size(lee_heights) * height).max(f32::MIN_POSITIVE);
                // Downwind and across, horizontally, in the box's frame.
                let wind = turn(self.to_local, downwind);
                let wind = Vec3::new(wind.x, 0.0, wind.z).normalize_or_zero();
                let side = Vec3::new(-wind.z, 0.0, wind.x);
                // Half the box's extent along and across the wind.
                let deep = self.half.x * wind.x.abs() + self.half.z * wind.z.abs();
                let wide = self.half.x * side.x.abs() + self.half.z * side.z.abs();
                let past = local.dot(wind) - deep;
                if past <= 0.0 || past >= length {
                    return 1.0;
                }
                let aside = (local.dot(side).abs() - wide).max(0.0) / (0.5 * height);
                let above = (local.y - self.half.y).max(0.0) / (0.5 * height);
                let below = local.y < -self.half.y;
                if below {
                    return 1.0;
                }
                1.0 - depth.clamp(0.0, 1.0) * fade(past / length) * fade(aside) * fade(above)
            }
        }
    }
}

/// Why a [`WindShelter`] calms nothing: a number that is not finite or out of range, or a
/// transform that places it nowhere (the error names the field). Inserted when the problem
/// appears (logged once), removed once it is gone; the other shelters and sources go on.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct WindShelterInvalid(pub WindError);

crate::lifecycle::invalid_marker!(WindShelterInvalid, WindError);
