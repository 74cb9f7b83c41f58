//! A drop-in tuning panel (feature `egui`): the wind, a falling object, a cloth, the local wind
//! sources, the aero bodies and the debug drawing, edited live in any game that adds
//! [`WindfallInspectorPlugin`].
//!
//! Everything it edits is plain data the plugins already follow: [`WindSettings`] (speed and
//! direction at once, the turbulence rebuilt in the background once a control is let go), the
//! [`FallingObject`] and [`Cloth`] components (a change releases or rebuilds them) and the aero
//! bodies' coefficients. Entities with a [`Name`] are offered first.

mod local;
mod sections;

use bevy::app::{App, Plugin};
use bevy::ecs::name::Name;
use bevy::ecs::prelude::*;
use bevy::ecs::system::SystemParam;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy_egui::{EguiContexts, EguiPlugin, EguiPrimaryContextPass, egui};

use crate::aero::AeroBody;
use crate::cloth::Cloth;
use crate::freefall::{FallState, FallingObject, FallingObjectInvalid};
use crate::wind::{WindConfig, WindRebuild, WindSettings, WindShelter, WindSource};

/// Adds the panel (and bevy_egui's plugin if it is missing). Needs a window and a camera.
///
/// # Example
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::inspector::WindfallInspectorPlugin;
///
/// App::new()
///     .add_plugins((DefaultPlugins, WindfallPlugins::default(), WindfallInspectorPlugin))
///     .run();
/// ```
pub struct WindfallInspectorPlugin;

impl Plugin for WindfallInspectorPlugin {
    fn build(&self, app: &mut App) {
        if !app.is_plugin_added::<EguiPlugin>() {
            app.add_plugins(EguiPlugin::default());
        }
        app.register_type::<WindfallInspector>()
            .init_resource::<WindfallInspector>()
            .add_systems(EguiPrimaryContextPass, show_inspector);
    }
}

/// The panel's state: whether it is shown, which falling object and cloth it edits, and the
/// turbulence settings being dragged (applied when the pointer lets go).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::inspector::WindfallInspector;
///
/// // F2 shows or hides the panel.
/// fn toggle(keys: Res<ButtonInput<KeyCode>>, mut inspector: ResMut<WindfallInspector>) {
///     if keys.just_pressed(KeyCode::F2) {
///         inspector.hidden = !inspector.hidden;
///     }
/// }
/// # let _ = toggle;
/// ```
#[derive(Resource, Default, Debug, Reflect)]
#[reflect(Resource, Default, Debug)]
pub struct WindfallInspector {
    /// Hide the panel.
    pub hidden: bool,
    /// The falling object edited (`None`: the first one, named ones first).
    pub falling: Option<Entity>,
    /// The cloth edited (`None`: the first one).
    pub cloth: Option<Entity>,
    /// Turbulence settings being edited, applied once no control is held.
    draft: Option<WindConfig>,
}

/// A falling object as the panel sees it.
type FallingParts = (
    Entity,
    &'static mut FallingObject,
    &'static FallState,
    Option<&'static Name>,
    Option<&'static FallingObjectInvalid>,
);

#[derive(SystemParam)]
struct Targets<'w, 's> {
    settings: Option<ResMut<'w, WindSettings>>,
    rebuild: Option<Res<'w, WindRebuild>>,
    falling: Query<'w, 's, FallingParts>,
    cloths: Query<'w, 's, (Entity, &'static mut Cloth, Option<&'static Name>)>,
    bodies: Query<'w, 's, &'static mut AeroBody>,
    sources: Query<'w, 's, (Entity, &'static mut WindSource, Option<&'static Name>)>,
    shelters: Query<'w, 's, &'static WindShelter>,
    #[cfg(feature = "gizmos")]
    gizmos: Option<ResMut<'w, bevy::gizmos::config::GizmoConfigStore>>,
}

fn show_inspector(
    mut contexts: EguiContexts,
    mut inspector: ResMut<WindfallInspector>,
    mut targets: Targets,
) -> Result {
    if inspector.hidden {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    // Its first frames wait for the window's size (a web page's canvas is sized after the
    // first frame): whether it starts open is decided once, on the real size.
    if ctx.cumulative_pass_nr() < 3 {
        return Ok(());
    }
    // In the top-right corner of any window, also after it is resized; on a small one (a web
    // page's canvas, a laptop's split screen) narrower and folded to its title until opened.
    let screen = ctx.content_rect();
    let width = (0.4 * screen.width()).clamp(200.0, 300.0);
    egui::Window::new("bevy_windfall")
        .anchor(egui::Align2::RIGHT_TOP, [-10.0, 10.0])
        .default_width(width)
        .default_open(screen.width() >= 1000.0)
        .show(ctx, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.collapsing("Wind", |ui| {
                    sections::wind(ui, &mut inspector, &mut targets)
                });
                ui.collapsing("Falling object", |ui| {
                    sections::falling(ui, &mut inspector, &mut targets)
                });
                ui.collapsing("Cloth", |ui| {
                    sections::cloth(ui, &mut inspector, &mut targets)
                });
                ui.collapsing("Local wind", |ui| local::local_wind(ui, &mut targets));
                ui.collapsing("Aero bodies", |ui| sections::aero(ui, &mut targets));
                #[cfg(feature = "gizmos")]
                ui.collapsing("Debug drawing", |ui| sections::gizmos(ui, &mut targets));
            });
        });
    Ok(())
}
