//! The panel's sections.

use std::f32::consts::PI;

use bevy::ecs::prelude::*;
use bevy::math::Vec2;
use bevy_egui::egui;

use super::{Targets, WindfallInspector};
use crate::cloth::{ClothPreset, ClothWindModel, LeadingYarn};
use crate::freefall::{FallPreset, FallingObject, Fluid, PrimitiveMotion, Shape};
use crate::wind::{Pulse, TemporalMode};

/// Picks `current` or the first of `candidates` (named ones first) with a combo box of at most
/// 40 of them.
fn pick(
    ui: &mut egui::Ui,
    label: &str,
    current: &mut Option<Entity>,
    candidates: &[(Entity, Option<String>)],
) -> Option<Entity> {
    let mut sorted: Vec<&(Entity, Option<String>)> = candidates.iter().collect();
    sorted.sort_by_key(|(e, name)| (name.is_none(), *e));
    let valid = current.filter(|c| candidates.iter().any(|(e, _)| e == c));
    let chosen = valid.or_else(|| sorted.first().map(|(e, _)| *e))?;
    *current = Some(chosen);
    let text = |e: Entity| {
        candidates
            .iter()
            .find(|(c, _)| *c == e)
            .and_then(|(_, n)| n.clone())
            .unwrap_or_else(|| format!("entity {e}"))
    };
    egui::ComboBox::from_label(label)
        .selected_text(text(chosen))
        .show_ui(ui, |ui| {
            for (e, _) in sorted.iter().take(40) {
                if ui.selectable_label(*e == chosen, text(*e)).clicked() {
                    *current = Some(*e);
                }
            }
        });
    *current
}

/// Sliders for a [`Pulse`]'s magnitude and frequency; whether either changed.
pub(super) fn pulse_sliders(ui: &mut egui::Ui, pulse: &mut Pulse) -> bool {
    let magnitude = ui.add(egui::Slider::new(&mut pulse.magnitude, 0.0..=1.0).text("pulse ±"));
    let frequency =
        ui.add(egui::Slider::new(&mut pulse.frequency, 0.0..=2.0).text("pulse frequency, Hz"));
    magnitude.changed() || frequency.changed()
}

pub(super) fn wind(ui: &mut egui::Ui, inspector: &mut WindfallInspector, targets: &mut Targets) {
    let Some(settings) = targets.settings.as_mut() else {
        ui.label("no wind (add WindPlugin)");
        return;
    };
    // Speed and direction apply at once.
    let mut speed = settings.reference_speed;
    if ui
        .add(egui::Slider::new(&mut speed, 0.0..=70.0).text("U at 10 m, m/s"))
        .changed()
    {
        settings.reference_speed = speed;
    }
    let d = settings.direction;
    let mut heading = d.y.atan2(d.x).to_degrees();
    if ui
        .add(egui::Slider::new(&mut heading, -180.0..=180.0).text("direction, °"))
        .changed()
    {
        settings.direction = Vec2::from_angle(heading.to_radians());
    }
    let mut pulse = settings.pulse;
    if pulse_sliders(ui, &mut pulse) {
        settings.pulse = pulse;
    }
    // The turbulence: edited in a draft, applied (a background rebuild) when no control is
    // held, so dragging a slider does not start a rebuild a frame.
    let live = settings.config.clone();
    let draft = inspector.draft.get_or_insert_with(|| live.clone());
    *draft = draft.with_mean(live.mean());
    ui.add(
        egui::Slider::new(&mut draft.roughness, 1e-4..=2.0)
            .logarithmic(true)
            .text("roughness z0, m"),
    );
    ui.add(egui::Slider::new(&mut draft.beta, 0.0..=5.0).text("β (5/3 Kolmogorov)"));
    let mut evolving = matches!(draft.temporal, TemporalMode::Evolving { .. });
    if ui
        .checkbox(&mut evolving, "evolving (not frozen)")
        .changed()
    {
        draft.temporal = if evolving {
            TemporalMode::Evolving {
                samples: 16,
                period: 20.0,
            }
        } else {
            TemporalMode::Frozen
        };
    }
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut draft.seed).prefix("seed "));
        if ui.button("New seed").clicked() {
            draft.seed = draft.seed.wrapping_add(1);
        }
    });
    if *draft != live && !ui.input(|i| i.pointer.any_down()) {
        settings.config = draft.clone();
    }
    if let Some(rebuild) = targets.rebuild.as_ref() {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(format!(
                "building in the background, lands in {} steps",
                rebuild.steps_left()
            ));
        });
    }
}

pub(super) fn falling(ui: &mut egui::Ui, inspector: &mut WindfallInspector, targets: &mut Targets) {
    let candidates: Vec<(Entity, Option<String>)> = targets
        .falling
        .iter()
        .map(|(e, _, _, n, _)| (e, n.map(|n| n.to_string())))
        .collect();
    let Some(entity) = pick(ui, "object", &mut inspector.falling, &candidates) else {
        ui.label("no falling object");
        return;
    };
    let Ok((_, mut object, state, _, invalid)) = targets.falling.get_mut(entity) else {
        return;
    };
    let mut edit = object.clone();
    egui::ComboBox::from_label("preset")
        .selected_text("choose…")
        .show_ui(ui, |ui| {
            for preset in FallPreset::ALL {
                if ui.selectable_label(false, preset.name()).clicked() {
                    edit = FallingObject {
                        seed: edit.seed.wrapping_add(1),
                        ..preset.object()
                    };
                }
            }
        });
    // The width over the length, kept when the size or the outline changes.
    let (length, width, _) = edit.shape.lengths();
    let aspect = (width / length).clamp(0.05, 1.0);
    let (mut kind, mut size, mut thickness) = match edit.shape {
        Shape::Disk {
            diameter,
            thickness,
        } => (0, diameter, thickness),
        Shape::Rectangle {
            length, thickness, ..
        } => (1, length, thickness),
        Shape::Ellipse {
            major, thickness, ..
        } => (2, major, thickness),
    };
    ui.horizontal(|ui| {
        for (i, name) in ["disk", "rectangle", "ellipse"].into_iter().enumerate() {
            ui.radio_value(&mut kind, i, name);
        }
    });
    ui.add(
        egui::Slider::new(&mut size, 1e-3..=0.5)
            .logarithmic(true)
            .text("size L, m"),
    );
    ui.add(
        egui::Slider::new(&mut thickness, 1e-5..=1e-2)
            .logarithmic(true)
            .text("thickness b, m"),
    );
    edit.shape = match kind {
        0 => Shape::Disk {
            diameter: size,
            thickness,
        },
        1 => Shape::Rectangle {
            length: size,
            width: aspect * size,
            thickness,
        },
        _ => Shape::Ellipse {
            major: size,
            minor: aspect * size,
            thickness,
        },
    };
    ui.add(
        egui::Slider::new(&mut edit.density, 10.0..=20_000.0)
            .logarithmic(true)
            .text("density ρs, kg/m³"),
    );
    ui.horizontal(|ui| {
        ui.label("fluid");
        ui.radio_value(&mut edit.fluid, Fluid::AIR, "air");
        ui.radio_value(&mut edit.fluid, Fluid::WATER, "water");
    });
    egui::ComboBox::from_label("main motion")
        .selected_text(
            edit.main_motion
                .map_or("phase diagram".into(), |m| format!("{} {m:?}", m.label())),
        )
        .show_ui(ui, |ui| {
            if ui
                .selectable_label(edit.main_motion.is_none(), "phase diagram")
                .clicked()
            {
                edit.main_motion = None;
            }
            for m in PrimitiveMotion::ALL {
                let text = format!("{} {m:?}", m.label());
                if ui
                    .selectable_label(edit.main_motion == Some(m), text)
                    .clicked()
                {
                    edit.main_motion = Some(m);
                }
            }
        });
    if edit != *object {
        *object = edit;
    }
    match (state.regime(), invalid) {
        (_, Some(invalid)) => {
            ui.colored_label(egui::Color32::RED, format!("{}", invalid.0));
        }
        (Some(r), None) => {
            ui.label(format!(
                "Re = {:.3e}   I* = {:.3e}\nU = {:.3} m/s\nmain motion: {} {:?}",
                r.reynolds,
                r.inertia,
                r.descent_speed,
                r.main.label(),
                r.main
            ));
            let now = state
                .motion()
                .map_or("landed".into(), |m| format!("{} {m:?}", m.label()));
            ui.label(format!("Markov state: {now}"));
        }
        (None, None) => {
            ui.label("not released yet");
        }
    }
}

pub(super) fn cloth(ui: &mut egui::Ui, inspector: &mut WindfallInspector, targets: &mut Targets) {
    let candidates: Vec<(Entity, Option<String>)> = targets
        .cloths
        .iter()
        .map(|(e, _, n)| (e, n.map(|n| n.to_string())))
        .collect();
    let Some(entity) = pick(ui, "cloth", &mut inspector.cloth, &candidates) else {
        ui.label("no cloth");
        return;
    };
    let Ok((_, mut cloth, _)) = targets.cloths.get_mut(entity) else {
        return;
    };
    let mut p = cloth.params;
    egui::ComboBox::from_label("Table 1 preset")
        .selected_text("choose…")
        .show_ui(ui, |ui| {
            for preset in ClothPreset::ALL {
                if ui.selectable_label(false, format!("{preset:?}")).clicked() {
                    p = preset.params();
                }
            }
        });
    let mut follow = cloth.follow_wind;
    ui.checkbox(&mut follow, "|v| follows the wind field");
    ui.add_enabled(
        !follow,
        egui::Slider::new(&mut p.wind_steps_per_frame, 0.0..=20.0).text("1 wind speed |v|"),
    );
    ui.add(egui::Slider::new(&mut p.amplitude, 0.0..=PI).text("2 amplitude θ, rad"));
    ui.add(egui::Slider::new(&mut p.beta, 0.0..=5.0).text("3 smoothness β"));
    ui.add(egui::Slider::new(&mut p.swirl, -5.0..=5.0).text("4 swirl |u|"));
    ui.add(egui::Slider::new(&mut p.twist, -5.0..=5.0).text("5 twist"));
    ui.add(egui::Slider::new(&mut p.bow, 0.0..=0.3).text("W1 bow (eq. 8)"));
    ui.add(egui::Slider::new(&mut p.lean, 0.0..=0.3).text("W2 lean (eq. 8)"));
    ui.horizontal(|ui| {
        ui.label("6 leading yarn");
        ui.radio_value(&mut p.leading, LeadingYarn::Top, "top");
        ui.radio_value(&mut p.leading, LeadingYarn::Center, "centre");
        ui.radio_value(&mut p.leading, LeadingYarn::Bottom, "bottom");
    });
    let mut evolving = matches!(p.model, ClothWindModel::Evolving { .. });
    if ui.checkbox(&mut evolving, "evolving").changed() {
        p.model = if evolving {
            ClothWindModel::Evolving { frames: 64 }
        } else {
            ClothWindModel::Frozen
        };
    }
    // A cloth rebuilds when its parameters change: only once a control is let go.
    let settled = !ui.input(|i| i.pointer.any_down());
    if (p != cloth.params && settled) || follow != cloth.follow_wind {
        cloth.params = p;
        cloth.follow_wind = follow;
    }
}

pub(super) fn aero(ui: &mut egui::Ui, targets: &mut Targets) {
    let Some(first) = targets.bodies.iter().next() else {
        ui.label("no aero bodies");
        return;
    };
    let before = *first.plate.coefficients();
    let c = &mut before.clone();
    ui.add(egui::Slider::new(&mut c.drag, 0.0..=3.0).text("C_D"));
    ui.add(egui::Slider::new(&mut c.lift, 0.0..=3.0).text("C_L"));
    ui.add(
        egui::Slider::new(&mut c.density, 0.1..=1000.0)
            .logarithmic(true)
            .text("ρ, kg/m³"),
    );
    if *c != before {
        for mut body in &mut targets.bodies {
            let _ = body.plate.set_coefficients(*c);
        }
    }
    ui.label(format!("{} rigid plates", targets.bodies.iter().len()));
}

#[cfg(feature = "gizmos")]
pub(super) fn gizmos(ui: &mut egui::Ui, targets: &mut Targets) {
    use crate::cloth::ClothGizmos;
    use crate::freefall::FallGizmos;
    use crate::wind::WindGizmos;
    let Some(store) = targets.gizmos.as_mut() else {
        ui.label("no gizmos (add Bevy's gizmo plugin and WindfallDebugPlugin)");
        return;
    };
    if store
        .get_config_dyn(&std::any::TypeId::of::<WindGizmos>())
        .is_none()
    {
        ui.label("add WindfallDebugPlugin to draw");
        return;
    }
    ui.checkbox(
        &mut store.config_mut::<WindGizmos>().0.enabled,
        "wind arrows",
    );
    ui.checkbox(
        &mut store.config_mut::<FallGizmos>().0.enabled,
        "falling paths",
    );
    ui.checkbox(
        &mut store.config_mut::<ClothGizmos>().0.enabled,
        "cloth yarns",
    );
}
