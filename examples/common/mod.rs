//! What every example scene shares: `--frames N`, `--screenshot PATH`, `--window WxH`.
#![allow(dead_code)]

use std::path::PathBuf;

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::window::WindowResolution;

/// Command-line options of the example scenes.
#[derive(Resource, Clone, Debug, Default)]
pub struct ExampleArgs {
    /// Run this many frames, then exit.
    pub frames: Option<u32>,
    /// Save a screenshot here once the scene has rendered, then exit.
    pub screenshot: Option<PathBuf>,
    /// Window size in pixels (default 1280 × 720; CI renders smaller, in software).
    pub window: Option<(u32, u32)>,
    /// Other arguments, for the scene itself.
    pub rest: Vec<String>,
}

impl ExampleArgs {
    /// Reads `--frames N`, `--screenshot PATH` and `--window WxH` from the command line.
    pub fn parse() -> Self {
        let mut args = Self::default();
        let mut it = std::env::args().skip(1);
        while let Some(arg) = it.next() {
            match arg.as_str() {
                "--frames" => {
                    args.frames = it.next().and_then(|n| n.parse().ok());
                }
                "--screenshot" => args.screenshot = it.next().map(PathBuf::from),
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
}

/// Software renderers show black frames while shaders compile: the screenshot waits this long
/// unless `--frames` says when.
const DEFAULT_SCREENSHOT_FRAME: u32 = 400;

/// `DefaultPlugins` with a window titled `title` (1280×720 unless `--window` says), plus the
/// `--frames`/`--screenshot` handling.
pub fn example_app(title: &str) -> App {
    let args = ExampleArgs::parse();
    let (width, height) = args.window.unwrap_or((1280, 720));
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(WindowPlugin {
        primary_window: Some(Window {
            title: title.into(),
            resolution: WindowResolution::new(width, height),
            ..default()
        }),
        ..default()
    }))
    .insert_resource(args)
    .init_resource::<FrameCount>()
    .add_systems(Last, frames_and_screenshot);
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
    mut count: ResMut<FrameCount>,
    done: Query<(), With<ScreenshotDone>>,
    mut exit: MessageWriter<AppExit>,
) {
    count.frames += 1;
    if let Some(path) = &args.screenshot {
        let at = args.frames.unwrap_or(DEFAULT_SCREENSHOT_FRAME);
        if count.frames >= at && !count.requested {
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
            Mesh3d(meshes.add(Plane3d::default().mesh().size(size, size))),
            MeshMaterial3d(materials.add(Color::srgb(0.38, 0.52, 0.28))),
        ))
        .id();
    [light, ground]
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
