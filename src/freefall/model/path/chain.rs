//! The Markov step at the end of each piece (§3.2 of the free-fall paper) and the piece that
//! follows: a swing found in the trajectory database by its search key (§2.3), or a helix or
//! spiral curve of eq. 6 carried on or started afresh.

use std::f32::consts::{PI, TAU};

use bevy::math::Vec3;

use super::super::FallModel;
use super::super::database::TrajectoryDatabase;
use super::super::motion::next_glide;
use super::super::piece::{Piece, SwingChoice};
use super::super::regime::PrimitiveMotion;
use super::{BLEND_SWINGS, Blend, FallPath, MIN_BLEND};

impl FallPath {
    /// The Markov step at the end of a piece (§3.2), then the next piece.
    pub(super) fn next_piece(&mut self, model: &FallModel, wind: Vec3) {
        let db = model.database();
        let old = self.piece;
        let next = self
            .chain
            .next_after(self.motion, old.duration(), &mut self.rng);
        self.markov_steps += 1;
        let changed = next != self.motion;
        if changed {
            self.enter_motion(next);
        }
        let theta = old.end_angle();
        let survival = self
            .scales
            .tumble_survival((wind.x * wind.x + wind.z * wind.z).sqrt());
        self.piece = self.build_piece(db, theta, survival, Some(old));
        if changed && !(old_is_planar(&old) && self.motion.is_planar()) {
            self.previous = Some(Box::new(Blend {
                piece: old,
                time: self.piece_time,
                offset: self.piece_offset,
                elapsed: 0.0,
                length: (BLEND_SWINGS * self.scales.swing_time()).max(MIN_BLEND),
            }));
        }
        self.piece_time = 0.0;
        self.piece_offset = Vec3::ZERO;
        self.piece_tilt = self.piece.tilt(db, 0.0);
    }

    /// A new motion: its amplitude with the Gaussian spread; swings go round where it is.
    pub(super) fn enter_motion(&mut self, motion: PrimitiveMotion) {
        if !(motion.is_planar() && self.motion.is_planar()) {
            self.centre = self.lateral;
        }
        self.motion = motion;
        self.amplitude = self.scales.spread_amplitude(motion, &mut self.rng);
    }

    pub(super) fn build_piece(
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
            let key = self.scales.swing_key(glide_to, choice.swings(same_side));
            let segment = db.find(&key, &mut self.rng);
            return Piece::swing(db, &self.scales, segment, choice);
        }
        let flip = PI * (theta / PI).round();
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

fn old_is_planar(piece: &Piece) -> bool {
    matches!(piece, Piece::Swing { .. })
}
