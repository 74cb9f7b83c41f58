//! Primitive motions (§2.3): swings assembled by the trajectory search tree for fluttering,
//! chaotic and tumbling motion, and the unified trajectory function (eq. 6) for steady descent,
//! helix and spiral. Amplitudes from eq. 7–8 with the Gaussian spread of §2.3.2.
//!
//! **Plate angle.** Every swing turns the plate from the angle it has when the swing starts to
//! an end angle, along the database's eq. 4 profile, so the orientation is continuous across
//! swings, whichever child the search tree picks. A plate is symmetric under a half-turn about
//! its long axis, so angles are read modulo π: a swing that reverses the glide (fluttering) ends
//! at ±Θ about the current half-turn; a swing that keeps the side (tumbling, and a chaotic swing
//! that repeats its side) turns on by a half-turn, as a tumbling card does.

use std::f32::consts::PI;

use bevy::math::{Quat, Vec2, Vec3};

use super::database::{Feature, SEGMENT_SAMPLES, TrajectoryDatabase};
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
pub const CHAOTIC_MIN_TIME: f32 = 0.5;

/// The Strouhal number St = f a / U of the swings: f the oscillation frequency (one period is
/// two swings), a the chord, U the descent speed of eq. 3. Measured fluttering of falling disks
/// and plates lies at St ≈ 0.1–0.25 (see [`FallScales::swing_rate`]); 1/(2π) ≈ 0.16 makes
/// Ω = U / a, eq. 8's Ω ∼ √(b/a) in units of √(g/a).
pub const STROUHAL: f32 = 0.159_154_94;

/// The sizes of one fall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FallScales {
    /// U of eq. 3, m/s.
    pub descent_speed: f32,
    /// Ω, rad/s: the swing rate, Ω = 2π St U / a. One swing (turning point to turning point)
    /// takes π / Ω; a flutter period, two swings, has frequency f = St U / a. Eq. 8 gives only
    /// Ω ∼ √(b/a) (in units of √(g/a)); U / a = √((ρ_s/ρ_f − 1) b/a) √(g/a) has that form, and
    /// the Strouhal number [`STROUHAL`] fixes the constant from measured falls.
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
            / (std::f32::consts::TAU * STROUHAL)
    }

    /// A₀ with the Gaussian spread of §2.3.2: the deviations are distributed as
    /// A_i e^(−((r − A_i)/σ_i)²), a normal law of mean A_i and standard deviation σ_i/√2; one
    /// draw per motion of a fall, kept within [0.2, 2.5] A_i.
    pub fn spread_amplitude(&self, motion: PrimitiveMotion, rng: &mut FallRng) -> f32 {
        let shape = MOTION_SHAPES[motion.index()];
        let factor = 1.0 + shape.spread * std::f32::consts::FRAC_1_SQRT_2 * rng.normal();
        self.amplitude(motion) * factor.clamp(0.2, 2.5)
    }

    /// The search key of §2.3.1 for a swing that should glide `glide` metres sideways over
    /// `swings` swing times: the feature vector it should have, in the database's units (length
    /// U/Ω times `swings`): glide, drop −π, a medium modulation, and an angle half-range that
    /// grows with I* (plates near the tumbling boundary swing wider).
    pub fn swing_key(&self, glide: f32, swings: f32) -> Feature {
        let unit = (self.descent_speed / self.swing_rate * swings).max(1e-12);
        let inertia = if self.inertia > 0.0 {
            self.inertia
        } else {
            1e-4
        };
        // log10 I* from 1e-3 (narrow swings) to 4e-2 (the tumbling boundary).
        let t = ((inertia.log10() + 3.0) / 1.6).clamp(0.0, 1.0);
        [glide.abs() / unit, -PI, 0.6, 0.5 + 0.7 * t]
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
pub enum Glide {
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
            let r = (rng.normal() * std::f32::consts::LN_10 / 3.0).exp();
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

/// A stretch of still-fluid motion, evaluated relative to its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Piece {
    /// A database segment along the heading.
    Swing {
        /// Database index.
        segment: u32,
        /// +1 right, −1 left.
        sign: f32,
        /// Metres per database unit (U/Ω times the chaotic scale r).
        scale: f32,
        /// Sideways factor (1; less for a tumble in strong wind or a small chaotic swing).
        sideways: f32,
        /// s.
        duration: f32,
        /// The plate turns along the tumbling profile (a half-turn) rather than the swing's.
        tumble: bool,
        /// Plate angle at the start, rad.
        theta0: f32,
        /// Angle turned over the swing, rad.
        turn: f32,
        /// (cos θ₀/2, sin θ₀/2).
        start_half: Vec2,
    },
    /// Eq. 6 from curve time `start`.
    Curve {
        /// A_e, m.
        amplitude: f32,
        /// ε_e.
        eccentricity: f32,
        /// k.
        lobes: f32,
        /// Ω, rad/s.
        rate: f32,
        /// U, m/s.
        descent: f32,
        /// Curve time at the piece's start, s.
        start: f32,
        /// s.
        duration: f32,
        /// The half-turns the plate carries from earlier tumbles (a multiple of π), rad.
        flip: f32,
    },
}

/// What a swing needs besides its database segment: the search tree's choice and the plate's
/// state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SwingChoice {
    /// The child of the search tree: which way it glides.
    pub glide: Glide,
    /// Whether the glide keeps the previous swing's side (a half-turn) rather than reversing.
    pub same_side: bool,
    /// The chaotic scale r (1 otherwise): the swing lasts r swing times, but at least
    /// [`CHAOTIC_MIN_TIME`] (a plate cannot turn through its range in a blink) and at least one
    /// for a half-turn.
    pub r: f32,
    /// The plate angle when the swing starts, rad.
    pub theta: f32,
    /// [`FallScales::tumble_survival`] in the current wind (1 in still fluid).
    pub survival: f32,
}

impl SwingChoice {
    /// How many swing times the swing lasts.
    pub fn swings(&self, half_turn: bool) -> f32 {
        let r = if self.r.is_finite() { self.r } else { 1.0 };
        let least = if half_turn { 1.0 } else { CHAOTIC_MIN_TIME };
        r.clamp(least, CHAOTIC_SCALE.1)
    }
}

impl Piece {
    /// A swing along database segment `segment` (the search tree's pick), with the segment's
    /// own glide, modulation and angle range, scaled in size and duration by the time the swing
    /// lasts ([`SwingChoice::swings`]). The plate turns from its current angle to the segment's ±Θ about
    /// its current half-turn, or by a half-turn when the glide keeps its side.
    pub fn swing(
        db: &TrajectoryDatabase,
        scales: &FallScales,
        segment: u32,
        choice: SwingChoice,
    ) -> Self {
        let unit = scales.descent_speed / scales.swing_rate;
        let range = db.segment(segment).angle_range;
        let sign = choice.glide.sign();
        let theta = if choice.theta.is_finite() {
            choice.theta
        } else {
            0.0
        };
        // The half-turn the plate is in, and where the swing ends.
        let base = PI * (theta / PI).round();
        let (tumble, end) = if choice.same_side {
            let survival = choice.survival.clamp(0.0, 1.0);
            let full = base + sign * (PI + range) - theta;
            (true, theta + survival * full)
        } else {
            // A quick swing turns the plate no faster than the widest swing of the database
            // does over a whole swing time: the angle follows the swing's size.
            let most = 2.0 * db.widest_angle_range() * choice.swings(false);
            (
                false,
                theta + (base + sign * range - theta).clamp(-most, most),
            )
        };
        let (sin, cos) = (0.5 * theta).sin_cos();
        let sideways = if tumble { choice.survival } else { 1.0 };
        let swings = choice.swings(tumble);
        Self::Swing {
            segment,
            sign,
            scale: swings * unit,
            sideways,
            duration: (swings * scales.swing_time()).max(MIN_PIECE),
            tumble,
            theta0: theta,
            turn: end - theta,
            start_half: Vec2::new(cos, sin),
        }
    }

    /// Eq. 6 for steady descent, helix or spiral, with radius `amplitude` (A₀, m): for the helix
    /// A_e = A₀ / (1 + ε_e), so its outer petals reach A₀.
    pub fn curve(
        scales: &FallScales,
        motion: PrimitiveMotion,
        amplitude: f32,
        start: f32,
        flip: f32,
    ) -> Self {
        let shape = MOTION_SHAPES[motion.index()];
        Self::Curve {
            amplitude: amplitude / (1.0 + shape.eccentricity),
            eccentricity: shape.eccentricity,
            lobes: shape.lobes,
            rate: shape.rate * scales.swing_rate,
            descent: scales.descent_speed,
            start,
            duration: scales.swing_time().max(MIN_PIECE),
            flip,
        }
    }

    /// Length, s.
    pub fn duration(&self) -> f32 {
        match *self {
            Self::Swing { duration, .. } | Self::Curve { duration, .. } => duration,
        }
    }

    /// Displacement since the start and the plate's tilt at piece time `t`, in the frame where
    /// x is the heading, y up and z the heading × up. Beyond its end a swing continues in a
    /// straight line at its final velocity and keeps its final angle; a curve continues eq. 6.
    pub fn sample(&self, db: &TrajectoryDatabase, t: f32) -> (Vec3, Quat) {
        match *self {
            Self::Swing {
                segment,
                sign,
                scale,
                sideways,
                duration,
                tumble,
                turn,
                start_half,
                ..
            } => {
                let seg = db.segment(segment);
                let last = SEGMENT_SAMPLES - 1;
                let s = t / duration;
                let x = s.clamp(0.0, 1.0) * last as f32;
                // x ∈ [0, last]: the i32 conversion is the cheap one.
                let i = (x as i32).clamp(0, last as i32 - 1) as usize;
                let f = x - i as f32;
                let mut p = seg.points[i].lerp(seg.points[i + 1], f);
                if s > 1.0 {
                    p += (seg.points[last] - seg.points[last - 1]) * (last as f32 * (s - 1.0));
                }
                let shape = if tumble {
                    db.tumble_shape()
                } else {
                    &seg.angle_shape
                };
                let progress = shape[i] + (shape[i + 1] - shape[i]) * f;
                let offset = Vec3::new(sign * p.x * scale * sideways, p.y * scale, 0.0);
                (offset, rotation_z(start_half, turn * progress))
            }
            Self::Curve { start, .. } => {
                let (position, velocity) = self.curve_motion(start + t);
                (
                    position - self.curve_motion(start).0,
                    self.curve_tilt(velocity),
                )
            }
        }
    }

    /// [`Piece::sample`]'s displacement alone.
    pub fn offset(&self, db: &TrajectoryDatabase, t: f32) -> Vec3 {
        self.sample(db, t).0
    }

    /// [`Piece::sample`]'s tilt alone.
    pub fn tilt(&self, db: &TrajectoryDatabase, t: f32) -> Quat {
        self.sample(db, t).1
    }

    /// Eq. 6 at curve time `time` and its time derivative, from one `sin_cos` of the phase and
    /// one of the lobes' phase: r = A(1 + ε sin kφ), φ = Ω t, p = (r cos φ, −U t, r sin φ), so
    /// ṗ = (ṙ cos φ − r Ω sin φ, −U, ṙ sin φ + r Ω cos φ) with ṙ = A ε k Ω cos kφ. (A finite
    /// difference in f32 loses its digits as curve time grows: at 100 s a step of 1 ms is
    /// 1 % of the time's last bit.)
    fn curve_motion(&self, time: f32) -> (Vec3, Vec3) {
        let Self::Curve {
            amplitude,
            eccentricity,
            lobes,
            rate,
            descent,
            ..
        } = *self
        else {
            return (Vec3::ZERO, Vec3::ZERO);
        };
        let phase = rate * time;
        let (sl, cl) = (lobes * phase).sin_cos();
        let radius = amplitude * (1.0 + eccentricity * sl);
        let d_radius = amplitude * eccentricity * lobes * rate * cl;
        let (s, c) = phase.sin_cos();
        (
            Vec3::new(radius * c, -descent * time, radius * s),
            Vec3::new(
                d_radius * c - radius * rate * s,
                -descent,
                d_radius * s + radius * rate * c,
            ),
        )
    }

    /// A curve's plate leans into its horizontal velocity `velocity` by half its glide angle
    /// (after the half-turns it carries).
    fn curve_tilt(&self, velocity: Vec3) -> Quat {
        let Self::Curve { descent, flip, .. } = *self else {
            return Quat::IDENTITY;
        };
        let horizontal = Vec2::new(velocity.x, velocity.z);
        let speed = horizontal.length();
        let base = Quat::from_rotation_z(flip);
        if speed > 1e-6 && speed.is_finite() {
            let axis = Vec3::new(-horizontal.y, 0.0, horizontal.x) / speed;
            Quat::from_axis_angle(axis, 0.5 * speed.atan2(descent.max(1e-6))) * base
        } else {
            base
        }
    }

    /// Plate angle at the end, about the heading frame's z (for a curve: its half-turns).
    pub fn end_angle(&self) -> f32 {
        match *self {
            Self::Swing { theta0, turn, .. } => theta0 + turn,
            Self::Curve { flip, .. } => flip,
        }
    }
}

/// Shortest piece, s: keeps the piece loop finite for any input.
pub const MIN_PIECE: f32 = 1e-4;

/// The rotation about z by θ₀ + φ, from (cos θ₀/2, sin θ₀/2) and φ (|φ| ≤ 2π).
fn rotation_z(start_half: Vec2, phi: f32) -> Quat {
    let (s, c) = sin_cos_small(0.5 * phi);
    let (c0, s0) = (start_half.x, start_half.y);
    Quat::from_xyzw(0.0, 0.0, s0 * c + c0 * s, c0 * c - s0 * s)
}

/// sin and cos of |x| ≤ π by their Taylor series to x¹⁴ (error < 3e-5 at π, < 1e-6 below 2):
/// no range reduction and no library call on the per-object hot path. Larger |x| falls back to
/// the library.
pub(crate) fn sin_cos_small(x: f32) -> (f32, f32) {
    if x.is_nan() || x.abs() > PI {
        return x.sin_cos();
    }
    // Horner form with the factorials' reciprocals as constants (multiplications only).
    const S: [f32; 6] = [
        1.0 / 6.0,
        1.0 / 120.0,
        1.0 / 5040.0,
        1.0 / 362_880.0,
        1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
    ];
    const C: [f32; 7] = [
        1.0 / 2.0,
        1.0 / 24.0,
        1.0 / 720.0,
        1.0 / 40_320.0,
        1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        1.0 / 87_178_291_200.0,
    ];
    let x2 = x * x;
    let sin =
        x * (1.0 - x2 * (S[0] - x2 * (S[1] - x2 * (S[2] - x2 * (S[3] - x2 * (S[4] - x2 * S[5]))))));
    let cos = 1.0
        - x2 * (C[0]
            - x2 * (C[1] - x2 * (C[2] - x2 * (C[3] - x2 * (C[4] - x2 * (C[5] - x2 * C[6]))))));
    (sin, cos)
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

    #[test]
    fn curve_velocity_is_the_derivative_of_eq_6() {
        let piece = |eccentricity| Piece::Curve {
            amplitude: 0.05,
            eccentricity,
            lobes: 3.0,
            rate: 7.0,
            descent: 0.4,
            start: 0.0,
            duration: 1.0,
            flip: 0.0,
        };
        let lobed = piece(0.3);
        for tau in [0.1f32, 0.37, 1.2] {
            let h = 1e-3;
            let (ahead, behind) = (lobed.curve_motion(tau + h).0, lobed.curve_motion(tau - h).0);
            let difference = (ahead - behind) / (2.0 * h);
            let velocity = lobed.curve_motion(tau).1;
            assert!(
                (difference - velocity).length() < 2e-3 * velocity.length(),
                "{tau}: {difference} vs {velocity}"
            );
        }
        // A circle (ε = 0) is swept at A Ω whenever it is, long into a fall too.
        let circle = piece(0.0);
        for tau in [0.2f32, 50.0, 500.0] {
            let v = circle.curve_motion(tau).1;
            let speed = Vec2::new(v.x, v.z).length();
            assert!((speed - 0.05 * 7.0).abs() < 1e-5, "{tau}: {speed}");
            assert_eq!(v.y, -0.4);
        }
    }

    #[test]
    fn small_angle_series_is_accurate() {
        for i in 0..=2000 {
            let x = -PI + std::f32::consts::TAU * i as f32 / 2000.0;
            let (s, c) = sin_cos_small(x);
            assert!(
                (s - x.sin()).abs() < 3e-5 && (c - x.cos()).abs() < 3e-5,
                "{x}"
            );
        }
    }
}
