//! Wind on the GPU (feature `render`): the [`WindField`] uploaded as two storage buffers and a
//! WESL module, `bevy_windfall::wind`, whose `wind_velocity_at(position, dt)` returns what
//! [`WindField::velocity_at`] returns on the CPU for the same field: the same nodes read by the
//! same multilinear interpolation and wrapping, the same log law (eq. 10, 14), pulse, shelters
//! and local sources. Grass, foliage and particles then sway in the very gusts that carry the
//! falling leaves.
//!
//! | binding | contents | uploaded |
//! |---|---|---|
//! | 100 `wind_nodes` | the turbulence nodes, 3 × f32 each | when the field is built or rebuilt |
//! | 101 `wind_params` | the field's parameters: clock, log-law constants, σ's, travel, pulse, ≤ 64 shelters and sources | every frame (7 280 B) |
//!
//! Both live in [`WindGpuBuffers`]. Where the device has storage buffers ([`GpuLayout::Storage`]:
//! WebGPU, Vulkan, Metal, DX12) they are two read-only storage [`ShaderBuffer`]s: bind them in a
//! material (`#[storage(100, read_only)]`, `#[storage(101, read_only)]`) or in a compute pass
//! (set the shader def `WIND_BIND_GROUP` to the group's index). On WebGL2
//! ([`GpuLayout::Texture`]) the nodes are an RGBA32F texture ([`WindGpuBuffers::node_texture`],
//! one node a texel, rows as wide as the device allows: 2 048 on WebGL2) and the parameters a
//! uniform buffer of the same bytes;
//! [`WindGpuBuffers::layout_entries`] and [`WindGpuBuffers::bindings`] bind whichever the device
//! has, as [`WindSway`] does. The module is WESL (a game's shader that imports it is a `.wesl`
//! file) and reads either the same way:
//!
//! ```wgsl
//! import bevy_windfall::wind::{wind_velocity, wind_velocity_at};
//!
//! let here = wind_velocity(world_position);        // at the field's clock
//! let soon = wind_velocity_at(world_position, 0.5); // half a second of wind time later
//! ```
//!
//! [`LeafCloudRenderPlugin`] draws every [`LeafCloud`](crate::freefall::LeafCloud) in one draw
//! call: a mesh of all its leaves whose vertex shader reads each leaf's pose from a storage
//! buffer, or on WebGL2 a texture (`cloud.wesl`, binding 103, so a cloud's material may also bind
//! the wind at 100 and 101; the sway material's settings are at 102). Helpers the shaders share (a rotation by a
//! quaternion) are in the module `bevy_windfall::math`.
//!
//! Time in the shader is relative to the uploaded clock (`dt`, seconds): everything that grows
//! with the clock is reduced on the CPU in f64, so f32 on the GPU stays as exact as the CPU
//! after hours of play. `tests/it/gpu_wind.rs` checks the GPU against the CPU at thousands of points.

mod cloud;
mod layout;
mod look;
mod params;
mod sway;

pub use cloud::{CloudPoses, LeafCloudLook, LeafCloudMaterial, LeafCloudRenderPlugin};
pub use layout::GpuLayout;
pub use look::WindfallRenderPlugin;

use params::{GpuWindParams, node_bytes};
pub use sway::{SwaySettings, WindSway, WindSwayMaterial};

use bevy::app::{App, Plugin, PostUpdate};
use bevy::asset::{Assets, Handle, RenderAssetUsages};
use bevy::ecs::prelude::*;
use bevy::image::Image;
use bevy::log::warn;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    AsBindGroupError, BindGroupLayoutEntry, BufferUsages, OwnedBindingResource, ShaderStages,
};
use bevy::render::renderer::RenderDevice;
use bevy::render::storage::{GpuShaderBuffer, ShaderBuffer};
use bevy::render::texture::GpuImage;
use bevy::shader::Shader;

use layout::{bound_buffer, bound_texture, record_texture, texture_width};

use crate::wind::WindField;

/// The crate's WESL modules, kept loaded: `bevy_windfall::math`, `bevy_windfall::wind` (the one a
/// game imports), and the sway and leaf-cloud vertex shaders.
#[derive(Resource)]
struct ShaderModules(
    #[allow(dead_code, reason = "held so the modules stay loaded")] Vec<Handle<Shader>>,
);

/// Embeds the crate's shaders at `embedded://bevy_windfall/NAME.wesl`, so that each is the WESL
/// module `bevy_windfall::NAME` (the folder `render/` is left out of the path: the wind module's
/// import path is part of the public contract), and loads them for good. Both plugins that draw
/// call it; the second call changes nothing.
fn embed_shaders(app: &mut App) {
    if app.world().contains_resource::<ShaderModules>() {
        return;
    }
    bevy::asset::embedded_asset!(app, "render", "math.wesl");
    bevy::asset::embedded_asset!(app, "render", "wind.wesl");
    bevy::asset::embedded_asset!(app, "render", "sway.wesl");
    bevy::asset::embedded_asset!(app, "render", "cloud.wesl");
    let server = app.world().resource::<bevy::asset::AssetServer>();
    let modules = ["math", "wind", "sway", "cloud"]
        .map(|name| server.load(format!("embedded://bevy_windfall/{name}.wesl")))
        .to_vec();
    app.insert_resource(ShaderModules(modules));
}

/// Uploads the [`WindField`] to the GPU and registers the WESL module `bevy_windfall::wind`.
/// [`WindfallPlugins`](struct@crate::WindfallPlugins) adds it (through [`WindfallRenderPlugin`]) in an
/// app with the renderer; on its own, add it after `DefaultPlugins` and a
/// [`WindPlugin`](crate::wind::WindPlugin).
///
/// # Example
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
/// use bevy_windfall::render::WindGpuPlugin;
///
/// App::new()
///     .add_plugins((DefaultPlugins, WindPlugin::default(), WindGpuPlugin))
///     .run();
/// ```
#[derive(Default)]
pub struct WindGpuPlugin;

/// The wind's GPU data (see the [module](self)): bind these handles, or let
/// [`Self::layout_entries`] and [`Self::bindings`] bind them.
#[derive(Resource, Clone, Debug, Default)]
pub struct WindGpuBuffers {
    /// The turbulence nodes (`wind_nodes`, binding 100) as a storage buffer
    /// ([`GpuLayout::Storage`]; a placeholder otherwise).
    pub nodes: Handle<ShaderBuffer>,
    /// The turbulence nodes as an RGBA32F texture, node `i` at texel (i mod width, i / width)
    /// ([`GpuLayout::Texture`]; a placeholder otherwise).
    pub node_texture: Handle<Image>,
    /// The field's per-frame parameters (`wind_params`, binding 101): the struct
    /// `WindParams` of the WESL module, as a storage or (textures layout) a uniform buffer.
    pub params: Handle<ShaderBuffer>,
    /// Which of the above the shaders read on this device.
    pub layout: GpuLayout,
}

impl WindGpuBuffers {
    /// The bind group layout entries of the wind (bindings 100 and 101) on `device`, seen by
    /// `visibility`.
    pub fn layout_entries(
        device: &RenderDevice,
        visibility: ShaderStages,
    ) -> [BindGroupLayoutEntry; 2] {
        let layout = GpuLayout::of(device);
        [
            layout.array_entry(100, visibility),
            layout.buffer_entry(101, visibility),
        ]
    }

    /// The resources to bind at 100 and 101 (render world), or
    /// [`AsBindGroupError::RetryNextUpdate`] while they are not on the GPU yet.
    pub fn bindings(
        &self,
        images: &RenderAssets<GpuImage>,
        buffers: &RenderAssets<GpuShaderBuffer>,
    ) -> Result<[(u32, OwnedBindingResource); 2], AsBindGroupError> {
        let nodes = match self.layout {
            GpuLayout::Storage => bound_buffer(buffers, &self.nodes)?,
            GpuLayout::Texture => bound_texture(images, &self.node_texture)?,
        };
        Ok([(100, nodes), (101, bound_buffer(buffers, &self.params)?)])
    }
}

/// What the last uploads cost: bytes of nodes per field and of parameters per frame (the
/// crate's GPU test reads it; not API).
#[doc(hidden)]
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct WindGpuUploads {
    /// The [`WindField::generation`] the nodes on the GPU belong to (0: none yet).
    pub generation: u64,
    /// Bytes of the node buffer.
    pub node_bytes: usize,
    /// How many times the nodes were uploaded.
    pub node_uploads: u32,
    /// Bytes of the parameters, sent every frame.
    pub param_bytes: usize,
}

impl Plugin for WindGpuPlugin {
    fn build(&self, app: &mut App) {
        // Added twice (by you and by `WindfallPlugins`): once is enough.
        if app.world().contains_resource::<WindGpuUploads>() {
            return;
        }
        embed_shaders(app);
        app.init_resource::<WindGpuUploads>()
            .add_plugins(bevy::pbr::MaterialPlugin::<WindSwayMaterial>::default())
            .add_systems(PostUpdate, (upload_wind, refresh_sway_materials).chain());
    }

    /// Not unique: [`WindfallRenderPlugin`] adds it, and so may you.
    fn is_unique(&self) -> bool {
        false
    }

    fn finish(&self, app: &mut App) {
        if app.world().contains_resource::<WindGpuBuffers>() {
            return;
        }
        let world = app.world_mut();
        let Some(layout) = world.get_resource::<RenderDevice>().map(GpuLayout::of) else {
            warn!("WindGpuPlugin needs the renderer (add it after DefaultPlugins)");
            return;
        };
        // Placeholders of the right kind until the first upload: one node, empty parameters.
        let mut buffers = world.resource_mut::<Assets<ShaderBuffer>>();
        let nodes = buffers.add(ShaderBuffer::new(
            vec![0u8; 12],
            RenderAssetUsages::RENDER_WORLD,
        ));
        let params = buffers.add(params_buffer(&empty_params(), layout));
        let node_texture = world
            .resource_mut::<Assets<Image>>()
            .add(record_texture(vec![0; 16], 2));
        world.insert_resource(WindGpuBuffers {
            nodes,
            node_texture,
            params,
            layout,
        });
    }
}

fn empty_params() -> GpuWindParams {
    GpuWindParams::of(
        &WindField::new(crate::wind::WindConfig {
            grid: [2, 2],
            ..Default::default()
        })
        .expect("a valid field"),
    )
}

fn params_buffer(params: &GpuWindParams, layout: GpuLayout) -> ShaderBuffer {
    let mut buffer = ShaderBuffer::new(params.bytes(), RenderAssetUsages::default());
    if layout == GpuLayout::Texture {
        buffer.buffer_usage = BufferUsages::UNIFORM | BufferUsages::COPY_DST;
    }
    buffer
}

/// When the node buffer or texture changes size (a new grid), the GPU resource is a new one: the
/// sway materials' bind groups are rebuilt by marking the materials changed, in that frame and
/// the next (the render world may prepare the materials before the new nodes in the first).
fn refresh_sway_materials(
    uploads: Res<WindGpuUploads>,
    mut materials: ResMut<Assets<WindSwayMaterial>>,
    mut bound: Local<(usize, u8)>,
) {
    let (bytes, frames) = &mut *bound;
    if uploads.node_bytes != *bytes {
        *bytes = uploads.node_bytes;
        *frames = 2;
    }
    if *frames > 0 {
        *frames -= 1;
        let ids: Vec<_> = materials.ids().collect();
        for id in ids {
            materials.get_mut(id);
        }
    }
}

/// Sends the nodes when the field is new and the parameters every frame.
fn upload_wind(
    field: Option<Res<WindField>>,
    gpu: Option<Res<WindGpuBuffers>>,
    device: Option<Res<RenderDevice>>,
    mut buffers: ResMut<Assets<ShaderBuffer>>,
    mut images: ResMut<Assets<Image>>,
    mut uploads: ResMut<WindGpuUploads>,
) {
    let (Some(field), Some(gpu)) = (field, gpu) else {
        return;
    };
    if uploads.generation != field.generation() {
        uploads.generation = field.generation();
        uploads.node_uploads += 1;
        // Kept on the render side only: no CPU copy of the nodes stays behind.
        let removed = match gpu.layout {
            GpuLayout::Storage => {
                let bytes = node_bytes(&field, 3);
                uploads.node_bytes = bytes.len();
                let buffer = ShaderBuffer::new(bytes, RenderAssetUsages::RENDER_WORLD);
                buffers.insert(&gpu.nodes, buffer).is_err()
            }
            GpuLayout::Texture => {
                let max = device.map_or(2048, |d| d.limits().max_texture_dimension_2d);
                let nodes = field.nodes().len();
                let width = texture_width(nodes, max);
                let room = width as usize * max as usize;
                if nodes > room {
                    warn!(
                        "WindGpuPlugin: {nodes} nodes do not fit a {max}-texel texture; the \
                         GPU reads the first {room}"
                    );
                }
                let mut bytes = node_bytes(&field, 4);
                bytes.truncate(room * 16);
                uploads.node_bytes = bytes.len();
                let image = record_texture(bytes, width);
                images.insert(&gpu.node_texture, image).is_err()
            }
        };
        if removed {
            warn!("WindGpuPlugin: the node buffer was removed");
        }
    }
    let params = GpuWindParams::of(&field);
    if let Some(mut buffer) = buffers.get_mut(&gpu.params) {
        let bytes = params.bytes();
        uploads.param_bytes = bytes.len();
        buffer.data = ShaderBuffer::new(bytes, buffer.asset_usage).data;
    }
}
