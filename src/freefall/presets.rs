//! Named falling objects with real sizes and densities, each with the Markov chain that gives it
//! a believable sequence of motions.
//!
//! Sizes and densities: the paper's three objects of §5 (Fig. 15) as it states them; tree leaves
//! from the usual blade sizes of field guides (Norway maple 7–14 cm, about as wide as long;
//! pedunculate oak 7–14 cm; silver birch 3–7 cm) with autumn leaf mass per area of 50–90 g/m²
//! (Niinemets & Kull 1994 give 69 g/m² on average over 85 woody species) and thicknesses of
//! 0.15–0.25 mm; office paper of 80 g/m² (0.1 mm, 800 kg/m³); a poker card 88.9 × 63.5 mm of
//! 1.8 g; an elm samara of 6.5 mg and 1.5 × 1.2 cm.
//!
//! **Main motions.** With those sizes the phase diagram puts every object in air near or above
//! the tumbling boundary (I* ∝ ρ_s / ρ_f ≈ 500 in air), where the paper reports spiral and helix
//! for its paper and leaf (§5 prints I* values its sizes cannot give: see the README). Presets
//! whose main motion is the paper's report or a designer's choice say so and force it through
//! [`FallingObject::main_motion`]; the others use the phase diagram.
//!
//! **Chains.** Each preset starts where the paper's Fig. 15 (or common sight) starts and climbs
//! the hypothesis of §3.1 at the dwell times in [`FallPreset::dwell_times`], seconds on average
//! in each motion before the next. The measured seconds per motion are in the report.

use bevy::color::Color;
use bevy::reflect::Reflect;

use super::model::body::{Fluid, Shape};
use super::model::markov::MarkovChain;
use super::model::regime::PrimitiveMotion;

/// A named object: shape, density, fluid, main motion and Markov chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Reflect)]
pub enum FallPreset {
    /// The paper's coin (Fig. 15a): aluminium, 2 cm across, 1.5 mm thick, in water. Steady at
    /// first, then fluttering (the phase diagram's main motion).
    Coin,
    /// The paper's sheet (Fig. 15b): an ellipse of 80 g/m² paper, 8 × 2 cm, 0.1 mm, in air.
    /// Tumbles, then spirals (the paper's report; forced).
    PaperSheet,
    /// The paper's leaf (Fig. 15c): 7.3 × 4.2 cm, 0.3 mm, 500 kg/m³. Steady, tumbling, then a
    /// helix (the paper's report; forced).
    Leaf,
    /// A Norway maple leaf in autumn: 11 × 10 cm, 0.2 mm, 300 kg/m³ (60 g/m²). Steady,
    /// fluttering, then chaotic (the phase diagram's I* ≈ 0.027).
    MapleLeaf,
    /// An oak leaf in autumn: 10 × 5 cm, 0.25 mm, 350 kg/m³ (88 g/m²). Steady, fluttering,
    /// chaotic, then tumbling (the phase diagram's).
    OakLeaf,
    /// A silver birch leaf in autumn: 5 × 3.5 cm, 0.15 mm, 400 kg/m³ (60 g/m²). Steady,
    /// fluttering, then a helix (designer's choice; the phase diagram says tumbling).
    BirchLeaf,
    /// A poker card, 88.9 × 63.5 mm, 0.3 mm, 1.8 g. Flutters, then tumbles end over end (the
    /// phase diagram's I* ≈ 3.5; Mahadevan et al. 1999).
    PlayingCard,
    /// An elm samara, a light winged seed: 1.5 × 1.2 cm, 0.1 mm, 460 kg/m³ (6.5 mg). Flutters,
    /// then spirals down (designer's choice).
    Samara,
}

impl FallPreset {
    /// Every preset.
    pub const ALL: [Self; 8] = [
        Self::Coin,
        Self::PaperSheet,
        Self::Leaf,
        Self::MapleLeaf,
        Self::OakLeaf,
        Self::BirchLeaf,
        Self::PlayingCard,
        Self::Samara,
    ];

    /// A short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Coin => "coin (Fig. 15a)",
            Self::PaperSheet => "paper sheet (Fig. 15b)",
            Self::Leaf => "leaf (Fig. 15c)",
            Self::MapleLeaf => "maple leaf",
            Self::OakLeaf => "oak leaf",
            Self::BirchLeaf => "birch leaf",
            Self::PlayingCard => "playing card",
            Self::Samara => "elm samara",
        }
    }

    /// Shape, density (kg/m³), fluid and forced main motion.
    pub(super) fn body(self) -> (Shape, f32, Fluid, Option<PrimitiveMotion>) {
        use PrimitiveMotion::*;
        let ellipse = |major, minor, thickness| Shape::Ellipse {
            major,
            minor,
            thickness,
        };
        match self {
            Self::Coin => (
                Shape::Disk {
                    diameter: 0.02,
                    thickness: 0.0015,
                },
                2700.0,
                Fluid::WATER,
                None,
            ),
            Self::PaperSheet => (ellipse(0.08, 0.02, 1.0e-4), 800.0, Fluid::AIR, Some(Spiral)),
            Self::Leaf => (
                ellipse(0.073, 0.042, 3.0e-4),
                500.0,
                Fluid::AIR,
                Some(Helix),
            ),
            Self::MapleLeaf => (ellipse(0.11, 0.10, 2.0e-4), 300.0, Fluid::AIR, None),
            Self::OakLeaf => (ellipse(0.10, 0.05, 2.5e-4), 350.0, Fluid::AIR, None),
            Self::BirchLeaf => (ellipse(0.05, 0.035, 1.5e-4), 400.0, Fluid::AIR, Some(Helix)),
            Self::PlayingCard => (
                Shape::Rectangle {
                    length: 0.0889,
                    width: 0.0635,
                    thickness: 3.0e-4,
                },
                1060.0,
                Fluid::AIR,
                None,
            ),
            Self::Samara => (
                ellipse(0.015, 0.012, 1.0e-4),
                460.0,
                Fluid::AIR,
                Some(Spiral),
            ),
        }
    }

    /// Where a fall starts (weights over L1..L6), the mean seconds it stays in each motion, and
    /// the weights of the motions it goes to next (only higher ones count; the main motion,
    /// the last, holds).
    pub fn dwell_times(self) -> ([f32; 6], [f32; 6]) {
        const F: f32 = f32::INFINITY;
        match self {
            Self::Coin => ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.5, F, F, F, F, F]),
            Self::PaperSheet => ([0.3, 0.0, 0.0, 0.7, 0.0, 0.0], [0.3, F, F, 1.2, F, F]),
            Self::Leaf => ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.6, F, F, 1.2, F, F]),
            Self::MapleLeaf => ([0.6, 0.4, 0.0, 0.0, 0.0, 0.0], [0.5, 1.2, F, F, F, F]),
            Self::OakLeaf => ([0.6, 0.4, 0.0, 0.0, 0.0, 0.0], [0.4, 0.8, 1.0, F, F, F]),
            Self::BirchLeaf => ([0.5, 0.5, 0.0, 0.0, 0.0, 0.0], [0.5, 1.2, F, F, F, F]),
            Self::PlayingCard => ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], [F, 0.5, 0.6, F, F, F]),
            Self::Samara => ([0.3, 0.7, 0.0, 0.0, 0.0, 0.0], [0.3, 0.8, F, F, F, F]),
        }
    }

    /// The motions a fall of this preset goes through, in order (the paper's sequence).
    pub fn sequence(self) -> &'static [PrimitiveMotion] {
        use PrimitiveMotion::*;
        match self {
            Self::Coin => &[SteadyDescent, Fluttering],
            Self::PaperSheet => &[SteadyDescent, Tumbling, Spiral],
            Self::Leaf => &[SteadyDescent, Tumbling, Helix],
            Self::MapleLeaf => &[SteadyDescent, Fluttering, Chaotic],
            Self::OakLeaf => &[SteadyDescent, Fluttering, Chaotic, Tumbling],
            Self::BirchLeaf => &[SteadyDescent, Fluttering, Helix],
            Self::PlayingCard => &[Fluttering, Chaotic, Tumbling],
            Self::Samara => &[SteadyDescent, Fluttering, Spiral],
        }
    }

    /// The preset's chain: from [`FallPreset::dwell_times`], each motion going on to the next
    /// one of [`FallPreset::sequence`].
    pub fn chain(self) -> MarkovChain {
        let (initial, dwell) = self.dwell_times();
        let sequence = self.sequence();
        let mut next = [[0.0f32; 6]; 6];
        for pair in sequence.windows(2) {
            next[pair[0].index()][pair[1].index()] = 1.0;
        }
        MarkovChain::from_dwell_times(initial, dwell, next)
            .expect("every preset's chain is a valid upper-triangular matrix")
    }
}

impl FallPreset {
    /// The colours objects of this preset are drawn in (sRGB); each object takes one by its seed.
    pub fn palette(self) -> &'static [Color] {
        const COIN: [Color; 2] = [Color::srgb(0.80, 0.81, 0.83), Color::srgb(0.70, 0.72, 0.75)];
        const PAPER: [Color; 2] = [Color::srgb(0.96, 0.95, 0.91), Color::srgb(0.93, 0.93, 0.96)];
        const GREEN: [Color; 3] = [
            Color::srgb(0.33, 0.55, 0.14),
            Color::srgb(0.45, 0.62, 0.18),
            Color::srgb(0.56, 0.64, 0.16),
        ];
        const MAPLE: [Color; 4] = [
            Color::srgb(0.82, 0.20, 0.06),
            Color::srgb(0.92, 0.45, 0.08),
            Color::srgb(0.72, 0.12, 0.05),
            Color::srgb(0.95, 0.62, 0.12),
        ];
        const OAK: [Color; 4] = [
            Color::srgb(0.58, 0.34, 0.12),
            Color::srgb(0.66, 0.44, 0.16),
            Color::srgb(0.48, 0.28, 0.10),
            Color::srgb(0.72, 0.52, 0.20),
        ];
        const BIRCH: [Color; 3] = [
            Color::srgb(0.96, 0.78, 0.15),
            Color::srgb(0.90, 0.68, 0.10),
            Color::srgb(0.86, 0.80, 0.26),
        ];
        const CARD: [Color; 2] = [Color::srgb(0.97, 0.97, 0.95), Color::srgb(0.80, 0.10, 0.12)];
        const SAMARA: [Color; 2] = [Color::srgb(0.80, 0.74, 0.44), Color::srgb(0.70, 0.66, 0.38)];
        match self {
            Self::Coin => &COIN,
            Self::PaperSheet => &PAPER,
            Self::Leaf => &GREEN,
            Self::MapleLeaf => &MAPLE,
            Self::OakLeaf => &OAK,
            Self::BirchLeaf => &BIRCH,
            Self::PlayingCard => &CARD,
            Self::Samara => &SAMARA,
        }
    }
}
