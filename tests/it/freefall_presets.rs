//! Falling-object presets as a designer uses them: the paper's Fig. 15 sequences, the seconds a
//! fall spends in each motion, the response to wind by mass, tumbling fading in strong wind, and
//! the showcase's leaves showing at least four motions at once.

use crate::common;
#[path = "../../examples/showcase/population.rs"]
mod population;

use bevy::prelude::*;
use bevy_windfall::freefall::*;
use bevy_windfall::wind::{TemporalMode, WindConfig, WindField, WindPlugin};

const DT: f32 = 1.0 / 60.0;

fn still_tilt() -> WindTilt {
    WindTilt {
        max_angle: 0.0,
        reference_speed: 1.0,
    }
}

/// The motion at every step of a fall of `seconds` in still fluid.
fn motions(object: &FallingObject, model: &FallModel, seconds: f32) -> (Vec<PrimitiveMotion>, f32) {
    let mut path = object
        .path(model, FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY))
        .unwrap();
    let mut seen = vec![path.motion()];
    for _ in 0..(seconds / DT) as usize {
        path.advance(model, DT, Vec3::ZERO, &still_tilt());
        seen.push(path.motion());
    }
    (seen, path.scales().swing_time())
}

#[test]
fn fig_15_objects_go_through_the_papers_sequences() {
    // (a) coin: steady → fluttering; (b) paper: tumbling → spiral; (c) leaf: steady → tumbling
    // → helix. Every fall keeps the order; most show the whole sequence within a few seconds.
    let model = FallModel::default();
    let cases = [
        (
            FallPreset::Coin,
            6.0,
            &[PrimitiveMotion::SteadyDescent, PrimitiveMotion::Fluttering][..],
        ),
        (
            FallPreset::PaperSheet,
            4.0,
            &[PrimitiveMotion::Tumbling, PrimitiveMotion::Spiral][..],
        ),
        (
            FallPreset::Leaf,
            4.0,
            &[
                PrimitiveMotion::SteadyDescent,
                PrimitiveMotion::Tumbling,
                PrimitiveMotion::Helix,
            ][..],
        ),
    ];
    for (preset, seconds, sequence) in cases {
        let mut whole = 0;
        let falls = 200;
        for seed in 0..falls {
            let object = FallingObject {
                seed,
                ..preset.object()
            };
            let (seen, _) = motions(&object, &model, seconds);
            let mut order: Vec<PrimitiveMotion> = seen.clone();
            order.dedup();
            // Only the preset's motions, in its order.
            let positions: Vec<usize> = order
                .iter()
                .map(|m| {
                    preset
                        .sequence()
                        .iter()
                        .position(|s| s == m)
                        .unwrap_or_else(|| panic!("{preset:?} seed {seed}: {m:?} in {order:?}"))
                })
                .collect();
            assert!(
                positions.windows(2).all(|w| w[1] > w[0]),
                "{preset:?} seed {seed}: {order:?}"
            );
            whole += usize::from(order == sequence);
        }
        assert!(
            whole as f32 > 0.5 * falls as f32,
            "{preset:?}: the whole sequence in {whole} of {falls} falls"
        );
    }
}

/// Mean seconds per visit of each motion over many falls of a preset.
fn seconds_per_motion(preset: FallPreset, model: &FallModel, falls: u64) -> [Option<f32>; 6] {
    let (mut total, mut visits) = ([0.0f32; 6], [0u32; 6]);
    for seed in 0..falls {
        let object = FallingObject {
            seed,
            ..preset.object()
        };
        let (seen, _) = motions(&object, model, 12.0);
        // Whole visits only: the last motion may be cut off by the end of the run.
        let last = *seen.last().unwrap();
        let mut run = 0usize;
        for pair in seen.windows(2) {
            run += 1;
            if pair[1] != pair[0] {
                total[pair[0].index()] += run as f32 * DT;
                visits[pair[0].index()] += 1;
                run = 0;
            }
        }
        let _ = last;
    }
    std::array::from_fn(|i| (visits[i] > 20).then(|| total[i] / visits[i] as f32))
}

#[test]
fn each_motion_lasts_as_long_as_its_preset_says() {
    // A motion whose pieces last d seconds and which changes at a rate of 1/D is seen for
    // d / (1 − e^(−d/D)) on average (changes happen where pieces end).
    let model = FallModel::default();
    for preset in [FallPreset::Coin, FallPreset::Leaf, FallPreset::OakLeaf] {
        let (_, dwell) = preset.dwell_times();
        let measured = seconds_per_motion(preset, &model, 400);
        let object = preset.object();
        let d = object.scales(&object.regime().unwrap()).swing_time();
        for motion in [
            PrimitiveMotion::SteadyDescent,
            PrimitiveMotion::Fluttering,
            PrimitiveMotion::Tumbling,
        ] {
            let (Some(seen), true) = (measured[motion.index()], dwell[motion.index()].is_finite())
            else {
                continue;
            };
            let expected = d / (1.0 - (-d / dwell[motion.index()]).exp());
            assert!(
                (seen / expected - 1.0).abs() < 0.15,
                "{preset:?} {motion:?}: {seen} s against {expected} s"
            );
        }
    }
}

/// A fall that only descends steadily (no swings), for the response to wind.
fn steady(preset: FallPreset) -> FallingObject {
    let mut transitions = [[0.0; 6]; 6];
    for (i, row) in transitions.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    FallingObject {
        main_motion: Some(PrimitiveMotion::SteadyDescent),
        markov: Some(MarkovChain::new([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], transitions).unwrap()),
        ..preset.object()
    }
}

#[test]
fn heavy_objects_take_up_the_wind_more_slowly() {
    // τ = (U / g) ρ_s / (ρ_s − ρ_f) in gentle wind: a coin in air 0.6 s, a leaf 0.1 s.
    let model = FallModel::default();
    let mut coin_in_air = steady(FallPreset::Coin);
    coin_in_air.fluid = Fluid::AIR;
    let leaf = steady(FallPreset::Leaf);
    let u = Vec3::new(0.1, 0.0, 0.0);
    let mut taus = Vec::new();
    for object in [coin_in_air, leaf] {
        let regime = object.regime().unwrap();
        let ratio = object.density / (object.density - object.fluid.density);
        let tau = regime.descent_speed / object.gravity * ratio;
        let mut path = object
            .path(&model, FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY))
            .unwrap();
        let dt = 1e-3;
        let steps = (tau / dt).round() as usize;
        for _ in 0..steps {
            path.advance(&model, dt, u, &still_tilt());
        }
        // After one τ: 1 − 1/e of the wind.
        let share = path.drift().x / u.x;
        assert!(
            (share - (1.0 - (-1.0f32).exp())).abs() < 0.02,
            "{}: {share} after τ = {tau}",
            object.density
        );
        taus.push(tau);
    }
    assert!(taus[0] > 4.0 * taus[1], "{taus:?}");
}

#[test]
fn light_leaves_follow_gusts_more_closely_than_a_coin() {
    let model = FallModel::default();
    let wind = WindField::new(WindConfig {
        reference_speed: 5.0,
        temporal: TemporalMode::Evolving {
            samples: 16,
            period: 8.0,
        },
        grid: [64, 64],
        cell_size: 0.5,
        ..default()
    })
    .unwrap();
    let mut coin_in_air = steady(FallPreset::Coin);
    coin_in_air.fluid = Fluid::AIR;
    // How far each lags the gusts it meets (RMS of u − v across the wind): a low-pass filter
    // of time constant τ lags in proportion to τ.
    let mut lag = Vec::new();
    for object in [coin_in_air, steady(FallPreset::Leaf)] {
        let mut path = object
            .path(
                &model,
                FallRelease::at(Vec3::new(0.0, 1.0e4, 0.0), f32::NEG_INFINITY),
            )
            .unwrap();
        let mut squares = 0.0;
        let mut n = 0;
        for i in 0..3000 {
            // Hold the height the wind is sampled at: only its gusts matter here.
            let p = path.position() * Vec3::new(1.0, 0.0, 1.0) + Vec3::Y * 3.0;
            let u = wind.velocity_at(p, i as f32 * DT);
            path.advance(&model, DT, u, &still_tilt());
            if i > 600 {
                squares += (u.z - path.drift().z).powi(2);
                n += 1;
            }
        }
        lag.push((squares / n as f32).sqrt());
    }
    assert!(
        lag[0] > 2.0 * lag[1],
        "coin lags {} m/s, leaf {} m/s",
        lag[0],
        lag[1]
    );
}

#[test]
fn tumbling_fades_in_strong_wind_and_the_object_travels_far() {
    // §5, Fig. 17: "under a strong wind field, tumbling motion disappears and the object
    // travels far".
    let model = FallModel::default();
    let mut transitions = [[0.0; 6]; 6];
    for (i, row) in transitions.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    let card = FallingObject {
        main_motion: Some(PrimitiveMotion::Tumbling),
        markov: Some(MarkovChain::new([0.0, 0.0, 0.0, 1.0, 0.0, 0.0], transitions).unwrap()),
        ..FallPreset::PlayingCard.object()
    };
    let run = |speed: f32| {
        let mut path = card
            .path(
                &model,
                FallRelease::at(Vec3::new(0.0, 100.0, 0.0), f32::NEG_INFINITY),
            )
            .unwrap();
        let (mut turned, mut q) = (0.0, path.orientation());
        for _ in 0..600 {
            path.advance(&model, DT, Vec3::new(speed, 0.0, 0.0), &still_tilt());
            turned += q.angle_between(path.orientation());
            q = path.orientation();
        }
        let travel = Vec2::new(path.position().x, path.position().z).length();
        (turned, travel)
    };
    let (still_turn, still_travel) = run(0.0);
    let (windy_turn, windy_travel) = run(10.0);
    assert!(
        windy_turn < 0.3 * still_turn,
        "{windy_turn} vs {still_turn} rad"
    );
    assert!(
        windy_travel > 5.0 * still_travel,
        "{windy_travel} vs {still_travel} m"
    );
    // A breeze of one descent speed barely changes it.
    let (breeze_turn, _) = run(card.regime().unwrap().descent_speed);
    assert!(
        breeze_turn > 0.8 * still_turn,
        "{breeze_turn} vs {still_turn}"
    );
}

#[test]
fn the_showcase_leaves_show_four_motions_at_once() {
    let mut app = common::headless_app();
    app.add_plugins((
        WindPlugin::new(WindConfig {
            reference_speed: 2.5,
            grid: [48, 48],
            ..default()
        }),
        FallPlugin::default(),
    ));
    let mut canopy = population::Canopy(population::Stream::new(99));
    for i in 0..population::LEAVES {
        let transform = Transform::from_translation(canopy.midair()).with_rotation(canopy.turn());
        app.world_mut().spawn((population::leaf(i), transform));
    }
    common::ready(&mut app);
    let mut at_once = Vec::new();
    for step in 0..240 {
        app.update();
        if step >= 60 && step % 20 == 0 {
            let mut seen = [false; 6];
            let mut states = app.world_mut().query::<&FallState>();
            for state in states.iter(app.world()) {
                if let (false, Some(m)) = (state.landed(), state.motion()) {
                    seen[m.index()] = true;
                }
            }
            at_once.push(seen.iter().filter(|s| **s).count());
        }
    }
    assert!(
        at_once.iter().all(|n| *n >= 4),
        "motions at once: {at_once:?}"
    );
}
