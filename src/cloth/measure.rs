//! What a viewer sees of a flapping flag, measured over time: how far the free edge swings, how
//! much the cloth bends, and how fast it flaps. For any cloth laid out like
//! [`ClothSim`](super::sim::ClothSim) on a pole (yarns from the pole along +X, flapping along Z,
//! row-major), procedural or physical.

use bevy::math::Vec3;
use rustfft::{FftPlanner, num_complex::Complex};

/// Flapping statistics, lengths as fractions of the yarn length L.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlapStats {
    /// Free-edge swing: the time standard deviation of each yarn's free-edge offset along Z
    /// (out of plane), root-mean-square over the yarns, over L.
    pub swing: f32,
    /// Bend: the root-mean-square distance of every node from the straight line between its
    /// yarn's pole node and free-edge node, over all nodes and times, over L.
    pub bend: f32,
    /// Peak-to-peak trailing-edge amplitude A over L: 2√2 times the middle yarn's free-edge
    /// standard deviation (the peak-to-peak of a sine of that spread).
    pub amplitude: f32,
    /// The dominant flapping frequency of the middle yarn's free edge, Hz (the highest peak of
    /// its spectrum, DC excluded).
    pub frequency: f32,
    /// How fast waves run down the middle yarn, m/s: the phase speed 2π f / (dφ/ds) at the
    /// flapping frequency f, with φ(s) the phase of each node's motion at f (unwrapped node by
    /// node, nodes being much closer than a wavelength) fitted by a line over the outer two
    /// thirds of the yarn. Infinite when the phase does not change along the yarn (it swings
    /// as a whole); negative if waves ran toward the pole.
    pub wave_speed: f32,
}

impl FlapStats {
    /// The Strouhal number f A / U in wind of `speed` m/s on a yarn of `length` m (A
    /// peak-to-peak, as for flags and swimmers).
    pub fn strouhal(&self, length: f32, speed: f32) -> f32 {
        self.frequency * self.amplitude * length / speed
    }
}

/// Collects frames of node positions at a fixed interval and reduces them to [`FlapStats`].
#[derive(Clone, Debug)]
pub struct FlapRecorder {
    rows: usize,
    columns: usize,
    length: f32,
    dt: f32,
    /// Free-edge Z of every row at every frame.
    tips: Vec<Vec<f32>>,
    /// Z of every node of the middle yarn at every frame, node by node.
    yarn: Vec<Vec<f32>>,
    bend_squares: f64,
    bend_count: u64,
}

impl FlapRecorder {
    /// For a `rows × columns` grid with yarns `length` m long, frames `dt` s apart.
    pub fn new(rows: usize, columns: usize, length: f32, dt: f32) -> Self {
        Self {
            rows,
            columns,
            length,
            dt,
            tips: vec![Vec::new(); rows],
            yarn: vec![Vec::new(); columns],
            bend_squares: 0.0,
            bend_count: 0,
        }
    }

    /// Adds one frame (row-major positions, yarn by yarn from the pole).
    pub fn record(&mut self, positions: &[Vec3]) {
        let c = self.columns;
        for (k, tips) in self.tips.iter_mut().enumerate() {
            let yarn = &positions[k * c..(k + 1) * c];
            let (a, b) = (yarn[0], yarn[c - 1]);
            let chord = (b - a).normalize_or_zero();
            for p in yarn {
                let v = *p - a;
                let off = v - chord * v.dot(chord);
                self.bend_squares += f64::from(off.length_squared());
                self.bend_count += 1;
            }
            tips.push(b.z);
        }
        let middle = self.rows / 2 * c;
        for (j, z) in self.yarn.iter_mut().enumerate() {
            if let Some(p) = positions.get(middle + j) {
                z.push(p.z);
            }
        }
    }

    /// The statistics of the frames so far.
    pub fn finish(&self) -> FlapStats {
        let spread = |x: &[f32]| {
            let n = x.len().max(1) as f64;
            let m = x.iter().map(|v| f64::from(*v)).sum::<f64>() / n;
            (x.iter().map(|v| (f64::from(*v) - m).powi(2)).sum::<f64>() / n).sqrt()
        };
        let swing = (self.tips.iter().map(|t| spread(t).powi(2)).sum::<f64>()
            / self.rows.max(1) as f64)
            .sqrt();
        let middle = &self.tips[self.rows / 2];
        let bend = (self.bend_squares / self.bend_count.max(1) as f64).sqrt();
        let l = f64::from(self.length);
        let frequency = dominant_frequency(middle, self.dt);
        let wave_speed = self.wave_speed(frequency);
        FlapStats {
            swing: (swing / l) as f32,
            bend: (bend / l) as f32,
            amplitude: (2.0 * std::f64::consts::SQRT_2 * spread(middle) / l) as f32,
            frequency,
            wave_speed,
        }
    }
}

impl FlapRecorder {
    /// [`FlapStats::wave_speed`] at `frequency` Hz.
    fn wave_speed(&self, frequency: f32) -> f32 {
        let c = self.yarn.len();
        if c < 3 || !(frequency.is_finite() && frequency > 0.0) {
            return f32::INFINITY;
        }
        let ds = f64::from(self.length) / (c - 1) as f64;
        let mut unwrapped: Vec<f64> = Vec::with_capacity(c);
        for z in &self.yarn {
            let phase = phase_at(z, frequency, self.dt);
            let phase = match unwrapped.last() {
                Some(&previous) => {
                    let step = (phase - previous + std::f64::consts::PI)
                        .rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI;
                    previous + step
                }
                None => phase,
            };
            unwrapped.push(phase);
        }
        // The outer two thirds: a line through (s, −φ) by least squares.
        let points: Vec<(f64, f64)> = (c / 3..c).map(|j| (j as f64 * ds, -unwrapped[j])).collect();
        let n = points.len() as f64;
        let (sx, sy) = points
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p.0, b + p.1));
        let (mx, my) = (sx / n, sy / n);
        let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), p| {
            (a + (p.0 - mx) * (p.1 - my), b + (p.0 - mx) * (p.0 - mx))
        });
        let slope = sxy / sxx;
        if slope.abs() < 1e-9 || !slope.is_finite() {
            return f32::INFINITY;
        }
        (std::f64::consts::TAU * f64::from(frequency) / slope) as f32
    }
}

/// The phase (rad) of `x`, sampled every `dt` s, at `frequency` Hz: the angle of its
/// Hann-windowed Fourier sum there, mean removed.
fn phase_at(x: &[f32], frequency: f32, dt: f32) -> f64 {
    let n = x.len();
    if n < 2 {
        return 0.0;
    }
    let mean = x.iter().map(|v| f64::from(*v)).sum::<f64>() / n as f64;
    let (mut re, mut im) = (0.0f64, 0.0f64);
    for (i, v) in x.iter().enumerate() {
        let w = 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / (n - 1) as f64).cos();
        let angle = std::f64::consts::TAU * f64::from(frequency) * f64::from(dt) * i as f64;
        let y = (f64::from(*v) - mean) * w;
        re += y * angle.cos();
        im -= y * angle.sin();
    }
    im.atan2(re)
}

/// The frequency (Hz) of the highest peak of the spectrum of `x` sampled every `dt` s, DC
/// excluded (Hann window, a parabola through the peak's neighbours).
fn dominant_frequency(x: &[f32], dt: f32) -> f32 {
    let n = x.len();
    if n < 8 {
        return 0.0;
    }
    let mean = x.iter().sum::<f32>() / n as f32;
    let mut buffer: Vec<Complex<f32>> = x
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let w = 0.5 - 0.5 * (std::f32::consts::TAU * i as f32 / (n - 1) as f32).cos();
            Complex::new((v - mean) * w, 0.0)
        })
        .collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buffer);
    let power: Vec<f32> = buffer[..n / 2].iter().map(|c| c.norm_sqr()).collect();
    let Some((peak, _)) = power
        .iter()
        .enumerate()
        .skip(1)
        .max_by(|a, b| a.1.total_cmp(b.1))
    else {
        return 0.0;
    };
    let shift = if peak + 1 < power.len() {
        let (a, b, c) = (power[peak - 1], power[peak], power[peak + 1]);
        let d = a - 2.0 * b + c;
        if d.abs() > 0.0 {
            0.5 * (a - c) / d
        } else {
            0.0
        }
    } else {
        0.0
    };
    (peak as f32 + shift) / (n as f32 * dt)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_tip_gives_its_frequency_amplitude_and_no_bend() {
        // A rigid yarn whose free edge moves as 0.1 sin(2π 1.5 t): f = 1.5 Hz, A = 0.2.
        let (rows, columns, dt) = (3, 5, 0.02);
        let mut recorder = FlapRecorder::new(rows, columns, 1.0, dt);
        for i in 0..1000 {
            let z = 0.1 * (std::f32::consts::TAU * 1.5 * i as f32 * dt).sin();
            let frame: Vec<Vec3> = (0..rows * columns)
                .map(|n| {
                    let s = (n % columns) as f32 / (columns - 1) as f32;
                    Vec3::new(s, -((n / columns) as f32), z * s)
                })
                .collect();
            recorder.record(&frame);
        }
        let stats = recorder.finish();
        assert!((stats.frequency - 1.5).abs() < 0.02, "{stats:?}");
        assert!((stats.amplitude - 0.2).abs() < 0.005, "{stats:?}");
        assert!(stats.bend < 1e-6, "{stats:?}");
        // The yarn swings as a whole: no travelling wave.
        assert_eq!(stats.wave_speed, f32::INFINITY, "{stats:?}");
    }

    #[test]
    fn a_travelling_wave_gives_its_speed() {
        // z = 0.1 s sin(2π (1.5 t − s / 0.8)) on a yarn 1.2 m long: waves at 1.5 × 0.8 × 1.2
        // = 1.44 m/s from the pole to the free edge.
        let (rows, columns, dt, length) = (3, 13, 0.01, 1.2);
        let mut recorder = FlapRecorder::new(rows, columns, length, dt);
        for i in 0..2000 {
            let t = i as f32 * dt;
            let frame: Vec<Vec3> = (0..rows * columns)
                .map(|n| {
                    let s = (n % columns) as f32 / (columns - 1) as f32;
                    let z = 0.1 * s * (std::f32::consts::TAU * (1.5 * t - s / 0.8)).sin();
                    Vec3::new(s * length, -((n / columns) as f32), z)
                })
                .collect();
            recorder.record(&frame);
        }
        let stats = recorder.finish();
        assert!((stats.frequency - 1.5).abs() < 0.02, "{stats:?}");
        assert!((stats.wave_speed - 1.44).abs() < 0.05, "{stats:?}");
    }
}
