//! What the examples share, none of it needed by a game: the harness CI renders them with
//! ([`ScreenshotPlugin`]: `--screenshot PATH`, `--tour DIR`, `--window WxH`, `--frames N`,
//! `--msaa N`; on the web the page's address), Bevy UI text that fits any window (`layout`,
//! native), the web page's loading indicator and notices ([`page`]), and the showcase's
//! scenery ([`scenery`]).
#![allow(dead_code, unused_imports)] // each example uses a different subset

mod args;
pub mod fingerprint;
mod harness;
#[cfg(not(target_arch = "wasm32"))]
pub mod layout;
pub mod page;
pub mod scenery;

pub use args::{ExampleArgs, SceneOptions};
pub use harness::{
    CheckLayout, DEFAULT_SCREENSHOT_FRAME, LayoutFailures, RECORDED_FRAME, Readiness,
    ScreenshotDone, ScreenshotPlugin, example_app, exit_code, take_screenshot,
};
pub use scenery::{blades, grass, meadow, two_sided};
