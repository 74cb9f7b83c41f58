// The wind of a bevy_windfall `WindField` on the GPU: the same log-law mean wind, the same
// periodic grid read by the same multilinear interpolation, the same shelters and local sources
// as `WindField::velocity_at` on the CPU (see `src/wind/field.rs`, `source.rs`, `shelter.rs`;
// equation numbers are those of Realistic Motion Simulations of Objects in Free Fall).
//
// Bindings: `wind_nodes` (binding 100) and `wind_params` (binding 101) in the bind group
// `WIND_BIND_GROUP` if that shader def is set (a compute pass), otherwise in the material's bind
// group (`MATERIAL_BIND_GROUP`, for a `MaterialExtension`).
//
// Time: `dt` is seconds of wind time after the clock the parameters were uploaded at
// (`wind_params.time`, the field's clock at the frame's last fixed step). Everything that grows
// with the clock was reduced on the CPU in f64, so f32 here stays exact after hours of play.
#define_import_path bevy_windfall::wind

#import bevy_windfall::math::rotate_by_quat

struct WindLocal {
    origin: vec3<f32>,
    kind: u32,
    to_local: vec4<f32>,
    to_world: vec4<f32>,
    vector: vec3<f32>,
    reach_squared: f32,
    shape: vec4<f32>,
    strength: f32,
    age: f32,
    pulse: vec3<f32>,
}

struct WindParams {
    dims: vec4<u32>,
    along: vec2<f32>,
    drift: vec2<f32>,
    reference_speed: f32,
    roughness: f32,
    log_roughness: f32,
    log_reference: f32,
    sigma: vec3<f32>,
    cell_size: f32,
    volume: u32,
    time_coordinate: f32,
    samples_per_second: f32,
    time: f32,
    pulse: vec3<f32>,
    shelter_count: u32,
    source_count: u32,
    dropped: u32,
    locals: array<WindLocal, 64>,
}

// Where the device has storage buffers (Bevy's `AVAILABLE_STORAGE_BUFFER_BINDINGS`, the rule of
// `GpuLayout::of` in src/render/layout.rs) the nodes and parameters are read-only storage; on
// WebGL2 the nodes are an RGBA32F texture and the parameters a uniform buffer of the same bytes.
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 4
#ifdef WIND_BIND_GROUP
@group(#{WIND_BIND_GROUP}) @binding(100) var<storage, read> wind_nodes: array<f32>;
@group(#{WIND_BIND_GROUP}) @binding(101) var<storage, read> wind_params: WindParams;
#else
@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<storage, read> wind_nodes: array<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var<storage, read> wind_params: WindParams;
#endif
#else
#ifdef WIND_BIND_GROUP
@group(#{WIND_BIND_GROUP}) @binding(100) var wind_node_texture: texture_2d<f32>;
@group(#{WIND_BIND_GROUP}) @binding(101) var<uniform> wind_params: WindParams;
#else
@group(#{MATERIAL_BIND_GROUP}) @binding(100) var wind_node_texture: texture_2d<f32>;
@group(#{MATERIAL_BIND_GROUP}) @binding(101) var<uniform> wind_params: WindParams;
#endif
#endif

const WIND_TAU: f32 = 6.283185307179586;
const WIND_ROOM_EDGE: f32 = 0.25;
const WIND_TINY: f32 = 1.1754944e-38;

// (u, v, w) of node `i`.
fn wind_node(i: u32) -> vec3<f32> {
#if AVAILABLE_STORAGE_BUFFER_BINDINGS >= 4
    return vec3<f32>(wind_nodes[3u * i], wind_nodes[3u * i + 1u], wind_nodes[3u * i + 2u]);
#else
    // Node i at texel (i mod width, i / width); a field larger than the texture (warned about
    // on the CPU) reads its last texel.
    let size = textureDimensions(wind_node_texture);
    let j = min(i, size.x * size.y - 1u);
    return textureLoad(wind_node_texture, vec2<u32>(j % size.x, j / size.x), 0).xyz;
#endif
}

// Multilinear interpolation on the periodic grid at node coordinates `c` = (time, x, y, z);
// an axis of one node contributes nothing (as `periodic_lerp` in src/spectrum/sample.rs).
fn wind_lerp(c: vec4<f32>) -> vec3<f32> {
    let dims = wind_params.dims;
    var low = vec4<u32>(0u);
    var high = vec4<u32>(0u);
    var frac = vec4<f32>(0.0);
    for (var axis = 0u; axis < 4u; axis++) {
        let n = dims[axis];
        let len = f32(n);
        var x = c[axis] - floor(c[axis] / len) * len;
        x = clamp(x, 0.0, len);
        let i = min(u32(x), n - 1u);
        low[axis] = i;
        high[axis] = (i + 1u) % n;
        frac[axis] = clamp(x - f32(i), 0.0, 1.0);
    }
    let strides = vec4<u32>(dims.y * dims.z * dims.w, dims.z * dims.w, dims.w, 1u);
    var sum = vec3<f32>(0.0);
    for (var corner = 0u; corner < 16u; corner++) {
        var weight = 1.0;
        var index = 0u;
        for (var axis = 0u; axis < 4u; axis++) {
            if ((corner >> axis) & 1u) == 1u {
                weight *= frac[axis];
                index += high[axis] * strides[axis];
            } else {
                weight *= 1.0 - frac[axis];
                index += low[axis] * strides[axis];
            }
        }
        if weight != 0.0 {
            sum += wind_node(index) * weight;
        }
    }
    return sum;
}

// 1 + m sin(2π (phase + f dt)) for a pulse (magnitude, frequency, phase at the upload).
fn wind_pulse(pulse: vec3<f32>, dt: f32) -> f32 {
    if pulse.x == 0.0 {
        return 1.0;
    }
    let cycles = fract(pulse.z + pulse.y * dt);
    return max(1.0 + pulse.x * sin(WIND_TAU * cycles), 0.0);
}

// The log-law mean wind plus turbulence (eq. 10, 14), without shelters and sources.
fn wind_global(p: vec3<f32>, dt: f32) -> vec3<f32> {
    let w = wind_params;
    var log_ratio = 0.0;
    if p.y > w.roughness {
        log_ratio = max(log(p.y) - w.log_roughness, 0.0);
    }
    let g = log_ratio / w.log_reference; // eq. 14
    let mean = w.reference_speed * g; // = (u*/κ) ln(h/z0), eq. 10
    var scale = g;
    var travel = w.drift + w.along * (w.reference_speed * dt);
    if w.volume == 1u {
        scale = min(g, 1.0);
        travel = travel * g; // the pattern travels at the local mean wind
    }
    // Taylor's hypothesis: the pattern translates with the mean wind.
    let per_cell = 1.0 / w.cell_size;
    let x = (p.x - travel.x) * per_cell;
    let z = (p.z - travel.y) * per_cell;
    let t = w.time_coordinate + dt * w.samples_per_second;
    let n = wind_lerp(vec4<f32>(t, x, p.y * per_cell, z)) * scale * w.sigma;
    let along = vec3<f32>(w.along.x, 0.0, w.along.y);
    let across = vec3<f32>(-w.along.y, 0.0, w.along.x); // along × Y
    let wind = along * (mean + n.x) + across * n.y + vec3<f32>(0.0, n.z, 0.0);
    return wind * wind_pulse(w.pulse, dt);
}

// The fade (1 − s²)², 1 at s = 0, 0 with zero slope at |s| ≥ 1.
fn wind_fade(s: f32) -> f32 {
    let t = max(1.0 - s * s, 0.0);
    return t * t;
}

// 1 up to `inner`, then fading to 0 at `outer`.
fn wind_plateau(x: f32, inner: f32, outer: f32) -> f32 {
    if x <= inner {
        return 1.0;
    }
    return wind_fade((x - inner) / max(outer - inner, WIND_TINY));
}

// How much of the global wind a shelter leaves at `p` (src/wind/shelter.rs).
fn wind_shelter(s: WindLocal, p: vec3<f32>) -> f32 {
    let d = p - s.origin;
    let rr = dot(d, d);
    if rr >= s.reach_squared {
        return 1.0;
    }
    let local = rotate_by_quat(s.to_local, d);
    let outside = length(max(abs(local) - s.vector, vec3<f32>(0.0)));
    if s.kind == 10u {
        return 1.0 - wind_fade(outside / WIND_ROOM_EDGE);
    }
    if outside == 0.0 {
        return 0.0;
    }
    let half = s.vector;
    let height = 2.0 * half.y;
    let length_ = max(max(s.shape.x, 0.0) * height, WIND_TINY);
    let downwind = rotate_by_quat(s.to_local, vec3<f32>(wind_params.along.x, 0.0, wind_params.along.y));
    var wind = vec3<f32>(downwind.x, 0.0, downwind.z);
    let wl = length(wind);
    if wl > 0.0 {
        wind = wind / wl;
    }
    let side = vec3<f32>(-wind.z, 0.0, wind.x);
    let deep = half.x * abs(wind.x) + half.z * abs(wind.z);
    let wide = half.x * abs(side.x) + half.z * abs(side.z);
    let past = dot(local, wind) - deep;
    if past <= 0.0 || past >= length_ {
        return 1.0;
    }
    let aside = max(abs(dot(local, side)) - wide, 0.0) / (0.5 * height);
    let above = max(local.y - half.y, 0.0) / (0.5 * height);
    if local.y < -half.y {
        return 1.0;
    }
    return 1.0 - clamp(s.shape.y, 0.0, 1.0) * wind_fade(past / length_) * wind_fade(aside)
        * wind_fade(above);
}

// The velocity a source adds at `p`, `dt` after the upload (src/wind/source.rs).
fn wind_source(s: WindLocal, p: vec3<f32>, dt: f32) -> vec3<f32> {
    let d = p - s.origin;
    let rr = dot(d, d);
    if rr >= s.reach_squared {
        return vec3<f32>(0.0);
    }
    let r = sqrt(rr);
    let k = s.shape;
    var v = vec3<f32>(0.0);
    switch s.kind {
        case 1u: { // sphere
            v = s.vector * wind_fade(r / k.x);
        }
        case 2u: { // fan: range, half angle, speed
            let forward = rotate_by_quat(s.to_world, vec3<f32>(0.0, 0.0, -1.0));
            let along = dot(d, forward);
            if along > 0.0 && r > 0.0 {
                let angle = acos(min(along / r, 1.0));
                if angle < k.y {
                    v = d / r * (k.z * wind_fade(angle / k.y) * wind_fade(along / k.x));
                }
            }
        }
        case 3u: { // vortex: radius, peak speed, updraft
            let local = rotate_by_quat(s.to_local, d);
            let horizontal = sqrt(local.x * local.x + local.z * local.z);
            let envelope = wind_plateau(r, 0.5 * k.x, k.x);
            let core = 0.2 * k.x;
            var swirl = core / horizontal;
            if horizontal <= core {
                swirl = horizontal / core;
            }
            var tangent = vec3<f32>(0.0);
            if horizontal > 0.0 {
                tangent = vec3<f32>(local.z, 0.0, -local.x) / horizontal;
            }
            let lift = k.z * wind_fade(horizontal / max(k.x, WIND_TINY));
            v = rotate_by_quat(s.to_world, tangent * (k.y * swirl) + vec3<f32>(0.0, lift, 0.0))
                * envelope;
        }
        case 4u: { // blast: peak speed, front speed, radius
            let age = s.age + dt;
            if age >= 0.0 && r > 0.0 {
                let front = age * k.y;
                let width = 0.2 * k.z;
                let behind = front - r;
                if behind >= 0.0 && behind <= width {
                    let u = behind / max(width, WIND_TINY);
                    v = d / r * (k.x * wind_fade(u) * wind_plateau(r, 0.5 * k.z, k.z));
                }
            }
        }
        case 5u: { // gust: strength, front speed, width, range
            let age = s.age + dt;
            let local = rotate_by_quat(s.to_local, d);
            let along = -local.z;
            if age >= 0.0 && along >= 0.0 && along <= k.w {
                let behind = age * k.y - along;
                if behind >= 0.0 && behind <= k.z {
                    let u = 2.0 * behind / max(k.z, WIND_TINY) - 1.0;
                    let across = length(local.xy) / (0.5 * k.w);
                    v = rotate_by_quat(s.to_world, vec3<f32>(0.0, 0.0, -1.0))
                        * (k.x * wind_fade(u) * wind_fade(across));
                }
            }
        }
        default: {}
    }
    return v * (s.strength * wind_pulse(s.pulse, dt));
}

// The wind velocity at world position `p`, `dt` seconds of wind time after the uploaded clock,
// m/s: `WindField::velocity_at(p, t0 + dt)` on the CPU.
fn wind_velocity_at(p: vec3<f32>, dt: f32) -> vec3<f32> {
    var wind = wind_global(p, dt);
    let shelters = wind_params.shelter_count;
    for (var i = 0u; i < shelters; i++) {
        wind *= wind_shelter(wind_params.locals[i], p);
    }
    let end = shelters + wind_params.source_count;
    for (var i = shelters; i < end; i++) {
        wind += wind_source(wind_params.locals[i], p, dt);
    }
    return wind;
}

// The wind velocity at world position `p` at the uploaded clock, m/s.
fn wind_velocity(p: vec3<f32>) -> vec3<f32> {
    return wind_velocity_at(p, 0.0);
}
