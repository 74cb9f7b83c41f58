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
//! **Off screen.** With a [`LodView`] beside the focus, what lies outside the cone it sees and
//! beyond `near` takes the coarsest tier the tiers allow (4, or 2 if `far` is infinite), at any
//! distance: a storm behind the camera costs what a distant one does. Within `near` nothing is
//! coarsened (its shadow may be on screen). [`LodView::from_fov`] makes the cone of a
//! perspective camera.
//!
//! Without a focus everything is at full detail. Tiers that fail their check (a NaN or
//! negative `near`, a `far` below `near`) on a `FallLod` or `ClothLod` mean full detail, and the
//! entity gets a [`LodInvalid`] naming the field (logged once with `warn!`) until they are
//! fixed or removed.

use crate::error::InvalidValue;
use std::f32::consts::PI;

use bevy::ecs::prelude::*;
use bevy::math::{DVec3, Vec3};
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
        self.steps_at_squared(distance.map(|d| f64::from(d) * f64::from(d.abs())))
    }

    /// [`Self::steps_at`] from the squared distance (no square root per object), in f64: the
    /// square of any f32 distance or threshold, up to `f32::MAX`, is exact enough and finite.
    pub(crate) fn steps_at_squared(&self, squared: Option<f64>) -> u32 {
        if self.check().is_err() {
            return 1;
        }
        let (near, far) = (f64::from(self.near), f64::from(self.far));
        // (Checked: 0 ≤ near ≤ far. An infinite distance never reaches an infinite threshold.)
        match squared {
            Some(d2) if far < f64::INFINITY && d2 >= far * far => 4,
            Some(d2) if near < f64::INFINITY && d2 >= near * near => 2,
            _ => 1,
        }
    }

    /// Checks the distances: `near` ≥ 0 and `far` ≥ `near`, neither NaN; the error names the
    /// bad field (`near` or `far`).
    pub(crate) fn check(&self) -> Result<(), InvalidValue> {
        self.check_as("near", "far")
    }

    /// [`Self::check`], the fields named `near` and `far` as the holder calls them (a cloud's
    /// `lod.near`).
    pub(crate) fn check_as(
        &self,
        near: &'static str,
        far: &'static str,
    ) -> Result<(), InvalidValue> {
        InvalidValue::check(
            !(self.near.is_nan() || self.near < 0.0),
            near,
            self.near,
            "must be ≥ 0",
        )?;
        InvalidValue::check(
            !(self.far.is_nan() || self.far < self.near),
            far,
            self.far,
            "must be ≥ near",
        )
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
///     .add_plugins(ClothPlugin::default());
/// let cloth = app
///     .world_mut()
///     .spawn((Cloth::default(), ClothLod(LodTiers { near: 30.0, far: 10.0 })))
///     .id();
/// app.update();
/// let invalid = app.world().get::<LodInvalid>(cloth).unwrap();
/// assert_eq!(invalid.0.field, "far");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct LodInvalid(pub InvalidValue);

crate::lifecycle::invalid_marker!(LodInvalid, InvalidValue, |e: &InvalidValue| e.field);

/// A component that carries [`LodTiers`] (`FallLod`, `ClothLod`).
pub(crate) trait HasLodTiers: Component {
    fn tiers(&self) -> LodTiers;
}

/// Registers the level-of-detail types that every plugin with levels of detail shares (the
/// focus, the view cone, the tiers and their refusal), for reflection: one list, called by each
/// such plugin, since each can be added alone.
pub(crate) fn register_types(app: &mut bevy::app::App) {
    app.register_type::<LodFocus>()
        .register_type::<LodView>()
        .register_type::<LodTiers>()
        .register_type::<LodInvalid>();
}

/// Whether [`check_tiers`] has anything to do: a `C` to check, or a [`LodInvalid`] that a
/// removed `C` may leave behind.
pub(crate) fn any_tiers<C: HasLodTiers>(
    tiers: Query<(), With<C>>,
    invalid: Query<(), With<LodInvalid>>,
) -> bool {
    !(tiers.is_empty() && invalid.is_empty())
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
        crate::lifecycle::mark(
            &mut commands,
            entity,
            component.tiers().check(),
            invalid,
            "levels of detail of",
            "full detail instead",
        );
    }
    for entity in removed.read() {
        if marked.contains(entity)
            && let Ok(mut e) = commands.get_entity(entity)
        {
            e.try_remove::<LodInvalid>();
        }
    }
}

/// What the [`LodFocus`] sees, beside it on the same entity: a cone of half angle `half_angle`
/// about its forward direction (−Z of its `GlobalTransform`, where a Bevy camera looks). What is
/// outside the cone and beyond the tiers' `near` is worked on at the coarsest tier. Without it,
/// everything counts as on screen.
///
/// A NaN or negative `half_angle` counts as no view (everything on screen, warned by no one:
/// the safe side); one of π or more sees everything.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::lod::{LodFocus, LodView};
///
/// fn setup(mut commands: Commands) {
///     // Bevy's default perspective: 45° vertical field of view; a 16:9 window.
///     let view = LodView::from_fov(std::f32::consts::FRAC_PI_4, 16.0 / 9.0);
///     // On the camera (here an entity with only a transform, looking along −z).
///     commands.spawn((LodFocus, view, Transform::from_xyz(0.0, 2.0, 10.0)));
/// }
/// # let _ = setup;
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct LodView {
    /// Half the cone's opening angle, rad.
    pub half_angle: f32,
}

impl Default for LodView {
    /// The cone of Bevy's default perspective (45° vertical) on a 16:9 window:
    /// [`LodView::from_fov`]`(π/4, 16/9)`.
    fn default() -> Self {
        Self::from_fov(std::f32::consts::FRAC_PI_4, 16.0 / 9.0)
    }
}

impl LodView {
    /// Extra angle around a screen's corner, rad (10°): a leaf's centre just off screen can
    /// still show its edge, and the view turns between steps.
    pub const MARGIN: f32 = 0.175;

    /// The cone around a perspective camera's view: through the corners of a screen of vertical
    /// field of view `fov_y` (rad, as `PerspectiveProjection::fov`) and `aspect_ratio` (width
    /// over height), widened by [`Self::MARGIN`]. A field of view that is not in (0, π) or an
    /// aspect ratio that is not finite and > 0 gives a view that sees everything (no object is
    /// coarsened for being off screen).
    pub fn from_fov(fov_y: f32, aspect_ratio: f32) -> Self {
        let valid = fov_y > 0.0 && fov_y < PI && aspect_ratio > 0.0 && aspect_ratio.is_finite();
        if !valid {
            return Self { half_angle: PI };
        }
        // Portable libm (the tiers a leaf is stepped in follow from it); hypot, not
        // sqrt(1 + a²): a huge aspect ratio must not overflow to ∞ (and 0 × ∞ to NaN).
        let tan_y = libm::tanf(0.5 * fov_y);
        let half_diagonal = libm::atanf(tan_y * libm::hypotf(1.0, aspect_ratio));
        Self {
            half_angle: half_diagonal + Self::MARGIN,
        }
    }
}

/// Where levels of detail are measured from: the focus's position and, if it has a
/// [`LodView`], the cone it sees. The systems find it from [`LodFocus`]; code that steps a cloud
/// by hand ([`CloudStep`](crate::freefall::cloud::CloudStep)) makes it, from a position alone
/// with `Focus::from`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Focus {
    /// The focus, world space, m.
    pub position: Vec3,
    /// The unit direction it looks along and the cosine of its [`LodView::half_angle`] (`None`:
    /// everything on screen).
    pub view: Option<(Vec3, f32)>,
}

impl From<Vec3> for Focus {
    fn from(position: Vec3) -> Self {
        Self {
            position,
            view: None,
        }
    }
}

impl Focus {
    /// A focus at `position` looking along `forward` with `view`. A `forward` that cannot be
    /// normalised, or a view whose angle is NaN or negative, gives no view.
    pub fn looking(position: Vec3, forward: Vec3, view: LodView) -> Self {
        let cone = forward
            .try_normalize()
            .filter(|_| view.half_angle >= 0.0)
            .map(|f| (f, libm::cosf(view.half_angle.min(PI))));
        Self {
            position,
            view: cone,
        }
    }

    /// The tier (1, 2 or 4) of `tiers` for something at `at`: by its distance, or the coarsest
    /// the tiers allow when it is off screen and beyond `near`.
    /// Measured in f64: no distance between two f32 positions overflows.
    pub fn tier(&self, tiers: &LodTiers, at: Vec3) -> u32 {
        let offset = at.as_dvec3() - self.position.as_dvec3();
        let squared = offset.length_squared();
        let by_distance = tiers.steps_at_squared(Some(squared));
        if by_distance > 1 && !self.sees(offset, squared) {
            tiers.steps_at_squared(Some(f64::INFINITY))
        } else {
            by_distance
        }
    }

    /// Whether `offset` (from the focus, |offset|² = `squared`) lies in the view's cone: the
    /// angle to the forward direction at most the half angle, cos θ = f·o / |o| ≥ c, compared
    /// squared (no square root per object).
    fn sees(&self, offset: DVec3, squared: f64) -> bool {
        let Some((forward, cos_half)) = self.view else {
            return true;
        };
        let (forward, cos_half) = (forward.as_dvec3(), f64::from(cos_half));
        let along = forward.dot(offset);
        let bound = cos_half * cos_half * squared;
        match (along >= 0.0, cos_half >= 0.0) {
            (true, true) => along * along >= bound,
            (true, false) => true,
            (false, true) => false,
            (false, false) => along * along <= bound,
        }
    }
}

/// The [`LodFocus`] entities, with their views.
pub(crate) type Foci<'w, 's> =
    Query<'w, 's, (Entity, &'static GlobalTransform, Option<&'static LodView>), With<LodFocus>>;

/// The focus: the [`LodFocus`] with the lowest entity, where it is and what it sees (`None` if
/// there is none or its position is not finite; no view if its direction is not).
pub(crate) fn focus(foci: &Foci) -> Option<Focus> {
    let (_, transform, view) = foci.iter().min_by_key(|(entity, ..)| *entity)?;
    let position = transform.translation();
    if !position.is_finite() {
        return None;
    }
    Some(match view {
        Some(&view) => Focus::looking(position, transform.forward().as_vec3(), view),
        None => Focus::from(position),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Any field of view and aspect ratio gives a cone in (0, π], never NaN (a tiny field of
    /// view on a huge aspect ratio overflowed to 0 × ∞).
    #[test]
    fn extreme_views_give_a_cone() {
        let values = [1e-45, 1e-6, 1.0, 3.0, 1e30, f32::MAX, 0.0, -1.0, f32::NAN];
        for (fov, aspect) in values.iter().flat_map(|&f| values.map(|a| (f, a))) {
            let half = LodView::from_fov(fov, aspect).half_angle;
            assert!(
                half > 0.0 && half <= PI,
                "fov {fov}, aspect {aspect}: {half}"
            );
        }
    }

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
            .field,
            "near"
        );
        assert_eq!(
            LodTiers {
                near: 2.0,
                far: 1.0
            }
            .check()
            .unwrap_err()
            .field,
            "far"
        );
    }

    /// The cone: in front within the half angle, behind, to the side; what is within `near`
    /// keeps its tier; tiers that allow only 1 or 2 give those; a NaN view sees everything.
    #[test]
    fn off_screen_takes_the_coarsest_tier_beyond_near() {
        let tiers = LodTiers::default(); // 25 m, 60 m
        let view = LodView { half_angle: 0.5 };
        let focus = Focus::looking(Vec3::ZERO, Vec3::NEG_Z, view);
        let at = |angle: f32, d: f32| Vec3::new(angle.sin(), 0.0, -angle.cos()) * d;
        assert_eq!(focus.tier(&tiers, at(0.0, 30.0)), 2);
        assert_eq!(focus.tier(&tiers, at(0.49, 30.0)), 2);
        assert_eq!(focus.tier(&tiers, at(0.51, 30.0)), 4);
        assert_eq!(focus.tier(&tiers, at(3.0, 30.0)), 4);
        assert_eq!(focus.tier(&tiers, at(3.0, 10.0)), 1);
        assert_eq!(focus.tier(&tiers, at(0.0, 70.0)), 4);
        let no_far = LodTiers {
            near: 25.0,
            far: f32::INFINITY,
        };
        assert_eq!(focus.tier(&no_far, at(3.0, 30.0)), 2);
        assert_eq!(focus.tier(&LodTiers::FULL, at(3.0, 1e6)), 1);
        // A cone wider than a half-space: only a narrow cone behind is off screen.
        let wide = Focus::looking(Vec3::ZERO, Vec3::NEG_Z, LodView { half_angle: 2.5 });
        assert_eq!(wide.tier(&tiers, at(2.4, 30.0)), 2);
        assert_eq!(wide.tier(&tiers, at(2.6, 30.0)), 4);
        for bad in [f32::NAN, -1.0] {
            let blind = Focus::looking(Vec3::ZERO, Vec3::NEG_Z, LodView { half_angle: bad });
            assert_eq!(blind.tier(&tiers, at(3.0, 30.0)), 2);
        }
        let nowhere = Focus::looking(Vec3::ZERO, Vec3::NAN, view);
        assert_eq!(nowhere.tier(&tiers, at(3.0, 30.0)), 2);
    }

    /// Bevy's default camera on a 16:9 window: the screen's corners are seen, a point half as
    /// far again off the axis is not.
    #[test]
    fn the_default_view_covers_the_corners_of_the_screen() {
        let focus = Focus::looking(Vec3::ZERO, Vec3::NEG_Z, LodView::default());
        let tan_y = (std::f32::consts::PI / 8.0).tan();
        let corner = Vec3::new(tan_y * 16.0 / 9.0, tan_y, -1.0);
        let tiers = LodTiers::default();
        assert_eq!(focus.tier(&tiers, corner * 30.0), 2);
        assert_eq!(focus.tier(&tiers, -corner * 30.0), 4);
        let beyond = Vec3::new(corner.x * 1.5, corner.y * 1.5, -1.0);
        assert_eq!(focus.tier(&tiers, beyond * 30.0), 4);
        // Hostile fields of view or aspect ratios see everything: nothing is coarsened for it.
        for (fov, aspect) in [
            (f32::NAN, 1.0),
            (-1.0, 1.0),
            (0.0, 1.0),
            (4.0, 1.0),
            (1.0, 0.0),
        ]
        .into_iter()
        .chain([(1.0, f32::INFINITY), (1.0, f32::NAN)])
        {
            let view = LodView::from_fov(fov, aspect);
            let blind = Focus::looking(Vec3::ZERO, Vec3::NEG_Z, view);
            assert_eq!(blind.tier(&tiers, -corner * 30.0), 2, "{fov} {aspect}");
        }
        // A huge aspect ratio still gives a cone within a half-space plus the margin.
        let wide = LodView::from_fov(1.0, 1e30).half_angle;
        assert!(wide.is_finite() && wide <= 0.5 * PI + LodView::MARGIN + 1e-6);
    }
}
