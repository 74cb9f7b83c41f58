//! Procedural against physical: what the paper's synthesis saves over simulating the same
//! object, and the wind sampler against a well-known noise crate.

use std::hint::black_box;

use bevy::math::Vec3;
use bevy_windfall::aero::{AeroCoefficients, ParticleCloth, Pinning, PlateState, RigidPlate};
use bevy_windfall::cloth::{ClothAttachment, ClothGrid, ClothPreset, ClothSim};
use bevy_windfall::freefall::{FallModel, FallPath, FallingObject, WindTilt};
use bevy_windfall::wind::{WindConfig, WindField};
use noise::{Fbm, MultiFractal, NoiseFn, Perlin};

use super::aero::G;
use super::{Report, seconds_per};

const DT: f32 = 1.0 / 60.0;

pub fn report(r: &mut Report) {
    r.section(
        "Procedural against physical: cost of one 1/60 s step",
        "Same object, same wind (a uniform 3 m/s breeze). The procedural leaf is a \
         `FallingObject`'s path (phase diagram, Markov chain, database); the physical one a \
         `RigidPlate` of 2 × 2 faces with lift and drag. The procedural flag is the P-type \
         descriptor cloth (advance and rebuild); the physical one the particle cloth (4 ms \
         ticks, the face law's pressure along each node's normal). The wind sampler is \
         compared with `noise::Fbm<Perlin>` (4 octaves, 3 components) at the same points.",
    );
    let n = if r.quick { 100 } else { 20_000 };
    let breeze = Vec3::new(3.0, 0.0, 0.0);
    let mut rows = Vec::new();
    let mut row = |name: &str, ours: f64, baseline_name: &str, baseline: f64| {
        rows.push(vec![
            name.into(),
            format!("{:.3}", ours * 1e6),
            baseline_name.into(),
            format!("{:.3}", baseline * 1e6),
            format!("1/{:.0}", baseline / ours),
        ]);
    };

    // A 7.3 × 4.2 cm leaf, 500 kg/m³.
    let leaf = FallingObject::default();
    let regime = leaf.regime().expect("the default leaf is valid");
    let model = FallModel::default();
    let tilt = WindTilt {
        max_angle: leaf.wind_tilt,
        reference_speed: 4.0,
    };
    let start = Vec3::new(0.0, 1e6, 0.0); // never lands during the measurement
    let mut path = FallPath::new(&model, leaf.scales(&regime), regime.main, 1, start, 0.0)
        .expect("a release within bounds");
    let procedural = seconds_per(n, || {
        black_box(path.advance(&model, DT, breeze, &tilt));
    });
    let plate = RigidPlate::rectangle(0.073, 0.042, 3e-4, 500.0, AeroCoefficients::default(), 2)
        .expect("a valid plate");
    let mut s = PlateState {
        position: start,
        ..Default::default()
    };
    let physical = seconds_per(n, || plate.step(&mut s, DT, G, &|_| breeze, false));
    row(
        "falling leaf (FallPath)",
        procedural,
        "rigid plate, 4 faces",
        physical,
    );

    let grid = ClothGrid {
        rows: 16,
        columns: 24,
        width: 1.5,
        height: 1.0,
    };
    let params = ClothPreset::FlagFlappingFrozen.params();
    let mut flag = ClothSim::new(grid, params, ClothAttachment::Pole).expect("valid flag");
    let frames = n / 20;
    let procedural = seconds_per(frames, || {
        flag.advance(DT, params.wind_steps_per_frame);
        flag.rebuild();
    });
    let mut cloth =
        ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
            .expect("valid cloth");
    let physical = seconds_per(frames / 10 + 1, || cloth.step(DT, G, &|_| breeze));
    row(
        "flag 24×16 (P-descriptor)",
        procedural,
        "particle cloth",
        physical,
    );

    let wind = WindField::new(WindConfig::default()).expect("default wind");
    let points: Vec<Vec3> = (0..4096)
        .map(|i| Vec3::new((i % 64) as f32 * 0.37, 1.5, (i / 64) as f32 * 0.37))
        .collect();
    let mut out = Vec::new();
    let repeats = if r.quick { 1 } else { 100 };
    let ours = seconds_per(repeats, || wind.velocities_at(&points, 1.0, &mut out)) / 4096.0;
    let fbm: [Fbm<Perlin>; 3] = [1, 2, 3].map(|seed| Fbm::<Perlin>::new(seed).set_octaves(4));
    let baseline = seconds_per(repeats, || {
        for p in &points {
            let q = [f64::from(p.x), f64::from(p.y), f64::from(p.z)];
            black_box([fbm[0].get(q), fbm[1].get(q), fbm[2].get(q)]);
        }
    }) / 4096.0;
    row(
        "wind sample (WindField)",
        ours,
        "noise Fbm<Perlin> ×3",
        baseline,
    );
    r.table(&["ours", "µs", "baseline", "µs", "ours / baseline"], &rows);
}
