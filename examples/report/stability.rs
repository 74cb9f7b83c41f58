//! The stability table: each stiff or extreme case the crate claims to handle, run here, with
//! its outcome, the largest value reached and the NaN count. Baselines that are expected to
//! fail are included to show the case is hard.

use std::f32::consts::PI;

use bevy::math::{Quat, Vec3};
use bevy_windfall::aero::{AeroCoefficients, Face, ParticleCloth, Pinning, PlateState, RigidPlate};
use bevy_windfall::cloth::{ClothAttachment, ClothGrid, ClothParams, ClothSim};
use bevy_windfall::freefall::ode::{Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{FallModel, FallPath, FallingObject, Shape, WindTilt};
use bevy_windfall::wind::{WindConfig, WindField};

use super::aero::{G, card};
use super::{Report, sci};

/// One row: largest value and NaN count over a run; `bound` decides the outcome.
struct Outcome {
    largest: f64,
    nans: usize,
}

impl Outcome {
    fn new() -> Self {
        Self {
            largest: 0.0,
            nans: 0,
        }
    }

    fn see(&mut self, value: f64) {
        if value.is_finite() {
            self.largest = self.largest.max(value);
        } else {
            self.nans += 1;
        }
    }

    fn row(&self, case: &str, method: &str, measure: &str, bound: f64) -> Vec<String> {
        let stable = self.nans == 0 && self.largest <= bound;
        vec![
            case.into(),
            method.into(),
            if stable { "stable" } else { "**blows up**" }.into(),
            format!("{measure} {} (bound {})", sci(self.largest), sci(bound)),
            self.nans.to_string(),
        ]
    }
}

pub fn report(r: &mut Report) {
    r.section(
        "Stability table",
        "Each stiff or extreme case, run here. Outcome: stable when no value is NaN and the \
         largest value stays within the physical bound given. Rows marked baseline are the \
         textbook method the crate replaces, shown failing.",
    );
    let mut rows = Vec::new();
    ode_rows(&mut rows);
    plate_rows(&mut rows);
    fall_rows(&mut rows);
    wind_rows(&mut rows);
    cloth_rows(&mut rows);
    r.table(
        &["case", "method", "outcome", "largest value", "NaN count"],
        &rows,
    );
}

fn ode_rows(rows: &mut Vec<Vec<String>>) {
    let stiff = TanabeKaneko {
        a_perp: 1.0e5,
        a_par: 2.0e4,
        ..TanabeKaneko::FLUTTER
    };
    let start = OdeState {
        theta: 0.5,
        u: 2.0,
        v: -3.0,
        ..OdeState::default()
    };
    let bound = start.speed().max(stiff.gravity / stiff.a_par);
    let case = "eq. 4, A⊥ = 1e5, A∥ = 2e4, dt = 0.25 s, 100 steps";
    for (method, name) in [
        (Some(Integrator::Rk4), "RK4 with stable substeps"),
        (Some(Integrator::SemiImplicit), "linearly implicit"),
        (None, "baseline: RK4, one step per dt"),
    ] {
        let mut s = start;
        let mut o = Outcome::new();
        for _ in 0..100 {
            s = match method {
                Some(m) => stiff.step(s, 0.25, m),
                None => stiff.single_step(&s, 0.25, Integrator::Rk4),
            };
            o.see(if s.is_finite() { s.speed() } else { f64::NAN });
        }
        rows.push(o.row(case, name, "speed m/s", bound * 1.001));
    }
}

fn plate_rows(rows: &mut Vec<Vec<String>>) {
    let card = card();
    // Drag rate ρ C_D A |v_rel| / m ≈ 140 1/s: 35 times past the explicit limit at this step.
    let gust = Vec3::new(20.0, 0.0, 0.0);
    let case = "card in a 20 m/s wind, dt = 0.25 s, 20 s";
    for implicit in [true, false] {
        let mut s = PlateState::default();
        let mut o = Outcome::new();
        for _ in 0..80 {
            if implicit {
                card.step(&mut s, 0.25, G, &|_| gust, false);
            } else {
                card.step_explicit(&mut s, 0.25, G, &|_| gust);
            }
            o.see(f64::from((s.velocity - gust).length()));
        }
        let name = if implicit {
            "implicit drag"
        } else {
            "baseline: explicit Euler"
        };
        // Relative to the wind it starts at 20 m/s and only gravity can add (g t over 20 s
        // would be 196 m/s; it settles near the 1.3 m/s terminal speed).
        rows.push(o.row(
            case,
            name,
            "speed relative to the wind, m/s",
            20.0 + 9.81 * 20.0,
        ));
    }
    // A 2 mm foil lighter than water with lift but no drag in a 20 m/s current.
    let foil = AeroCoefficients {
        drag: 0.0,
        lift: 1.6,
        density: 997.0,
    };
    let length = 0.00225;
    let plate = RigidPlate::rectangle(length, 0.6 * length, 0.01 * length, 50.0, foil, 2)
        .expect("valid foil");
    let u = Vec3::new(20.0, 0.0, 5.0);
    let mut s = PlateState {
        rotation: Quat::from_rotation_x(0.23),
        ..Default::default()
    };
    let mut o = Outcome::new();
    let dt = 0.089;
    let steps = 60;
    for _ in 0..steps {
        plate.step(&mut s, dt, G, &|_| u, false);
        o.see(f64::from((s.velocity - u).length()));
    }
    let bound = f64::from(u.length() + 9.81 * dt * steps as f32);
    rows.push(o.row(
        "2 mm foil, 50 kg/m³ in water, C_D = 0, C_L = 1.6, 20.6 m/s current, dt = 0.089 s",
        "implicit drag, lift limiter, wind-frame energy guard",
        "speed relative to the current, m/s",
        bound,
    ));
    // Degenerate faces: NaN and zero normals, zero area, next to one good face.
    let faces = vec![
        Face {
            center: Vec3::ZERO,
            normal: Vec3::NAN,
            area: 0.01,
        },
        Face {
            center: Vec3::X * 0.01,
            normal: Vec3::ZERO,
            area: 0.01,
        },
        Face {
            center: Vec3::Z * 0.01,
            normal: Vec3::Y,
            area: 0.0,
        },
        Face {
            center: Vec3::ZERO,
            normal: Vec3::Y * 3.0,
            area: 0.004,
        },
    ];
    let plate = RigidPlate::new(faces, 0.001, Vec3::splat(1e-6), AeroCoefficients::default())
        .expect("valid mass and inertia");
    let mut s = PlateState::default();
    let mut o = Outcome::new();
    for _ in 0..200 {
        plate.step(&mut s, 0.25, G, &|_| Vec3::new(70.0, 0.0, 0.0), false);
        o.see(f64::from(s.velocity.length()));
    }
    rows.push(o.row(
        "degenerate faces (NaN, zero normal, zero area) in a 70 m/s gale, dt = 0.25 s",
        "faces that exert no force dropped",
        "speed m/s",
        70.0 + 9.81 * 50.0,
    ));
}

fn fall_rows(rows: &mut Vec<Vec<String>>) {
    let model = FallModel::default();
    let tilt = WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    };
    let feather = FallingObject {
        shape: Shape::Disk {
            diameter: 0.002,
            thickness: 1e-5,
        },
        density: 1.3,
        ..Default::default()
    };
    for (case, object, wind, dt) in [
        (
            "leaf in a 70 m/s gale, dt = 0.25 s, 200 steps",
            FallingObject::default(),
            70.0,
            0.25,
        ),
        (
            "2 mm feather-light disk (1.3 kg/m³ in air), dt = 0.25 s",
            feather,
            10.0,
            0.25,
        ),
    ] {
        let regime = object.regime().expect("valid object");
        let start = Vec3::new(0.0, 1e5, 0.0);
        let mut path = FallPath::new(&model, object.scales(&regime), regime.main, 3, start, 0.0)
            .expect("a release within bounds");
        let u = Vec3::new(wind, 0.0, 0.0);
        let mut o = Outcome::new();
        let mut last = start;
        for _ in 0..200 {
            path.advance(&model, dt, u, &tilt);
            let (p, q) = path.smoothed(1.0);
            let moved = f64::from(p.distance(last)) / f64::from(dt);
            o.see(if q.is_finite() { moved } else { f64::NAN });
            last = p;
        }
        let bound = f64::from(wind + 20.0 * regime.descent_speed);
        rows.push(o.row(case, "FallPath (synthesis)", "speed m/s", bound));
    }
    let balloon = FallingObject {
        density: 0.5,
        ..Default::default()
    };
    let refused = match balloon.regime() {
        Err(e) => format!("refused: `{}` ({e})", e.field()),
        Ok(_) => "**accepted**".into(),
    };
    rows.push(vec![
        "leaf lighter than air (0.5 kg/m³)".into(),
        "FallingObject::regime".into(),
        refused,
        "–".into(),
        "0".into(),
    ]);
}

fn wind_rows(rows: &mut Vec<Vec<String>>) {
    for (case, config) in [
        (
            "wind 1e4 m/s (the accepted maximum)",
            WindConfig {
                reference_speed: 1e4,
                ..Default::default()
            },
        ),
        (
            "β = 0 (white noise)",
            WindConfig {
                beta: 0.0,
                ..Default::default()
            },
        ),
        (
            "β = 5",
            WindConfig {
                beta: 5.0,
                ..Default::default()
            },
        ),
    ] {
        let speed = config.reference_speed;
        let wind = WindField::new(config).expect("valid wind");
        let mut o = Outcome::new();
        for i in 0..20_000 {
            let p = Vec3::new((i % 200) as f32 * 0.9, 0.5 + (i / 200) as f32 * 0.3, 3.0);
            o.see(f64::from(wind.velocity_at(p, i as f32 * 0.01).length()));
        }
        // Mean at the highest probe plus 12 σ there.
        let top = wind.mean_speed_at(30.5);
        let bound = f64::from(top + 12.0 * wind.sigma().length() * (top / speed).max(1.0));
        rows.push(o.row(
            case,
            "WindField sampling, 20 000 points",
            "wind speed, m/s",
            bound,
        ));
    }
}

fn cloth_rows(rows: &mut Vec<Vec<String>>) {
    let grid = ClothGrid {
        rows: 16,
        columns: 24,
        width: 1.5,
        height: 1.0,
    };
    let params = ClothParams {
        amplitude: PI,
        wind_steps_per_frame: 50.0,
        swirl: 50.0,
        ..ClothParams::default()
    };
    let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).expect("valid cloth");
    let mut o = Outcome::new();
    for _ in 0..200 {
        sim.advance(0.25, 50.0);
        sim.rebuild();
        let p = sim.positions();
        for (a, b) in p.iter().zip(&p[grid.columns..]) {
            o.see(f64::from(a.distance(*b)));
        }
    }
    let bound = f64::from(grid.row_spacing() * params.max_stretch) * (1.0 + 1e-5);
    rows.push(o.row(
        "flag, θ = π, shifts along and across 50 per frame, dt = 0.25 s",
        "P-descriptor with eq. 7",
        "yarn gap m",
        bound,
    ));
    let mut cloth =
        ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
            .expect("valid cloth");
    let mut o = Outcome::new();
    for _ in 0..200 {
        cloth.step(0.25, G, &|_| Vec3::new(70.0, 0.0, 0.0));
        for p in cloth.positions() {
            o.see(f64::from(p.distance(cloth.positions()[0])));
        }
    }
    rows.push(o.row(
        "particle flag in a 70 m/s gale, dt = 0.25 s",
        "4 ms ticks, implicit normal pressure, yarns solved together, attachments",
        "reach from the pin m",
        f64::from(grid.width + grid.height),
    ));
}
