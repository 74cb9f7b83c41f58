//! Error against run time for the cloth: harmonics kept by the descriptor's low-pass filter
//! against the shape error and the cost of a frame, and grid size against the cost of a frame.
//! Prints Markdown tables. `cargo run --release --example cloth_report`
//!
//! Shape error: RMS distance between the nodes of the filtered cloth and the unfiltered one
//! (every harmonic kept), as a fraction of the yarn length, averaged over 50 frames.

use std::hint::black_box;
use std::time::Instant;

use bevy_windfall::cloth::{
    ClothAttachment, ClothGrid, ClothPreset, ClothSim, HarmonicFilter, cloth_mesh, write_cloth_mesh,
};

const FRAMES: usize = 50;
const DT: f32 = 1.0 / 64.0;

/// Mean seconds per frame (advance, rebuild, mesh write) over `FRAMES × repeats` frames.
fn seconds_per_frame(sim: &mut ClothSim, repeats: usize) -> f64 {
    let g = *sim.grid();
    let mut mesh = cloth_mesh(g.rows, g.columns, sim.positions());
    let speed = sim.params().wind_speed;
    let start = Instant::now();
    for _ in 0..FRAMES * repeats {
        sim.advance(DT, speed);
        sim.rebuild();
        write_cloth_mesh(&mut mesh, g.rows, g.columns, black_box(sim.positions()));
    }
    start.elapsed().as_secs_f64() / (FRAMES * repeats) as f64
}

fn main() {
    let grid = ClothGrid {
        rows: 64,
        columns: 64,
        width: 1.5,
        height: 1.0,
    };
    let base = ClothPreset::FlagGentleFrozen.params();
    println!("## Cloth: harmonics kept against shape error and run time (64×64, release)\n");
    println!("| harmonics kept | RMS shape error (fraction of yarn length) | µs per frame |");
    println!("|---|---|---|");
    let filters = [1usize, 2, 3, 5, 8, 12, 16, 24, 31]
        .map(|max| HarmonicFilter::LowPass { max })
        .into_iter()
        .chain([HarmonicFilter::All]);
    for filter in filters {
        let params = bevy_windfall::cloth::ClothParams { filter, ..base };
        let exact_params = bevy_windfall::cloth::ClothParams {
            filter: HarmonicFilter::All,
            ..base
        };
        let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).unwrap();
        let mut exact = ClothSim::new(grid, exact_params, ClothAttachment::Pole).unwrap();
        let mut error = 0.0f64;
        for _ in 0..FRAMES {
            sim.advance(DT, base.wind_speed);
            exact.advance(DT, base.wind_speed);
            sim.rebuild();
            exact.rebuild();
            let sq: f64 = sim
                .positions()
                .iter()
                .zip(exact.positions())
                .map(|(a, b)| f64::from(a.distance_squared(*b)))
                .sum();
            error += (sq / sim.positions().len() as f64).sqrt() / f64::from(grid.width);
        }
        let label = match filter {
            HarmonicFilter::LowPass { max } => format!("1..={max}"),
            _ => "all (no filter, no FFT)".into(),
        };
        let time = seconds_per_frame(&mut sim, 4);
        println!(
            "| {label} | {:.2e} | {:.1} |",
            error / FRAMES as f64,
            time * 1e6
        );
    }
    println!("\n## Cloth: grid size against run time (release)\n");
    println!("| grid | frozen µs per frame | non-frozen µs per frame | ns per node (frozen) |");
    println!("|---|---|---|---|");
    for size in [8usize, 16, 32, 64, 128, 256] {
        let grid = ClothGrid {
            rows: size,
            columns: size,
            ..grid
        };
        let mut frozen = ClothSim::new(grid, base, ClothAttachment::Pole).unwrap();
        let mut non_frozen = ClothSim::new(
            grid,
            ClothPreset::FlagGentleNonFrozen.params(),
            ClothAttachment::Pole,
        )
        .unwrap();
        let repeats = (4096 / (size * size)).clamp(1, 64);
        let t_frozen = seconds_per_frame(&mut frozen, repeats);
        let t_non = seconds_per_frame(&mut non_frozen, repeats);
        println!(
            "| {size}×{size} | {:.1} | {:.1} | {:.1} |",
            t_frozen * 1e6,
            t_non * 1e6,
            t_frozen * 1e9 / (size * size) as f64
        );
    }
}
