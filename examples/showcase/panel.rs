//! With feature `egui`: the crate's inspector ([`WindfallInspectorPlugin`]) and a small window
//! of scene buttons. The inspector edits the entities the scenes name first (the coin, the
//! featured leaf, the flag).

use bevy::prelude::*;
use bevy_egui::{EguiContexts, EguiPrimaryContextPass, egui};
use bevy_windfall::inspector::WindfallInspectorPlugin;

use super::Scene;

pub fn plugin(app: &mut App) {
    app.add_plugins(WindfallInspectorPlugin)
        .add_systems(EguiPrimaryContextPass, scene_buttons);
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
