//! The Markov chain of primitive motions (§3.1–3.2, eq. 9).

use bevy::reflect::Reflect;
use thiserror::Error;

use super::random::FallRng;
use super::regime::PrimitiveMotion;

/// Why a transition matrix was rejected. `row` is 0-based (L1 = 0); the initial distribution is
/// reported as row `None`.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
pub enum MarkovError {
    /// An entry is negative or not finite.
    #[error("row {row:?}, column {column}: probability {value} must be finite and ≥ 0")]
    Negative {
        /// Offending row.
        row: Option<usize>,
        /// Offending column.
        column: usize,
        /// The entry.
        value: f32,
    },
    /// A row does not sum to 1 within 1e-6.
    #[error("row {row:?} sums to {sum}, not 1")]
    RowSum {
        /// Offending row.
        row: Option<usize>,
        /// Its sum.
        sum: f32,
    },
    /// A transition to a lower-numbered motion, which the paper's hypothesis (§3.1) forbids.
    #[error("row {row}: backward transition to column {column} (p = {value})")]
    Backward {
        /// Offending row.
        row: usize,
        /// The lower state.
        column: usize,
        /// The entry.
        value: f32,
    },
}

impl MarkovError {
    /// The offending row (`None`: the initial distribution).
    pub fn row(&self) -> Option<usize> {
        match *self {
            Self::Negative { row, .. } | Self::RowSum { row, .. } => row,
            Self::Backward { row, .. } => Some(row),
        }
    }
}

/// First-order discrete-time Markov chain over L1..L6 (§3.2): where a fall starts, and
/// p_ij = P[next motion L_j | current motion L_i] over one chain step of
/// [`MarkovChain::step_seconds`] of fall.
///
/// A fall changes motion only where one piece (a swing, or a stretch of eq. 6) ends and the next
/// begins; a piece of d seconds leaves motion L_i with probability 1 − p_ii^(d / step), to L_j
/// (j ≠ i) in proportion to p_ij. So a motion lasts step / (1 − p_ii) seconds on average,
/// whatever the object's size, and the matrix is what a designer reads: "stays a second in
/// fluttering" is p_ii = 1 − step / 1 s.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct MarkovChain {
    initial: [f32; 6],
    transitions: [[f32; 6]; 6],
    step: f32,
}

impl Default for MarkovChain {
    /// Our default (the paper's Fig. 11 numbers are not in its text). Rows L1..L6:
    ///
    /// | from \ to | L1 | L2 | L3 | L4 | L5 | L6 |
    /// |---|---|---|---|---|---|---|
    /// | start | .35 | .30 | .10 | .15 | .05 | .05 |
    /// | L1 SD | .40 | .30 | .10 | .10 | .05 | .05 |
    /// | L2 PF | 0 | .70 | .10 | .10 | .05 | .05 |
    /// | L3 TC | 0 | 0 | .50 | .30 | .10 | .10 |
    /// | L4 PT | 0 | 0 | 0 | .75 | .15 | .10 |
    /// | L5 TH | 0 | 0 | 0 | 0 | .80 | .20 |
    /// | L6 PS | 0 | 0 | 0 | 0 | 0 | 1 |
    ///
    /// One step is [`MarkovChain::STEP_SECONDS`](crate::freefall::MarkovChain::STEP_SECONDS) = 0.25 s: a release usually starts steady or fluttering, and a
    /// motion lasts 0.25 s / (1 − p_ii) on average (0.4 s steady, 0.8 s fluttering, 1 s
    /// tumbling, 1.25 s helix) before the next.
    fn default() -> Self {
        Self {
            step: MarkovChain::STEP_SECONDS,
            initial: [0.35, 0.30, 0.10, 0.15, 0.05, 0.05],
            transitions: [
                [0.40, 0.30, 0.10, 0.10, 0.05, 0.05],
                [0.0, 0.70, 0.10, 0.10, 0.05, 0.05],
                [0.0, 0.0, 0.50, 0.30, 0.10, 0.10],
                [0.0, 0.0, 0.0, 0.75, 0.15, 0.10],
                [0.0, 0.0, 0.0, 0.0, 0.80, 0.20],
                [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            ],
        }
    }
}

impl MarkovChain {
    /// A validated chain: entries finite and ≥ 0, every row (and `initial`) summing to 1 within
    /// 1e-6, and no entry below the diagonal above zero.
    pub fn new(initial: [f32; 6], transitions: [[f32; 6]; 6]) -> Result<Self, MarkovError> {
        check_row(None, &initial)?;
        for (i, row) in transitions.iter().enumerate() {
            check_row(Some(i), row)?;
            if let Some((column, &value)) = row[..i].iter().enumerate().find(|(_, p)| **p > 0.0) {
                return Err(MarkovError::Backward {
                    row: i,
                    column,
                    value,
                });
            }
        }
        Ok(Self {
            initial,
            transitions,
            step: MarkovChain::STEP_SECONDS,
        })
    }

    /// The same chain with one step lasting `seconds` (finite, > 0; otherwise the step is
    /// kept).
    pub fn with_step_seconds(mut self, seconds: f32) -> Self {
        if seconds.is_finite() && seconds > 0.0 {
            self.step = seconds;
        }
        self
    }

    /// Seconds of fall per chain step.
    pub fn step_seconds(&self) -> f32 {
        self.step
    }

    /// A chain from the mean time (s) a fall stays in each motion and where it goes next:
    /// `dwell[i]` seconds in L_i (infinite: it stays), `next[i]` the relative weights of the
    /// motions after L_i (only those above i count). p_ii = e^(−step / dwell), a rate of one
    /// change per `dwell` seconds, the rest shared by the weights. Since changes happen where
    /// pieces end, a motion whose pieces last d seconds is seen for d / (1 − e^(−d / dwell)) on
    /// average (about dwell + d/2). Errors as [`MarkovChain::new`] (a row with no weight above
    /// it must stay).
    pub fn from_dwell_times(
        initial: [f32; 6],
        dwell: [f32; 6],
        next: [[f32; 6]; 6],
    ) -> Result<Self, MarkovError> {
        let mut transitions = [[0.0f32; 6]; 6];
        for i in 0..6 {
            let stay = if dwell[i].is_finite() && dwell[i] > 0.0 {
                libm::expf(-MarkovChain::STEP_SECONDS / dwell[i])
            } else if dwell[i] == f32::INFINITY {
                1.0
            } else {
                return Err(MarkovError::Negative {
                    row: Some(i),
                    column: i,
                    value: dwell[i],
                });
            };
            let weights: f32 = next[i][i + 1..].iter().filter(|w| **w > 0.0).sum();
            if weights > 0.0 && weights.is_finite() {
                transitions[i][i] = stay;
                for j in i + 1..6 {
                    transitions[i][j] = (1.0 - stay) * next[i][j].max(0.0) / weights;
                }
            } else {
                transitions[i][i] = 1.0;
            }
        }
        let total: f32 = initial.iter().filter(|p| **p > 0.0).sum();
        let initial = if total > 0.0 && total.is_finite() {
            initial.map(|p| p.max(0.0) / total)
        } else {
            initial
        };
        Self::new(initial, transitions)
    }

    /// Where falls start.
    pub fn initial(&self) -> &[f32; 6] {
        &self.initial
    }

    /// The matrix P = (p_ij).
    pub fn transitions(&self) -> &[[f32; 6]; 6] {
        &self.transitions
    }

    /// The chain an object with main motion `main` follows: states above `main` are out of
    /// reach (eq. 9 counts the motion classes of L1..L_k), so a step that would go past `main`
    /// goes to `main`, which then holds.
    pub(crate) fn bounded(&self, main: PrimitiveMotion) -> BoundedChain {
        let k = main.index();
        let collapse = |row: &[f32; 6]| {
            let mut out = [0.0f32; 6];
            out[..k].copy_from_slice(&row[..k]);
            out[k] = row[k..].iter().sum();
            cumulative(&out)
        };
        let mut rows = [[1.0f32; 6]; 6];
        for (i, row) in self.transitions.iter().enumerate().take(k + 1) {
            rows[i] = collapse(row);
        }
        let leave_rate = std::array::from_fn(|i| {
            let stay = rows[i][i].clamp(0.0, 1.0);
            if stay >= 1.0 {
                0.0
            } else if stay <= 0.0 {
                f32::INFINITY
            } else {
                -libm::logf(stay) / self.step
            }
        });
        BoundedChain {
            main,
            initial: collapse(&self.initial),
            rows,
            leave_rate,
        }
    }
}

/// Number of motion classes of a fall whose main motion is L_k (eq. 9): Σ_{i=1..k} C(k, i) =
/// 2^k − 1, the non-empty increasing sequences of L1..L_k.
#[cfg(test)]
pub(crate) fn motion_class_count(main: PrimitiveMotion) -> u32 {
    (1u32 << (main.index() + 1)) - 1
}

/// A [`MarkovChain`] limited to L1..main, with cumulative rows for sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BoundedChain {
    main: PrimitiveMotion,
    initial: [f32; 6],
    rows: [[f32; 6]; 6],
    /// −ln p_ii / step for each row: the rate at which a fall leaves the motion, 1/s.
    leave_rate: [f32; 6],
}

impl BoundedChain {
    /// The upper bound (and absorbing state).
    pub fn main(&self) -> PrimitiveMotion {
        self.main
    }

    /// Draws the first motion.
    pub fn start(&self, rng: &mut FallRng) -> PrimitiveMotion {
        draw(&self.initial, rng.uniform())
    }

    #[cfg(test)]
    /// Draws the motion one chain step after `current` (never lower, never above `main`).
    pub fn next(&self, current: PrimitiveMotion, rng: &mut FallRng) -> PrimitiveMotion {
        let current = current.min(self.main);
        draw(&self.rows[current.index()], rng.uniform()).max(current)
    }

    /// How long a fall that has just entered `current` stays in it, s: exponential with the
    /// rate at which the chain leaves it, −ln p_ii per step (infinite for a motion it never
    /// leaves). Drawn once on entering, so a piece's end only counts it down: staying through a
    /// piece of d seconds then has probability p_ii^(d / step), as the matrix says.
    pub fn sojourn(&self, current: PrimitiveMotion, rng: &mut FallRng) -> f32 {
        let rate = self.leave_rate[current.min(self.main).index()];
        if rate > 0.0 {
            // 1 − u in (0, 1]: a finite time.
            -libm::logf(1.0 - rng.uniform()) / rate
        } else {
            f32::INFINITY
        }
    }

    /// The motion a fall goes to when its sojourn in `current` is over: another one, in
    /// proportion to its p_ij (never lower, never above `main`).
    pub fn leave(&self, current: PrimitiveMotion, rng: &mut FallRng) -> PrimitiveMotion {
        let current = current.min(self.main);
        let row = &self.rows[current.index()];
        // Nothing below the diagonal: the cumulative row at i is p_ii.
        let stay = row[current.index()].clamp(0.0, 1.0);
        if stay >= 1.0 {
            return current;
        }
        // Among the others, in proportion to p_ij: a uniform draw over the leaving share.
        let target = stay + rng.uniform() * (1.0 - stay);
        draw(row, target.min(1.0 - f32::EPSILON)).max(current)
    }
}

fn draw(cdf: &[f32; 6], u: f32) -> PrimitiveMotion {
    let index = cdf.iter().position(|&c| u < c).unwrap_or_else(|| {
        // u above the rounded total: the last state with any probability.
        cdf.iter().rposition(|&c| c > 0.0).unwrap_or(0)
    });
    PrimitiveMotion::from_index(index)
}

fn cumulative(row: &[f32; 6]) -> [f32; 6] {
    let mut out = [0.0; 6];
    let mut sum = 0.0;
    for (o, p) in out.iter_mut().zip(row) {
        sum += p;
        *o = if *p > 0.0 { sum } else { -1.0 };
    }
    out
}

fn check_row(row: Option<usize>, values: &[f32; 6]) -> Result<(), MarkovError> {
    if let Some((column, &value)) = values
        .iter()
        .enumerate()
        .find(|(_, p)| !(p.is_finite() && **p >= 0.0))
    {
        return Err(MarkovError::Negative { row, column, value });
    }
    let sum: f32 = values.iter().map(|&p| f64::from(p)).sum::<f64>() as f32;
    if (sum - 1.0).abs() > 1e-6 {
        return Err(MarkovError::RowSum { row, sum });
    }
    Ok(())
}

/// Limits and constants of [`MarkovChain`].
impl MarkovChain {
    /// Seconds of fall per chain step of the default chain and of [`MarkovChain::new`].
    pub const STEP_SECONDS: f32 = 0.25;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markov_chain_matches_its_matrix() {
        let chain = MarkovChain::default();
        let bounded = chain.bounded(PrimitiveMotion::Spiral);
        let mut rng = FallRng::new(11);
        let mut counts = [[0u32; 6]; 6];
        let mut state = bounded.start(&mut rng);
        for i in 0..400_000 {
            let next = bounded.next(state, &mut rng);
            counts[state.index()][next.index()] += 1;
            // Restart now and then so every row is visited.
            state = if i % 8 == 7 {
                PrimitiveMotion::from_index(i / 8 % 6)
            } else {
                next
            };
        }
        for (i, row) in counts.iter().enumerate() {
            let n: u32 = row.iter().sum();
            assert!(n > 10_000, "row {i} visited {n} times");
            for (j, &c) in row.iter().enumerate() {
                let p = f64::from(chain.transitions()[i][j]);
                let f = f64::from(c) / f64::from(n);
                let sigma = (p * (1.0 - p) / f64::from(n)).sqrt();
                assert!(
                    (f - p).abs() <= 4.0 * sigma + 1e-9,
                    "p[{i}][{j}] = {p}, seen {f}"
                );
            }
        }
    }

    #[test]
    fn bounded_chain_collapses_the_motions_past_the_main_one() {
        // Bounded at L3, the default chain's row L1 (.40 .30 .10 .10 .05 .05) becomes
        // (.40 .30 .30): everything past L3 lands on L3, and L3 holds.
        let bounded = MarkovChain::default().bounded(PrimitiveMotion::Chaotic);
        let mut rng = FallRng::new(5);
        let mut counts = [0u32; 6];
        let n = 50_000;
        for _ in 0..n {
            counts[bounded
                .next(PrimitiveMotion::SteadyDescent, &mut rng)
                .index()] += 1;
        }
        let expected = [0.40, 0.30, 0.30, 0.0, 0.0, 0.0];
        for (c, p) in counts.iter().zip(expected) {
            let f = f64::from(*c) / f64::from(n);
            assert!((f - p).abs() < 0.01, "{counts:?}");
        }
        for _ in 0..1000 {
            assert_eq!(
                bounded.next(PrimitiveMotion::Chaotic, &mut rng),
                PrimitiveMotion::Chaotic
            );
        }
        assert_eq!(motion_class_count(PrimitiveMotion::Chaotic), 7);
    }

    #[test]
    fn a_fall_stays_in_a_motion_through_a_piece_as_the_matrix_says() {
        // p_ii = 0.8 per 0.25 s step: a fall stays through 0.1 s with 0.8^0.4, through 1 s
        // with 0.8^4, whatever pieces it is cut into (the sojourn is drawn on entering).
        let chain = MarkovChain::default();
        let bounded = chain.bounded(PrimitiveMotion::Spiral);
        let p = f64::from(chain.transitions()[4][4]);
        let mut rng = FallRng::new(17);
        let n = 40_000;
        let sojourns: Vec<f32> = (0..n)
            .map(|_| bounded.sojourn(PrimitiveMotion::Helix, &mut rng))
            .collect();
        for seconds in [0.1f32, 0.25, 1.0] {
            let stayed = sojourns.iter().filter(|&&s| s > seconds).count();
            let expected = p.powf(f64::from(seconds) / f64::from(MarkovChain::STEP_SECONDS));
            let f = stayed as f64 / f64::from(n);
            let sigma = (expected * (1.0 - expected) / f64::from(n)).sqrt();
            assert!(
                (f - expected).abs() < 5.0 * sigma,
                "{seconds} s: {f} vs {expected}"
            );
        }
        // The absorbing motion is never left; leaving goes up the chain only.
        assert_eq!(
            bounded.sojourn(PrimitiveMotion::Spiral, &mut rng),
            f32::INFINITY
        );
        for _ in 0..1000 {
            let next = bounded.leave(PrimitiveMotion::Tumbling, &mut rng);
            assert!(next > PrimitiveMotion::Tumbling, "{next:?}");
        }
    }
}
