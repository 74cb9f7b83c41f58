//! The default look: what a game sees with nothing but the crate's components. A
//! [`FallingObject`] without a [`Mesh3d`] gets its preset's outline and one of its colours, lit
//! on both sides; a [`Cloth`] or a [`PhysicalCloth`] without a [`StandardMaterial`] gets a
//! fabric. Meshes and materials are shared: a thousand maple leaves use one mesh and four
//! materials.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::{Assets, Handle};
use bevy::camera::visibility::VisibilitySystems;
use bevy::color::Color;
use bevy::ecs::prelude::*;
use bevy::mesh::{Mesh, Mesh3d};
use bevy::pbr::{MeshMaterial3d, StandardMaterial};
use bevy::platform::collections::HashMap;
use bevy::render::RenderApp;

use super::WindGpuPlugin;
use super::cloud::LeafCloudRenderPlugin;
use crate::aero::PhysicalCloth;
use crate::cloth::Cloth;
use crate::freefall::{FallPreset, FallingObject, Shape};

/// Draws what the crate animates (feature `render`, in [`WindfallPlugins`](struct@crate::WindfallPlugins)):
/// default looks for [`FallingObject`]s and cloths, [`LeafCloudRenderPlugin`] for leaf clouds and
/// [`WindGpuPlugin`] for the wind on the GPU. In an app without Bevy's renderer (a server, a
/// headless test) it does nothing, so add the group after `DefaultPlugins`.
///
/// - A [`FallingObject`] spawned without a [`Mesh3d`] gets [`FallingObject::mesh`] (its
///   preset's outline) and a two-sided [`StandardMaterial`] of [`FallingObject::color`]; a new
///   look, shape or seed redraws it. Spawn it with your own `Mesh3d` and material to draw it
///   your way.
/// - A [`Cloth`] (a red flag fabric) or a [`PhysicalCloth`] (blue) spawned without a
///   `MeshMaterial3d<StandardMaterial>` gets a two-sided fabric. With a material of another type,
///   remove that default.
///
/// # Example
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// App::new()
///     .add_plugins((DefaultPlugins, WindfallPlugins::default()))
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 2.0, 4.0)));
///         commands.spawn(DirectionalLight::default());
///         // A maple leaf, drawn as one, and a flag.
///         commands.spawn((FallPreset::MapleLeaf.object(), Transform::from_xyz(0.0, 3.0, 0.0)));
///         commands.spawn((Cloth::default(), Transform::from_xyz(-1.0, 1.5, 0.0)));
///     })
///     .run();
/// ```
#[derive(Default)]
pub struct WindfallRenderPlugin;

impl Plugin for WindfallRenderPlugin {
    fn build(&self, app: &mut App) {
        if app.get_sub_app(RenderApp).is_none() {
            bevy::log::debug!("WindfallRenderPlugin: no renderer in this app, nothing is drawn");
            return;
        }
        if !app.is_plugin_added::<LeafCloudRenderPlugin>() {
            app.add_plugins(LeafCloudRenderPlugin);
        }
        if !app.is_plugin_added::<WindGpuPlugin>() {
            app.add_plugins(WindGpuPlugin);
        }
        app.init_resource::<Looks>().add_systems(
            PostUpdate,
            (dress_objects, dress_cloths).before(VisibilitySystems::CalculateBounds),
        );
    }
}

/// Marks an object drawn with the default look, and what it was drawn for.
#[derive(Component, Clone, Debug, PartialEq)]
struct DefaultLook {
    look: Option<FallPreset>,
    shape: Shape,
    color: usize,
}

/// The shared meshes and materials.
#[derive(Resource, Default)]
struct Looks {
    meshes: HashMap<(Option<FallPreset>, [u32; 4]), Handle<Mesh>>,
    materials: HashMap<(Option<FallPreset>, usize), Handle<StandardMaterial>>,
    fabrics: HashMap<[u32; 4], Handle<StandardMaterial>>,
}

/// A shape as bits, for the mesh cache.
fn shape_key(shape: &Shape) -> [u32; 4] {
    match *shape {
        Shape::Disk {
            diameter,
            thickness,
        } => [
            0,
            diameter.to_bits(),
            diameter.to_bits(),
            thickness.to_bits(),
        ],
        Shape::Rectangle {
            length,
            width,
            thickness,
        } => [1, length.to_bits(), width.to_bits(), thickness.to_bits()],
        Shape::Ellipse {
            major,
            minor,
            thickness,
        } => [2, major.to_bits(), minor.to_bits(), thickness.to_bits()],
    }
}

/// A matte (or, for a coin, metallic) material seen from both sides. Leaves, paper and cloth
/// let some light through (diffuse transmission), so that the side away from the sun glows
/// rather than going black, as a leaf seen from below does.
pub(crate) fn two_sided(color: Color, metal: bool) -> StandardMaterial {
    StandardMaterial {
        base_color: color,
        double_sided: true,
        cull_mode: None,
        perceptual_roughness: if metal { 0.35 } else { 0.8 },
        metallic: if metal { 0.8 } else { 0.0 },
        diffuse_transmission: if metal { 0.0 } else { 0.45 },
        ..Default::default()
    }
}

/// Gives new objects without a mesh (and redrawn ones) their default look.
#[allow(clippy::type_complexity)]
fn dress_objects(
    mut commands: Commands,
    objects: Query<
        (Entity, &FallingObject, Has<Mesh3d>, Option<&DefaultLook>),
        Changed<FallingObject>,
    >,
    mut looks: ResMut<Looks>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    for (entity, object, has_mesh, dressed) in &objects {
        // The user's own mesh (not one we gave): theirs to draw.
        if has_mesh && dressed.is_none() {
            continue;
        }
        let color = object.color_index();
        let wanted = DefaultLook {
            look: object.look,
            shape: object.shape,
            color,
        };
        if dressed == Some(&wanted) {
            continue;
        }
        let mesh = looks
            .meshes
            .entry((object.look, shape_key(&object.shape)))
            .or_insert_with(|| meshes.add(object.mesh()))
            .clone();
        let metal = matches!(object.shape, Shape::Disk { .. });
        let material = looks
            .materials
            .entry((object.look, color))
            .or_insert_with(|| materials.add(two_sided(object.color(), metal)))
            .clone();
        commands
            .entity(entity)
            .try_insert((Mesh3d(mesh), MeshMaterial3d(material), wanted));
    }
}

/// Gives new cloths without a standard material a fabric.
#[allow(clippy::type_complexity)]
fn dress_cloths(
    mut commands: Commands,
    cloths: Query<
        (Entity, Has<PhysicalCloth>),
        (
            Or<(Added<Cloth>, Added<PhysicalCloth>)>,
            Without<MeshMaterial3d<StandardMaterial>>,
        ),
    >,
    mut looks: ResMut<Looks>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    for (entity, physical) in &cloths {
        // A red flag for the procedural cloth, blue for the physical one (side by side they
        // are told apart).
        let color = if physical {
            Color::srgb(0.16, 0.30, 0.72)
        } else {
            Color::srgb(0.80, 0.12, 0.10)
        };
        let c = color.to_srgba();
        let key = [c.red, c.green, c.blue, c.alpha].map(f32::to_bits);
        let fabric = looks
            .fabrics
            .entry(key)
            .or_insert_with(|| materials.add(two_sided(color, false)))
            .clone();
        commands.entity(entity).try_insert(MeshMaterial3d(fabric));
    }
}
