//! Free fall: the eq. 4 ODE by four integrators and several steps; the trajectory database;
//! the paper's Fig. 15 objects from their stated sizes.

use bevy_windfall::freefall::Regime;
use std::hint::black_box;
use std::time::Instant;

use bevy_windfall::freefall::ode::{Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{Fluid, Shape, TrajectoryDatabase};

use super::plot::{Plot, Series};
use super::{Report, sci, seconds_per};

const DURATION: f64 = 2.0;
const METHODS: [Integrator; 4] = [
    Integrator::Euler,
    Integrator::Midpoint,
    Integrator::Rk4,
    Integrator::SemiImplicit,
];

fn start() -> OdeState {
    OdeState {
        theta: 0.3,
        v: -0.5,
        ..OdeState::default()
    }
}

/// Distance in (x, y) plus |Δθ|.
fn error(a: &OdeState, b: &OdeState) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2)).sqrt() + (a.theta - b.theta).abs()
}

fn end_of(params: &TanabeKaneko, dt: f64, method: Integrator) -> OdeState {
    *params
        .trajectory(start(), dt, DURATION, method)
        .expect("a valid step")
        .last()
        .expect("a trajectory")
}

pub fn report(r: &mut Report) {
    r.section(
        "Free fall: the eq. 4 ODE, error against run time",
        "The fluttering plate (`TanabeKaneko::FLUTTER`) for 2 s from θ = 0.3, v = −0.5 m/s. \
         Error: distance in (x, y) plus |Δθ| at 2 s against RK4 at dt = 1e-5 s. Time: µs of \
         wall time per simulated second.",
    );
    let params = TanabeKaneko::FLUTTER;
    let reference = end_of(&params, 1e-5, Integrator::Rk4);
    let steps: &[f64] = &[
        1.0 / 30.0,
        1.0 / 60.0,
        1.0 / 120.0,
        1.0 / 240.0,
        1.0 / 960.0,
    ];
    let mut rows = Vec::new();
    let mut series = Vec::new();
    for method in METHODS {
        let mut points = Vec::new();
        for &dt in steps {
            let e = error(&end_of(&params, dt, method), &reference);
            let repeats = if r.quick {
                1
            } else {
                (2000.0 * dt).clamp(1.0, 200.0) as usize * 5
            };
            let seconds = seconds_per(repeats, || {
                let _ = black_box(params.trajectory(black_box(start()), dt, DURATION, method));
            }) / DURATION;
            points.push((seconds * 1e6, e));
            rows.push(vec![
                format!("{method:?}"),
                format!("1/{:.0}", 1.0 / dt),
                sci(e),
                format!("{:.1}", seconds * 1e6),
            ]);
        }
        series.push(Series::new(format!("{method:?}"), points));
    }
    r.table(
        &[
            "integrator",
            "dt (s)",
            "error (m + rad)",
            "µs per simulated s",
        ],
        &rows,
    );
    r.figure(
        "freefall_ode",
        &Plot {
            title: "Eq. 4: error at 2 s against run time (dt = 1/30 … 1/960 s)",
            x_label: "µs per simulated second",
            y_label: "error (m + rad)",
            series,
        },
    );

    let begin = Instant::now();
    let db = TrajectoryDatabase::default();
    let build = begin.elapsed();
    r.section(
        "Free fall: trajectory database",
        &format!(
            "{} eq. 5 segments of {} samples in {} clusters, {:.1} KiB, built in \
             {:.1} ms.",
            db.segment_count(),
            db.tumble_shape().len(),
            db.cluster_count(),
            db.size_bytes() as f64 / 1024.0,
            build.as_secs_f64() * 1e3
        ),
    );

    r.section(
        "Free fall: the paper's Fig. 15 objects from their stated sizes",
        "Our Re and I* come from the sizes and densities; the paper's own values are quoted. In \
         air I* scales with ρ_s/ρ_f ≈ 500, so the paper's I* for the ellipse and the leaf cannot \
         come from the sizes it states (see the README).",
    );
    let ellipse = |major, minor, thickness| Shape::Ellipse {
        major,
        minor,
        thickness,
    };
    let coin = Shape::Disk {
        diameter: 0.02,
        thickness: 0.0015,
    };
    let mut rows = Vec::new();
    for (name, shape, density, fluid, paper) in [
        (
            "coin in water",
            coin,
            2700.0,
            Fluid::WATER,
            "Re 3.55e3, I* 1e-2, fluttering",
        ),
        (
            "paper ellipse in air",
            ellipse(0.08, 0.02, 1e-4),
            800.0,
            Fluid::AIR,
            "Re 6.8e3, I* 2.2e-3, spiral",
        ),
        (
            "leaf in air",
            ellipse(0.073, 0.042, 3e-4),
            500.0,
            Fluid::AIR,
            "Re 1.2e4, I* 6.3e-3, helix",
        ),
    ] {
        if let Ok(g) = Regime::new(&shape, density, &fluid, 9.81) {
            rows.push(vec![
                name.into(),
                format!("{density}"),
                sci(f64::from(g.reynolds)),
                sci(f64::from(g.inertia)),
                format!("{:.3}", g.descent_speed),
                format!("{:?}", g.main),
                paper.into(),
            ]);
        }
    }
    r.table(
        &[
            "object",
            "ρ_s (kg/m³)",
            "Re",
            "I*",
            "U (m/s)",
            "main motion",
            "paper",
        ],
        &rows,
    );
}
