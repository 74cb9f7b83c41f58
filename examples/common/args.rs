//! The examples' options: the harness's own (`--screenshot PATH`, `--tour DIR`, `--window WxH`,
//! `--frames N`, `--msaa N`) and a scene's (the showcase's `--scene`, `--fabric`, ...). On the
//! web the page's address is the command line: `index.html?scene=flag&tour=shots` reads as
//! `--scene flag --tour shots`. An option that is not known, or a value that is not valid, is
//! answered with the valid ones: on the command line an error (exit code 2), on the page a notice
//! above the game, which then starts with its defaults.

use std::path::PathBuf;

use bevy::prelude::*;

/// The harness's options, as `--help` shows them.
pub const HARNESS_OPTIONS: &str =
    "--screenshot PATH, --tour DIR, --window WxH, --frames N, --msaa 1|2|4|8";

/// Command-line options of the example scenes.
#[derive(Resource, Clone, Debug, Default)]
pub struct ExampleArgs {
    /// Run this many frames, then exit; with a screenshot, take it after this many frames
    /// played once the renderer has caught up.
    pub frames: Option<u32>,
    /// Save a screenshot here once the scene has rendered, then exit.
    pub screenshot: Option<PathBuf>,
    /// Save a screenshot of each scene into this folder (the showcase's tour), then exit.
    pub tour: Option<PathBuf>,
    /// Window size in pixels (default 1280 × 720; CI renders smaller, in software).
    pub window: Option<(u32, u32)>,
    /// Samples per pixel of every camera (1: multisampling off). CI renders with 1: a software
    /// renderer takes about four times as long with Bevy's default of 4.
    pub msaa: Option<u32>,
    /// The scene's own options, as `(name, value)` (`("--scene", Some("flag"))`).
    pub rest: Vec<(String, Option<String>)>,
}

/// A scene's options and their values: `(name, valid values)`, an empty list for a flag and
/// `&["N"]` for a number. Options not listed here (or in the harness) are refused.
#[derive(Resource, Clone, Copy, Debug, Default)]
pub struct SceneOptions(pub &'static [(&'static str, &'static [&'static str])]);

impl ExampleArgs {
    /// Reads the options from the command line (the page's address on the web).
    pub fn parse() -> Self {
        Self::from_words(command_line())
    }

    fn from_words(words: Vec<String>) -> Self {
        let mut args = Self::default();
        let mut it = words.into_iter().peekable();
        while let Some(name) = it.next() {
            let value = it.next_if(|w| !w.starts_with("--"));
            let number = |v: &Option<String>| v.as_deref().and_then(|n| n.parse().ok());
            match name.as_str() {
                "--frames" => args.frames = number(&value).or_else(|| bad(&name, &value, "N")),
                "--screenshot" => args.screenshot = value.map(PathBuf::from),
                "--tour" => args.tour = value.map(PathBuf::from),
                "--window" => {
                    let size = value.as_deref().and_then(|s| {
                        let (w, h) = s.split_once('x')?;
                        Some((w.parse().ok()?, h.parse().ok()?))
                    });
                    args.window = size.or_else(|| bad(&name, &value, "WxH"));
                }
                "--msaa" => {
                    args.msaa = number(&value)
                        .filter(|n| [1, 2, 4, 8].contains(n))
                        .or_else(|| bad(&name, &value, "1, 2, 4 or 8"));
                }
                _ => args.rest.push((name, value)),
            }
        }
        args
    }

    /// Whether screenshots are being recorded (`--screenshot` or `--tour`): then the game runs
    /// on the [`super::RECORDED_FRAME`] clock.
    pub fn recording(&self) -> bool {
        self.screenshot.is_some() || self.tour.is_some()
    }

    /// Whether the flag `name` (`"--gizmos"`) was given.
    pub fn flag(&self, name: &str) -> bool {
        self.rest.iter().any(|(n, _)| n == name)
    }

    /// The value of `name`, one of `valid` (returned with its `T`); a value not among them is
    /// answered with the valid ones, and gives `None`.
    pub fn choice<T: Copy>(&self, name: &str, valid: &[(&str, T)]) -> Option<T> {
        let (_, value) = self.rest.iter().find(|(n, _)| n == name)?;
        let found = valid
            .iter()
            .find(|(v, _)| Some(*v) == value.as_deref())
            .map(|&(_, t)| t);
        found.or_else(|| {
            let names: Vec<_> = valid.iter().map(|(v, _)| *v).collect();
            bad(name, value, &names.join(", "))
        })
    }

    /// The number given as `name`, within `range`; anything else is answered with the range.
    pub fn number(&self, name: &str, range: std::ops::RangeInclusive<usize>) -> Option<usize> {
        let (_, value) = self.rest.iter().find(|(n, _)| n == name)?;
        let n = value.as_deref().and_then(|v| v.parse().ok());
        n.filter(|n| range.contains(n)).or_else(|| {
            let span = format!("a number from {} to {}", range.start(), range.end());
            bad(name, value, &span)
        })
    }
}

/// Refuses every option that neither the harness nor the scene knows, naming the valid ones.
pub fn refuse_unknown(args: &ExampleArgs, scene: &SceneOptions) {
    for (name, _) in &args.rest {
        if !scene.0.iter().any(|(known, _)| known == name) {
            let mut valid: Vec<String> = scene
                .0
                .iter()
                .map(|(n, values)| match values {
                    [] => n.to_string(),
                    _ => format!("{n} {}", values.join("|")),
                })
                .collect();
            valid.push(HARNESS_OPTIONS.into());
            super::page::refuse(&format!(
                "unknown option {name}; the options are: {}",
                valid.join(", ")
            ));
        }
    }
}

/// Answers a bad value of `name` with what it should be.
fn bad<T>(name: &str, value: &Option<String>, valid: &str) -> Option<T> {
    let given = value.as_deref().unwrap_or("nothing");
    super::page::refuse(&format!("{name}: {given} is not one of: {valid}"));
    None
}

/// The arguments after the program's name; on the web, the page's address as a command line
/// (values are taken as written, not percent-decoded).
fn command_line() -> Vec<String> {
    #[cfg(not(target_arch = "wasm32"))]
    let line = std::env::args().skip(1).collect();
    #[cfg(target_arch = "wasm32")]
    let line = {
        let query = web_sys::window()
            .and_then(|window| window.location().search().ok())
            .unwrap_or_default();
        query
            .trim_start_matches('?')
            .split('&')
            .filter(|pair| !pair.is_empty())
            .flat_map(|pair| {
                let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
                std::iter::once(format!("--{key}"))
                    .chain((!value.is_empty()).then(|| value.to_string()))
            })
            .collect()
    };
    line
}
