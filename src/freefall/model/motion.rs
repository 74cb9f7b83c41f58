//! Primitive motions (§2.3): swings assembled by the trajectory search tree for fluttering,
//! chaotic and tumbling motion, and the unified trajectory function (eq. 6) for steady descent,
//! helix and spiral. Amplitudes from eq. 7–8 with the Gaussian spread of §2.3.2; the pieces a
//! fall is assembled from are in `piece.rs`.

use std::f32::consts::PI;

use super::database::Feature;
use super::random::FallRng;
use super::regime::PrimitiveMotion;

/// Per-motion constants of eq. 6–8. `deviation` is B_i of eq. 7 (the deviation coefficient k
/// is [`FallScales::deviation`]) and `spread` the relative width σ_i / A_i of its Gaussian
/// (§2.3.2); `rate` multiplies the swing rate Ω; `eccentricity` is ε_e and `lobes` k of eq. 6.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MotionShape {
    /// B_i: the sideways excursion per swing (or the curve's radius), in object lengths L.
    pub deviation: f32,
    /// σ_i / A_i of the deviations' Gaussian A_i e^(−((r − A_i)/σ_i)²).
    pub spread: f32,
    /// Ω of the motion in units of the swing rate.
    pub rate: f32,
    /// ε_e of eq. 6.
    pub eccentricity: f32,
    /// k of eq. 6.
    pub lobes: f32,
}

/// L1..L6. Eq. 6 with ε_e → 0, k = 1 is the spiral (a circle of radius A₀ from above); with
/// ε_e ≠ 0, k = 4 the helix, whose radius A_e (1 + ε_e sin 4φ) changes sign for ε_e > 1, so the
/// path crosses the axis eight times a turn: the paper's eight-petal rose (Fig. 8). A_e → 0 is
/// steady descent. The paper gives no values; these are ours, chosen so the paths look like
/// Fig. 1 and Fig. 9: fluttering swings about 0.6 L to each side; tumbling drifts L per
/// half-turn, which with a drop of a / (2 St) ≈ 3 a per swing is a glide of 18° from the
/// vertical for a disk and about 30° for a card (tumbling cards and disks drift at 10–30°); the
/// spiral circles at 0.8 L once every 2.7 swings; the helix's outer petals reach 0.6 L and it
/// turns once every eight swings, so each petal takes one swing as a zigzag does.
pub(crate) const MOTION_SHAPES: [MotionShape; 6] = [
    MotionShape {
        deviation: 0.0,
        spread: 0.0,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.6,
        spread: 0.35,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.6,
        spread: 0.5,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.5,
        spread: 0.35,
        rate: 1.0,
        eccentricity: 0.0,
        lobes: 0.0,
    },
    MotionShape {
        deviation: 0.6,
        spread: 0.25,
        rate: 0.25,
        eccentricity: 3.0,
        lobes: 4.0,
    },
    MotionShape {
        deviation: 0.8,
        spread: 0.25,
        rate: 0.75,
        eccentricity: 0.0,
        lobes: 1.0,
    },
];

/// Range of the chaotic scale r (§2.3.2).
pub const CHAOTIC_SCALE: (f32, f32) = (0.1, 10.0);

/// The shortest chaotic swing, in swings: below it r shrinks the glide, not the duration.
/// A half-turn takes at least one swing.
///
/// One whole swing: a plate's period is set by the plate (St = f a / U), not by how far it
/// glides, so a small chaotic swing takes as long as a wide one. Half a swing was tried first:
/// a light leaf (swing time 0.12 s) then turned 75° in 3–4 fixed steps of 1/60 s, one step
/// turning twice as far as the steps beside it (a visible jerk in 1 fall in 4).
pub(crate) const CHAOTIC_MIN_TIME: f32 = 1.0;

/// The sizes of one fall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FallScales {
    /// U of eq. 3, m/s.
    pub descent_speed: f32,
    /// Ω, rad/s: the swing rate, Ω = 2π St U / a. One swing (turning point to turning point)
    /// takes π / Ω; a flutter period, two swings, has frequency f = St U / a. Eq. 8 gives only
    /// Ω ∼ √(b/a) (in units of √(g/a)); U / a = √((ρ_s/ρ_f − 1) b/a) √(g/a) has that form, and
    /// the Strouhal number [`FallScales::STROUHAL`](crate::freefall::FallScales::STROUHAL) fixes the constant from measured falls.
    pub swing_rate: f32,
    /// L, m.
    pub length: f32,
    /// a, the chord, m.
    pub chord: f32,
    /// k of eq. 7 (1 by default).
    pub deviation: f32,
    /// ℓ = ρ_s b / ρ_f, m: the length over which the fluid's drag changes the object's
    /// velocity relative to the fluid by a factor e (see [`FallScales::response_time`]).
    pub drag_length: f32,
    /// I*, for the angle the search key asks for.
    pub inertia: f32,
}

impl FallScales {
    /// A₀ of eq. 8 for `motion`, before the Gaussian spread. Eq. 7 read with the release height
    /// the text says it is linear in, D_i = k B_i h L / a, gives A₀ = D_i U / (h Ω) = k B_i L
    /// U / (a Ω): with Ω = 2π St U / a, A₀ = k B_i L / (2π St) = k B_i L at the default St.
    pub fn amplitude(&self, motion: PrimitiveMotion) -> f32 {
        self.deviation * MOTION_SHAPES[motion.index()].deviation * self.length
            / (std::f32::consts::TAU * FallScales::STROUHAL)
    }

    /// A₀ with the Gaussian spread of §2.3.2: the deviations are distributed as
    /// A_i e^(−((r − A_i)/σ_i)²), a normal law of mean A_i and standard deviation σ_i/√2; one
    /// draw per motion of a fall, kept within [0.2, 2.5] A_i.
    pub(crate) fn spread_amplitude(&self, motion: PrimitiveMotion, rng: &mut FallRng) -> f32 {
        let shape = MOTION_SHAPES[motion.index()];
        let factor = 1.0 + shape.spread * std::f32::consts::FRAC_1_SQRT_2 * rng.normal();
        self.amplitude(motion) * factor.clamp(0.2, 2.5)
    }

    /// The search key of §2.3.1 for a swing that should glide `glide` metres sideways over
    /// `swings` swing times: the feature vector it should have, in the database's units (length
    /// U/Ω times `swings`): glide, drop −π, a medium modulation, and an angle half-range that
    /// grows with I* (plates near the tumbling boundary swing wider).
    #[cfg(test)]
    pub(crate) fn swing_key(&self, glide: f32, swings: f32) -> Feature {
        self.swing_key_with(self.swing_key_angle(), glide, swings)
    }

    /// [`FallScales::swing_key`] with its angle component given (it depends on I* alone, so a
    /// fall computes it once).
    pub(crate) fn swing_key_with(&self, angle: f32, glide: f32, swings: f32) -> Feature {
        let unit = (self.descent_speed / self.swing_rate * swings).max(1e-12);
        [glide.abs() / unit, -PI, 0.6, angle]
    }

    /// The search key's angle half-range: wider for plates near the tumbling boundary.
    pub(crate) fn swing_key_angle(&self) -> f32 {
        let inertia = if self.inertia > 0.0 {
            self.inertia
        } else {
            1e-4
        };
        // log10 I* from 1e-3 (narrow swings) to 4e-2 (the tumbling boundary).
        let t = ((libm::log10f(inertia) + 3.0) / 1.6).clamp(0.0, 1.0);
        0.5 + 0.7 * t
    }

    /// Time of one swing (and one curve piece), s.
    pub fn swing_time(&self) -> f32 {
        PI / self.swing_rate
    }

    /// The time over which the object takes up a change of the fluid's velocity around it,
    /// when it slips through the fluid at `slip` m/s (besides falling at U).
    ///
    /// The drag on a plate, ½ ρ_f C_D A |w| w, with the C_D = 2 for which eq. 3's U is the
    /// terminal speed ((ρ_s − ρ_f) g b = ½ ρ_f C_D U²), accelerates the object's mass ρ_s A b by
    /// |w| w / ℓ with ℓ = ρ_s b / ρ_f. The object always moves through the fluid at about U, so
    /// the relative speed is |w| ≈ √(U² + slip²) and τ = ℓ / √(U² + slip²); in gentle wind
    /// τ = ℓ / U = (U / g) ρ_s / (ρ_s − ρ_f). A 0.3 mm leaf in air: 0.11 s; the paper's coin in
    /// water: 0.03 s; the same coin in air: 0.6 s. Added mass is neglected.
    pub fn response_time(&self, slip: f32) -> f32 {
        let u = self.descent_speed;
        self.drag_length / (u * u + slip * slip).sqrt().max(1e-9)
    }

    /// 1/τ for a squared slip speed `slip_squared` (m²/s²): [`FallScales::response_time`]'s
    /// reciprocal with one square root.
    pub fn response_rate(&self, slip_squared: f32) -> f32 {
        let u = self.descent_speed;
        (u * u + slip_squared).sqrt() / self.drag_length.max(1e-12)
    }

    /// How much of a tumble's turn (and its sideways drift) survives in wind of horizontal speed
    /// `wind` (m/s): the paper's §5 finds that "under a strong wind field, tumbling motion
    /// disappears and the object travels far" (Fig. 17). Modelled as 1 / (1 + (|u_h| / 3U)²):
    /// unchanged in still air, half at three descent speeds, a fifth at six.
    pub fn tumble_survival(&self, wind: f32) -> f32 {
        let x = wind / (3.0 * self.descent_speed).max(1e-9);
        if x.is_finite() {
            1.0 / (1.0 + x * x)
        } else {
            0.0
        }
    }
}

/// Which way a swing glides along the heading (the search tree's two children, Fig. 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Glide {
    /// gl.
    Left,
    /// gr.
    Right,
}

impl Glide {
    /// −1 or +1.
    pub fn sign(self) -> f32 {
        match self {
            Self::Left => -1.0,
            Self::Right => 1.0,
        }
    }

    fn flip(self) -> Self {
        match self {
            Self::Left => Self::Right,
            Self::Right => Self::Left,
        }
    }
}

/// One node of the trajectory search tree (§2.3.1): the child to take after `previous` and its
/// scale r. Fluttering alternates (gl, gr, gl, ...); tumbling keeps one side; chaotic motion
/// takes either side at random with r from a log-normal clamped to [1/10, 10], so it flutters
/// with changing amplitude and tumbles when it repeats a side.
pub fn next_glide(motion: PrimitiveMotion, previous: Glide, rng: &mut FallRng) -> (Glide, f32) {
    match motion {
        PrimitiveMotion::Tumbling => (previous, 1.0),
        PrimitiveMotion::Chaotic => {
            // σ = ln(10)/3: r = 10 is three standard deviations out.
            let r = libm::expf(rng.normal() * std::f32::consts::LN_10 / 3.0);
            let glide = if rng.coin() {
                previous
            } else {
                previous.flip()
            };
            (glide, r.clamp(CHAOTIC_SCALE.0, CHAOTIC_SCALE.1))
        }
        _ => (previous.flip(), 1.0),
    }
}

/// Limits and constants of [`FallScales`].
impl FallScales {
    /// The Strouhal number St = f a / U of the swings: f the oscillation frequency (one period is
    /// two swings), a the chord, U the descent speed of eq. 3. Measured fluttering of falling disks
    /// and plates lies at St ≈ 0.1–0.25 (see [`FallScales::swing_rate`]); 1/(2π) ≈ 0.16 makes
    /// Ω = U / a, eq. 8's Ω ∼ √(b/a) in units of √(g/a).
    pub const STROUHAL: f32 = 0.159_154_94;
}

#[cfg(test)]
mod tests {
    #[test]
    fn chaotic_swings_vary_within_the_r_range() {
        let mut rng = FallRng::new(9);
        let mut glide = Glide::Right;
        let (mut same, mut lo, mut hi) = (0, f32::INFINITY, 0.0f32);
        let n = 20_000;
        for _ in 0..n {
            let (g, r) = next_glide(PrimitiveMotion::Chaotic, glide, &mut rng);
            same += usize::from(g == glide);
            lo = lo.min(r);
            hi = hi.max(r);
            glide = g;
        }
        assert!((same as f32 / n as f32 - 0.5).abs() < 0.02);
        assert!(
            lo >= 0.1 && hi <= 10.0 && lo < 0.2 && hi > 5.0,
            "r in [{lo}, {hi}]"
        );
        // Fluttering alternates, tumbling keeps its side.
        assert_eq!(
            next_glide(PrimitiveMotion::Fluttering, Glide::Left, &mut rng),
            (Glide::Right, 1.0)
        );
        assert_eq!(
            next_glide(PrimitiveMotion::Tumbling, Glide::Left, &mut rng),
            (Glide::Left, 1.0)
        );
    }

    use super::*;
}
