//! The `serde` feature: the wind's settings and clock sent as text rebuild the same wind, bit
//! for bit (what a multiplayer client needs to agree with its server without sending velocities).

use bevy::math::{Vec2, Vec3};
use bevy_windfall::wind::{
    SpatialMode, TemporalMode, WindConfig, WindField, WindSettings, WindSnapshot,
};

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

/// A few points spread over the field and beyond its period.
fn probes() -> Vec<Vec3> {
    (0..40)
        .map(|i| {
            let i = i as f32;
            Vec3::new(37.3 * i - 600.0, 0.2 + 1.9 * (i % 13.0), -23.9 * i + 111.0)
        })
        .collect()
}

#[test]
fn a_snapshot_sent_as_json_blows_the_same_wind_bit_for_bit() {
    let configs = [
        WindConfig {
            grid: [48, 32],
            seed: 91,
            ..Default::default()
        },
        WindConfig {
            reference_speed: 11.0,
            direction: Vec2::new(-0.3, 0.8),
            beta: 2.2,
            grid: [32, 32],
            temporal: TemporalMode::Evolving {
                samples: 8,
                period: 13.0,
            },
            spatial: SpatialMode::Volume { vertical_nodes: 8 },
            seed: u64::MAX - 3,
            ..Default::default()
        },
    ];
    // Clocks from the start of a game to a week in, with fractions an f32 cannot hold.
    let clocks = [0.0, 1.0 / 3.0, 1_234.567_890_123, 7.0 * 86_400.0 + 0.1];
    for config in configs {
        for time in clocks {
            let mut server = WindField::new(config.clone()).unwrap();
            server.set_clock(time);
            server.time_scale = 1.5;
            let text = serde_json::to_string(&server.snapshot()).unwrap();
            let received: WindSnapshot = serde_json::from_str(&text).unwrap();
            let mut client = WindField::from_snapshot(&received).unwrap();
            assert_eq!(client.time_f64().to_bits(), time.to_bits(), "{text}");
            for p in probes() {
                assert_eq!(bits(client.velocity(p)), bits(server.velocity(p)), "{text}");
            }
            // And they stay together as both clocks run.
            for _ in 0..50 {
                server.advance(1.0 / 60.0);
                client.advance(1.0 / 60.0);
            }
            for p in probes() {
                assert_eq!(bits(client.velocity(p)), bits(server.velocity(p)), "{text}");
            }
        }
    }
}

#[test]
fn settings_round_trip_and_bad_snapshots_name_the_field() {
    let settings = WindSettings::new(WindConfig {
        reference_speed: 6.5,
        roughness: 0.3,
        seed: 12,
        ..Default::default()
    });
    let text = serde_json::to_string(&settings).unwrap();
    let back: WindSettings = serde_json::from_str(&text).unwrap();
    assert_eq!(back, settings);

    let mut snapshot = WindField::new(WindConfig {
        grid: [16, 16],
        ..Default::default()
    })
    .unwrap()
    .snapshot();
    snapshot.time = f64::INFINITY;
    let error = WindField::from_snapshot(&snapshot).unwrap_err();
    assert!(error.to_string().contains("time"), "{error}");
    snapshot.time = 0.0;
    snapshot.config.roughness = -1.0;
    let error = WindField::from_snapshot(&snapshot).unwrap_err();
    assert!(error.to_string().contains("roughness"), "{error}");
}

/// A server app and a client app in lockstep (one fixed step per update each).
fn lockstep_app() -> bevy::app::App {
    use bevy_windfall::prelude::*;
    let mut app = crate::common::headless_app();
    app.add_plugins(WindPlugin::new(WindConfig {
        grid: [32, 32],
        seed: 3,
        ..Default::default()
    }));
    crate::common::ready(&mut app);
    app
}

/// Hostile input, round 4, item 8: a snapshot taken 0, 1 or 5 frames after a β and seed edit,
/// sent as JSON and restored into a client at the same step, keeps the client bit for bit with
/// the server through the step the rebuild lands and 60 steps beyond.
#[test]
fn a_snapshot_sent_after_a_settings_edit_keeps_the_client_in_step() {
    for after in [0, 1, 5] {
        let (mut server, mut client) = (lockstep_app(), lockstep_app());
        // The client's own history differs: it matters not once it has the snapshot.
        client
            .world_mut()
            .resource_mut::<WindField>()
            .set_reference_speed(9.0)
            .unwrap();
        for _ in 0..3 {
            server.update();
            client.update();
        }
        {
            let mut settings = server.world_mut().resource_mut::<WindSettings>();
            settings.beta = 2.5;
            settings.seed = 44;
            settings.reference_speed = 6.0;
        }
        for _ in 0..after {
            server.update();
            client.update();
        }
        let snapshot = WindSnapshot::capture(server.world()).unwrap();
        let text = serde_json::to_string(&snapshot).unwrap();
        let received: WindSnapshot = serde_json::from_str(&text).unwrap();
        received.restore(client.world_mut()).unwrap();
        for step in 0..100 {
            server.update();
            client.update();
            let (s, c) = (
                server.world().resource::<WindField>(),
                client.world().resource::<WindField>(),
            );
            for p in probes() {
                assert_eq!(
                    bits(s.velocity(p)),
                    bits(c.velocity(p)),
                    "{after} frames after the edit, step {step}, at {p}"
                );
            }
        }
        let field = server.world().resource::<WindField>();
        assert_eq!((field.config().beta, field.config().seed), (2.5, 44));
    }
}

/// Hostile input, round 4, item 9: an easing's start speed beyond what the wind may have is
/// refused by name, not taken as the reference speed a step later.
#[test]
fn an_easing_from_an_impossible_speed_is_refused() {
    let mut field = WindField::new(WindConfig {
        grid: [16, 16],
        ..Default::default()
    })
    .unwrap();
    field.ease_to(8.0, Vec2::Y, 2.0).unwrap();
    field.advance(0.5);
    let good = serde_json::to_value(field.snapshot()).unwrap();
    for speed in [2e4, 1e6, 1e30, 3e38, -1.0] {
        let mut hostile = good.clone();
        hostile["easing"]["from_speed"] = serde_json::json!(speed);
        let snapshot: WindSnapshot = serde_json::from_value(hostile).unwrap();
        let error = WindField::from_snapshot(&snapshot).unwrap_err();
        assert_eq!(error.field(), "easing.from_speed", "{speed}");
    }
    // A sound one still resumes, to the bit.
    let snapshot: WindSnapshot = serde_json::from_value(good).unwrap();
    let mut client = WindField::from_snapshot(&snapshot).unwrap();
    let mut server = field;
    server.advance(1.0);
    client.advance(1.0);
    assert_eq!(
        bits(server.velocity(Vec3::new(1.0, 2.0, 3.0))),
        bits(client.velocity(Vec3::new(1.0, 2.0, 3.0)))
    );
}
