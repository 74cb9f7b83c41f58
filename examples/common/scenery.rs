//! The showcase's scenery: a sunlit meadow, its ground in patches of green, blades of grass for
//! the GPU to bend, and a matte two-sided material.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;

/// A sunlit meadow: a directional light from `sun` toward the origin, ambient light and a grass
/// plane `size` metres across at y = 0. Returns the light and the plane.
pub fn meadow(
    commands: &mut Commands,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<StandardMaterial>,
    sun: Vec3,
    size: f32,
) -> [Entity; 2] {
    let light = commands
        .spawn((
            DirectionalLight {
                illuminance: 9_000.0,
                ..default()
            },
            Transform::from_translation(sun).looking_at(Vec3::ZERO, Vec3::Y),
        ))
        .id();
    commands.insert_resource(GlobalAmbientLight {
        brightness: 700.0,
        ..default()
    });
    let ground = commands
        .spawn((
            Mesh3d(meshes.add(grass(size, Color::srgb(0.38, 0.52, 0.28)))),
            MeshMaterial3d(materials.add(Color::WHITE)),
        ))
        .id();
    [light, ground]
}

/// A grass plane `size` metres across at y = 0, in patches of lighter and darker green around
/// `color` (vertex colours from a few crossed sines: lush and dry patches a few metres wide), so
/// that the ground reads as a meadow rather than a flat sheet.
pub fn grass(size: f32, color: Color) -> Mesh {
    let cells = 96;
    let mut mesh = Plane3d::default()
        .mesh()
        .size(size, size)
        .subdivisions(cells - 1)
        .build();
    let Some(bevy::mesh::VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        return mesh;
    };
    let base = color.to_linear();
    let colors: Vec<[f32; 4]> = positions
        .iter()
        .map(|&[x, _, z]| {
            let patches = (0.43 * x + 0.2 * z).sin() * (0.31 * z - 0.15 * x).cos()
                + 0.5 * (1.7 * x + 1.1).sin() * (1.3 * z + 0.4).sin();
            let light = 1.0 + 0.22 * patches;
            let dry = (0.5 + 0.5 * (0.11 * x - 0.23 * z + 2.0).sin()).powi(3);
            [
                base.red * light * (1.0 + 0.5 * dry),
                base.green * light,
                base.blue * light * (1.0 - 0.3 * dry),
                1.0,
            ]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_COLOR, colors);
    mesh
}

/// A matte material seen from both sides (leaves, cloth).
pub fn two_sided(
    materials: &mut Assets<StandardMaterial>,
    color: Color,
) -> Handle<StandardMaterial> {
    materials.add(StandardMaterial {
        base_color: color,
        double_sided: true,
        cull_mode: None,
        perceptual_roughness: 0.8,
        ..default()
    })
}

/// `count` blades over the rectangle `min`..`max` (x, z) at y = 0: each a tapered strip of
/// three triangles, 2–3 cm wide, 0.35–1 × `tallest` m tall, turned at random, darker at the root. The
/// mesh's y is the height above the ground, as `SwaySettings::grass` expects.
pub fn blades(count: u32, tallest: f32, min: Vec2, max: Vec2) -> Mesh {
    let (mut positions, mut normals, mut colors, mut indices) = (vec![], vec![], vec![], vec![]);
    for blade in 0..count {
        // Four numbers in [0, 1) per blade from a low-discrepancy sequence.
        let r = [0.754_877_7, 0.569_840_3, 0.438_993_9, 0.324_717_9]
            .map(|a| (blade as f32 * a).fract());
        let root = min + (max - min) * Vec2::new(r[0], r[1]);
        let yaw = std::f32::consts::TAU * r[2];
        let (side, face) = (
            Vec3::new(yaw.cos(), 0.0, yaw.sin()),
            Vec3::new(-yaw.sin(), 0.0, yaw.cos()),
        );
        let height = tallest * (0.35 + 0.65 * r[3]);
        let width = 0.02 + 0.01 * r[2];
        let base = positions.len() as u32;
        // Root pair, middle pair, tip.
        for (h, w) in [
            (0.0, 0.5),
            (0.0, -0.5),
            (0.55, 0.35),
            (0.55, -0.35),
            (1.0, 0.0),
        ] {
            let p = Vec3::new(root.x, 0.0, root.y) + side * (w * width) + Vec3::Y * (h * height);
            positions.push(p.to_array());
            normals.push((Vec3::Y + 0.4 * face).normalize().to_array());
            let c = Vec3::new(0.16, 0.34, 0.08).lerp(Vec3::new(0.45, 0.56, 0.18), h);
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
