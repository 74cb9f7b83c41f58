//! The search space of the trajectory database: features standardised per axis and clustered
//! by k-means (Lloyd's algorithm, hand-written: see docs/handwritten.md).

use super::super::random::FallRng;
use super::Feature;

/// The feature vector as the search compares it: the glide on a log scale.
pub(super) fn search_space(f: &Feature) -> Feature {
    [
        crate::portable::transcendental::ln(f[0].abs().max(1e-3)),
        f[1],
        f[2],
        f[3],
    ]
}

/// 1 / standard deviation of each component over `features` (0 where it is constant), the
/// glide's doubled.
pub(super) fn standardising_weights(features: &[Feature]) -> Feature {
    let n = features.len().max(1) as f32;
    std::array::from_fn(|c| {
        let mean = features.iter().map(|f| f[c]).sum::<f32>() / n;
        let var = features.iter().map(|f| (f[c] - mean).powi(2)).sum::<f32>() / n;
        let emphasis = if c == 0 { 2.0 } else { 1.0 };
        if var > 1e-12 {
            emphasis / var.sqrt()
        } else {
            0.0
        }
    })
}

pub(super) fn scale(f: &Feature, weights: &Feature) -> Feature {
    std::array::from_fn(|c| f[c] * weights[c])
}

pub(super) fn distance_squared<const N: usize>(a: &[f32; N], b: &[f32; N]) -> f32 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Lloyd's k-means with k-means++ seeding from a seeded stream; returns centres and labels.
pub(crate) fn kmeans<const N: usize>(
    points: &[[f32; N]],
    k: usize,
    seed: u64,
) -> (Vec<[f32; N]>, Vec<usize>) {
    if points.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let k = k.min(points.len());
    let mut rng = FallRng::new(seed);
    let mut centres = vec![points[(rng.uniform() * points.len() as f32) as usize % points.len()]];
    while centres.len() < k {
        let d2: Vec<f32> = points
            .iter()
            .map(|p| {
                centres
                    .iter()
                    .map(|c| distance_squared(c, p))
                    .fold(f32::INFINITY, f32::min)
            })
            .collect();
        let total: f32 = d2.iter().sum();
        let mut target = rng.uniform() * total;
        let mut chosen = points.len() - 1;
        for (i, d) in d2.iter().enumerate() {
            if target < *d {
                chosen = i;
                break;
            }
            target -= d;
        }
        centres.push(points[chosen]);
    }
    let mut labels = vec![0; points.len()];
    for _ in 0..100 {
        let mut changed = false;
        for (label, p) in labels.iter_mut().zip(points) {
            let nearest = (0..k)
                .min_by(|&a, &b| {
                    distance_squared(&centres[a], p).total_cmp(&distance_squared(&centres[b], p))
                })
                .unwrap_or(0);
            changed |= nearest != *label;
            *label = nearest;
        }
        for (c, centre) in centres.iter_mut().enumerate() {
            let (sum, n) = points.iter().zip(&labels).filter(|(_, l)| **l == c).fold(
                ([0.0f32; N], 0),
                |(mut s, n), (p, _)| {
                    s.iter_mut().zip(p).for_each(|(a, b)| *a += b);
                    (s, n + 1)
                },
            );
            if n > 0 {
                *centre = sum.map(|s| s / n as f32);
            }
        }
        if !changed {
            break;
        }
    }
    (centres, labels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kmeans_separates_two_blobs() {
        let mut points: Vec<[f32; 2]> = (0..20).map(|i| [i as f32 * 0.01, 0.0]).collect();
        points.extend((0..20).map(|i| [10.0 + i as f32 * 0.01, 0.0]));
        let (centres, labels) = kmeans(&points, 2, 1);
        assert!(labels[..20].iter().all(|l| *l == labels[0]));
        assert!(
            labels[20..]
                .iter()
                .all(|l| *l == labels[20] && *l != labels[0])
        );
        let mut xs: Vec<f32> = centres.iter().map(|c| c[0]).collect();
        xs.sort_by(f32::total_cmp);
        assert!((xs[0] - 0.095).abs() < 1e-4 && (xs[1] - 10.095).abs() < 1e-4);
    }
}
