//! A block of the fall store: [`W`] falls side by side, each number of their state in a column
//! of `W` lanes ([`Hot`]), so a step loads and stores whole lanes; their constants
//! ([`ConstantStorage`]) shared by the store or held per fall. Their rarely touched state is
//! [`Cold`](super::cold::Cold), one struct a fall beside the blocks.

use crate::freefall::model::motion::FallScales;

use crate::freefall::model::database::TrajectoryDatabase;
use crate::freefall::model::piece::Piece;
use crate::lod::LodTiers;
use crate::portable::lane::Lane;

/// Falls a block holds: the widest lanes the step may use on this target (eight on x86-64,
/// where AVX2 may be found at run time; four elsewhere). A fall's bits do not depend on it.
#[cfg(target_arch = "x86_64")]
pub(crate) const W: usize = 8;
/// Falls a block holds: the widest lanes the step may use on this target (eight on x86-64,
/// where AVX2 may be found at run time; four elsewhere). A fall's bits do not depend on it.
#[cfg(not(target_arch = "x86_64"))]
pub(crate) const W: usize = 4;

/// Declares a struct of `[f32; W]` columns and a copy of one lane of all of them.
macro_rules! columns {
    ($(#[$meta:meta])* $name:ident { $($(#[$field_meta:meta])* $field:ident),* $(,)? }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, Default)]
        pub(crate) struct $name {
            $($(#[$field_meta])* pub $field: [f32; W],)*
        }

        impl $name {
            /// Lane `from` of `source` into lane `to`.
            pub fn copy_lane(&mut self, to: usize, source: &Self, from: usize) {
                $(self.$field[to] = source.$field[from];)*
            }
        }
    };
}

columns!(
    /// What a step reads and writes of each fall, and what its pose is made from.
    Hot {
        /// Control points p_{i−2}, p_{i−1}, p_i (p_i is where the fall is), m.
        p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z,
        /// Orientations at p_{i−1} and p_i.
        q0x, q0y, q0z, q0w, q1x, q1y, q1z, q1w,
        /// What rounding left out of p_i so far (compensated summation), m.
        cx, cy, cz,
        /// Velocity of the fluid-following part, m/s.
        vx, vy, vz,
        /// f(t), the still-fluid displacement since release, m.
        sx, sy, sz,
        /// The piece's clock, s, and its displacement at that time (heading frame), m.
        t, ox, oy, oz,
        /// (cos ψ/2, sin ψ/2) and (cos ψ, sin ψ) of the heading ψ (a turn about +Y).
        hc, hs, tc, ts,
        /// The piece's duration T and 1/T, and its words (see `PieceWords`).
        duration, inv_duration,
        w0, w1, w2, w3, w4, w5, w6, w7, w8, w9, w10,
        /// 1 where: on the ground; a usual step is possible (no blend from a motion change, no
        /// release fading, no easing of the shown pose); the piece is an eq. 6 curve; a swing
        /// turns along the tumbling profile. 0 elsewhere.
        landed, plain, curve, tumble,
        /// Seconds on the ground since landing.
        rest,
        /// Seconds the last step covered, shown over (0 before the first step).
        span,
    }
);

/// The constants of one fall the step reads: U (m/s), 1/ℓ (1/m, ℓ the drag length), the
/// ground's height (m) and eq. 15's W (rad); and its levels of detail.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FallConstants {
    pub descent_speed: f32,
    pub inv_drag_length: f32,
    pub ground: f32,
    pub max_angle: f32,
    pub lod: Option<LodTiers>,
}

impl FallConstants {
    /// Those of a fall of `scales` above `ground` turned by the wind up to `max_angle`, with
    /// levels of detail `lod`.
    pub fn new(scales: &FallScales, ground: f32, max_angle: f32, lod: Option<LodTiers>) -> Self {
        Self {
            descent_speed: scales.descent_speed,
            inv_drag_length: 1.0 / scales.drag_length.max(1e-12),
            ground,
            max_angle,
            lod,
        }
    }
}

/// [`FallConstants`] in lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneConstants<L> {
    pub descent_speed: L,
    pub inv_drag_length: L,
    pub ground: L,
    pub max_angle: L,
}

columns!(
    /// [`FallConstants`] held per fall (no levels of detail: `near` NaN).
    ConstantColumns { descent_speed, inv_drag_length, ground, max_angle, near, far }
);

/// Where a store keeps its falls' constants: once for all ([`SharedConstants`], splatted into the lanes:
/// a cloud's leaves and a single path) or per fall ([`PerFallConstants`], in a column: the app's falling
/// objects, each of its own description).
pub(crate) trait ConstantStorage: Clone + Send + Sync + 'static {
    /// What a block holds of them (nothing when shared).
    type Lanes: Copy + Default + Send + Sync + std::fmt::Debug;
    /// The constants of lanes `k..k + L::WIDTH`.
    fn load<L: Lane>(&self, lanes: &Self::Lanes, k: usize) -> LaneConstants<L>;
    /// Sets lane `k`'s (nothing when shared).
    fn set(lanes: &mut Self::Lanes, k: usize, constants: &FallConstants);
    /// Lane `k`'s levels of detail.
    fn lod(&self, lanes: &Self::Lanes, k: usize) -> Option<LodTiers>;
    /// Lane `k`'s, as one fall.
    fn get(&self, lanes: &Self::Lanes, k: usize) -> FallConstants {
        let c = self.load::<f32>(lanes, k);
        FallConstants {
            descent_speed: c.descent_speed,
            inv_drag_length: c.inv_drag_length,
            ground: c.ground,
            max_angle: c.max_angle,
            lod: self.lod(lanes, k),
        }
    }
    /// Copies lane `from` of `source` into lane `to`.
    fn copy_lane(lanes: &mut Self::Lanes, to: usize, source: &Self::Lanes, from: usize);
}

/// Constants every fall of the store shares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SharedConstants(pub FallConstants);

impl ConstantStorage for SharedConstants {
    type Lanes = ();

    #[inline(always)]
    fn load<L: Lane>(&self, _: &(), _: usize) -> LaneConstants<L> {
        let c = &self.0;
        LaneConstants {
            descent_speed: L::splat(c.descent_speed),
            inv_drag_length: L::splat(c.inv_drag_length),
            ground: L::splat(c.ground),
            max_angle: L::splat(c.max_angle),
        }
    }

    fn set(_: &mut (), _: usize, _: &FallConstants) {}

    fn lod(&self, _: &(), _: usize) -> Option<LodTiers> {
        self.0.lod
    }

    fn copy_lane(_: &mut (), _: usize, _: &(), _: usize) {}
}

/// Constants held per fall.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct PerFallConstants;

impl ConstantStorage for PerFallConstants {
    type Lanes = ConstantColumns;

    #[inline(always)]
    fn load<L: Lane>(&self, lanes: &ConstantColumns, k: usize) -> LaneConstants<L> {
        LaneConstants {
            descent_speed: L::load(&lanes.descent_speed, k),
            inv_drag_length: L::load(&lanes.inv_drag_length, k),
            ground: L::load(&lanes.ground, k),
            max_angle: L::load(&lanes.max_angle, k),
        }
    }

    fn set(lanes: &mut ConstantColumns, k: usize, c: &FallConstants) {
        lanes.descent_speed[k] = c.descent_speed;
        lanes.inv_drag_length[k] = c.inv_drag_length;
        lanes.ground[k] = c.ground;
        lanes.max_angle[k] = c.max_angle;
        (lanes.near[k], lanes.far[k]) = c.lod.map_or((f32::NAN, f32::NAN), |l| (l.near, l.far));
    }

    fn lod(&self, lanes: &ConstantColumns, k: usize) -> Option<LodTiers> {
        let (near, far) = (lanes.near[k], lanes.far[k]);
        (!near.is_nan()).then_some(LodTiers { near, far })
    }

    fn copy_lane(lanes: &mut ConstantColumns, to: usize, source: &ConstantColumns, from: usize) {
        lanes.copy_lane(to, source, from);
    }
}

/// [`W`] falls' lanes.
#[derive(Debug)]
pub(crate) struct Block<K: ConstantStorage> {
    pub hot: Hot,
    /// A swing's first database row.
    pub row: [u32; W],
    /// The fall's clock when it was last stepped, s.
    pub updated: [f64; W],
    /// Which fall each lane holds (its handle in the store).
    pub handle: [u32; W],
    pub consts: K::Lanes,
}

impl<K: ConstantStorage> Clone for Block<K> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<K: ConstantStorage> Copy for Block<K> {}

impl<K: ConstantStorage> Default for Block<K> {
    fn default() -> Self {
        Self {
            hot: Hot::default(),
            row: [0; W],
            updated: [0.0; W],
            handle: [0; W],
            consts: K::Lanes::default(),
        }
    }
}

impl<K: ConstantStorage> Block<K> {
    /// Lane `from` of `source` into lane `to`.
    pub fn copy_lane(&mut self, to: usize, source: &Self, from: usize) {
        self.hot.copy_lane(to, &source.hot, from);
        self.row[to] = source.row[from];
        self.updated[to] = source.updated[from];
        self.handle[to] = source.handle[from];
        K::copy_lane(&mut self.consts, to, &source.consts, from);
    }

    /// Writes `piece`, compiled, into lane `k`.
    pub fn write_piece(&mut self, k: usize, piece: &Piece, db: &TrajectoryDatabase) {
        let words = piece.words(db);
        let h: &mut Hot = &mut self.hot;
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
        self.row[k] = words.row;
    }
}

#[cfg(test)]
mod tests {
    use super::super::cold::Cold;
    use super::*;

    /// What a usual step reads and writes of a fall is its lanes of a block: at most 300 bytes a
    /// fall (a cloud of 100 000 leaves streams more than the caches hold, so a step waits for
    /// memory: docs/performance.md). The cold state is read only when a piece ends, a motion
    /// changes, a fall lands, is let go or changes tier; it takes at most 256 bytes.
    #[test]
    fn a_usual_step_streams_at_most_300_bytes_a_fall() {
        let shared = std::mem::size_of::<Block<SharedConstants>>() / W;
        let own = std::mem::size_of::<Block<PerFallConstants>>() / W;
        let cold = std::mem::size_of::<Cold>();
        println!(
            "a fall's lanes: {shared} bytes in a cloud, {own} as an entity; cold state {cold}"
        );
        assert!(shared <= 300 && own <= 300, "{shared} / {own} bytes a fall");
        assert!(cold <= 256, "{cold} bytes of cold state");
    }
}
