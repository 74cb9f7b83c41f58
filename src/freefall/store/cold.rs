//! The state of a fall that a usual step does not touch, one struct a fall beside the blocks:
//! its generator, Markov chain, motion and sojourn, the piece itself, blends, the release fade
//! and easing. Written when a piece begins (the motion entered, its amplitude and sojourn drawn
//! once; the piece built: a swing searched, eq. 6 otherwise), a motion changes, a fall lands or
//! is let go.

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use bevy::math::Vec3;

use crate::freefall::model::database::{SearchMemo, TrajectoryDatabase};
use crate::freefall::model::markov::BoundedChain;
use crate::freefall::model::motion::{FallScales, Glide, next_glide};
use crate::freefall::model::piece::{Piece, SwingChoice};
use crate::freefall::model::random::FallRng;
use crate::freefall::model::regime::PrimitiveMotion;
use crate::freefall::model::release::FallRelease;
use crate::lod::LodTiers;
use crate::portable::geometry::Q;

/// Everything that starts a fall.
#[derive(Clone, Debug)]
pub(crate) struct FallStart {
    pub scales: FallScales,
    pub chain: Arc<BoundedChain>,
    pub seed: u64,
    pub release: FallRelease,
    /// Eq. 15's W, rad.
    pub max_angle: f32,
    pub lod: Option<LodTiers>,
    /// How far into its first piece the fall begins, a fraction of the piece in [0, 1): 0 for a
    /// fall let go at rest (a plate let go starts at a turning point of its swing); a cloud's
    /// leaves, already in the air, each begin at their own.
    pub phase: f32,
}

/// The piece before a motion change, while the change blends: its time and offset run on past
/// its end.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Blend {
    pub piece: Piece,
    pub time: f32,
    pub offset: Vec3,
    pub elapsed: f32,
    pub length: f32,
    /// What was shown when the blend began × the piece's own tilt then, inverted: the identity,
    /// unless the change came while another blend ran (the new blend starts from what that one
    /// showed, not from the piece's own tilt).
    pub residual: Q<f32>,
}

impl Blend {
    /// The tilt the blend starts from, at its current time: the piece's, coasting past its end
    /// ([`Piece::coasting_tilt`]), after the residual.
    pub fn tilt(&self, db: &TrajectoryDatabase) -> Q<f32> {
        self.residual
            .mul(Q::of(self.piece.coasting_tilt(db, self.time, self.length)))
            .normalize()
    }

    /// What the blend shows at its current time, blending into `tilt`, the new piece's.
    pub fn shown(&self, db: &TrajectoryDatabase, tilt: Q<f32>) -> Q<f32> {
        self.tilt(db)
            .slerp(tilt, smoothstep(self.elapsed / self.length))
    }
}

/// The part of the release orientation the synthesis does not reproduce, fading out.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ReleaseFade {
    pub residual: bevy::math::Quat,
    pub elapsed: f32,
    pub length: f32,
}

/// How far the shown pose was from the path when the fall was stepped, eased out by `end`
/// (a step that came before the last span was shown: a change to a finer tier).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Easing {
    /// Shown position − the path's, at `start`.
    pub offset: Vec3,
    /// Shown rotation × the path's inverse, at `start`.
    pub turn: bevy::math::Quat,
    pub start: f64,
    /// The clock when the easing is over (later steps do not push it back).
    pub end: f64,
}

/// What only a piece's end, a motion change, a landing or a change of tier touches.
#[derive(Clone, Debug)]
pub(crate) struct Cold {
    pub scales: FallScales,
    pub chain: Arc<BoundedChain>,
    pub rng: FallRng,
    pub motion: PrimitiveMotion,
    /// Seconds left in `motion` (drawn on entering it, counted down by each piece).
    pub sojourn: f32,
    /// A₀ of the current motion with its Gaussian draw (§2.3.2), m.
    pub amplitude: f32,
    pub glide: Glide,
    /// No swing yet: the first one reverses nothing.
    pub fresh: bool,
    /// The piece under way (its compiled words are in the block).
    pub piece: Piece,
    /// Sideways position along the heading when the piece began, m, and the centre the swings
    /// go round (moved on by half-turns, which drift).
    pub lateral: f32,
    pub centre: f32,
    /// The swing search key's angle component (from I*, fixed for a fall).
    pub key_angle: f32,
    /// Seconds since release when the piece began.
    pub piece_start: f64,
    pub markov_steps: u32,
    /// Boxed: rare, and the cold state of a hundred thousand leaves stays small.
    pub previous: Option<Box<Blend>>,
    pub release: Option<Box<ReleaseFade>>,
    pub easing: Option<Box<Easing>>,
    /// Times it was let go (its first release counts).
    pub releases: u32,
    /// Set when its motion changed or it was lifted from the ground, until the step reports it.
    pub changed: bool,
    pub lifted: bool,
    /// The candidates of its last swing search.
    pub search: SearchMemo,
}

impl Cold {
    /// The cold state of a fall about to be let go (what
    /// [`Slot::release`](super::slot::Slot::release) fills in).
    pub(crate) fn blank(start: &FallStart) -> Self {
        Self {
            scales: start.scales,
            chain: Arc::clone(&start.chain),
            rng: FallRng::new(start.seed),
            motion: PrimitiveMotion::SteadyDescent,
            sojourn: f32::INFINITY,
            amplitude: 0.0,
            glide: Glide::Right,
            fresh: true,
            piece: Piece::curve(&start.scales, PrimitiveMotion::SteadyDescent, 0.0, 0.0, 0.0),
            lateral: 0.0,
            centre: 0.0,
            key_angle: start.scales.swing_key_angle(),
            piece_start: 0.0,
            markov_steps: 0,
            previous: None,
            release: None,
            easing: None,
            releases: 1,
            changed: false,
            lifted: false,
            search: SearchMemo::default(),
        }
    }

    /// A new motion: its amplitude with the Gaussian spread and its sojourn; swings go round
    /// where the fall is.
    pub(crate) fn enter_motion(&mut self, motion: PrimitiveMotion) {
        if !(motion.is_planar() && self.motion.is_planar()) {
            self.centre = self.lateral;
        }
        self.motion = motion;
        self.amplitude = self.scales.spread_amplitude(motion, &mut self.rng);
        self.sojourn = self.chain.sojourn(motion, &mut self.rng);
    }

    /// The piece that follows `old` (or the first, `None`) with the plate at angle `theta`: a
    /// swing found by the search tree (§2.3.1) for a planar motion, eq. 6 otherwise (the same
    /// curve carried on where it can be).
    pub(crate) fn build_piece(
        &mut self,
        db: &TrajectoryDatabase,
        theta: f32,
        survival: f32,
        old: Option<Piece>,
    ) -> Piece {
        if self.motion.is_planar() {
            let (glide, r) = next_glide(self.motion, self.glide, &mut self.rng);
            let same_side = !self.fresh && glide == self.glide;
            self.fresh = false;
            self.glide = glide;
            let choice = SwingChoice {
                glide,
                same_side,
                r,
                theta,
                survival,
                rate: old.map_or(0.0, |p| p.end_rate(db)),
            };
            // The search key (§2.3.1): the glide to the next turning point, r A₀ to the other
            // side of the centre (A_e = r A₀), or on by 2 r A₀ for a half-turn, which drifts.
            let reach = r * self.amplitude;
            let glide_to = if same_side {
                self.centre += glide.sign() * 2.0 * reach;
                2.0 * reach
            } else {
                // Past the turning point already (a long previous swing): a short swing back.
                ((self.centre + glide.sign() * reach - self.lateral) * glide.sign()).max(0.0)
            };
            let key =
                self.scales
                    .swing_key_with(self.key_angle, glide_to, choice.swings(same_side));
            let segment = db.find_remembered(&key, &mut self.rng, &mut self.search);
            return Piece::swing(db, &self.scales, segment, choice);
        }
        // The plate's half-turns, less whole turns of the half angle (4π: the same quaternion).
        let turns = 4.0 * PI;
        let flip = PI * crate::portable::transcendental::round(theta / PI);
        let flip = flip - turns * crate::portable::transcendental::round(flip / turns);
        match old {
            // The same curve carries on from where it was.
            Some(Piece::Curve {
                start, duration, ..
            }) if old.is_some_and(|p| p.end_angle() == flip && p.is_curve_of(self.motion)) => {
                Piece::curve(
                    &self.scales,
                    self.motion,
                    self.amplitude,
                    start + duration,
                    flip,
                )
            }
            _ => {
                let phase = self.rng.uniform() * TAU / (self.scales.swing_rate * 0.25).max(1e-6);
                Piece::curve(&self.scales, self.motion, self.amplitude, phase, flip)
            }
        }
    }
}

/// 3x² − 2x³ on x clamped to [0, 1] (bevy_curve's `EaseFunction::SmoothStep`): how a blend and
/// the release's residual fade.
pub(crate) fn smoothstep(x: f32) -> f32 {
    use bevy::curve::{Curve, EaseFunction};
    EaseFunction::SmoothStep.sample_clamped(x)
}
