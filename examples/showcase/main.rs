//! The showcase: autumn leaves (procedural and physical), the paper's coin falling in water, a
//! flag, banner or curtain, and a gallery of the free-fall paper's motions, in one app sharing
//! one wind field. With `--features egui` the crate's inspector tunes the wind, the falling objects, the cloth
//! and the aero bodies live.
//!
//! Keys: 1 leaves, 2 coin, 3 flag, 4 gallery · G gizmos (off, wind, paths and yarns, all) ·
//! ↑/↓ wind speed · ←/→ wind direction · in the leaves scene B a blast, C the view (a dust devil
//! wanders anyway) · in the flag scene V flag/banner/curtain/physical (the procedural flag beside
//! a particle one), F frozen/evolving (the curtain has a fan).
//!
//! `cargo run --example showcase --features egui -- [--scene leaves|coin|flag|gallery]
//! [--fabric flag|banner|curtain|physical] [--view tree|meadow] [--blades N] [--gizmos]
//! [--check-layout] [--frames N] [--screenshot PATH] [--tour DIR] [--window WxH] [--msaa N]`
//! (on the web the page's address: `?scene=flag&blades=20000`).
//!
//! `--tour DIR` visits every scene and saves `DIR/showcase_<scene>.png` in each, then exits
//! (with `--film`, without the text and the panel, also the leaves' and the flag's last
//! [`FILM_FRAMES`] frames before it, `DIR/film_<scene>_<nn>.png`: the README's moving picture,
//! `docs/film.py`);
//! `--gizmos` starts with the falling paths and cloth yarns drawn; `--blades N` sows N grass
//! blades in the meadow (120 000 by default; a software renderer draws fewer faster);
//! `--check-layout` visits every scene at 640 × 360, 960 × 540 and 1280 × 720 and fails if any
//! on-screen text overlaps another or the panel.

mod coin;
#[path = "../common/mod.rs"]
mod common;
mod flag;
mod gallery;
mod grass;
mod leaves;
#[cfg(feature = "egui")]
mod panel;
mod population;
mod text;

use std::path::PathBuf;

use bevy::diagnostic::{DiagnosticsStore, FrameTimeDiagnosticsPlugin};
use bevy::gizmos::config::GizmoConfigStore;
use bevy::prelude::*;
use bevy_windfall::cloth::ClothGizmos;
use bevy_windfall::freefall::FallGizmos;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindGizmos;

/// The scenes, one at a time; each despawns its entities when left.
#[derive(States, Default, Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Scene {
    /// Autumn leaves from a tree.
    #[default]
    Leaves,
    /// The paper's coin in a water tank.
    Coin,
    /// A flag, banner or curtain.
    Flag,
    /// The six primitive motions and the paper's Fig. 15 objects.
    Gallery,
}

impl Scene {
    const ALL: [Self; 4] = [Self::Leaves, Self::Coin, Self::Flag, Self::Gallery];

    fn name(self) -> &'static str {
        match self {
            Self::Leaves => "leaves",
            Self::Coin => "coin",
            Self::Flag => "flag",
            Self::Gallery => "gallery",
        }
    }
}

/// The showcase's options besides the harness's (`--scene`'s and `--fabric`'s values are the
/// scenes' and fabrics' names).
const OPTIONS: common::SceneOptions = common::SceneOptions(&[
    ("--scene", &["leaves", "coin", "flag", "gallery"]),
    ("--fabric", &["flag", "banner", "curtain", "physical"]),
    ("--view", &["tree", "meadow"]),
    ("--blades", &["N"]),
    ("--gizmos", &[]),
    ("--check-layout", &[]),
    ("--film", &[]),
]);

/// Lines a scene shows under the common header.
#[derive(Resource, Default)]
pub struct SceneInfo(pub String);

/// A falling object the panel edits and reports on (the coin, one leaf).
#[derive(Component)]
pub struct Featured;

/// `--tour DIR`: where the screenshots go and how far the tour is. Each scene is saved once
/// every render pipeline it needs has compiled (software renderers show black frames until then,
/// and the game's clock stands still) and 64 frames have been played.
#[derive(Resource)]
struct Tour {
    dir: PathBuf,
    next: usize,
    frames_in_scene: u32,
    requested: bool,
    /// The falls' fingerprint (`common::fingerprint`), computed before this app runs: an app
    /// updated from inside another app's system waits on the compute pool that system holds.
    fingerprint: u64,
    /// The frame (of those played in the scene) last filmed.
    filmed_at: Option<u32>,
    /// `--film`: the frames before each moving scene's screenshot are saved too.
    film: bool,
}

/// Frames of the leaves and the flag `--film` saves, the last before each scene's screenshot:
/// two seconds on the recording clock (16 frames a second).
const FILM_FRAMES: u32 = 32;

fn main() {
    let mut app = common::example_app("bevy_windfall: showcase");
    let args = app.world().resource::<common::ExampleArgs>().clone();
    app.insert_resource(OPTIONS);
    let start = args
        .choice("--scene", &Scene::ALL.map(|scene| (scene.name(), scene)))
        .unwrap_or_default();
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(WindConfig {
        reference_speed: 2.5,
        // Open grassland with a few trees: grass-high wind is not zero (the log law is 0 at z0).
        roughness: 0.05,
        grid: [96, 96],
        temporal: TemporalMode::Evolving {
            samples: 16,
            period: 20.0,
        },
        seed: 5,
        ..default()
    })))
    .add_plugins((FrameTimeDiagnosticsPlugin::default(), WindfallDebugPlugin))
    .insert_state(start)
    .init_resource::<SceneInfo>()
    .add_plugins((
        leaves::plugin,
        coin::plugin,
        flag::plugin,
        gallery::plugin,
        text::plugin,
    ))
    .add_systems(Update, (switch_scene, toggle_gizmos, steer_wind, show_hud));
    if args.flag("--check-layout") {
        app.init_resource::<LayoutTour>()
            .add_systems(Last, layout_tour);
    } else if let Some(dir) = args.tour.clone() {
        // On the web the screenshots are downloads: the browser chooses the folder.
        #[cfg(not(target_arch = "wasm32"))]
        std::fs::create_dir_all(&dir).expect("--tour: cannot create the folder");
        app.insert_resource(Tour {
            dir,
            next: 0,
            frames_in_scene: 0,
            requested: false,
            fingerprint: common::fingerprint::fingerprint(None),
            film: args.flag("--film"),
            filmed_at: None,
        })
        .insert_state(Scene::ALL[0])
        .add_systems(Last, tour);
    }
    // A film shows the scene alone: no header, no panel.
    let film = args.tour.is_some() && args.flag("--film");
    #[cfg(feature = "egui")]
    if !film {
        app.add_plugins(panel::plugin);
    }
    if film {
        app.insert_resource(text::Hidden);
    }
    // The camera and the header text outlive the scenes; each scene places the camera when it
    // is entered, which for the first scene happens before `Startup`.
    let paths = args.flag("--gizmos");
    let mut store = app.world_mut().resource_mut::<GizmoConfigStore>();
    let (_, wind) = store.config_mut::<WindGizmos>();
    *wind = WindGizmos {
        center: Vec2::new(2.0, 0.0),
        half_extent: Vec2::new(10.0, 6.0),
        height: 1.5,
        ..default()
    };
    store.config_mut::<FallGizmos>().0.enabled = paths;
    store.config_mut::<ClothGizmos>().0.enabled = paths;
    // The focus of the leaf clouds' levels of detail.
    app.world_mut()
        .spawn((Camera3d::default(), LodFocus, LodView::default()));
    app.run();
}

/// Points the shared camera for a scene.
pub fn place_camera(camera: &mut Transform, eye: Vec3, target: Vec3) {
    *camera = Transform::from_translation(eye).looking_at(target, Vec3::Y);
}

fn switch_scene(keys: Res<ButtonInput<KeyCode>>, mut next: ResMut<NextState<Scene>>) {
    for (key, scene) in [
        (KeyCode::Digit1, Scene::Leaves),
        (KeyCode::Digit2, Scene::Coin),
        (KeyCode::Digit3, Scene::Flag),
        (KeyCode::Digit4, Scene::Gallery),
    ] {
        if keys.just_pressed(key) {
            next.set(scene);
        }
    }
}

/// G cycles: off → wind arrows → falling paths and cloth yarns → everything.
fn toggle_gizmos(keys: Res<ButtonInput<KeyCode>>, mut store: ResMut<GizmoConfigStore>) {
    if keys.just_pressed(KeyCode::KeyG) {
        let wind = store.config::<WindGizmos>().0.enabled;
        let falls = store.config::<FallGizmos>().0.enabled;
        let next = (u8::from(wind) + 2 * u8::from(falls) + 1) % 4;
        store.config_mut::<WindGizmos>().0.enabled = next & 1 != 0;
        store.config_mut::<FallGizmos>().0.enabled = next & 2 != 0;
        store.config_mut::<ClothGizmos>().0.enabled = next & 2 != 0;
    }
}

/// The arrow keys edit [`WindSettings`]: speed and direction apply on the next fixed step.
fn steer_wind(keys: Res<ButtonInput<KeyCode>>, mut wind: ResMut<WindSettings>, time: Res<Time>) {
    let dt = time.delta_secs();
    let speed = wind.reference_speed;
    let change = if keys.pressed(KeyCode::ArrowUp) {
        3.0 * dt
    } else if keys.pressed(KeyCode::ArrowDown) {
        -3.0 * dt
    } else {
        0.0
    };
    if change != 0.0 {
        wind.reference_speed = (speed + change).clamp(0.0, 70.0);
    }
    let turn = if keys.pressed(KeyCode::ArrowLeft) {
        dt
    } else if keys.pressed(KeyCode::ArrowRight) {
        -dt
    } else {
        0.0
    };
    if turn != 0.0 {
        wind.direction = Vec2::from_angle(turn).rotate(wind.direction);
    }
}

fn show_hud(
    scene: Res<State<Scene>>,
    info: Res<SceneInfo>,
    wind: Res<WindField>,
    diagnostics: Res<DiagnosticsStore>,
    mut hud: ResMut<text::Hud>,
) {
    let frame_ms = diagnostics
        .get(&FrameTimeDiagnosticsPlugin::FRAME_TIME)
        .and_then(|d| d.smoothed())
        .unwrap_or(0.0);
    hud.0 = format!(
        "{:?}   frame {frame_ms:.1} ms   wind {:.1} m/s at 10 m\n\
         1 leaves  2 coin  3 flag  4 gallery   G gizmos   Up/Down speed   Left/Right direction\n{}",
        scene.get(),
        wind.config().reference_speed,
        info.0
    );
}

/// Saves each scene once it has rendered, then exits.
#[allow(clippy::too_many_arguments)] // a Bevy system's parameters
fn tour(
    mut commands: Commands,
    mut tour: ResMut<Tour>,
    mut readiness: ResMut<common::Readiness>,
    done: Query<Entity, With<common::ScreenshotDone>>,
    mut next: ResMut<NextState<Scene>>,
    mut check: MessageWriter<common::CheckLayout>,
    failures: Res<common::LayoutFailures>,
    mut exit: MessageWriter<AppExit>,
) {
    tour.frames_in_scene += 1;
    // The first scene waits for every shader; later ones only for their own new pipelines.
    if tour.frames_in_scene == 1 {
        readiness.reset();
    }
    if tour.frames_in_scene.is_multiple_of(50) {
        info!("tour: scene {}, frame {}", tour.next, tour.frames_in_scene);
    }
    let Some(&scene) = Scene::ALL.get(tour.next) else {
        return; // The tour is over: the app is exiting.
    };
    let played = readiness.played();
    let filmed = matches!(scene, Scene::Leaves | Scene::Flag);
    if tour.film
        && filmed
        && !tour.requested
        && (common::DEFAULT_SCREENSHOT_FRAME - FILM_FRAMES..common::DEFAULT_SCREENSHOT_FRAME)
            .contains(&played)
        && tour.filmed_at != Some(played)
    {
        // A plain save: only the scene's own screenshot moves the tour on.
        tour.filmed_at = Some(played);
        let n = played + FILM_FRAMES - common::DEFAULT_SCREENSHOT_FRAME;
        let path = tour.dir.join(format!("film_{}_{n:02}.png", scene.name()));
        commands
            .spawn(bevy::render::view::screenshot::Screenshot::primary_window())
            .observe(bevy::render::view::screenshot::save_to_disk(path));
    }
    if played >= common::DEFAULT_SCREENSHOT_FRAME && !tour.requested {
        tour.requested = true;
        let path = tour.dir.join(format!("showcase_{}.png", scene.name()));
        check.write(common::CheckLayout(path.display().to_string()));
        common::take_screenshot(&mut commands, path);
        // The clock stands still from the request until the next scene has compiled: the
        // screenshot's read-back takes a varying number of frames.
        readiness.reset();
    }
    for entity in &done {
        commands.entity(entity).despawn();
        tour.next += 1;
        tour.frames_in_scene = 0;
        tour.requested = false;
        match Scene::ALL.get(tour.next) {
            Some(&scene) => next.set(scene),
            None => {
                // The falls' fingerprint: the same on every machine and in the browser (CI
                // compares the browser's with the desktop's).
                info!("fingerprint: {:016x}", tour.fingerprint);
                exit.write(common::exit_code(&failures));
            }
        }
    }
}

/// `--check-layout`: which scene at which window size is being laid out.
#[derive(Resource, Default)]
struct LayoutTour {
    step: usize,
    frames: u32,
}

/// Visits every scene at each of these window sizes and checks its text once laid out.
const LAYOUT_SIZES: [(u32, u32); 3] = [(640, 360), (960, 540), (1280, 720)];

/// Frames a scene is given to lay its text out (fonts, the panel, labels following the camera).
const LAYOUT_FRAMES: u32 = 12;

fn layout_tour(
    mut tour: ResMut<LayoutTour>,
    mut window: Single<&mut Window>,
    mut next: ResMut<NextState<Scene>>,
    mut check: MessageWriter<common::CheckLayout>,
    failures: Res<common::LayoutFailures>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(&(width, height)) = LAYOUT_SIZES.get(tour.step / Scene::ALL.len()) else {
        exit.write(common::exit_code(&failures));
        return;
    };
    let scene = Scene::ALL[tour.step % Scene::ALL.len()];
    tour.frames += 1;
    if tour.frames == 1 {
        window.resolution.set(width as f32, height as f32);
        next.set(scene);
    } else if tour.frames == LAYOUT_FRAMES {
        let name = format!("the {} scene at {width} x {height}", scene.name());
        check.write(common::CheckLayout(name));
    } else if tour.frames > LAYOUT_FRAMES {
        tour.step += 1;
        tour.frames = 0;
    }
}
