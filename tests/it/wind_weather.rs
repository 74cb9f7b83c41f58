//! Weather: the mean wind easing toward a new speed and direction (no jumps), and the Beaufort
//! presets.

use bevy::math::{Vec2, Vec3};
use bevy_windfall::wind::{Pulse, WindConfig, WindField};

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
        assert!((u - WindConfig::BEAUFORT_SPEEDS[force]).abs() < 1e-4);
    }
    assert_eq!(WindConfig::beaufort(200), WindConfig::beaufort(12));
}

/// The largest change of the wind at a few fixed points over one step of `dt`.
fn largest_step_change(field: &mut WindField, dt: f32) -> f32 {
    let points: Vec<Vec3> = (0..16)
        .map(|i| Vec3::new(i as f32 * 3.7, 10.0, i as f32 * -2.3))
        .collect();
    let before: Vec<Vec3> = points.iter().map(|&p| field.velocity(p)).collect();
    field.advance(dt);
    points
        .iter()
        .zip(&before)
        .map(|(&p, &b)| (field.velocity(p) - b).length())
        .fold(0.0, f32::max)
}

#[test]
fn easing_late_in_a_session_moves_the_pattern_no_faster_than_the_wind() {
    // Taylor's hypothesis with a changing mean wind: the pattern travels ∫ U dt. Reading it as
    // U(t)·t instead would make it race at t·dU/dt (here 3600 s × 4 m/s² ≈ 14 km/s) while the
    // wind eases, or rotate around the origin when the direction veers.
    let dt = 1.0 / 60.0;
    let mut steady = calm_field(8.0);
    steady.set_clock(3600.0);
    let steady_change = (0..30)
        .map(|_| largest_step_change(&mut steady, dt))
        .fold(0.0, f32::max);
    for (speed, direction) in [(8.0, Vec2::X), (4.0, Vec2::new(0.0, 1.0))] {
        let mut field = calm_field(4.0);
        field.set_clock(3600.0);
        field.ease_to(speed, direction, 1.0).unwrap();
        let easing_change = (0..30)
            .map(|_| largest_step_change(&mut field, dt))
            .fold(0.0, f32::max);
        // The eased wind changes by the mean's own change (≤ 4 m/s × dt/τ) plus what the pattern
        // does travelling at ≤ 8 m/s, as in the steady field.
        assert!(
            easing_change < 1.5 * steady_change + 4.0 * dt + 0.05,
            "to {speed} m/s {direction}: {easing_change} m/s per step against {steady_change}"
        );
    }
    // A direct change of the direction changes the mean wind but does not fling the pattern.
    let mut field = calm_field(4.0);
    field.set_clock(3600.0);
    let p = Vec3::new(5.0, 10.0, 5.0);
    let before = field.velocity(p);
    field.set_reference_speed(4.0).unwrap();
    assert_eq!(
        field.velocity(p),
        before,
        "re-setting the same speed changes nothing"
    );
}

#[test]
fn a_pulse_swells_the_wind_periodically_without_changing_its_mean() {
    let plain = calm_field(6.0);
    let mut pulsed = calm_field(6.0);
    let pulse = Pulse::new(0.5, 0.25); // ±50 %, every 4 s
    pulsed.set_pulse(pulse).unwrap();
    let p = Vec3::new(3.0, 10.0, -2.0);
    let (mut sum, mut plain_sum, mut low, mut high) = (0.0f64, 0.0f64, f32::MAX, 0.0f32);
    let n = 400;
    for i in 0..n {
        let t = 4.0 * i as f32 / n as f32; // one period
        let ratio = pulsed.velocity_at(p, t).length() / plain.velocity_at(p, t).length();
        low = low.min(ratio);
        high = high.max(ratio);
        sum += f64::from(pulsed.velocity_at(p, t).x);
        plain_sum += f64::from(plain.velocity_at(p, t).x);
    }
    assert!(
        (high - 1.5).abs() < 1e-3 && (low - 0.5).abs() < 1e-3,
        "{low}..{high}"
    );
    // The peak is a quarter period in, the trough three quarters.
    let at = |t: f32| pulsed.velocity_at(p, t).length() / plain.velocity_at(p, t).length();
    assert!((at(1.0) - 1.5).abs() < 1e-4 && (at(3.0) - 0.5).abs() < 1e-4);
    // The mean over a period is kept (the turbulence varies along it, so within a few %).
    assert!((sum / plain_sum - 1.0).abs() < 0.05, "{}", sum / plain_sum);
    // A full swing never reverses the wind.
    pulsed.set_pulse(Pulse::new(1.0, 3.0)).unwrap();
    for i in 0..1000 {
        let t = i as f32 * 0.001;
        assert!(pulsed.velocity_at(p, t).dot(plain.velocity_at(p, t)) >= 0.0);
    }
    // Bad pulses are named and change nothing.
    for (bad, field) in [
        (Pulse::new(1.5, 1.0), "pulse.magnitude"),
        (Pulse::new(-0.1, 1.0), "pulse.magnitude"),
        (Pulse::new(0.5, f32::NAN), "pulse.frequency"),
        (Pulse::new(0.5, 1e6), "pulse.frequency"),
    ] {
        assert_eq!(pulsed.set_pulse(bad).unwrap_err().field(), field);
        let config = WindConfig {
            pulse: bad,
            ..WindConfig::default()
        };
        assert_eq!(config.validate().unwrap_err().field(), field);
    }
    assert_eq!(pulsed.config().pulse, Pulse::new(1.0, 3.0));
}

#[test]
fn a_pulse_set_in_the_settings_applies_at_once_without_a_rebuild() {
    use bevy::prelude::*;
    use bevy::time::TimeUpdateStrategy;
    use bevy_windfall::prelude::*;
    use bevy_windfall::wind::WindRebuild;
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        WindPlugin::new(WindConfig {
            grid: [16, 16],
            ..WindConfig::default()
        }),
    ))
    .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app.update();
    app.world_mut().resource_mut::<WindSettings>().pulse = Pulse::new(0.3, 0.5);
    app.update();
    assert!(app.world().get_resource::<WindRebuild>().is_none());
    assert_eq!(
        app.world().resource::<WindField>().config().pulse,
        Pulse::new(0.3, 0.5)
    );
    // A bad one is refused (the wind keeps its pulse); the settings keep what was set, and
    // the next good value applies.
    app.world_mut().resource_mut::<WindSettings>().pulse = Pulse::new(2.0, 0.5);
    app.update();
    assert_eq!(
        app.world().resource::<WindField>().config().pulse,
        Pulse::new(0.3, 0.5)
    );
    assert_eq!(
        app.world().resource::<WindSettings>().pulse,
        Pulse::new(2.0, 0.5)
    );
    app.world_mut().resource_mut::<WindSettings>().pulse = Pulse::new(0.8, 0.5);
    app.update();
    assert_eq!(
        app.world().resource::<WindField>().config().pulse,
        Pulse::new(0.8, 0.5)
    );
}
