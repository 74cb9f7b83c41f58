//! [`FallPath`]: one fall on its own, a store of one stepped by the same driver as a cloud's
//! leaves and an app's falling objects.

use std::sync::Arc;

use bevy::math::{Quat, Vec3};

use super::Store;
use super::air::Air;
use super::block::{FallConstants, SharedConstants};
use super::cold::FallStart;
use super::slot::StepOutcome;
use super::step::Step;
use super::view::FallView;
use crate::freefall::model::FallModel;
use crate::freefall::model::error::FallError;
use crate::freefall::model::markov::BoundedChain;
use crate::freefall::model::motion::FallScales;
use crate::freefall::model::regime::PrimitiveMotion;
use crate::freefall::model::release::FallRelease;
use crate::freefall::model::tilt::WindTilt;

/// One falling object's fall through time (§4 of the free-fall paper): the Markov chain picks
/// primitive motions, pieces give the still-fluid path f(t), the fluid carries it (§4.2)
/// through a response time, Béziers smooth what is shown. Stepped one at a time with
/// [`FallPath::advance`]; a [`LeafCloud`](crate::freefall::LeafCloud)'s leaves and the app's
/// [`FallingObject`](crate::freefall::FallingObject)s fall by the same step, many at a time.
///
/// # Example
///
/// ```
/// use bevy::math::Vec3;
/// use bevy_windfall::freefall::{FallModel, FallPath, FallingObject, WindTilt};
///
/// let model = FallModel::default();
/// let leaf = FallingObject::default();
/// let regime = leaf.regime().unwrap();
/// let mut path = FallPath::new(&model, leaf.scales(&regime), regime.main, 7, Vec3::Y * 3.0, 0.0)
///     .unwrap();
/// let tilt = WindTilt { max_angle: 0.6, reference_speed: 4.0 };
/// while !path.landed() {
///     path.advance(&model, 1.0 / 60.0, Vec3::new(2.0, 0.0, 0.0), &tilt);
/// }
/// assert!(path.position().x > 0.5, "the breeze carried it");
/// ```
#[derive(Clone, Debug)]
pub struct FallPath {
    store: Store<SharedConstants>,
}

impl FallPath {
    /// A fall with main motion `main` and the model's chain, let go at rest at `position`,
    /// flat, with a heading from the seed, landing at height `ground` (−∞: never).
    ///
    /// # Errors
    /// A `position` or `ground` that [`FallRelease::validate`] refuses (not finite, or beyond
    /// ±[`MAX_COORDINATE`](crate::guard::MAX_COORDINATE)), named `release.position` or
    /// `release.ground`.
    pub fn new(
        model: &FallModel,
        scales: FallScales,
        main: PrimitiveMotion,
        seed: u64,
        position: Vec3,
        ground: f32,
    ) -> Result<Self, FallError> {
        let release = FallRelease::at(position, ground);
        release.validate()?;
        Ok(Self::release(
            model,
            scales,
            model.bounded_shared(main),
            seed,
            release,
        ))
    }

    /// A fall following `chain` (bounded by its main motion), let go as `release` says
    /// (validated by the caller).
    ///
    /// The release orientation is kept: the plate's long axis sets the heading (it glides
    /// across it), its pitch about that axis is the first swing's start angle, and whatever
    /// else it has (a roll, a tilt the first motion does not have) fades out over a swing.
    pub(crate) fn release(
        model: &FallModel,
        scales: FallScales,
        chain: Arc<BoundedChain>,
        seed: u64,
        release: FallRelease,
    ) -> Self {
        let constants = FallConstants::new(&scales, release.ground, 0.0, None);
        let mut store = Store::new(SharedConstants(constants));
        store.insert(
            model,
            &FallStart {
                scales,
                chain,
                seed,
                release,
                max_angle: 0.0,
                lod: None,
                phase: 0.0,
            },
        );
        Self { store }
    }

    /// Advances by `dt` seconds: p ← p + v dt + Δf (§4.2), where v, the velocity of the part of
    /// the motion the fluid carries, relaxes toward `wind` (the fluid's velocity at the current
    /// position; zero in still fluid) over [`FallScales::response_time`], and Δf is the
    /// still-fluid path's increment; `tilt` is the wind's turn of eq. 15.
    ///
    /// Hostile input is clamped: `dt` to 0..=[`FallRelease::MAX_STEP`] (non-finite: 0), `wind`
    /// to [`FallRelease::MAX_SPEED`] (non-finite: still fluid).
    pub fn advance(
        &mut self,
        model: &FallModel,
        dt: f32,
        wind: Vec3,
        tilt: &WindTilt,
    ) -> StepOutcome {
        let was_landed = self.landed();
        self.store.kind.0.max_angle = tilt.max_angle;
        let step = Step {
            model,
            air: Air::Uniform(wind, tilt.reference_speed),
            focus: None,
            width: crate::portable::lane_width(),
            recycle_after: None,
        };
        let report = self.store.step(dt, &step, None);
        if !report.landed.is_empty() {
            StepOutcome::Landed
        } else if was_landed && self.landed() {
            StepOutcome::Resting
        } else {
            StepOutcome::Falling
        }
    }

    /// The fall, to read.
    pub fn view(&self) -> FallView<'_> {
        self.store.view(0).expect("a path holds one fall")
    }

    /// p_i, the latest control point.
    pub fn position(&self) -> Vec3 {
        self.view().position()
    }

    /// The latest orientation (normalised).
    pub fn orientation(&self) -> Quat {
        self.view().orientation()
    }

    /// The velocity of the fluid-following part of the motion, m/s.
    pub fn drift(&self) -> Vec3 {
        self.view().drift()
    }

    /// f(t): the still-fluid displacement since release.
    pub fn still_displacement(&self) -> Vec3 {
        self.view().still_displacement()
    }

    /// The current primitive motion (Markov state).
    pub fn motion(&self) -> PrimitiveMotion {
        self.view().motion()
    }

    /// The chain's bound: the main motion from the phase diagram.
    pub fn main_motion(&self) -> PrimitiveMotion {
        self.view().main_motion()
    }

    /// A₀ of the current motion, with its Gaussian draw, m.
    pub fn amplitude(&self) -> f32 {
        self.view().amplitude()
    }

    /// The heading: the rotation about +Y whose local +X the swings glide along.
    pub fn heading(&self) -> Quat {
        self.view().heading()
    }

    /// Seconds since release.
    pub fn time(&self) -> f32 {
        self.view().time()
    }

    /// True once on the ground.
    pub fn landed(&self) -> bool {
        self.view().landed()
    }

    /// Markov steps taken (one per finished piece).
    pub fn markov_steps(&self) -> u32 {
        self.view().markov_steps()
    }

    /// The sizes of this fall.
    pub fn scales(&self) -> &FallScales {
        self.view().scales()
    }

    /// The shown pose a fraction `s` ∈ [0, 1] of a step after the second-to-last control point
    /// ([`FallView::smoothed`]).
    pub fn smoothed(&self, s: f32) -> (Vec3, Quat) {
        self.view().smoothed(s)
    }
}

impl From<Store<SharedConstants>> for FallPath {
    /// The first fall of `store` (a store of one).
    fn from(store: Store<SharedConstants>) -> Self {
        Self { store }
    }
}
