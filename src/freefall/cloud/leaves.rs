//! The state of a leaf cloud: its leaves in a fall store (a structure of arrays in blocks of
//! the lane width, grouped by level of detail), stepped by the store's one driver in parallel
//! chunks. Pure math: no ECS.

use std::sync::Arc;

use bevy::math::Vec3;
use bevy::tasks::TaskPool;

use super::CloudRegion;
use crate::freefall::model::{
    FallModel, markov::BoundedChain, motion::FallScales, random::FallRng, release::FallRelease,
};
use crate::freefall::store::Store;
use crate::freefall::store::air::Air;
use crate::freefall::store::block::{FallConstants, SharedConstants};
use crate::freefall::store::cold::FallStart;
use crate::freefall::store::path::FallPath;
use crate::freefall::store::step::Step;
use crate::freefall::store::view::FallView;
use crate::lod::{Focus, LodTiers};
use crate::portable::geometry::{Q, V3};
use crate::wind::WindField;

pub use crate::freefall::store::pose::LeafPose;

/// What one [`CloudLeaves::step`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CloudStepReport {
    /// Leaves advanced in this step (the others wait for their tier's turn).
    pub advanced: usize,
    /// Leaves that reached the ground in this step.
    pub landed: usize,
    /// Leaves let go again from the top of the region ([`LeafCloud::recycle_after`]).
    ///
    /// [`LeafCloud::recycle_after`]: super::LeafCloud::recycle_after
    pub recycled: usize,
}

/// Everything one step of a cloud reads.
#[derive(Clone, Copy, Debug)]
pub struct CloudStep<'a> {
    /// The trajectory database and chain.
    pub model: &'a FallModel,
    /// The wind (`None`: still air).
    pub wind: Option<&'a WindField>,
    /// The fixed step, s.
    pub dt: f32,
    /// W, the largest angle the wind turns a leaf by (eq. 15), rad; the wind's reference speed
    /// is `wind`'s own (1 m/s in still air, where nothing tilts).
    pub wind_tilt: f32,
    /// Where the levels of detail are measured from (the camera, and what it sees);
    /// `None`: every leaf at full detail.
    pub focus: Option<Focus>,
}

/// The leaves of one cloud (see [`LeafCloud`](super::LeafCloud)): built by
/// a [`LeafCloud`](super::LeafCloud), stepped by [`CloudLeaves::step`], shown by [`CloudLeaves::poses`].
#[derive(Clone, Debug)]
pub struct CloudLeaves {
    store: Store<SharedConstants>,
    scales: FallScales,
    chain: Arc<BoundedChain>,
    seed: u64,
    region: CloudRegion,
    ground: f32,
    lod: LodTiers,
    recycle_after: Option<f32>,
}

impl CloudLeaves {
    /// `count` leaves with the sizes `scales` and the chain `chain`, each let go at a point of
    /// `region` drawn from its own stream (the cloud's `seed` mixed with its index), turned at
    /// random, above `ground`, and already in the air: at its own point of its first swing
    /// (so the leaves' piece ends come evenly, not all on the same steps). The rest of the
    /// description: `lod`, `max_angle` (eq. 15's W) and `recycle_after` (a leaf resting that
    /// long is let go again from the region's top).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        model: &FallModel,
        scales: FallScales,
        chain: Arc<BoundedChain>,
        count: u32,
        seed: u64,
        region: CloudRegion,
        ground: f32,
        lod: LodTiers,
        max_angle: f32,
        recycle_after: Option<f32>,
    ) -> Self {
        let constants = FallConstants::new(&scales, ground, max_angle, Some(lod));
        let mut cloud = Self {
            store: Store::new(SharedConstants(constants)),
            scales,
            chain,
            seed,
            region,
            ground,
            lod,
            recycle_after,
        };
        for index in 0..count {
            let start = cloud.start(index, 0, false);
            cloud.store.insert(model, &start);
        }
        cloud
    }

    /// The `release`-th fall of leaf `index`: anywhere in the region (`top`: at its top), turned
    /// at random, at a point of its first piece drawn at random, from a stream that depends
    /// only on the seed, the index and the release.
    fn start(&self, index: u32, release: u32, top: bool) -> FallStart {
        let mut rng = FallRng::new(leaf_seed(self.seed, index as usize, release));
        let (min, max) = (self.region.min, self.region.max);
        let mut position =
            min + (max - min) * Vec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        if top {
            position.y = max.y;
        }
        let axis = Vec3::new(rng.normal(), rng.normal(), rng.normal());
        let rotation = Q::from_axis_angle(
            V3::of(axis.try_normalize().unwrap_or(Vec3::Y)),
            rng.uniform() * std::f32::consts::TAU,
        )
        .quat();
        let phase = rng.uniform();
        FallStart {
            scales: self.scales,
            chain: Arc::clone(&self.chain),
            seed: rng.bits(),
            release: FallRelease {
                position,
                rotation: Some(rotation),
                velocity: Vec3::ZERO,
                ground: self.ground,
            },
            max_angle: self.store.kind.0.max_angle,
            lod: Some(self.lod),
            phase,
        }
    }

    /// Advances the cloud by one fixed step `step.dt`: every leaf whose tier is due (see
    /// [`LodTiers`]) is advanced over the time since its last step, in the wind where it is,
    /// exactly as a single [`FallingObject`](crate::freefall::FallingObject) is. The leaves are
    /// independent, so the chunks run on `pool`'s threads (`None`: this thread) and the result
    /// is the same bits for any number of threads.
    pub fn step(&mut self, step: &CloudStep, pool: Option<&TaskPool>) -> CloudStepReport {
        self.store.kind.0.max_angle = step.wind_tilt;
        let driver = Step {
            model: step.model,
            air: step.wind.map_or(Air::Still, Air::Field),
            focus: step.focus,
            width: crate::portable::lane_width(),
            recycle_after: self.recycle_after,
        };
        let done = self.store.step(step.dt, &driver, pool);
        let mut report = CloudStepReport {
            advanced: done.advanced,
            landed: done.landed.len(),
            recycled: 0,
        };
        // Let go again, in index order (each from its own stream: order changes nothing).
        for index in done.recycle {
            let releases = self.store.view(index).map_or(1, |leaf| leaf.cold.releases);
            let start = self.start(index, releases, true);
            self.store.replace(index, step.model, &start);
            report.recycled += 1;
        }
        report
    }

    /// The shown poses, `overstep` ∈ [0, 1] of a step (as long as the last one) after the last
    /// one: each leaf on the Bézier between its last two control points
    /// ([`FallView::smoothed`]), at the share of its last step's span that has passed, so a
    /// leaf stepped every fourth step moves as smoothly as one stepped every step and a change
    /// of tier never jumps. `out` is resized to the leaves, in order.
    pub fn poses(&self, overstep: f32, pool: Option<&TaskPool>, out: &mut Vec<LeafPose>) {
        let overstep = if overstep.is_finite() {
            overstep.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let clock = &self.store.clock;
        let now = clock.seconds + f64::from(overstep * clock.last_dt);
        self.store.poses(now, pool, out);
    }

    /// Bytes the leaves take (their blocks and cold state; a leaf blending a motion change or
    /// easing after a change of tier holds a few more on the heap).
    pub fn memory_bytes(&self) -> usize {
        self.store.memory_bytes()
    }

    /// How many leaves.
    pub fn len(&self) -> usize {
        self.store.len()
    }

    /// True for a cloud of no leaves.
    pub fn is_empty(&self) -> bool {
        self.store.len() == 0
    }

    /// Leaf `index`'s fall.
    pub fn path(&self, index: usize) -> Option<FallView<'_>> {
        self.store.view(u32::try_from(index).ok()?)
    }

    /// Every leaf's fall, in order.
    pub fn paths(&self) -> impl ExactSizeIterator<Item = FallView<'_>> {
        (0..self.store.handles() as u32).map(|h| self.store.view(h).expect("every leaf lives"))
    }

    /// Leaf `index` on its own, as it is now, at full detail: every
    /// [`advance`](FallPath::advance) advances it. Stepped alone from here in the same wind, a
    /// leaf of a cloud at full detail follows the same path as in the cloud, bit for bit; a leaf
    /// on a coarser tier first catches up over the time since its own last step, then goes on at
    /// full detail.
    pub fn single(&self, index: usize) -> Option<FallPath> {
        self.store
            .single(u32::try_from(index).ok()?)
            .map(FallPath::from)
    }

    /// Leaves on the ground after the last step.
    pub fn resting(&self) -> usize {
        self.store.resting
    }

    /// Seconds stepped.
    pub fn clock(&self) -> f64 {
        self.store.clock.seconds
    }

    /// The sizes every leaf shares.
    pub fn scales(&self) -> &FallScales {
        &self.scales
    }
}

/// The seed of leaf `index`'s `release`-th fall: SplitMix64's finaliser over the cloud's seed,
/// the index and the release, so neighbouring leaves get unrelated streams.
fn leaf_seed(seed: u64, index: usize, release: u32) -> u64 {
    let mut z = seed
        ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ u64::from(release).wrapping_mul(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Limits and constants of [`CloudLeaves`].
impl CloudLeaves {
    /// Leaves a parallel task steps together: big enough that the task costs little beside its
    /// work (≈ 50 µs), small enough that two threads share the work of a few thousand leaves.
    pub const CHUNK: usize = 512;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::freefall::LeafCloud;

    /// Every leaf's position, drift, motion and piece clock, as bits, after steps of `dts`
    /// seconds in `wind` (`None`: still air) with the store's lanes `width` wide.
    fn bits_after(width: usize, dts: &[f32], wind: Option<&WindField>) -> Vec<u32> {
        let model = FallModel::default();
        let cloud = LeafCloud {
            count: 200,
            seed: 3,
            ..LeafCloud::default()
        };
        // Far below: every leaf falls for the whole run.
        let mut leaves = cloud.leaves(&model, -1.0e6).unwrap();
        let step = Step {
            model: &model,
            air: wind.map_or(Air::Still, Air::Field),
            focus: None,
            width,
            recycle_after: None,
        };
        for &dt in dts {
            leaves.store.step(dt, &step, None);
        }
        leaves
            .paths()
            .flat_map(|leaf| {
                let (p, v) = (leaf.position(), leaf.drift());
                [p.x, p.y, p.z, v.x, v.y, v.z, leaf.time()]
                    .map(f32::to_bits)
                    .into_iter()
                    .chain([leaf.motion() as u32])
            })
            .collect()
    }

    /// One, four and eight lanes (where this CPU has them) give every leaf the same bits, over
    /// frame-length steps and over steps of seconds that cross tens of pieces, up to the most
    /// one step may cross (after which a leaf falls straight on).
    #[test]
    fn every_lane_width_gives_every_leaf_the_same_bits_over_short_and_long_steps() {
        let mut dts = vec![1.0 / 60.0; 30];
        // 5 to 12 s: about 40 to 100 pieces of a default leaf's tenth of a second and more.
        dts.extend((0..24).map(|i| 5.0 + 0.29 * i as f32));
        dts.extend([1.0 / 60.0, 0.5, 1.0 / 24.0, FallRelease::MAX_STEP]);
        // In wind a tumbling swing's end depends on the wind (its survival), in still air not.
        let field = WindField::new(crate::wind::WindConfig::default()).unwrap();
        for wind in [None, Some(&field)] {
            let one = bits_after(1, &dts, wind);
            let widths = [4, 8]
                .into_iter()
                .filter(|&w| w <= crate::portable::widest_lanes());
            for width in widths {
                let lanes = bits_after(width, &dts, wind);
                let differ = one
                    .chunks(8)
                    .zip(lanes.chunks(8))
                    .filter(|(a, b)| a != b)
                    .count();
                let air = if wind.is_some() { "wind" } else { "still air" };
                assert_eq!(
                    differ, 0,
                    "{differ} of 200 leaves differ at width {width} in {air}"
                );
            }
        }
    }

    /// A fall's pose taken alone (as the entity plugin takes it, in its query's pass) has the
    /// bits the lanes give it, at every share of a step: in every band, while a motion change
    /// blends, while a change of tier eases.
    #[test]
    fn a_pose_taken_alone_has_the_bits_the_lanes_give() {
        let model = FallModel::default();
        let cloud = LeafCloud {
            count: 300,
            seed: 9,
            lod: LodTiers {
                near: 8.0,
                far: 16.0,
            },
            ..LeafCloud::default()
        };
        let mut leaves = cloud.leaves(&model, -1.0e6).unwrap();
        let field = WindField::new(crate::wind::WindConfig::default()).unwrap();
        let mut all = Vec::new();
        let (mut checked, mut eased) = (0, 0);
        for frame in 0..240 {
            // The focus jumps between the cloud and far away every half second: every leaf
            // changes tier, and eases when it comes back to full detail.
            let x = if (frame / 30) % 2 == 0 { 0.0 } else { 1.0e3 };
            let step = Step {
                model: &model,
                air: Air::Field(&field),
                focus: Some(Focus::from(Vec3::new(x, 5.0, 0.0))),
                width: crate::portable::lane_width(),
                recycle_after: None,
            };
            leaves.store.step(1.0 / 60.0, &step, None);
            let store = &leaves.store;
            for s in [0.0, 0.37, 1.0] {
                let now = store.clock.seconds + f64::from(s * store.clock.last_dt);
                store.poses(now, None, &mut all);
                for (h, lanes) in all.iter().enumerate() {
                    let alone = store.pose(h as u32, now).unwrap();
                    let bits = |p: &LeafPose| {
                        let (x, q) = (p.position, p.rotation);
                        [x.x, x.y, x.z, q.x, q.y, q.z, q.w].map(f32::to_bits)
                    };
                    assert_eq!(bits(&alone), bits(lanes), "fall {h} at {now} s");
                    checked += 1;
                }
            }
            // Falls whose change of tier still eases at the step's end.
            let now = store.clock.seconds;
            eased += store.bands[..crate::freefall::store::BANDS]
                .iter()
                .flat_map(|b| &b.cold)
                .filter(|c| c.easing.as_deref().is_some_and(|e| e.end > now))
                .count();
        }
        assert_eq!(checked, 300 * 240 * 3);
        assert!(
            eased > 100,
            "only {eased} poses eased: the test would not see the easing"
        );
    }
}
