//! How a falling object is outlined (a maple, oak or birch leaf, an ovate leaf, an ellipse of
//! paper, a coin, a card), from its [`Outline`] (its preset's, or ovate without one) and its
//! [`Shape`], and the colours of a leaf without a preset: one source for the single objects' meshes
//! ([`FallingObject::mesh`](super::FallingObject::mesh)), the leaf cloud's mesh and the
//! examples. A preset's palette is
//! [`FallPreset::palette`](super::FallPreset::palette).
//!
//! Hand-written: the outlines are polar functions chosen by eye (no crate draws leaves).

use std::f32::consts::{PI, TAU};

use bevy::color::Color;
use bevy::math::Vec2;

use super::model::body::Shape;

/// Reds, oranges, yellows and browns: the look of a leaf without a preset.
pub(crate) const AUTUMN: [Color; 5] = [
    Color::srgb(0.80, 0.30, 0.08),
    Color::srgb(0.90, 0.55, 0.10),
    Color::srgb(0.85, 0.72, 0.20),
    Color::srgb(0.55, 0.28, 0.10),
    Color::srgb(0.70, 0.15, 0.08),
];

/// Outline points of a single object's mesh (a cloud draws [`CLOUD_POINTS`]).
pub(crate) const SINGLE_POINTS: usize = 72;

/// Outline points of each leaf of a cloud: enough for the maple's five lobes at a distance.
#[cfg_attr(not(feature = "render"), allow(dead_code))]
pub(crate) const CLOUD_POINTS: usize = 14;

/// (width along X, length along Z) of a shape's plate, m.
pub(crate) fn extent(shape: &Shape) -> (f32, f32) {
    match *shape {
        Shape::Disk { diameter, .. } => (diameter, diameter),
        Shape::Rectangle { length, width, .. } => (width, length),
        Shape::Ellipse { major, minor, .. } => (minor, major),
    }
}

/// Rise of a leaf's edges per metre of half-width: leaves fold, paper, cards and coins do not.
pub(crate) fn fold(outline: Outline, shape: &Shape) -> f32 {
    match (outline, shape) {
        (_, Shape::Disk { .. } | Shape::Rectangle { .. }) | (Outline::Round, _) => 0.0,
        _ => 0.18,
    }
}

/// The outline as it would be drawn, and the point it is star-shaped about: `points` points from
/// the tip (+Z) toward +X, so that a fan `(centre, p[i], p[i + 1])` faces +Y, scaled to the
/// shape's width (X) and length (Z) about the middle of its bounding box. A disk or a rectangle
/// keeps its own outline whatever `kind` says.
pub(crate) fn outline(kind: Outline, shape: &Shape, points: usize) -> (Vec2, Vec<Vec2>) {
    let (width, length) = extent(shape);
    let half = 0.5 * Vec2::new(width, length);
    let (centre, unit): (Vec2, Vec<Vec2>) = match shape {
        Shape::Rectangle { .. } => {
            // The four corners, each edge split so a fan from the centre stays even.
            let corners = [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)];
            let per_edge = (points / 4).max(1);
            let edges = (0..4).flat_map(|e| {
                let a = Vec2::from(corners[e]);
                let b = Vec2::from(corners[(e + 1) % 4]);
                (0..per_edge).map(move |k| a.lerp(b, k as f32 / per_edge as f32))
            });
            (Vec2::ZERO, edges.collect())
        }
        _ => {
            let kind = match shape {
                Shape::Disk { .. } => Outline::Round,
                _ => kind,
            };
            let raw: Vec<Vec2> = (0..points.max(3))
                .map(|i| kind.point(TAU * i as f32 / points.max(3) as f32))
                .collect();
            normalise(raw)
        }
    };
    (centre * half, unit.into_iter().map(|p| p * half).collect())
}

/// Scales a raw outline (star-shaped about the origin) into [−1, 1]² about its bounding box's
/// middle; returns where the origin went, and the outline.
fn normalise(raw: Vec<Vec2>) -> (Vec2, Vec<Vec2>) {
    let (lo, hi) = raw.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let middle = 0.5 * (lo + hi);
    let scale = 2.0 / (hi - lo).max(Vec2::splat(f32::MIN_POSITIVE));
    let outline = raw.into_iter().map(|p| (p - middle) * scale).collect();
    (-middle * scale, outline)
}

/// The outline families.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outline {
    /// A disk or an ellipse of paper.
    Round,
    /// Ovate, pointed at the tip (the paper's leaf, a samara's wing).
    Ovate,
    /// Five pointed lobes (Norway maple).
    Maple,
    /// Rounded lobes along the sides (oak).
    Oak,
    /// Ovate with a toothed edge (birch).
    Birch,
}

impl Outline {
    /// The point at parameter `t` ∈ [0, 2π): 0 at the tip (+Z), π at the stalk, toward +X first.
    fn point(self, t: f32) -> Vec2 {
        // Ovate: x = sin t · w(t), z = cos t with w = ((1 − cos t)/2)^0.4: pointed at the tip,
        // rounded at the stalk.
        let width = (0.5 * (1.0 - t.cos())).powf(0.4);
        let ovate = Vec2::new(t.sin() * width, t.cos());
        match self {
            Self::Round => Vec2::new(t.sin(), t.cos()),
            Self::Ovate => ovate,
            Self::Birch => ovate * Vec2::new(1.0 + 0.04 * (13.0 * t).sin().abs(), 1.0),
            // Lobes as radial bulges, so that the outline stays star-shaped.
            Self::Oak => ovate * (0.75 + 0.25 * (4.5 * t).cos().abs().powf(0.6)),
            Self::Maple => {
                // Lobes at 0, ±0.95 and ±1.9 rad from the tip; a notch at the stalk.
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
}

/// SplitMix64's finaliser: a colour index from a seed or a leaf's index.
pub(crate) fn mix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::freefall::object::{FallPreset, FallingObject};
    use bevy::mesh::Mesh;

    /// Every outline spans its shape exactly and winds so that the fan's faces point up (+Y),
    /// for every preset and without one.
    #[test]
    fn outlines_span_their_shape_and_wind_one_way() {
        let looks = FallPreset::ALL.map(Some).into_iter().chain([None]);
        for look in looks {
            let object = FallingObject {
                look,
                ..look.map_or_else(FallingObject::default, FallPreset::object)
            };
            let (width, length) = extent(&object.shape);
            for points in [CLOUD_POINTS, SINGLE_POINTS] {
                let (centre, o) = outline(object.outline(), &object.shape, points);
                let (lo, hi) = o.iter().fold((Vec2::MAX, Vec2::MIN), |(lo, hi), p| {
                    (lo.min(*p), hi.max(*p))
                });
                let span = hi - lo;
                assert!(
                    (span.x - width).abs() < 1e-3 * width,
                    "{look:?}: {span} vs {width}"
                );
                assert!((span.y - length).abs() < 1e-3 * length, "{look:?}: {span}");
                // Every fan triangle, in (z, x) order: positive when it faces +Y.
                for i in 0..o.len() {
                    let (a, b) = (o[i] - centre, o[(i + 1) % o.len()] - centre);
                    let twice_area = a.y * b.x - b.y * a.x;
                    assert!(twice_area > 0.0, "{look:?}: triangle {i} faces −Y");
                }
            }
            let mesh = object.mesh();
            let normals = mesh.attribute(Mesh::ATTRIBUTE_NORMAL).unwrap().as_float3();
            let up = normals.unwrap().iter().filter(|n| n[1] > 0.5).count();
            assert_eq!(up, mesh.count_vertices(), "{look:?}: every face toward +Y");
        }
    }
}
