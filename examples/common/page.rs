//! The web page around the game (`web/index.html`): its loading indicator says "compiling
//! shaders…" until the scene's first frame (the page itself shows the download before that), and
//! its notice line answers a bad option. Natively a bad option is an error on the command line.

use bevy::prelude::*;

use super::harness::Readiness;

/// Answers a bad option: natively an error and exit code 2; on the page a notice above the game,
/// which goes on with its defaults.
pub fn refuse(message: &str) {
    #[cfg(not(target_arch = "wasm32"))]
    {
        eprintln!("error: {message}");
        std::process::exit(2);
    }
    #[cfg(target_arch = "wasm32")]
    {
        warn!("{message}");
        if let Some(notice) = element("notice") {
            let text = notice.text_content().unwrap_or_default();
            let text = if text.is_empty() {
                message.to_string()
            } else {
                format!("{text}\n{message}")
            };
            notice.set_text_content(Some(&text));
            let _ = notice.remove_attribute("hidden");
        }
    }
}

/// Shows the page's loading indicator while the scene's shaders compile, hides it from the first
/// frame drawn (a scene that brings new pipelines shows it again until they are in).
pub fn show_loading(readiness: Res<Readiness>, mut shown: Local<Option<bool>>) {
    let loading = !readiness.drawing();
    if *shown == Some(loading) {
        return;
    }
    *shown = Some(loading);
    #[cfg(target_arch = "wasm32")]
    if let Some(indicator) = element("loading") {
        if loading {
            if let Some(status) = element("status") {
                status.set_text_content(Some("compiling shaders…"));
            }
            let _ = indicator.remove_attribute("hidden");
        } else {
            let _ = indicator.set_attribute("hidden", "");
        }
    }
}

#[cfg(target_arch = "wasm32")]
fn element(id: &str) -> Option<web_sys::Element> {
    web_sys::window()?.document()?.get_element_by_id(id)
}
