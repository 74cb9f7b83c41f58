//! The yarn directions of every line of the noise, through the P-type descriptor (cloth paper
//! §3.2, §4).
//!
//! **Our reading of §3–4.** §4.2 applies "every line of the noise array to an entry of the P
//! descriptor": the descriptor runs over the whole noise line, and a yarn is the stretch of it
//! between the pole and the free edge. So the harmonics of Table 1's band-pass are counted over
//! the noise line, which is [`LINE_YARNS`] yarn lengths long (the paper's 256-wide matrix holds a
//! few of its flags): a band [3, 5] keeps waves of 1 to 1.7 yarn lengths, the waves real flags
//! carry (about 1.9 lengths, Raynaud & Mulleners 2026), and wrinkles come with the higher
//! bands. The band limits the noise's own spectrum S(k) of §3.1 (the paper names both spectra
//! S(k)) and the descriptor's S(k) of eq. 5 alike: the angles θ(j) are band-limited before ω =
//! exp(iθ) and scaled so the sheet spans [−θ, θ] (θ is three standard deviations, and a clamp);
//! the descriptor keeps the same band of ω and
//! its mean, which drops the harmonics exp(iθ) adds and smooths the curve. The mean direction
//! (k = 0) of a periodic line does not change when the line shifts, so it cannot swing the yarn;
//! each line is turned so its mean points along the stream.
//!
//! **Done once.** The DFT of a periodic line commutes with shifting it, so every frame's yarn is
//! a shifted read of these precomputed lines: the paper's per-frame descriptor, computed once per
//! line when the cloth is built.

use std::sync::Arc;

use bevy::math::Vec2;
use rustfft::{Fft, FftPlanner, num_complex::Complex};

use super::descriptor::HarmonicFilter;
use super::noise::NoiseSheet;

/// A noise line is this many yarn lengths long.
pub const LINE_YARNS: usize = 5;
/// Noise cells per yarn length: Table 1's shifts |v| are cells per paper frame.
pub const CELLS_PER_YARN: usize = 32;

/// The weight of harmonic k of the angles: (k / k₂)², at most 1, where k₂ = [`LINE_YARNS`] / 2
/// is the harmonic two yarn lengths long.
///
/// A wave longer than two yarns does not bend the yarn it passes: it turns the whole yarn about
/// the pole, one way and then the other, and a flag swung so is a board, not cloth. Real flags
/// carry waves of about 1.9 lengths and are held toward the wind by its drag. Table 1's bands
/// that start at 1 (the flapping evolving banner, the fluttering evolving curtain) put most
/// of a 1/f^β spectrum's energy in those tilts: the banner's free edge swung by 0.31–0.42 L,
/// where every other row swings by at most 0.25 L. Weighted so, the band keeps its harmonics
/// (a wave of 5 yarns keeps 16 % of its amplitude, one of 2.5 yarns 64 %) and step 2 rescales
/// the sheet to the row's θ, which moves the spread into the waves that bend the cloth.
fn tilt_weight(k: usize) -> f32 {
    let two_yarns = LINE_YARNS as f32 / 2.0;
    (k as f32 / two_yarns).min(1.0).powi(2)
}

/// Unit segment directions for every (frame, row, column) of a noise sheet, in the yarn plane:
/// x along the stream, y across it.
#[derive(Clone, Debug)]
pub struct DirectionSheet {
    frames: usize,
    rows: usize,
    columns: usize,
    directions: Vec<Vec2>,
}

/// Forward and inverse transforms of one line length.
struct LineTransforms {
    forward: Arc<dyn Fft<f32>>,
    inverse: Arc<dyn Fft<f32>>,
    buffer: Vec<Complex<f32>>,
    scratch: Vec<Complex<f32>>,
}

impl LineTransforms {
    fn new(n: usize) -> Self {
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let scratch = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        Self {
            forward,
            inverse,
            buffer: vec![Complex::new(0.0, 0.0); n],
            scratch: vec![Complex::new(0.0, 0.0); scratch],
        }
    }

    /// Transforms `buffer`, scales harmonic k by `weight(k)` (k and n − k together; 0 drops
    /// it), and transforms back (scaled by n).
    fn filter(&mut self, weight: impl Fn(usize) -> f32) {
        let n = self.buffer.len();
        self.forward
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
        for (k, s) in self.buffer.iter_mut().enumerate() {
            *s *= weight(k.min(n - k));
        }
        self.inverse
            .process_with_scratch(&mut self.buffer, &mut self.scratch);
    }
}

impl DirectionSheet {
    /// Runs every line of `noise` through the pipeline of the module docs with the angle
    /// amplitude `amplitude` (θ, rad) and the band `filter`.
    pub fn new(noise: &NoiseSheet, amplitude: f32, filter: HarmonicFilter) -> Self {
        let (frames, rows, columns) = noise.size();
        let lines = frames * rows;
        let mut transforms = LineTransforms::new(columns);
        let band = |k: usize| k > 0 && filter.keeps(k, columns);
        // 1. Band-limit the angles along each line (the noise's S(k), §3.1), the waves longer
        //    than two yarns weighted down (`tilt_weight`).
        let weight = |k: usize| if band(k) { tilt_weight(k) } else { 0.0 };
        let mut angles = vec![0.0f32; lines * columns];
        for (line, out) in angles.chunks_exact_mut(columns).enumerate() {
            for (b, v) in transforms.buffer.iter_mut().zip(noise.line(line)) {
                *b = Complex::new(*v, 0.0);
            }
            transforms.filter(weight);
            for (o, b) in out.iter_mut().zip(&transforms.buffer) {
                *o = b.re;
            }
        }
        // 2. Scale the sheet to span [−θ, θ]: three standard deviations to θ (clamped there), so
        //    the spread does not depend on how many cells the sheet has (a peak would).
        let n = angles.len().max(1) as f64;
        let rms = (angles.iter().map(|a| f64::from(*a).powi(2)).sum::<f64>() / n).sqrt() as f32;
        let scale = if rms > 0.0 && rms.is_finite() {
            amplitude / (3.0 * rms)
        } else {
            0.0
        };
        // 3. The descriptor of each line (eq. 4–6): ω = exp(iθ), its mean and band, turned so
        //    the mean points along the stream, normalised.
        let mut directions = vec![Vec2::X; lines * columns];
        for (out, line) in directions
            .chunks_exact_mut(columns)
            .zip(angles.chunks_exact(columns))
        {
            for (b, a) in transforms.buffer.iter_mut().zip(line) {
                let (sin, cos) = (a * scale).clamp(-amplitude, amplitude).sin_cos();
                *b = Complex::new(cos, sin);
            }
            transforms.filter(|k| if k == 0 || band(k) { 1.0 } else { 0.0 });
            let mean: Complex<f32> = transforms.buffer.iter().sum();
            let turn = if mean.norm() > 1e-12 {
                mean.conj() / mean.norm()
            } else {
                Complex::new(1.0, 0.0)
            };
            let mut previous = Vec2::X;
            for (o, b) in out.iter_mut().zip(&transforms.buffer) {
                let w = b * turn;
                let v = Vec2::new(w.re, w.im);
                let length = v.length();
                *o = if length > 1e-9 && length.is_finite() {
                    v / length
                } else {
                    previous
                };
                previous = *o;
            }
        }
        Self {
            frames,
            rows,
            columns,
            directions,
        }
    }

    /// (frames, rows, columns).
    pub fn size(&self) -> (usize, usize, usize) {
        (self.frames, self.rows, self.columns)
    }

    /// The columns a line read from `first` in steps of `step` falls between, `count` of them:
    /// (left column, right column, weight of the right one). Yarns read with the same offsets
    /// share them.
    pub fn column_taps(&self, first: f64, step: f64, count: usize, taps: &mut Vec<ColumnTap>) {
        let columns = self.columns;
        let len = columns as f64;
        let step = if step.is_finite() { step } else { 1.0 };
        let mut c = {
            let c = first - (first / len).floor() * len;
            if c.is_finite() {
                c.clamp(0.0, len)
            } else {
                0.0
            }
        };
        taps.clear();
        taps.extend((0..count).map(|_| {
            let i0 = (c as usize).min(columns - 1);
            let i1 = if i0 + 1 == columns { 0 } else { i0 + 1 };
            let tap = ColumnTap {
                left: i0 as u32,
                right: i1 as u32,
                weight: (c - i0 as f64) as f32,
            };
            c += step;
            if c >= len {
                c -= len;
            }
            tap
        }));
    }

    /// Fills `out[j]` with the direction at (frame, row, column tap j), interpolated linearly
    /// on every axis but not normalised (its length is a little under 1 between nodes).
    pub fn blend_line(&self, frame: f64, row: f64, taps: &[ColumnTap], out: &mut [Vec2]) {
        let split = |x: f64, n: usize| -> (usize, usize, f32) {
            let len = n as f64;
            let c = x - (x / len).floor() * len;
            let c = if c.is_finite() {
                c.clamp(0.0, len)
            } else {
                0.0
            };
            let i = (c as usize).min(n - 1);
            (i, (i + 1) % n, (c - i as f64).clamp(0.0, 1.0) as f32)
        };
        let (r0, r1, tr) = split(row, self.rows);
        let columns = self.columns;
        let line =
            |f: usize, r: usize| &self.directions[(f * self.rows + r) * columns..][..columns];
        let lerp = |l: &[Vec2], tap: &ColumnTap| {
            let (a, b) = (l[tap.left as usize], l[tap.right as usize]);
            a + (b - a) * tap.weight
        };
        if self.frames > 1 {
            let (f0, f1, tf) = split(frame, self.frames);
            let (a, b, c, d) = (line(f0, r0), line(f0, r1), line(f1, r0), line(f1, r1));
            let w = [
                (1.0 - tf) * (1.0 - tr),
                (1.0 - tf) * tr,
                tf * (1.0 - tr),
                tf * tr,
            ];
            for (o, tap) in out.iter_mut().zip(taps) {
                *o = lerp(a, tap) * w[0]
                    + lerp(b, tap) * w[1]
                    + lerp(c, tap) * w[2]
                    + lerp(d, tap) * w[3];
            }
        } else {
            let (a, b) = (line(0, r0), line(0, r1));
            for (o, tap) in out.iter_mut().zip(taps) {
                *o = lerp(a, tap) * (1.0 - tr) + lerp(b, tap) * tr;
            }
        }
    }
}

/// Two columns of a noise line and the weight of the second: where a node reads the line.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ColumnTap {
    /// The column to the node's left.
    pub left: u32,
    /// The column to its right (wrapping).
    pub right: u32,
    /// The right one's weight, in [0, 1).
    pub weight: f32,
}
