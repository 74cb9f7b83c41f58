//! The panel's "Local wind" section: every [`WindSource`] (strength and extent) and the count of
//! shelters.

use bevy_egui::egui;

use super::Targets;
use crate::wind::SourceShape;

/// A short name for a source's kind.
fn kind(shape: &SourceShape) -> &'static str {
    match shape {
        SourceShape::Sphere { .. } => "sphere",
        SourceShape::Fan { .. } => "fan",
        SourceShape::Vortex { .. } => "vortex",
        SourceShape::Blast { .. } => "blast",
        SourceShape::Gust { .. } => "gust",
    }
}

/// The size that bounds a source, m: its radius or range.
fn extent(shape: &mut SourceShape) -> &mut f32 {
    match shape {
        SourceShape::Sphere { radius, .. }
        | SourceShape::Vortex { radius, .. }
        | SourceShape::Blast { radius, .. } => radius,
        SourceShape::Fan { range, .. } | SourceShape::Gust { range, .. } => range,
    }
}

pub(super) fn local_wind(ui: &mut egui::Ui, targets: &mut Targets) {
    let shelters = targets.shelters.iter().len();
    let mut sources: Vec<_> = targets.sources.iter_mut().collect();
    if sources.is_empty() {
        ui.label("no WindSource");
    }
    sources.sort_by_key(|(e, _, name)| (name.is_none(), *e));
    for (entity, source, name) in sources.into_iter().take(20) {
        let label = name.map_or_else(|| format!("entity {entity}"), |n| n.to_string());
        ui.label(format!("{} ({label})", kind(&source.shape)));
        let (mut strength, mut shape, mut pulse) = (source.strength, source.shape, source.pulse);
        ui.add(egui::Slider::new(&mut strength, 0.0..=3.0).text("strength"));
        super::sections::pulse_sliders(ui, &mut pulse);
        ui.add(
            egui::Slider::new(extent(&mut shape), 0.1..=50.0)
                .logarithmic(true)
                .text("reach, m"),
        );
        // Written only when changed, so an untouched panel leaves change detection alone.
        if strength != source.strength || shape != source.shape || pulse != source.pulse {
            let source = source.into_inner();
            source.strength = strength;
            source.shape = shape;
            source.pulse = pulse;
        }
        ui.separator();
    }
    ui.label(format!("{shelters} shelters"));
}
