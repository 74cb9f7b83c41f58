//! Vectors and quaternions of [`Lane`]s with every operation in one fixed order: glam's own
//! quaternion product and normalisation sum their terms pairwise with SSE2 and in a row
//! without, so their last bits differ between a desktop and a browser. These do not.

use bevy::math::{Quat, Vec3};

use super::lane::Lane;
use super::transcendental::{acos, sin_cos};

/// A vector of lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct V3<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lane> V3<L> {
    #[inline(always)]
    pub fn new(x: L, y: L, z: L) -> Self {
        Self { x, y, z }
    }

    #[inline(always)]
    pub fn splat(v: Vec3) -> Self {
        Self::new(L::splat(v.x), L::splat(v.y), L::splat(v.z))
    }

    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }

    #[inline(always)]
    pub fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }

    #[inline(always)]
    pub fn scale(self, k: L) -> Self {
        Self::new(self.x * k, self.y * k, self.z * k)
    }

    /// (x² + y²) + z².
    #[inline(always)]
    pub fn length_squared(self) -> L {
        (self.x * self.x + self.y * self.y) + self.z * self.z
    }

    /// `a` where `mask`, else `b`.
    #[inline(always)]
    pub fn select(mask: L::Mask, a: Self, b: Self) -> Self {
        Self::new(
            L::select(mask, a.x, b.x),
            L::select(mask, a.y, b.y),
            L::select(mask, a.z, b.z),
        )
    }
}

/// A quaternion of lanes, (x, y, z, w).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Q<L> {
    pub x: L,
    pub y: L,
    pub z: L,
    pub w: L,
}

impl<L: Lane> Q<L> {
    #[inline(always)]
    pub fn new(x: L, y: L, z: L, w: L) -> Self {
        Self { x, y, z, w }
    }

    #[inline(always)]
    pub fn identity() -> Self {
        Self::new(L::splat(0.0), L::splat(0.0), L::splat(0.0), L::splat(1.0))
    }

    /// The Hamilton product `self · o`, each component in one fixed order.
    #[inline(always)]
    pub fn mul(self, o: Self) -> Self {
        let (x0, y0, z0, w0) = (self.x, self.y, self.z, self.w);
        let (x1, y1, z1, w1) = (o.x, o.y, o.z, o.w);
        Self::new(
            ((w0 * x1 + x0 * w1) + y0 * z1) - z0 * y1,
            ((w0 * y1 - x0 * z1) + y0 * w1) + z0 * x1,
            ((w0 * z1 + x0 * y1) - y0 * x1) + z0 * w1,
            ((w0 * w1 - x0 * x1) - y0 * y1) - z0 * z1,
        )
    }

    /// ((x² + y²) + z²) + w².
    #[inline(always)]
    pub fn length_squared(self) -> L {
        ((self.x * self.x + self.y * self.y) + self.z * self.z) + self.w * self.w
    }

    /// Divided by its length (a zero quaternion stays zero, as glam's gives NaN: callers keep
    /// their quaternions of unit length).
    #[inline(always)]
    pub fn normalize(self) -> Self {
        let length = self.length_squared().sqrt();
        let inv = L::select(
            length.gt(L::splat(0.0)),
            L::splat(1.0) / length,
            L::splat(0.0),
        );
        Self::new(self.x * inv, self.y * inv, self.z * inv, self.w * inv)
    }

    /// The rotation by `angle` about the unit `axis` (x, y, z).
    #[inline(always)]
    pub fn from_axis_angle(axis: V3<L>, angle: L) -> Self {
        let (s, c) = sin_cos(angle * L::splat(0.5));
        Self::new(axis.x * s, axis.y * s, axis.z * s, c)
    }

    /// `a` where `mask`, else `b`.
    #[inline(always)]
    pub fn select(mask: L::Mask, a: Self, b: Self) -> Self {
        Self::new(
            L::select(mask, a.x, b.x),
            L::select(mask, a.y, b.y),
            L::select(mask, a.z, b.z),
            L::select(mask, a.w, b.w),
        )
    }

    /// The conjugate: the inverse of a unit quaternion.
    #[inline(always)]
    pub fn conjugate(self) -> Self {
        Self::new(-self.x, -self.y, -self.z, self.w)
    }

    /// `v` turned by this unit quaternion: v (w² − b·b) + b 2(v·b) + (b × v) 2w, b = (x, y, z).
    #[inline(always)]
    pub fn rotate(self, v: V3<L>) -> V3<L> {
        let b = V3::new(self.x, self.y, self.z);
        let two = L::splat(2.0);
        let b2 = b.length_squared();
        let vb = (v.x * b.x + v.y * b.y) + v.z * b.z;
        let cross = V3::new(
            b.y * v.z - b.z * v.y,
            b.z * v.x - b.x * v.z,
            b.x * v.y - b.y * v.x,
        );
        v.scale(self.w * self.w - b2)
            .add(b.scale(vb * two))
            .add(cross.scale(self.w * two))
    }

    /// The rotation by `angle` about +Y.
    #[inline(always)]
    pub fn from_rotation_y(angle: L) -> Self {
        let (s, c) = sin_cos(angle * L::splat(0.5));
        let zero = L::splat(0.0);
        Self::new(zero, s, zero, c)
    }
}

impl Q<f32> {
    /// The spherical interpolation from `self` to `end` by `s` (the short way; a normalised
    /// lerp where they nearly agree), as glam's, in portable arithmetic.
    pub fn slerp(self, end: Self, s: f32) -> Self {
        let mut dot = ((self.x * end.x + self.y * end.y) + self.z * end.z) + self.w * end.w;
        let end = if dot < 0.0 {
            dot = -dot;
            Self::new(-end.x, -end.y, -end.z, -end.w)
        } else {
            end
        };
        let blend = |a: f32, b: f32| (a, b);
        let (a, b) = if dot > 1.0 - f32::EPSILON {
            blend(1.0 - s, s)
        } else {
            let theta = acos(dot);
            let inv = 1.0 / sin_cos(theta).0;
            blend(
                sin_cos(theta * (1.0 - s)).0 * inv,
                sin_cos(theta * s).0 * inv,
            )
        };
        let q = Self::new(
            self.x * a + end.x * b,
            self.y * a + end.y * b,
            self.z * a + end.z * b,
            self.w * a + end.w * b,
        );
        if dot > 1.0 - f32::EPSILON {
            q.normalize()
        } else {
            q
        }
    }
}

impl V3<f32> {
    pub fn vec3(self) -> Vec3 {
        Vec3::new(self.x, self.y, self.z)
    }

    pub fn of(v: Vec3) -> Self {
        Self::new(v.x, v.y, v.z)
    }
}

impl Q<f32> {
    pub fn quat(self) -> Quat {
        Quat::from_xyzw(self.x, self.y, self.z, self.w)
    }

    pub fn of(q: Quat) -> Self {
        Self::new(q.x, q.y, q.z, q.w)
    }
}
