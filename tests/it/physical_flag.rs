//! The physical flag flaps as flags do: a 1.5 m × 1 m particle flag of 0.15 kg/m² on a pole in
//! a uniform wind of 4, 8 and 12 m/s, at 16 × 24 and 32 × 48 nodes, 50 steps a second, measured
//! over 20 s after 2 s of settling, against the flapping-flag literature (Shelley & Zhang 2011;
//! Taneda 1968; Eloy et al. 2008; Raynaud & Mulleners 2026) and the free-flag drag of AS/NZS
//! 1170.2 Appendix F.

use std::sync::LazyLock;

use bevy::math::Vec3;
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning};
use bevy_windfall::cloth::{ClothGrid, FlapRecorder, FlapStats};

const WIDTH: f32 = 1.5;
const HEIGHT: f32 = 1.0;
const AREAL_DENSITY: f32 = 0.15;
const DT: f32 = 0.02;
const SPEEDS: [f32; 3] = [4.0, 8.0, 12.0];
const GRIDS: [(usize, usize); 2] = [(16, 24), (32, 48)];

/// One run: the flapping statistics and the mean drag, N.
struct Run {
    rows: usize,
    speed: f32,
    stats: FlapStats,
    drag: f32,
}

fn run(rows: usize, columns: usize, speed: f32) -> Run {
    run_in(rows, columns, speed, Vec3::new(0.0, -9.81, 0.0))
}

fn run_in(rows: usize, columns: usize, speed: f32, gravity: Vec3) -> Run {
    let grid = ClothGrid {
        rows,
        columns,
        width: WIDTH,
        height: HEIGHT,
    };
    let mut cloth = ParticleCloth::new(
        grid,
        AREAL_DENSITY,
        AeroCoefficients::default(),
        Pinning::PoleColumn,
    )
    .unwrap();
    let wind = Vec3::new(speed, 0.0, 0.0);
    for _ in 0..100 {
        cloth.step(DT, gravity, &|_| wind);
    }
    let mut recorder = FlapRecorder::new(rows, columns, WIDTH, DT);
    let mut drag = 0.0f64;
    let steps = 1000;
    for _ in 0..steps {
        cloth.step(DT, gravity, &|_| wind);
        assert!(cloth.positions().iter().all(|p| p.is_finite()));
        recorder.record(cloth.positions());
        drag += f64::from(cloth.aerodynamic_force().x);
    }
    Run {
        rows,
        speed,
        stats: recorder.finish(),
        drag: (drag / f64::from(steps)) as f32,
    }
}

/// Every grid at every speed, run once for all the tests (in parallel).
static RUNS: LazyLock<Vec<Run>> = LazyLock::new(|| {
    std::thread::scope(|scope| {
        let handles: Vec<_> = GRIDS
            .iter()
            .flat_map(|&(rows, columns)| {
                SPEEDS.map(|speed| scope.spawn(move || run(rows, columns, speed)))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    })
});

fn describe(r: &Run) -> String {
    let s = &r.stats;
    format!(
        "{} rows at {} m/s: bend {:.3} L, f {:.2} Hz, A {:.3} L, f A / U {:.3}, waves {:.2} U, λ {:.2} L, drag {:.2} N",
        r.rows,
        r.speed,
        s.bend,
        s.frequency,
        s.amplitude,
        s.strouhal(WIDTH, r.speed),
        s.wave_speed / r.speed,
        s.wave_speed / s.frequency / WIDTH,
        r.drag
    )
}

#[test]
fn the_flag_bends_into_waves_not_a_board() {
    for r in RUNS.iter() {
        println!("{}", describe(r));
        assert!(r.stats.bend >= 0.04, "{}", describe(r));
    }
}

#[test]
fn it_flaps_at_the_strouhal_number_of_flags_and_swimmers() {
    for r in RUNS.iter() {
        let st = r.stats.strouhal(WIDTH, r.speed);
        assert!((0.1..=0.4).contains(&st), "{}", describe(r));
    }
}

#[test]
fn waves_run_from_the_pole_to_the_free_edge_at_about_the_wind_speed() {
    for r in RUNS.iter() {
        let c = r.stats.wave_speed / r.speed;
        assert!((0.5..=1.0).contains(&c), "{}", describe(r));
    }
}

#[test]
fn it_flaps_faster_and_wider_in_stronger_wind_once_gravity_is_small() {
    for &(rows, _) in &GRIDS {
        let runs: Vec<&Run> = RUNS.iter().filter(|r| r.rows == rows).collect();
        for pair in runs.windows(2) {
            let (slow, fast) = (pair[0], pair[1]);
            assert!(
                fast.stats.frequency > slow.stats.frequency,
                "{}\n{}",
                describe(slow),
                describe(fast)
            );
        }
        // From 8 to 12 m/s gravity's share falls (g L / U² from 0.23 to 0.10) and the swing
        // widens. At 4 m/s the flag droops and its tip's swing depends on the grid (wider than at
        // 8 m/s at 16 rows, as wide at 32): not asserted.
        let (eight, twelve) = (runs[1], runs[2]);
        assert!(
            twelve.stats.amplitude > eight.stats.amplitude,
            "{}\n{}",
            describe(eight),
            describe(twelve)
        );
    }
}

#[test]
fn without_gravity_its_motion_scales_with_the_wind() {
    // With the face law's forces quadratic in the wind and the fabric's bending negligible
    // (B / (ρ U² L³) ~ 1e-6 for flag cloth), a weightless flag has no length or time scale of its
    // own but L / U: doubling the wind doubles the frequency and the drag fourfold and leaves the
    // shape (A / L) as it was. So the swing can grow with the wind only through the flag's
    // weight (g L / U²); a check that the solver, whose step and substeps do not scale with
    // U, keeps the model's similarity.
    let [slow, fast] =
        [4.0, 8.0].map(|speed| std::thread::spawn(move || run_in(16, 24, speed, Vec3::ZERO)));
    let (slow, fast) = (slow.join().unwrap(), fast.join().unwrap());
    let (a, b) = (&slow.stats, &fast.stats);
    let report = format!("{}\n{}", describe(&slow), describe(&fast));
    println!("{report}");
    assert!(
        (1.8..=2.2).contains(&(b.frequency / a.frequency)),
        "{report}"
    );
    assert!(
        (0.85..=1.15).contains(&(b.amplitude / a.amplitude)),
        "{report}"
    );
    assert!((3.4..=4.6).contains(&(fast.drag / slow.drag)), "{report}");
}

#[test]
fn its_waves_are_about_twice_its_length() {
    // Raynaud & Mulleners (2026), 48 paper flags of several aspect and mass ratios: the waves'
    // length λ = c / f is 1.87 L, nearly whatever the flag. Where gravity is small (8 and
    // 12 m/s); at 4 m/s the drooping flag's waves are longer (2.3–2.4 L).
    for r in RUNS.iter().filter(|r| r.speed >= 8.0) {
        let wavelength = r.stats.wave_speed / r.stats.frequency / WIDTH;
        assert!(
            (1.4..=2.4).contains(&wavelength),
            "{}: λ = {wavelength:.2} L",
            describe(r)
        );
    }
}

#[test]
fn its_drag_is_the_free_flag_drag_of_the_wind_code() {
    // AS/NZS 1170.2 Appendix F: C = 0.05 + 0.7 (m / (ρ c)) (A / c²)^−1.25 on ½ ρ U² A, with m
    // the mass per area, c the flag's height and A its area: about 0.10 here.
    let rho = AeroCoefficients::AIR_DENSITY;
    let area = WIDTH * HEIGHT;
    let c = 0.05 + 0.7 * (AREAL_DENSITY / (rho * HEIGHT)) * (area / (HEIGHT * HEIGHT)).powf(-1.25);
    assert!((c - 0.103).abs() < 0.005, "{c}");
    // Within ±35 % (measured: 0.72–1.07 of it; without the added mass of air it was
    // 0.58–0.82, with lift smoothed over a tenth of the span too 0.47–0.73).
    for r in RUNS.iter() {
        let expected = c * 0.5 * rho * r.speed * r.speed * area;
        let ratio = r.drag / expected;
        assert!(
            (0.65..=1.35).contains(&ratio),
            "{}: {ratio:.2} of the code's {expected:.2} N",
            describe(r)
        );
    }
}
