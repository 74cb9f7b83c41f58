//! Lift and drag on one face (the lift-and-drag paper's *Aerodynamics* section, after Stam and Fiume 1992).

use bevy::math::{DVec3, Vec3};

/// Drag plus lift on one face, N.
///
/// `v_rel` = v_face − u is the face's velocity relative to the fluid, `normal` the face's normal
/// (either side, any length), `area` in m², `drag` C_D, `lift` C_L, `density` ρ in kg/m³.
///
/// Our reading of the paper's damaged text around eq. 3.1:
/// - The face is two-sided: the normal is turned to the side the face moves toward,
///   n ← −n when n · v_rel < 0 (eq. 3.1), so c = n · v̂_rel ≥ 0.
/// - Drag F_D = ½ C_D ρ |v_rel|² A c (−v̂_rel): it opposes v_rel and never does positive work;
///   it is largest broadside (c = 1) and zero edge-on (c = 0).
/// - Lift F_L = ½ C_L ρ |v_rel|² A cos θ û with û = (n × v̂_rel) × v̂_rel = c v̂_rel − n, left
///   unnormalised (|û| = sin θ), and θ the angle between v_rel and the face's normal, so
///   cos θ = c. The lift is perpendicular to v_rel, lies in the plane of v_rel and n, and its
///   size ½ C_L ρ |v_rel|² A cos θ sin θ is zero both for flow along the face (θ = 90°) and
///   flow into it (θ = 0), largest at 45°: the flat-plate law. Reading θ as the angle to the
///   face itself, with û normalised, would give the largest lift for flow along the face.
///
/// Zero area, a zero or non-finite normal or velocity, or non-finite coefficients give zero.
/// Every finite normal works, from subnormal to `f32::MAX` long, and every finite velocity: the
/// law is evaluated in f64 and a force beyond f32's range is clamped to ±`f32::MAX` per axis
/// (never zeroed), so a hostile input still pushes the right way.
pub fn face_force(
    v_rel: Vec3,
    normal: Vec3,
    area: f32,
    drag: f32,
    lift: f32,
    density: f32,
) -> Vec3 {
    // With a = |n · v_rel| / |n| = cos θ |v_rel| and n' the normal turned toward v_rel:
    // F_D = −½ C_D ρ A a v_rel and F_L = ½ C_L ρ A a (a v̂_rel − |v_rel| n'): the formulas above,
    // with two square roots and one division. In f64 every f32 input squares without overflow or
    // underflow.
    let scale = 0.5 * f64::from(density) * f64::from(area);
    let (v, normal) = (v_rel.as_dvec3(), normal.as_dvec3());
    let n2 = normal.length_squared();
    let speed2 = v.length_squared();
    let finite = n2.is_finite() && speed2.is_finite() && drag.is_finite() && lift.is_finite();
    if !(finite && speed2 > 0.0 && n2 > 0.0 && scale > 0.0 && scale.is_finite()) {
        return Vec3::ZERO; // also false for NaN
    }
    let speed = speed2.sqrt();
    let inv_n = 1.0 / n2.sqrt();
    let along = normal.dot(v) * inv_n;
    let (a, n) = if along < 0.0 {
        (-along, -normal * inv_n)
    } else {
        (along, normal * inv_n)
    };
    let (drag, lift) = (f64::from(drag), f64::from(lift));
    let force = (scale * a) * (lift * (a / speed * v - speed * n) - drag * v);
    let most = f64::from(f32::MAX);
    if force.is_nan() {
        Vec3::ZERO
    } else {
        force
            .clamp(DVec3::splat(-most), DVec3::splat(most))
            .as_vec3()
    }
}

/// The rate k = ρ C_D A |v_rel| / m (1/s) at which drag relaxes a body of mass `mass` toward
/// the fluid; explicit integration is stable only for dt × k below about 2.
pub fn drag_rate(speed: f32, area: f32, drag: f32, density: f32, mass: f32) -> f32 {
    let k = density * drag.abs() * area * speed / mass;
    if k.is_finite() { k.max(0.0) } else { f32::MAX }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aero::AeroCoefficients;

    #[test]
    fn the_normal_may_have_any_finite_length() {
        let v = Vec3::new(2.0, -1.0, 0.5);
        let n = Vec3::new(0.3, 1.0, -0.2);
        let unit = face_force(v, n, 0.01, 1.2, 0.9, AeroCoefficients::AIR_DENSITY);
        assert!(unit.length() > 1e-4);
        for scale in [1e-37f32, 1e-30, 1e-19, 1e19, 1e30, f32::MAX / 2.0] {
            let f = face_force(v, n * scale, 0.01, 1.2, 0.9, AeroCoefficients::AIR_DENSITY);
            assert!(
                (f - unit).length() <= 1e-5 * unit.length(),
                "×{scale}: {f} vs {unit}"
            );
        }
        // A subnormal normal along an axis (its direction exact) acts as the unit one.
        let up = face_force(v, Vec3::Y, 0.01, 1.2, 0.9, AeroCoefficients::AIR_DENSITY);
        assert_eq!(
            face_force(
                v,
                Vec3::Y * 1e-44,
                0.01,
                1.2,
                0.9,
                AeroCoefficients::AIR_DENSITY
            ),
            up
        );
    }

    #[test]
    fn a_force_beyond_f32_is_clamped_not_dropped() {
        // Drag on a face moving at 1e30 m/s: far beyond f32, still finite and still opposing.
        let v = Vec3::new(1e30, 0.0, 0.0);
        let f = face_force(v, Vec3::X, 1.0, 1.0, 0.0, AeroCoefficients::WATER_DENSITY);
        assert_eq!(f, Vec3::new(-f32::MAX, 0.0, 0.0));
        for bad in [f32::NAN, f32::INFINITY] {
            assert_eq!(face_force(v, Vec3::X, 1.0, bad, 0.0, 1.0), Vec3::ZERO);
            assert_eq!(
                face_force(Vec3::splat(bad), Vec3::X, 1.0, 1.0, 0.0, 1.0),
                Vec3::ZERO
            );
        }
    }
}
