//! Cloth: harmonics kept by the descriptor's low-pass filter against shape error and run time;
//! grid size against run time.

use std::hint::black_box;

use bevy_windfall::cloth::{
    ClothAttachment, ClothGrid, ClothParams, ClothPreset, ClothSim, HarmonicFilter, cloth_mesh,
    write_cloth_mesh,
};

use super::plot::{Plot, Series};
use super::{Report, sci, seconds_per};

const FRAMES: usize = 50;
const DT: f32 = 1.0 / 64.0;

/// Mean seconds per frame (advance, rebuild, mesh write).
fn seconds_per_frame(sim: &mut ClothSim, repeats: usize) -> f64 {
    let g = *sim.grid();
    let mut mesh = cloth_mesh(g.rows, g.columns, sim.positions());
    let speed = sim.params().wind_speed;
    seconds_per(FRAMES * repeats, || {
        sim.advance(DT, speed);
        sim.rebuild();
        write_cloth_mesh(&mut mesh, g.rows, g.columns, black_box(sim.positions()));
    })
}

pub fn report(r: &mut Report) {
    r.section(
        "Cloth: harmonics kept against shape error and run time (64 × 64)",
        "The flag preset (Table 1, gentle, frozen) with its descriptor low-pass filtered to the \
         first harmonics. Shape error: RMS distance between the nodes of the filtered cloth and \
         the unfiltered one, as a fraction of the yarn length, averaged over 50 frames. Time: \
         one frame (advance, rebuild, mesh write).",
    );
    let grid = ClothGrid {
        rows: 64,
        columns: 64,
        width: 1.5,
        height: 1.0,
    };
    let base = ClothPreset::FlagGentleFrozen.params();
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
                s.advance(DT, base.wind_speed);
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
        let time = seconds_per_frame(&mut sim, repeats);
        let label = match filter {
            HarmonicFilter::LowPass { max } => format!("1..={max}"),
            _ => "all (no filter, no FFT)".into(),
        };
        if matches!(filter, HarmonicFilter::LowPass { .. }) {
            points.push((time * 1e6, error));
        }
        rows.push(vec![label, sci(error), format!("{:.1}", time * 1e6)]);
    }
    r.table(
        &[
            "harmonics kept",
            "RMS shape error (of yarn length)",
            "µs per frame",
        ],
        &rows,
    );
    r.figure(
        "cloth_harmonics",
        &Plot {
            title: "Cloth 64×64: shape error against µs per frame (1 … 31 harmonics)",
            x_label: "µs per frame",
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
        let non_frozen = ClothPreset::FlagGentleNonFrozen.params();
        let mut a = ClothSim::new(grid, base, ClothAttachment::Pole).expect("valid cloth");
        let mut b = ClothSim::new(grid, non_frozen, ClothAttachment::Pole).expect("valid cloth");
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
