//! The air a store's falls move in, and one step's read of it: the wind field's moment taken
//! once, then read where each block's falls are, in lanes.

use bevy::math::Vec3;

use super::block::{Block, ConstantStorage, W};
use crate::freefall::model::release::FallRelease;
use crate::portable::geometry::V3;
use crate::portable::lane::{Lane, MAX_WIDTH, per_lane};
use crate::wind::{Moment, MoverFlow, WindField};

/// The air the falls move in.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Air<'a> {
    /// Still air.
    Still,
    /// The wind field, read where each fall is at its own clock.
    Field(&'a WindField),
    /// The same velocity everywhere, m/s, and the reference speed of eq. 15 the tilt is
    /// measured against (a field's is its own).
    Uniform(Vec3, f32),
}

impl Air<'_> {
    /// Eq. 15's U_ref, m/s: the field's reference speed, a uniform air's own, 1 m/s in still
    /// air (where nothing tilts).
    pub(crate) fn reference_speed(&self) -> f32 {
        match *self {
            Air::Still => 1.0,
            Air::Field(field) => field.config().reference_speed,
            Air::Uniform(_, reference_speed) => reference_speed,
        }
    }
}

/// The air of one step, with what its reads share.
pub(super) enum Reading<'a> {
    Still,
    Field(&'a WindField, Moment),
    /// The field for falls that all lie in a box: only the movers whose flow reaches it (the
    /// same bits: the others add exact zeros there).
    Near(&'a WindField, Moment, Vec<MoverFlow>),
    /// Already held to [`FallRelease::MAX_SPEED`].
    Uniform(Vec3),
}

impl<'a> Reading<'a> {
    /// What every read of the wind on a step shares, taken once.
    pub(super) fn of(air: Air<'a>) -> Self {
        match air {
            Air::Field(field) => Reading::Field(field, field.moment(field.time_f64())),
            Air::Uniform(u, _) => {
                Reading::Uniform(clamp_speed(V3::of(u), FallRelease::MAX_SPEED).vec3())
            }
            Air::Still => Reading::Still,
        }
    }

    /// This step's air for the first `live` falls of `blocks`: the movers whose flow cannot
    /// reach any of them left out (`None` where nothing would be).
    pub(super) fn around<K: ConstantStorage>(
        &self,
        blocks: &[Block<K>],
        live: usize,
    ) -> Option<Reading<'a>> {
        let Reading::Field(field, moment) = self else {
            return None;
        };
        if field.placed_movers().is_empty() {
            return None;
        }
        let (mut low, mut high) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for (b, block) in blocks.iter().enumerate() {
            let h = &block.hot;
            for j in 0..live.saturating_sub(b * W).min(W) {
                let p = Vec3::new(h.p2x[j], h.p2y[j], h.p2z[j]);
                (low, high) = (low.min(p), high.max(p));
            }
        }
        (low.is_finite() && high.is_finite())
            .then(|| Reading::Near(field, *moment, field.movers_near(low, high)))
    }

    /// The air's velocity at lanes `k..` of `block` (where each fall is), held to
    /// [`FallRelease::MAX_SPEED`].
    #[inline(always)]
    pub(super) fn lanes<L: Lane, K: ConstantStorage>(&self, block: &Block<K>, k: usize) -> V3<L> {
        let h = &block.hot;
        match self {
            Reading::Still => V3::splat(Vec3::ZERO),
            Reading::Uniform(u) => V3::splat(*u),
            Reading::Field(field, moment) => {
                let p = V3::new(L::load(&h.p2x, k), L::load(&h.p2y, k), L::load(&h.p2z, k));
                clamp_speed(field.velocity_lanes(moment, p), FallRelease::MAX_SPEED)
            }
            Reading::Near(field, moment, movers) => {
                let p = V3::new(L::load(&h.p2x, k), L::load(&h.p2y, k), L::load(&h.p2z, k));
                let v = field.velocity_lanes_among(moment, p, movers);
                clamp_speed(v, FallRelease::MAX_SPEED)
            }
        }
    }
}

/// `v` held to `max` long (a non-finite vector: zero), lane by lane: the usual case with no
/// division, the rest one lane at a time (overflow-safe).
#[inline(always)]
fn clamp_speed<L: Lane>(v: V3<L>, max: f32) -> V3<L> {
    let squared = v.length_squared();
    let ok = L::and(squared.gt(L::splat(0.0)), squared.le(L::splat(max * max)));
    let zero = squared.eq(L::splat(0.0));
    if L::all(L::or(ok, zero)) {
        return v;
    }
    let each = |j: usize| {
        if L::mask_get(ok, j) {
            Vec3::new(v.x.get(j), v.y.get(j), v.z.get(j))
        } else {
            crate::guard::clamp_length(Vec3::new(v.x.get(j), v.y.get(j), v.z.get(j)), max)
        }
    };
    let lanes: [Vec3; MAX_WIDTH] = per_lane(|j| if j < L::WIDTH { each(j) } else { Vec3::ZERO });
    V3::new(
        L::from_fn(|j| lanes[j].x),
        L::from_fn(|j| lanes[j].y),
        L::from_fn(|j| lanes[j].z),
    )
}
