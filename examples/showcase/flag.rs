//! A flag on a pole, a banner on a mast, or a curtain in an open window, shaped by P-type
//! Fourier-descriptor yarns driven by 1/f^β noise and the shared wind field, each with its Table 1
//! preset named on screen; and the procedural flag beside the physical one (a `PhysicalCloth`:
//! particles pushed by per-face lift and drag). V cycles them, F switches to the same object's
//! row of the other wind model (frozen or evolving).

use bevy::asset::RenderAssetUsages;
use bevy::image::Image;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy_windfall::cloth::{ClothWindModel, HarmonicFilter};
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindSource;

use super::{Scene, SceneInfo, common, place_camera};

/// What hangs in the wind.
#[derive(Resource, Clone, Copy, PartialEq, Eq, Debug, Default)]
pub enum Fabric {
    #[default]
    Flag,
    Banner,
    Curtain,
    /// The procedural flag with a physical one on a second pole upwind.
    Physical,
}

impl Fabric {
    /// Table 1 row for this fabric in a gentle breeze.
    pub fn preset(self, evolving: bool) -> ClothPreset {
        match (self, evolving) {
            (Self::Flag | Self::Physical, false) => ClothPreset::FlagFlappingFrozen,
            (Self::Flag | Self::Physical, true) => ClothPreset::FlagFlappingEvolving,
            (Self::Banner, false) => ClothPreset::BannerFlappingFrozen,
            (Self::Banner, true) => ClothPreset::BannerFlappingEvolving,
            (Self::Curtain, false) => ClothPreset::CurtainDriftingFrozen,
            (Self::Curtain, true) => ClothPreset::CurtainDriftingEvolving,
        }
    }

    const ALL: [Self; 4] = [Self::Flag, Self::Banner, Self::Curtain, Self::Physical];

    fn name(self) -> &'static str {
        match self {
            Self::Flag => "flag",
            Self::Banner => "banner",
            Self::Curtain => "curtain",
            Self::Physical => "physical",
        }
    }

    fn next(self) -> Self {
        match self {
            Self::Flag => Self::Banner,
            Self::Banner => Self::Curtain,
            Self::Curtain => Self::Physical,
            Self::Physical => Self::Flag,
        }
    }
}

/// Height of the window's sill, m.
const WINDOW_BOTTOM: f32 = 0.9;

/// The cloth entity.
#[derive(Component)]
pub struct Hanging;

/// The physical flag and its pole, there only with [`Fabric::Physical`].
#[derive(Component)]
struct PhysicalSide;

/// Where the physical flag's pole stands: 3.4 m upwind of the procedural one, so the two fly
/// side by side in the camera's view.
const PHYSICAL_POLE: Vec3 = Vec3::new(-3.4, 0.0, 0.0);

/// Scenery shown only with one fabric: the pole with the flag and banner, the wall, window and
/// rod with the curtain.
#[derive(Component)]
struct Setting(&'static [Fabric]);

#[derive(Resource)]
struct Textures([Handle<Image>; 3]);

pub fn plugin(app: &mut App) {
    // `--fabric flag|banner|curtain|physical` picks the first fabric.
    let fabric = app
        .world()
        .resource::<super::common::ExampleArgs>()
        .choice("--fabric", &Fabric::ALL.map(|f| (f.name(), f)))
        .unwrap_or_default();
    app.insert_resource(fabric)
        .add_systems(Startup, paint_textures)
        .add_systems(OnEnter(Scene::Flag), setup)
        .add_systems(
            Update,
            (
                keys,
                apply_fabric.run_if(resource_changed::<Fabric>),
                show_info,
            )
                .chain()
                .run_if(in_state(Scene::Flag)),
        );
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
    let size = Extent3d {
        width: w,
        height: h,
        depth_or_array_layers: 1,
    };
    let format = TextureFormat::Rgba8UnormSrgb;
    let usage = RenderAssetUsages::RENDER_WORLD;
    images.add(Image::new(size, TextureDimension::D2, data, format, usage))
}

fn paint_textures(mut commands: Commands, mut images: ResMut<Assets<Image>>) {
    // A tricolour with a golden disk; pennant stripes; checked linen.
    let flag = paint(&mut images, |u, v| {
        if ((u - 0.5) * 1.6).hypot(v - 0.5) < 0.17 {
            [240, 190, 40]
        } else if v < 1.0 / 3.0 {
            [20, 60, 150]
        } else if v < 2.0 / 3.0 {
            [245, 245, 240]
        } else {
            [190, 30, 40]
        }
    });
    let banner = paint(&mut images, |u, v| {
        if ((v * 6.0) as u32).is_multiple_of(2) {
            [200, 40, 40]
        } else if u < 0.1 {
            [30, 30, 30]
        } else {
            [250, 220, 80]
        }
    });
    let curtain = paint(&mut images, |u, v| {
        if ((u * 12.0) as u32 + (v * 8.0) as u32).is_multiple_of(2) {
            [235, 230, 215]
        } else {
            [215, 225, 235]
        }
    });
    commands.insert_resource(Textures([flag, banner, curtain]));
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut fabric: ResMut<Fabric>,
) {
    let here = DespawnOnExit(Scene::Flag);
    commands.insert_resource(ClearColor(Color::srgb(0.62, 0.78, 0.92)));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 600.0,
        ..default()
    });
    commands.spawn((
        DirectionalLight {
            illuminance: 10_000.0,
            ..default()
        },
        Transform::from_xyz(-4.0, 8.0, 6.0).looking_at(Vec3::new(1.0, 4.0, 0.0), Vec3::Y),
        here.clone(),
    ));
    commands.spawn((
        Mesh3d(meshes.add(common::grass(60.0, Color::srgb(0.36, 0.55, 0.32)))),
        MeshMaterial3d(materials.add(Color::WHITE)),
        here.clone(),
    ));
    let metal = materials.add(Color::srgb(0.75, 0.75, 0.78));
    let on_pole: &'static [Fabric] = &[Fabric::Flag, Fabric::Banner, Fabric::Physical];
    commands.spawn((
        Setting(on_pole),
        Mesh3d(meshes.add(Cylinder::new(0.05, 6.0))),
        MeshMaterial3d(metal.clone()),
        Transform::from_xyz(0.0, 3.0, 0.0),
        here.clone(),
    ));
    // A wall across the wind (+X) with an open window, the room on the downwind side; the
    // curtain rod inside, above the window.
    let wall = materials.add(Color::srgb(0.86, 0.82, 0.74));
    let in_window: &'static [Fabric] = &[Fabric::Curtain];
    let (bottom, top, width) = (WINDOW_BOTTOM, WINDOW_BOTTOM + 1.9, 2.0);
    for (size, centre) in [
        (
            Vec3::new(0.2, bottom, 6.0),
            Vec3::new(0.0, bottom / 2.0, 0.0),
        ),
        (
            Vec3::new(0.2, 4.0 - top, 6.0),
            Vec3::new(0.0, (top + 4.0) / 2.0, 0.0),
        ),
        (
            Vec3::new(0.2, top - bottom, 2.0),
            Vec3::new(0.0, (top + bottom) / 2.0, -(width / 2.0 + 1.0)),
        ),
        (
            Vec3::new(0.2, top - bottom, 2.0),
            Vec3::new(0.0, (top + bottom) / 2.0, width / 2.0 + 1.0),
        ),
    ] {
        commands.spawn((
            Setting(in_window),
            Mesh3d(meshes.add(Cuboid::from_size(size))),
            MeshMaterial3d(wall.clone()),
            Transform::from_translation(centre),
            here.clone(),
        ));
    }
    commands.spawn((
        Setting(in_window),
        Mesh3d(meshes.add(Cuboid::new(0.05, 0.05, width + 0.6))),
        MeshMaterial3d(metal.clone()),
        Transform::from_xyz(0.25, top + 0.08, 0.0),
        here.clone(),
    ));
    // A fan outside the window blowing in: a local WindSource (its cone drawn with G) aimed at
    // the curtain's rod, on top of the gentle breeze.
    let fan = Transform::from_xyz(-2.4, bottom + 0.9, -1.2)
        .looking_at(Vec3::new(0.25, top - 0.1, 0.9), Vec3::Y);
    commands
        .spawn((
            Setting(in_window),
            WindSource::fan(6.0, 0.6, 9.0),
            Name::new("fan"),
            fan,
            Visibility::default(),
            here.clone(),
        ))
        .with_children(|fan| {
            // The housing faces the fan's forward (local −Z).
            fan.spawn((
                Mesh3d(meshes.add(Cylinder::new(0.38, 0.16))),
                MeshMaterial3d(materials.add(Color::srgb(0.2, 0.22, 0.25))),
                Transform::from_rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
            ));
            fan.spawn((
                Mesh3d(meshes.add(Cylinder::new(0.06, 1.0))),
                MeshMaterial3d(metal),
                Transform::from_xyz(0.0, -0.5, 0.0),
            ));
        });
    // The cloth's mesh and shape come from `apply_fabric`.
    commands.spawn((
        Hanging,
        Name::new("flag"),
        MeshMaterial3d(materials.add(StandardMaterial {
            perceptual_roughness: 0.8,
            double_sided: true,
            cull_mode: None,
            ..default()
        })),
        here,
    ));
    fabric.set_changed();
}

fn grid(rows: usize, columns: usize, width: f32, height: f32) -> ClothGrid {
    ClothGrid {
        rows,
        columns,
        width,
        height,
    }
}

/// The cloth for the current [`Fabric`]: its Table 1 preset, grid, edge and place.
pub fn cloth_for(fabric: Fabric, evolving: bool) -> (Cloth, Transform) {
    let params = fabric.preset(evolving).params();
    let pole = Transform::from_xyz(0.05, 5.95, 0.0);
    let (grid, attachment, transform) = match fabric {
        Fabric::Flag | Fabric::Physical => (grid(28, 42, 2.1, 1.4), ClothAttachment::Pole, pole),
        Fabric::Banner => (grid(14, 64, 3.6, 0.6), ClothAttachment::Pole, pole),
        // The rod runs along local +X (world −Z); the curtain billows along local +Z (world +X),
        // into the room, downwind.
        Fabric::Curtain => (
            grid(30, 36, 1.85, 2.1),
            ClothAttachment::Rod,
            Transform::from_xyz(0.25, WINDOW_BOTTOM + 1.95, 1.05)
                .with_rotation(Quat::from_rotation_y(std::f32::consts::FRAC_PI_2)),
        ),
    };
    let cloth = Cloth {
        grid,
        params,
        attachment,
        follow_wind: true,
    };
    (cloth, transform)
}

fn keys(
    keys: Res<ButtonInput<KeyCode>>,
    mut fabric: ResMut<Fabric>,
    mut cloth: Single<&mut Cloth, With<Hanging>>,
) {
    if keys.just_pressed(KeyCode::KeyV) {
        *fabric = fabric.next();
    }
    if keys.just_pressed(KeyCode::KeyF) {
        // The same object and band of Table 1 in the other wind model: the whole row.
        let evolving = !matches!(cloth.params.model, ClothWindModel::Evolving { .. });
        let (fresh, _) = cloth_for(*fabric, evolving);
        cloth.params = fresh.params;
    }
}

/// With [`Fabric::Physical`], a second pole upwind flying a [`PhysicalCloth`] of the procedural
/// flag's size (20 × 30 nodes, 0.15 kg/m²) and fabric; otherwise neither.
fn physical_side(
    commands: &mut Commands,
    fabric: Fabric,
    shown: &Query<Entity, With<PhysicalSide>>,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
    texture: Handle<Image>,
) {
    for entity in shown {
        commands.entity(entity).despawn();
    }
    if fabric != Fabric::Physical {
        return;
    }
    let here = DespawnOnExit(Scene::Flag);
    commands.spawn((
        PhysicalSide,
        Mesh3d(meshes.add(Cylinder::new(0.05, 6.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.75, 0.75, 0.78))),
        Transform::from_translation(PHYSICAL_POLE + Vec3::Y * 3.0),
        here.clone(),
    ));
    commands.spawn((
        PhysicalSide,
        Name::new("physical flag"),
        PhysicalCloth {
            grid: grid(20, 30, 2.1, 1.4),
            ..default()
        },
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color_texture: Some(texture),
            perceptual_roughness: 0.8,
            double_sided: true,
            cull_mode: None,
            ..default()
        })),
        Transform::from_translation(PHYSICAL_POLE + Vec3::new(0.05, 5.95, 0.0)),
        here,
    ));
}

#[allow(clippy::too_many_arguments)]
fn apply_fabric(
    mut commands: Commands,
    fabric: Res<Fabric>,
    textures: Res<Textures>,
    hanging: Single<(Entity, &MeshMaterial3d<StandardMaterial>), With<Hanging>>,
    shown: Query<Entity, With<PhysicalSide>>,
    mut scenery: Query<(&Setting, &mut Visibility)>,
    mut camera: Single<&mut Transform, (With<Camera3d>, Without<Hanging>)>,
    mut wind: ResMut<WindSettings>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let (entity, material) = *hanging;
    let flag = textures.0[Fabric::Flag as usize].clone();
    physical_side(
        &mut commands,
        *fabric,
        &shown,
        &mut meshes,
        &mut materials,
        flag,
    );
    for (setting, mut visibility) in &mut scenery {
        *visibility = if setting.0.contains(&*fabric) {
            Visibility::Inherited
        } else {
            Visibility::Hidden
        };
    }
    // A gentle breeze at the flag (6 m/s at 5.5 m); at the window a light one, and the fan.
    let (speed, eye, target) = match *fabric {
        Fabric::Curtain => (
            4.0,
            Vec3::new(4.6, 2.1, 2.6),
            Vec3::new(0.3, WINDOW_BOTTOM + 0.9, 0.0),
        ),
        // From above and in front, so the waves show in the outline.
        Fabric::Banner => (7.5, Vec3::new(-2.2, 7.6, 6.6), Vec3::new(1.6, 5.2, 0.0)),
        Fabric::Flag => (7.5, Vec3::new(-1.4, 7.8, 4.6), Vec3::new(1.1, 4.9, 0.0)),
        // Both flags, the physical one on the left.
        Fabric::Physical => (7.5, Vec3::new(-2.0, 8.4, 7.4), Vec3::new(-0.9, 4.9, 0.0)),
    };
    wind.reference_speed = speed;
    place_camera(&mut camera, eye, target);
    let (cloth, transform) = cloth_for(*fabric, false);
    if let Some(mut m) = materials.get_mut(&material.0) {
        let texture = match *fabric {
            Fabric::Physical => Fabric::Flag,
            other => other,
        };
        m.base_color_texture = Some(textures.0[texture as usize].clone());
    }
    commands.entity(entity).insert((cloth, transform));
}

fn show_info(
    wind: Res<WindField>,
    fabric: Res<Fabric>,
    hanging: Query<(&Cloth, &ClothState, &GlobalTransform), With<Hanging>>,
    mut info: ResMut<SceneInfo>,
) {
    let Ok((cloth, state, at)) = hanging.single() else {
        return;
    };
    let p = &cloth.params;
    let evolving = matches!(p.model, ClothWindModel::Evolving { .. });
    let preset = fabric.preset(evolving);
    let physical = if *fabric == Fabric::Physical {
        "left: PhysicalCloth (particles, lift and drag)   right: procedural Cloth\n"
    } else {
        ""
    };
    info.0 = format!(
        "{physical}{}: Table 1 row \"{}\", {} wind (theta {:.1}, beta {:.2}, swirl |u| {}, band {})\n\
         wind here {:.1} m/s -> |v| = {:.1} cells/frame      V flag/banner/curtain/physical   \
         F frozen/evolving",
        preset.kind().name(),
        preset.observation(),
        if evolving { "evolving" } else { "frozen" },
        p.amplitude,
        p.beta,
        p.swirl,
        match p.filter {
            HarmonicFilter::All => "all".to_string(),
            HarmonicFilter::LowPass { max } => format!("[1, {max}]"),
            HarmonicFilter::BandPass { min, max } => format!("[{min}, {max}]"),
        },
        wind.velocity(at.translation()).length(),
        state.wind_steps_per_frame,
    );
}
