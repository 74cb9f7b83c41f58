//! Shape constraints of the cloth paper §5.1: the pole edge (eq. 8) and the distance between
//! neighbouring yarns (eq. 7).

use std::f32::consts::{FRAC_PI_2, PI};

use bevy::math::{Vec2, Vec3};

/// The pole edge of eq. 8 as a hem of fixed length: the start of every yarn, written to `out`
/// (x downwind, y up, z across; one node per yarn, `spacing` m apart along the hem).
///
/// Eq. 8 bows the edge by W1 cos(γ + α_k) = −W1 sin α_k (γ = π/2, α_k = kπ/(n−1)), an arc that
/// is 0 at both ends and W1 in the middle; we turn its sign so the edge bows downwind. Its lean
/// −W2 γ (1 + α_k) is linear in k and would move the lower end off the pole, which §7 says is
/// fixed ("a flag fixed at two ends with its left edge stretching ... simple arc-like
/// stretching"); we read it as the same arc across the stream, W2 sin α_k. So both ends stay on
/// the pole and the edge between them bulges downwind by `bow` and sideways by `lean` (m).
///
/// The paper keeps the nodes' heights, so a bowed edge is longer than the cloth and its
/// neighbouring nodes break eq. 7 (by 2.4 % at a flag's bow in a strong wind). Here the hem
/// keeps its length: each node sits `spacing` below-and-out from the one above, so bowing the
/// edge lifts its lower end up the pole by about (π W / 2)² / H metres, W the bulge (m) and H the
/// edge's length (0.8–1.2 % of H at a flag's bow), as a real hem does. A bow so deep that one step of the arc would take more than half a spacing is
/// scaled down to that (the hem would otherwise fold back on itself).
pub fn pole_hem(rows: usize, spacing: f32, bow: f32, lean: f32, out: &mut Vec<Vec3>) {
    out.clear();
    let arc = |k: usize| {
        let (gamma, alpha) = edge_angle(k, rows);
        if k == 0 || k + 1 == rows {
            0.0
        } else {
            -(gamma + alpha).cos()
        }
    };
    let bulge = Vec2::new(bow, lean);
    let bulge = if bulge.is_finite() { bulge } else { Vec2::ZERO };
    // The steepest step of the arc is at the ends: sin(π / (n − 1)).
    let steepest = (0..rows.saturating_sub(1))
        .map(|k| (arc(k + 1) - arc(k)).abs())
        .fold(0.0f32, f32::max)
        * bulge.length();
    let scale = if steepest > 0.5 * spacing {
        0.5 * spacing / steepest
    } else {
        1.0
    };
    let mut y = 0.0;
    let mut last = Vec2::ZERO;
    for k in 0..rows {
        let h = bulge * (scale * arc(k));
        if k > 0 {
            let step = (h - last).length_squared();
            y -= (spacing * spacing - step).max(0.0).sqrt();
        }
        out.push(Vec3::new(h.x, y, h.y));
        last = h;
    }
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

    #[test]
    fn the_hem_keeps_its_length_and_both_ends_on_the_pole() {
        let mut hem = Vec::new();
        for (rows, bow) in [(2, 0.3), (9, 0.0), (9, 0.2), (24, 0.06), (64, 5.0)] {
            pole_hem(rows, 0.1, bow, bow / 2.0, &mut hem);
            assert_eq!(hem.len(), rows);
            assert_eq!(hem[0], Vec3::ZERO);
            let last = hem[rows - 1];
            assert!(last.x == 0.0 && last.z == 0.0, "{rows} {bow}: {last}");
            for pair in hem.windows(2) {
                let gap = pair[0].distance(pair[1]);
                assert!((gap - 0.1).abs() < 1e-6, "{rows} {bow}: a gap of {gap}");
            }
        }
    }
}
