//! A meadow of grass blades that sway on the GPU in the same wind that carries the leaves: one
//! mesh of [`BLADES`] blades by default (one draw), bent vertex by vertex by a [`WindSwayMaterial`].

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy_windfall::render::{SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial};

/// Blades in the meadow by default.
pub const BLADES: usize = 120_000;

/// Blades in the meadow (`--blades N`).
#[derive(Resource, Clone, Copy)]
pub struct Blades(pub usize);
/// Tallest blade, m.
const TALLEST: f32 = 0.42;

/// `count` blades over the rectangle `min`..`max` (x, z) at y = 0: each a tapered, slightly
/// curved strip of two triangles, 2–3 cm wide at the root, 0.15–0.42 m tall, turned at random,
/// darker at the root and yellower at the tip. The mesh's y is the height above the ground, as
/// [`SwaySettings::grass`] expects.
pub fn blades(count: usize, min: Vec2, max: Vec2, seed: u64) -> Mesh {
    let mut rng = super::population::Stream::new(seed);
    let mut positions = Vec::with_capacity(count * 5);
    let mut normals = Vec::with_capacity(count * 5);
    let mut colors = Vec::with_capacity(count * 5);
    let mut indices = Vec::with_capacity(count * 9);
    for _ in 0..count {
        let root = Vec3::new(
            min.x + (max.x - min.x) * rng.uniform(),
            0.0,
            min.y + (max.y - min.y) * rng.uniform(),
        );
        let yaw = std::f32::consts::TAU * rng.uniform();
        let (side, face) = (
            Vec3::new(yaw.cos(), 0.0, yaw.sin()),
            Vec3::new(-yaw.sin(), 0.0, yaw.cos()),
        );
        let height = TALLEST * (0.35 + 0.65 * rng.uniform());
        let width = 0.02 + 0.01 * rng.uniform();
        let lean = face * (0.15 * height * (rng.uniform() - 0.3));
        let dry = rng.uniform();
        let base = positions.len() as u32;
        // Root pair, middle pair, tip.
        for (h, w) in [
            (0.0, 0.5),
            (0.0, -0.5),
            (0.55, 0.35),
            (0.55, -0.35),
            (1.0, 0.0),
        ] {
            let p = root + side * (w * width) + Vec3::Y * (h * height) + lean * (h * h);
            positions.push(p.to_array());
            normals.push((Vec3::Y + 0.4 * face).normalize().to_array());
            let green = Vec3::new(0.16, 0.34, 0.08).lerp(Vec3::new(0.42, 0.55, 0.18), h);
            let c = green.lerp(Vec3::new(0.55, 0.5, 0.22), 0.35 * dry * h);
            colors.push([c.x, c.y, c.z, 1.0]);
        }
        indices.extend_from_slice(&[base, base + 1, base + 2, base + 1, base + 3, base + 2]);
        indices.extend_from_slice(&[base + 2, base + 3, base + 4]);
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colors)
    .with_inserted_indices(Indices::U32(indices))
}

/// Spawns the meadow's grass, `count` blades over `min`..`max`; returns its entity.
pub fn spawn(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<WindSwayMaterial>,
    wind: &WindGpuBuffers,
    count: usize,
    min: Vec2,
    max: Vec2,
) -> Entity {
    let mesh = meshes.add(blades(count, min, max, 17));
    let material = materials.add(WindSwayMaterial {
        base: StandardMaterial {
            base_color: Color::WHITE,
            perceptual_roughness: 0.85,
            double_sided: true,
            cull_mode: None,
            ..default()
        },
        extension: WindSway::new(
            wind,
            SwaySettings {
                stiffness: 1.5,
                ..SwaySettings::grass(TALLEST)
            },
        ),
    });
    commands
        .spawn((Mesh3d(mesh), MeshMaterial3d(material)))
        .id()
}
