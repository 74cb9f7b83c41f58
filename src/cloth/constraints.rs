//! Shape constraints of the cloth paper §5.1: the pole edge (eq. 8) and the distance between
//! neighbouring yarns (eq. 7).

use std::f32::consts::{FRAC_PI_2, PI};

use bevy::math::{Vec2, Vec3};

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
pub(crate) fn align_to_leading_yarn(
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

/// The angles of the pole edge's nodes in eq. 8: γ = π/2 and α_k = kπ/(n−1), so that the first
/// and last nodes (the two fixed ends) stay on the pole.
fn edge_angle(k: usize, rows: usize) -> (f32, f32) {
    let alpha = if rows > 1 {
        k as f32 * PI / (rows - 1) as f32
    } else {
        0.0
    };
    (FRAC_PI_2, alpha)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constraint_allows_folds_and_leaves_the_leading_yarn_alone() {
        // A yarn closer than L to its neighbour is not pushed apart.
        let mut p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(1.0, -0.2, 0.0), // 0.2 from the leading yarn: a fold
            Vec3::new(0.0, -2.0, 0.0),
            Vec3::new(1.0, -3.0, 0.0), // 2.8 from its neighbour: pulled to 1
        ];
        let before = p.clone();
        align_to_leading_yarn(&mut p, 3, 2, 0, 1.0);
        assert_eq!(&p[..4], &before[..4]);
        assert!((p[5].distance(p[3]) - 1.0).abs() < 1e-6);
        assert_eq!(p[4], before[4], "the pole column is fixed");
    }
}
