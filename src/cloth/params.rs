//! The cloth's grid and the six interactive parameters of the cloth paper §5.2.

use crate::error::InvalidValue;
use bevy::reflect::Reflect;
use thiserror::Error;

use super::descriptor::HarmonicFilter;

/// The grid of a cloth: `rows` yarns (horizontal threads, top to bottom), each of `columns`
/// nodes from the pole to the free edge, spanning `width × height` metres at rest.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct ClothGrid {
    /// Yarns, ≥ 1.
    pub rows: usize,
    /// Nodes per yarn, ≥ 2.
    pub columns: usize,
    /// Length of a yarn, m.
    pub width: f32,
    /// Distance from the top yarn to the bottom one, m.
    pub height: f32,
}

impl Default for ClothGrid {
    fn default() -> Self {
        Self {
            rows: 24,
            columns: 36,
            width: 1.5,
            height: 1.0,
        }
    }
}

impl ClothGrid {
    /// Length of one yarn segment, m.
    pub fn segment(&self) -> f32 {
        self.width / (self.columns - 1) as f32
    }

    /// Rest distance between neighbouring yarns, m (0 for a single yarn).
    pub fn row_spacing(&self) -> f32 {
        if self.rows > 1 {
            self.height / (self.rows - 1) as f32
        } else {
            0.0
        }
    }
}

/// The yarn the others are aligned to by eq. 7 (the flattening line, §5.2 item 6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect)]
pub enum LeadingYarn {
    /// The top edge.
    #[default]
    Top,
    /// The middle yarn.
    Center,
    /// The bottom edge.
    Bottom,
}

impl LeadingYarn {
    /// Index of the leading yarn among `rows`.
    pub fn index(self, rows: usize) -> usize {
        match self {
            Self::Top => 0,
            Self::Center => rows / 2,
            Self::Bottom => rows.saturating_sub(1),
        }
    }
}

/// Frozen (a 2-D noise matrix shifted each frame, §4.1) or evolving (the paper's non-frozen: a 3-D matrix sliced in
/// time and shifted, §4.2) wind on the cloth.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub enum ClothWindModel {
    /// 2-D noise, shifted.
    Frozen,
    /// 3-D noise of `frames` slices, one per paper frame (50 per second), each shifted on by
    /// |v| (§4.2). The slices are periodic, so the change loops every `frames` / 50 s (the
    /// shift goes on, so the cloth does not repeat with it).
    Evolving {
        /// Slices of the noise along time, ≥ 2.
        frames: usize,
    },
}

/// How a cloth moves: the six interactive parameters of §5.2 plus the descriptor filter, the
/// pole-edge elongation of eq. 8 and a seed. Shifts are in noise steps per frame at the paper's
/// 50 frames per second, as in Table 1; the simulation converts them to steps per second.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct ClothParams {
    /// 1. Wind speed |v|: steps the noise travels along the yarns per frame.
    pub wind_steps_per_frame: f32,
    /// 2. Vibration amplitude θ: the angles span [−θ, θ], radians, ≤ π.
    pub amplitude: f32,
    /// 3. Smoothness β of the noise (with θ): larger is smoother.
    pub beta: f32,
    /// 4. Swirling |u|: steps the noise travels across the yarns per frame.
    pub swirl: f32,
    /// 5. Twisting: columns by which each yarn's noise is offset from the previous yarn's.
    pub twist: f32,
    /// 6. Flattening line: the leading yarn of eq. 7.
    pub leading: LeadingYarn,
    /// Harmonics of the descriptor kept (Table 1's BPF ranges).
    pub filter: HarmonicFilter,
    /// Frozen or evolving wind.
    pub model: ClothWindModel,
    /// W1 of eq. 8: how far the pole edge bows downwind at its middle, as a fraction of the
    /// edge's length (grows with the wind, see [`ClothSim::rebuild`](super::sim::ClothSim::rebuild)).
    pub bow: f32,
    /// W2 of eq. 8: how far the pole edge bulges across the stream at its middle, as a fraction
    /// of the edge's length. The edge keeps its length (a hem): a bow and lean so deep that one
    /// node would stand more than half a row spacing out from the next are scaled down.
    pub lean: f32,
    /// Largest distance between neighbouring yarns, as a multiple of the rest spacing (L of
    /// eq. 7 is this times [`ClothGrid::row_spacing`]).
    pub max_stretch: f32,
    /// The air speed θ is the amplitude at, m/s (the middle of the row's Table 1 band): in
    /// other winds the waves scale by √(U / this) (see [`ClothSim::rebuild`](super::sim::ClothSim::rebuild)).
    pub reference_speed: f32,
    /// Seed of the noise.
    pub seed: u64,
}

/// A cloth configuration field out of range; [`ClothError::field`] names it.
#[derive(Clone, Debug, Error, PartialEq, Reflect)]
pub enum ClothError {
    /// A number outside its valid range.
    #[error(transparent)]
    Invalid(#[from] InvalidValue),
    /// A count outside its valid range.
    #[error("`{field}` = {value}: {reason}")]
    Count {
        /// The field's name.
        field: &'static str,
        /// The rejected count.
        value: usize,
        /// What it must be.
        reason: &'static str,
    },
}

impl ClothError {
    /// Name of the offending field (`"grid.columns"`, `"params.amplitude"`, ...).
    pub fn field(&self) -> &'static str {
        match self {
            Self::Invalid(InvalidValue { field, .. }) | Self::Count { field, .. } => field,
        }
    }
}

fn finite(
    field: &'static str,
    value: f32,
    ok: bool,
    reason: &'static str,
) -> Result<(), ClothError> {
    Ok(InvalidValue::check(
        value.is_finite() && ok,
        field,
        value,
        reason,
    )?)
}

impl ClothGrid {
    /// Checks the grid.
    pub fn validate(&self) -> Result<(), ClothError> {
        if self.rows < 1 {
            return Err(ClothError::Count {
                field: "grid.rows",
                value: self.rows,
                reason: "must be ≥ 1",
            });
        }
        if self.columns < 2 {
            return Err(ClothError::Count {
                field: "grid.columns",
                value: self.columns,
                reason: "must be ≥ 2",
            });
        }
        let nodes = self.rows.saturating_mul(self.columns);
        if nodes > ClothGrid::MAX_NODES {
            return Err(ClothError::Count {
                field: "grid",
                value: nodes,
                reason: "more than 2^20 nodes",
            });
        }
        finite(
            "grid.width",
            self.width,
            self.width > 0.0 && self.width <= ClothGrid::MAX_SIZE,
            crate::error::reason!("must be > 0 and ≤ {:e} m", ClothGrid::MAX_SIZE),
        )?;
        finite(
            "grid.height",
            self.height,
            self.height >= 0.0 && self.height <= ClothGrid::MAX_SIZE,
            crate::error::reason!("must be ≥ 0 and ≤ {:e} m", ClothGrid::MAX_SIZE),
        )
    }
}

impl ClothParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), ClothError> {
        let reason = "must be finite";
        finite(
            "params.wind_steps_per_frame",
            self.wind_steps_per_frame,
            true,
            reason,
        )?;
        finite(
            "params.amplitude",
            self.amplitude,
            (0.0..=std::f32::consts::PI).contains(&self.amplitude),
            "must be in [0, π]",
        )?;
        finite(
            "params.beta",
            self.beta,
            self.beta >= 0.0,
            "must be finite and ≥ 0",
        )?;
        finite("params.swirl", self.swirl, true, reason)?;
        finite("params.twist", self.twist, true, reason)?;
        finite(
            "params.bow",
            self.bow,
            self.bow.abs() <= 1.0,
            "a fraction of the edge, in [−1, 1]",
        )?;
        finite(
            "params.lean",
            self.lean,
            self.lean.abs() <= 1.0,
            "a fraction of the edge, in [−1, 1]",
        )?;
        finite(
            "params.reference_speed",
            self.reference_speed,
            self.reference_speed > 0.0,
            "must be finite and > 0",
        )?;
        finite(
            "params.max_stretch",
            self.max_stretch,
            self.max_stretch >= 1.0,
            "must be finite and ≥ 1",
        )?;
        if let HarmonicFilter::BandPass { min, max } = self.filter
            && min > max
        {
            return Err(ClothError::Count {
                field: "params.filter",
                value: min,
                reason: "band-pass min exceeds max",
            });
        }
        if let ClothWindModel::Evolving { frames } = self.model
            && frames < 2
        {
            return Err(ClothError::Count {
                field: "params.model.frames",
                value: frames,
                reason: "must be ≥ 2",
            });
        }
        Ok(())
    }
}

/// Limits and constants of [`ClothGrid`].
impl ClothGrid {
    /// Most nodes a cloth may have (1024 × 1024).
    pub const MAX_NODES: usize = 1 << 20;

    /// Largest width or height of a cloth, m: every node position stays far inside f32's range.
    pub const MAX_SIZE: f32 = 1.0e4;
}
