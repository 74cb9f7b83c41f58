//! Lift and drag on one face (`aerodynamic-lift-and-drag.txt`, after Stam and Fiume 1992).

use bevy::math::Vec3;

/// Air at about 20 °C, kg/m³.
pub const AIR_DENSITY: f32 = 1.204;
/// Water at 25 °C, kg/m³.
pub const WATER_DENSITY: f32 = 997.0;

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
    // with two square roots and one division.
    let scale = 0.5 * density * area;
    let n2 = normal.length_squared();
    let speed2 = v_rel.length_squared();
    if !(speed2 > 0.0 && n2 > 0.0 && scale > 0.0) {
        return Vec3::ZERO; // also false for NaN
    }
    let speed = speed2.sqrt();
    let inv_n = 1.0 / n2.sqrt();
    let along = normal.dot(v_rel) * inv_n;
    let (a, n) = if along < 0.0 {
        (-along, -normal * inv_n)
    } else {
        (along, normal * inv_n)
    };
    let force = (scale * a) * (lift * (a / speed * v_rel - speed * n) - drag * v_rel);
    if force.is_finite() { force } else { Vec3::ZERO }
}

/// The rate k = ρ C_D A |v_rel| / m (1/s) at which drag relaxes a body of mass `mass` toward
/// the fluid; explicit integration is stable only for dt × k below about 2.
pub fn drag_rate(speed: f32, area: f32, drag: f32, density: f32, mass: f32) -> f32 {
    let k = density * drag.abs() * area * speed / mass;
    if k.is_finite() { k.max(0.0) } else { f32::MAX }
}
