//! The showcase's on-screen text, drawn with egui beside the panel: the header in the top-left
//! corner ([`Hud`]) and labels that follow points of the scene ([`SceneLabel`], the gallery's).
//! Fonts follow the window (18 px at 1280 × 720, never under 10 px), the header wraps short of
//! the panels, and labels are shortened on small windows. At every screenshot (and in
//! `--check-layout`) the text and the panels are measured: text that overlaps other text or a
//! panel, or runs out of the window, fails the run.

use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};

use super::common::{CheckLayout, LayoutFailures};

/// The header's text (the scene, its figures and keys).
#[derive(Resource, Default)]
pub struct Hud(pub String);

/// A label that follows a point of the scene: its full text, and the short one shown on a small
/// window (under [`SceneLabel::WIDE`] logical pixels), where full ones would run into each other.
#[derive(Component)]
pub struct SceneLabel {
    pub at: Vec3,
    pub full: String,
    pub short: String,
    pub color: Color,
}

impl SceneLabel {
    /// The narrowest window, logical pixels, that shows labels in full.
    pub const WIDE: f32 = 800.0;
}

/// No text on screen (the tour's `--film`).
#[derive(Resource)]
pub struct Hidden;

pub fn plugin(app: &mut App) {
    app.init_resource::<Hud>()
        .init_resource::<Drawn>()
        .add_systems(
            EguiPrimaryContextPass,
            (draw_text, check_layout)
                .chain()
                .run_if(not(resource_exists::<Hidden>)),
        );
}

/// Space between text, panels and the window's edges, logical pixels.
const MARGIN: f32 = 10.0;

/// A font size for a window of `size`: `px` at 1280 × 720, scaled down with the window, and at
/// least 10 px (readable at 640 × 360).
fn font(px: f32, size: Vec2) -> f32 {
    (px * (size.x / 1280.0).min(size.y / 720.0).min(1.0)).max(10.0)
}

/// The areas of text drawn this frame, by egui id, and what they show (for the layout check).
#[derive(Resource, Default)]
struct Drawn(Vec<(egui::Id, String)>);

fn draw_text(
    mut contexts: EguiContexts,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<Camera3d>>,
    hud: Res<Hud>,
    labels: Query<(Entity, &SceneLabel)>,
    mut drawn: ResMut<Drawn>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    let size = window.size();
    drawn.0.clear();
    // The header: left of the panels in the window's upper half (as drawn last frame).
    let right = panels(ctx)
        .into_iter()
        .filter(|r| r.min.y < 0.5 * size.y)
        .map(|r| r.min.x)
        .fold(size.x, f32::min);
    let id = egui::Id::new("showcase header");
    egui::Area::new(id)
        .order(egui::Order::Background)
        .fixed_pos([MARGIN, MARGIN])
        .show(ctx, |ui| {
            // A light veil behind the letters, so they read over the scene.
            egui::Frame::new()
                .fill(egui::Color32::from_white_alpha(110))
                .corner_radius(3.0)
                .inner_margin(2.0)
                .show(ui, |ui| {
                    ui.set_max_width((right - 2.0 * MARGIN - 4.0).max(100.0));
                    let text = egui::RichText::new(&hud.0)
                        .monospace()
                        .size(font(16.0, size))
                        .color(egui::Color32::BLACK);
                    ui.add(egui::Label::new(text).wrap());
                });
        });
    drawn.0.push((id, hud.0.clone()));
    // The labels, centred under their points.
    let (camera, view) = *camera;
    let wide = size.x >= SceneLabel::WIDE;
    for (entity, label) in &labels {
        let Ok(p) = camera.world_to_viewport(view, label.at) else {
            continue;
        };
        let text = if wide { &label.full } else { &label.short };
        let [r, g, b, _] = label.color.to_srgba().to_u8_array();
        let id = egui::Id::new(("scene label", entity));
        egui::Area::new(id)
            .order(egui::Order::Background)
            .pivot(egui::Align2::CENTER_TOP)
            .fixed_pos([p.x, p.y])
            .show(ctx, |ui| {
                ui.with_layout(egui::Layout::top_down(egui::Align::Center), |ui| {
                    let rich = egui::RichText::new(text)
                        .monospace()
                        .size(font(14.0, size))
                        .color(egui::Color32::from_rgb(r, g, b));
                    ui.add(egui::Label::new(rich).extend());
                });
            });
        drawn.0.push((id, text.clone()));
    }
    Ok(())
}

/// The rectangles of egui's windows (the inspector, the scene buttons) as last drawn.
fn panels(ctx: &egui::Context) -> Vec<egui::Rect> {
    ctx.memory(|memory| {
        memory
            .areas()
            .visible_layer_ids()
            .into_iter()
            .filter(|layer| layer.order == egui::Order::Middle)
            .filter_map(|layer| memory.area_rect(layer.id))
            .collect()
    })
}

/// On a [`CheckLayout`] request: every text area drawn against the others, the panels and the
/// window (one point of slack for rounding); a failure is logged and counted.
fn check_layout(
    mut requests: MessageReader<CheckLayout>,
    mut contexts: EguiContexts,
    window: Single<&Window, With<PrimaryWindow>>,
    drawn: Res<Drawn>,
    mut failures: ResMut<LayoutFailures>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    for CheckLayout(name) in requests.read() {
        let texts: Vec<(egui::Rect, String)> = drawn
            .0
            .iter()
            .filter(|(_, text)| !text.trim().is_empty())
            .filter_map(|(id, text)| {
                let rect = ctx.memory(|m| m.area_rect(*id))?.shrink(1.0);
                let words: Vec<&str> = text.split_whitespace().take(4).collect();
                Some((rect, words.join(" ")))
            })
            .collect();
        let screen = egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(window.width(), window.height()),
        );
        let mut problems = Vec::new();
        for (i, (a, text)) in texts.iter().enumerate() {
            for (b, other) in &texts[i + 1..] {
                if a.intersects(*b) {
                    problems.push(format!("\"{text}\" overlaps \"{other}\""));
                }
            }
            for panel in panels(ctx) {
                if a.intersects(panel) {
                    problems.push(format!("\"{text}\" runs under a panel at {panel:?}"));
                }
            }
            if !screen.contains_rect(*a) {
                problems.push(format!("\"{text}\" runs out of the window ({a:?})"));
            }
        }
        if problems.is_empty() {
            info!("layout of {name}: {} texts, none overlapping", texts.len());
        } else {
            failures.0 += 1;
            for problem in problems {
                error!("layout of {name} at {}: {problem}", window.size());
            }
        }
    }
    Ok(())
}
