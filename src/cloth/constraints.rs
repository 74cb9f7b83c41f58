//! Shape constraints of the cloth paper §5.1: the pole edge (eq. 8) and the distance between
//! neighbouring yarns (eq. 7).

use bevy::math::{Vec2, Vec3};

use super::sim::edge_angle;

/// Start of yarn `k` in its yarn plane (along the yarn, across it): eq. 8's pole edge.
///
/// Eq. 8 bows the edge by W1 cos(γ + α_k) = −W1 sin α_k (γ = π/2, α_k = kπ/(n−1)), an arc that
/// is 0 at both ends and W1 in the middle; we turn its sign so the edge bows downwind. Its lean
/// −W2 γ (1 + α_k) is linear in k and would move the lower end off the pole, which §7 says is
/// fixed ("a flag fixed at two ends with its left edge stretching ... simple arc-like
/// stretching"); we read it as the same arc across the stream, W2 sin α_k. So both ends stay on
/// the pole and the edge between them bulges downwind by `bow` and sideways by `lean` (m).
pub fn pole_edge(k: usize, rows: usize, bow: f32, lean: f32) -> Vec2 {
    let (gamma, alpha) = edge_angle(k, rows);
    let arc = -(gamma + alpha).cos();
    let arc = if k == 0 || k + 1 == rows { 0.0 } else { arc };
    Vec2::new(bow * arc, lean * arc)
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
