//! Shape constraints of the cloth paper §5.1: the pole edge (eq. 8) and the distance between
//! neighbouring yarns (eq. 7).

use bevy::math::{Vec2, Vec3};

use super::sim::edge_angle;

/// Start of yarn `k` in its yarn plane (along the yarn, across it), eq. 8 with the paper's
/// constant offset removed so the top node sits at the pole:
/// along = W1·(−cos(γ + α_k)) = W1·sin α_k (the edge bows downwind, most at its middle), and
/// across = −W2·γ·α_k (the edge leans sideways). The row itself is placed by the caller.
pub fn pole_edge(k: usize, rows: usize, bow: f32, lean: f32) -> Vec2 {
    let (gamma, alpha) = edge_angle(k, rows);
    Vec2::new(-bow * (gamma + alpha).cos(), -lean * gamma * alpha)
}

/// Eq. 7: working outward from the leading yarn, every node further than `max_distance` from
/// the (already corrected) node of its neighbouring yarn nearer the leading one is pulled
/// along the line between them to exactly that distance. Closer nodes are left alone (folds are
/// allowed). The pole-edge column (j = 0) is fixed and not moved.
pub fn align_to_leading_yarn(
    positions: &mut [Vec3],
    rows: usize,
    columns: usize,
    leading: usize,
    max_distance: f32,
) {
    let max_squared = max_distance * max_distance;
    let pull = |positions: &mut [Vec3], k: usize, toward: usize| {
        for j in 1..columns {
            let anchor = positions[toward * columns + j];
            let node = &mut positions[k * columns + j];
            let r = *node - anchor;
            let squared = r.length_squared();
            if squared > max_squared && squared.is_finite() {
                *node = anchor + r * (max_distance / squared.sqrt());
            }
        }
    };
    for k in (0..leading).rev() {
        pull(positions, k, k + 1);
    }
    for k in leading + 1..rows {
        pull(positions, k, k - 1);
    }
}
