//! The double-sided triangle mesh of a cloth's node grid ([`build`]), rewritten in place each
//! frame ([`write()`]): a [`ClothSim`](super::ClothSim)'s or a particle cloth's.

use bevy::asset::RenderAssetUsages;
use bevy::math::Vec3;
use bevy::mesh::{Indices, Mesh, PrimitiveTopology, VertexAttributeValues};

/// A double-sided mesh of a `rows × columns` node grid: the front side's vertices, then the
/// back side's with flipped normals and reversed winding. UVs run along the yarns (u) and down
/// the cloth (v). Kept in main-world memory so it can be rewritten every frame.
pub fn build(rows: usize, columns: usize, positions: &[Vec3]) -> Mesh {
    let count = rows * columns;
    let mut uvs = Vec::with_capacity(2 * count);
    for _side in 0..2 {
        for k in 0..rows {
            for j in 0..columns {
                let v = if rows > 1 {
                    k as f32 / (rows - 1) as f32
                } else {
                    0.0
                };
                uvs.push([j as f32 / (columns - 1).max(1) as f32, v]);
            }
        }
    }
    let mut indices = Vec::with_capacity(12 * rows.saturating_sub(1) * columns.saturating_sub(1));
    for k in 0..rows.saturating_sub(1) {
        for j in 0..columns.saturating_sub(1) {
            let a = (k * columns + j) as u32;
            let b = a + columns as u32;
            let (c, d) = (a + 1, b + 1);
            // Front: counter-clockwise seen from the front normal.
            indices.extend([a, b, c, c, b, d]);
            let o = count as u32;
            indices.extend([a + o, c + o, b + o, c + o, d + o, b + o]);
        }
    }
    let mut mesh = Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, vec![[0.0f32; 3]; 2 * count])
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 0.0, 1.0]; 2 * count])
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
    .with_inserted_indices(Indices::U32(indices));
    write(&mut mesh, rows, columns, positions);
    mesh
}

/// Rewrites the positions and normals of a mesh made by [`build`] in place. Front normals
/// are along-yarn tangent × upward tangent by central differences (one-sided at the edges), +Z
/// where the grid is degenerate.
pub fn write(mesh: &mut Mesh, rows: usize, columns: usize, positions: &[Vec3]) {
    let count = rows * columns;
    if let Some(VertexAttributeValues::Float32x3(out)) =
        mesh.attribute_mut(Mesh::ATTRIBUTE_POSITION)
        && out.len() == 2 * count
    {
        for (i, p) in positions.iter().enumerate() {
            out[i] = p.to_array();
            out[i + count] = p.to_array();
        }
    }
    if let Some(VertexAttributeValues::Float32x3(out)) = mesh.attribute_mut(Mesh::ATTRIBUTE_NORMAL)
        && out.len() == 2 * count
    {
        let (front, back) = out.split_at_mut(count);
        for k in 0..rows {
            // Rows above and below (the row itself at an edge): one-sided differences there.
            let above = &positions[k.saturating_sub(1) * columns..][..columns];
            let below = &positions[(k + 1).min(rows - 1) * columns..][..columns];
            let row = &positions[k * columns..][..columns];
            let normals = front[k * columns..][..columns].iter_mut();
            let flipped = back[k * columns..][..columns].iter_mut();
            for (j, (n, b)) in normals.zip(flipped).enumerate() {
                let along = row[(j + 1).min(columns - 1)] - row[j.saturating_sub(1)];
                let up = if rows > 1 {
                    above[j] - below[j]
                } else {
                    Vec3::Y
                };
                let normal = along.cross(up).normalize_or(Vec3::Z);
                *n = normal.to_array();
                *b = (-normal).to_array();
            }
        }
    }
}
