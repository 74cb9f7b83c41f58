//! A flag on a pole in a gentle breeze, a banner, and a curtain in a window, shaped by P-type
//! Fourier-descriptor yarns driven by 1/f^β noise and the crate's wind field.
//!
//! Keys: 1 flag, 2 banner, 3 curtain, F frozen / non-frozen, ↑/↓ wind speed.
//! `cargo run --example flag --features example_scenes -- [--scene flag|banner|curtain]
//! [--frames N] [--screenshot PATH]`

mod common;

use bevy::asset::RenderAssetUsages;
use bevy::image::Image;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy_windfall::cloth::ClothWindModel;
use bevy_windfall::prelude::*;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Scene {
    Flag,
    Banner,
    Curtain,
}

#[derive(Resource)]
struct Current(Scene);

#[derive(Component)]
struct Fabric;

#[derive(Component)]
struct InfoText;

#[derive(Resource)]
struct Textures {
    flag: Handle<Image>,
    banner: Handle<Image>,
    curtain: Handle<Image>,
}

fn main() {
    let mut app = common::example_app("bevy_windfall: flag");
    let args = app.world().resource::<common::ExampleArgs>().clone();
    let scene = match args
        .rest
        .windows(2)
        .find(|w| w[0] == "--scene")
        .map(|w| w[1].as_str())
    {
        Some("banner") => Scene::Banner,
        Some("curtain") => Scene::Curtain,
        _ => Scene::Flag,
    };
    app.add_plugins(WindfallPlugins.set(WindPlugin::new(WindConfig {
        reference_speed: 4.5,
        seed: 11,
        ..default()
    })))
    .insert_resource(ClearColor(Color::srgb(0.62, 0.78, 0.92)))
    .insert_resource(Current(scene))
    .insert_resource(bevy_windfall::wind::WindGizmos {
        enabled: false,
        ..default()
    })
    .add_systems(Startup, setup)
    .add_systems(Update, (controls, show_info))
    .run();
}

/// A texture from a function of (u, v) in [0, 1]².
fn paint(images: &mut Assets<Image>, f: impl Fn(f32, f32) -> [u8; 3]) -> Handle<Image> {
    let (w, h) = (256u32, 160u32);
    let mut data = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let [r, g, b] = f(x as f32 / w as f32, y as f32 / h as f32);
            data.extend([r, g, b, 255]);
        }
    }
    images.add(Image::new(
        Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    ))
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    current: Res<Current>,
) {
    let textures = Textures {
        // A tricolour with a golden disk.
        flag: paint(&mut images, |u, v| {
            let d = ((u - 0.5) * 1.6).hypot(v - 0.5);
            if d < 0.17 {
                [240, 190, 40]
            } else if v < 1.0 / 3.0 {
                [20, 60, 150]
            } else if v < 2.0 / 3.0 {
                [245, 245, 240]
            } else {
                [190, 30, 40]
            }
        }),
        // Long pennant stripes along the yarns.
        banner: paint(&mut images, |u, v| {
            if ((v * 6.0) as u32).is_multiple_of(2) {
                [200, 40, 40]
            } else if u < 0.1 {
                [30, 30, 30]
            } else {
                [250, 220, 80]
            }
        }),
        // Light, checked linen.
        curtain: paint(&mut images, |u, v| {
            let check = ((u * 12.0) as u32 + (v * 8.0) as u32) % 2;
            if check == 0 {
                [235, 230, 215]
            } else {
                [215, 225, 235]
            }
        }),
    };
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(-1.0, 4.6, 7.5).looking_at(Vec3::new(1.2, 4.4, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 10_000.0,
            ..default()
        },
        Transform::from_xyz(-4.0, 8.0, 6.0).looking_at(Vec3::new(1.0, 4.0, 0.0), Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 600.0,
        ..default()
    });
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(60.0, 60.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.36, 0.55, 0.32))),
    ));
    let metal = materials.add(Color::srgb(0.75, 0.75, 0.78));
    // Pole for the flag and the banner.
    commands.spawn((
        Mesh3d(meshes.add(Cylinder::new(0.05, 6.0))),
        MeshMaterial3d(metal.clone()),
        Transform::from_xyz(0.0, 3.0, 0.0),
    ));
    // A window frame with a curtain rod, behind and to the side.
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(2.2, 0.06, 0.06))),
        MeshMaterial3d(metal),
        Transform::from_xyz(-2.6, 4.9, -2.5),
    ));
    commands.spawn((
        Fabric,
        Mesh3d(meshes.add(Plane3d::default().mesh().size(0.1, 0.1))),
        MeshMaterial3d(materials.add(StandardMaterial::default())),
        Transform::default(),
    ));
    commands.insert_resource(textures);
    commands.spawn((InfoText, common::info_text()));
    commands.insert_resource(Current(current.0));
    commands.queue(|world: &mut World| {
        let scene = world.resource::<Current>().0;
        apply_scene(world, scene, false);
    });
}

fn cloth_for(scene: Scene, non_frozen: bool) -> (Cloth, Transform) {
    let preset = match (scene, non_frozen) {
        (Scene::Flag, false) => ClothPreset::FlagGentleFrozen,
        (Scene::Flag, true) => ClothPreset::FlagGentleNonFrozen,
        (Scene::Banner, false) => ClothPreset::BannerGentleFrozen,
        (Scene::Banner, true) => ClothPreset::BannerGentleNonFrozen,
        (Scene::Curtain, false) => ClothPreset::CurtainGentleFrozen,
        (Scene::Curtain, true) => ClothPreset::CurtainGentleNonFrozen,
    };
    let mut params = preset.params();
    let (grid, attachment, transform) = match scene {
        Scene::Flag => (
            ClothGrid {
                rows: 28,
                columns: 42,
                width: 2.1,
                height: 1.4,
            },
            ClothAttachment::Pole,
            Transform::from_xyz(0.05, 5.95, 0.0),
        ),
        Scene::Banner => {
            params.bow = 0.12;
            (
                ClothGrid {
                    rows: 14,
                    columns: 64,
                    width: 3.6,
                    height: 0.6,
                },
                ClothAttachment::Pole,
                Transform::from_xyz(0.05, 5.95, 0.0),
            )
        }
        Scene::Curtain => (
            ClothGrid {
                rows: 30,
                columns: 36,
                width: 2.0,
                height: 2.0,
            },
            ClothAttachment::Rod,
            // The rod runs along local +X; the curtain billows along local +Z, into the room.
            Transform::from_xyz(-3.6, 4.88, -2.5),
        ),
    };
    (
        Cloth {
            grid,
            params,
            attachment,
            follow_wind: true,
        },
        transform,
    )
}

fn apply_scene(world: &mut World, scene: Scene, non_frozen: bool) {
    let (cloth, transform) = cloth_for(scene, non_frozen);
    let textures = world.resource::<Textures>();
    let texture = match scene {
        Scene::Flag => textures.flag.clone(),
        Scene::Banner => textures.banner.clone(),
        Scene::Curtain => textures.curtain.clone(),
    };
    let mut q = world.query_filtered::<(Entity, &MeshMaterial3d<StandardMaterial>), With<Fabric>>();
    let (entity, material) = q.single(world).map(|(e, m)| (e, m.0.clone())).unwrap();
    if let Some(mut m) = world
        .resource_mut::<Assets<StandardMaterial>>()
        .get_mut(&material)
    {
        m.base_color_texture = Some(texture);
        m.perceptual_roughness = 0.8;
    }
    world.entity_mut(entity).insert((cloth, transform));
    world.resource_mut::<Current>().0 = scene;
}

fn controls(
    mut commands: Commands,
    keys: Res<ButtonInput<KeyCode>>,
    mut wind: ResMut<WindField>,
    fabric: Single<&Cloth, With<Fabric>>,
    current: Res<Current>,
) {
    let non_frozen = matches!(fabric.params.model, ClothWindModel::NonFrozen { .. });
    for (key, scene) in [
        (KeyCode::Digit1, Scene::Flag),
        (KeyCode::Digit2, Scene::Banner),
        (KeyCode::Digit3, Scene::Curtain),
    ] {
        if keys.just_pressed(key) {
            commands.queue(move |world: &mut World| apply_scene(world, scene, non_frozen));
        }
    }
    if keys.just_pressed(KeyCode::KeyF) {
        let scene = current.0;
        commands.queue(move |world: &mut World| apply_scene(world, scene, !non_frozen));
    }
    let speed = wind.config().reference_speed;
    if keys.just_pressed(KeyCode::ArrowUp) {
        let _ = wind.set_reference_speed(speed + 1.0);
    }
    if keys.just_pressed(KeyCode::ArrowDown) {
        let _ = wind.set_reference_speed((speed - 1.0).max(0.0));
    }
}

fn show_info(
    wind: Res<WindField>,
    current: Res<Current>,
    fabric: Single<(&Cloth, &ClothState, &GlobalTransform), With<Fabric>>,
    mut text: Single<&mut Text, With<InfoText>>,
) {
    let (cloth, state, at) = *fabric;
    let p = &cloth.params;
    let model = match p.model {
        ClothWindModel::Frozen => "frozen",
        ClothWindModel::NonFrozen { .. } => "non-frozen",
    };
    text.0 = format!(
        "{:?} ({model})   wind here {:.1} m/s -> |v| = {:.1} steps/frame   theta = {:.1}   beta = {:.2}   swirl |u| = {}\n\
         1 flag   2 banner   3 curtain   F frozen/non-frozen   Up/Down wind speed",
        current.0,
        wind.velocity(at.translation()).length(),
        state.wind_speed,
        p.amplitude,
        p.beta,
        p.swirl,
    );
}
