//! The state of a leaf cloud: one [`FallPath`] per leaf in a contiguous array, stepped in
//! parallel chunks, with levels of detail by distance. Pure math: no ECS.

use std::sync::Arc;

use bevy::math::{Quat, Vec3};
use bevy::tasks::{ParallelSliceMut, TaskPool};

use super::CloudRegion;
use crate::freefall::lod::{FallClock, TierClock};
use crate::freefall::model::path::{FallPath, StepOutcome, WindTilt, usual, usual::UsualJob};
use crate::freefall::model::{
    FallModel, markov::BoundedChain, motion::FallScales, piece::Piece, random::FallRng,
    release::FallRelease,
};
use crate::lod::{Focus, LodTiers};
use crate::math::geometry::{Q, V3};
use crate::wind::WindField;

/// One leaf: its fall and when it was last stepped.
#[derive(Clone, Debug)]
struct Leaf {
    path: FallPath,
    /// When it was last stepped, over how long, and the easing after a change of tier.
    tier: TierClock,
    /// Seconds on the ground since it landed.
    resting: f32,
    /// Times it was let go (its first release counts).
    releases: u32,
}

impl Leaf {
    /// The pose shown at `now`.
    fn shown(&self, now: f64) -> LeafPose {
        let (position, rotation) = self.tier.shown(&self.path, now);
        LeafPose { position, rotation }
    }
}

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
    /// is read from `wind` ([`WindTilt::in_wind`]).
    pub wind_tilt: f32,
    /// Where the levels of detail are measured from (the camera, and what it sees);
    /// `None`: every leaf at full detail.
    pub focus: Option<Focus>,
}

/// A shown pose: position and orientation, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeafPose {
    /// Where the leaf is, m.
    pub position: Vec3,
    /// How it is turned (the plate in its local XZ plane, long axis local Z).
    pub rotation: Quat,
}

/// The leaves of one cloud (see [`LeafCloud`](super::LeafCloud)): built by
/// a [`LeafCloud`](super::LeafCloud), stepped by [`CloudLeaves::step`], shown by [`CloudLeaves::poses`].
#[derive(Clone, Debug)]
pub struct CloudLeaves {
    leaves: Vec<Leaf>,
    scales: FallScales,
    chain: Arc<BoundedChain>,
    seed: u64,
    region: CloudRegion,
    ground: f32,
    lod: LodTiers,
    recycle_after: Option<f32>,
    /// Seconds and fixed steps taken, and the last step's length (what an overstep is a share
    /// of): the clock single objects' tiers run on too.
    clock: FallClock,
    /// Leaves on the ground.
    resting: usize,
}

impl CloudLeaves {
    /// `count` leaves with the sizes `scales` and the chain `chain`, each let go at rest at a
    /// point of `region` drawn from its own stream (the cloud's `seed` mixed with its index),
    /// turned at random, above `ground`. The rest of the description: `lod`, and
    /// `recycle_after` (a leaf resting that long is let go again from the region's top).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        model: &FallModel,
        scales: FallScales,
        chain: Arc<BoundedChain>,
        count: usize,
        seed: u64,
        region: CloudRegion,
        ground: f32,
        lod: LodTiers,
        recycle_after: Option<f32>,
    ) -> Self {
        let mut cloud = Self {
            leaves: Vec::with_capacity(count),
            scales,
            chain,
            seed,
            region,
            ground,
            lod,
            recycle_after,
            clock: FallClock::default(),
            resting: 0,
        };
        for index in 0..count {
            let path = cloud.release(model, index, 0, false);
            cloud.leaves.push(Leaf {
                path,
                tier: TierClock::default(),
                resting: 0.0,
                releases: 1,
            });
        }
        cloud
    }

    /// The `release`-th fall of leaf `index`: anywhere in the region (`top`: at its top), turned
    /// at random, from a stream that depends only on the seed, the index and the release.
    fn release(&self, model: &FallModel, index: usize, release: u32, top: bool) -> FallPath {
        let mut rng = FallRng::new(leaf_seed(self.seed, index, release));
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
        FallPath::release(
            model,
            self.scales,
            Arc::clone(&self.chain),
            rng.bits(),
            FallRelease {
                position,
                rotation: Some(rotation),
                velocity: Vec3::ZERO,
                ground: self.ground,
            },
        )
    }

    /// Advances the cloud by one fixed step `step.dt`: every leaf whose tier is due (see
    /// [`LodTiers`]) is advanced over the time since its last step, in the wind where it is,
    /// exactly as a single [`FallingObject`](crate::freefall::FallingObject) is. The leaves are
    /// independent, so the chunks run on `pool`'s threads (`None`: this thread) and the result
    /// is the same bits for any number of threads.
    pub fn step(&mut self, step: &CloudStep, pool: Option<&TaskPool>) -> CloudStepReport {
        let dt = if step.dt.is_finite() {
            step.dt.clamp(0.0, FallRelease::MAX_STEP)
        } else {
            0.0
        };
        self.clock.tick(dt);
        let ctx = ChunkContext {
            step,
            tilt: WindTilt::in_wind(step.wind_tilt, step.wind),
            lanes: crate::math::lanes_enabled(),
            clock: self.clock,
            lod: self.lod,
            recycle_after: self.recycle_after,
        };
        let reports: Vec<ChunkReport> = match pool {
            Some(pool) if self.leaves.len() > CloudLeaves::CHUNK => {
                self.leaves
                    .par_chunk_map_mut(pool, CloudLeaves::CHUNK, |c, chunk| {
                        step_chunk(chunk, c * CloudLeaves::CHUNK, &ctx)
                    })
            }
            _ => self
                .leaves
                .chunks_mut(CloudLeaves::CHUNK)
                .enumerate()
                .map(|(c, chunk)| step_chunk(chunk, c * CloudLeaves::CHUNK, &ctx))
                .collect(),
        };
        let mut report = CloudStepReport::default();
        let mut due = Vec::new();
        self.resting = 0;
        for (chunk, r) in reports.into_iter().enumerate() {
            report.advanced += r.advanced;
            report.landed += r.landed;
            self.resting += r.resting;
            due.extend(
                r.recycle
                    .into_iter()
                    .map(|i| chunk * CloudLeaves::CHUNK + i as usize),
            );
        }
        // Let go again, in index order (each from its own stream: order changes nothing).
        for index in due {
            let releases = self.leaves[index].releases;
            let path = self.release(step.model, index, releases, true);
            let leaf = &mut self.leaves[index];
            leaf.path = path;
            leaf.releases += 1;
            leaf.resting = 0.0;
            leaf.tier = TierClock::stepped_at(self.clock.seconds, 0.0);
            report.recycled += 1;
            self.resting -= 1;
        }
        report
    }

    /// The shown poses, `overstep` ∈ [0, 1] of a step (as long as the last one) after the last
    /// one: each leaf on the
    /// Bézier between its last two control points ([`FallPath::smoothed`]), at the share of its
    /// last step's span that has passed, so a leaf stepped every fourth step moves as smoothly
    /// as one stepped every step and a change of tier never jumps. `out` is resized to the
    /// leaves.
    pub fn poses(&self, overstep: f32, pool: Option<&TaskPool>, out: &mut Vec<LeafPose>) {
        let overstep = if overstep.is_finite() {
            overstep.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let now = self.clock.seconds + f64::from(overstep * self.clock.last_dt);
        out.resize(
            self.leaves.len(),
            LeafPose {
                position: Vec3::ZERO,
                rotation: Quat::IDENTITY,
            },
        );
        let pose = |leaf: &Leaf| leaf.shown(now);
        match pool {
            Some(pool) if self.leaves.len() > CloudLeaves::CHUNK => {
                let leaves = &self.leaves;
                out.par_chunk_map_mut(pool, CloudLeaves::CHUNK, |c, poses| {
                    let first = c * CloudLeaves::CHUNK;
                    for (i, p) in poses.iter_mut().enumerate() {
                        *p = pose(&leaves[first + i]);
                    }
                });
            }
            _ => {
                for (p, leaf) in out.iter_mut().zip(&self.leaves) {
                    *p = pose(leaf);
                }
            }
        }
    }

    /// Bytes the leaves take (their array; a leaf easing after a change of tier holds 48 more,
    /// a leaf blending a motion change a few more on the heap).
    pub fn memory_bytes(&self) -> usize {
        self.leaves.capacity() * std::mem::size_of::<Leaf>()
    }

    /// How many leaves.
    pub fn len(&self) -> usize {
        self.leaves.len()
    }

    /// True for a cloud of no leaves.
    pub fn is_empty(&self) -> bool {
        self.leaves.is_empty()
    }

    /// Leaf `index`'s fall.
    pub fn path(&self, index: usize) -> Option<&FallPath> {
        self.leaves.get(index).map(|l| &l.path)
    }

    /// Every leaf's fall, in order.
    pub fn paths(&self) -> impl ExactSizeIterator<Item = &FallPath> {
        self.leaves.iter().map(|l| &l.path)
    }

    /// Leaves on the ground after the last step.
    pub fn resting(&self) -> usize {
        self.resting
    }

    /// Seconds stepped.
    pub fn clock(&self) -> f64 {
        self.clock.seconds
    }

    /// The sizes every leaf shares.
    pub fn scales(&self) -> &FallScales {
        &self.scales
    }
}

/// What the chunks of one step share.
struct ChunkContext<'a> {
    step: &'a CloudStep<'a>,
    tilt: WindTilt,
    /// Whether usual steps go four leaves at a time (the same bits either way).
    lanes: bool,
    clock: FallClock,
    lod: LodTiers,
    recycle_after: Option<f32>,
}

#[derive(Default)]
struct ChunkReport {
    advanced: usize,
    landed: usize,
    /// Leaves on the ground after the step.
    resting: usize,
    /// Indices within the chunk of leaves to let go again.
    recycle: Vec<u32>,
}

fn step_chunk(chunk: &mut [Leaf], first: usize, ctx: &ChunkContext) -> ChunkReport {
    let mut report = ChunkReport::default();
    let step = ctx.step;
    // The leaves due this step (a leaf's tier says how often it is stepped: every 1, 2 or 4
    // steps, the leaves of a tier taking their turns on different steps; a leaf just let go
    // takes its first step at once and its next on its phase), and where they are.
    let (mut due, mut positions) = (Vec::new(), Vec::new());
    for (i, leaf) in chunk.iter().enumerate() {
        let position = leaf.path.position();
        let every = step.focus.map_or(1, |f| f.tier(&ctx.lod, position));
        let index = (first + i) as u32;
        if !ctx.clock.due(every, index) && !leaf.tier.fresh() {
            report.resting += usize::from(leaf.path.landed());
            continue;
        }
        // Its tier's next turn is this many steps on.
        due.push((i, ctx.clock.steps_to_next(every, index) as f32 * step.dt));
        positions.push(position);
    }
    // The wind where they are, four points at a time.
    let mut winds = Vec::new();
    match step.wind {
        Some(w) => w.velocities(&positions, &mut winds),
        None => winds.resize(positions.len(), Vec3::ZERO),
    }
    // Leaves whose step is a usual one (inside a piece, at full step, no easing) wait for the
    // lanes, swings apart from curves; the others step now.
    let (mut swings, mut curves) = (Vec::new(), Vec::new());
    for (&(i, next), wind) in due.iter().zip(winds) {
        let leaf = &mut chunk[i];
        let waited = leaf.tier.waited(ctx.clock.seconds);
        let usual = UsualJob {
            next,
            ..UsualJob::new(i, wind, waited, ctx.tilt)
        };
        if ctx.lanes && leaf.tier.plain_at(ctx.clock.seconds) && leaf.path.usual(usual.dt) {
            match leaf.path.piece() {
                Piece::Swing { .. } => swings.push(usual),
                Piece::Curve { .. } => curves.push(usual),
            }
            continue;
        }
        let (outcome, waited) = leaf.tier.advance(
            &mut leaf.path,
            step.model,
            ctx.clock.seconds,
            next,
            wind,
            &ctx.tilt,
        );
        report.count(leaf, i, outcome, waited, ctx.recycle_after);
    }
    for jobs in [&swings, &curves] {
        let db = step.model.database();
        usual::run_usual(
            chunk,
            jobs,
            |leaf| &mut leaf.path,
            db,
            |leaf, job, landed| {
                leaf.tier.stepped(ctx.clock.seconds, job.next, job.waited);
                let outcome = if landed {
                    StepOutcome::Landed
                } else {
                    StepOutcome::Falling
                };
                report.count(leaf, job.index, outcome, job.waited, ctx.recycle_after);
            },
        );
    }
    report
}

impl ChunkReport {
    /// Counts what a leaf's step did.
    fn count(
        &mut self,
        leaf: &mut Leaf,
        i: usize,
        outcome: StepOutcome,
        waited: f32,
        recycle_after: Option<f32>,
    ) {
        self.advanced += 1;
        match outcome {
            StepOutcome::Landed => {
                self.landed += 1;
                leaf.resting = 0.0;
            }
            StepOutcome::Resting => {
                leaf.resting += waited;
                if recycle_after.is_some_and(|t| leaf.resting >= t) {
                    self.recycle.push(i as u32);
                }
            }
            StepOutcome::Falling => leaf.resting = 0.0,
        }
        self.resting += usize::from(leaf.path.landed());
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
