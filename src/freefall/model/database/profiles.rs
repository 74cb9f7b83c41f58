//! The profiles of a database segment: the Tanabe–Kaneko ODE run over a swing (flutter) or a
//! turn (tumble), resampled at [`SEGMENT_SAMPLES`](super::SEGMENT_SAMPLES) points, and the eq. 5
//! segment they give.

use bevy::math::Vec2;

use super::super::ode::{Integrator, OdeState, TanabeKaneko, trajectory};
use super::{SEGMENT_SAMPLES, Segment};

/// Eq. 5 in the fall's units between the turning points π/2 and 3π/2, with an angle profile.
pub(super) fn harmonic_segment(
    alpha: f32,
    gamma: f32,
    flutter: &[f32; SEGMENT_SAMPLES],
) -> Segment {
    let at = |tau: f32| {
        Vec2::new(
            -alpha * libm::sinf(tau),
            -tau - 0.5 * gamma * libm::cosf(2.0 * tau),
        )
    };
    let start = at(std::f32::consts::FRAC_PI_2);
    let points = std::array::from_fn(|i| {
        let s = i as f32 / (SEGMENT_SAMPLES - 1) as f32;
        at(std::f32::consts::FRAC_PI_2 + std::f32::consts::PI * s) - start
    });
    let (first, last) = (flutter[0], flutter[SEGMENT_SAMPLES - 1]);
    Segment {
        alpha,
        gamma,
        points,
        angle_range: 0.5 * (last - first).abs(),
        angle_shape: progress(flutter),
    }
}

/// A profile's progress from its first to its last value, 0 → 1, made monotone (a running
/// maximum) so a swing never turns back within itself.
fn progress(profile: &[f32; SEGMENT_SAMPLES]) -> [f32; SEGMENT_SAMPLES] {
    let (first, last) = (profile[0], profile[SEGMENT_SAMPLES - 1]);
    let span = last - first;
    let mut running = 0.0f32;
    std::array::from_fn(|i| {
        let s = if span.abs() > 1e-9 {
            ((profile[i] - first) / span).clamp(0.0, 1.0)
        } else {
            i as f32 / (SEGMENT_SAMPLES - 1) as f32
        };
        running = running.max(s);
        if i == SEGMENT_SAMPLES - 1 {
            1.0
        } else {
            running
        }
    })
}

/// The last complete half-swing (between sign changes of u) of a fluttering run of eq. 4,
/// resampled to [`SEGMENT_SAMPLES`] equal times, signed so the swing goes right. `None` if the
/// run does not flutter.
pub(super) fn flutter_profile(params: &TanabeKaneko) -> Option<[f32; SEGMENT_SAMPLES]> {
    let start = OdeState {
        theta: 0.3,
        v: -0.01,
        ..OdeState::default()
    };
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4)
        .expect("12 s in 1 ms steps is within the budget");
    let turns: Vec<usize> = (1..run.len())
        .filter(|&i| (run[i - 1].u < 0.0) != (run[i].u < 0.0))
        .collect();
    let (&a, &b) = (
        turns.get(turns.len().checked_sub(3)?)?,
        turns.get(turns.len() - 2)?,
    );
    let swing = &run[a..=b];
    if swing.iter().any(|s| !s.is_finite()) || swing.len() < 4 {
        return None;
    }
    let sign = if swing[swing.len() / 2].u >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let profile = resample(swing, |s| (sign * s.theta) as f32);
    // A swing to the right turns the plate counter-clockwise (as a right tumble does).
    if profile[SEGMENT_SAMPLES - 1] - profile[0] > 0.05 {
        Some(profile)
    } else if profile[0] - profile[SEGMENT_SAMPLES - 1] > 0.05 {
        Some(profile.map(|a| -a))
    } else {
        None
    }
}

/// One half-turn of a tumbling run of eq. 4 (θ advancing by π), as progress 0 → 1, resampled to
/// equal times. Falls back to a uniform turn if the run does not tumble.
pub(super) fn tumble_profile(params: &TanabeKaneko) -> [f32; SEGMENT_SAMPLES] {
    let uniform = std::array::from_fn(|i| i as f32 / (SEGMENT_SAMPLES - 1) as f32);
    let start = OdeState {
        theta: 0.3,
        v: -0.01,
        ..OdeState::default()
    };
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4)
        .expect("12 s in 1 ms steps is within the budget");
    let Some(last) = run.last() else {
        return uniform;
    };
    let direction = last.theta.signum();
    let half_turn = |s: &OdeState| (direction * s.theta / std::f64::consts::PI).floor();
    let marks: Vec<usize> = (1..run.len())
        .filter(|&i| half_turn(&run[i]) != half_turn(&run[i - 1]))
        .collect();
    if marks.len() < 4 || !last.is_finite() {
        return uniform;
    }
    let swing = &run[marks[marks.len() - 3]..=marks[marks.len() - 2]];
    let theta0 = swing[0].theta;
    progress(&resample(swing, |s| {
        (direction * (s.theta - theta0)) as f32
    }))
}

fn resample(run: &[OdeState], value: impl Fn(&OdeState) -> f32) -> [f32; SEGMENT_SAMPLES] {
    std::array::from_fn(|i| {
        let x = i as f32 / (SEGMENT_SAMPLES - 1) as f32 * (run.len() - 1) as f32;
        let j = (x as usize).min(run.len() - 2);
        let f = x - j as f32;
        value(&run[j]) * (1.0 - f) + value(&run[j + 1]) * f
    })
}
