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

/// The fingerprint of the falls and of the physical flag the scene also flies, since the flag's
/// default tick became 4 ms (CHANGELOG): the same natively, in every lane width and thread count,
/// and in Chromium.
const FINGERPRINT: &str = "c882af8ec213453a";

#[path = "../../examples/common/fingerprint.rs"]
pub(crate) mod fingerprint;

/// 1 000 falling objects and a cloud of 2 000 leaves, 600 steps in a gusty wind with a fan
/// (`examples/common/fingerprint.rs`, the hash the showcase's tour prints in the browser): the
/// same bits in eight lanes (where the CPU has AVX2), four and one, on 1, 2 and 4 compute
/// threads. Each thread count runs in a process of its own (Bevy's pools are sized once per
/// process).
#[test]
fn falls_have_the_same_bits_in_any_lanes_on_any_number_of_threads() {
    let widths: Vec<usize> = [8, 4, 1]
        .into_iter()
        .filter(|&w| w <= bevy_windfall::widest_lanes())
        .collect();
    if let Ok(threads) = std::env::var("WINDFALL_FINGERPRINT_THREADS") {
        let threads = threads.parse().expect("a thread count");
        let mut line = format!("fingerprint {threads} threads:");
        for &width in &widths {
            bevy_windfall::set_lane_width(width);
            let hash = fingerprint::fingerprint(Some(threads));
            line += &format!(" width {width} {hash:016x},");
        }
        bevy_windfall::set_lanes(true);
        println!("{line}");
        return;
    }
    let test = module_path!()
        .split_once("::")
        .map_or("", |(_, m)| m)
        .to_owned()
        + "::falls_have_the_same_bits_in_any_lanes_on_any_number_of_threads";
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
    assert_eq!(seen.len(), 3 * widths.len(), "{seen:?}");
    assert!(seen.iter().all(|h| *h == seen[0]), "{seen:?}");
    // And the value itself: a change to any fall's bits is made on purpose, said in the
    // CHANGELOG, and the value here with it (CI compares the browser's with the desktop's).
    assert_eq!(seen[0], FINGERPRINT, "the falls' bits changed");
}

/// The bits of `leaf`'s fall (position, orientation, drift, motion, landing) after each of
/// `steps` fixed steps in a gusty evolving wind with a fan; `around` spawns other objects before
/// and after it and `disturb` acts on them at a given step.
fn one_fall(
    steps: usize,
    around: impl Fn(&mut App) -> Vec<Entity>,
    disturb: impl Fn(&mut App, usize, &[Entity]),
) -> Vec<[u32; 11]> {
    use bevy_windfall::freefall::FallPreset;
    let mut app = headless_app();
    let wind = WindConfig {
        reference_speed: 6.0,
        grid: [48, 48],
        seed: 11,
        temporal: TemporalMode::Evolving {
            samples: 8,
            period: 10.0,
        },
        ..default()
    };
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(wind)));
    app.world_mut().spawn((
        WindSource::fan(12.0, 0.7, 14.0),
        Transform::from_xyz(-6.0, 6.0, 0.0).looking_at(Vec3::new(0.0, 6.0, 0.0), Vec3::Y),
    ));
    let mut others = around(&mut app);
    let leaf = app
        .world_mut()
        .spawn((
            FallingObject {
                seed: 7,
                ..FallPreset::MapleLeaf.object()
            },
            Transform::from_xyz(0.5, 8.0, 0.0).with_rotation(Quat::from_rotation_x(0.4)),
        ))
        .id();
    others.extend(around(&mut app));
    ready(&mut app);
    (0..steps)
        .map(|step| {
            disturb(&mut app, step, &others);
            app.update();
            let fall = app
                .world()
                .resource::<FallStore>()
                .fall(leaf)
                .expect("a fall");
            let (p, q, v) = (fall.position(), fall.orientation(), fall.drift());
            let bits = [p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z].map(f32::to_bits);
            let flags = fall.motion().index() as u32 | (u32::from(fall.landed()) << 8);
            let mut out = [0; 11];
            out[..10].copy_from_slice(&bits);
            out[10] = flags;
            out
        })
        .collect()
}

/// A fall depends on nothing but its own description and the wind: alone, or beside a thousand
/// other objects spawned before and after it (of every preset, in the same lanes and blocks of
/// the store), one of which has its transform set to NaN, one is despawned and one is given an
/// invalid description mid-fall, it has the same bits at every step.
#[test]
fn a_fall_depends_only_on_its_description_and_the_wind() {
    use bevy_windfall::freefall::FallPreset;
    const STEPS: usize = 400;
    let alone = one_fall(STEPS, |_| Vec::new(), |_, _, _| {});
    let presets = [
        FallPreset::MapleLeaf,
        FallPreset::PaperSheet,
        FallPreset::Coin,
        FallPreset::Samara,
        FallPreset::PlayingCard,
    ];
    let crowd = |app: &mut App| {
        (0..500u32)
            .map(|i| {
                let object = FallingObject {
                    seed: u64::from(i) + 100,
                    ..presets[i as usize % presets.len()].object()
                };
                let at = Vec3::new((i % 25) as f32 - 12.0, 3.0 + (i / 25) as f32 * 0.5, 1.0);
                app.world_mut()
                    .spawn((object, Transform::from_translation(at)))
                    .id()
            })
            .collect()
    };
    let disturb = |app: &mut App, step: usize, others: &[Entity]| {
        let world = app.world_mut();
        match step {
            50 => {
                world.get_mut::<Transform>(others[499]).unwrap().translation = Vec3::NAN;
            }
            100 => {
                world.despawn(others[500]);
            }
            150 => {
                world.get_mut::<FallingObject>(others[3]).unwrap().density = -1.0;
            }
            200 => {
                world.despawn(others[0]);
            }
            _ => {}
        }
    };
    let crowded = one_fall(STEPS, crowd, disturb);
    for (step, (a, b)) in alone.iter().zip(&crowded).enumerate() {
        assert_eq!(a, b, "step {step}");
    }
    // Not a still picture: it moved, turned and changed motion.
    assert_ne!(alone[0], alone[STEPS - 1]);
}
