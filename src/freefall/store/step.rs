//! [`Step`]: everything one step of the store reads, handed whole to the driver and to each
//! fall's slot.

use super::air::Air;
use crate::freefall::model::FallModel;
use crate::lod::Focus;

/// Everything one step reads.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step<'a> {
    pub model: &'a FallModel,
    /// The air, with eq. 15's reference speed ([`Air::reference_speed`]).
    pub air: Air<'a>,
    /// Where levels of detail are measured from (`None`: every fall at full detail).
    pub focus: Option<Focus>,
    /// How many falls go side by side in SIMD lanes: 1, 4 or 8 (the same bits at each; 8
    /// only where [`crate::portable::widest_lanes`] is 8).
    pub width: usize,
    /// Falls resting this long, s, are reported ([`StepReport::recycle`](super::driver::StepReport::recycle)).
    pub recycle_after: Option<f32>,
}
