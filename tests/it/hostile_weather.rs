//! Hostile input, third round, on the weather: an easing of any time constant arrives at 60 Hz
//! (a step too small for an f32 speed is not lost), a snapshot refuses the easings `ease_to`
//! refuses, and a snapshot taken mid-easing resumes it to the bit.

use bevy::math::Vec2;
use bevy_windfall::wind::{WindConfig, WindField};

const HZ_60: f32 = 1.0 / 60.0;

fn field(speed: f32) -> WindField {
    WindField::new(WindConfig {
        reference_speed: speed,
        grid: [16, 16],
        ..WindConfig::default()
    })
    .unwrap()
}

/// The fraction of the way from 2 to 12 m/s the speed has come.
fn progress(field: &WindField) -> f64 {
    (f64::from(field.config().reference_speed) - 2.0) / 10.0
}

#[test]
fn an_easing_of_any_time_constant_arrives_at_60_hz() {
    // τ = 60 s: after 30 τ it has arrived, exactly, and stopped easing.
    let mut slow = field(2.0);
    slow.ease_to(12.0, Vec2::new(0.0, 1.0), 60.0).unwrap();
    for _ in 0..(30 * 60 * 60) {
        slow.advance(HZ_60);
    }
    assert_eq!(slow.config().reference_speed, 12.0);
    assert_eq!(slow.config().direction, Vec2::new(0.0, 1.0));
    assert_eq!(slow.easing(), None);
    // A day and a week: after one day, 1 − e^(−t/τ) of the way, as the lag says (a stalled
    // easing stays at 0 or falls short).
    for tau in [86_400.0f32, 604_800.0] {
        let mut weather = field(2.0);
        weather.ease_to(12.0, Vec2::X, tau).unwrap();
        let steps = 86_400 * 60;
        for _ in 0..steps {
            weather.advance(HZ_60);
        }
        let elapsed = f64::from(steps) * f64::from(HZ_60);
        let expected = 1.0 - (-elapsed / f64::from(tau)).exp();
        let got = progress(&weather);
        assert!(
            (got - expected).abs() < 1e-3,
            "τ = {tau} s: {got:.5} of the way after a day, expected {expected:.5}"
        );
    }
}

#[test]
fn a_snapshot_refuses_the_easings_ease_to_refuses() {
    let mut server = field(5.0);
    server.ease_to(9.0, Vec2::Y, 3.0).unwrap();
    server.advance(0.5);
    for tau in [f32::NAN, -3.0, -0.5, f32::NEG_INFINITY, f32::INFINITY] {
        let mut snapshot = server.snapshot();
        snapshot.easing.as_mut().unwrap().time_constant = tau;
        let refused = WindField::from_snapshot(&snapshot).unwrap_err();
        assert_eq!(refused.field(), "time_constant", "τ = {tau}");
        assert!(server.ease_to(9.0, Vec2::Y, tau).is_err());
    }
    // The target is checked as ease_to checks it.
    let mut snapshot = server.snapshot();
    snapshot.easing.as_mut().unwrap().speed = f32::NAN;
    assert!(WindField::from_snapshot(&snapshot).is_err());
}

#[test]
fn a_snapshot_taken_mid_easing_resumes_it_to_the_bit() {
    let mut server = field(3.0);
    server.ease_to(11.0, Vec2::new(-1.0, 1.0), 4.0).unwrap();
    for _ in 0..97 {
        server.advance(HZ_60);
    }
    let mut client = WindField::from_snapshot(&server.snapshot()).unwrap();
    assert_eq!(client.easing(), server.easing());
    for step in 0..4000 {
        server.advance(HZ_60);
        client.advance(HZ_60);
        let (s, c) = (server.config(), client.config());
        assert_eq!(
            (
                s.reference_speed.to_bits(),
                s.direction.to_array().map(f32::to_bits)
            ),
            (
                c.reference_speed.to_bits(),
                c.direction.to_array().map(f32::to_bits)
            ),
            "step {step}"
        );
    }
    assert_eq!(server.easing(), None, "arrived");
}
