//! One cloth's shape over time: noise → angles → descriptor → yarns → constraints
//! (cloth paper §4–5), in the cloth's local frame.
//!
//! Per frame, each yarn reads its directions from the [`DirectionSheet`] where the wind has
//! shifted the noise, holds them along the stream near the pole, scales them with the wind's
//! strength, and is traced from its pole-edge node (eq. 8) in equal segments; eq. 7 then aligns
//! the yarns. See [`ClothSim::rebuild`] for what the wind's strength does.

use std::f32::consts::PI;

use bevy::math::{Vec2, Vec3};

use super::constraints::{align_to_leading_yarn, pole_hem};
use super::directions::{CELLS_PER_YARN, ColumnTap, DirectionSheet, LINE_YARNS};
use super::noise::NoiseSheet;
use super::params::{ClothError, ClothGrid, ClothParams, ClothWindModel};

/// How the yarns sit in the cloth's local frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bevy::reflect::Reflect)]
pub enum ClothAttachment {
    /// Flag or banner: the fixed edge runs down local −Y from the origin, yarns stream along +X
    /// and flap along Z.
    #[default]
    Pole,
    /// Curtain: the fixed edge runs along local +X from the origin, yarns hang down −Y and
    /// billow along +Z (turn +Z downwind).
    Rod,
}

/// What the wind's strength does to the shape, from the air speed U (m/s) and the speed the
/// parameters were set for.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Strength {
    /// Angle scale: √(U / U_ref), at most 1.2.
    gain: f32,
    /// 1 in calm air (a flag hangs), 0 from 3 m/s (it flies).
    droop: f32,
    /// A curtain's lean downwind, rad.
    lean: f32,
}

impl Strength {
    fn new(speed: f32, reference: f32) -> Self {
        let speed = if speed.is_finite() {
            speed.max(0.0)
        } else {
            0.0
        };
        let gain = (speed / reference.max(0.1)).sqrt().min(1.2);
        let calm = ((speed - 0.5) / 2.5).clamp(0.0, 1.0);
        let droop = 1.0 - calm * calm * (3.0 - 2.0 * calm);
        // tan(lean) ∝ U² (drag over weight): 35° at 5 m/s, at most 60°.
        let lean = (0.028 * speed * speed).atan().min(PI / 3.0);
        Self { gain, droop, lean }
    }
}

/// The state of one cloth: its noise, the shifts so far, and the node positions.
#[derive(Clone)]
pub struct ClothSim {
    grid: ClothGrid,
    params: ClothParams,
    attachment: ClothAttachment,
    sheet: DirectionSheet,
    /// Noise cells the pattern has moved along / across the yarns, and the time for the
    /// evolving slices.
    along: f64,
    across: f64,
    time: f64,
    /// What the last step added to `along`, `across` and `time`.
    last_step: [f64; 3],
    /// |v| of the last step.
    speed: f32,
    positions: Vec<Vec3>,
    directions: Vec<Vec2>,
    /// (cos, sin) of each segment's turn down in calm air.
    droop: Vec<Vec2>,
    /// How much of each segment's deviation from the stream is kept (the pole's hold × the
    /// wind's gain).
    keep: Vec<f32>,
    taps: Vec<ColumnTap>,
    /// The pole edge's nodes (eq. 8, a hem of fixed length).
    hem: Vec<Vec3>,
}

impl Default for ClothSim {
    /// The default cloth: a flag on a pole, Table 1's gentle frozen row.
    fn default() -> Self {
        Self::new(
            ClothGrid::default(),
            ClothParams::default(),
            ClothAttachment::Pole,
        )
        .expect("the default cloth is valid")
    }
}

impl ClothSim {
    /// Validates the configuration, makes the noise matrix and its directions, and the first
    /// shape.
    pub fn new(
        grid: ClothGrid,
        params: ClothParams,
        attachment: ClothAttachment,
    ) -> Result<Self, ClothError> {
        grid.validate()?;
        params.validate()?;
        let segments = grid.columns - 1;
        let noise_rows = grid.rows.max(16);
        let frames = match params.model {
            ClothWindModel::Frozen => 1,
            ClothWindModel::Evolving { frames } => frames,
        };
        // Checked before anything is allocated: the noise and its directions take 12 bytes a
        // cell.
        let cells = frames
            .saturating_mul(noise_rows)
            .saturating_mul(LINE_YARNS * CELLS_PER_YARN);
        if cells > ClothSim::MAX_NOISE_CELLS {
            let (field, value) = if frames > 1 {
                ("params.model.frames", frames)
            } else {
                ("grid.rows", grid.rows)
            };
            return Err(ClothError::Count {
                field,
                value,
                reason: "the noise would exceed 2^22 cells (frames × max(rows, 16) × 160)",
            });
        }
        let noise = NoiseSheet::new(
            frames,
            noise_rows,
            LINE_YARNS * CELLS_PER_YARN,
            params.beta,
            params.seed,
        )?;
        let sheet = DirectionSheet::new(&noise, params.amplitude, params.filter);
        let mut sim = Self {
            grid,
            params,
            attachment,
            sheet,
            along: 0.0,
            across: 0.0,
            time: 0.0,
            last_step: [0.0; 3],
            speed: params.wind_steps_per_frame,
            positions: vec![Vec3::ZERO; grid.rows * grid.columns],
            directions: vec![Vec2::X; segments],
            droop: vec![Vec2::X; segments],
            keep: vec![1.0; segments],
            taps: Vec::with_capacity(segments),
            hem: Vec::with_capacity(grid.rows),
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

    /// Pole or rod.
    pub fn attachment(&self) -> ClothAttachment {
        self.attachment
    }

    /// Node positions in the local frame, row-major (yarn by yarn, pole to free edge).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Sets every node to `from[i]` lerped toward where it is by `w` ∈ [0, 1] (a cross-fade
    /// from another shape of the same grid); a `from` of another length changes nothing.
    pub(crate) fn fade_from(&mut self, from: &[Vec3], w: f32) {
        if from.len() == self.positions.len() {
            let w = w.clamp(0.0, 1.0);
            for (p, f) in self.positions.iter_mut().zip(from) {
                *p = f.lerp(*p, w);
            }
        }
    }

    /// Noise cells moved along the yarns so far.
    pub fn shift_along(&self) -> f64 {
        self.along
    }

    /// The air speed the cloth flaps in now, m/s (from the last step's |v|, [`Self::speed_of_steps`]).
    pub fn air_speed(&self) -> f32 {
        Self::speed_of_steps(self.speed, self.grid.width)
    }

    /// Advances the noise by `dt` seconds at `wind_steps_per_frame` (|v|, noise steps per paper
    /// frame) and the parameters' swirl (|u|). Frozen wind only shifts (§4.1); evolving wind (the
    /// paper's non-frozen) also moves on one time slice per paper frame (§4.2: slice f is the
    /// first slice shifted f |v| cells, so the pattern both travels and changes). Non-finite
    /// input is ignored.
    pub fn advance(&mut self, dt: f32, wind_steps_per_frame: f32) {
        let dt = f64::from(dt);
        let steps = f64::from(wind_steps_per_frame) * f64::from(ClothSim::PAPER_FPS) * dt;
        let swirl = f64::from(self.params.swirl) * f64::from(ClothSim::PAPER_FPS) * dt;
        if steps.is_finite() && swirl.is_finite() && dt.is_finite() && dt >= 0.0 {
            // Keep the offsets within one period of the noise so f64 precision never runs out.
            let (frames, rows, columns) = self.sheet.size();
            self.along = (self.along + steps).rem_euclid(columns as f64);
            self.across = (self.across + swirl).rem_euclid(rows as f64);
            self.time = (self.time + dt).rem_euclid(frames as f64 / f64::from(ClothSim::PAPER_FPS));
            self.last_step = [steps, swirl, dt];
            self.speed = wind_steps_per_frame;
        }
    }

    /// Rebuilds every node from the current shift. Each yarn k reads the directions of its
    /// noise row (k + the swirl's shift, offset by the twist) where the wind has moved them, and
    /// the wind's strength U (from |v|, [`Self::speed_of_steps`]) shapes them:
    /// - near the pole the yarn leaves along the stream: the deviation from it grows from 0 at
    ///   the pole to full over the first 30 % of the yarn (the pole holds the cloth);
    /// - the deviation scales with √(U / U_ref), U_ref the parameters' reference speed (the
    ///   middle of the Table 1 row's band), so waves grow with the wind (at most 1.2×), and so
    ///   do eq. 8's bow and lean;
    /// - in calm air a flag or banner hangs: the paper has no gravity, so the yarns are turned
    ///   down by up to 65°–85° (more toward the free edge) below 0.5 m/s, blending to flying at
    ///   3 m/s;
    /// - a curtain leans downwind (+Z) by atan(0.028 U²): 35° at 5 m/s.
    pub fn rebuild(&mut self) {
        self.rebuild_with(self.along, self.across, self.time, 1);
    }

    /// [`ClothSim::rebuild`] a fraction `s` ∈ [0, 1] of the way from the step before the last
    /// one to the last: the shape between fixed steps, so a cloth drawn every frame moves
    /// smoothly at any frame rate (1 is [`ClothSim::rebuild`]).
    pub fn rebuild_at(&mut self, s: f32) {
        self.rebuild_at_stride(s, 1);
    }

    /// [`ClothSim::rebuild_at`] on a grid `stride` times coarser (1 is the full grid; see
    /// [`ClothLod`](super::component::ClothLod)): every `stride`-th yarn is traced, in segments `stride`
    /// times longer that read the noise at their middle, and the nodes between are placed
    /// evenly along them; the yarns between are interpolated, each moved so its pole-edge node
    /// is where eq. 8 puts it. The mesh keeps every node, so a change of stride changes no
    /// topology. The cost falls about as the square of the stride.
    pub fn rebuild_at_stride(&mut self, s: f32, stride: usize) {
        let back = 1.0
            - f64::from(if s.is_finite() {
                s.clamp(0.0, 1.0)
            } else {
                1.0
            });
        let [along, across, time] = self.last_step;
        self.rebuild_with(
            self.along - back * along,
            self.across - back * across,
            self.time - back * time,
            stride,
        );
    }

    fn rebuild_with(&mut self, along: f64, across: f64, time: f64, stride: usize) {
        let (rows, columns) = (self.grid.rows, self.grid.columns);
        let segments = columns - 1;
        let n = stride.clamp(1, segments);
        let coarse = segments.div_ceil(n);
        let segment = self.grid.segment();
        let spacing = self.grid.row_spacing();
        let strength = Strength::new(self.air_speed(), self.params.reference_speed);
        let frame = match self.params.model {
            ClothWindModel::Frozen => 0.0,
            ClothWindModel::Evolving { .. } => time * f64::from(ClothSim::PAPER_FPS),
        };
        let step = CELLS_PER_YARN as f64 / segments as f64;
        // A coarse segment reads the noise at its middle.
        let middle = step * (n - 1) as f64 * 0.5;
        let hold = (0.3 * segments as f32).max(1.0);
        let (lean_sin, lean_cos) = strength.lean.sin_cos();
        for (j, (turn, keep)) in self.droop.iter_mut().zip(&mut self.keep).enumerate() {
            let fraction = (j as f32 + 0.5) / segments as f32;
            let down = strength.droop * (65f32 + 20.0 * fraction).to_radians();
            let (sin, cos) = down.sin_cos();
            *turn = Vec2::new(cos, sin);
            // Held along the stream at the pole, scaled by the wind.
            let s = ((j as f32 + 0.5) / hold).min(1.0);
            *keep = strength.gain * (1.0 - (1.0 - s) * (1.0 - s));
        }
        let twist = f64::from(self.params.twist);
        if twist == 0.0 {
            self.sheet
                .column_taps(middle - along, step * n as f64, coarse, &mut self.taps);
        }
        if self.attachment == ClothAttachment::Pole {
            pole_hem(
                rows,
                spacing,
                self.params.bow * strength.gain * self.grid.height,
                self.params.lean * strength.gain * self.grid.height,
                &mut self.hem,
            );
        }
        let edge = |k: usize| match self.attachment {
            ClothAttachment::Pole => self.hem[k],
            ClothAttachment::Rod => Vec3::new(k as f32 * spacing, 0.0, 0.0),
        };
        // Traced yarns: every n-th and the last.
        for k in (0..rows)
            .step_by(n)
            .chain(((rows - 1) % n != 0).then_some(rows - 1))
        {
            let row = k as f64 + across;
            if twist != 0.0 {
                self.sheet.column_taps(
                    middle + twist * k as f64 - along,
                    step * n as f64,
                    coarse,
                    &mut self.taps,
                );
            }
            self.sheet
                .blend_line(frame, row, &self.taps, &mut self.directions[..coarse]);
            let mut p = edge(k);
            self.positions[k * columns] = p;
            let out = &mut self.positions[k * columns + 1..(k + 1) * columns];
            for (c, d) in self.directions[..coarse].iter().enumerate() {
                let first = c * n;
                let len = n.min(segments - first);
                let mid = first + len / 2;
                let (keep, down) = (self.keep[mid], self.droop[mid]);
                let d = (Vec2::X + (*d - Vec2::X) * keep).normalize_or(Vec2::X);
                let v = match self.attachment {
                    ClothAttachment::Pole => Vec3::new(d.x * down.x, -d.x * down.y, d.y) * segment,
                    ClothAttachment::Rod => {
                        // Down the curtain, leaning downwind.
                        let (a, b) = (
                            d.x * lean_cos - d.y * lean_sin,
                            d.x * lean_sin + d.y * lean_cos,
                        );
                        Vec3::new(0.0, -a, b) * segment
                    }
                };
                if len == 1 {
                    p += v;
                    out[first] = p;
                } else {
                    for (i, node) in out[first..first + len].iter_mut().enumerate() {
                        *node = p + v * (i + 1) as f32;
                    }
                    p += v * len as f32;
                }
            }
        }
        // Yarns between: interpolated, moved onto their own pole-edge node.
        if n > 1 {
            for k in (0..rows).filter(|k| k % n != 0 && *k != rows - 1) {
                let (k0, k1) = (k / n * n, (k / n * n + n).min(rows - 1));
                let t = (k - k0) as f32 / (k1 - k0) as f32;
                let shift = edge(k) - edge(k0).lerp(edge(k1), t);
                for j in 0..columns {
                    let (a, b) = (
                        self.positions[k0 * columns + j],
                        self.positions[k1 * columns + j],
                    );
                    self.positions[k * columns + j] = a.lerp(b, t) + shift;
                }
            }
        }
        let max_distance = spacing * self.params.max_stretch;
        let leading = self.params.leading.index(rows);
        align_to_leading_yarn(&mut self.positions, rows, columns, leading, max_distance);
    }
}

/// Limits and constants of [`ClothSim`].
impl ClothSim {
    /// Most noise cells a cloth may have (frames × max(rows, 16) × 160): 4 M cells, 48 MiB.
    pub const MAX_NOISE_CELLS: usize = 1 << 22;

    /// The paper's frame rate: Table 1's shifts are steps per frame at 50 fps.
    pub const PAPER_FPS: f32 = 50.0;
}

/// The one conversion between the paper's noise shift (steps per paper frame, as
/// [`ClothParams::wind_steps_per_frame`]) and the wind's speed (m/s).
impl ClothSim {
    /// The wind speed, m/s, at which noise shifting `steps` cells per paper frame along yarns
    /// `length` m long runs at the wind's own speed: waves on flags travel at about the speed of
    /// the flow (Alben's simulations of light flags; Raynaud & Mulleners 2026 in a wind tunnel).
    /// For a 1.5 m flag this is Table 1's pairing: |v| = 2 in a gentle breeze (4.7 m/s), 4 in a
    /// moderate one. The inverse of [`Self::steps_for_speed`].
    pub fn speed_of_steps(steps: f32, length: f32) -> f32 {
        steps * Self::PAPER_FPS * length / CELLS_PER_YARN as f32
    }

    /// The shift |v|, cells per paper frame, of noise that moves at `speed` m/s along yarns
    /// `length` m long: the cloth's waves then run at the wind's speed (0 for a degenerate
    /// length).
    pub fn steps_for_speed(speed: f32, length: f32) -> f32 {
        let steps = speed * CELLS_PER_YARN as f32 / (Self::PAPER_FPS * length.max(1e-6));
        if steps.is_finite() { steps } else { 0.0 }
    }
}
