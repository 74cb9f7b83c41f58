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
