//! Where the crate's shaders find their data on this device: storage buffers where the device
//! has them (WebGPU and every native backend), textures and a uniform buffer where it has not
//! (WebGL2). The choice is made at run time from the device's limits, by the same rule on the
//! CPU ([`GpuLayout::of`]) and in WESL (`@if(AVAILABLE_STORAGE_BUFFER_BINDINGS__GE_6)`, a flag
//! Bevy sets from the same limit).
//!
//! Hand-written rather than derived: `#[derive(AsBindGroup)]` fixes each binding's kind at
//! compile time, and one build of a game may run on either kind of device (a browser with or
//! without WebGPU).

use bevy::asset::{Handle, RenderAssetUsages};
use bevy::image::Image;
use bevy::reflect::Reflect;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::{
    AsBindGroupError, BindGroupBuilder, BindGroupLayoutEntry, BindingType, BufferBindingType,
    Extent3d, OwnedBindingResource, ShaderStages, TextureDimension, TextureFormat,
    TextureSampleType, TextureViewDimension, UnpreparedBindingResource,
};
use bevy::render::renderer::RenderDevice;
use bevy::render::storage::{GpuShaderBuffer, ShaderBuffer};
use bevy::render::texture::GpuImage;

/// How the crate's shaders read the wind's nodes and parameters and a leaf cloud's poses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Reflect)]
pub enum GpuLayout {
    /// Read-only storage buffers (WebGPU, Vulkan, Metal, DX12).
    #[default]
    Storage,
    /// Float textures read texel by texel (the wind's nodes, a cloud's poses) and a uniform
    /// buffer (the wind's parameters): WebGL2, or any device with fewer than
    /// [`GpuLayout::STORAGE_BUFFERS_NEEDED`] storage buffers in a shader stage.
    Texture,
}

impl GpuLayout {
    /// Storage buffers a shader stage must offer for [`GpuLayout::Storage`]. A vertex stage
    /// needs four (the wind's two, a cloud's poses and Bevy's own mesh array); six is the
    /// smallest count at or above that which Bevy's shader flags test
    /// (`AVAILABLE_STORAGE_BUFFER_BINDINGS__GE_6`), the flag the WESL modules read. Every
    /// WebGPU, Vulkan, Metal and DX12 device offers at least eight.
    pub const STORAGE_BUFFERS_NEEDED: u32 = 6;

    /// The layout the shaders compiled for `device` use.
    pub fn of(device: &RenderDevice) -> Self {
        Self::for_storage_buffers(device.limits().max_storage_buffers_per_shader_stage)
    }

    /// The layout for a device with `per_stage` storage buffers in each shader stage.
    pub fn for_storage_buffers(per_stage: u32) -> Self {
        if per_stage >= Self::STORAGE_BUFFERS_NEEDED {
            Self::Storage
        } else {
            Self::Texture
        }
    }

    /// The layout entry of a buffer of data at `binding`: read-only storage, or (textures
    /// layout) a uniform buffer.
    pub fn buffer_entry(self, binding: u32, visibility: ShaderStages) -> BindGroupLayoutEntry {
        let ty = match self {
            Self::Storage => BufferBindingType::Storage { read_only: true },
            Self::Texture => BufferBindingType::Uniform,
        };
        BindGroupLayoutEntry {
            binding,
            visibility,
            ty: BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }
    }

    /// The layout entry of an array of records at `binding`: read-only storage, or (textures
    /// layout) an unfilterable float texture read with `textureLoad`.
    pub fn array_entry(self, binding: u32, visibility: ShaderStages) -> BindGroupLayoutEntry {
        match self {
            Self::Storage => self.buffer_entry(binding, visibility),
            Self::Texture => BindGroupLayoutEntry {
                binding,
                visibility,
                ty: BindingType::Texture {
                    sample_type: TextureSampleType::Float { filterable: false },
                    view_dimension: TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
        }
    }
}

/// The bound resource of a [`ShaderBuffer`], or "try again" while it is not on the GPU yet.
pub(crate) fn bound_buffer(
    buffers: &RenderAssets<GpuShaderBuffer>,
    handle: &Handle<ShaderBuffer>,
) -> Result<OwnedBindingResource, AsBindGroupError> {
    buffers
        .get(handle)
        .map(|b| OwnedBindingResource::Buffer(b.buffer.clone()))
        .ok_or(AsBindGroupError::RetryNextUpdate)
}

/// Adds `bindings` (as [`WindGpuBuffers::bindings`](super::WindGpuBuffers::bindings) returns
/// them) to the bind group a hand-written `AsBindGroup::build_bind_group` builds.
pub(crate) fn push_bindings(
    output: &mut BindGroupBuilder,
    bindings: impl IntoIterator<Item = (u32, OwnedBindingResource)>,
) {
    for (binding, resource) in bindings {
        let resource = match resource {
            OwnedBindingResource::Buffer(buffer) => UnpreparedBindingResource::Buffer(buffer),
            OwnedBindingResource::ShaderBuffer(handle) => {
                UnpreparedBindingResource::ShaderBuffer(handle)
            }
            OwnedBindingResource::TextureView(dimension, view) => {
                UnpreparedBindingResource::TextureView(dimension, view)
            }
            OwnedBindingResource::Sampler(kind, sampler) => {
                UnpreparedBindingResource::Sampler(kind, sampler)
            }
            OwnedBindingResource::Data(data) => {
                let start = output.data_buffer.len() as u32;
                output.data_buffer.extend_from_slice(&data);
                UnpreparedBindingResource::Data(start..output.data_buffer.len() as u32)
            }
        };
        output.binding_resources.push((binding, resource));
    }
}

/// The bound resource of an [`Image`], or "try again" while it is not on the GPU yet.
pub(crate) fn bound_texture(
    images: &RenderAssets<GpuImage>,
    handle: &Handle<Image>,
) -> Result<OwnedBindingResource, AsBindGroupError> {
    images
        .get(handle)
        .map(|i| {
            OwnedBindingResource::TextureView(TextureViewDimension::D2, i.texture_view.clone())
        })
        .ok_or(AsBindGroupError::RetryNextUpdate)
}

/// Texels of a record texture's row: as many as the records need, at most `max_width`, and
/// even (a leaf's pose is two texels, never split across rows).
pub(crate) fn texture_width(texels: usize, max_width: u32) -> u32 {
    let max = (max_width.max(2) & !1) as usize;
    (texels.clamp(2, max) as u32 + 1) & !1
}

/// `texels` RGBA32F texels (16 bytes each, in `bytes`) as a texture `width` texels wide, the
/// last row padded with zeros. `bytes` must hold whole texels.
pub(crate) fn record_texture(mut bytes: Vec<u8>, width: u32) -> Image {
    let texels = (bytes.len() / 16).max(1);
    let height = texels.div_ceil(width as usize) as u32;
    bytes.resize((width * height) as usize * 16, 0);
    Image::new(
        Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        bytes,
        TextureFormat::Rgba32Float,
        RenderAssetUsages::RENDER_WORLD,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_even_and_within_the_device_limit() {
        for (texels, max, width) in [(1, 2048, 2), (7, 2048, 8), (5000, 2048, 2048), (9, 7, 6)] {
            assert_eq!(
                texture_width(texels, max),
                width,
                "{texels} texels, ≤ {max}"
            );
        }
        let image = record_texture(vec![0; 16 * 5000], 2048);
        assert_eq!((image.width(), image.height()), (2048, 3));
        assert_eq!(image.data.as_ref().map(Vec::len), Some(2048 * 3 * 16));
    }

    #[test]
    fn webgl2_limits_choose_textures() {
        let webgl2 = bevy::render::settings::WgpuLimits::downlevel_webgl2_defaults();
        let webgpu = bevy::render::settings::WgpuLimits::default();
        assert_eq!(
            GpuLayout::for_storage_buffers(webgl2.max_storage_buffers_per_shader_stage),
            GpuLayout::Texture
        );
        assert_eq!(
            GpuLayout::for_storage_buffers(webgpu.max_storage_buffers_per_shader_stage),
            GpuLayout::Storage
        );
    }
}
