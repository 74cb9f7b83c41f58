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
    /// Whether falls go several at a time in SIMD lanes (the same bits either way).
    pub lanes: bool,
    /// Falls resting this long, s, are reported ([`StepReport::recycle`](super::driver::StepReport::recycle)).
    pub recycle_after: Option<f32>,
}
