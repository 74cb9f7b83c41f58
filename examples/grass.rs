//! Grass that sways on the GPU in the very wind that carries the leaves: 60 000 blades in one
//! mesh (one draw call), bent vertex by vertex by a `WindSwayMaterial`, whose vertex shader
//! samples the `WindField` that `WindfallPlugins` uploads each frame (the WESL module
//! `bevy_windfall::wind`). Gusts cross the meadow as waves of bending grass.
//!
//! `cargo run --example grass`

mod common;

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::render::{SwaySettings, WindGpuBuffers, WindSway, WindSwayMaterial};

/// Blades, and the tallest blade, m.
const BLADES: u32 = 60_000;
const TALLEST: f32 = 0.42;

fn main() {
    let wind = WindConfig {
        reference_speed: 6.0,
        ..default()
    };
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(WindfallPlugins.set(WindPlugin::new(wind)))
        .add_plugins(common::ScreenshotPlugin)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.76, 0.90)))
        .add_systems(Startup, setup)
        .run();
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut sway: ResMut<Assets<WindSwayMaterial>>,
    wind: Res<WindGpuBuffers>,
) {
    commands.spawn((
        Camera3d::default(),
        Transform::from_xyz(0.0, 1.6, 7.0).looking_at(Vec3::new(0.0, 0.2, 0.0), Vec3::Y),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 8.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(40.0, 40.0))),
        MeshMaterial3d(materials.add(Color::srgb(0.30, 0.42, 0.20))),
    ));
    // The blades' material: a standard one, bent by the wind (grass rooted at y = 0).
    let material = sway.add(WindSwayMaterial {
        base: StandardMaterial {
            perceptual_roughness: 0.85,
            double_sided: true,
            cull_mode: None,
            ..default()
        },
        extension: WindSway::new(&wind, SwaySettings::grass(TALLEST)),
    });
    commands.spawn((
        Mesh3d(meshes.add(blades(Vec2::new(-8.0, -8.0), Vec2::new(8.0, 5.0)))),
        MeshMaterial3d(material),
    ));
}

/// [`BLADES`] blades over the rectangle `min`..`max` (x, z) at y = 0: each a tapered strip of
/// three triangles, 2–3 cm wide, 0.15–0.42 m tall, turned at random, darker at the root. The
/// mesh's y is the height above the ground, as [`SwaySettings::grass`] expects.
fn blades(min: Vec2, max: Vec2) -> Mesh {
    let (mut positions, mut normals, mut colors, mut indices) = (vec![], vec![], vec![], vec![]);
    for blade in 0..BLADES {
        // Four numbers in [0, 1) per blade from a low-discrepancy sequence.
        let r = [0.754_877_7, 0.569_840_3, 0.438_993_9, 0.324_717_9]
            .map(|a| (blade as f32 * a).fract());
        let root = min + (max - min) * Vec2::new(r[0], r[1]);
        let yaw = std::f32::consts::TAU * r[2];
        let (side, face) = (
            Vec3::new(yaw.cos(), 0.0, yaw.sin()),
            Vec3::new(-yaw.sin(), 0.0, yaw.cos()),
        );
        let height = TALLEST * (0.35 + 0.65 * r[3]);
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
