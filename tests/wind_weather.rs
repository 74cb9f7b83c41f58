//! Weather: the mean wind easing toward a new speed and direction (no jumps), and the Beaufort
//! presets.

use bevy::math::{Vec2, Vec3};
use bevy_windfall::wind::{BEAUFORT_SPEEDS, WindConfig, WindField};

fn calm_field(speed: f32) -> WindField {
    WindField::new(WindConfig {
        reference_speed: speed,
        grid: [16, 16],
        ..WindConfig::default()
    })
    .unwrap()
}

#[test]
fn the_mean_wind_eases_as_a_first_order_lag_without_jumps() {
    let mut field = calm_field(2.0);
    let (from, to, tau) = (2.0f32, 10.0f32, 2.0f32);
    let veered = Vec2::new(0.0, -1.0); // a quarter turn from +X
    field.ease_to(to, veered, tau).unwrap();
    let dt = 1.0 / 60.0;
    let mut last = field.config().reference_speed;
    for step in 1..=120 {
        field.advance(dt);
        let speed = field.config().reference_speed;
        // Never a jump: each step moves at most the lag's largest rate, (to − from) dt / τ.
        assert!(
            speed - last <= (to - from) * dt / tau * 1.001,
            "step {step}: {last} → {speed}"
        );
        assert!(speed >= last);
        last = speed;
    }
    // After one τ: 1 − 1/e of the way, in speed and in angle.
    let expected = to - (to - from) * (-1.0f32).exp();
    assert!(
        (last - expected).abs() < 0.01 * to,
        "{last} against {expected}"
    );
    let d = field.direction();
    let turned = Vec2::new(d.x, d.z).angle_to(Vec2::X).abs();
    let expected_angle = std::f32::consts::FRAC_PI_2 * (1.0 - (-1.0f32).exp());
    assert!(
        (turned - expected_angle).abs() < 0.01,
        "{turned} against {expected_angle}"
    );
    assert!(d.z < 0.0, "turns the short way, toward −Z");
    // The mean wind the samples carry follows the eased speed.
    let u = field.mean_speed_at(10.0);
    assert!((u - last).abs() < 1e-4 * last);
    // Arrives exactly, then stops easing.
    for _ in 0..60 * 30 {
        field.advance(dt);
    }
    assert_eq!(field.config().reference_speed, to);
    assert!((field.direction() - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
    assert_eq!(field.easing(), None);
}

#[test]
fn a_paused_clock_holds_the_weather_and_a_direct_set_ends_it() {
    let mut field = calm_field(3.0);
    field.ease_to(12.0, Vec2::X, 1.0).unwrap();
    field.paused = true;
    for _ in 0..60 {
        field.advance(1.0 / 60.0);
    }
    assert_eq!(field.config().reference_speed, 3.0);
    field.paused = false;
    field.advance(0.5);
    assert!(field.config().reference_speed > 3.0);
    field.set_reference_speed(5.0).unwrap();
    assert_eq!(field.easing(), None);
    field.advance(0.5);
    assert_eq!(field.config().reference_speed, 5.0);
    // τ = 0 sets at once.
    field.ease_to(7.0, Vec2::new(0.0, 1.0), 0.0).unwrap();
    assert_eq!(field.config().reference_speed, 7.0);
    assert!((field.direction() - Vec3::Z).length() < 1e-6);
}

#[test]
fn bad_targets_are_named() {
    let mut field = calm_field(3.0);
    let field_of = |r: Result<(), bevy_windfall::wind::WindError>| r.unwrap_err().field();
    assert_eq!(
        field_of(field.ease_to(f32::NAN, Vec2::X, 1.0)),
        "reference_speed"
    );
    assert_eq!(
        field_of(field.ease_to(-1.0, Vec2::X, 1.0)),
        "reference_speed"
    );
    assert_eq!(field_of(field.ease_to(5.0, Vec2::ZERO, 1.0)), "direction");
    assert_eq!(field_of(field.ease_to(5.0, Vec2::X, -1.0)), "time_constant");
    assert_eq!(
        field_of(field.ease_to(5.0, Vec2::X, f32::INFINITY)),
        "time_constant"
    );
    assert_eq!(field.easing(), None, "a refused target changes nothing");
}

#[test]
fn beaufort_presets_blow_within_their_force_at_ten_metres() {
    // The WMO ranges, m/s at 10 m (force 12: at least 32.7).
    let ranges = [
        (0.0, 0.2),
        (0.3, 1.5),
        (1.6, 3.3),
        (3.4, 5.4),
        (5.5, 7.9),
        (8.0, 10.7),
        (10.8, 13.8),
        (13.9, 17.1),
        (17.2, 20.7),
        (20.8, 24.4),
        (24.5, 28.4),
        (28.5, 32.6),
        (32.7, f32::INFINITY),
    ];
    for (force, (low, high)) in ranges.into_iter().enumerate() {
        let field = WindField::new(WindConfig {
            grid: [16, 16],
            ..WindConfig::beaufort(force as u8)
        })
        .unwrap();
        let u = field.mean_speed_at(10.0);
        assert!((low..=high).contains(&u), "force {force}: {u} m/s");
        assert!((u - BEAUFORT_SPEEDS[force]).abs() < 1e-4);
    }
    assert_eq!(WindConfig::beaufort(200), WindConfig::beaufort(12));
}
