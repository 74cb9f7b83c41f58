//! With feature `egui`: the crate's inspector ([`WindfallInspectorPlugin`]) and a small window
//! of scene buttons. The inspector edits the entities the scenes name first (the coin, the
//! featured leaf, the flag).

use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_windfall::inspector::WindfallInspectorPlugin;

use super::Scene;
use super::common::Covered;

pub fn plugin(app: &mut App) {
    app.add_plugins(WindfallInspectorPlugin)
        .add_systems(EguiPrimaryContextPass, (report_panels, scene_buttons));
}

/// Tells the on-screen text where egui's windows are (as they were drawn last frame), in
/// logical pixels, so that it wraps short of them and the layout check sees them.
fn report_panels(
    mut contexts: EguiContexts,
    window: Single<&Window, With<PrimaryWindow>>,
    mut covered: ResMut<Covered>,
) -> Result {
    let ctx = contexts.ctx_mut()?;
    let to_logical = ctx.pixels_per_point() / window.scale_factor();
    covered.0 = ctx.memory(|memory| {
        memory
            .areas()
            .visible_layer_ids()
            .into_iter()
            .filter(|layer| layer.order == egui::Order::Middle)
            .filter_map(|layer| memory.area_rect(layer.id))
            .map(|r| {
                let corner = |p: egui::Pos2| Vec2::new(p.x, p.y) * to_logical;
                Rect::from_corners(corner(r.min), corner(r.max))
            })
            .collect()
    });
    Ok(())
}

fn scene_buttons(
    mut contexts: EguiContexts,
    scene: Res<State<Scene>>,
    mut next: ResMut<NextState<Scene>>,
) -> Result {
    egui::Window::new("scene")
        .anchor(egui::Align2::RIGHT_BOTTOM, [-10.0, -10.0])
        .title_bar(false)
        .resizable(false)
        .show(contexts.ctx_mut()?, |ui| {
            ui.horizontal(|ui| {
                for s in Scene::ALL {
                    if ui.selectable_label(*scene.get() == s, s.name()).clicked() {
                        next.set(s);
                    }
                }
            });
        });
    Ok(())
}
