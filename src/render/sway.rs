//! [`WindSway`]: a material extension that bends any mesh (grass, foliage, a tree's crown,
//! reeds, hanging cloth strips) in the GPU wind, vertex by vertex.
//!
//! The model is described on [`WindSway`].

use bevy::asset::Asset;
use bevy::ecs::system::SystemParamItem;
use bevy::ecs::system::lifetimeless::SRes;
use bevy::math::Vec4;
use bevy::pbr::{ExtendedMaterial, MaterialExtension, StandardMaterial};
use bevy::reflect::Reflect;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::binding_types::uniform_buffer;
use bevy::render::render_resource::encase::UniformBuffer;
use bevy::render::render_resource::{
    AsBindGroup, AsBindGroupError, BindGroupBuilder, BindGroupLayout, BindGroupLayoutEntry,
    BufferInitDescriptor, BufferUsages, OwnedBindingResource, ShaderStages, ShaderType,
};
use bevy::render::renderer::RenderDevice;
use bevy::render::storage::GpuShaderBuffer;
use bevy::render::texture::GpuImage;
use bevy::shader::ShaderRef;

use super::WindGpuBuffers;
use super::layout::push_bindings;

/// A [`StandardMaterial`] that sways in the wind: use it like any material,
/// `MeshMaterial3d(materials.add(WindSwayMaterial { base, extension }))`.
pub type WindSwayMaterial = ExtendedMaterial<StandardMaterial, WindSway>;

/// How a mesh bends in the wind (see [`WindSway`]); all lengths in the mesh's own units.
#[derive(ShaderType, Clone, Copy, Debug, PartialEq, Reflect)]
pub struct SwaySettings {
    /// Height (mesh coordinates) below which nothing moves: a blade's root, a crown's bottom.
    pub anchor: f32,
    /// Height above the anchor over which the bending weight grows to 1.
    pub height: f32,
    /// Wind speed, m/s, at which the bend reaches 1 − 1/e of `max_bend`.
    pub stiffness: f32,
    /// Largest bend, rad.
    pub max_bend: f32,
}

impl SwaySettings {
    /// Grass blades rooted at y = 0, `height` tall: they lie down to 70° in a strong breeze.
    pub fn grass(height: f32) -> Self {
        Self {
            anchor: 0.0,
            height,
            stiffness: 6.0,
            max_bend: 1.2,
        }
    }

    /// A tree's crown from `anchor` up over `height`: it leans a little, up to 0.15 rad in a gale.
    pub fn crown(anchor: f32, height: f32) -> Self {
        Self {
            anchor,
            height,
            stiffness: 12.0,
            max_bend: 0.15,
        }
    }

    /// As a vector (anchor, height, stiffness, max bend), with sizes kept positive.
    pub fn to_vec4(&self) -> Vec4 {
        Vec4::new(
            self.anchor,
            self.height.max(1e-6),
            self.stiffness.max(1e-6),
            self.max_bend,
        )
    }
}

/// The material extension: the wind's buffers ([`WindGpuBuffers`]) and how the mesh sways.
///
/// The model: each vertex turns downwind about the horizontal axis across the wind, about the
/// point at the anchor's height straight below it, by the angle
/// θ·w with θ = `max_bend` (1 − exp(−(|u_h| / `stiffness`)²)) and
/// w = clamp((y − `anchor`) / `height`, 0, 1)², where u_h is the horizontal wind at the vertex
/// and y its height in the mesh's own coordinates. So a blade's root (y = anchor) stays put, its
/// tip bends most (w² as a cantilever's deflection grows toward its free end), a light breeze
/// bends it in proportion to the dynamic pressure |u|² and a gale saturates it at `max_bend`;
/// turning (rather than shifting) keeps the blade's length. Each vertex samples the wind where it
/// is, so a gust front crossing a meadow bends the grass it reaches and no other.
///
/// Normals are not bent, and the material casts no shadows (its shadow would be the unbent
/// mesh's).
///
/// # Example
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_windfall::render::{SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial};
///
/// fn meadow(
///     mut commands: Commands,
///     mut meshes: ResMut<Assets<Mesh>>,
///     mut materials: ResMut<Assets<WindSwayMaterial>>,
///     wind: Res<WindGpuBuffers>,
/// ) {
///     commands.spawn((
///         Mesh3d(meshes.add(Cuboid::new(0.02, 0.6, 0.02))), // a reed, 0.6 m
///         MeshMaterial3d(materials.add(WindSwayMaterial {
///             base: StandardMaterial::from(Color::srgb(0.4, 0.6, 0.2)),
///             extension: WindSway::new(&wind, SwaySettings { anchor: -0.3, ..SwaySettings::grass(0.6) }),
///         })),
///     ));
/// }
/// ```
///
/// The wind is bound at 100 and 101 as [`WindGpuBuffers::bindings`] says (storage buffers, or a
/// texture and a uniform buffer on WebGL2), the settings at 102.
#[derive(Asset, Clone, Debug, Reflect)]
pub struct WindSway {
    /// The wind's data ([`WindGpuBuffers`]).
    #[reflect(ignore)]
    pub wind: WindGpuBuffers,
    /// How the mesh bends: [`SwaySettings::to_vec4`].
    pub sway: Vec4,
}

impl WindSway {
    /// Bending as `settings` says, in the wind of `buffers`.
    pub fn new(buffers: &WindGpuBuffers, settings: SwaySettings) -> Self {
        Self {
            wind: buffers.clone(),
            sway: settings.to_vec4(),
        }
    }
}

impl AsBindGroup for WindSway {
    type Data = ();
    type Param = (
        SRes<RenderAssets<GpuImage>>,
        SRes<RenderAssets<GpuShaderBuffer>>,
    );

    fn label() -> &'static str {
        "WindSway"
    }

    fn bind_group_data(&self) -> Self::Data {}

    fn build_bind_group(
        &self,
        _layout: &BindGroupLayout,
        device: &RenderDevice,
        (images, buffers): &mut SystemParamItem<'_, '_, Self::Param>,
        _force_no_bindless: bool,
        output: &mut BindGroupBuilder,
    ) -> Result<(), AsBindGroupError> {
        let mut sway = UniformBuffer::new(Vec::new());
        sway.write(&self.sway)
            .map_err(|_| AsBindGroupError::RetryNextUpdate)?;
        let sway = device.create_buffer_with_data(&BufferInitDescriptor {
            label: Some("WindSway settings"),
            contents: sway.as_ref(),
            usage: BufferUsages::UNIFORM | BufferUsages::COPY_DST,
        });
        let wind = self.wind.bindings(images, buffers)?;
        push_bindings(output, wind);
        push_bindings(output, [(102, OwnedBindingResource::Buffer(sway))]);
        Ok(())
    }

    fn bind_group_layout_entries(
        device: &RenderDevice,
        _force_no_bindless: bool,
    ) -> Vec<BindGroupLayoutEntry> {
        let mut entries = WindGpuBuffers::layout_entries(device, ShaderStages::VERTEX).to_vec();
        entries.push(uniform_buffer::<Vec4>(false).build(102, ShaderStages::VERTEX));
        entries
    }
}

impl MaterialExtension for WindSway {
    fn vertex_shader() -> ShaderRef {
        "embedded://bevy_windfall/sway.wesl".into()
    }

    fn enable_shadows() -> bool {
        false
    }

    fn enable_prepass() -> bool {
        false
    }
}
