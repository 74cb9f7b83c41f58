// Helpers shared by the crate's shaders: the wind module (`wind.wgsl`), the sway material and the
// leaf cloud. Import with `#import bevy_windfall::math::rotate_by_quat`.
#define_import_path bevy_windfall::math

// v turned by the unit quaternion q (x, y, z, w): v + 2w (q × v) + 2 q × (q × v).
fn rotate_by_quat(q: vec4<f32>, v: vec3<f32>) -> vec3<f32> {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}
