//! The air's reactive force on a particle cloth along its chordwise yarns (the yarns from the
//! pins to the free edge), implicit: Lighthill's large-amplitude elongated-body theory
//! (Lighthill, "Large-amplitude elongated-body theory of fish locomotion", Proc. R. Soc. B 179,
//! 1971; Candelier, Boyer & Leroyer, J. Fluid Mech. 674, 2011), as applied to flags by
//! Lemaitre, Hémon & de Langre (J. Fluids Struct. 20, 2005) and Michelin & Doaré (J. Fluid Mech.
//! 714, 2013).
//!
//! Across the sheet each strip of a chordwise yarn carries the air a flat plate of span H
//! carries, spread elliptically over the span: m̃ = 2 ρ √(H²/4 − y²) per area at y from the
//! middle of the span (in all ρ π H² / 4 per length of chord, the 2D added mass of the plate's
//! cross-section). The air that slides along the yarn at U = (u − v) · τ (τ the yarn's tangent
//! away from its pin) carries that momentum m̃ w along, w = (v − u) · n the normal velocity
//! relative to the air: the force on the sheet per length is −∂ₜ(m̃ w) − ∂ₛ(U m̃ w). The first
//! part is the carried air's inertia, which the nodes' inertia m I + m_a n nᵀ and the turn of
//! their velocities with their normals hold, but for the wind's share −m̃ u · ∂ₜn, which
//! [`ReactiveAir::turn`] supplies to the turn; this module adds the second, the momentum flux,
//! with the local resistive drag K w (the face law's
//! C_D sin²α share along the normal). Over a node's stretch of yarn (finite volumes, the flux at
//! each face taken from the node upwind of it, the flux at the free edge shed into the wake):
//!
//! (m + m_a) (w′ᵢ − w*ᵢ) / h = −(|Uᵢ| m̃ᵢ w′ᵢ − U⁺ᵢ₋₁ m̃ᵢ₋₁ w′ᵢ₋₁ − U⁻ᵢ₊₁ m̃ᵢ₊₁ w′ᵢ₊₁) − Kᵢ w′ᵢ,
//!
//! m̃ᵢ here the air carried per length of chord by the node's strip, U⁺ = max(U, 0), U⁻ =
//! max(−U, 0), w* the normal velocity before the air, w′ after. Each yarn's system is
//! tridiagonal and diagonally dominant by columns (each node's outflow goes to one neighbour), so
//! Thomas' algorithm solves it in one sweep from the pin without pivoting; pinned nodes keep
//! their velocity and take their share of the force into the pin.
//!
//! On a flat sheet in a uniform wind at a small incidence α, w is uniform and the flux is the
//! same at every face but the first: the whole normal force, U² sin α cos α ρ π H² / 4, acts at
//! the leading edge, Jones' slender-wing lift C_Lα = (π/2) AR with nothing fitted. On a
//! travelling wave the force sets waves to run at U m_a / (μ + m_a). In still air (U = −v · τ)
//! the upwind, implicit flux only takes energy out of the motion: Σ F w′ ≤ 0.
//!
//! Over a stretch of yarn shorter than the span the air cannot take up the sheet's motion as
//! slender-body theory has it (it flows round the side edges instead): the flux is carried by
//! S w′ rather than w′, S the screen (1 − ℓ²∂ₛ²)⁻¹ along the yarn over the strip's semi-span
//! ℓ = √(H²/4 − y²), the screened velocity falling to zero past the end the air enters by. A
//! wave of wavenumber k keeps 1 / (1 + k²ℓ²) of its flux; on a held sheet the leading edge's
//! force is spread over ℓ behind it. The screened system is solved by a few solves of the
//! unscreened one with the screen's correction on the right side.
//!
//! Opt-in ([`ParticleCloth::with_reactive_air`](super::ParticleCloth::with_reactive_air)) while
//! it is measured: it gives a held sheet Jones' lift slope on any grid and, at ticks of 2 ms, a
//! flag's waves Lighthill's speed, but the flag swings too wide, does not hang in light
//! air, and does not converge in its tick: its swing and wave speed fall with each halving of
//! the tick down to 0.125 ms (docs/aero.md).
//!
//! Hand-written: a tridiagonal solve per yarn (Thomas' algorithm), which no maintained crate
//! offers for strided data.

use bevy::math::Vec3;

use super::screen::Screen;
use super::{ParticleCloth, Pinning};
use crate::cloth::ClothGrid;

/// Largest flux rate |U| m̃, kg/s: keeps every coefficient, and its product with a finite
/// velocity, finite.
const MOST_RATE: f32 = 1e30;

/// Solves of the screened system after the first, unscreened one: each takes the correction
/// h D (S − I) w′ of the last to the right side (contracting by about h U m̃ / (m + m_a), m̃ per
/// length: a third a solve for a flag in 8 m/s).
const SCREEN_SOLVES: usize = 3;

/// The chordwise yarns of a `rows × columns` row-major grid: `count` of them, each of `length`
/// nodes, the first node of yarn `y` at `y × between`, its nodes `along` apart.
#[derive(Clone, Copy, Debug)]
struct Chords {
    count: usize,
    length: usize,
    between: usize,
    along: usize,
}

impl Chords {
    /// The rows of a flag on a pole, the columns of a curtain on a rod.
    fn new(grid: &ClothGrid, pinning: Pinning) -> Self {
        let (rows, columns) = (grid.rows, grid.columns);
        match pinning {
            Pinning::PoleColumn => Self {
                count: rows,
                length: columns,
                between: columns,
                along: 1,
            },
            Pinning::TopRow => Self {
                count: columns,
                length: rows,
                between: 1,
                along: columns,
            },
        }
    }

    /// The grid index of node `s` along yarn `yarn`.
    fn node(&self, yarn: usize, s: usize) -> usize {
        yarn * self.between + s * self.along
    }
}

/// The reactive air of a particle cloth: what each node's strip carries and the state of the
/// substep's solve.
#[derive(Clone, Debug)]
pub(super) struct ReactiveAir {
    chords: Chords,
    /// Per node: pinned, the air carried per length of chord m̃ (kg/m), the inertia along the
    /// normal m + m_a (kg), the air's speed along the yarn away from the pin U (m/s) and the
    /// normal velocity relative to the air after the substep's air (m/s).
    held: Vec<bool>,
    carried: Vec<f32>,
    inertia: Vec<f32>,
    along: Vec<f32>,
    after: Vec<f32>,
    turned: Vec<f32>,
    /// Per yarn: the screen's (ℓ / Δs)².
    spread: Vec<f32>,
    /// One yarn's work space: the system's eliminated upper diagonal and inverse pivots, its
    /// right side, the velocities, a line to screen and a corrected right side.
    upper: Vec<f32>,
    inverse: Vec<f32>,
    right: Vec<f32>,
    w: Vec<f32>,
    line: Vec<f32>,
    corrected: Vec<f32>,
    smoothing: Vec<f32>,
    /// Pivots not positive and finite so far.
    guarded: u64,
}

impl ReactiveAir {
    /// The air of `cloth`'s grid and pinning, and each node's added mass m_a, kg: its strip's
    /// carried air per length (elliptic over the span across the chordwise yarns, ρ π H² / 4
    /// per length in all on any grid) times its length of yarn.
    pub fn new(cloth: &ParticleCloth) -> (Self, Vec<f32>) {
        let grid = cloth.grid;
        let chords = Chords::new(&grid, cloth.pinning);
        let density = cloth.coefficients.density;
        let (span, across, chord) = match cloth.pinning {
            Pinning::PoleColumn => (grid.height, grid.row_spacing(), grid.segment()),
            Pinning::TopRow => (grid.width, grid.segment(), grid.row_spacing()),
        };
        let n = grid.rows * grid.columns;
        let mut carried = vec![0.0; n];
        let mut added_mass = vec![0.0; n];
        let mut spread = Vec::with_capacity(chords.count);
        for yarn in 0..chords.count {
            let middle = yarn as f32 * across - 0.5 * span;
            let per_length =
                carried_air(density, span, middle - 0.5 * across, middle + 0.5 * across);
            // The strip's semi-span √(R² − y²), averaged over it: its carried air per area
            // over 2 ρ (the edge strips reach only half a spacing past their yarn).
            let width =
                (middle + 0.5 * across).min(0.5 * span) - (middle - 0.5 * across).max(-0.5 * span);
            let semi_span = per_length / (2.0 * density * width);
            let a = (semi_span / chord).powi(2);
            spread.push(if a.is_finite() { a.min(1e12) } else { 0.0 });
            for s in 0..chords.length {
                let i = chords.node(yarn, s);
                let share = if s == 0 || s + 1 == chords.length {
                    0.5
                } else {
                    1.0
                };
                let m_a = per_length * chord * share;
                carried[i] = per_length;
                added_mass[i] = if m_a.is_finite() { m_a } else { 0.0 };
            }
        }
        let air = Self {
            chords,
            held: cloth.inverse_mass.iter().map(|w| *w == 0.0).collect(),
            carried,
            inertia: added_mass.iter().map(|m_a| cloth.node_mass + m_a).collect(),
            along: vec![0.0; n],
            after: vec![0.0; n],
            turned: vec![0.0; n],
            spread,
            upper: vec![0.0; chords.length],
            inverse: vec![0.0; chords.length],
            right: vec![0.0; chords.length],
            w: vec![0.0; chords.length],
            line: vec![0.0; chords.length],
            corrected: vec![0.0; chords.length],
            smoothing: Vec::new(),
            guarded: 0,
        };
        (air, added_mass)
    }

    /// Each node's air speed along its yarn away from the pin, U = (u − v) · τ, τ the yarn's
    /// unit tangent (from the neighbours along it; one-sided at the ends).
    pub fn measure(&mut self, positions: &[Vec3], velocities: &[Vec3], wind: &[Vec3]) {
        let chords = self.chords;
        for yarn in 0..chords.count {
            for s in 0..chords.length {
                let i = chords.node(yarn, s);
                let ahead = chords.node(yarn, (s + 1).min(chords.length - 1));
                let behind = chords.node(yarn, s.saturating_sub(1));
                let tangent = (positions[ahead] - positions[behind]).normalize_or_zero();
                let speed = (wind[i] - velocities[i]).dot(tangent);
                self.along[i] = if speed.is_finite() { speed } else { 0.0 };
            }
        }
    }

    /// The screen along `yarn`: the air enters it by the end its speed along the yarn points
    /// from, on the whole; past that end the screened velocity falls to zero, past the other
    /// its flux does.
    fn screen(&self, yarn: usize) -> Screen {
        let chords = self.chords;
        let entering_first = (0..chords.length)
            .map(|s| self.along[chords.node(yarn, s)])
            .sum::<f32>()
            >= 0.0;
        Screen {
            rows: 1,
            columns: chords.length,
            along_rows: self.spread[yarn],
            along_columns: 0.0,
            free_rows: (entering_first, !entering_first),
            free_columns: (false, false),
        }
    }

    /// The wind's share of each node's turn, u · (n_new − n_old) (m/s), screened along the
    /// yarns as the flux is (the Coriolis-like half of Lighthill's −2 m̃ U ∂ₓ∂ₜy, whose other
    /// half the flux carries): into [`Self::turned`].
    pub fn turn(&mut self, wind: &[Vec3], old: &[Vec3], new: &[Vec3]) {
        let chords = self.chords;
        for yarn in 0..chords.count {
            for s in 0..chords.length {
                let i = chords.node(yarn, s);
                let value = wind[i].dot(new[i] - old[i]);
                self.line[s] = if value.is_finite() { value } else { 0.0 };
            }
            let screen = self.screen(yarn);
            screen.smooth(&mut self.line, &mut self.smoothing);
            for s in 0..chords.length {
                self.turned[chords.node(yarn, s)] = self.line[s];
            }
        }
    }

    /// What [`Self::turn`] left: each node's screened u · Δn.
    pub fn turned(&self) -> &[f32] {
        &self.turned
    }

    /// The normal velocities relative to the air after the air's force.
    pub fn after(&self) -> &[f32] {
        &self.after
    }

    /// Pivots that were not positive and finite (each replaced by its diagonal) so far.
    pub fn guarded_pivots(&self) -> u64 {
        self.guarded
    }

    /// A substep of `h` under the reactive force and the resistive drag (rates `drag`, kg/s)
    /// from the normal velocities relative to the air `relative` (m/s): the velocities after
    /// into [`Self::after`], the force on each node into `force` (N, positive against its
    /// normal; a pinned node's goes into the pin).
    pub fn solve(&mut self, h: f32, drag: &[f32], relative: &[f32], force: &mut [f32]) {
        let chords = self.chords;
        let n = chords.length;
        for yarn in 0..chords.count {
            let node = |s: usize| chords.node(yarn, s);
            let (held, along, carried, inertia) =
                (&self.held, &self.along, &self.carried, &self.inertia);
            let rate = |i: usize| {
                let r = (along[i].abs() * carried[i]).min(MOST_RATE);
                if r.is_finite() { r } else { 0.0 }
            };
            let downstream = |i: usize| if along[i] > 0.0 { rate(i) } else { 0.0 };
            let upstream = |i: usize| if along[i] < 0.0 { rate(i) } else { 0.0 };
            // The flux of U m̃ q out of node s less what flows in from upwind.
            let flux = |q: &[f32], s: usize| {
                let mut value = rate(node(s)) * q[s];
                if s > 0 {
                    value -= downstream(node(s - 1)) * q[s - 1];
                }
                if s + 1 < n {
                    value -= upstream(node(s + 1)) * q[s + 1];
                }
                value
            };
            let lower = |s: usize| {
                if s == 0 || held[node(s)] {
                    0.0
                } else {
                    -h * downstream(node(s - 1))
                }
            };
            // (M + h K + h D) by Thomas' algorithm, D the upwind flux difference; pinned rows
            // keep w*.
            let mut upper_before = 0.0f32;
            for s in 0..n {
                let i = node(s);
                let (diagonal, up) = if held[i] {
                    (1.0, 0.0)
                } else {
                    let up = if s + 1 < n {
                        -h * upstream(node(s + 1))
                    } else {
                        0.0
                    };
                    (inertia[i] + h * (drag[i] + rate(i)).min(MOST_RATE), up)
                };
                let mut pivot = diagonal - lower(s) * upper_before;
                if !(pivot > 0.0 && pivot.is_finite()) {
                    self.guarded += 1;
                    pivot = diagonal;
                }
                self.inverse[s] = 1.0 / pivot;
                self.upper[s] = up * self.inverse[s];
                self.right[s] = if held[i] {
                    relative[i]
                } else {
                    inertia[i] * relative[i]
                };
                upper_before = self.upper[s];
            }
            let (upper, inverse) = (&self.upper, &self.inverse);
            let solve = |right: &[f32], w: &mut [f32]| {
                let mut before = 0.0f32;
                for s in 0..n {
                    w[s] = (right[s] - lower(s) * before) * inverse[s];
                    before = w[s];
                }
                for s in (0..n.saturating_sub(1)).rev() {
                    w[s] -= upper[s] * w[s + 1];
                }
                for v in w.iter_mut() {
                    if !v.is_finite() {
                        *v = 0.0;
                    }
                }
            };
            solve(&self.right, &mut self.w);
            // The air enters the yarn by the end its speed along the yarn points from, on the
            // whole: past that end the screened velocity falls to zero, past the other its flux.
            let screen = self.screen(yarn);
            for _ in 0..SCREEN_SOLVES {
                self.line.copy_from_slice(&self.w);
                screen.smooth(&mut self.line, &mut self.smoothing);
                for (l, w) in self.line.iter_mut().zip(&self.w) {
                    *l -= w;
                }
                // The right side less h D (S − I) w.
                for s in 0..n {
                    self.corrected[s] = if held[node(s)] {
                        self.right[s]
                    } else {
                        self.right[s] - h * flux(&self.line, s)
                    };
                }
                solve(&self.corrected, &mut self.w);
            }
            self.line.copy_from_slice(&self.w);
            screen.smooth(&mut self.line, &mut self.smoothing);
            for s in 0..n {
                let i = node(s);
                self.after[i] = self.w[s];
                let value = flux(&self.line, s) + drag[i] * self.w[s];
                force[i] = if value.is_finite() { value } else { 0.0 };
            }
        }
    }
}

/// The air a strip of a flat plate of span `span` carries per length of chord, kg/m, between
/// `from` and `to` measured from the middle of the span: ∫ 2 ρ √(R² − y²) dy over the part
/// within the span (R = span / 2). In portable arithmetic (the same bits everywhere).
fn carried_air(density: f32, span: f32, from: f32, to: f32) -> f32 {
    let radius = 0.5 * span;
    // ∫₋ᵣʸ √(R² − t²) dt = ½ (y √(R² − y²) + R² asin(y / R)) + π R² / 4, asin = π/2 − acos.
    let primitive = |y: f32| {
        let y = y.clamp(-radius, radius);
        let ratio = (y / radius).clamp(-1.0, 1.0);
        let arcsine = std::f32::consts::FRAC_PI_2 - crate::portable::transcendental::acos(ratio);
        y * (radius * radius - y * y).max(0.0).sqrt() + radius * radius * arcsine
    };
    let value = density * (primitive(to) - primitive(from));
    if value.is_finite() {
        value.max(0.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_strips_carry_a_plates_air_on_any_grid() {
        // ρ π H² / 4 in all, however many strips.
        for strips in [1usize, 7, 24, 200] {
            let span = 1.3f32;
            let width = span / strips as f32;
            let total: f32 = (0..strips)
                .map(|k| {
                    let from = -0.5 * span + k as f32 * width;
                    carried_air(1.2, span, from, from + width)
                })
                .sum();
            let exact = 1.2 * std::f32::consts::PI * span * span / 4.0;
            assert!(
                (total / exact - 1.0).abs() < 1e-4,
                "{strips}: {total} vs {exact}"
            );
        }
    }
}
