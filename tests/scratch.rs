use bevy::prelude::*;
use bevy_windfall::cloth::*;

fn stats(preset: ClothPreset, speed_scale: f32) -> (f32, f32, f32) {
    let grid = ClothGrid { rows: 24, columns: 36, width: 1.5, height: 1.0 };
    let params = preset.params();
    let mut sim = ClothSim::new(grid, params, ClothAttachment::Pole).unwrap();
    let (rows, cols) = (grid.rows, grid.columns);
    let dt = 1.0 / 50.0;
    let mut tips: Vec<Vec<f32>> = vec![vec![]; rows];
    let mut bend2 = 0.0f64; let mut n = 0usize;
    let mut crossings = 0; let mut last = 0.0f32;
    for f in 0..1000 {
        sim.advance(dt, params.wind_speed * speed_scale);
        sim.rebuild();
        let p = sim.positions();
        for k in 0..rows {
            let a = p[k * cols]; let b = p[k * cols + cols - 1];
            let d = (b - a).normalize_or_zero();
            for j in 0..cols { let v = p[k*cols+j] - a; let perp = v - d * v.dot(d); bend2 += (perp.length_squared()) as f64; n += 1; }
            tips[k].push(b.z);
        }
        let t = p[(rows/2)*cols + cols-1].z;
        if f > 0 && (t - 0.0) * (last - 0.0) < 0.0 { crossings += 1; }
        last = t;
    }
    let swing: f32 = (tips.iter().map(|t| { let m = t.iter().sum::<f32>()/t.len() as f32; t.iter().map(|x| (x-m).powi(2)).sum::<f32>()/t.len() as f32 }).sum::<f32>() / rows as f32).sqrt();
    ((bend2 / n as f64).sqrt() as f32 / 1.5, swing / 1.5, crossings as f32 / 2.0 / 20.0)
}

#[test]
fn scratch() {
    for p in ClothPreset::ALL {
        let (b, s, f) = stats(p, 1.0);
        println!("{:28} bend {:.3} swing {:.3} f {:.2} Hz  U {:.1}", format!("{p:?}"), b, s, f, air_speed(p.params().wind_speed, 1.5));
    }
}
