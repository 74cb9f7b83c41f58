//! The live tuning panel (feature `egui`): wind, falling objects, cloth, aero bodies, gizmos.
//! Every change takes effect at once; a wind rebuild runs in the background
//! ([`WindRebuild`]) while the old field keeps blowing.

use std::f32::consts::PI;

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPlugin, EguiPrimaryContextPass, egui};
use bevy_windfall::cloth::{ClothGizmos, ClothWindModel, LeadingYarn};
use bevy_windfall::freefall::{FallGizmos, FallPreset};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::{WindGizmos, WindRebuild, WindRebuilt};

use super::flag::Hanging;
use super::{Featured, Scene};

pub fn plugin(app: &mut App) {
    app.add_plugins(EguiPlugin::default())
        .init_resource::<Draft>()
        .add_systems(EguiPrimaryContextPass, panel);
}

/// Wind settings being edited that need a rebuild, the last rebuild's refusal, and the scene
/// the panel last showed (a new scene opens its own sections).
#[derive(Resource, Default)]
struct Draft {
    wind: Option<WindConfig>,
    rebuild_error: Option<String>,
    scene: Option<Scene>,
    /// When the rebuild in flight started, and how long the last one took.
    rebuild_started: Option<std::time::Instant>,
    last_rebuild: Option<std::time::Duration>,
}

#[derive(SystemParam)]
struct Wind<'w, 's> {
    field: ResMut<'w, WindField>,
    rebuild: Option<Res<'w, WindRebuild>>,
    rebuilt: MessageReader<'w, 's, WindRebuilt>,
    wind_gizmos: ResMut<'w, WindGizmos>,
    fall_gizmos: ResMut<'w, FallGizmos>,
    cloth_gizmos: ResMut<'w, ClothGizmos>,
}

#[derive(SystemParam)]
struct Objects<'w, 's> {
    featured: Query<'w, 's, (&'static mut FallingObject, &'static FallState), With<Featured>>,
    cloth: Query<'w, 's, &'static mut Cloth, With<Hanging>>,
    bodies: Query<'w, 's, &'static mut AeroBody>,
}

fn panel(
    mut contexts: EguiContexts,
    mut commands: Commands,
    mut draft: ResMut<Draft>,
    scene: Res<State<Scene>>,
    mut next: ResMut<NextState<Scene>>,
    mut wind: Wind,
    mut objects: Objects,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    // On entering a scene, open the sections that edit what it shows and close the others.
    let now = *scene.get();
    let entered = draft.scene.replace(now) != Some(now);
    let open = |shown: bool| entered.then_some(shown);
    egui::Window::new("bevy_windfall")
        .default_pos([960.0, 10.0])
        .default_width(300.0)
        .show(ctx, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.horizontal(|ui| {
                    for s in Scene::ALL {
                        if ui.selectable_label(*scene.get() == s, s.name()).clicked() {
                            next.set(s);
                        }
                    }
                });
                ui.collapsing("Wind", |ui| {
                    wind_section(ui, &mut commands, &mut draft, &mut wind)
                })
                .header_response
                .on_hover_text("the WindField shared by every scene");
                egui::CollapsingHeader::new("Falling object")
                    .open(open(now != Scene::Flag))
                    .show(ui, |ui| falling_section(ui, &mut objects));
                egui::CollapsingHeader::new("Cloth")
                    .open(open(now == Scene::Flag))
                    .show(ui, |ui| cloth_section(ui, &mut objects));
                egui::CollapsingHeader::new("Aero bodies")
                    .open(open(false))
                    .show(ui, |ui| aero_section(ui, &mut objects));
                ui.collapsing("Gizmos", |ui| {
                    ui.checkbox(&mut wind.wind_gizmos.enabled, "wind arrows");
                    ui.checkbox(&mut wind.fall_gizmos.enabled, "falling paths");
                    ui.checkbox(&mut wind.cloth_gizmos.enabled, "cloth yarns");
                });
            });
        });
    Ok(())
}

fn wind_section(ui: &mut egui::Ui, commands: &mut Commands, draft: &mut Draft, wind: &mut Wind) {
    // Speed and direction apply at once; the rest rebuilds the turbulence.
    let mut speed = wind.field.config().reference_speed;
    if ui
        .add(egui::Slider::new(&mut speed, 0.0..=70.0).text("U at 10 m, m/s"))
        .changed()
    {
        let _ = wind.field.set_reference_speed(speed);
    }
    let d = wind.field.config().direction;
    let mut heading = d.y.atan2(d.x).to_degrees();
    if ui
        .add(egui::Slider::new(&mut heading, -180.0..=180.0).text("direction, °"))
        .changed()
    {
        let _ = wind
            .field
            .set_direction(Vec2::from_angle(heading.to_radians()));
    }
    let current = wind.field.config().clone();
    let config = draft.wind.get_or_insert_with(|| current.clone());
    config.reference_speed = current.reference_speed;
    config.direction = current.direction;
    ui.add(
        egui::Slider::new(&mut config.roughness, 1e-4..=2.0)
            .logarithmic(true)
            .text("roughness z0, m"),
    );
    ui.add(egui::Slider::new(&mut config.beta, 0.0..=5.0).text("β (5/3 Kolmogorov)"));
    let mut evolving = matches!(config.temporal, TemporalMode::Evolving { .. });
    if ui
        .checkbox(&mut evolving, "non-frozen (evolving)")
        .changed()
    {
        config.temporal = if evolving {
            TemporalMode::Evolving {
                samples: 16,
                period: 20.0,
            }
        } else {
            TemporalMode::Frozen
        };
    }
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut config.seed).prefix("seed "));
        if ui.button("New seed").clicked() {
            config.seed = config.seed.wrapping_add(1);
        }
    });
    // The turbulence is rebuilt in the background once the pointer lets go of a control, and
    // again after that if the settings changed meanwhile; the old field blows until then.
    let dirty = *config != current;
    if wind.rebuild.is_some() {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label("building in the background…");
        });
    } else if dirty && !ui.input(|i| i.pointer.any_down()) {
        match WindRebuild::start(config.clone()) {
            Ok(job) => {
                commands.insert_resource(job);
                draft.rebuild_error = None;
                draft.rebuild_started = Some(std::time::Instant::now());
            }
            Err(e) => draft.rebuild_error = Some(e.to_string()),
        }
    }
    if wind.rebuilt.read().count() > 0 {
        draft.last_rebuild = draft.rebuild_started.take().map(|t| t.elapsed());
    }
    if let Some(took) = draft.last_rebuild {
        ui.label(format!(
            "last rebuild: {:.0} ms, off the frame",
            took.as_secs_f64() * 1e3
        ));
    }
    if let Some(e) = &draft.rebuild_error {
        ui.colored_label(egui::Color32::RED, e);
    }
}

fn falling_section(ui: &mut egui::Ui, objects: &mut Objects) {
    let Ok((mut object, state)) = objects.featured.single_mut() else {
        ui.label("no featured object in this scene");
        return;
    };
    let mut edit = object.clone();
    egui::ComboBox::from_label("preset")
        .selected_text("choose…")
        .show_ui(ui, |ui| {
            for preset in FallPreset::ALL {
                if ui.selectable_label(false, preset.name()).clicked() {
                    edit = FallingObject {
                        seed: edit.seed + 1,
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
    if edit != *object {
        *object = edit;
    }
    match (state.regime(), state.error()) {
        (_, Some(e)) => {
            ui.colored_label(egui::Color32::RED, format!("{e}"));
        }
        (Some(r), None) => {
            ui.label(format!(
                "Re = {:.3e}   I* = {:.3e}\nU = {:.3} m/s\nregime (phase diagram): {} {:?}",
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
            ui.label("released next frame");
        }
    }
}

fn cloth_section(ui: &mut egui::Ui, objects: &mut Objects) {
    let Ok(mut cloth) = objects.cloth.single_mut() else {
        ui.label("no cloth in this scene (press 3)");
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
        egui::Slider::new(&mut p.wind_speed, 0.0..=20.0).text("1 wind speed |v|"),
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
    let mut non_frozen = matches!(p.model, ClothWindModel::NonFrozen { .. });
    if ui.checkbox(&mut non_frozen, "non-frozen").changed() {
        p.model = if non_frozen {
            ClothWindModel::NonFrozen { frames: 64 }
        } else {
            ClothWindModel::Frozen
        };
    }
    if p != cloth.params || follow != cloth.follow_wind {
        cloth.params = p;
        cloth.follow_wind = follow;
    }
}

fn aero_section(ui: &mut egui::Ui, objects: &mut Objects) {
    let Some(first) = objects.bodies.iter().next() else {
        ui.label("no aero bodies in this scene (press 1)");
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
        for mut body in &mut objects.bodies {
            let _ = body.plate.set_coefficients(*c);
        }
    }
    ui.label(format!("{} rigid plates", objects.bodies.iter().len()));
}
