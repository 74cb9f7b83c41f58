//! Error against run time for free fall: the eq. 4 ODE by four integrators and several steps,
//! the stiff case, and the trajectory database's build time and size. Prints Markdown tables.
//! `cargo run --release --example freefall_report`
//!
//! ODE error: distance in (x, y) plus |Δθ| after 2 s of the fluttering plate
//! ([`TanabeKaneko::FLUTTER`]) against RK4 at dt = 1e-5 s.

use std::hint::black_box;
use std::time::Instant;

use bevy_windfall::freefall::ode::{self, Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{FallModel, FallingObject, TrajectoryDatabase, regime};

const DURATION: f64 = 2.0;

fn start() -> OdeState {
    OdeState {
        theta: 0.3,
        v: -0.5,
        ..OdeState::default()
    }
}

fn error(a: &OdeState, b: &OdeState) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2)).sqrt() + (a.theta - b.theta).abs()
}

/// Final state and mean wall time per simulated second.
fn run(params: &TanabeKaneko, dt: f64, method: Integrator) -> (OdeState, f64) {
    let repeats = (2000.0 * dt).clamp(1.0, 200.0) as usize * 5;
    let begin = Instant::now();
    let mut last = start();
    for _ in 0..repeats {
        last = *ode::trajectory(params, black_box(start()), dt, DURATION, method)
            .last()
            .unwrap_or(&last);
    }
    let seconds = begin.elapsed().as_secs_f64() / repeats as f64 / DURATION;
    (last, seconds)
}

fn main() {
    let params = TanabeKaneko::FLUTTER;
    let reference = *ode::trajectory(&params, start(), 1e-5, DURATION, Integrator::Rk4)
        .last()
        .expect("a trajectory");
    println!("## Eq. 4 (fluttering plate, 2 s): error against run time (release)\n");
    println!("| integrator | dt (s) | error (m + rad) | µs per simulated s |");
    println!("|---|---|---|---|");
    for method in [
        Integrator::Euler,
        Integrator::Midpoint,
        Integrator::Rk4,
        Integrator::SemiImplicit,
    ] {
        for dt in [
            1.0 / 30.0,
            1.0 / 60.0,
            1.0 / 120.0,
            1.0 / 240.0,
            1.0 / 960.0,
        ] {
            let (state, seconds) = run(&params, dt, method);
            println!(
                "| {method:?} | 1/{:.0} | {:.2e} | {:.1} |",
                1.0 / dt,
                error(&state, &reference),
                seconds * 1e6
            );
        }
    }

    println!("\n## Stiff eq. 4: A⊥ = 1e5, A∥ = 2e4, dt = 0.25 s, 100 steps\n");
    println!("| integrator | finite | final speed (m/s) | g / A∥ (m/s) |");
    println!("|---|---|---|---|");
    let stiff = TanabeKaneko {
        a_perp: 1.0e5,
        a_par: 2.0e4,
        ..TanabeKaneko::FLUTTER
    };
    for method in [Integrator::Rk4, Integrator::SemiImplicit] {
        let mut s = OdeState {
            theta: 0.5,
            u: 2.0,
            v: -3.0,
            ..OdeState::default()
        };
        for _ in 0..100 {
            s = ode::step(&stiff, s, 0.25, method);
        }
        println!(
            "| {method:?} (with substeps) | {} | {:.2e} | {:.2e} |",
            s.is_finite(),
            s.speed(),
            stiff.gravity / stiff.a_par
        );
    }
    let mut raw = OdeState {
        theta: 0.5,
        u: 2.0,
        v: -3.0,
        ..OdeState::default()
    };
    for _ in 0..20 {
        raw = ode::single_step(&stiff, &raw, 0.25, Integrator::Rk4);
    }
    println!(
        "| Rk4, one step of 0.25 s (no substeps), 20 steps | {} | {:.2e} | |",
        raw.is_finite(),
        raw.speed()
    );

    println!("\n## Trajectory database\n");
    let begin = Instant::now();
    let db = TrajectoryDatabase::default();
    let build = begin.elapsed();
    println!(
        "{} segments of {} samples in {} clusters, {:.1} KiB, built in {:.1} ms",
        db.segments().len(),
        bevy_windfall::freefall::SEGMENT_SAMPLES,
        db.centroids().len(),
        db.size_bytes() as f64 / 1024.0,
        build.as_secs_f64() * 1e3
    );
    let model = FallModel::new(db, Default::default());
    black_box(&model);

    println!("\n## Objects of the paper's Fig. 15 from their stated sizes\n");
    println!("| object | ρ_s (kg/m³) | Re | I* | U (m/s) | main motion | paper |");
    println!("|---|---|---|---|---|---|---|");
    let coin = FallingObject {
        shape: bevy_windfall::freefall::Shape::Disk {
            diameter: 0.02,
            thickness: 0.0015,
        },
        density: 2700.0,
        fluid: bevy_windfall::freefall::Fluid::WATER,
        ..Default::default()
    };
    let paper = bevy_windfall::freefall::Shape::Ellipse {
        major: 0.08,
        minor: 0.02,
        thickness: 1e-4,
    };
    let leaf = bevy_windfall::freefall::Shape::Ellipse {
        major: 0.073,
        minor: 0.042,
        thickness: 3e-4,
    };
    let air = bevy_windfall::freefall::Fluid::AIR;
    for (name, shape, density, fluid, paper_says) in [
        (
            "coin in water",
            coin.shape,
            2700.0,
            coin.fluid,
            "Re 3.55e3, I* 1e-2, fluttering",
        ),
        (
            "paper ellipse in air",
            paper,
            800.0,
            air,
            "Re 6.8e3, I* 2.2e-3, spiral",
        ),
        (
            "leaf in air",
            leaf,
            500.0,
            air,
            "Re 1.2e4, I* 6.3e-3, helix",
        ),
    ] {
        if let Ok(r) = regime(&shape, density, &fluid, 9.81) {
            println!(
                "| {name} | {density} | {:.2e} | {:.2e} | {:.3} | {:?} | {paper_says} |",
                r.reynolds, r.inertia, r.descent_speed, r.main
            );
        }
    }
}
