//! A piece begins: the motion entered (its amplitude and sojourn drawn once), the piece
//! built (a swing searched, eq. 6 otherwise) and compiled into the block's columns.

use std::f32::consts::{PI, TAU};

use super::block::{Block, Cold, Constants, Hot};
use crate::freefall::model::database::TrajectoryDatabase;
use crate::freefall::model::motion::next_glide;
use crate::freefall::model::piece::{Piece, SwingChoice};
use crate::freefall::model::regime::PrimitiveMotion;

impl Cold {
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
        let flip = PI * crate::math::kernels::round(theta / PI);
        let flip = flip - turns * crate::math::kernels::round(flip / turns);
        match old {
            // The same curve carries on from where it was.
            Some(Piece::Curve {
                start, duration, ..
            }) if old.is_some_and(|p| p.end_angle() == flip) && !self.curve_changed(&old) => {
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

    /// Whether the last piece was a curve of another motion.
    fn curve_changed(&self, old: &Option<Piece>) -> bool {
        let Some(Piece::Curve {
            eccentricity,
            lobes,
            ..
        }) = old
        else {
            return true;
        };
        let fresh = Piece::curve(&self.scales, self.motion, self.amplitude, 0.0, 0.0);
        !matches!(fresh, Piece::Curve { eccentricity: e, lobes: l, .. } if e == *eccentricity && l == *lobes)
    }
}

/// Writes `piece`, compiled, into lane `k` of `block`.
pub(crate) fn write_piece<K: Constants>(
    block: &mut Block<K>,
    k: usize,
    piece: &Piece,
    db: &TrajectoryDatabase,
) {
    let words = piece.words(db);
    let h: &mut Hot = &mut block.hot;
    h.duration[k] = words.duration;
    h.inv_duration[k] = words.inv_duration;
    for (column, value) in [
        &mut h.w0, &mut h.w1, &mut h.w2, &mut h.w3, &mut h.w4, &mut h.w5, &mut h.w6, &mut h.w7,
        &mut h.w8, &mut h.w9, &mut h.w10,
    ]
    .into_iter()
    .zip(words.words)
    {
        column[k] = value;
    }
    h.curve[k] = if words.curve { 1.0 } else { 0.0 };
    h.tumble[k] = if words.tumble { 1.0 } else { 0.0 };
    block.row[k] = words.row;
}
