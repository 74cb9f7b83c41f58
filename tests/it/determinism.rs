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

#[path = "../../examples/common/fingerprint.rs"]
mod fingerprint;

/// 1 000 falling objects and a cloud of 2 000 leaves, 600 steps in a gusty wind with a fan
/// (`examples/common/fingerprint.rs`, the hash the showcase's tour prints in the browser): the
/// same bits with the SIMD lanes on and off, on 1, 2 and 4 compute threads. Each thread count
/// runs in a process of its own (Bevy's pools are sized once per process).
#[test]
fn falls_have_the_same_bits_with_lanes_or_without_on_any_number_of_threads() {
    if let Ok(threads) = std::env::var("WINDFALL_FINGERPRINT_THREADS") {
        let threads = threads.parse().expect("a thread count");
        bevy_windfall::set_lanes(true);
        let on = fingerprint::fingerprint(Some(threads));
        bevy_windfall::set_lanes(false);
        let off = fingerprint::fingerprint(Some(threads));
        bevy_windfall::set_lanes(true);
        println!("fingerprint {threads} threads: lanes {on:016x}, without {off:016x}");
        return;
    }
    let test = module_path!()
        .split_once("::")
        .map_or("", |(_, m)| m)
        .to_owned()
        + "::falls_have_the_same_bits_with_lanes_or_without_on_any_number_of_threads";
    let mut seen = Vec::new();
    for threads in [1, 2, 4] {
        let output = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", &test, "--nocapture", "--test-threads=1"])
            .env("WINDFALL_FINGERPRINT_THREADS", threads.to_string())
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        let line = stdout
            .lines()
            .find_map(|l| l.find("fingerprint ").map(|at| &l[at..]))
            .unwrap_or_else(|| panic!("no fingerprint from {threads} threads:\n{stdout}"));
        let hashes: Vec<&str> = line.split([' ', ',']).filter(|w| w.len() == 16).collect();
        println!("{line}");
        seen.extend(hashes.iter().map(|h| h.to_string()));
    }
    assert_eq!(seen.len(), 6, "{seen:?}");
    assert!(seen.iter().all(|h| *h == seen[0]), "{seen:?}");
}
