//! Cloth: how every Table 1 row flaps (bend, swing, frequency); the procedural flag against the
//! physical one; harmonics kept by the descriptor's low-pass filter against shape error and
//! build time; grid size against run time.

use bevy_windfall::cloth::mesh;
use std::hint::black_box;
use std::time::Instant;

use bevy::math::Vec3;
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning};
use bevy_windfall::cloth::{
    ClothAttachment, ClothGrid, ClothParams, ClothPreset, ClothSim, FlapRecorder, FlapStats,
    HarmonicFilter,
};

use super::plot::{Plot, Series};
use super::{Report, sci, seconds_per};

const FRAMES: usize = 50;
const DT: f32 = 1.0 / 64.0;

/// Mean seconds per frame (advance, rebuild, mesh write).
fn seconds_per_frame(sim: &mut ClothSim, repeats: usize) -> f64 {
    let g = *sim.grid();
    let mut mesh = mesh::build(g.rows, g.columns, sim.positions());
    let speed = sim.params().wind_steps_per_frame;
    seconds_per(FRAMES * repeats, || {
        sim.advance(DT, speed);
        sim.rebuild();
        mesh::write(&mut mesh, g.rows, g.columns, black_box(sim.positions()));
    })
}

/// A procedural cloth flapping for `seconds` at 50 fps.
fn procedural(grid: ClothGrid, params: ClothParams, steps: f32, seconds: f32) -> FlapStats {
    let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).expect("valid cloth");
    let mut recorder = FlapRecorder::new(grid.rows, grid.columns, grid.width, 0.02);
    for _ in 0..(seconds * 50.0) as usize {
        sim.advance(0.02, steps);
        sim.rebuild();
        recorder.record(sim.positions());
    }
    recorder.finish()
}

/// The particle flag (its default 4 ms ticks, the face law's pressure along the normal, 0.15 kg/m²) in a uniform wind, after 2 s
/// of settling, and its mean drag over the free-flag drag of AS/NZS 1170.2 Appendix F,
/// C = 0.05 + 0.7 (m / (ρ c)) (A / c²)^−1.25 on ½ ρ U² A.
fn physical(grid: ClothGrid, speed: f32, seconds: f32) -> (FlapStats, f32) {
    let mut cloth =
        ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
            .expect("valid cloth");
    let wind = Vec3::new(speed, 0.0, 0.0);
    let mut recorder = FlapRecorder::new(grid.rows, grid.columns, grid.width, 0.02);
    let (mut drag, mut frames) = (0.0f32, 0);
    for i in 0..((seconds + 2.0) * 50.0) as usize {
        cloth.step(0.02, Vec3::new(0.0, -9.81, 0.0), &|_| wind);
        if i >= 100 {
            recorder.record(cloth.positions());
            drag += cloth.aerodynamic_force().x;
            frames += 1;
        }
    }
    let (rho, c, area) = (
        AeroCoefficients::AIR_DENSITY,
        grid.height,
        grid.width * grid.height,
    );
    let code = 0.05 + 0.7 * (0.15 / (rho * c)) * (area / (c * c)).powf(-1.25);
    let expected = code * 0.5 * rho * speed * speed * area;
    (recorder.finish(), drag / frames.max(1) as f32 / expected)
}

pub fn report(r: &mut Report) {
    flapping(r);
    procedural_against_physical(r);
    r.section(
        "Cloth: harmonics kept against shape error and build time (64 × 64)",
        "The flag preset (Table 1, gentle, frozen) with its descriptor low-pass filtered to the \
         first harmonics (of the noise line, five yarns long). Shape error: RMS distance between \
         the nodes of the filtered cloth and the unfiltered one, as a fraction of the yarn \
         length, averaged over 50 frames. The descriptor runs once per noise line when the \
         cloth is built, so the filter costs build time (shown), not frame time.",
    );
    let grid = ClothGrid {
        rows: 64,
        columns: 64,
        width: 1.5,
        height: 1.0,
    };
    let base = ClothPreset::FlagFlappingFrozen.params();
    let repeats = if r.quick { 1 } else { 4 };
    let mut rows = Vec::new();
    let mut points = Vec::new();
    let filters = [1usize, 2, 3, 5, 8, 12, 16, 24, 31]
        .map(|max| HarmonicFilter::LowPass { max })
        .into_iter()
        .chain([HarmonicFilter::All]);
    for filter in filters {
        let params = ClothParams { filter, ..base };
        let exact = ClothParams {
            filter: HarmonicFilter::All,
            ..base
        };
        let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).expect("valid cloth");
        let mut truth = ClothSim::new(grid, exact, ClothAttachment::Pole).expect("valid cloth");
        let mut error = 0.0f64;
        for _ in 0..FRAMES {
            for s in [&mut sim, &mut truth] {
                s.advance(DT, base.wind_steps_per_frame);
                s.rebuild();
            }
            let sq: f64 = sim
                .positions()
                .iter()
                .zip(truth.positions())
                .map(|(a, b)| f64::from(a.distance_squared(*b)))
                .sum();
            error += (sq / sim.positions().len() as f64).sqrt() / f64::from(grid.width);
        }
        let error = error / FRAMES as f64;
        let begin = Instant::now();
        for _ in 0..repeats {
            black_box(ClothSim::new(grid, params, ClothAttachment::Pole).expect("valid cloth"));
        }
        let time = begin.elapsed().as_secs_f64() / repeats as f64;
        let label = match filter {
            HarmonicFilter::LowPass { max } => format!("1..={max}"),
            _ => "all (no filter)".into(),
        };
        if let HarmonicFilter::LowPass { max } = filter {
            points.push((max as f64, error));
        }
        rows.push(vec![label, sci(error), format!("{:.2}", time * 1e3)]);
    }
    r.table(
        &[
            "harmonics kept",
            "RMS shape error (of yarn length)",
            "build ms",
        ],
        &rows,
    );
    r.figure(
        "cloth_harmonics",
        &Plot {
            title: "Cloth 64×64: shape error against harmonics kept",
            x_label: "harmonics kept (of the noise line)",
            y_label: "RMS shape error / yarn length",
            series: vec![Series::new("low-pass descriptor", points)],
        },
    );

    r.section("Cloth: grid size against run time", "");
    let mut rows = Vec::new();
    let sizes: &[usize] = if r.quick {
        &[8, 16, 32]
    } else {
        &[8, 16, 32, 64, 128, 256]
    };
    for &size in sizes {
        let grid = ClothGrid {
            rows: size,
            columns: size,
            ..grid
        };
        let evolving = ClothPreset::FlagFlappingEvolving.params();
        let mut a = ClothSim::new(grid, base, ClothAttachment::Pole).expect("valid cloth");
        let mut b = ClothSim::new(grid, evolving, ClothAttachment::Pole).expect("valid cloth");
        let repeats = if r.quick {
            1
        } else {
            (4096 / (size * size)).clamp(1, 64)
        };
        let (ta, tb) = (
            seconds_per_frame(&mut a, repeats),
            seconds_per_frame(&mut b, repeats),
        );
        rows.push(vec![
            format!("{size}×{size}"),
            format!("{:.1}", ta * 1e6),
            format!("{:.1}", tb * 1e6),
            format!("{:.1}", ta * 1e9 / (size * size) as f64),
        ]);
    }
    r.table(
        &[
            "grid",
            "frozen µs per frame",
            "non-frozen µs per frame",
            "ns per node (frozen)",
        ],
        &rows,
    );
}

/// Every Table 1 row on the grid: how much it bends, how far its free edge swings, how
/// fast it flaps.
fn flapping(r: &mut Report) {
    let seconds = if r.quick { 2.0 } else { 20.0 };
    r.section(
        "Cloth: how every Table 1 row flaps",
        &format!(
            "24 yarns of 36 nodes, 1.5 × 1 m on a pole, {seconds} s at 50 fps, each row at its \
             own |v| (U: the wind speed that moves the noise at |v|, waves at the wind's \
             speed). Bend: RMS distance of the nodes from the straight line pole → free edge; \
             swing: time standard deviation of the free edge's out-of-plane offset; both over \
             the yarn length L. f: dominant flapping frequency of the middle yarn's free edge; \
             A: its peak-to-peak amplitude; St = f A / U. The paper calls every flag and banner \
             row flapping (or fluttering); the test asks bend ≥ 4 % and swing ≤ 35 % of them."
        ),
    );
    let grid = ClothGrid {
        rows: 24,
        columns: 36,
        width: 1.5,
        height: 1.0,
    };
    let mut rows = Vec::new();
    for preset in ClothPreset::ALL {
        let params = preset.params();
        let stats = procedural(grid, params, params.wind_steps_per_frame, seconds);
        let u = ClothSim::speed_of_steps(params.wind_steps_per_frame, grid.width);
        rows.push(vec![
            format!("{preset:?}"),
            preset.observation().into(),
            format!("{}", params.wind_steps_per_frame),
            format!("{u:.1}"),
            format!("{:.3}", stats.bend),
            format!("{:.3}", stats.swing),
            format!("{:.2}", stats.frequency),
            format!("{:.2}", stats.amplitude),
            format!("{:.2}", stats.strouhal(grid.width, u)),
        ]);
    }
    r.table(
        &[
            "row",
            "paper's observation",
            "|v|",
            "U (m/s)",
            "bend / L",
            "swing / L",
            "f (Hz)",
            "A / L",
            "St = f A / U",
        ],
        &rows,
    );
}

/// The P-descriptor flag and the particle flag in the same uniform wind.
fn procedural_against_physical(r: &mut Report) {
    let seconds = if r.quick { 2.0 } else { 20.0 };
    r.section(
        "Cloth: the procedural flag against the physical flag",
        &format!(
            "A 1.5 × 1 m flag, 16 yarns of 24 nodes, in a uniform wind for {seconds} s at 50 fps: \
             the P-descriptor `ClothSim` (Table 1's gentle frozen flag, |v| from the wind) and the \
             `ParticleCloth` (4 ms ticks, implicit pressure along the normal, 0.15 kg/m², after 2 s of settling). \
             Literature for flags: waves travel at about the wind speed (Alben, simulations of \
             light flags; Raynaud & Mulleners 2026, 48 paper flags in a wind tunnel), with a \
             wavelength of about 1.9 L (Raynaud & Mulleners), so f L / U ≈ 0.5; flapping sheets \
             have St = f A / U of 0.2–0.4 with A peak-to-peak (Shelley, Vandenberghe & Zhang \
             2005, heavy flags in water), the range of swimming and flying animals (Eloy 2012). \
             These are the ranges we could check; we found no measured A / L for cloth flags \
             in air. The physical flag's drag is given as a share of the free-flag drag of \
             AS/NZS 1170.2 Appendix F (about C = 0.10 for this flag); `tests/physical_flag.rs` \
             checks these numbers at 16 and 32 rows."
        ),
    );
    let grid = ClothGrid {
        rows: 16,
        columns: 24,
        width: 1.5,
        height: 1.0,
    };
    let params = ClothPreset::FlagFlappingFrozen.params();
    let mut rows = Vec::new();
    for speed in [4.0f32, 8.0, 12.0] {
        let steps = ClothSim::steps_for_speed(speed, grid.width);
        let (physical, drag) = physical(grid, speed, seconds);
        for (name, stats, drag) in [
            (
                "procedural",
                procedural(grid, params, steps, seconds),
                "".into(),
            ),
            ("physical", physical, format!("{drag:.2}")),
        ] {
            rows.push(vec![
                format!("{speed}"),
                name.into(),
                format!("{:.2}", stats.amplitude),
                format!("{:.2}", stats.frequency),
                format!("{:.2}", stats.frequency * grid.width / speed),
                format!("{:.2}", stats.strouhal(grid.width, speed)),
                format!("{:.3}", stats.bend),
                format!("{:.2}", stats.wave_speed / speed),
                drag,
            ]);
        }
    }
    r.table(
        &[
            "U (m/s)",
            "flag",
            "A / L (peak-to-peak)",
            "f (Hz)",
            "f L / U",
            "St = f A / U",
            "bend / L",
            "waves / U",
            "drag / AS/NZS",
        ],
        &rows,
    );
}
