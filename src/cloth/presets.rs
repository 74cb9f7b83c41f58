//! Presets for every row of Table 1 of the cloth paper.
//!
//! The paper names its rows by its own speed bands (light breeze 2.7–3.6 m/s, gentle 3.6–7.2,
//! moderate 8.9–12.5). On the standard Beaufort scale at 10 m these are force 2 (light breeze,
//! 1.6–3.3 m/s), force 3–4 (gentle 3.4–5.4, moderate 5.5–7.9) and force 5 (fresh breeze,
//! 8.0–10.7 m/s) respectively. Where the paper gives a range of β, the preset takes its middle.

use std::f32::consts::FRAC_PI_2;

use super::component::Cloth;
use super::descriptor::HarmonicFilter;
use super::params::{ClothParams, ClothWindModel, LeadingYarn};
use super::sim::ClothAttachment;

/// θ, β, |v|, |u|, BPF range, non-frozen, and what the paper observed.
struct TableRow {
    theta: f32,
    beta: f32,
    v: f32,
    u: f32,
    band: Option<(usize, usize)>,
    non_frozen: bool,
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
        let row = |theta, beta, v, u, band, non_frozen, observation| TableRow {
            theta,
            beta,
            v,
            u,
            band,
            non_frozen,
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

    /// "banner", "curtain" or "flag".
    pub fn kind(self) -> &'static str {
        use ClothPreset::*;
        match self {
            BannerFlutteringFrozen
            | BannerFlutteringEvolving
            | BannerFlappingFrozen
            | BannerFlappingEvolving => "banner",
            CurtainDriftingFrozen
            | CurtainDriftingEvolving
            | CurtainFlutteringFrozen
            | CurtainFlutteringEvolving => "curtain",
            FlagFlappingFrozen
            | FlagFlappingEvolving
            | FlagUncurlingFrozen
            | FlagUncurlingEvolving => "flag",
        }
    }

    /// "banner", "curtain" or "flag".
    #[deprecated(since = "0.2.0", note = "renamed to `kind`")]
    pub fn object(self) -> &'static str {
        self.kind()
    }

    /// A [`Cloth`] of this row, ready to spawn: its parameters, on a pole (banners, flags) or a
    /// rod (curtains), following the wind.
    pub fn cloth(self) -> Cloth {
        Cloth {
            params: self.params(),
            attachment: if self.kind() == "curtain" {
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
        self.row().non_frozen
    }

    /// Whether this row uses evolving (the paper's non-frozen) wind.
    #[deprecated(since = "0.2.0", note = "renamed to `evolving`")]
    pub fn non_frozen(self) -> bool {
        self.evolving()
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
            v: wind_speed,
            u: swirl,
            band,
            non_frozen,
            ..
        } = self.row();
        // Eq. 8's W1 and W2 (the paper gives no values): a banner's long edge bulges more than a
        // flag's; a curtain hangs from a rigid rod.
        let (bow, lean) = match self.kind() {
            "banner" => (0.08, 0.04),
            "flag" => (0.05, 0.03),
            _ => (0.0, 0.0),
        };
        ClothParams {
            wind_speed,
            amplitude,
            beta,
            swirl,
            twist: 0.0,
            leading: LeadingYarn::Top,
            filter: match band {
                Some((min, max)) => HarmonicFilter::BandPass { min, max },
                None => HarmonicFilter::All,
            },
            model: if non_frozen {
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

/// The names of the first release (the paper's wind band and "non-frozen"), kept for one
/// release.
#[allow(non_upper_case_globals)]
impl ClothPreset {
    /// Renamed to [`ClothPreset::BannerFlutteringFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `BannerFlutteringFrozen`")]
    pub const BannerLightFrozen: Self = Self::BannerFlutteringFrozen;
    /// Renamed to [`ClothPreset::BannerFlutteringEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `BannerFlutteringEvolving`")]
    pub const BannerLightNonFrozen: Self = Self::BannerFlutteringEvolving;
    /// Renamed to [`ClothPreset::BannerFlappingFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `BannerFlappingFrozen`")]
    pub const BannerGentleFrozen: Self = Self::BannerFlappingFrozen;
    /// Renamed to [`ClothPreset::BannerFlappingEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `BannerFlappingEvolving`")]
    pub const BannerGentleNonFrozen: Self = Self::BannerFlappingEvolving;
    /// Renamed to [`ClothPreset::CurtainDriftingFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `CurtainDriftingFrozen`")]
    pub const CurtainGentleFrozen: Self = Self::CurtainDriftingFrozen;
    /// Renamed to [`ClothPreset::CurtainDriftingEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `CurtainDriftingEvolving`")]
    pub const CurtainGentleNonFrozen: Self = Self::CurtainDriftingEvolving;
    /// Renamed to [`ClothPreset::CurtainFlutteringFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `CurtainFlutteringFrozen`")]
    pub const CurtainModerateFrozen: Self = Self::CurtainFlutteringFrozen;
    /// Renamed to [`ClothPreset::CurtainFlutteringEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `CurtainFlutteringEvolving`")]
    pub const CurtainModerateNonFrozen: Self = Self::CurtainFlutteringEvolving;
    /// Renamed to [`ClothPreset::FlagFlappingFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `FlagFlappingFrozen`")]
    pub const FlagGentleFrozen: Self = Self::FlagFlappingFrozen;
    /// Renamed to [`ClothPreset::FlagFlappingEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `FlagFlappingEvolving`")]
    pub const FlagGentleNonFrozen: Self = Self::FlagFlappingEvolving;
    /// Renamed to [`ClothPreset::FlagUncurlingFrozen`].
    #[deprecated(since = "0.2.0", note = "renamed to `FlagUncurlingFrozen`")]
    pub const FlagModerateFrozen: Self = Self::FlagUncurlingFrozen;
    /// Renamed to [`ClothPreset::FlagUncurlingEvolving`].
    #[deprecated(since = "0.2.0", note = "renamed to `FlagUncurlingEvolving`")]
    pub const FlagModerateNonFrozen: Self = Self::FlagUncurlingEvolving;
}

impl Default for ClothParams {
    /// The gentle frozen flag of Table 1 ([`ClothPreset::FlagFlappingFrozen`]).
    fn default() -> Self {
        ClothPreset::FlagFlappingFrozen.params()
    }
}
