//! Free fall as a designer sees it: every preset's numbers (Re, I*, U, swing frequency, response
//! time), the seconds its falls spend in each motion, and how often they show the paper's
//! sequence.

use bevy::math::Vec3;
use bevy_windfall::freefall::FallScales;
use bevy_windfall::freefall::{
    FallModel, FallPreset, FallRelease, FallingObject, PrimitiveMotion, WindTilt,
};

use super::{Report, sci};

const DT: f32 = 1.0 / 60.0;

/// The motion at every step of a fall of `seconds` in still fluid.
fn motions(object: &FallingObject, model: &FallModel, seconds: f32) -> Vec<PrimitiveMotion> {
    let mut path = object
        .path(model, FallRelease::at(Vec3::ZERO, f32::NEG_INFINITY))
        .expect("a valid preset");
    let tilt = WindTilt {
        max_angle: 0.0,
        reference_speed: 1.0,
    };
    let mut seen = vec![path.motion()];
    for _ in 0..(seconds / DT) as usize {
        path.advance(model, DT, Vec3::ZERO, &tilt);
        seen.push(path.motion());
    }
    seen
}

pub fn report(r: &mut Report) {
    let strouhal = FallScales::STROUHAL;
    r.section(
        "Free fall: presets",
        &format!(
            "Every `FallPreset` with its sizes' Re and I*, the main motion it falls toward \
             (forced where the paper reports one its sizes cannot give, see the README), the \
             descent speed U of eq. 3, the swing frequency f = St U / a with St = {strouhal:.3} \
             (one flutter period is two swings), and the response time τ = ρ_s b / (ρ_f U) over \
             which it takes up a change of the wind."
        ),
    );
    let model = FallModel::default();
    let mut rows = Vec::new();
    for preset in FallPreset::ALL {
        let object = preset.object();
        let Ok(regime) = object.regime() else {
            continue;
        };
        let scales = object.scales(&regime);
        let frequency = scales.swing_rate / std::f32::consts::TAU;
        rows.push(vec![
            preset.name().into(),
            sci(f64::from(regime.reynolds)),
            sci(f64::from(regime.inertia)),
            format!(
                "{:?}{}",
                regime.main,
                if object.main_motion.is_some() {
                    " (forced)"
                } else {
                    ""
                }
            ),
            format!("{:.2}", regime.descent_speed),
            format!("{frequency:.2}"),
            format!("{:.3}", scales.response_time(0.0)),
        ]);
    }
    r.table(
        &[
            "preset",
            "Re",
            "I*",
            "main motion",
            "U (m/s)",
            "f (Hz)",
            "τ (s)",
        ],
        &rows,
    );

    let falls = if r.quick { 20 } else { 400 };
    r.section(
        "Free fall: seconds in each motion, per preset",
        &format!(
            "{falls} falls of 12 s in still fluid per preset. Each cell: the mean seconds of one \
             visit of that motion (whole visits only; the main motion, which holds, is not \
             timed), and in brackets the preset's dwell time D (a change happens where a piece \
             ends, so a visit lasts about D plus half a piece). Last column: the share of falls \
             in their main motion (the last of the preset's sequence) after 6 s."
        ),
    );
    let mut rows = Vec::new();
    for preset in FallPreset::ALL {
        let (_, dwell) = preset.dwell_times();
        let (mut total, mut visits) = ([0.0f32; 6], [0u32; 6]);
        let mut whole = 0;
        for seed in 0..falls {
            let object = FallingObject {
                seed,
                ..preset.object()
            };
            let seen = motions(&object, &model, 12.0);
            let mut run = 0usize;
            for pair in seen.windows(2) {
                run += 1;
                if pair[1] != pair[0] {
                    total[pair[0].index()] += run as f32 * DT;
                    visits[pair[0].index()] += 1;
                    run = 0;
                }
            }
            let reached = seen[(6.0 / DT) as usize];
            whole += usize::from(Some(&reached) == preset.sequence().last());
        }
        let mut row = vec![preset.name().to_string()];
        for m in PrimitiveMotion::ALL {
            let i = m.index();
            row.push(if visits[i] > 0 {
                format!("{:.2} ({:.1})", total[i] / visits[i] as f32, dwell[i])
            } else {
                "–".into()
            });
        }
        row.push(format!("{:.0} %", 100.0 * whole as f32 / falls as f32));
        rows.push(row);
    }
    r.table(
        &[
            "preset",
            "L1 SD",
            "L2 PF",
            "L3 TC",
            "L4 PT",
            "L5 TH",
            "L6 PS",
            "in the main motion at 6 s",
        ],
        &rows,
    );
}
