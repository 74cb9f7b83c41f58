//! The P-type Fourier descriptor of an open polyline (cloth paper §3.2, eq. 2–6).
//!
//! A yarn is a polyline of `n` equal segments of length δ (eq. 2). Its shape is the direction of
//! each segment, the total curvature θ(j) (eq. 3), the running sum of the bend angles α(j). The
//! descriptor is `ω(j) = exp(iθ(j))` (eq. 4); its DFT `S(k)` (eq. 5) can be filtered and
//! transformed back (eq. 6). After filtering, `ω(j)` is no longer of unit length: we keep its
//! direction, so every segment keeps length δ and the yarn its length `n δ`.
//!
//! The yarn's geometry is here for those who build yarns by hand: [`yarn_from_angles`] and
//! [`trace_yarn`].

use std::sync::Arc;

use bevy::math::Vec2;
use rustfft::{Fft, FftPlanner, num_complex::Complex};

/// Points of a yarn whose segment `j` points in direction `angles[j]` (θ(j), radians from +X):
/// `n` angles give `n + 1` points, the first at the origin, each segment `segment` long.
/// A non-finite angle is read as 0.
pub fn yarn_from_angles(angles: &[f32], segment: f32) -> Vec<Vec2> {
    let mut points = Vec::with_capacity(angles.len() + 1);
    let mut p = Vec2::ZERO;
    points.push(p);
    for &theta in angles {
        let theta = if theta.is_finite() { theta } else { 0.0 };
        p += Vec2::from_angle(theta) * segment;
        points.push(p);
    }
    points
}

/// Which harmonics of the descriptor survive. The mean direction (k = 0) always does; a harmonic
/// `k` and its mirror `n − k` are kept or dropped together, so a straight yarn stays straight.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, bevy::reflect::Reflect)]
pub enum HarmonicFilter {
    /// Keep every harmonic: the yarn follows the angles exactly.
    #[default]
    All,
    /// Keep harmonics `1..=max` (the paper's LPF).
    LowPass {
        /// Highest harmonic kept.
        max: usize,
    },
    /// Keep harmonics `min..=max` (the paper's BPF, Table 1: e.g. [3, 7]).
    BandPass {
        /// Lowest harmonic kept (besides the mean).
        min: usize,
        /// Highest harmonic kept.
        max: usize,
    },
}

impl HarmonicFilter {
    /// Whether harmonic index `k` of an `n`-point transform passes.
    pub fn keeps(self, k: usize, n: usize) -> bool {
        let k = k.min(n - k);
        k == 0
            || match self {
                Self::All => true,
                Self::LowPass { max } => k <= max,
                Self::BandPass { min, max } => (min..=max).contains(&k),
            }
    }
}

/// Planned transforms for yarns of one segment count: turns angles θ(j) into unit segment
/// directions through eq. 4–6 and a [`HarmonicFilter`], without allocating per call.
pub struct DescriptorFilter {
    forward: Arc<dyn Fft<f32>>,
    inverse: Arc<dyn Fft<f32>>,
    omega: Vec<Complex<f32>>,
    scratch: Vec<Complex<f32>>,
    filter: HarmonicFilter,
}

impl DescriptorFilter {
    /// Transforms for `segments` segments (≥ 1).
    pub fn new(segments: usize, filter: HarmonicFilter) -> Self {
        let n = segments.max(1);
        let mut planner = FftPlanner::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let scratch_len = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        Self {
            forward,
            inverse,
            omega: vec![Complex::new(0.0, 0.0); n],
            scratch: vec![Complex::new(0.0, 0.0); scratch_len],
            filter,
        }
    }

    /// The filter in use.
    pub fn filter(&self) -> HarmonicFilter {
        self.filter
    }

    /// Writes the unit direction of each segment into `directions` (same length as `angles`).
    /// With [`HarmonicFilter::All`] these are exactly `(cos θ, sin θ)`. Where filtering leaves a
    /// zero descriptor, the previous segment's direction (or +X) is kept.
    pub fn directions(&mut self, angles: &[f32], directions: &mut [Vec2]) {
        let n = self.omega.len();
        debug_assert_eq!(angles.len(), n);
        for (w, &theta) in self.omega.iter_mut().zip(angles) {
            let theta = if theta.is_finite() { theta } else { 0.0 };
            let (sin, cos) = theta.sin_cos();
            *w = Complex::new(cos, sin); // eq. 4
        }
        if self.filter != HarmonicFilter::All {
            self.forward
                .process_with_scratch(&mut self.omega, &mut self.scratch); // eq. 5 (× n)
            for (k, s) in self.omega.iter_mut().enumerate() {
                if !self.filter.keeps(k, n) {
                    *s = Complex::new(0.0, 0.0);
                }
            }
            self.inverse
                .process_with_scratch(&mut self.omega, &mut self.scratch); // eq. 6 (× n)
        }
        let mut previous = Vec2::X;
        for (d, w) in directions.iter_mut().zip(&self.omega) {
            let v = Vec2::new(w.re, w.im);
            let length = v.length();
            *d = if length > 1e-12 && length.is_finite() {
                v / length
            } else {
                previous
            };
            previous = *d;
        }
    }
}

/// Places a yarn from `start` along unit `directions`, each segment `segment` long.
pub fn trace_yarn(start: Vec2, directions: &[Vec2], segment: f32, points: &mut [Vec2]) {
    let mut p = start;
    points[0] = p;
    for (point, &d) in points[1..].iter_mut().zip(directions) {
        p += d * segment;
        *point = p;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contract_example() {
        let pts = yarn_from_angles(&[0.0, std::f32::consts::FRAC_PI_2], 2.0);
        assert_eq!(pts.len(), 3);
        assert_eq!(pts[0], Vec2::ZERO);
        assert!((pts[1] - Vec2::new(2.0, 0.0)).length() < 1e-6);
        assert!((pts[2] - Vec2::new(2.0, 2.0)).length() < 1e-6);
    }

    #[test]
    fn low_pass_of_a_smooth_curve_is_close_and_of_a_straight_line_exact() {
        let n = 32;
        let smooth: Vec<f32> = (0..n)
            .map(|j| 0.5 * (std::f32::consts::TAU * j as f32 / n as f32).sin())
            .collect();
        let mut filter = DescriptorFilter::new(n, HarmonicFilter::LowPass { max: 4 });
        let mut dirs = vec![Vec2::ZERO; n];
        filter.directions(&smooth, &mut dirs);
        for (d, &theta) in dirs.iter().zip(&smooth) {
            assert!(
                (d.to_angle() - theta).abs() < 0.05,
                "{} vs {theta}",
                d.to_angle()
            );
        }
        let straight = vec![0.25; n];
        let mut filter = DescriptorFilter::new(n, HarmonicFilter::BandPass { min: 3, max: 7 });
        filter.directions(&straight, &mut dirs);
        for d in &dirs {
            assert!((d.to_angle() - 0.25).abs() < 1e-5);
        }
    }
}
