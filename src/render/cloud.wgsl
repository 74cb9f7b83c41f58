// Vertex shader of `LeafCloudMaterial`: one mesh holds every leaf of a cloud at the origin,
// each vertex tagged with its leaf's index (the second UV set's x); the leaf's pose (position,
// rotation) is read from a storage buffer (or a texture) written once per frame. See `src/render/cloud.rs`.
#import bevy_pbr::{
    forward_io::{Vertex, VertexOutput},
    view_transformations::position_world_to_clip,
}
#import bevy_windfall::math::rotate_by_quat

struct LeafPose {
    // xyz: position, m; w: scale.
    position: vec4<f32>,
    // A unit quaternion (x, y, z, w).
    rotation: vec4<f32>,
}

// Binding 103: 100 and 101 stay free for the wind (`bevy_windfall::wind`), 102 is the sway's.
// A storage buffer where the device has them (`GpuLayout::of`), else (WebGL2) an RGBA32F
// texture, two texels a leaf in rows of an even width.
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 4
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var<storage, read> leaf_poses: array<LeafPose>;

fn leaf_pose(leaf: u32) -> LeafPose {
    return leaf_poses[min(leaf, arrayLength(&leaf_poses) - 1u)];
}
#else
@group(#{MATERIAL_BIND_GROUP}) @binding(103) var leaf_pose_texture: texture_2d<f32>;

fn leaf_pose(leaf: u32) -> LeafPose {
    let size = textureDimensions(leaf_pose_texture);
    let k = min(2u * leaf, size.x * size.y - 2u);
    let at = vec2<u32>(k % size.x, k / size.x);
    return LeafPose(
        textureLoad(leaf_pose_texture, at, 0),
        textureLoad(leaf_pose_texture, at + vec2<u32>(1u, 0u), 0),
    );
}
#endif

@vertex
fn vertex(vertex: Vertex) -> VertexOutput {
    var out: VertexOutput;
#ifdef VERTEX_UVS_B
    let leaf = u32(vertex.uv_b.x);
#else
    let leaf = 0u;
#endif
    let pose = leaf_pose(leaf);
    let world = pose.position.xyz + rotate_by_quat(pose.rotation, vertex.position * pose.position.w);
    out.world_position = vec4<f32>(world, 1.0);
    out.position = position_world_to_clip(world);
#ifdef VERTEX_NORMALS
    out.world_normal = rotate_by_quat(pose.rotation, vertex.normal);
#endif
#ifdef VERTEX_UVS_A
    out.uv = vertex.uv;
#endif
#ifdef VERTEX_UVS_B
    out.uv_b = vertex.uv_b;
#endif
#ifdef VERTEX_COLORS
    out.color = vertex.color;
#endif
#ifdef VERTEX_OUTPUT_INSTANCE_INDEX
    out.instance_index = vertex.instance_index;
#endif
    return out;
}
