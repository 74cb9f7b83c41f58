//! Drawing a [`LeafCloud`]: one mesh, one draw call, the leaves' poses in a storage buffer.
//!
//! The mesh holds `count` copies of the leaf's outline at the origin, each vertex tagged with
//! its leaf's index (the second UV set) and coloured from the cloud's [`LeafCloudLook`]; the
//! vertex shader (`cloud.wgsl`) moves each copy to its leaf's pose, which the plugin writes into
//! a [`ShaderBuffer`] once per frame (32 bytes a leaf, in place). There is one entity, one mesh
//! and one material per cloud, and nothing per leaf on the CPU but the pose.
//!
//! The mesh is built once (again when the count, the shape or the look changes). Leaves cast no
//! shadows, and the cloud is never frustum-culled as a whole (its leaves are wherever the wind
//! takes them).

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::{Asset, Assets, Handle, RenderAssetUsages};
use bevy::camera::visibility::NoFrustumCulling;
use bevy::color::{Color, LinearRgba};
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::mesh::{Indices, Mesh, Mesh3d, PrimitiveTopology};
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MeshMaterial3d, StandardMaterial};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::render::render_resource::AsBindGroup;
use bevy::render::render_resource::Face;
use bevy::render::storage::ShaderBuffer;
use bevy::shader::ShaderRef;

use crate::freefall::cloud::LeafPose;
use crate::freefall::{LeafCloud, LeafCloudState, Shape};

/// A [`StandardMaterial`] whose mesh is a whole leaf cloud (see [`LeafCloudRenderPlugin`]).
pub type LeafCloudMaterial = ExtendedMaterial<StandardMaterial, CloudPoses>;

/// Bytes of one leaf's pose: position and scale, then the rotation, as 8 × f32.
pub(crate) const POSE_BYTES: usize = 32;

/// The material extension: the buffer of poses.
#[derive(Asset, AsBindGroup, Clone, Debug, Reflect)]
pub struct CloudPoses {
    /// `count` × (position.xyz, scale, rotation.xyzw), f32.
    #[storage(103, read_only, visibility(vertex))]
    #[reflect(ignore)]
    pub poses: Handle<ShaderBuffer>,
}

impl MaterialExtension for CloudPoses {
    fn vertex_shader() -> ShaderRef {
        "embedded://bevy_windfall/gpu/cloud.wgsl".into()
    }

    fn enable_shadows() -> bool {
        false
    }

    fn enable_prepass() -> bool {
        false
    }
}

/// How a [`LeafCloud`]'s leaves look: each leaf takes a colour of the palette (chosen by a hash
/// of its index) darkened or lightened by up to `variation`. Optional: without it, autumn.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct LeafCloudLook {
    /// The colours.
    pub palette: Vec<Color>,
    /// Largest relative change of brightness per leaf, in [0, 1].
    pub variation: f32,
    /// The material's perceptual roughness.
    pub roughness: f32,
}

impl Default for LeafCloudLook {
    /// Autumn: reds, oranges, yellows and browns.
    fn default() -> Self {
        Self {
            palette: vec![
                Color::srgb(0.80, 0.30, 0.08),
                Color::srgb(0.90, 0.55, 0.10),
                Color::srgb(0.85, 0.72, 0.20),
                Color::srgb(0.55, 0.28, 0.10),
                Color::srgb(0.70, 0.15, 0.08),
            ],
            variation: 0.25,
            roughness: 0.8,
        }
    }
}

/// What the plugin made for a cloud: its pose buffer and what its mesh was built for.
#[derive(Component, Clone, Debug)]
pub(crate) struct LeafCloudVisual {
    /// The poses ([`CloudPoses::poses`]).
    pub poses: Handle<ShaderBuffer>,
    /// Leaves drawn.
    count: usize,
    shape: Shape,
    look: LeafCloudLook,
}

/// Draws every [`LeafCloud`]: gives it a mesh and a [`LeafCloudMaterial`] and writes its poses
/// each frame, after [`WindfallSystems::WriteBack`](crate::schedule::WindfallSystems::WriteBack) posed
/// them. Add it after `DefaultPlugins`.
///
/// The mesh holds `count` copies of the leaf's outline at the origin, each vertex tagged with its
/// leaf's index (the second UV set) and coloured from the cloud's [`LeafCloudLook`]; the vertex
/// shader moves each copy to its leaf's pose, read from a [`ShaderBuffer`] of
/// 32 bytes a leaf (position and rotation) written in place. One entity, one mesh, one material and one draw call
/// per cloud. The mesh is rebuilt when the count, the shape or the look changes. Leaves cast no
/// shadows, and the cloud is never frustum-culled as a whole.
///
/// # Example
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::{LeafCloud, LodFocus};
/// use bevy_windfall::gpu::LeafCloudRenderPlugin;
/// use bevy_windfall::prelude::*;
///
/// App::new()
///     .add_plugins((DefaultPlugins, WindfallPlugins, LeafCloudRenderPlugin))
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn((Camera3d::default(), LodFocus, Transform::from_xyz(0.0, 3.0, 20.0)));
///         commands.spawn(LeafCloud { count: 50_000, ..default() });
///     })
///     .run();
/// ```
#[derive(Default)]
pub struct LeafCloudRenderPlugin;

impl Plugin for LeafCloudRenderPlugin {
    fn build(&self, app: &mut App) {
        bevy::shader::load_shader_library!(app, "math.wgsl");
        bevy::asset::embedded_asset!(app, "cloud.wgsl");
        app.register_type::<LeafCloudLook>()
            .add_plugins(bevy::pbr::MaterialPlugin::<LeafCloudMaterial>::default())
            .add_systems(
                PostUpdate,
                (attach_visuals, write_poses)
                    .chain()
                    .after(crate::schedule::WindfallSystems::WriteBack),
            );
    }
}

#[allow(clippy::type_complexity)]
fn attach_visuals(
    mut commands: Commands,
    clouds: Query<(
        Entity,
        &LeafCloud,
        &LeafCloudState,
        Option<&LeafCloudLook>,
        Option<&LeafCloudVisual>,
    )>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<LeafCloudMaterial>>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
) {
    for (entity, cloud, state, look, visual) in &clouds {
        // An invalid cloud (its error is in `LeafCloudInvalid`) has nothing to draw.
        let Some(leaves) = state.leaves() else {
            continue;
        };
        let look = look.cloned().unwrap_or_default();
        let count = drawn(leaves.len());
        if visual.is_some_and(|v| {
            v.count == count
                && v.shape == cloud.object.shape
                && format!("{:?}", v.look) == format!("{look:?}")
        }) {
            continue;
        }
        if count < leaves.len() {
            bevy::log::warn!(
                "LeafCloud {entity}: drawing {count} of its {} leaves (MAX_DRAWN_LEAVES)",
                leaves.len()
            );
        }
        let poses = buffers.add(ShaderBuffer::new(
            &vec![0; count.max(1) * POSE_BYTES],
            RenderAssetUsages::RENDER_WORLD,
        ));
        let material = materials.add(LeafCloudMaterial {
            base: StandardMaterial {
                base_color: Color::WHITE,
                perceptual_roughness: look.roughness,
                double_sided: true,
                cull_mode: None::<Face>,
                ..Default::default()
            },
            extension: CloudPoses {
                poses: poses.clone(),
            },
        });
        let mesh = meshes.add(cloud_mesh(&cloud.object.shape, count as u32, &look));
        commands.entity(entity).insert((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            NoFrustumCulling,
            LeafCloudVisual {
                poses,
                count,
                shape: cloud.object.shape,
                look,
            },
        ));
    }
}

/// Copies each cloud's poses into its buffer (written in place: the bind group stays valid).
fn write_poses(
    clouds: Query<(&LeafCloudState, &LeafCloudVisual)>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
) {
    for (state, visual) in &clouds {
        let poses = state.poses();
        if poses.len() < visual.count || visual.count == 0 {
            continue;
        }
        let poses = &poses[..visual.count];
        let Some(mut buffer) = buffers.get_mut(&visual.poses) else {
            continue;
        };
        let data = buffer.data.get_or_insert_with(Vec::new);
        data.clear();
        data.reserve(poses.len() * POSE_BYTES);
        for pose in poses {
            pack_pose(pose, data);
        }
    }
}

/// Appends one pose as 8 little-endian f32: position, scale 1, rotation.
fn pack_pose(pose: &LeafPose, data: &mut Vec<u8>) {
    let [x, y, z] = pose.position.to_array();
    let [qx, qy, qz, qw] = pose.rotation.to_array();
    for v in [x, y, z, 1.0, qx, qy, qz, qw] {
        data.extend_from_slice(&v.to_le_bytes());
    }
}

/// The outline of one leaf in its own frame (the plate in XZ, long axis Z), convex: an ellipse
/// as a leaf (a hexagon pointed at the tip, rounder at the stalk), a disk as an octagon, a
/// rectangle as itself.
fn outline(shape: &Shape) -> Vec<Vec3> {
    match *shape {
        Shape::Ellipse { major, minor, .. } => {
            let (x, z) = (0.5 * minor, 0.5 * major);
            // Counter-clockwise seen from +Y (+Z toward −X), as the fan's faces need.
            [
                (0.0, 1.0),
                (-0.9, 0.25),
                (-0.75, -0.55),
                (0.0, -0.9),
                (0.75, -0.55),
                (0.9, 0.25),
            ]
            .map(|(a, b)| Vec3::new(a * x, 0.0, b * z))
            .to_vec()
        }
        Shape::Disk { diameter, .. } => (0..8)
            .map(|k| {
                let a = std::f32::consts::TAU * k as f32 / 8.0;
                0.5 * diameter * Vec3::new(-a.sin(), 0.0, a.cos())
            })
            .collect(),
        Shape::Rectangle { length, width, .. } => {
            let (x, z) = (0.5 * width, 0.5 * length);
            vec![
                Vec3::new(-x, 0.0, -z),
                Vec3::new(x, 0.0, -z),
                Vec3::new(x, 0.0, z),
                Vec3::new(-x, 0.0, z),
            ]
        }
    }
}

/// Most leaves of one cloud that are drawn: the vertex buffer (6–8 vertices of 56 bytes a leaf)
/// stays under 256 MiB, wgpu's default largest buffer. Leaves beyond are simulated, not drawn.
pub(crate) const MAX_DRAWN_LEAVES: usize = 500_000;

/// How many of `leaves` are drawn.
fn drawn(leaves: usize) -> usize {
    leaves.min(MAX_DRAWN_LEAVES)
}

/// `count` leaves (at least 1, at most [`LeafCloudRenderPlugin::MAX_DRAWN_LEAVES`](crate::gpu::LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)) of `shape`'s outline at the origin,
/// each a triangle fan facing +Y, tagged with its index in UV set 1 and coloured from `look`.
pub(crate) fn cloud_mesh(shape: &Shape, count: u32, look: &LeafCloudLook) -> Mesh {
    let corners = outline(shape);
    let n = corners.len() as u32;
    let count = drawn(count as usize).max(1) as u32;
    let palette: Vec<LinearRgba> = if look.palette.is_empty() {
        vec![LinearRgba::WHITE]
    } else {
        look.palette.iter().map(|c| c.to_linear()).collect()
    };
    let mut positions = Vec::with_capacity((count * n) as usize);
    let mut uvs = Vec::with_capacity((count * n) as usize);
    let mut tags = Vec::with_capacity((count * n) as usize);
    let mut colors = Vec::with_capacity((count * n) as usize);
    let mut indices = Vec::with_capacity((count * (n - 2) * 3) as usize);
    let variation = look.variation.clamp(0.0, 1.0);
    for leaf in 0..count {
        let h = hash(leaf);
        let base = palette[(h % palette.len() as u64) as usize];
        let shade = 1.0 + variation * (((h >> 32) & 0xFFFF) as f32 / 32767.5 - 1.0);
        let color = [base.red * shade, base.green * shade, base.blue * shade, 1.0];
        let first = leaf * n;
        for c in &corners {
            positions.push(c.to_array());
            uvs.push([0.5 + c.x, 0.5 + c.z]);
            tags.push([leaf as f32, 0.0]);
            colors.push(color);
        }
        for k in 1..n - 1 {
            indices.extend_from_slice(&[first, first + k + 1, first + k]);
        }
    }
    let normals = vec![[0.0, 1.0, 0.0]; positions.len()];
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_1, tags)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colors)
    .with_inserted_indices(Indices::U32(indices))
}

/// SplitMix64 of a leaf index: its colour and shade.
fn hash(leaf: u32) -> u64 {
    let mut z = u64::from(leaf).wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Limits and constants of [`LeafCloudRenderPlugin`].
impl LeafCloudRenderPlugin {
    /// Most leaves of one cloud that are drawn: the vertex buffer (6–8 vertices of 56 bytes a leaf)
    /// stays under 256 MiB, wgpu's default largest buffer. Leaves beyond are simulated, not drawn.
    pub const MAX_DRAWN_LEAVES: usize = MAX_DRAWN_LEAVES;
}

impl LeafCloudLook {
    /// `count` leaves (at least 1, at most [`LeafCloudRenderPlugin::MAX_DRAWN_LEAVES`](crate::gpu::LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)) of
    /// `shape`'s outline at the origin, each a triangle fan facing +Y, tagged with its index in
    /// UV set 1 and coloured from this look: the mesh a cloud is drawn with.
    pub fn mesh(&self, shape: &Shape, count: u32) -> Mesh {
        cloud_mesh(shape, count, self)
    }
}
