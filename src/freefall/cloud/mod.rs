//! Leaf clouds: thousands to hundreds of thousands of falling leaves in one entity.
//!
//! A [`LeafCloud`] is a [`FallingObject`] description times `count`: every leaf is a full
//! [`FallPath`](super::FallPath) (the same phase diagram, Markov chain, trajectory database,
//! search tree and wind coupling as a single `FallingObject`), but the leaves live in one
//! contiguous array in [`LeafCloudState`] instead of an entity each, are stepped in parallel
//! chunks of [`CloudLeaves::CHUNK`](crate::freefall::cloud::CloudLeaves::CHUNK), and are drawn (feature `render`, `render::LeafCloudRenderPlugin`) by
//! one draw of one mesh whose vertices read their leaf's pose from a storage buffer. No
//! `Transform` per leaf, no change detection, no transform propagation: that is what 10 000
//! single entities spend most of their frame on.
//!
//! # Levels of detail
//!
//! With a [`LodFocus`](crate::lod::LodFocus) (put it on the camera), each leaf's distance d from it picks a tier:
//!
//! | tier | distance | stepped every | shown |
//! |---|---|---|---|
//! | full | d < [`LodTiers::near`] | fixed step | Bézier between its last two steps |
//! | half | near ≤ d < [`LodTiers::far`] | 2nd fixed step | the same, over two steps |
//! | quarter | d ≥ far | 4th fixed step | the same, over four steps |
//!
//! With a [`LodView`](crate::lod::LodView) beside the focus, a leaf off screen and beyond `near` is at the quarter
//! tier wherever it is.
//!
//! A leaf stepped less often is advanced over the whole time since its last step, so it follows
//! the same path (the pieces are sampled by time) and lands at the same time; it reads the wind
//! less often. The leaves of a tier take turns (leaf i on steps where (step + i) is a multiple of
//! the period), so the cost per step is even. Changing tier never moves a leaf: the shown pose
//! runs from its last control point to the next over the share of the span that has passed.
//!
//! # Determinism
//!
//! Leaf i's stream is seeded from the cloud's seed and i (and how many times it was let go), and
//! leaves do not interact, so a cloud gives the same bits on one thread or many
//! (`tests/it/cloud.rs`).

mod leaves;
mod plugin;

use crate::lod::LodTiers;
pub use leaves::{CloudLeaves, CloudStep, CloudStepReport, LeafPose};
pub use plugin::{LeafCloudPlugin, LeafCloudState};

use crate::error::InvalidValue;
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

use super::model::FallModel;
use super::model::error::FallError;
use super::object::FallingObject;

/// A box the leaves are let go in, world coordinates, m.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Default, Debug)]
pub struct CloudRegion {
    /// The lowest corner.
    pub min: Vec3,
    /// The highest corner.
    pub max: Vec3,
}

impl Default for CloudRegion {
    /// 20 m × 20 m, from 2 m to 12 m up, centred on the origin.
    fn default() -> Self {
        Self {
            min: Vec3::new(-10.0, 2.0, -10.0),
            max: Vec3::new(10.0, 12.0, 10.0),
        }
    }
}

/// A cloud of `count` falling leaves (or paper, confetti, ash) let go in `region`.
///
/// Each leaf falls as a single [`FallingObject`] with the description `object` would (its own
/// seed from the cloud's `seed` and its index), lands on [`FallSettings::ground_height`],
/// stays there, and is lifted again by a strong enough wind as a single object is. Change the
/// component to let the whole cloud go again. The cloud's own `Transform` does not move the
/// leaves: they live in world space.
///
/// [`FallSettings::ground_height`]: super::FallSettings::ground_height
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::{FallPreset, LeafCloud, LeafCloudState};
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// let storm = app
///     .world_mut()
///     .spawn(LeafCloud {
///         object: FallPreset::MapleLeaf.object(),
///         count: 2_000,
///         ..default()
///     })
///     .id();
/// app.update();
/// let leaves = app.world().get::<LeafCloudState>(storm).unwrap().leaves().unwrap();
/// assert_eq!(leaves.len(), 2_000);
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform, LeafCloudState)]
pub struct LeafCloud {
    /// What each leaf is (its `seed` is mixed into the cloud's).
    pub object: FallingObject,
    /// How many leaves (≤ [`LeafCloud::MAX_LEAVES`](crate::freefall::LeafCloud::MAX_LEAVES)).
    pub count: u32,
    /// Seed of the whole cloud.
    pub seed: u64,
    /// Where they are let go.
    pub region: CloudRegion,
    /// Levels of detail.
    pub lod: LodTiers,
    /// A leaf resting this long, s, is let go again from the top of the region (`None`: leaves
    /// stay down until the wind lifts them).
    pub recycle_after: Option<f32>,
}

impl Default for LeafCloud {
    /// 10 000 default leaves in the default region, staying down once landed.
    fn default() -> Self {
        Self {
            object: FallingObject::default(),
            count: 10_000,
            seed: 0,
            region: CloudRegion::default(),
            lod: LodTiers::default(),
            recycle_after: None,
        }
    }
}

impl LeafCloud {
    /// Checks every field (the error names it: `count`, `region.min`, `lod.near`, ...) and
    /// builds the leaves above `ground`.
    ///
    /// # Errors
    /// What [`FallingObject::regime`] rejects, a count above [`LeafCloud::MAX_LEAVES`](crate::freefall::LeafCloud::MAX_LEAVES), a region
    /// whose corners are not finite, beyond ±[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE) or not
    /// ordered, negative or NaN LOD distances (far < near), a `recycle_after` not finite and
    /// ≥ 0, or a ground that is not finite and within ±[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE).
    pub fn leaves(&self, model: &FallModel, ground: f32) -> Result<CloudLeaves, FallError> {
        let regime = self.object.regime()?;
        InvalidValue::check(
            self.count <= LeafCloud::MAX_LEAVES,
            "count",
            self.count as f32,
            crate::error::reason!("must be ≤ {}", LeafCloud::MAX_LEAVES),
        )?;
        let within = |c: f32| c.abs() <= crate::guard::MAX_COORDINATE;
        let (min, max) = (self.region.min, self.region.max);
        if let Some(value) = crate::guard::first_refused(min, |_, c| within(c)) {
            InvalidValue::check(
                false,
                "region.min",
                value,
                "must be finite and within ±MAX_COORDINATE",
            )?;
        }
        let ordered = |axis: usize, c: f32| within(c) && c >= min.to_array()[axis];
        if let Some(value) = crate::guard::first_refused(max, ordered) {
            InvalidValue::check(
                false,
                "region.max",
                value,
                "must be finite, within ±MAX_COORDINATE and ≥ region.min on every axis",
            )?;
        }
        self.lod.check_as("lod.near", "lod.far")?;
        if let Some(t) = self.recycle_after {
            InvalidValue::check(
                t.is_finite() && t >= 0.0,
                "recycle_after",
                t,
                "must be finite and ≥ 0",
            )?;
        }
        // The ground single objects accept, but finite: a cloud's leaves always land.
        super::model::release::check_ground(ground, false)?;
        let chain = match &self.object.markov {
            Some(chain) => std::sync::Arc::new(chain.bounded(regime.main)),
            None => model.bounded_shared(regime.main),
        };
        Ok(CloudLeaves::new(
            model,
            self.object.scales(&regime),
            chain,
            self.count,
            self.seed ^ self.object.seed.rotate_left(32),
            self.region,
            ground,
            self.lod,
            self.object.wind_tilt,
            self.recycle_after,
        ))
    }
}

/// Why a [`LeafCloud`] does not fall: the error names the field. Inserted in place of the
/// leaves (logged once), removed once the component is changed and valid.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct LeafCloudInvalid(pub FallError);

crate::lifecycle::invalid_marker!(LeafCloudInvalid, FallError);

/// Limits and constants of [`LeafCloud`].
impl LeafCloud {
    /// Most leaves one cloud may hold.
    pub const MAX_LEAVES: u32 = 4_000_000;
}
