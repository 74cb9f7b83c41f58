//! Presets for every row of Table 1 of the cloth paper.
//!
//! The paper names its rows by its own speed bands (light breeze 2.7–3.6 m/s, gentle 3.6–7.2,
//! moderate 8.9–12.5). On the standard Beaufort scale at 10 m these are force 2 (light breeze,
//! 1.6–3.3 m/s), force 3–4 (gentle 3.4–5.4, moderate 5.5–7.9) and force 5 (fresh breeze,
//! 8.0–10.7 m/s) respectively. Where the paper gives a range of β, the preset takes its middle.

use std::f32::consts::FRAC_PI_2;

use super::descriptor::HarmonicFilter;
use super::params::{ClothParams, ClothWindModel, LeadingYarn};

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

/// One row of Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // the names say it: object, paper's wind band, model
pub enum ClothPreset {
    BannerLightFrozen,
    BannerLightNonFrozen,
    BannerGentleFrozen,
    BannerGentleNonFrozen,
    CurtainGentleFrozen,
    CurtainGentleNonFrozen,
    CurtainModerateFrozen,
    CurtainModerateNonFrozen,
    FlagGentleFrozen,
    FlagGentleNonFrozen,
    FlagModerateFrozen,
    FlagModerateNonFrozen,
}

impl ClothPreset {
    /// Every preset, in Table 1's order.
    pub const ALL: [Self; 12] = [
        Self::BannerLightFrozen,
        Self::BannerLightNonFrozen,
        Self::BannerGentleFrozen,
        Self::BannerGentleNonFrozen,
        Self::CurtainGentleFrozen,
        Self::CurtainGentleNonFrozen,
        Self::CurtainModerateFrozen,
        Self::CurtainModerateNonFrozen,
        Self::FlagGentleFrozen,
        Self::FlagGentleNonFrozen,
        Self::FlagModerateFrozen,
        Self::FlagModerateNonFrozen,
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
            BannerLightFrozen => row(1.4, 2.75, 1.0, 0.0, Some((3, 7)), false, "banner lightly fluttering"),
            BannerLightNonFrozen => row(1.4, 2.75, 2.0, 1.0, Some((3, 7)), true, "banner lightly fluttering"),
            BannerGentleFrozen => row(1.4, 2.25, 2.0, 1.0, Some((3, 7)), false, "banner intensively flapping"),
            BannerGentleNonFrozen => row(1.4, 2.25, 8.0, 0.0, Some((1, 7)), true, "banner intensively flapping"),
            CurtainGentleFrozen => row(1.9, 2.5, 2.0, 1.0, None, false, "light curtain moving toward wind"),
            CurtainGentleNonFrozen => row(1.9, 2.75, 4.0, 0.0, None, true, "light curtain moving toward wind"),
            CurtainModerateFrozen => row(2.8, 2.5, 1.0, 0.0, None, false, "curtain intensively fluttering"),
            CurtainModerateNonFrozen => row(FRAC_PI_2, 2.75, 10.0, 1.0, Some((1, 6)), true, "curtain intensively fluttering"),
            FlagGentleFrozen => row(1.4, 2.75, 2.0, 1.0, Some((3, 5)), false, "light flag flapping"),
            FlagGentleNonFrozen => row(0.8, 2.5, 2.0, 1.0, Some((3, 6)), true, "light flag flapping"),
            FlagModerateFrozen => row(FRAC_PI_2, 2.9, 3.0, 1.0, Some((3, 5)), false, "uncurling of flag"),
            FlagModerateNonFrozen => row(2.0, 2.85, 4.0, 0.0, Some((3, 6)), true, "uncurling of flag"),
        };
        table
    }

    /// "banner", "curtain" or "flag".
    pub fn object(self) -> &'static str {
        let name = format!("{self:?}");
        if name.starts_with("Banner") {
            "banner"
        } else if name.starts_with("Curtain") {
            "curtain"
        } else {
            "flag"
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
            BannerLightFrozen | BannerLightNonFrozen => 3.15,
            CurtainModerateFrozen
            | CurtainModerateNonFrozen
            | FlagModerateFrozen
            | FlagModerateNonFrozen => 10.7,
            _ => 5.4,
        }
    }

    /// Whether this row uses non-frozen wind.
    pub fn non_frozen(self) -> bool {
        self.row().non_frozen
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
        let (bow, lean) = match self.object() {
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
                ClothWindModel::NonFrozen { frames: 64 }
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
