//! Spectral amplitudes of a sampled 1/f^β field (free-fall paper eq. 13, cloth paper eq. 1).

use super::grid::GridShape;

/// Spectral amplitude `A(f) = √S(f)` of eq. 13 (free-fall paper), `S(f) = |f|^−(β+n−1)`, with
/// `f` in cycles per node, for a continuous field sampled at the nodes: each bin also receives
/// the power of its nearest alias along every axis, `S_grid(f) = Σ_{m ∈ {0,1}ⁿ} S(|f| − m)`.
///
/// Without the aliases, a line through an n-D field misses the power of the transverse
/// frequencies beyond Nyquist and its spectrum steepens (slope −1.13 instead of −1 for β = 1 on a
/// 128³ grid); with them, the line spectra follow `f^−β` within 0.04 up to a quarter of Nyquist.
/// `S` depends only on `|f_i|`, so it is tabulated on one octant.
///
/// `S` is a power of the squared frequency, and on a grid that is an integer in disguise:
/// `f_a = k_a / len_a = k_a (L / len_a) / L` with `L` the least common multiple of the lengths,
/// so `|f|² L² = Σ (k_a L / len_a)²` is an integer key. Where the keys are few (a cubic grid of
/// side `N` has `3N² + 1` of them against `(N/2+1)³ · 8` images), each key's power is computed
/// once and looked up ([`PowerOfKey`]); either way a power is the same function of its key, so
/// the table is the same bits. Powers use the `libm` crate (pure Rust), so the table is
/// the same on every platform; they are taken relative to the lowest frequency's, which only
/// rescales the field before normalisation and never overflows.
pub(crate) struct AmplitudeTable {
    octant: GridShape,
    values: Vec<f32>,
}

/// Most entries a [`PowerOfKey`] memo may have (64 MiB). The rule "a few entries per
/// evaluation" alone lets a big grid's memo reach 16 entries per node: a 8192² grid has keys up
/// to 2 · 4096² (a 128 MiB memo), and grids near [`Synthesizer::MAX_NODES`](crate::spectrum::Synthesizer::MAX_NODES) up to 4 GiB.
const MAX_MEMO_ENTRIES: usize = 1 << 24;

/// `S` as a function of the integer key `|f|² L²`, relative to the lowest frequency's.
struct PowerOfKey {
    exponent: f32,
    log_key_min: f32,
    /// Memoised powers by key (NaN: not yet computed), when the keys are few enough.
    memo: Option<Vec<f32>>,
}

impl PowerOfKey {
    fn new(exponent: f32, key_min: u64, key_max: u64, evaluations: usize) -> Self {
        // A memo entry costs a 4-byte fill, a power an `exp` and a `log`: worth it up to a few
        // entries per evaluation.
        let memo = usize::try_from(key_max)
            .ok()
            .filter(|&k| evaluations > 0 && k / 4 <= evaluations && k < MAX_MEMO_ENTRIES)
            .map(|k| vec![f32::NAN; k + 1]);
        Self {
            exponent,
            log_key_min: libm::logf(key_min as f32),
            memo,
        }
    }

    fn direct(&self, key: u64) -> f32 {
        libm::expf(self.exponent * (libm::logf(key as f32) - self.log_key_min))
    }

    fn power(&mut self, key: u64) -> f32 {
        let cached = match &self.memo {
            Some(memo) => memo[key as usize],
            None => return self.direct(key),
        };
        if !cached.is_nan() {
            return cached;
        }
        let power = self.direct(key);
        if let Some(memo) = self.memo.as_mut() {
            memo[key as usize] = power;
        }
        power
    }
}

/// Least common multiple of the lengths, if it fits.
fn common_length(dims: &[usize]) -> Option<u64> {
    fn gcd(a: u64, b: u64) -> u64 {
        if b == 0 { a } else { gcd(b, a % b) }
    }
    dims.iter().try_fold(1u64, |l, &n| {
        let n = n as u64;
        (l / gcd(l, n)).checked_mul(n)
    })
}

impl AmplitudeTable {
    pub(crate) fn new(dims: &[usize], beta: f32) -> Self {
        Self::build(dims, beta, true)
    }

    fn build(dims: &[usize], beta: f32, memoise: bool) -> Self {
        let half: Vec<usize> = dims.iter().map(|&n| n / 2 + 1).collect();
        let octant = GridShape::new(&half);
        let n = dims.len();
        let exponent = -(beta + n as f32 - 1.0) / 2.0;
        // Keys are at most n · L² with L ≤ the node count (≤ 2^26 for valid grids, n ≤ 4):
        // below 2^55. Past that (never for valid grids) they saturate, which only flattens
        // the top octave.
        let l = common_length(dims).unwrap_or(u64::MAX);
        // Per axis: the key term (k · L / len)² of the bin and of its nearest alias.
        let near: Vec<Vec<[u64; 2]>> = dims
            .iter()
            .zip(&half)
            .map(|(&len, &h)| {
                let unit = l / len as u64;
                let square = |k: usize| (k as u64).saturating_mul(unit).saturating_pow(2);
                (0..h).map(|i| [square(i), square(len - i)]).collect()
            })
            .collect();
        // The lowest non-zero key (one step along the longest axis), whose power is exp(0) = 1
        // for any β: an enormous β leaves the lowest frequencies at 1 and the rest at 0,
        // never a field of zeros (or of overflowed powers).
        let key_min = near.iter().map(|axis| axis[1][0]).min().unwrap_or(1);
        let key_max = near
            .iter()
            .map(|axis| axis[0][1])
            .fold(0u64, u64::saturating_add);
        let evaluations = if memoise {
            octant.len().saturating_mul(1 << n)
        } else {
            0
        };
        let mut powers = PowerOfKey::new(exponent, key_min, key_max, evaluations);
        let mut values = Vec::with_capacity(octant.len());
        // Odometer over the octant, last axis fastest.
        let mut index = vec![0usize; n];
        for _ in 0..octant.len() {
            let mut power = 0.0f64;
            for images in 0..(1usize << n) {
                let key = index.iter().enumerate().fold(0u64, |key, (a, &i)| {
                    key.saturating_add(near[a][i][images >> a & 1])
                });
                if key > 0 {
                    power += f64::from(powers.power(key));
                }
            }
            values.push(libm::sqrt(power) as f32);
            for a in (0..n).rev() {
                index[a] += 1;
                if index[a] < half[a] {
                    break;
                }
                index[a] = 0;
            }
        }
        Self { octant, values }
    }

    /// Offsets into the table of each index along each axis of the full grid `dims`.
    pub(crate) fn offsets(&self, dims: &[usize]) -> Vec<Vec<usize>> {
        dims.iter()
            .zip(self.octant.strides())
            .map(|(&n, &stride)| (0..n).map(|i| i.min(n - i) * stride).collect())
            .collect()
    }

    /// Amplitude at an offset made from [`Self::offsets`].
    pub(crate) fn at(&self, offset: usize) -> f32 {
        self.values[offset]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Memoised or not, the table is the same bits, and it falls as |f|^−(β+n−1)/2 along an
    /// axis (below a quarter of Nyquist, where the aliases add little).
    #[test]
    fn memo_is_invisible_and_the_amplitude_follows_the_power_law() {
        for (dims, beta) in [
            (vec![64, 64, 32], 5.0 / 3.0),
            (vec![256, 256], 1.0),
            (vec![12, 10, 6], 2.5),
        ] {
            let memo = AmplitudeTable::build(&dims, beta, true);
            let direct = AmplitudeTable::build(&dims, beta, false);
            let bits =
                |t: &AmplitudeTable| t.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&memo), bits(&direct), "{dims:?}");
            let last = dims.len() - 1;
            let (k1, k2) = (1, dims[last] / 8);
            if k2 > k1 {
                let slope = (memo.at(k2) / memo.at(k1)).ln() / (k2 as f32 / k1 as f32).ln();
                let expected = -(beta + dims.len() as f32 - 1.0) / 2.0;
                assert!(
                    (slope - expected).abs() < 0.02,
                    "{dims:?}: {slope} vs {expected}"
                );
            }
        }
    }

    /// The memo is bounded whatever the grid: past the bound the powers are computed directly,
    /// to the same bits.
    #[test]
    fn memo_memory_is_bounded() {
        // An 8192² grid: keys up to 2 · 4096², evaluations 4 per octant bin.
        let big = PowerOfKey::new(-1.0, 1, 2 * 4096 * 4096, 4 * 4097 * 4097);
        assert!(big.memo.is_none());
        let mut cubic = PowerOfKey::new(-1.0, 1, 3 * 64 * 64, 1 << 20);
        assert_eq!(cubic.memo.as_ref().map(Vec::len), Some(3 * 64 * 64 + 1));
        for key in [1, 7, 3 * 64 * 64] {
            assert_eq!(cubic.power(key).to_bits(), big.direct(key).to_bits());
        }
    }
}
