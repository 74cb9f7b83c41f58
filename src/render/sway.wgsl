// Vertex shader of `WindSway` materials: every vertex bends downwind by the wind where it is
// (`bevy_windfall::wind`, the same field the falling leaves feel), more the higher it is above
// the material's anchor. See `src/render/sway.rs` for the model.
#import bevy_pbr::{
    mesh_functions,
    forward_io::{Vertex, VertexOutput},
    view_transformations::position_world_to_clip,
}
#import bevy_windfall::wind::wind_velocity

struct Sway {
    anchor: f32,
    height: f32,
    stiffness: f32,
    max_bend: f32,
}

@group(#{MATERIAL_BIND_GROUP}) @binding(102) var<uniform> sway: Sway;

// The vertex at `world` (its local height `local_y`) bent by the wind: it turns about the
// horizontal axis across the wind, about the point at the anchor's height below it, by
// θ·w, θ = max_bend (1 − exp(−(|u_h| / stiffness)²)), w = clamp((y − anchor) / height, 0, 1)².
fn sway_bend(world: vec3<f32>, local_y: f32, scale_y: f32) -> vec3<f32> {
    let above = (local_y - sway.anchor) * scale_y;
    if above <= 0.0 {
        return world;
    }
    let u = wind_velocity(world);
    let speed = length(u.xz);
    if speed == 0.0 {
        return world;
    }
    let w = clamp((local_y - sway.anchor) / sway.height, 0.0, 1.0);
    let r = speed / sway.stiffness;
    let theta = sway.max_bend * (1.0 - exp(-r * r)) * w * w;
    let downwind = u.xz / speed;
    let shift = above * sin(theta);
    let drop = above * (1.0 - cos(theta));
    return world + vec3<f32>(downwind.x * shift, -drop, downwind.y * shift);
}

@vertex
fn vertex(vertex: Vertex) -> VertexOutput {
    var out: VertexOutput;
    let world_from_local = mesh_functions::get_world_from_local(vertex.instance_index);
    let rest = mesh_functions::mesh_position_local_to_world(
        world_from_local,
        vec4<f32>(vertex.position, 1.0),
    );
    let scale_y = length(world_from_local[1].xyz);
    let bent = sway_bend(rest.xyz, vertex.position.y, scale_y);
    out.world_position = vec4<f32>(bent, 1.0);
    out.position = position_world_to_clip(bent);
#ifdef VERTEX_NORMALS
    out.world_normal = mesh_functions::mesh_normal_local_to_world(
        vertex.normal,
        vertex.instance_index,
    );
#endif
#ifdef VERTEX_UVS_A
    out.uv = vertex.uv;
#endif
#ifdef VERTEX_UVS_B
    out.uv_b = vertex.uv_b;
#endif
#ifdef VERTEX_TANGENTS
    out.world_tangent = mesh_functions::mesh_tangent_local_to_world(
        world_from_local,
        vertex.tangent,
        vertex.instance_index,
    );
#endif
#ifdef VERTEX_COLORS
    out.color = vertex.color;
#endif
#ifdef VERTEX_OUTPUT_INSTANCE_INDEX
    out.instance_index = vertex.instance_index;
#endif
    return out;
}
