//! What the examples share: [`ScreenshotPlugin`], how CI renders them (`--screenshot PATH`,
//! `--tour DIR`, `--window WxH`, `--frames N`), and the showcase's scenery. Nothing a game needs.
#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use bevy::prelude::*;
use bevy::render::render_resource::{PipelineCache, PipelineDescriptor};
use bevy::render::renderer::RenderDevice;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::render::{Render, RenderApp, RenderSystems};
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowResolution;

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
    /// Other arguments, for the scene itself.
    pub rest: Vec<String>,
}

impl ExampleArgs {
    /// Reads `--frames N`, `--screenshot PATH`, `--tour DIR` and `--window WxH` from the command
    /// line.
    pub fn parse() -> Self {
        let mut args = Self::default();
        let mut it = command_line().into_iter();
        while let Some(arg) = it.next() {
            match arg.as_str() {
                "--frames" => {
                    args.frames = it.next().and_then(|n| n.parse().ok());
                }
                "--screenshot" => args.screenshot = it.next().map(PathBuf::from),
                "--tour" => args.tour = it.next().map(PathBuf::from),
                "--window" => {
                    args.window = it.next().and_then(|s| {
                        let (w, h) = s.split_once('x')?;
                        Some((w.parse().ok()?, h.parse().ok()?))
                    });
                }
                _ => args.rest.push(arg),
            }
        }
        args
    }

    /// Whether screenshots are being recorded (`--screenshot` or `--tour`): then the game runs
    /// on the [`RECORDED_FRAME`] clock.
    pub fn recording(&self) -> bool {
        self.screenshot.is_some() || self.tour.is_some()
    }
}

/// The arguments after the program's name; on the web, the page's address as a command line:
/// `index.html?scene=flag&tour=shots` reads as `--scene flag --tour shots` (values are taken as
/// written, not percent-decoded).
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

/// The game time one frame takes while recording. A software renderer takes 0.1–1.5 s a frame,
/// and a clock that followed it would show each scene at a different moment on each run (a leaf
/// storm that had half landed, or not yet): recorded frames each last 62.5 ms of game time (four
/// of Bevy's default 64 Hz fixed steps), and none passes while shaders compile, so every
/// screenshot shows its scene at the same moment, 4 s in.
pub const RECORDED_FRAME: Duration = Duration::from_micros(62_500);

/// Software renderers show black frames while shaders compile: a screenshot waits until
/// [`Readiness::ready`], then this many frames (or `--frames`) of [`RECORDED_FRAME`] each.
pub const DEFAULT_SCREENSHOT_FRAME: u32 = 64;

/// Render pipelines still compiling, counted by the render world each frame.
#[derive(Resource, Clone, Default)]
struct PendingPipelines(Arc<AtomicUsize>);

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
    pending.0.store(waiting, Ordering::Relaxed);
}

/// Whether the renderer has caught up: no pipeline has been waiting for the last
/// [`Readiness::CALM`] frames. Screenshots wait for it; on a cold software renderer that can
/// take minutes.
#[derive(Resource, Default)]
pub struct Readiness {
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
    if pending.0.load(Ordering::Relaxed) == 0 {
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

/// How CI renders an example (not needed in a game): `--screenshot PATH` saves the window once
/// every render pipeline has compiled and 64 frames (or `--frames N`) have been played on the
/// [`RECORDED_FRAME`] clock, and exits; `--window WxH` sizes the window; `--frames N` alone
/// exits after N frames. Add it after `DefaultPlugins`.
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
            .init_resource::<FrameCount>()
            .init_resource::<Readiness>()
            .add_systems(First, track_readiness.before(bevy::time::TimeSystems))
            .add_systems(Last, frames_and_screenshot);
        let pending = PendingPipelines::default();
        app.insert_resource(pending.clone());
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

fn frames_and_screenshot(
    mut commands: Commands,
    args: Res<ExampleArgs>,
    readiness: Res<Readiness>,
    mut count: ResMut<FrameCount>,
    done: Query<(), With<ScreenshotDone>>,
    mut exit: MessageWriter<AppExit>,
) {
    count.frames += 1;
    if let Some(path) = &args.screenshot {
        let at = args.frames.unwrap_or(DEFAULT_SCREENSHOT_FRAME);
        if readiness.played() >= at && !count.requested {
            count.requested = true;
            take_screenshot(&mut commands, path.clone());
        }
        if !done.is_empty() {
            info!("screenshot saved to {}", path.display());
            exit.write(AppExit::Success);
        }
    } else if args.frames.is_some_and(|n| count.frames >= n) {
        exit.write(AppExit::Success);
    }
}

/// A block of black text in the top-left corner, for a scene's live figures and keys.
pub fn info_text() -> impl Bundle {
    (
        Text::new(""),
        TextFont {
            font_size: FontSize::Px(18.0),
            ..default()
        },
        TextColor(Color::BLACK),
        Node {
            position_type: PositionType::Absolute,
            top: px(10),
            left: px(12),
            ..default()
        },
    )
}

/// A sunlit meadow: a directional light from `sun` toward the origin, ambient light and a grass
/// plane `size` metres across at y = 0. Returns the light and the plane.
pub fn meadow(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
    sun: Vec3,
    size: f32,
) -> [Entity; 2] {
    let light = commands
        .spawn((
            DirectionalLight {
                illuminance: 9_000.0,
                ..default()
            },
            Transform::from_translation(sun).looking_at(Vec3::ZERO, Vec3::Y),
        ))
        .id();
    commands.insert_resource(GlobalAmbientLight {
        brightness: 700.0,
        ..default()
    });
    let ground = commands
        .spawn((
            Mesh3d(meshes.add(grass(size, Color::srgb(0.38, 0.52, 0.28)))),
            MeshMaterial3d(materials.add(Color::WHITE)),
        ))
        .id();
    [light, ground]
}

/// A grass plane `size` metres across at y = 0, in patches of lighter and darker green around
/// `color` (vertex colours from a few crossed sines: lush and dry patches a few metres wide), so
/// that the ground reads as a meadow rather than a flat sheet.
pub fn grass(size: f32, color: Color) -> Mesh {
    let cells = 96;
    let mut mesh = Plane3d::default()
        .mesh()
        .size(size, size)
        .subdivisions(cells - 1)
        .build();
    let Some(bevy::mesh::VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        return mesh;
    };
    let base = color.to_linear();
    let colors: Vec<[f32; 4]> = positions
        .iter()
        .map(|&[x, _, z]| {
            let patches = (0.43 * x + 0.2 * z).sin() * (0.31 * z - 0.15 * x).cos()
                + 0.5 * (1.7 * x + 1.1).sin() * (1.3 * z + 0.4).sin();
            let light = 1.0 + 0.22 * patches;
            let dry = (0.5 + 0.5 * (0.11 * x - 0.23 * z + 2.0).sin()).powi(3);
            [
                base.red * light * (1.0 + 0.5 * dry),
                base.green * light,
                base.blue * light * (1.0 - 0.3 * dry),
                1.0,
            ]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    mesh
}

/// A matte material seen from both sides (leaves, cloth).
pub fn two_sided(
    materials: &mut Assets<StandardMaterial>,
    color: Color,
) -> Handle<StandardMaterial> {
    materials.add(StandardMaterial {
        base_color: color,
        double_sided: true,
        cull_mode: None,
        perceptual_roughness: 0.8,
        ..default()
    })
}
