//! The precomputed trajectory database of §2.2: swing segments of the harmonic fluttering
//! function (eq. 5), clustered by feature vector with k-means, each with an orientation profile
//! from the ODE of eq. 4.
//!
//! Units are the fall's own: length U/Ω and time 1/Ω (U from eq. 3, Ω the swing rate). Eq. 5
//! becomes x = −α sin τ, y = −τ − (γ/2) cos 2τ with α = A_x/U and γ = A_y/U; a segment runs
//! between the turning points τ = π/2 and 3π/2, so its feature vector is V = (2α, −π): in these
//! units k-means groups the segments by how far they glide sideways per drop.

use bevy::math::Vec2;

use super::ode::{Integrator, OdeState, TanabeKaneko, trajectory};
use super::random::FallRng;

/// Samples per segment (positions and angles, both ends included).
pub const SEGMENT_SAMPLES: usize = 33;

/// One swing from turning point to turning point, gliding right (+x).
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// α = A_x / U of eq. 5.
    pub alpha: f32,
    /// γ = A_y / U of eq. 5.
    pub gamma: f32,
    /// Positions relative to the start, at equal times.
    pub points: [Vec2; SEGMENT_SAMPLES],
    /// Fluttering plate angle (rad, counter-clockwise from horizontal) at the same times, from
    /// a half-swing of eq. 4.
    pub flutter: [f32; SEGMENT_SAMPLES],
    /// Tumbling: angle turned since the start of the swing, 0 → π, from eq. 4.
    pub tumble: [f32; SEGMENT_SAMPLES],
    /// (cos θ/2, sin θ/2) of `flutter`: the rotation as a unit complex number, so a pose is a
    /// normalised lerp, not a sine and cosine per frame.
    pub flutter_half: [Vec2; SEGMENT_SAMPLES],
    /// (cos θ/2, sin θ/2) of `tumble`.
    pub tumble_half: [Vec2; SEGMENT_SAMPLES],
}

impl Segment {
    /// P¹ − P⁰.
    pub fn feature(&self) -> Vec2 {
        self.points[SEGMENT_SAMPLES - 1] - self.points[0]
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
    /// half-swings give the fluttering angles; larger K, wider swings.
    pub flutter_lifts: Vec<f64>,
    /// Seed of the k-means initialisation.
    pub seed: u64,
}

impl Default for DatabaseConfig {
    fn default() -> Self {
        Self {
            alphas: (0..12).map(|i| 0.15 * 1.35f32.powi(i)).collect(),
            gammas: vec![0.0, 0.3, 0.6, 0.9, 1.2],
            clusters: 6,
            flutter_lifts: vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
            seed: 7,
        }
    }
}

/// Segments, their k-means clusters, and the lookup the search tree uses.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryDatabase {
    segments: Vec<Segment>,
    centroids: Vec<Vec2>,
    members: Vec<Vec<u32>>,
}

impl Default for TrajectoryDatabase {
    /// [`TrajectoryDatabase::build`] with the default configuration.
    fn default() -> Self {
        Self::build(&DatabaseConfig::default())
    }
}

impl TrajectoryDatabase {
    /// Builds the database: one segment per (α, γ), angles from RK4 solutions of eq. 4,
    /// k-means over the feature vectors. Empty parameter lists fall back to the defaults.
    pub fn build(config: &DatabaseConfig) -> Self {
        let defaults = DatabaseConfig::default();
        let pick = |v: &Vec<f32>, d: &Vec<f32>| {
            let v: Vec<f32> = v
                .iter()
                .copied()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .collect();
            if v.is_empty() { d.clone() } else { v }
        };
        let alphas = pick(&config.alphas, &defaults.alphas);
        let gammas = pick(&config.gammas, &defaults.gammas);
        let lifts = if config.flutter_lifts.is_empty() {
            defaults.flutter_lifts.clone()
        } else {
            config.flutter_lifts.clone()
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
            profiles.push([0.0; SEGMENT_SAMPLES]);
        }
        profiles.sort_by(|a, b| a[0].abs().total_cmp(&b[0].abs()));
        let tumble = tumble_profile(&TanabeKaneko::TUMBLE);
        let (alpha_min, alpha_max) = alphas.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &a| {
            (lo.min(a), hi.max(a))
        });
        let mut segments = Vec::with_capacity(alphas.len() * gammas.len());
        for &alpha in &alphas {
            // Wider glides get the wider ODE swings.
            let rank = if alpha_max > alpha_min {
                (alpha.ln() - alpha_min.max(1e-6).ln())
                    / (alpha_max.ln() - alpha_min.max(1e-6).ln())
            } else {
                0.5
            };
            let profile = profiles
                [((rank * (profiles.len() - 1) as f32).round() as usize).min(profiles.len() - 1)];
            for &gamma in &gammas {
                segments.push(harmonic_segment(alpha, gamma, profile, tumble));
            }
        }
        let features: Vec<Vec2> = segments.iter().map(Segment::feature).collect();
        let (centroids, labels) = kmeans(&features, config.clusters.max(1), config.seed);
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
            segments,
            centroids,
            members,
        }
    }

    /// All segments.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Segment `index`.
    pub fn segment(&self, index: u32) -> &Segment {
        &self.segments[index as usize]
    }

    /// Cluster centres (feature vectors).
    pub fn centroids(&self) -> &[Vec2] {
        &self.centroids
    }

    /// Segment indices of each cluster.
    pub fn members(&self) -> &[Vec<u32>] {
        &self.members
    }

    /// The cluster whose centre is nearest to `feature` (the search key of §2.3.1), with the
    /// key's vertical component normalised to the database's −π so the glide ratio decides.
    pub fn nearest_cluster(&self, feature: Vec2) -> usize {
        let key = if feature.y.abs() > 0.0 && feature.is_finite() {
            feature * (std::f32::consts::PI / feature.y.abs())
        } else {
            Vec2::new(0.0, -std::f32::consts::PI)
        };
        let mut best = (0, f32::INFINITY);
        for (i, c) in self.centroids.iter().enumerate() {
            let d = c.distance_squared(key);
            if d < best.1 {
                best = (i, d);
            }
        }
        best.0
    }

    /// A segment of the cluster nearest to `feature`, picked at random.
    pub fn find(&self, feature: Vec2, rng: &mut FallRng) -> u32 {
        self.pick(self.nearest_cluster(feature), rng)
    }

    /// A random member of cluster `cluster` (clamped to the last cluster).
    pub fn pick(&self, cluster: usize, rng: &mut FallRng) -> u32 {
        let members = &self.members[cluster.min(self.members.len() - 1)];
        let pick = ((rng.uniform() * members.len() as f32) as usize).min(members.len() - 1);
        members[pick]
    }

    /// Approximate heap size, bytes.
    pub fn size_bytes(&self) -> usize {
        self.segments.len() * std::mem::size_of::<Segment>()
            + self.centroids.len() * std::mem::size_of::<Vec2>()
            + self.members.iter().map(|m| m.len() * 4).sum::<usize>()
    }
}

/// Eq. 5 in the fall's units between the turning points π/2 and 3π/2.
fn harmonic_segment(
    alpha: f32,
    gamma: f32,
    flutter: [f32; SEGMENT_SAMPLES],
    tumble: [f32; SEGMENT_SAMPLES],
) -> Segment {
    let at = |tau: f32| Vec2::new(-alpha * tau.sin(), -tau - 0.5 * gamma * (2.0 * tau).cos());
    let start = at(std::f32::consts::FRAC_PI_2);
    let points = std::array::from_fn(|i| {
        let s = i as f32 / (SEGMENT_SAMPLES - 1) as f32;
        at(std::f32::consts::FRAC_PI_2 + std::f32::consts::PI * s) - start
    });
    let half = |angles: &[f32; SEGMENT_SAMPLES]| {
        angles.map(|a| {
            let (s, c) = (0.5 * a).sin_cos();
            Vec2::new(c, s)
        })
    };
    Segment {
        alpha,
        gamma,
        points,
        flutter_half: half(&flutter),
        tumble_half: half(&tumble),
        flutter,
        tumble,
    }
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
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4);
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
    Some(resample(swing, |s| (sign * s.theta) as f32))
}

/// One half-turn of a tumbling run of eq. 4 (θ advancing by π), as the angle turned since its
/// start, resampled to equal times. Falls back to a uniform turn if the run does not tumble.
fn tumble_profile(params: &TanabeKaneko) -> [f32; SEGMENT_SAMPLES] {
    let uniform =
        std::array::from_fn(|i| std::f32::consts::PI * i as f32 / (SEGMENT_SAMPLES - 1) as f32);
    let start = OdeState {
        theta: 0.3,
        v: -0.01,
        ..OdeState::default()
    };
    let run = trajectory(params, start, 1e-3, 12.0, Integrator::Rk4);
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
    resample(swing, |s| (direction * (s.theta - theta0)) as f32)
}

fn resample(run: &[OdeState], value: impl Fn(&OdeState) -> f32) -> [f32; SEGMENT_SAMPLES] {
    std::array::from_fn(|i| {
        let x = i as f32 / (SEGMENT_SAMPLES - 1) as f32 * (run.len() - 1) as f32;
        let j = (x as usize).min(run.len() - 2);
        let f = x - j as f32;
        value(&run[j]) * (1.0 - f) + value(&run[j + 1]) * f
    })
}

/// Lloyd's k-means with k-means++ seeding from a seeded stream; returns centres and labels.
pub fn kmeans(points: &[Vec2], k: usize, seed: u64) -> (Vec<Vec2>, Vec<usize>) {
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
                    .map(|c| c.distance_squared(*p))
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
                    centres[a]
                        .distance_squared(*p)
                        .total_cmp(&centres[b].distance_squared(*p))
                })
                .unwrap_or(0);
            changed |= nearest != *label;
            *label = nearest;
        }
        for (c, centre) in centres.iter_mut().enumerate() {
            let (sum, n) = points
                .iter()
                .zip(&labels)
                .filter(|(_, l)| **l == c)
                .fold((Vec2::ZERO, 0), |(s, n), (p, _)| (s + *p, n + 1));
            if n > 0 {
                *centre = sum / n as f32;
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
    fn segments_end_at_turning_points_with_the_eq5_feature() {
        let db = TrajectoryDatabase::default();
        for s in db.segments() {
            let f = s.feature();
            assert!((f.x - 2.0 * s.alpha).abs() < 1e-5, "{f:?} α = {}", s.alpha);
            assert!((f.y + std::f32::consts::PI).abs() < 1e-5);
        }
    }

    #[test]
    fn ode_profiles_flutter_and_tumble() {
        let db = TrajectoryDatabase::default();
        let s = &db.segments()[0];
        // A half-swing goes from one extreme angle to the opposite one.
        assert!(
            s.flutter[0] * s.flutter[SEGMENT_SAMPLES - 1] < 0.0,
            "{:?}",
            s.flutter
        );
        assert!((s.tumble[SEGMENT_SAMPLES - 1] - std::f32::consts::PI).abs() < 0.05);
        assert!(s.tumble.windows(2).all(|w| w[1] >= w[0] - 1e-3));
    }

    #[test]
    fn kmeans_separates_two_blobs() {
        let mut points: Vec<Vec2> = (0..20).map(|i| Vec2::new(i as f32 * 0.01, 0.0)).collect();
        points.extend((0..20).map(|i| Vec2::new(10.0 + i as f32 * 0.01, 0.0)));
        let (centres, labels) = kmeans(&points, 2, 1);
        assert!(labels[..20].iter().all(|l| *l == labels[0]));
        assert!(
            labels[20..]
                .iter()
                .all(|l| *l == labels[20] && *l != labels[0])
        );
        let mut xs: Vec<f32> = centres.iter().map(|c| c.x).collect();
        xs.sort_by(f32::total_cmp);
        assert!((xs[0] - 0.095).abs() < 1e-4 && (xs[1] - 10.095).abs() < 1e-4);
    }
}
