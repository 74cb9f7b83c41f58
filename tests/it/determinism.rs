//! Same seed, same wind, bit for bit, across apps stepped on the fixed timestep.
use crate::common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use common::{headless_app, ready};

fn run(config: WindConfig, steps: usize) -> Vec<u32> {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config));
    ready(&mut app);
    for _ in 0..steps {
        app.update();
    }
    let wind = app.world().resource::<WindField>();
    (0..200)
        .map(|i| Vec3::new(i as f32 * 1.37, (i % 17) as f32, -(i as f32) * 0.61))
        .flat_map(|p| wind.velocity(p).to_array())
        .map(f32::to_bits)
        .collect()
}

#[test]
fn same_seed_same_wind_bit_for_bit() {
    for (spatial, temporal) in [
        (SpatialMode::Plane, TemporalMode::Frozen),
        (
            SpatialMode::Volume { vertical_nodes: 8 },
            TemporalMode::Evolving {
                samples: 8,
                period: 4.0,
            },
        ),
    ] {
        let config = WindConfig {
            spatial,
            temporal,
            grid: [48, 40],
            seed: 99,
            ..default()
        };
        let a = run(config.clone(), 300);
        assert_eq!(a, run(config.clone(), 300), "{spatial:?} {temporal:?}");
        assert_ne!(
            a,
            run(
                WindConfig {
                    seed: 100,
                    ..config.clone()
                },
                300
            )
        );
        assert_ne!(a, run(config, 299), "the clock moved the wind");
    }
}
