//! The precomputed trajectory database of §2.2: swing segments of the harmonic fluttering
//! function (eq. 5), each paired with a plate-angle profile from the ODE of eq. 4, clustered by
//! feature vector with k-means.
//!
//! Units are the fall's own: length U/Ω and time 1/Ω (U from eq. 3, Ω the swing rate). Eq. 5
//! becomes x = −α sin τ, y = −τ − (γ/2) cos 2τ with α = A_x/U and γ = A_y/U; a segment runs
//! between the turning points τ = π/2 and 3π/2.
//!
//! **Feature vectors.** The paper's V = P¹ − P⁰ is (2α, −π) for every segment of eq. 5 in these
//! units: the drop per swing is the same for all, and γ, which shapes the descent within a swing,
//! cancels at the turning points. Clustering on it alone would sort the segments by α and nothing
//! else. Each segment's feature vector therefore carries what really tells swings apart, in four
//! components: the paper's glide P¹ − P⁰ (2α, −π), the depth γ of the vertical modulation (how
//! much the object slows at the turning points and hurries in the middle), and the half-range Θ
//! of the plate angle from eq. 4. k-means runs on them standardised: the glide on a log scale
//! (swings of 0.2 and 0.3 differ as much as swings of 2 and 3), each component divided by its
//! spread over the database (a constant component drops out), the glide counted twice, since it
//! is what keeps a zigzag round its centre.
//!
//! **Search.** The key is the feature vector the next swing should have (§2.3.1); the search
//! goes to the nearest cluster and takes one of its [`CANDIDATES`] members nearest to the key at
//! random, so the glide is close to the one asked for and the modulation and angle vary from
//! swing to swing.

use bevy::math::Vec2;

use super::ode::{Integrator, OdeState, TanabeKaneko, trajectory};
use super::random::FallRng;

/// Samples per segment (positions and angles, both ends included).
pub const SEGMENT_SAMPLES: usize = 33;

/// Components of a feature vector: glide Δx, drop Δy, modulation γ, angle half-range Θ.
pub const FEATURES: usize = 4;

/// A feature vector (see the module docs).
pub type Feature = [f32; FEATURES];

/// One swing from turning point to turning point, gliding right (+x), in the fall's units.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// α = A_x / U of eq. 5.
    pub alpha: f32,
    /// γ = A_y / U of eq. 5.
    pub gamma: f32,
    /// Positions relative to the start, at equal times over the segment's duration π.
    pub points: [Vec2; SEGMENT_SAMPLES],
    /// Θ: half the plate's angle range over the swing, rad (from the eq. 4 profile).
    pub angle_range: f32,
    /// The plate angle's progress over the swing from eq. 4, 0 at the start and 1 at the end
    /// (monotone): a swing turns the plate from its start angle to its end angle along it.
    pub angle_shape: [f32; SEGMENT_SAMPLES],
}

impl Segment {
    /// P¹ − P⁰, the paper's feature vector.
    pub fn glide(&self) -> Vec2 {
        self.points[SEGMENT_SAMPLES - 1] - self.points[0]
    }

    /// The full feature vector: (P¹ − P⁰, γ, Θ).
    pub fn feature(&self) -> Feature {
        let g = self.glide();
        [g.x, g.y, self.gamma, self.angle_range]
    }
}

/// How the database is built.
#[derive(Clone, Debug, PartialEq)]
pub struct DatabaseConfig {
    /// Values of α = A_x / U.
    pub alphas: Vec<f32>,
    /// Values of γ = A_y / U.
    pub gammas: Vec<f32>,
    /// Number of k-means clusters.
    pub clusters: usize,
    /// Lift values K of eq. 4 (with [`TanabeKaneko::FLUTTER`]'s other parameters) whose
    /// half-swings give the plate-angle profiles; larger K, wider swings. Every (α, γ) is paired
    /// with every profile.
    pub flutter_lifts: Vec<f64>,
    /// Seed of the k-means initialisation.
    pub seed: u64,
}

impl Default for DatabaseConfig {
    fn default() -> Self {
        Self {
            alphas: (0..12).map(|i| 0.1 * 1.5f32.powi(i)).collect(),
            gammas: vec![0.0, 0.4, 0.8, 1.2],
            clusters: 12,
            flutter_lifts: vec![0.15, 0.3, 0.45, 0.6],
            seed: 7,
        }
    }
}

/// Members of the nearest cluster the search picks from at random.
pub const CANDIDATES: usize = 4;

/// Largest α and γ accepted in a [`DatabaseConfig`]: glides of 200 swing lengths per drop are
/// far beyond any fall; larger values are dropped.
pub const MAX_DATABASE_PARAMETER: f32 = 100.0;

/// Segments, their k-means clusters, and the lookup the search tree uses.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryDatabase {
    segments: Vec<Segment>,
    /// The tumbling half-turn of eq. 4: progress 0 → 1 over the half-turn.
    tumble_shape: [f32; SEGMENT_SAMPLES],
    /// 1 / spread of each feature component (0 for a constant one).
    weights: Feature,
    widest: f32,
    centroids: Vec<Feature>,
    members: Vec<Vec<u32>>,
    /// Each segment's standardised search-space feature, kept for the search: a search reads
    /// 16 bytes per member instead of its segment.
    scaled: Vec<Feature>,
}

impl Default for TrajectoryDatabase {
    /// [`TrajectoryDatabase::build`] with the default configuration.
    fn default() -> Self {
        Self::build(&DatabaseConfig::default())
    }
}

impl TrajectoryDatabase {
    /// Builds the database: one segment per (α, γ, profile), angles from RK4 solutions of eq. 4,
    /// k-means over the standardised feature vectors. Empty, negative, non-finite or oversized
    /// parameter lists fall back to the defaults.
    pub fn build(config: &DatabaseConfig) -> Self {
        let defaults = DatabaseConfig::default();
        let pick = |v: &Vec<f32>, d: &Vec<f32>| {
            let v: Vec<f32> = v
                .iter()
                .copied()
                .filter(|x| x.is_finite() && (0.0..=MAX_DATABASE_PARAMETER).contains(x))
                .take(64)
                .collect();
            if v.is_empty() { d.clone() } else { v }
        };
        let alphas = pick(&config.alphas, &defaults.alphas);
        let gammas = pick(&config.gammas, &defaults.gammas);
        let lifts: Vec<f64> = config
            .flutter_lifts
            .iter()
            .copied()
            .filter(|k| k.is_finite() && (0.0..=10.0).contains(k))
            .take(16)
            .collect();
        let lifts = if lifts.is_empty() {
            defaults.flutter_lifts.clone()
        } else {
            lifts
        };
        let mut profiles: Vec<[f32; SEGMENT_SAMPLES]> = lifts
            .iter()
            .filter_map(|&lift| {
                flutter_profile(&TanabeKaneko {
                    lift,
                    ..TanabeKaneko::FLUTTER
                })
            })
            .collect();
        if profiles.is_empty() {
            // A gentle rocking of ±0.3 rad if no lift flutters.
            profiles.push(std::array::from_fn(|i| {
                let s = i as f32 / (SEGMENT_SAMPLES - 1) as f32;
                -0.3 * (std::f32::consts::PI * s).cos()
            }));
        }
        let mut segments = Vec::with_capacity(alphas.len() * gammas.len() * profiles.len());
        for &alpha in &alphas {
            for &gamma in &gammas {
                for profile in &profiles {
                    segments.push(harmonic_segment(alpha, gamma, profile));
                }
            }
        }
        let features: Vec<Feature> = segments
            .iter()
            .map(|s| search_space(&s.feature()))
            .collect();
        let weights = standardising_weights(&features);
        let scaled: Vec<Feature> = features.iter().map(|f| scale(f, &weights)).collect();
        let (centroids, labels) = kmeans(&scaled, config.clusters.clamp(1, 64), config.seed);
        let mut members = vec![Vec::new(); centroids.len()];
        for (i, label) in labels.iter().enumerate() {
            members[*label].push(i as u32);
        }
        // Drop empty clusters so every lookup finds a segment.
        let keep: Vec<bool> = members.iter().map(|m| !m.is_empty()).collect();
        let centroids = centroids
            .into_iter()
            .zip(&keep)
            .filter_map(|(c, k)| k.then_some(c))
            .collect();
        members.retain(|m| !m.is_empty());
        Self {
            widest: segments.iter().map(|s| s.angle_range).fold(0.0, f32::max),
            segments,
            tumble_shape: tumble_profile(&TanabeKaneko::TUMBLE),
            weights,
            centroids,
            members,
            scaled,
        }
    }

    /// All segments.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Segment `index` (clamped to the last one).
    pub fn segment(&self, index: u32) -> &Segment {
        &self.segments[(index as usize).min(self.segments.len() - 1)]
    }

    /// The largest angle half-range Θ of any segment, rad.
    pub fn widest_angle_range(&self) -> f32 {
        self.widest
    }

    /// The tumbling half-turn's progress over a swing (0 → 1, from eq. 4).
    pub fn tumble_shape(&self) -> &[f32; SEGMENT_SAMPLES] {
        &self.tumble_shape
    }

    /// Cluster centres, in standardised feature units.
    pub fn centroids(&self) -> &[Feature] {
        &self.centroids
    }

    /// Segment indices of each cluster.
    pub fn members(&self) -> &[Vec<u32>] {
        &self.members
    }

    /// The cluster whose centre is nearest to `key` (the search key of §2.3.1, a feature vector
    /// in the fall's units; non-finite components count as 0).
    pub fn nearest_cluster(&self, key: &Feature) -> usize {
        self.nearest_to_scaled(&self.scaled_key(key))
    }

    /// [`Self::nearest_cluster`] of a key already scaled.
    fn nearest_to_scaled(&self, key: &Feature) -> usize {
        let mut best = (0, f32::INFINITY);
        for (i, c) in self.centroids.iter().enumerate() {
            let d = distance_squared(c, key);
            if d < best.1 {
                best = (i, d);
            }
        }
        best.0
    }

    /// The search tree's child for `key`: one of the [`CANDIDATES`] members of the nearest
    /// cluster that are nearest to the key, at random.
    pub fn find(&self, key: &Feature, rng: &mut FallRng) -> u32 {
        let scaled = self.scaled_key(key);
        let members = &self.members[self.nearest_to_scaled(&scaled)];
        let mut best = [(u32::MAX, f32::INFINITY); CANDIDATES];
        for &m in members {
            let d = distance_squared(&self.scaled[m as usize], &scaled);
            if let Some(slot) = best.iter().position(|b| d < b.1) {
                best.copy_within(slot..CANDIDATES - 1, slot + 1);
                best[slot] = (m, d);
            }
        }
        let found = best.iter().filter(|b| b.0 != u32::MAX).count().max(1);
        let pick = ((rng.uniform() * found as f32) as usize).min(found - 1);
        if best[pick].0 == u32::MAX {
            members[0]
        } else {
            best[pick].0
        }
    }

    fn scaled_key(&self, key: &Feature) -> Feature {
        let key = key.map(|x| if x.is_finite() { x } else { 0.0 });
        scale(&search_space(&key), &self.weights)
    }

    /// A random member of cluster `cluster` (clamped to the last cluster): one child of the
    /// search tree.
    pub fn pick(&self, cluster: usize, rng: &mut FallRng) -> u32 {
        let members = &self.members[cluster.min(self.members.len() - 1)];
        let pick = ((rng.uniform() * members.len() as f32) as usize).min(members.len() - 1);
        members[pick]
    }

    /// Approximate heap size, bytes.
    pub fn size_bytes(&self) -> usize {
        self.segments.len() * std::mem::size_of::<Segment>()
            + (self.centroids.len() + self.scaled.len()) * std::mem::size_of::<Feature>()
            + self.members.iter().map(|m| m.len() * 4).sum::<usize>()
    }
}

/// Eq. 5 in the fall's units between the turning points π/2 and 3π/2, with an angle profile.
fn harmonic_segment(alpha: f32, gamma: f32, flutter: &[f32; SEGMENT_SAMPLES]) -> Segment {
    let at = |tau: f32| Vec2::new(-alpha * tau.sin(), -tau - 0.5 * gamma * (2.0 * tau).cos());
    let start = at(std::f32::consts::FRAC_PI_2);
    let points = std::array::from_fn(|i| {
        let s = i as f32 / (SEGMENT_SAMPLES - 1) as f32;
        at(std::f32::consts::FRAC_PI_2 + std::f32::consts::PI * s) - start
    });
    let (first, last) = (flutter[0], flutter[SEGMENT_SAMPLES - 1]);
    Segment {
        alpha,
        gamma,
        points,
        angle_range: 0.5 * (last - first).abs(),
        angle_shape: progress(flutter),
    }
}

/// A profile's progress from its first to its last value, 0 → 1, made monotone (a running
/// maximum) so a swing never turns back within itself.
fn progress(profile: &[f32; SEGMENT_SAMPLES]) -> [f32; SEGMENT_SAMPLES] {
    let (first, last) = (profile[0], profile[SEGMENT_SAMPLES - 1]);
    let span = last - first;
    let mut running = 0.0f32;
    std::array::from_fn(|i| {
        let s = if span.abs() > 1e-9 {
            ((profile[i] - first) / span).clamp(0.0, 1.0)
        } else {
            i as f32 / (SEGMENT_SAMPLES - 1) as f32
        };
        running = running.max(s);
        if i == SEGMENT_SAMPLES - 1 {
            1.0
        } else {
            running
        }
    })
}

/// The last complete half-swing (between sign changes of u) of a fluttering run of eq. 4,
/// resampled to [`SEGMENT_SAMPLES`] equal times, signed so the swing goes right. `None` if the
/// run does not flutter.
fn flutter_profile(params: &TanabeKaneko) -> Option<[f32; SEGMENT_SAMPLES]> {
    let start = OdeState {
        theta: 0.3,
        v: -0.01,
        ..OdeState::default()
    };
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4)
        .expect("12 s in 1 ms steps is within the budget");
    let turns: Vec<usize> = (1..run.len())
        .filter(|&i| (run[i - 1].u < 0.0) != (run[i].u < 0.0))
        .collect();
    let (&a, &b) = (
        turns.get(turns.len().checked_sub(3)?)?,
        turns.get(turns.len() - 2)?,
    );
    let swing = &run[a..=b];
    if swing.iter().any(|s| !s.is_finite()) || swing.len() < 4 {
        return None;
    }
    let sign = if swing[swing.len() / 2].u >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let profile = resample(swing, |s| (sign * s.theta) as f32);
    // A swing to the right turns the plate counter-clockwise (as a right tumble does).
    if profile[SEGMENT_SAMPLES - 1] - profile[0] > 0.05 {
        Some(profile)
    } else if profile[0] - profile[SEGMENT_SAMPLES - 1] > 0.05 {
        Some(profile.map(|a| -a))
    } else {
        None
    }
}

/// One half-turn of a tumbling run of eq. 4 (θ advancing by π), as progress 0 → 1, resampled to
/// equal times. Falls back to a uniform turn if the run does not tumble.
fn tumble_profile(params: &TanabeKaneko) -> [f32; SEGMENT_SAMPLES] {
    let uniform = std::array::from_fn(|i| i as f32 / (SEGMENT_SAMPLES - 1) as f32);
    let start = OdeState {
        theta: 0.3,
        v: -0.01,
        ..OdeState::default()
    };
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4)
        .expect("12 s in 1 ms steps is within the budget");
    let Some(last) = run.last() else {
        return uniform;
    };
    let direction = last.theta.signum();
    let half_turn = |s: &OdeState| (direction * s.theta / std::f64::consts::PI).floor();
    let marks: Vec<usize> = (1..run.len())
        .filter(|&i| half_turn(&run[i]) != half_turn(&run[i - 1]))
        .collect();
    if marks.len() < 4 || !last.is_finite() {
        return uniform;
    }
    let swing = &run[marks[marks.len() - 3]..=marks[marks.len() - 2]];
    let theta0 = swing[0].theta;
    progress(&resample(swing, |s| {
        (direction * (s.theta - theta0)) as f32
    }))
}

fn resample(run: &[OdeState], value: impl Fn(&OdeState) -> f32) -> [f32; SEGMENT_SAMPLES] {
    std::array::from_fn(|i| {
        let x = i as f32 / (SEGMENT_SAMPLES - 1) as f32 * (run.len() - 1) as f32;
        let j = (x as usize).min(run.len() - 2);
        let f = x - j as f32;
        value(&run[j]) * (1.0 - f) + value(&run[j + 1]) * f
    })
}

/// The feature vector as the search compares it: the glide on a log scale.
fn search_space(f: &Feature) -> Feature {
    [f[0].abs().max(1e-3).ln(), f[1], f[2], f[3]]
}

/// 1 / standard deviation of each component over `features` (0 where it is constant), the
/// glide's doubled.
fn standardising_weights(features: &[Feature]) -> Feature {
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

fn scale(f: &Feature, weights: &Feature) -> Feature {
    std::array::from_fn(|c| f[c] * weights[c])
}

fn distance_squared<const N: usize>(a: &[f32; N], b: &[f32; N]) -> f32 {
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
