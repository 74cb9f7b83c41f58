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

use super::ode::TanabeKaneko;
use super::random::FallRng;

mod kmeans;
mod profiles;
pub(crate) use kmeans::kmeans;
use kmeans::{distance_squared, scale, search_space, standardising_weights};
use profiles::{flutter_profile, harmonic_segment, tumble_profile};

/// Samples per segment (positions and angles, both ends included).
pub(crate) const SEGMENT_SAMPLES: usize = 33;

/// Components of a feature vector: glide Δx, drop Δy, modulation γ, angle half-range Θ.
pub(crate) const FEATURES: usize = 4;

/// A feature vector (see the module docs).
pub(crate) type Feature = [f32; FEATURES];

/// One swing from turning point to turning point, gliding right (+x), in the fall's units.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Segment {
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
pub(crate) const CANDIDATES: usize = 4;

/// The candidates of a fall's last search and the key (its bits) they were found for.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SearchMemo {
    key: [u32; 4],
    candidates: [u32; CANDIDATES],
    /// How many candidates (0: none remembered).
    found: u8,
}

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
    /// Every segment's samples as rows (x, y, its angle progress, the tumble's progress),
    /// segment `s` at `s × SEGMENT_SAMPLES`: what a swing samples each step, one row load a lane.
    rows: Vec<[f32; 4]>,
    /// Each segment's ease bounds ([`EaseBounds::of`]), and the tumble's.
    ease: Vec<EaseBounds>,
    tumble_ease: EaseBounds,
}

/// The range of a swing's `ease` (the term `ease · s (1 − s)²` added to an angle profile so
/// that a swing starts at the rate the last piece ended with) that keeps the profile within
/// [−¼, 1¼] at every sample, and the profile's own start slope (per unit of s): computed once
/// per profile, not per swing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EaseBounds {
    low: f32,
    high: f32,
    slope: f32,
}

impl EaseBounds {
    /// The bounds of `shape` (progress 0 → 1 over s ∈ [0, 1]).
    fn of(shape: &[f32; SEGMENT_SAMPLES]) -> Self {
        const OVERSHOOT: f32 = 0.25;
        let last = (SEGMENT_SAMPLES - 1) as f32;
        let (mut low, mut high) = (f32::NEG_INFINITY, f32::INFINITY);
        for (i, p) in shape.iter().enumerate().take(SEGMENT_SAMPLES - 1).skip(1) {
            let s = i as f32 / last;
            let bump = s * (1.0 - s) * (1.0 - s);
            low = low.max((-OVERSHOOT - p) / bump);
            high = high.min((1.0 + OVERSHOOT - p) / bump);
        }
        Self {
            low: low.min(0.0),
            high: high.max(0.0),
            slope: (shape[1] - shape[0]) * last,
        }
    }

    /// The `ease` that starts the profile at slope `wanted` (progress per unit of s), held
    /// within the bounds.
    pub(crate) fn toward(&self, wanted: f32) -> f32 {
        (wanted - self.slope).clamp(self.low, self.high)
    }
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
                .filter(|x| x.is_finite() && (0.0..=DatabaseConfig::MAX_PARAMETER).contains(x))
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
                -0.3 * libm::cosf(std::f32::consts::PI * s)
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
        let tumble_shape = tumble_profile(&TanabeKaneko::TUMBLE);
        let rows = segments
            .iter()
            .flat_map(|s| {
                (0..SEGMENT_SAMPLES).map(move |i| {
                    let p = s.points[i];
                    [p.x, p.y, s.angle_shape[i], tumble_shape[i]]
                })
            })
            .collect();
        Self {
            widest: segments.iter().map(|s| s.angle_range).fold(0.0, f32::max),
            ease: segments
                .iter()
                .map(|s| EaseBounds::of(&s.angle_shape))
                .collect(),
            tumble_ease: EaseBounds::of(&tumble_shape),
            rows,
            segments,
            tumble_shape,
            weights,
            centroids,
            members,
            scaled,
        }
    }

    /// The rows of segment `segment` (clamped to the last one): sample i is row `base + i`.
    pub(crate) fn row_base(&self, segment: u32) -> u32 {
        (segment.min(self.segments.len() as u32 - 1)) * SEGMENT_SAMPLES as u32
    }

    /// Row `index` (see [`Self::row_base`]): x, y, the segment's angle progress and the
    /// tumble's.
    #[inline]
    pub(crate) fn row(&self, index: usize) -> [f32; 4] {
        self.rows[index.min(self.rows.len() - 1)]
    }

    /// The ease bounds of segment `segment`'s angle profile, or the tumble's.
    pub(crate) fn ease_bounds(&self, segment: u32, tumble: bool) -> &EaseBounds {
        if tumble {
            &self.tumble_ease
        } else {
            &self.ease[(segment as usize).min(self.ease.len() - 1)]
        }
    }

    /// How many segments it holds (the eq. 5 swings of §2.3).
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }

    /// How many clusters its search tree has.
    pub fn cluster_count(&self) -> usize {
        self.centroids.len()
    }

    /// Segment `index` (clamped to the last one).
    pub(crate) fn segment(&self, index: u32) -> &Segment {
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

    #[cfg(test)]
    /// Segment indices of each cluster.
    pub(crate) fn members(&self) -> &[Vec<u32>] {
        &self.members
    }

    #[cfg(test)]
    /// The cluster whose centre is nearest to `key` (the search key of §2.3.1, a feature vector
    /// in the fall's units; non-finite components count as 0).
    pub(crate) fn nearest_cluster(&self, key: &Feature) -> usize {
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
    #[cfg(test)]
    pub(crate) fn find(&self, key: &Feature, rng: &mut FallRng) -> u32 {
        self.find_remembered(key, rng, &mut SearchMemo::default())
    }

    /// [`Self::find`], remembering the candidates of the last key in `memo`: a fall that asks
    /// again with the same key (a tumble's half-turns, each the same glide) only draws among
    /// them.
    pub(crate) fn find_remembered(
        &self,
        key: &Feature,
        rng: &mut FallRng,
        memo: &mut SearchMemo,
    ) -> u32 {
        let bits = key.map(f32::to_bits);
        if memo.found == 0 || memo.key != bits {
            *memo = self.candidates(key);
            memo.key = bits;
        }
        let found = usize::from(memo.found);
        let pick = ((rng.uniform() * found as f32) as usize).min(found - 1);
        memo.candidates[pick]
    }

    /// The [`CANDIDATES`] members of the nearest cluster nearest to `key`.
    fn candidates(&self, key: &Feature) -> SearchMemo {
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
        let found = best.iter().filter(|b| b.0 != u32::MAX).count();
        let mut memo = SearchMemo {
            candidates: best.map(|b| b.0),
            found: found.max(1) as u8,
            key: [0; 4],
        };
        if found == 0 {
            memo.candidates[0] = members[0];
        }
        memo
    }

    fn scaled_key(&self, key: &Feature) -> Feature {
        let key = key.map(|x| if x.is_finite() { x } else { 0.0 });
        scale(&search_space(&key), &self.weights)
    }

    /// Approximate heap size, bytes.
    pub fn size_bytes(&self) -> usize {
        self.segments.len() * std::mem::size_of::<Segment>()
            + self.rows.len() * std::mem::size_of::<[f32; 4]>()
            + self.ease.len() * std::mem::size_of::<EaseBounds>()
            + (self.centroids.len() + self.scaled.len()) * std::mem::size_of::<Feature>()
            + self.members.iter().map(|m| m.len() * 4).sum::<usize>()
    }
}

/// Limits and constants of [`DatabaseConfig`].
impl DatabaseConfig {
    /// Largest α and γ accepted in a [`DatabaseConfig`]: glides of 200 swing lengths per drop are
    /// far beyond any fall; larger values are dropped.
    pub const MAX_PARAMETER: f32 = 100.0;
}
