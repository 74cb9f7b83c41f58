//! What the GPU needs of a [`WindField`], packed as `wind.wesl` reads it: the turbulence nodes
//! once per field, and every frame the small [`GpuWindParams`] (clock, log-law constants, σ's,
//! the pattern's travel, the pulse, shelters and local sources).
//!
//! Every time-dependent quantity is taken at the field's clock `t0` in f64 and reduced there
//! (the travel modulo the grid's period, the time coordinate modulo the samples, the pulse
//! phase modulo 1), so the shader only adds `dt` (seconds after `t0`) in f32 and stays as exact
//! as the CPU after hours of play.

use bevy::math::{DVec2, UVec4, Vec2, Vec3, Vec4};
use bevy::render::render_resource::ShaderType;
use bevy::render::render_resource::encase::StorageBuffer;

use crate::wind::{ShelterKind, SourceShape, SpatialMode, TemporalMode, WindField};

/// Shelters and sources the GPU sees at once, together ([`GpuWindParams::locals`]); the rest
/// are left out (and [`GpuWindParams::dropped`] counts them). A fixed size keeps the buffer's
/// size, so bind groups that hold it never go stale.
pub(crate) const MAX_GPU_LOCALS: usize = 64;

/// One shelter or local source, as `WindLocal` in `wind.wesl`.
#[derive(ShaderType, Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct GpuLocal {
    /// World position of the entity.
    pub origin: Vec3,
    /// What it is: 1 sphere, 2 fan, 3 vortex, 4 blast, 5 gust, 6 mover; 10 room, 11 wall.
    pub kind: u32,
    /// World-to-local rotation (x, y, z, w).
    pub to_local: Vec4,
    /// Local-to-world rotation (x, y, z, w).
    pub to_world: Vec4,
    /// A sphere's or a mover's velocity, or a shelter's half extents.
    pub vector: Vec3,
    /// Nothing beyond this distance², m².
    pub reach_squared: f32,
    /// The shape's numbers, in the order of [`SourceShape`]'s fields after the first vector
    /// (fan: range, half angle, speed; vortex: radius, peak speed, updraft; blast: peak speed,
    /// front speed, radius; gust: strength, front speed, width, range; sphere: radius; mover:
    /// radius, ground, mirror share; wall: lee heights, depth).
    pub shape: Vec4,
    /// The source's strength.
    pub strength: f32,
    /// Seconds since it started, at `t0`.
    pub age: f32,
    /// Its pulse: magnitude, frequency (Hz), phase at `t0` (cycles, in [0, 1)).
    pub pulse: Vec3,
}

/// The per-frame parameters of the wind, as `WindParams` in `wind.wesl`.
#[derive(ShaderType, Clone, Debug, PartialEq)]
pub(crate) struct GpuWindParams {
    /// Nodes along (time, x, y, z); 1 for an axis the field does not have.
    pub dims: UVec4,
    /// Unit direction of the mean wind (x, z).
    pub along: Vec2,
    /// How far the turbulence pattern has travelled at `t0` at the reference speed (x, z), m;
    /// for a plane field reduced modulo the grid's period.
    pub drift: Vec2,
    /// U(h_ref), m/s.
    pub reference_speed: f32,
    /// z0, m.
    pub roughness: f32,
    /// ln z0.
    pub log_roughness: f32,
    /// ln(h_ref/z0), eq. 14's denominator.
    pub log_reference: f32,
    /// (σ_u, σ_v, σ_w) at the reference height, m/s.
    pub sigma: Vec3,
    /// Distance between nodes, m.
    pub cell_size: f32,
    /// 1 for a volume field (the pattern travels at the local mean wind), 0 for a plane.
    pub volume: u32,
    /// The time coordinate at `t0`, in samples modulo the sample count (evolving fields).
    pub time_coordinate: f32,
    /// Samples per second of wind time (evolving fields; 0 when frozen).
    pub samples_per_second: f32,
    /// Wind time `t0`, s, as f32 (for display; the shader works relative to it).
    pub time: f32,
    /// The global pulse: magnitude, frequency (Hz), phase at `t0` (cycles, in [0, 1)).
    pub pulse: Vec3,
    /// How many of [`Self::locals`] are shelters (they come first).
    pub shelter_count: u32,
    /// How many of [`Self::locals`] are sources and movers (after the shelters).
    pub source_count: u32,
    /// Shelters and sources beyond [`MAX_GPU_LOCALS`], left out.
    pub dropped: u32,
    /// Shelters, then sources in the order the CPU sums them.
    pub locals: [GpuLocal; MAX_GPU_LOCALS],
}

/// `x` modulo `period` in [0, period) (f64, then f32).
fn wrap(x: f64, period: f64) -> f32 {
    if period > 0.0 && x.is_finite() {
        (x - (x / period).floor() * period) as f32
    } else {
        0.0
    }
}

/// A pulse as (magnitude, frequency, phase at `age`), clamped as
/// [`crate::wind::Pulse::factor`] clamps; an inactive pulse is all zeros.
fn pulse(p: crate::wind::Pulse, age: f64) -> Vec3 {
    let p = p.clamped();
    if !p.is_active() {
        return Vec3::ZERO;
    }
    let phase = if age.is_finite() {
        (age * f64::from(p.frequency)).rem_euclid(1.0) as f32
    } else {
        0.0
    };
    Vec3::new(p.magnitude, p.frequency, phase)
}

fn quat(q: bevy::math::Quat) -> Vec4 {
    Vec4::from(q)
}

impl GpuWindParams {
    /// The bytes the shader reads: the struct laid out by WGSL's rules (encase's storage
    /// layout, which a uniform buffer of this struct shares: every member is 16-byte aligned
    /// where the uniform rules ask it).
    pub fn bytes(&self) -> Vec<u8> {
        let mut buffer = StorageBuffer::new(Vec::new());
        buffer
            .write(self)
            .expect("a Vec grows to hold the parameters");
        buffer.into_inner()
    }

    /// The parameters of `field` at its own clock.
    pub fn of(field: &WindField) -> Self {
        let t0 = field.time_f64();
        let c = field.config();
        let dims = field.grid_dims();
        let evolving = matches!(c.temporal, TemporalMode::Evolving { .. });
        let volume = matches!(c.spatial, SpatialMode::Volume { .. });
        let mut axes = dims.iter().copied();
        let nt = if evolving {
            axes.next().unwrap_or(1)
        } else {
            1
        };
        let nx = axes.next().unwrap_or(1);
        let ny = if volume { axes.next().unwrap_or(1) } else { 1 };
        let nz = axes.next().unwrap_or(1);
        let (time_coordinate, samples_per_second) = match c.temporal {
            TemporalMode::Evolving { samples, period } => (
                wrap(t0 / f64::from(period) * samples as f64, samples as f64),
                samples as f32 / period,
            ),
            TemporalMode::Frozen => (0.0, 0.0),
        };
        let drift: DVec2 = field.drift_at(t0);
        let cell = f64::from(c.cell_size);
        // A plane's pattern repeats every n cells: reduce the travel there, exactly. A volume's
        // travel is scaled by the height's log-law ratio first, so it is sent whole.
        let drift = if volume {
            drift.as_vec2()
        } else {
            Vec2::new(
                wrap(drift.x, nx as f64 * cell),
                wrap(drift.y, nz as f64 * cell),
            )
        };
        let (log_reference, log_roughness) = field.log_constants();
        let along = field.direction();
        let mut locals = [GpuLocal::default(); MAX_GPU_LOCALS];
        let shelters = field.placed_shelters();
        let sources = field.placed_sources();
        let mut count = 0;
        for s in shelters.iter().take(MAX_GPU_LOCALS) {
            let (kind, shape) = match s.kind {
                ShelterKind::Indoor => (10, Vec4::ZERO),
                ShelterKind::Wall { lee_heights, depth } => {
                    (11, Vec4::new(lee_heights, depth, 0.0, 0.0))
                }
            };
            locals[count] = GpuLocal {
                origin: s.origin.into(),
                kind,
                to_local: quat(s.to_local),
                to_world: quat(s.to_local.inverse()),
                vector: s.half,
                reach_squared: s.reach2,
                shape,
                ..GpuLocal::default()
            };
            count += 1;
        }
        let shelter_count = count;
        for s in sources.iter().take(MAX_GPU_LOCALS - shelter_count) {
            let (kind, vector, shape) = match s.shape {
                SourceShape::Sphere { radius, velocity } => {
                    (1, velocity, Vec4::new(radius, 0.0, 0.0, 0.0))
                }
                SourceShape::Fan {
                    range,
                    half_angle,
                    speed,
                } => (2, Vec3::ZERO, Vec4::new(range, half_angle, speed, 0.0)),
                SourceShape::Vortex {
                    radius,
                    peak_speed,
                    updraft,
                } => (3, Vec3::ZERO, Vec4::new(radius, peak_speed, updraft, 0.0)),
                SourceShape::Blast {
                    peak_speed,
                    front_speed,
                    radius,
                } => (
                    4,
                    Vec3::ZERO,
                    // Never inward, as on the CPU.
                    Vec4::new(peak_speed.max(0.0), front_speed, radius, 0.0),
                ),
                SourceShape::Gust {
                    strength,
                    front_speed,
                    width,
                    range,
                } => (
                    5,
                    Vec3::ZERO,
                    Vec4::new(strength, front_speed, width, range),
                ),
            };
            let age = t0 - s.start;
            locals[count] = GpuLocal {
                origin: s.origin.into(),
                kind,
                to_local: quat(s.to_local),
                to_world: quat(s.to_world),
                vector,
                reach_squared: s.reach2,
                shape,
                strength: if kind == 4 {
                    s.strength.max(0.0)
                } else {
                    s.strength
                },
                age: age as f32,
                pulse: pulse(s.pulse, age),
            };
            count += 1;
        }
        // The movers after the sources, in the order the CPU sums them.
        let movers = field.placed_movers();
        for m in movers.iter().take(MAX_GPU_LOCALS - count) {
            locals[count] = GpuLocal {
                origin: m.centre,
                kind: 6,
                vector: m.velocity,
                reach_squared: m.reach2,
                shape: Vec4::new(m.radius, m.ground, m.mirror, 0.0),
                strength: 1.0,
                ..GpuLocal::default()
            };
            count += 1;
        }
        Self {
            dims: UVec4::new(nt as u32, nx as u32, ny as u32, nz as u32),
            along: Vec2::new(along.x, along.z),
            drift,
            reference_speed: c.reference_speed,
            roughness: c.roughness,
            log_roughness,
            log_reference,
            sigma: field.sigma(),
            cell_size: c.cell_size,
            volume: u32::from(volume),
            time_coordinate,
            samples_per_second,
            time: t0 as f32,
            pulse: pulse(c.pulse, t0),
            shelter_count: shelter_count as u32,
            source_count: (count - shelter_count) as u32,
            dropped: (shelters.len() + sources.len() + movers.len() - count) as u32,
            locals,
        }
    }
}

/// The turbulence nodes as the shader reads them: (u, v, w) per node, row-major over
/// (time, x, y, z), little-endian f32, `stride` floats a node (3 in a storage buffer, 4 in an
/// RGBA32F texel, the fourth 0).
pub(crate) fn node_bytes(field: &WindField, stride: usize) -> Vec<u8> {
    let nodes = field.nodes();
    let mut bytes = Vec::with_capacity(nodes.len() * 4 * stride);
    for n in nodes {
        for v in n.extend(0.0).to_array().into_iter().take(stride) {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the CPU spends on uploads (a test build, not a release benchmark): packing the nodes
    /// of the default 128² plane (once per field) and the parameters (every frame).
    #[test]
    fn packing_the_default_plane() {
        let field = WindField::new(crate::wind::WindConfig::default()).unwrap();
        let start = std::time::Instant::now();
        let bytes = node_bytes(&field, 3);
        let packing = start.elapsed();
        let start = std::time::Instant::now();
        for _ in 0..100 {
            std::hint::black_box(GpuWindParams::of(&field));
        }
        println!(
            "128² plane: {} B of nodes packed in {packing:?}; parameters in {:?} a frame",
            bytes.len(),
            start.elapsed() / 100
        );
        assert_eq!(bytes.len(), 128 * 128 * 12);
    }

    /// WebGL2 reads the parameters as a uniform buffer: the same bytes must satisfy the uniform
    /// address space's rules (16-byte array strides and struct alignment), and fit its 16 KiB.
    #[test]
    fn the_parameters_are_a_valid_uniform_block() {
        GpuWindParams::assert_uniform_compat();
        let size = GpuWindParams::min_size().get();
        assert!(size <= 16 * 1024 && size % 16 == 0, "{size} B");
    }
}
