//! The air a moving body pushes: potential flow round a sphere in front and at the sides, a
//! self-similar turbulent wake behind, and the ground as a mirror. Pure arithmetic (IEEE `+ − × ÷`
//! and `sqrt`, no library function), so the same bits on every platform.
//!
//! - **Potential flow** (Lamb, *Hydrodynamics*, §92; Batchelor, *An Introduction to Fluid
//!   Dynamics*, §6.8): a sphere of radius R moving at V through still air sets it moving at
//!   u = (R³ / 2r³) (3 (V · r̂) r̂ − V), a dipole: at the nose and the tail u = V (the air is
//!   pushed along), at the sides u = −V/2 (it slips back round the body), falling as 1/r³. It
//!   meets the body's boundary condition u · n = V · n on the sphere. Inside the sphere the
//!   value on its surface along the same ray is used (the air a player stands in is the air it
//!   carries), so |u| ≤ |V| everywhere. It fades to zero between 5 R and 8 R (at 5 R it is
//!   at most 0.8 % of V).
//! - **Ground** (method of images, Milne-Thomson, *Theoretical Hydrodynamics*, §16.50): a second
//!   dipole mirrored in the ground plane, with the vertical part of V reversed, so no air flows
//!   through the ground; it doubles the flow along the ground under a low body (what lifts
//!   leaves). It fades out as the body rises from 2 R to 4 R above the ground.
//! - **Wake** (Tennekes & Lumley, *A First Course in Turbulence*, §4.2; Pope, *Turbulent Flows*,
//!   §5.5): behind a bluff body the air is dragged along V. Far downstream the axisymmetric wake
//!   is self-similar: its centre-line speed falls as x^−2/3 and its width grows as x^1/3, so
//!   the momentum it carries, ρ U ∫ u dA, stays the body's drag ½ ρ U² C_D π R². Here
//!   u_c = c_u U ξ^−2/3 and the half width b = c_b D ξ^1/3 with ξ = x / D + 1 (D = 2R, the
//!   virtual origin one diameter upstream so the wake starts as wide as the body), c_b = ½, and
//!   c_u = C_D / (8 c_b²) from the momentum, C_D = 0.47 (a sphere at Re 10⁴–10⁵, Achenbach
//!   1972). The profile across it is (1 − ρ²/a²)², a = √3 b (the same momentum as a Gaussian
//!   of width b, but nothing beyond a); it grows in over the body's rear half and fades between
//!   12 R and 20 R behind the centre (six and ten diameters).
//!
//! Everything is zero beyond [`MoverFlow::REACH_RADII`] radii from the body's centre, so a
//! read far from every body costs one distance test per body.

use bevy::math::Vec3;

use super::super::local::fade;

/// Drag coefficient of the body the wake carries the momentum of: a sphere's (Achenbach 1972).
const DRAG_COEFFICIENT: f32 = 0.47;

/// The wake's half width at its virtual origin, in body diameters.
const WAKE_WIDTH: f32 = 0.5;

/// The wake's centre-line speed at its virtual origin, as a share of the body's speed: fixed by
/// its momentum, C_D / (8 c_b²).
const WAKE_SPEED: f32 = DRAG_COEFFICIENT / (8.0 * WAKE_WIDTH * WAKE_WIDTH);

/// The potential flow is the dipole up to this many radii, then fades to zero at
/// [`DIPOLE_END`].
const DIPOLE_FULL: f32 = 5.0;
const DIPOLE_END: f32 = 8.0;

/// The wake is whole up to this many radii behind the centre, then fades to zero at
/// [`WAKE_END`].
const WAKE_FULL: f32 = 12.0;
const WAKE_END: f32 = 20.0;

/// The ground's mirror image counts in full up to this height of the body's centre above the
/// ground (radii), then fades out by [`MIRROR_END`].
const MIRROR_FULL: f32 = 2.0;
const MIRROR_END: f32 = 4.0;

/// √3: the compact profile's edge for the momentum of a Gaussian of width b.
const SQRT_3: f32 = 1.732_050_8;

/// A moving body's flow for one fixed step: where it is, how fast it moves and how big it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MoverFlow {
    /// The body's centre, world frame, m.
    pub(crate) centre: Vec3,
    /// Its velocity (times its strength), m/s.
    pub(crate) velocity: Vec3,
    /// Its radius, m (> 0).
    pub(crate) radius: f32,
    /// Height of the ground plane, m.
    pub(crate) ground: f32,
    /// How much of the mirror image counts, in [0, 1] (0 with no ground or far above it).
    pub(crate) mirror: f32,
    /// ([`MoverFlow::REACH_RADII`] × radius)².
    pub(crate) reach2: f32,
}

/// 1 up to `inner`, then fading smoothly to 0 at `outer`.
fn plateau(x: f32, inner: f32, outer: f32) -> f32 {
    if x <= inner {
        1.0
    } else {
        fade((x - inner) / (outer - inner))
    }
}

/// ∛x for x in [1, 11] by Newton's iteration from above (a fixed count: the same bits
/// everywhere; five steps reach f32's precision from (x + 2) / 3 on that range).
fn cube_root(x: f32) -> f32 {
    let mut t = (x + 2.0) / 3.0;
    for _ in 0..5 {
        t -= (t * t * t - x) / (3.0 * t * t);
    }
    t
}

impl MoverFlow {
    /// Nothing reaches further than this many radii from the centre: the wake's far corner
    /// (20 R behind, 3.9 R wide) and the mirror's dipole (8 R round an image at most 8 R below).
    pub(crate) const REACH_RADII: f32 = 20.5;

    /// The flow of a body of `radius` at `centre` moving at `velocity` over the ground at height
    /// `ground` (−∞: none). `None` when it blows nothing (standing still, or a radius or
    /// position that is not a positive finite number).
    pub(crate) fn new(centre: Vec3, velocity: Vec3, radius: f32, ground: f32) -> Option<Self> {
        let moving = velocity != Vec3::ZERO && velocity.is_finite();
        let ok = radius > 0.0 && radius.is_finite() && centre.is_finite();
        if !(moving && ok) {
            return None;
        }
        let height = (centre.y - ground) / radius;
        let mirror = if ground.is_finite() && height > 0.0 {
            plateau(height, MIRROR_FULL, MIRROR_END)
        } else {
            0.0
        };
        let reach = Self::REACH_RADII * radius;
        Some(Self {
            centre,
            velocity,
            radius,
            ground: if ground.is_finite() { ground } else { 0.0 },
            mirror,
            reach2: reach * reach,
        })
    }

    /// The velocity the body adds at `p`, m/s: the dipole, its mirror image and the wake.
    #[inline]
    pub(crate) fn velocity(&self, p: Vec3) -> Vec3 {
        let d = p - self.centre;
        let r2 = d.length_squared();
        if r2.is_nan() || r2 >= self.reach2 {
            return Vec3::ZERO;
        }
        let (v, radius) = (self.velocity, self.radius);
        let mut u = dipole(d, v, radius);
        if self.mirror > 0.0 {
            let image = Vec3::new(
                self.centre.x,
                2.0 * self.ground - self.centre.y,
                self.centre.z,
            );
            let turned = Vec3::new(v.x, -v.y, v.z);
            u += dipole(p - image, turned, radius) * self.mirror;
        }
        u + wake(d, v, radius)
    }
}

/// The potential flow round a sphere of `radius` moving at `v`, at `d` from its centre.
fn dipole(d: Vec3, v: Vec3, radius: f32) -> Vec3 {
    let r2 = d.length_squared();
    let end = DIPOLE_END * radius;
    if r2.is_nan() || r2 >= end * end {
        return Vec3::ZERO;
    }
    if r2 == 0.0 {
        return v;
    }
    let r = r2.sqrt();
    let direction = d / r;
    // (R / r)³, at most 1: the surface's value inside the body.
    let s = (radius / r).min(1.0);
    let share = 0.5 * s * s * s * plateau(r, DIPOLE_FULL * radius, end);
    (direction * (3.0 * v.dot(direction)) - v) * share
}

/// The wake behind a body of `radius` moving at `v`, at `d` from its centre.
fn wake(d: Vec3, v: Vec3, radius: f32) -> Vec3 {
    let speed2 = v.length_squared();
    if speed2 == 0.0 {
        return Vec3::ZERO;
    }
    let speed = speed2.sqrt();
    let along = v / speed;
    // How far behind the centre, and how far off the wake's axis (squared).
    let behind = -d.dot(along);
    if !(behind > 0.0 && behind < WAKE_END * radius) {
        return Vec3::ZERO;
    }
    let aside2 = (d + along * behind).length_squared();
    let diameter = 2.0 * radius;
    let root = cube_root(behind / diameter + 1.0);
    let edge = SQRT_3 * WAKE_WIDTH * diameter * root;
    let across = aside2 / (edge * edge);
    if across.is_nan() || across >= 1.0 {
        return Vec3::ZERO;
    }
    let profile = (1.0 - across) * (1.0 - across);
    // Grows in over the body's rear half (from its sides to its tail), fades out far behind.
    let onset = if behind < radius {
        1.0 - fade(behind / radius)
    } else {
        1.0
    };
    let tail = plateau(behind, WAKE_FULL * radius, WAKE_END * radius);
    along * (WAKE_SPEED * speed / (root * root) * profile * onset * tail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_root_is_exact_enough_on_its_range() {
        for i in 0..=160 {
            let x = 1.0 + i as f32 * 0.0625;
            let t = cube_root(x);
            assert!((t * t * t - x).abs() < 4e-6 * x, "{x}: {t}");
        }
    }

    #[test]
    fn bounded_by_the_body_speed_and_compact() {
        let v = Vec3::new(7.0, -1.0, 2.0);
        let flow = MoverFlow::new(Vec3::new(1.0, 0.8, -2.0), v, 0.5, 0.0).unwrap();
        let mut most = 0.0f32;
        for i in 0..20_000u32 {
            // A scatter of points out to 10 m.
            let h = |k: u32| (i.wrapping_mul(2_654_435_761).rotate_left(k) % 10_000) as f32;
            let p = flow.centre + Vec3::new(h(0), h(11), h(22)) * 2e-3 - Vec3::splat(10.0);
            let u = flow.velocity(p);
            assert!(u.is_finite());
            most = most.max(u.length());
            if (p - flow.centre).length() > MoverFlow::REACH_RADII * 0.5 {
                assert_eq!(u, Vec3::ZERO);
            }
        }
        // The dipole and its image at most |V| each, the wake at most c_u |V|.
        assert!(most <= (2.0 + WAKE_SPEED) * v.length(), "{most}");
        assert!(MoverFlow::new(Vec3::ZERO, Vec3::ZERO, 0.5, 0.0).is_none());
        assert!(MoverFlow::new(Vec3::ZERO, Vec3::X, 0.0, 0.0).is_none());
        assert!(MoverFlow::new(Vec3::ZERO, Vec3::X, f32::NAN, 0.0).is_none());
    }
}
