//! The showcase's scenery: a sunlit meadow, its ground in patches of green, and a matte
//! two-sided material.

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
