//! One cloth's shape over time: noise → angles → descriptor → yarns → constraints
//! (cloth paper §4–5), in the cloth's local frame.

use std::f32::consts::{FRAC_PI_2, PI};

use bevy::math::{Vec2, Vec3};

use super::constraints::{align_to_leading_yarn, pole_edge};
use super::descriptor::{DescriptorFilter, trace_yarn};
use super::noise::NoiseSheet;
use super::params::{ClothError, ClothGrid, ClothParams, ClothWindModel};

/// The paper's frame rate: Table 1's shifts are steps per frame at 50 fps.
pub const PAPER_FPS: f32 = 50.0;

/// How the yarns sit in the cloth's local frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ClothAttachment {
    /// Flag or banner: the fixed edge runs down local −Y from the origin, yarns stream along +X
    /// and flap along Z.
    #[default]
    Pole,
    /// Curtain: the fixed edge runs along local +X from the origin, yarns hang down −Y and
    /// billow along +Z (turn +Z downwind).
    Rod,
}

/// The state of one cloth: its noise, the shifts so far, and the node positions.
#[derive(Clone)]
pub struct ClothSim {
    grid: ClothGrid,
    params: ClothParams,
    attachment: ClothAttachment,
    noise: NoiseSheet,
    filter: DescriptorFilterCell,
    /// Noise steps the pattern has moved along / across the yarns, and the time for the
    /// non-frozen slices.
    along: f64,
    across: f64,
    time: f64,
    positions: Vec<Vec3>,
    angles: Vec<f32>,
    directions: Vec<Vec2>,
    yarn: Vec<Vec2>,
}

/// [`DescriptorFilter`] holds planned FFTs; cloning a sim re-plans them.
struct DescriptorFilterCell(DescriptorFilter, usize);

impl Clone for DescriptorFilterCell {
    fn clone(&self) -> Self {
        Self(DescriptorFilter::new(self.1, self.0.filter()), self.1)
    }
}

impl ClothSim {
    /// Validates the configuration, makes the noise matrix and the first shape.
    pub fn new(
        grid: ClothGrid,
        params: ClothParams,
        attachment: ClothAttachment,
    ) -> Result<Self, ClothError> {
        grid.validate()?;
        params.validate()?;
        let segments = grid.columns - 1;
        // The noise is wider than the cloth so that a wave takes a while to come round again.
        let noise_columns = (4 * segments).max(64);
        let noise_rows = grid.rows.max(16);
        let frames = match params.model {
            ClothWindModel::Frozen => 1,
            ClothWindModel::NonFrozen { frames, .. } => frames,
        };
        let noise = NoiseSheet::new(frames, noise_rows, noise_columns, params.beta, params.seed)?;
        let mut sim = Self {
            grid,
            params,
            attachment,
            noise,
            filter: DescriptorFilterCell(DescriptorFilter::new(segments, params.filter), segments),
            along: 0.0,
            across: 0.0,
            time: 0.0,
            positions: vec![Vec3::ZERO; grid.rows * grid.columns],
            angles: vec![0.0; segments],
            directions: vec![Vec2::X; segments],
            yarn: vec![Vec2::ZERO; grid.columns],
        };
        sim.rebuild();
        Ok(sim)
    }

    /// The grid.
    pub fn grid(&self) -> &ClothGrid {
        &self.grid
    }

    /// The parameters.
    pub fn params(&self) -> &ClothParams {
        &self.params
    }

    /// Node positions in the local frame, row-major (yarn by yarn, pole to free edge).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Noise steps moved along the yarns so far.
    pub fn shift_along(&self) -> f64 {
        self.along
    }

    /// Advances the noise by `dt` seconds at `wind_speed` steps per paper frame (|v|) and the
    /// parameters' swirl (|u|). Frozen wind only shifts (§4.1); non-frozen wind also moves
    /// through its time slices (§4.2). Non-finite input is ignored.
    pub fn advance(&mut self, dt: f32, wind_speed: f32) {
        let dt = f64::from(dt);
        let steps = f64::from(wind_speed) * f64::from(PAPER_FPS) * dt;
        let swirl = f64::from(self.params.swirl) * f64::from(PAPER_FPS) * dt;
        if steps.is_finite() && swirl.is_finite() && dt.is_finite() {
            // Keep the offsets within one period of the noise so f64 precision never runs out.
            let (_, rows, columns) = self.noise.size();
            self.along = (self.along + steps).rem_euclid(columns as f64);
            self.across = (self.across + swirl).rem_euclid(rows as f64);
            if let ClothWindModel::NonFrozen { period, .. } = self.params.model {
                self.time = (self.time + dt).rem_euclid(f64::from(period));
            }
        }
    }

    /// Rebuilds every node from the current shift: the noise gives the angles θ(k, j) in
    /// [−θ, θ]; the descriptor (eq. 4–6, filtered) gives unit segment directions; each yarn is
    /// traced from its pole-edge node (eq. 8); then eq. 7 aligns the yarns to the leading one.
    pub fn rebuild(&mut self) {
        let (rows, columns) = (self.grid.rows, self.grid.columns);
        let segment = self.grid.segment();
        let spacing = self.grid.row_spacing();
        let frame = match self.params.model {
            ClothWindModel::Frozen => 0.0,
            ClothWindModel::NonFrozen { frames, period } => {
                self.time / f64::from(period) * frames as f64
            }
        };
        let amplitude = self.params.amplitude;
        for k in 0..rows {
            let row = k as f64 + self.across;
            let skew = f64::from(self.params.twist) * k as f64;
            // Waves travel from the pole to the free edge: segment j now reads what segment
            // j − Δ read Δ steps ago.
            let first = skew - self.along;
            self.noise
                .sample_line(frame, row, first, amplitude, &mut self.angles);
            self.filter.0.directions(&self.angles, &mut self.directions);
            let start = pole_edge(k, rows, self.params.bow, self.params.lean);
            trace_yarn(start, &self.directions, segment, &mut self.yarn);
            for (j, p) in self.yarn.iter().enumerate() {
                self.positions[k * columns + j] = self.to_local(*p, k, spacing);
            }
        }
        let max_distance = spacing * self.params.max_stretch;
        let leading = self.params.leading.index(rows);
        align_to_leading_yarn(&mut self.positions, rows, columns, leading, max_distance);
    }

    /// From the yarn plane (along the yarn, across it) of yarn `k` to the cloth's local frame.
    fn to_local(&self, p: Vec2, k: usize, spacing: f32) -> Vec3 {
        match self.attachment {
            ClothAttachment::Pole => Vec3::new(p.x, -(k as f32) * spacing, p.y),
            ClothAttachment::Rod => Vec3::new(k as f32 * spacing, -p.x, p.y),
        }
    }
}

/// The angles of the pole edge's nodes in eq. 8: γ = π/2 and α_k = kπ/(n−1), so that the first
/// and last nodes (the two fixed ends) stay on the pole.
pub(crate) fn edge_angle(k: usize, rows: usize) -> (f32, f32) {
    let alpha = if rows > 1 {
        k as f32 * PI / (rows - 1) as f32
    } else {
        0.0
    };
    (FRAC_PI_2, alpha)
}
