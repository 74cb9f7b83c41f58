//! The leaves of the showcase's tree: which kinds, where they are let go, and how they are
//! turned. Shared with `tests/freefall_presets.rs`, which checks headlessly that this population
//! shows at least four primitive motions at once.

use std::f32::consts::TAU;

use bevy::math::{Quat, Vec3};
use bevy_windfall::freefall::{FallPreset, FallingObject};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg32;

/// Leaves on the tree.
pub const LEAVES: usize = 600;
/// Centre and radius of the canopy leaves fall from, m.
pub const CANOPY: Vec3 = Vec3::new(0.0, 5.5, 0.0);
pub const CANOPY_RADIUS: f32 = 2.2;

/// The kinds of leaves, in turn: maple, oak, birch and the paper's leaf.
pub const KINDS: [FallPreset; 4] = [
    FallPreset::MapleLeaf,
    FallPreset::OakLeaf,
    FallPreset::BirchLeaf,
    FallPreset::Leaf,
];

/// Leaf `i`: its kind's preset with seed `i`.
pub fn leaf(i: usize) -> FallingObject {
    FallingObject {
        seed: i as u64,
        ..KINDS[i % KINDS.len()].object()
    }
}

/// A seeded stream for laying a scene out: PCG32, the same numbers on every platform.
pub struct Stream(Pcg32);

impl Stream {
    /// A stream from a seed.
    pub fn new(seed: u64) -> Self {
        Self(Pcg32::seed_from_u64(seed))
    }

    /// Uniform in [0, 1), from the top 24 bits of a draw.
    pub fn uniform(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }
}

/// Where leaves are let go, drawn from a seeded stream.
pub struct Canopy(pub Stream);

impl Canopy {
    /// A point in the lower half of the canopy.
    pub fn point(&mut self) -> Vec3 {
        let r = &mut self.0;
        let angle = r.uniform() * TAU;
        let radius = CANOPY_RADIUS * r.uniform().sqrt();
        let height = CANOPY.y - 0.8 + 1.4 * r.uniform();
        Vec3::new(
            CANOPY.x + radius * angle.cos(),
            height,
            CANOPY.z + radius * angle.sin(),
        )
    }

    /// Where a leaf is when the scene starts: anywhere on its way down from the canopy, carried
    /// downwind (+X) about as far as a leaf falling from there would be, so the scene starts as
    /// it will go on rather than with every leaf leaving the tree at once.
    pub fn midair(&mut self) -> Vec3 {
        let start = self.point();
        let height = 0.3 + (start.y - 0.3) * self.0.uniform();
        start + Vec3::new(1.5 * (start.y - height), height - start.y, 0.0)
    }

    /// How a leaf hangs when it lets go: any heading, tipped by up to 0.5 rad.
    pub fn turn(&mut self) -> Quat {
        let r = &mut self.0;
        Quat::from_rotation_y(r.uniform() * TAU)
            * Quat::from_rotation_x(0.5 * (2.0 * r.uniform() - 1.0))
    }
}
