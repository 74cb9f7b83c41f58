//! Falling paths as a viewer sees them: continuity (no pops) in every motion, the shapes of
//! eq. 5–6, the database's picks, the swing frequency, the release orientation, and randomized
//! extremes.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::freefall::*;
use bevy_windfall::wind::{TemporalMode, WindConfig, WindField};
use common::{only, paper_coin as coin};
use proptest::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn tilt() -> WindTilt {
    WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    }
}

/// An object forced into `main`, with a chain that climbs L1..main at a swing or two per
/// motion (so every join between motions happens), released turned by `seed`.
fn forced(object: &FallingObject, main: PrimitiveMotion, seed: u64) -> FallingObject {
    let chain = MarkovChain::default().with_step_seconds(0.1);
    FallingObject {
        main_motion: Some(main),
        markov: Some(chain),
        seed,
        ..object.clone()
    }
}

fn release_from(position: Vec3, rotation: Quat) -> FallRelease {
    FallRelease {
        position,
        rotation: Some(rotation),
        velocity: Vec3::ZERO,
        ground: f32::NEG_INFINITY,
    }
}

/// Turns (degrees) and moves (m) of every step of a fall, with a re-release from the shown pose
/// half-way (a new seed, the velocity kept), as the plugin does when the component changes.
fn step_changes(
    object: &FallingObject,
    model: &FallModel,
    wind: Option<&WindField>,
    steps: usize,
) -> (Vec<f32>, Vec<f32>) {
    changes(object, model, wind, steps, true)
}

/// [`step_changes`], the re-release optional.
fn changes(
    object: &FallingObject,
    model: &FallModel,
    wind: Option<&WindField>,
    steps: usize,
    rerelease: bool,
) -> (Vec<f32>, Vec<f32>) {
    changes_every(object, model, wind, steps, rerelease, DT)
}

/// [`changes`] with steps of `dt`.
fn changes_every(
    object: &FallingObject,
    model: &FallModel,
    wind: Option<&WindField>,
    steps: usize,
    rerelease: bool,
    dt: f32,
) -> (Vec<f32>, Vec<f32>) {
    let start = Quat::from_rotation_y(object.seed as f32) * Quat::from_rotation_x(0.4);
    let mut path = object
        .path(model, release_from(Vec3::new(0.0, 500.0, 0.0), start))
        .unwrap();
    let (mut turns, mut moves) = (Vec::new(), Vec::new());
    let (mut q, mut p) = (path.orientation(), path.position());
    for i in 0..steps {
        if rerelease && i == steps / 2 {
            let again = FallingObject {
                seed: object.seed + 1000,
                ..object.clone()
            };
            let release = FallRelease {
                velocity: path.drift(),
                ..release_from(path.position(), path.orientation())
            };
            path = again.path(model, release).unwrap();
        }
        let u = wind.map_or(Vec3::ZERO, |w| {
            w.velocity_at(path.position(), i as f32 * dt)
        });
        path.advance(model, dt, u, &tilt());
        let (nq, np) = (path.orientation(), path.position());
        turns.push(q.angle_between(nq).to_degrees());
        moves.push(p.distance(np));
        (q, p) = (nq, np);
    }
    (turns, moves)
}

/// The pop test of the issue: a step that turns more than 45° while the steps on both sides
/// turn less than a third of it.
fn pops(turns: &[f32]) -> Vec<(usize, [f32; 3])> {
    turns
        .windows(3)
        .enumerate()
        .filter(|(_, w)| w[1] > 45.0 && w[0] < w[1] / 3.0 && w[2] < w[1] / 3.0)
        .map(|(i, w)| (i + 1, [w[0], w[1], w[2]]))
        .collect()
}

/// The evolving 6 m/s wind the continuity checks fall through.
fn gusty_wind() -> WindField {
    WindField::new(WindConfig {
        reference_speed: 6.0,
        temporal: TemporalMode::Evolving {
            samples: 8,
            period: 10.0,
        },
        grid: [48, 48],
        ..default()
    })
    .unwrap()
}

/// A paper coin, a playing card and a maple leaf: the continuity checks' objects.
fn pop_objects() -> [FallingObject; 3] {
    [
        FallingObject::default(),
        FallPreset::PlayingCard.object(),
        FallPreset::MapleLeaf.object(),
    ]
}

#[test]
fn no_pops_in_any_motion_with_or_without_wind() {
    let model = FallModel::default();
    let wind = gusty_wind();
    let objects = pop_objects();
    let mut worst_move = 0.0f32;
    for object in &objects {
        let u = object.regime().unwrap().descent_speed;
        for main in PrimitiveMotion::ALL {
            for seed in 0..24 {
                for wind in [None, Some(&wind)] {
                    let object = forced(object, main, seed);
                    let (turns, moves) = step_changes(&object, &model, wind, 480);
                    let found = pops(&turns);
                    assert!(found.is_empty(), "{main:?} seed {seed}: {found:?}");
                    // Position: no step jumps past three times both neighbours and a descent
                    // step (the wind and the swings change speed smoothly).
                    for w in moves.windows(3) {
                        let jump = w[1] / w[0].max(w[2]).max(u * DT);
                        worst_move = worst_move.max(jump);
                        assert!(jump < 3.0, "{main:?} seed {seed}: moves {w:?}");
                    }
                }
            }
        }
    }
    assert!(worst_move > 1.0, "the check saw real steps: {worst_move}");
}

/// The neighbourhood check: steps that turn more than twice as far as either neighbour, plus
/// 3° (a join where the rate of turning jumps shows as such a spike; a smooth swing, however
/// fast, turns about as far in a step as in the steps beside it).
fn jerks(turns: &[f32]) -> Vec<(usize, f32, f32)> {
    turns
        .windows(3)
        .enumerate()
        .filter_map(|(i, w)| {
            let beside = w[0].max(w[2]);
            (w[1] > 2.0 * beside + 3.0).then_some((i + 1, w[1], beside))
        })
        .collect()
}

#[test]
fn every_join_turns_on_at_the_rate_of_its_neighbours() {
    // No step turns much more than the steps around it, in every motion, for many seeds, with
    // and without wind. (Chaotic swings of half a swing time spiked in 24 of 96 runs: a light
    // leaf turned 75° in 3–4 steps; they now last a whole swing.)
    let model = FallModel::default();
    let wind = gusty_wind();
    let objects = pop_objects();
    let (mut checked, mut failures) = (0usize, Vec::new());
    let mut fastest = 0.0f32;
    for object in &objects {
        for main in PrimitiveMotion::ALL {
            for seed in 0..16 {
                for wind in [None, Some(&wind)] {
                    let object = forced(object, main, seed);
                    let (turns, _) = changes(&object, &model, wind, 480, false);
                    // After the release has faded (a second).
                    let turns = &turns[60..];
                    checked += turns.len();
                    fastest = turns.iter().copied().fold(fastest, f32::max);
                    let found = jerks(turns);
                    if !found.is_empty() {
                        failures.push(format!(
                            "{main:?} seed {seed} wind {}: {:?}",
                            wind.is_some(),
                            &found[..found.len().min(3)]
                        ));
                    }
                }
            }
        }
    }
    assert!(fastest > 20.0, "the check saw fast turns: {fastest}°");
    assert!(
        failures.is_empty(),
        "{} of the falls jerk ({checked} steps):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn every_main_motion_descends_at_the_eq_3_speed() {
    let model = FallModel::default();
    for main in PrimitiveMotion::ALL {
        let object = forced(&coin(), main, 3);
        let u = object.regime().unwrap().descent_speed;
        let mut path = object
            .path(&model, FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY))
            .unwrap();
        for _ in 0..1200 {
            path.advance(&model, DT, Vec3::ZERO, &tilt());
        }
        let fall = -path.still_displacement().y / path.time();
        // Steady descent is exactly U; the others oscillate about it.
        let tolerance = if main == PrimitiveMotion::SteadyDescent {
            1e-4
        } else {
            0.03
        };
        assert!(
            (fall / u - 1.0).abs() < tolerance,
            "{main:?}: {fall} vs U = {u}"
        );
    }
}

/// A fall's path does not depend on the frame rate: in still air, 4 s in frames of 1/30 s and
/// of 1/15 s end within 2 mm of the same fall in frames of 1/60 s, for every preset and eight
/// seeds. The motion changes' blends are where it could: each is summed at its parts' middles
/// (measured: at most 0.26 mm, a paper sheet in frames of 1/15 s; 6.2 mm, a `Leaf`, when a
/// blend was summed whole over each frame).
#[test]
fn a_fall_follows_the_same_path_at_any_frame_rate() {
    let model = FallModel::default();
    let mut worst = (0.0f32, String::new());
    for preset in FallPreset::ALL {
        for seed in 0..8 {
            let object = FallingObject {
                seed,
                ..preset.object()
            };
            let end = |frames: u32| {
                let mut path = object
                    .path(&model, FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY))
                    .unwrap();
                for _ in 0..frames {
                    path.advance(&model, 4.0 / frames as f32, Vec3::ZERO, &tilt());
                }
                assert!((path.time() - 4.0).abs() < 1e-4, "{}", path.time());
                path.position()
            };
            let fine = end(240);
            for frames in [120, 60] {
                let gap = end(frames).distance(fine);
                if gap > worst.0 {
                    worst = (gap, format!("{preset:?}, seed {seed}, {frames} frames"));
                }
            }
        }
    }
    println!("worst: {:.3} mm ({})", worst.0 * 1e3, worst.1);
    assert!(worst.0 < 2e-3, "{:.3} mm off ({})", worst.0 * 1e3, worst.1);
}

fn pure_fall(object: &FallingObject, motion: PrimitiveMotion, seed: u64) -> FallPath {
    let object = FallingObject {
        main_motion: Some(motion),
        markov: Some(only(motion)),
        seed,
        ..object.clone()
    };
    object
        .path(
            &FallModel::default(),
            FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY),
        )
        .unwrap()
}

fn horizontal(p: Vec3) -> Vec2 {
    Vec2::new(p.x, p.z)
}

#[test]
fn steady_descent_drops_straight_and_fluttering_zigzags_in_one_plane() {
    let model = FallModel::default();
    let mut steady = pure_fall(&coin(), PrimitiveMotion::SteadyDescent, 1);
    let mut flutter = pure_fall(&coin(), PrimitiveMotion::Fluttering, 2);
    let mut xs = Vec::new();
    for _ in 0..600 {
        steady.advance(&model, DT, Vec3::ZERO, &tilt());
        flutter.advance(&model, DT, Vec3::ZERO, &tilt());
        xs.push(horizontal(flutter.still_displacement()));
    }
    assert!(horizontal(steady.still_displacement()).length() < 1e-5);
    // A zigzag: bounded, every swing reverses, all points on one line (the swing plane).
    let dir = xs
        .iter()
        .max_by(|a, b| a.length().total_cmp(&b.length()))
        .unwrap()
        .normalize();
    for x in &xs {
        assert!(x.perp_dot(dir).abs() < 1e-4, "{x:?} off the swing plane");
    }
    let along: Vec<f32> = xs.iter().map(|x| x.dot(dir)).collect();
    let reversals = along
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count();
    let swings = (600.0 * DT / flutter.scales().swing_time()) as usize;
    assert!(
        reversals + 2 >= swings && reversals <= swings + 2,
        "{reversals} reversals in {swings} swings"
    );
    // Round the release point: the swings reach about A₀ to either side and do not wander.
    let spread = along.iter().fold(0.0f32, |m, x| m.max(x.abs()));
    let a0 = flutter.amplitude();
    assert!(
        spread > 0.5 * a0 && spread < 2.5 * a0,
        "{spread} vs A₀ {a0}"
    );
}

#[test]
fn flutter_frequency_follows_the_strouhal_number() {
    // f = St U / a: the coin (U = 0.159 m/s, a = 2 cm) swings 1.26 times a second each way.
    let model = FallModel::default();
    let mut path = pure_fall(&coin(), PrimitiveMotion::Fluttering, 4);
    let seconds = 20.0;
    let heading = path.heading() * Vec3::X;
    let mut previous = path.still_displacement();
    let mut sideways = Vec::new();
    for _ in 0..(seconds / DT) as usize {
        path.advance(&model, DT, Vec3::ZERO, &tilt());
        let now = path.still_displacement();
        sideways.push((now - previous).dot(heading));
        previous = now;
    }
    let crossings = sideways.windows(2).filter(|w| w[0] * w[1] < 0.0).count() as f32;
    // Two reversals of the sideways velocity per period.
    let f = crossings / 2.0 / seconds;
    let r = coin().regime().unwrap();
    let expected = FallScales::STROUHAL * r.descent_speed / 0.02;
    assert!((f / expected - 1.0).abs() < 0.05, "{f} Hz vs {expected} Hz");
}

#[test]
fn tumbling_turns_on_and_drifts_to_one_side() {
    let model = FallModel::default();
    let mut path = pure_fall(&coin(), PrimitiveMotion::Tumbling, 4);
    let mut turned = 0.0;
    let mut q = path.orientation();
    for _ in 0..1800 {
        path.advance(&model, DT, Vec3::ZERO, &tilt());
        turned += q.angle_between(path.orientation());
        q = path.orientation();
    }
    let drift = horizontal(path.still_displacement()).length() / -path.still_displacement().y;
    // L per half-turn against a drop of a / (2 St) per swing: tan 18° for a disk.
    let expected = 2.0 * FallScales::STROUHAL;
    assert!(
        (drift / expected - 1.0).abs() < 0.25,
        "tumbling drift per drop {drift}, expected {expected}"
    );
    // A half-turn per swing.
    let swings = path.time() / path.scales().swing_time();
    assert!(
        (turned / (swings * std::f32::consts::PI) - 1.0).abs() < 0.1,
        "{turned} rad in {swings} swings"
    );
}

#[test]
fn spiral_circles_at_radius_a0_and_helix_draws_an_eight_petal_rose() {
    let model = FallModel::default();
    for seed in 0..8 {
        let mut spiral = pure_fall(&FallingObject::default(), PrimitiveMotion::Spiral, seed);
        let mut points = Vec::new();
        for _ in 0..1200 {
            spiral.advance(&model, DT, Vec3::ZERO, &tilt());
            points.push(horizontal(spiral.still_displacement()));
        }
        let centre = points.iter().sum::<Vec2>() / points.len() as f32;
        let a0 = spiral.amplitude();
        for p in &points[60..] {
            assert!(
                (p.distance(centre) / a0 - 1.0).abs() < 0.05,
                "seed {seed}: radius {} vs A₀ {a0}",
                p.distance(centre)
            );
        }
    }
    let mut helix = pure_fall(&FallingObject::default(), PrimitiveMotion::Helix, 3);
    let revolution = 8.0 * helix.scales().swing_time();
    let steps = (3.0 * revolution / 1e-3) as usize;
    let mut points = Vec::new();
    for _ in 0..steps {
        helix.advance(&model, 1e-3, Vec3::ZERO, &tilt());
        points.push(horizontal(helix.still_displacement()));
    }
    let centre = points.iter().sum::<Vec2>() / points.len() as f32;
    let radius: Vec<f32> = points.iter().map(|p| p.distance(centre)).collect();
    let petals = radius
        .windows(3)
        .filter(|w| w[1] > w[0] && w[1] >= w[2] && w[1] > 0.1 * helix.amplitude())
        .count() as f32
        / 3.0;
    assert!((petals - 8.0).abs() < 0.5, "{petals} petals a turn");
    // The outer petals reach A₀, and the path crosses near the axis between petals.
    let max = radius.iter().fold(0.0f32, |m, r| m.max(*r));
    let min = radius.iter().fold(f32::INFINITY, |m, r| m.min(*r));
    assert!((max / helix.amplitude() - 1.0).abs() < 0.05, "{max}");
    assert!(min < 0.05 * helix.amplitude(), "{min}");
}

#[test]
fn deviations_spread_as_the_papers_gaussian() {
    // §2.3.2: A_i e^(−((r − A_i)/σ_i)²), one draw per motion: mean A_i, spread σ_i/√2, and as
    // many falls above the mean as below.
    let object = FallingObject::default();
    let mean = object
        .scales(&object.regime().unwrap())
        .amplitude(PrimitiveMotion::Fluttering);
    let draws: Vec<f32> = (0..2000)
        .map(|seed| pure_fall(&object, PrimitiveMotion::Fluttering, seed).amplitude() / mean)
        .collect();
    let n = draws.len() as f32;
    let m = draws.iter().sum::<f32>() / n;
    let sd = (draws.iter().map(|d| (d - m).powi(2)).sum::<f32>() / n).sqrt();
    let above = draws.iter().filter(|d| **d > 1.0).count() as f32 / n;
    assert!((m - 1.0).abs() < 0.03, "mean {m}");
    assert!((sd - 0.35 / 2f32.sqrt()).abs() < 0.03, "sd {sd}");
    assert!((above - 0.5).abs() < 0.04, "{above}");
    // Within one standard deviation: 68 % of a normal law.
    let within = draws.iter().filter(|d| (*d - m).abs() < sd).count() as f32 / n;
    assert!((within - 0.683).abs() < 0.04, "{within}");
}

#[test]
fn release_orientation_is_kept_and_sets_the_swing_plane() {
    let model = FallModel::default();
    // Long axis (local Z) pointing along world X, pitched by 0.3 rad, rolled a little.
    let release = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2)
        * Quat::from_rotation_z(0.3)
        * Quat::from_rotation_x(0.2);
    let object = FallingObject {
        main_motion: Some(PrimitiveMotion::Fluttering),
        markov: Some(only(PrimitiveMotion::Fluttering)),
        ..coin()
    };
    let mut path = object
        .path(&model, release_from(Vec3::ZERO, release))
        .unwrap();
    assert!(path.orientation().angle_between(release) < 1e-4);
    assert!(path.smoothed(0.0).1.angle_between(release) < 1e-4);
    for _ in 0..600 {
        path.advance(&model, DT, Vec3::ZERO, &tilt());
    }
    // It glides across its long axis.
    let long = horizontal(release * Vec3::Z).normalize();
    let d = horizontal(path.still_displacement());
    assert!(
        d.length() > 1e-3 && d.dot(long).abs() < 1e-3 * d.length(),
        "{d:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Sizes from microns to metres, densities from barely sinking to osmium in air, water or
    /// air, any release orientation, time steps up to 0.25 s, wind to 70 m/s: finite poses,
    /// never NaN.
    #[test]
    fn extreme_objects_fall_without_nan(
        size in -6.0f32..1.0,
        aspect in 0.0f32..1.0,
        thin in -3.0f32..0.0,
        ratio in -4.0f32..5.0,
        water in any::<bool>(),
        shape in 0u8..3,
        dt in 1e-4f32..0.25,
        wind in prop::array::uniform3(-70.0f32..70.0),
        turn in prop::array::uniform4(-1.0f32..1.0),
        main in proptest::option::of(0usize..6),
        seed in any::<u64>(),
    ) {
        let chord = 10f32.powf(size);
        let length = chord * (1.0 + 4.0 * aspect);
        let thickness = (chord * 10f32.powf(thin)).max(Shape::MIN_SIZE);
        let fluid = if water { Fluid::WATER } else { Fluid::AIR };
        let density = fluid.density * (1.0 + 10f32.powf(ratio));
        let shape = match shape {
            0 => Shape::Disk { diameter: chord, thickness },
            1 => Shape::Rectangle { length, width: chord, thickness },
            _ => Shape::Ellipse { major: length, minor: chord, thickness },
        };
        let object = FallingObject {
            shape, density, fluid, seed,
            main_motion: main.map(PrimitiveMotion::from_index),
            ..FallingObject::default()
        };
        let model = FallModel::default();
        let rotation = Quat::from_array(turn);
        let mut path = match object.path(&model, release_from(Vec3::new(0.0, 10.0, 0.0), rotation)) {
            Ok(path) => path,
            Err(e) => {
                // Only a density past the documented maxima may be refused here.
                prop_assert_eq!(e.field(), "density");
                prop_assert!(density > 1.0e7 || density / fluid.density > Fluid::MAX_DENSITY_RATIO);
                return Ok(());
            }
        };
        for _ in 0..200 {
            path.advance(&model, dt, Vec3::from_array(wind), &tilt());
            let (p, q) = path.smoothed(0.5);
            prop_assert!(p.is_finite() && q.is_finite(), "{p:?} {q:?}");
            prop_assert!((q.length() - 1.0).abs() < 1e-3);
        }
    }
}

#[test]
fn drift_in_still_air_comes_to_rest_without_subnormals() {
    // Blown at 5 m/s, then in still air for 60 s: the drift the wind gave decays away and ends
    // exactly at rest, never lingering on subnormal values (which make every operation on them
    // a slow microcode assist, in every later step).
    let model = FallModel::default();
    let mut path = FallingObject::default()
        .path(
            &model,
            release_from(Vec3::new(0.0, 1.0e4, 0.0), Quat::IDENTITY),
        )
        .unwrap();
    for _ in 0..120 {
        path.advance(&model, DT, Vec3::new(5.0, 0.0, 0.0), &tilt());
    }
    assert!(path.drift().x > 1.0, "{}", path.drift());
    for step in 0..3600 {
        path.advance(&model, DT, Vec3::ZERO, &tilt());
        let d = path.drift().to_array();
        assert!(d.iter().all(|c| !c.is_subnormal()), "step {step}: {d:?}");
    }
    assert_eq!(path.drift(), Vec3::ZERO);
}

/// The continuity check over every preset in its own motions (`every_join_…` checks forced
/// motions of three objects): no step turns more than 30° and more than twice as far as either
/// step beside it, plus 3° (a spike; a tumble whose rate swings smoothly from 10° to 50° a step
/// within a half turn passes). Missed, by sampling rather than by a jump: what it still finds are
/// paper sheets tumbling a half turn in five frames and samaras fluttering a swing in four, whose
/// turn a frame swings from 10° to 75° within a half turn (watched four times as often they turn
/// smoothly: `no_fall_jumps_or_stops_dead_when_watched_four_times_as_often`).
#[test]
#[ignore = "missed: 59 of 768 falls: 13 paper sheets (steps of 58–71° beside steps of 17–33°, their tumble's own fastest: a half turn in five frames) and 46 samaras (steps of 69–78° beside steps of 31–36°: a swing in four frames)"]
fn no_step_turns_far_beyond_the_steps_around_it() {
    let spike = |t: &[f32]| t[1] > 30.0 && t[1] > 2.0 * t[0].max(t[2]) + 3.0;
    let (found, falls) = first_in_every_fall(600, DT, spike);
    assert!(
        found.is_empty(),
        "{} of {falls} falls: {found:#?}",
        found.len()
    );
}

/// A pop is a turn that happens at once, whatever the frame rate: watched four times as often
/// (240 steps a second), a fall that turns smoothly spreads each frame's turn over four steps of
/// about the same size, however fast it spins, while a jump of the orientation stays in one, and
/// so does a plate that stops dead. Every preset, 48 seeds, still and gusty air, 10 s: no step of
/// 1/240 s turns more than 10° and more than three times as far as either step beside it, plus
/// 1° (a jump); none turns less than a quarter of a step before it when the two before it both
/// turned more than 8° (a stop). (At 60 steps a second the fastest tumbles and flutters, a half
/// turn in five frames, are sampled too coarsely for such a check:
/// `no_step_turns_far_beyond_the_steps_around_it`.) It caught a card that tumbled from a
/// steady descent into a spiral: the second motion change, coming while the first still
/// blended, began from the tumble's own angle instead of the blended one shown, a jump of
/// 27–49° (8 of 256 falls on the first 16 seeds); and tumbles that stopped dead where a spiral began, from
/// 16–20° a step to under 5° (24 falls).
#[test]
fn no_fall_jumps_or_stops_dead_when_watched_four_times_as_often() {
    let jump = |t: &[f32]| t[1] > 10.0 && t[1] > 3.0 * t[0].max(t[2]) + 1.0;
    let stop = |t: &[f32]| t[0] > 8.0 && t[1] > 8.0 && t[2] < 0.25 * t[1];
    let (found, falls) = first_in_every_fall(2400, DT / 4.0, |t| jump(t) || stop(t));
    assert!(
        found.is_empty(),
        "{} of {falls} falls: {found:#?}",
        found.len()
    );
}

/// Every preset, 48 seeds, in still air and in gusty wind, `steps` steps of `dt`: for each fall
/// whose turns (degrees a step) have three in a row that `flagged` picks, the first of them, and
/// how many falls there were.
fn first_in_every_fall(
    steps: usize,
    dt: f32,
    flagged: impl Fn(&[f32]) -> bool,
) -> (Vec<String>, usize) {
    let model = FallModel::default();
    let wind = gusty_wind();
    let (mut found, mut falls) = (Vec::new(), 0);
    for preset in FallPreset::ALL {
        for seed in 0..48u64 {
            for (w, wind) in [None, Some(&wind)].into_iter().enumerate() {
                let object = FallingObject {
                    seed,
                    ..preset.object()
                };
                let (turns, _) = changes_every(&object, &model, wind, steps, false, dt);
                falls += 1;
                let first = turns
                    .windows(3)
                    .enumerate()
                    .find(|(_, t)| flagged(t))
                    .map(|(i, t)| (i + 1, [t[0], t[1], t[2]]));
                if let Some(first) = first {
                    found.push(format!("{preset:?} seed {seed} wind {w}: {first:?}"));
                }
            }
        }
    }
    (found, falls)
}
