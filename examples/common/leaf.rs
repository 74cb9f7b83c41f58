//! Leaf-shaped meshes: an outline from a polar function, a fan of triangles from its centre,
//! folded a little along the midrib so light shows its shape from either side.

use std::f32::consts::{PI, TAU};

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;

/// The outline of a leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outline {
    /// Five pointed lobes (Norway maple).
    Maple,
    /// Rounded lobes along the sides (oak).
    Oak,
    /// Ovate with a pointed tip and a toothed edge (birch).
    Birch,
    /// Ovate, smooth (the paper's leaf).
    Ovate,
}

/// A point of the outline at parameter `t` ∈ [0, 2π) (0 at the tip, local +Z; π at the stalk),
/// before scaling to size. Every outline is star-shaped about the origin.
fn outline_point(outline: Outline, t: f32) -> Vec2 {
    // Ovate: x = sin t · w(t), z = cos t with w = ((1 − cos t)/2)^0.4: pointed at the tip,
    // rounded at the stalk.
    let width = (0.5 * (1.0 - t.cos())).powf(0.4);
    let ovate = Vec2::new(t.sin() * width, t.cos());
    match outline {
        Outline::Ovate => ovate,
        Outline::Birch => ovate * Vec2::new(1.0 + 0.04 * (13.0 * t).sin().abs(), 1.0),
        Outline::Oak => ovate * Vec2::new(0.75 + 0.25 * (4.5 * t).cos().abs().powf(0.6), 1.0),
        Outline::Maple => {
            // Polar: lobes at 0, ±0.95 and ±1.9 rad from the tip; a notch at the stalk.
            let a = if t > PI { TAU - t } else { t };
            let lobe =
                |centre: f32, w: f32, height: f32| height * (-((a - centre) / w).powi(2)).exp();
            let lobes = lobe(0.0, 0.26, 1.0)
                .max(lobe(0.95, 0.24, 0.9))
                .max(lobe(1.9, 0.22, 0.65));
            let stalk = 1.0 - 0.5 * (-((a - PI) / 0.3).powi(2)).exp();
            let r = (0.4 + 0.6 * lobes) * stalk;
            Vec2::new(r * t.sin(), r * t.cos())
        }
    }
}

/// A leaf `major` m long (along local Z, the axis a falling leaf tumbles about) and `minor` m
/// wide (local X), in the local XZ plane with its faces toward ±Y, folded along the midrib by
/// `fold` (the rise of the edges per metre of half-width). Flat-shaded; use a two-sided
/// material.
pub fn leaf_mesh(outline: Outline, major: f32, minor: f32, fold: f32) -> Mesh {
    const POINTS: usize = 96;
    let raw: Vec<Vec2> = (0..POINTS)
        .map(|i| outline_point(outline, TAU * i as f32 / POINTS as f32))
        .collect();
    // Scale the outline to the size asked for.
    let (lo, hi) = raw.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let centre = 0.5 * (lo + hi);
    let scale = Vec2::new(minor, major) / (hi - lo);
    // The fold along the midrib, and the tip and stalk curling up a little.
    let lift = |p: Vec2| Vec3::new(p.x, fold * p.x.abs() + 0.3 * p.y * p.y / major, p.y);
    let mut positions = vec![lift(Vec2::ZERO)];
    positions.extend(raw.iter().map(|p| lift((*p - centre) * scale)));
    let mut indices = Vec::with_capacity(3 * POINTS);
    for i in 0..POINTS as u32 {
        // Counter-clockwise seen from +Y: the front faces up.
        indices.extend([0, 1 + i, 1 + (i + 1) % POINTS as u32]);
    }
    let mut mesh = Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        positions.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
    )
    .with_inserted_indices(Indices::U32(indices));
    mesh.duplicate_vertices();
    mesh.compute_flat_normals();
    mesh
}
