//! Drawing a [`LeafCloud`]: one mesh, one draw call, the leaves' poses in a storage buffer (on
//! WebGL2 a texture).
//!
//! The mesh holds `count` copies of the leaf's outline at the origin, each vertex tagged with
//! its leaf's index (the second UV set) and coloured from the cloud's [`LeafCloudLook`]; the
//! vertex shader (`cloud.wesl`) moves each copy to its leaf's pose, which the plugin writes into
//! a [`ShaderBuffer`] once per frame (32 bytes a leaf, in place), or where the device has no
//! storage buffers ([`GpuLayout::Texture`]) into an RGBA32F [`Image`], two texels a leaf. There is one entity, one mesh
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
use bevy::ecs::system::SystemParamItem;
use bevy::ecs::system::lifetimeless::SRes;
use bevy::image::Image;
use bevy::math::Vec3;
use bevy::mesh::{Indices, Mesh, Mesh3d, PrimitiveTopology};
use bevy::pbr::{ExtendedMaterial, MaterialExtension, MeshMaterial3d, StandardMaterial};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    AsBindGroup, AsBindGroupError, BindGroupBuilder, BindGroupLayout, BindGroupLayoutEntry, Face,
    ShaderStages,
};
use bevy::render::renderer::RenderDevice;
use bevy::render::storage::{GpuShaderBuffer, ShaderBuffer};
use bevy::render::texture::GpuImage;
use bevy::shader::ShaderRef;

use super::GpuLayout;
use super::layout::{bound_buffer, bound_texture, push_bindings, record_texture, texture_width};

use crate::freefall::cloud::LeafPose;
use crate::freefall::{
    CLOUD_POINTS, FallPreset, FallingObject, LeafCloud, LeafCloudState, Shape, mix, outline,
};

/// A [`StandardMaterial`] whose mesh is a whole leaf cloud (see [`LeafCloudRenderPlugin`]).
pub type LeafCloudMaterial = ExtendedMaterial<StandardMaterial, CloudPoses>;

/// Bytes of one leaf's pose: position and scale, then the rotation, as 8 × f32.
pub(crate) const POSE_BYTES: usize = 32;

/// The material extension: the leaves' poses, bound at 103.
#[derive(Asset, Clone, Debug, Reflect)]
pub struct CloudPoses {
    /// `count` × (position.xyz, scale, rotation.xyzw), f32 ([`GpuLayout::Storage`]).
    #[reflect(ignore)]
    pub poses: Handle<ShaderBuffer>,
    /// The same, two RGBA32F texels a leaf, rows of an even width ([`GpuLayout::Texture`]).
    #[reflect(ignore)]
    pub pose_texture: Handle<Image>,
    /// Which of the two the shader reads.
    pub layout: GpuLayout,
}

impl AsBindGroup for CloudPoses {
    type Data = ();
    type Param = (
        SRes<RenderAssets<GpuImage>>,
        SRes<RenderAssets<GpuShaderBuffer>>,
    );

    fn label() -> &'static str {
        "CloudPoses"
    }

    fn bind_group_data(&self) -> Self::Data {}

    fn build_bind_group(
        &self,
        _layout: &BindGroupLayout,
        _device: &RenderDevice,
        (images, buffers): &mut SystemParamItem<'_, '_, Self::Param>,
        _force_no_bindless: bool,
        output: &mut BindGroupBuilder,
    ) -> Result<(), AsBindGroupError> {
        let poses = match self.layout {
            GpuLayout::Storage => bound_buffer(buffers, &self.poses)?,
            GpuLayout::Texture => bound_texture(images, &self.pose_texture)?,
        };
        push_bindings(output, [(103, poses)]);
        Ok(())
    }

    fn bind_group_layout_entries(
        device: &RenderDevice,
        _force_no_bindless: bool,
    ) -> Vec<BindGroupLayoutEntry> {
        vec![GpuLayout::of(device).array_entry(103, ShaderStages::VERTEX)]
    }
}

impl MaterialExtension for CloudPoses {
    fn vertex_shader() -> ShaderRef {
        "embedded://bevy_windfall/cloud.wesl".into()
    }

    fn enable_shadows() -> bool {
        false
    }

    fn enable_prepass() -> bool {
        false
    }
}

/// How a [`LeafCloud`]'s leaves look: each leaf takes a colour of the palette (chosen by a hash
/// of its index) darkened or lightened by up to `variation`. Optional: without it, the colours
/// of the cloud's object ([`LeafCloudLook::of`]).
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

/// What the plugin made for a cloud: its pose buffer or texture and what its mesh was built for.
#[derive(Component, Clone, Debug)]
pub(crate) struct LeafCloudVisual {
    /// The poses ([`CloudPoses::poses`], [`CloudPoses::pose_texture`]).
    poses: CloudPoses,
    /// Leaves drawn.
    count: usize,
    /// The object's shape and look.
    object: (Shape, Option<FallPreset>),
    look: LeafCloudLook,
}

/// Draws every [`LeafCloud`]: gives it a mesh and a [`LeafCloudMaterial`] and writes its poses
/// each frame, after [`WindfallSystems::WriteBack`](crate::schedule::WindfallSystems::WriteBack) posed
/// them. [`WindfallPlugins`](struct@crate::WindfallPlugins) adds it in an app with the renderer (through
/// [`WindfallRenderPlugin`](super::WindfallRenderPlugin)).
///
/// The mesh holds `count` copies of the leaf's outline at the origin, each vertex tagged with its
/// leaf's index (the second UV set) and coloured from the cloud's [`LeafCloudLook`]; the vertex
/// shader moves each copy to its leaf's pose, read from a [`ShaderBuffer`] of 32 bytes a leaf
/// (position and rotation; on WebGL2 a texture of two texels a leaf) written in place. One entity, one mesh, one material and one draw call
/// per cloud. The mesh is rebuilt when the count, the shape or the look changes. Leaves cast no
/// shadows, and the cloud is never frustum-culled as a whole.
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
///         commands.spawn((Camera3d::default(), LodFocus, Transform::from_xyz(0.0, 3.0, 20.0)));
///         commands.spawn(LeafCloud { count: 50_000, ..default() });
///     })
///     .run();
/// ```
#[derive(Default)]
pub struct LeafCloudRenderPlugin;

impl Plugin for LeafCloudRenderPlugin {
    /// Not unique: [`WindfallRenderPlugin`](super::WindfallRenderPlugin) adds it, and so may you.
    fn is_unique(&self) -> bool {
        false
    }

    fn build(&self, app: &mut App) {
        // Added twice (by you and by `WindfallPlugins`): once is enough.
        if app.is_plugin_added::<bevy::pbr::MaterialPlugin<LeafCloudMaterial>>() {
            return;
        }
        super::embed_shaders(app);
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
    mut images: ResMut<Assets<Image>>,
    device: Option<Res<RenderDevice>>,
) {
    let layout = device
        .as_ref()
        .map_or(GpuLayout::Storage, |d| GpuLayout::of(d));
    let max_width = device.map_or(2048, |d| d.limits().max_texture_dimension_2d);
    for (entity, cloud, state, look, visual) in &clouds {
        // An invalid cloud (its error is in `LeafCloudInvalid`) has nothing to draw.
        let Some(leaves) = state.leaves() else {
            continue;
        };
        let look = look
            .cloned()
            .unwrap_or_else(|| LeafCloudLook::of(&cloud.object));
        let count = drawn(leaves.len());
        let object = (cloud.object.shape, cloud.object.look);
        if visual.is_some_and(|v| v.count == count && v.object == object && v.look == look) {
            continue;
        }
        if count < leaves.len() {
            bevy::log::warn!(
                "LeafCloud {entity}: drawing {count} of its {} leaves (LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)",
                leaves.len()
            );
        }
        let bytes = vec![0; count.max(1) * POSE_BYTES];
        let poses = match layout {
            GpuLayout::Storage => CloudPoses {
                poses: buffers.add(ShaderBuffer::new(bytes, RenderAssetUsages::RENDER_WORLD)),
                pose_texture: Handle::default(),
                layout,
            },
            GpuLayout::Texture => CloudPoses {
                poses: Handle::default(),
                pose_texture: images.add(record_texture(
                    bytes,
                    texture_width(count.max(1) * POSE_BYTES / 16, max_width),
                )),
                layout,
            },
        };
        let material = materials.add(LeafCloudMaterial {
            base: StandardMaterial {
                base_color: Color::WHITE,
                perceptual_roughness: look.roughness,
                // Lit from behind too: a leaf seen from below glows (see the default look).
                diffuse_transmission: 0.45,
                double_sided: true,
                cull_mode: None::<Face>,
                ..Default::default()
            },
            extension: poses.clone(),
        });
        let mesh = meshes.add(cloud_mesh(&cloud.object, count as u32, &look));
        commands.entity(entity).try_insert((
            Mesh3d(mesh),
            MeshMaterial3d(material),
            NoFrustumCulling,
            LeafCloudVisual {
                poses,
                count,
                object,
                look,
            },
        ));
    }
}

/// Copies each cloud's poses into its buffer or texture (written in place: the bind group
/// stays valid).
fn write_poses(
    clouds: Query<(&LeafCloudState, &LeafCloudVisual)>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut images: ResMut<Assets<Image>>,
) {
    for (state, visual) in &clouds {
        let poses = state.poses();
        if poses.len() < visual.count || visual.count == 0 {
            continue;
        }
        let poses = &poses[..visual.count];
        match visual.poses.layout {
            GpuLayout::Storage => {
                let Some(mut buffer) = buffers.get_mut(&visual.poses.poses) else {
                    continue;
                };
                // The render world took the last frame's data: the poses go in anew, as many
                // bytes as the buffer (the GPU buffer is written in place).
                let words: Vec<f32> = poses.iter().flat_map(pose_words).collect();
                buffer.data = ShaderBuffer::new(words, RenderAssetUsages::RENDER_WORLD).data;
            }
            GpuLayout::Texture => {
                let Some(image) = images.get_mut(&visual.poses.pose_texture) else {
                    continue;
                };
                let image = image.into_inner();
                let size = (image.width() * image.height()) as usize * 16;
                let data = image.data.get_or_insert_with(Vec::new);
                data.clear();
                data.reserve(size);
                for pose in poses {
                    for v in pose_words(pose) {
                        data.extend_from_slice(&v.to_le_bytes());
                    }
                }
                // A texture's last row is padded.
                data.resize(size, 0);
            }
        }
    }
}

/// One pose as 8 f32: position, scale 1, rotation.
fn pose_words(pose: &LeafPose) -> [f32; 8] {
    let [x, y, z] = pose.position.to_array();
    let [qx, qy, qz, qw] = pose.rotation.to_array();
    [x, y, z, 1.0, qx, qy, qz, qw]
}

/// How many of `leaves` are drawn.
fn drawn(leaves: usize) -> usize {
    leaves.min(LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)
}

/// `count` leaves (at least 1, at most [`LeafCloudRenderPlugin::MAX_DRAWN_LEAVES`](crate::render::LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)) of
/// `object`'s outline (its look's, as [`FallingObject::mesh`] draws it, with fewer points) at the
/// origin, each a flat fan from its centre facing +Y, tagged with its index in UV set 1 and
/// coloured from `look`.
pub(crate) fn cloud_mesh(object: &FallingObject, count: u32, look: &LeafCloudLook) -> Mesh {
    let (centre, corners) = outline(object.outline(), &object.shape, CLOUD_POINTS);
    let centre = Vec3::new(centre.x, 0.0, centre.y);
    let corners: Vec<Vec3> = corners.iter().map(|p| Vec3::new(p.x, 0.0, p.y)).collect();
    let n = corners.len() as u32;
    let per_leaf = (n + 1) as usize;
    let count = drawn(count as usize).max(1) as u32;
    let palette: Vec<LinearRgba> = if look.palette.is_empty() {
        vec![LinearRgba::WHITE]
    } else {
        look.palette.iter().map(|c| c.to_linear()).collect()
    };
    let total = count as usize * per_leaf;
    let mut positions = Vec::with_capacity(total);
    let mut uvs = Vec::with_capacity(total);
    let mut tags = Vec::with_capacity(total);
    let mut colors = Vec::with_capacity(total);
    let mut indices = Vec::with_capacity(count as usize * n as usize * 3);
    let variation = look.variation.clamp(0.0, 1.0);
    for leaf in 0..count {
        let h = mix(u64::from(leaf));
        let base = palette[(h % palette.len() as u64) as usize];
        let shade = 1.0 + variation * (((h >> 32) & 0xFFFF) as f32 / 32767.5 - 1.0);
        let color = [base.red * shade, base.green * shade, base.blue * shade, 1.0];
        let first = leaf * (n + 1);
        for c in std::iter::once(&centre).chain(&corners) {
            positions.push(c.to_array());
            uvs.push([0.5 + c.x, 0.5 + c.z]);
            tags.push([leaf as f32, 0.0]);
            colors.push(color);
        }
        for k in 0..n {
            indices.extend_from_slice(&[first, first + 1 + k, first + 1 + (k + 1) % n]);
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

/// Limits and constants of [`LeafCloudRenderPlugin`].
impl LeafCloudRenderPlugin {
    /// Most leaves of one cloud that are drawn: the vertex buffer (up to 15 vertices of 56 bytes
    /// a leaf) stays under 256 MiB, wgpu's default largest buffer. Leaves beyond are simulated,
    /// not drawn.
    pub const MAX_DRAWN_LEAVES: usize = 300_000;
}

impl LeafCloudLook {
    /// `count` leaves (at least 1, at most [`LeafCloudRenderPlugin::MAX_DRAWN_LEAVES`](crate::render::LeafCloudRenderPlugin::MAX_DRAWN_LEAVES)) of
    /// `object`'s outline at the origin, each a fan facing +Y, tagged with its index in UV set 1
    /// and coloured from this look: the mesh a cloud of `object` is drawn with.
    pub fn mesh(&self, object: &FallingObject, count: u32) -> Mesh {
        cloud_mesh(object, count, self)
    }

    /// The look of a cloud of `object` without a [`LeafCloudLook`]: its palette
    /// ([`FallingObject::palette`]), each leaf lightened or darkened by up to 25 %.
    pub fn of(object: &FallingObject) -> Self {
        Self {
            palette: object.palette().to_vec(),
            ..Self::default()
        }
    }
}
