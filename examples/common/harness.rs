//! How CI renders an example: `--screenshot PATH` saves the window once every render pipeline
//! has compiled and 64 frames (or `--frames N`) have been played on the [`RECORDED_FRAME`] clock,
//! then exits; `--window WxH` sizes the window; `--msaa N` sets every camera's samples per
//! pixel; `--frames N` alone exits after N frames. Each screenshot also checks that no on-screen
//! text overlaps another or a panel ([`CheckLayout`]); an overlap makes the run fail.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use bevy::prelude::*;
use bevy::render::render_resource::{PipelineCache, PipelineDescriptor};
use bevy::render::renderer::RenderDevice;
use bevy::render::view::Msaa;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::render::{Render, RenderApp, RenderSystems};
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowResolution;

use super::args::{ExampleArgs, SceneOptions, refuse_unknown};
use super::page;

/// Asks for a layout check now (the screenshot's name, for the log): the on-screen text may not
/// overlap other text or a panel, or run out of the window.
#[derive(Message, Clone, Debug)]
pub struct CheckLayout(pub String);

/// Screenshots whose layout check failed: the run then exits with an error.
#[derive(Resource, Default, Debug)]
pub struct LayoutFailures(pub u32);

/// The game time one frame takes while recording. A software renderer takes 0.1–1.5 s a frame,
/// and a clock that followed it would show each scene at a different moment on each run (a leaf
/// storm that had half landed, or not yet): recorded frames each last 62.5 ms of game time (four
/// of Bevy's default 64 Hz fixed steps), and none passes while shaders compile, so every
/// screenshot shows its scene at the same moment, 4 s in.
pub const RECORDED_FRAME: Duration = Duration::from_micros(62_500);

/// Software renderers show black frames while shaders compile: a screenshot waits until
/// [`Readiness::ready`], then this many frames (or `--frames`) of [`RECORDED_FRAME`] each.
pub const DEFAULT_SCREENSHOT_FRAME: u32 = 64;

/// Render pipelines still compiling, counted by the render world each frame, and (in the
/// top bit) whether any pipeline has been asked for at all.
#[derive(Resource, Clone, Default)]
struct PendingPipelines(Arc<AtomicUsize>);

/// The bit of [`PendingPipelines`] set once the cache holds a pipeline.
const ANY_PIPELINE: usize = 1 << (usize::BITS - 1);

/// On a device without compute shaders (WebGL2, or WebGL2's limits natively) compute pipelines
/// are not counted: Bevy queues one it cannot build (the sparse buffer update) again every frame,
/// and the scene would never count as rendered.
fn count_pending_pipelines(
    cache: Res<PipelineCache>,
    device: Res<RenderDevice>,
    pending: Res<PendingPipelines>,
) {
    let compute = device.limits().max_compute_workgroups_per_dimension > 0;
    let pipelines: Vec<_> = cache.pipelines().collect();
    let waiting = cache
        .waiting_pipelines()
        .filter(|&id| {
            compute
                || pipelines.get(id).is_some_and(|p| {
                    matches!(
                        p.descriptor,
                        PipelineDescriptor::RenderPipelineDescriptor(_)
                    )
                })
        })
        .count();
    let seen = if pipelines.is_empty() {
        0
    } else {
        ANY_PIPELINE
    };
    pending.0.store(waiting | seen, Ordering::Relaxed);
}

/// Whether the renderer has caught up: no pipeline has been waiting for the last
/// [`Readiness::CALM`] frames. Screenshots wait for it; on a cold software renderer that can
/// take minutes.
#[derive(Resource, Default)]
pub struct Readiness {
    /// Whether the renderer has been asked for any pipeline yet (none in the first frames).
    pipelines_seen: bool,
    calm_frames: u32,
    /// Frames played since the renderer caught up (the recording clock runs in these only).
    played: u32,
}

impl Readiness {
    /// Frames without a waiting pipeline before the scene counts as rendered.
    pub const CALM: u32 = 30;

    /// True once every pipeline the scene needs has compiled.
    pub fn ready(&self) -> bool {
        self.calm_frames >= Self::CALM
    }

    /// True from the first frame drawn with every pipeline asked for compiled.
    pub fn drawing(&self) -> bool {
        self.pipelines_seen && self.calm_frames > 0
    }

    /// Frames played since [`Self::ready`] turned true (since the last [`Self::reset`]).
    pub fn played(&self) -> u32 {
        self.played
    }

    /// Starts counting again (a new scene brings new pipelines).
    pub fn reset(&mut self) {
        self.calm_frames = 0;
        self.played = 0;
    }
}

fn track_readiness(pending: Res<PendingPipelines>, mut readiness: ResMut<Readiness>) {
    let pending = pending.0.load(Ordering::Relaxed);
    readiness.pipelines_seen |= pending & ANY_PIPELINE != 0;
    if pending & !ANY_PIPELINE == 0 {
        readiness.calm_frames += 1;
    } else {
        readiness.calm_frames = 0;
    }
    readiness.played += u32::from(readiness.ready());
}

/// While recording, the game's clock stands still until the renderer has caught up. Runs before
/// Bevy's clock update, so game time passes in exactly the frames counted as played.
fn hold_time_until_ready(readiness: Res<Readiness>, mut time: ResMut<Time<Virtual>>) {
    if readiness.ready() {
        time.unpause();
    } else {
        time.pause();
    }
}

/// The harness (not needed in a game): the options of [`ExampleArgs`], the recording clock,
/// screenshots, the layout check and the web page's indicator. Add it after `DefaultPlugins`.
pub struct ScreenshotPlugin;

impl Plugin for ScreenshotPlugin {
    fn build(&self, app: &mut App) {
        let args = ExampleArgs::parse();
        if let Some((width, height)) = args.window {
            let size = move |mut windows: Query<&mut Window>| {
                for mut window in &mut windows {
                    window.resolution = WindowResolution::new(width, height);
                }
            };
            app.add_systems(Startup, size);
        }
        if let Some(samples) = args.msaa {
            let msaa = match samples {
                1 => Msaa::Off,
                2 => Msaa::Sample2,
                8 => Msaa::Sample8,
                _ => Msaa::Sample4,
            };
            let set = move |mut commands: Commands, cameras: Query<Entity, Added<Camera>>| {
                for camera in &cameras {
                    commands.entity(camera).insert(msaa);
                }
            };
            app.add_systems(PostUpdate, set);
        }
        if args.recording() {
            app.insert_resource(TimeUpdateStrategy::ManualDuration(RECORDED_FRAME))
                .add_systems(
                    First,
                    hold_time_until_ready
                        .after(track_readiness)
                        .before(bevy::time::TimeSystems),
                );
        }
        app.insert_resource(args)
            .init_resource::<SceneOptions>()
            .init_resource::<FrameCount>()
            .init_resource::<Readiness>()
            .init_resource::<LayoutFailures>()
            .add_message::<CheckLayout>()
            .add_systems(
                PreStartup,
                |args: Res<ExampleArgs>, scene: Res<SceneOptions>| refuse_unknown(&args, &scene),
            )
            .add_systems(First, track_readiness.before(bevy::time::TimeSystems))
            .add_systems(Update, page::show_loading)
            .add_systems(Last, frames_and_screenshot);
        let pending = PendingPipelines::default();
        app.insert_resource(pending.clone());
        #[cfg(not(target_arch = "wasm32"))]
        app.add_plugins(super::layout::plugin);
        app.sub_app_mut(RenderApp)
            .insert_resource(pending)
            .add_systems(
                Render,
                count_pending_pipelines.in_set(RenderSystems::Cleanup),
            );
    }
}

/// `DefaultPlugins` with a window titled `title`, plus [`ScreenshotPlugin`].
pub fn example_app(title: &str) -> App {
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(Window {
            title: title.into(),
            // On the web: draw into the page's `<canvas id="bevy">`, sized by the page.
            canvas: Some("#bevy".into()),
            fit_canvas_to_parent: true,
            ..default()
        }),
        ..default()
    }))
    .add_plugins(ScreenshotPlugin);
    app
}

#[derive(Resource, Default)]
struct FrameCount {
    frames: u32,
    requested: bool,
}

/// Marks a screenshot request whose image has been captured (and is being saved).
#[derive(Component)]
pub struct ScreenshotDone;

/// Saves the primary window to `path`; the request entity gets [`ScreenshotDone`] once captured.
pub fn take_screenshot(commands: &mut Commands, path: PathBuf) {
    commands
        .spawn(Screenshot::primary_window())
        .observe(save_to_disk(path))
        .observe(|captured: On<ScreenshotCaptured>, mut commands: Commands| {
            commands.entity(captured.entity).insert(ScreenshotDone);
        });
}

/// The exit once the screenshot is saved (or `--frames` have passed): a failure if the layout
/// check found overlapping text in any screenshot.
pub fn exit_code(failures: &LayoutFailures) -> AppExit {
    if failures.0 == 0 {
        AppExit::Success
    } else {
        error!("{} screenshot(s) with overlapping text", failures.0);
        AppExit::error()
    }
}

// A Bevy system: its parameters are what it reads, not a call site to shorten.
#[allow(clippy::too_many_arguments)]
fn frames_and_screenshot(
    mut commands: Commands,
    args: Res<ExampleArgs>,
    readiness: Res<Readiness>,
    mut count: ResMut<FrameCount>,
    done: Query<(), With<ScreenshotDone>>,
    mut check: MessageWriter<CheckLayout>,
    failures: Res<LayoutFailures>,
    mut exit: MessageWriter<AppExit>,
) {
    count.frames += 1;
    if let Some(path) = &args.screenshot {
        let at = args.frames.unwrap_or(DEFAULT_SCREENSHOT_FRAME);
        if readiness.played() >= at && !count.requested {
            count.requested = true;
            take_screenshot(&mut commands, path.clone());
            check.write(CheckLayout(path.display().to_string()));
        }
        if !done.is_empty() {
            info!("screenshot saved to {}", path.display());
            exit.write(exit_code(&failures));
        }
    } else if args.frames.is_some_and(|n| count.frames >= n) {
        exit.write(exit_code(&failures));
    }
}
