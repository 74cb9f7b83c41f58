//! Presets for every row of Table 1 of the cloth paper.
//!
//! The paper names its rows by its own speed bands (light breeze 2.7–3.6 m/s, gentle 3.6–7.2,
//! moderate 8.9–12.5). On the standard Beaufort scale at 10 m these are force 2 (light breeze,
//! 1.6–3.3 m/s), force 3–4 (gentle 3.4–5.4, moderate 5.5–7.9) and force 5 (fresh breeze,
//! 8.0–10.7 m/s) respectively. Where the paper gives a range of β, the preset takes its middle.

use std::f32::consts::FRAC_PI_2;

use bevy::reflect::Reflect;

use super::component::Cloth;
use super::descriptor::HarmonicFilter;
use super::params::{ClothParams, ClothWindModel, LeadingYarn};
use super::sim::ClothAttachment;

/// θ, β, |v|, |u|, BPF range, evolving (the paper's "non-frozen"), and what the paper observed.
struct TableRow {
    theta: f32,
    beta: f32,
    v: f32,
    u: f32,
    band: Option<(usize, usize)>,
    evolving: bool,
    observation: &'static str,
}

/// One row of Table 1, named for what the paper saw (its "observation" column) and its wind
/// model: frozen (§4.1) or evolving (the paper's non-frozen, §4.2). Spawn one with
/// [`ClothPreset::cloth`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // the names say it: object, what it does, wind model
pub enum ClothPreset {
    BannerFlutteringFrozen,
    BannerFlutteringEvolving,
    BannerFlappingFrozen,
    BannerFlappingEvolving,
    CurtainDriftingFrozen,
    CurtainDriftingEvolving,
    CurtainFlutteringFrozen,
    CurtainFlutteringEvolving,
    FlagFlappingFrozen,
    FlagFlappingEvolving,
    FlagUncurlingFrozen,
    FlagUncurlingEvolving,
}

/// The three kinds of cloth of Table 1: a banner and a flag hang from a pole, a curtain from a
/// rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Reflect)]
pub enum ClothKind {
    /// A banner: a long cloth on a pole (the paper's banners bulge most, eq. 8).
    Banner,
    /// A curtain hanging from a rod.
    Curtain,
    /// A flag on a pole.
    Flag,
}

impl ClothKind {
    /// "banner", "curtain" or "flag".
    pub fn name(self) -> &'static str {
        match self {
            Self::Banner => "banner",
            Self::Curtain => "curtain",
            Self::Flag => "flag",
        }
    }
}

impl ClothPreset {
    /// Every preset, in Table 1's order.
    pub const ALL: [Self; 12] = [
        Self::BannerFlutteringFrozen,
        Self::BannerFlutteringEvolving,
        Self::BannerFlappingFrozen,
        Self::BannerFlappingEvolving,
        Self::CurtainDriftingFrozen,
        Self::CurtainDriftingEvolving,
        Self::CurtainFlutteringFrozen,
        Self::CurtainFlutteringEvolving,
        Self::FlagFlappingFrozen,
        Self::FlagFlappingEvolving,
        Self::FlagUncurlingFrozen,
        Self::FlagUncurlingEvolving,
    ];

    /// Table 1's row.
    fn row(self) -> TableRow {
        use ClothPreset::*;
        let row = |theta, beta, v, u, band, evolving, observation| TableRow {
            theta,
            beta,
            v,
            u,
            band,
            evolving,
            observation,
        };
        #[rustfmt::skip]
        let table = match self {
            BannerFlutteringFrozen => row(1.4, 2.75, 1.0, 0.0, Some((3, 7)), false, "banner lightly fluttering"),
            BannerFlutteringEvolving => row(1.4, 2.75, 2.0, 1.0, Some((3, 7)), true, "banner lightly fluttering"),
            BannerFlappingFrozen => row(1.4, 2.25, 2.0, 1.0, Some((3, 7)), false, "banner intensively flapping"),
            BannerFlappingEvolving => row(1.4, 2.25, 8.0, 0.0, Some((1, 7)), true, "banner intensively flapping"),
            CurtainDriftingFrozen => row(1.9, 2.5, 2.0, 1.0, None, false, "light curtain moving toward wind"),
            CurtainDriftingEvolving => row(1.9, 2.75, 4.0, 0.0, None, true, "light curtain moving toward wind"),
            CurtainFlutteringFrozen => row(2.8, 2.5, 1.0, 0.0, None, false, "curtain intensively fluttering"),
            CurtainFlutteringEvolving => row(FRAC_PI_2, 2.75, 10.0, 1.0, Some((1, 6)), true, "curtain intensively fluttering"),
            FlagFlappingFrozen => row(1.4, 2.75, 2.0, 1.0, Some((3, 5)), false, "light flag flapping"),
            FlagFlappingEvolving => row(0.8, 2.5, 2.0, 1.0, Some((3, 6)), true, "light flag flapping"),
            FlagUncurlingFrozen => row(FRAC_PI_2, 2.9, 3.0, 1.0, Some((3, 5)), false, "uncurling of flag"),
            FlagUncurlingEvolving => row(2.0, 2.85, 4.0, 0.0, Some((3, 6)), true, "uncurling of flag"),
        };
        table
    }

    /// What this row's cloth is: a banner, a curtain or a flag.
    pub fn kind(self) -> ClothKind {
        use ClothPreset::*;
        match self {
            BannerFlutteringFrozen
            | BannerFlutteringEvolving
            | BannerFlappingFrozen
            | BannerFlappingEvolving => ClothKind::Banner,
            CurtainDriftingFrozen
            | CurtainDriftingEvolving
            | CurtainFlutteringFrozen
            | CurtainFlutteringEvolving => ClothKind::Curtain,
            FlagFlappingFrozen
            | FlagFlappingEvolving
            | FlagUncurlingFrozen
            | FlagUncurlingEvolving => ClothKind::Flag,
        }
    }

    /// A [`Cloth`] of this row, ready to spawn: its parameters, on a pole (banners, flags) or a
    /// rod (curtains), following the wind.
    pub fn cloth(self) -> Cloth {
        Cloth {
            params: self.params(),
            attachment: if self.kind() == ClothKind::Curtain {
                ClothAttachment::Rod
            } else {
                ClothAttachment::Pole
            },
            ..Cloth::default()
        }
    }

    /// The same object and wind band in the other wind model (Table 1's other row).
    pub fn other_model(self) -> Self {
        let i = Self::ALL.iter().position(|p| *p == self).unwrap_or(0);
        Self::ALL[i ^ 1]
    }

    /// The middle of the row's wind band in the paper's Table 1, m/s: light breeze 2.7–3.6,
    /// gentle 3.6–7.2, moderate 8.9–12.5.
    pub fn band_speed(self) -> f32 {
        use ClothPreset::*;
        match self {
            BannerFlutteringFrozen | BannerFlutteringEvolving => 3.15,
            CurtainFlutteringFrozen
            | CurtainFlutteringEvolving
            | FlagUncurlingFrozen
            | FlagUncurlingEvolving => 10.7,
            _ => 5.4,
        }
    }

    /// Whether this row uses evolving (the paper's non-frozen) wind.
    pub fn evolving(self) -> bool {
        self.row().evolving
    }

    /// What the paper observed for this row.
    pub fn observation(self) -> &'static str {
        self.row().observation
    }

    /// The parameters of this row.
    pub fn params(self) -> ClothParams {
        let TableRow {
            theta: amplitude,
            beta,
            v: wind_steps_per_frame,
            u: swirl,
            band,
            evolving,
            ..
        } = self.row();
        // Eq. 8's W1 and W2 (the paper gives no values): a banner's long edge bulges more than a
        // flag's; a curtain hangs from a rigid rod.
        let (bow, lean) = match self.kind() {
            ClothKind::Banner => (0.08, 0.04),
            ClothKind::Flag => (0.05, 0.03),
            ClothKind::Curtain => (0.0, 0.0),
        };
        ClothParams {
            wind_steps_per_frame,
            amplitude,
            beta,
            swirl,
            twist: 0.0,
            leading: LeadingYarn::Top,
            filter: match band {
                Some((min, max)) => HarmonicFilter::BandPass { min, max },
                None => HarmonicFilter::All,
            },
            model: if evolving {
                ClothWindModel::Evolving { frames: 64 }
            } else {
                ClothWindModel::Frozen
            },
            bow,
            lean,
            max_stretch: 1.0,
            reference_speed: self.band_speed(),
            seed: 1,
        }
    }
}

impl Default for ClothParams {
    /// The gentle frozen flag of Table 1 ([`ClothPreset::FlagFlappingFrozen`]).
    fn default() -> Self {
        ClothPreset::FlagFlappingFrozen.params()
    }
}
