//! Guards against hostile numbers, shared by every domain: unit vectors of any finite length
//! and the bounds a pose must respect.

use bevy::math::{Quat, Vec2, Vec3};

use crate::error::reason;

/// Largest coordinate, m, a simulated pose may have. Beyond it an f32 position cannot resolve a
/// metre (its spacing exceeds 1 m at 1.7e7), far past any motion this crate makes, and products
/// of positions would overflow long before f32::MAX.
pub const MAX_COORDINATE: f32 = 1.0e7;

/// The unit vector along `v` for any finite non-zero length, from subnormal to `f32::MAX`: it is
/// divided by its largest component first, so its squared length can neither overflow nor
/// underflow. `None` for a zero or non-finite vector.
pub(crate) fn unit_vec2(v: Vec2) -> Option<Vec2> {
    let largest = v.abs().max_element();
    if !v.is_finite() || largest == 0.0 {
        return None;
    }
    (v / largest).try_normalize()
}

/// [`unit_vec2`] in three dimensions.
pub(crate) fn unit_vec3(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !v.is_finite() || largest == 0.0 {
        return None;
    }
    (v / largest).try_normalize()
}

/// `v` shortened to at most `max` long (overflow-safe: any finite `v`, even with components
/// near `f32::MAX`); zero for a non-finite `v`.
pub(crate) fn clamp_length(v: Vec3, max: f32) -> Vec3 {
    // The usual case, with no division: a finite vector whose squared length neither
    // underflows nor passes max².
    let squared = v.length_squared();
    if squared > 0.0 && squared <= max * max {
        return v;
    }
    let Some(unit) = unit_vec3(v) else {
        return Vec3::ZERO;
    };
    let largest = v.abs().max_element();
    if largest * (v / largest).length() > max {
        unit * max
    } else {
        v
    }
}

/// Why a position cannot start a simulation: `None` when it is finite and within
/// ±[`MAX_COORDINATE`] on every axis, otherwise the offending value (the component of the
/// largest magnitude, or NaN).
pub(crate) fn bad_position(p: Vec3) -> Option<f32> {
    let largest = largest_component(p);
    (largest.is_nan() || largest.abs() > MAX_COORDINATE).then_some(largest)
}

/// The component of `v` of the largest magnitude, with its sign (the first of equals), NaN if
/// any is NaN (glam's `max_element` passes over a NaN): the value an error about `v` names.
pub(crate) fn largest_component(v: Vec3) -> f32 {
    if v.is_nan() {
        return f32::NAN;
    }
    v.to_array()
        .into_iter()
        .fold(0.0f32, |m, c| if c.abs() > m.abs() { c } else { m })
}

/// The first component of `v` (x, y, z) that `ok` refuses, as a value an error can name.
pub(crate) fn first_refused(v: Vec3, ok: impl Fn(usize, f32) -> bool) -> Option<f32> {
    v.to_array()
        .into_iter()
        .enumerate()
        .find(|&(axis, c)| !ok(axis, c))
        .map(|(_, c)| c)
}

/// Why a global transform cannot place a simulation: `None` when it is finite, invertible
/// (|det| of its linear part ≥ 1e-18) and its translation within ±[`MAX_COORDINATE`];
/// otherwise the offending value (NaN, the determinant, or the coordinate).
pub(crate) fn bad_affine(affine: &bevy::math::Affine3A) -> Option<f32> {
    if !affine.is_finite() {
        return Some(f32::NAN);
    }
    let det = affine.matrix3.determinant();
    if !(det.abs() >= 1e-18 && det.is_finite()) {
        return Some(det);
    }
    bad_position(affine.translation.into())
}

/// What a global transform must be to place a simulation (the reason of a `transform` error).
pub(crate) fn transform_reason() -> &'static str {
    reason!(
        "the global transform must be finite, invertible and within ±MAX_COORDINATE ({MAX_COORDINATE:e} m)"
    )
}

/// What a position must be (the reason of a `position` error).
pub(crate) fn position_reason() -> &'static str {
    reason!("must be finite and within ±MAX_COORDINATE ({MAX_COORDINATE:e} m)")
}

/// What a ground height must be.
pub(crate) fn ground_reason() -> &'static str {
    reason!("must be within ±MAX_COORDINATE ({MAX_COORDINATE:e} m), or −∞ for no ground")
}

/// [`bad_affine`] as a check: the error names the field `transform`.
pub(crate) fn check_affine(
    affine: &bevy::math::Affine3A,
) -> Result<(), crate::error::InvalidValue> {
    match bad_affine(affine) {
        None => Ok(()),
        Some(value) => Err(crate::error::InvalidValue::new(
            "transform",
            value,
            transform_reason(),
        )),
    }
}

/// The rotation `q` describes, normalised, or `None` for a non-finite or zero quaternion (which
/// describes none).
pub(crate) fn unit_quat(q: Quat) -> Option<Quat> {
    let v = bevy::math::Vec4::from(q).to_array();
    let largest = v.iter().fold(0.0f32, |m, c| m.max(c.abs()));
    if !v.iter().all(|c| c.is_finite()) || largest == 0.0 {
        return None;
    }
    // Scaled, then normalised, each sum in one order (glam's SIMD sums pairwise).
    let [x, y, z, w] = v.map(|c| c / largest);
    let length = (((x * x + y * y) + z * z) + w * w).sqrt();
    let inv = 1.0 / length;
    (inv.is_finite() && inv > 0.0).then(|| Quat::from_xyzw(x * inv, y * inv, z * inv, w * inv))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_vectors_of_every_finite_length() {
        for scale in [1e-45f32, 1e-40, 1e-20, 1.0, 1e19, 1e30, f32::MAX] {
            let v = Vec3::new(3.0, -4.0, 0.0) * (scale / 5.0).max(f32::from_bits(1));
            let u = unit_vec3(v).unwrap_or_else(|| panic!("{scale}"));
            assert!((u.length() - 1.0).abs() < 1e-6, "{scale}: {u}");
            assert!(u.x > 0.0 && u.y < 0.0, "{scale}: {u}");
            let w = unit_vec2(Vec2::new(v.x, v.y)).unwrap();
            assert!((w.length() - 1.0).abs() < 1e-6);
        }
        assert_eq!(unit_vec3(Vec3::ZERO), None);
        assert_eq!(unit_vec3(Vec3::new(f32::INFINITY, 0.0, 0.0)), None);
        assert_eq!(unit_vec2(Vec2::new(f32::NAN, 1.0)), None);
        assert_eq!(unit_quat(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)), None);
        let q = unit_quat(Quat::from_xyzw(0.0, 1e-30, 0.0, 1e-30)).unwrap();
        assert!(q.is_normalized());
        assert_eq!(bad_position(Vec3::new(0.0, 2e7, 0.0)), Some(2e7));
        assert!(
            bad_position(Vec3::new(0.0, f32::NAN, 0.0))
                .unwrap()
                .is_nan()
        );
        assert_eq!(bad_position(Vec3::new(-1e6, 5.0, 1e6)), None);
    }
}
