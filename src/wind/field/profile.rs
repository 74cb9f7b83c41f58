//! Mean-wind profile and turbulence amplitudes of the neutral surface layer (free-fall paper §4.1).
//!
//! # How eq. 11–12 map onto the amplitudes used here
//! Eq. 11 is Kolmogorov's inertial-range spectrum `S_u(n) ∝ n^(−5/3)`; eq. 12 approximates its
//! level per axis as `A_u = u* (U(h)/h)^(2/3)`, `A_v = 0.88 A_u`, `A_w = 0.55 A_u`. The `A`s set
//! the *spectral shape's level* only up to the grid-dependent normalisation of the inverse FFT, so
//! a field built from them directly has a variance that changes with grid size and cell size. We
//! keep what eq. 11–12 fix physically and make it grid-independent:
//! - the shape, `S ∝ f^(−β)` along a line, β = 5/3 by default (eq. 11, 13);
//! - the per-axis ratios of eq. 12, applied to the standard deviations: σ_v = 0.88 σ_u,
//!   σ_w = 0.55 σ_u;
//! - the level, from surface-layer measurements: σ_u = I · U(h_ref) with turbulence intensity
//!   `I = 1/ln(h_ref/z0)` by default, which is exactly σ_u = u*/κ = 2.5 u* (κ = 0.40), the
//!   observed neutral value; the user may set `I` instead.
//!
//! Each turbulence component is a unit-variance fBm field times its σ.

/// σ_v / σ_u, cross-wind to along-wind (eq. 12).
pub(crate) const LATERAL_RATIO: f32 = 0.88;
/// σ_w / σ_u, vertical to along-wind (eq. 12).
pub(crate) const VERTICAL_RATIO: f32 = 0.55;

/// Friction velocity u* from a known mean speed at a known height: eq. 10 solved for u*,
/// `u* = κ U(h_ref) / ln(h_ref/z0)`. Needs `h_ref > z0 > 0`.
pub(crate) fn friction_velocity(
    reference_speed: f32,
    reference_height: f32,
    roughness: f32,
) -> f32 {
    super::WindField::VON_KARMAN * reference_speed / ln(reference_height / roughness)
}

/// Logarithmic wind law, eq. 10: `U(h) = (u*/κ) ln(h/z0)`, and 0 at or below z0 (and for a
/// non-finite height below the ground), never negative or NaN.
pub(crate) fn log_law(friction_velocity: f32, roughness: f32, height: f32) -> f32 {
    friction_velocity / super::WindField::VON_KARMAN * log_ratio(height, roughness)
}

/// Height scaling of eq. 14: `(ln h − ln z0) / (ln h0 − ln z0)`, clamped to 0 at or below z0.
/// It carries a wind sampled at height `h0` to height `h`.
#[cfg(test)]
fn height_factor(height: f32, plane_height: f32, roughness: f32) -> f32 {
    log_ratio(height, roughness) / log_ratio(plane_height, roughness)
}

/// Default turbulence intensity σ_u / U(h_ref) of the neutral surface layer: `1/ln(h_ref/z0)`.
pub(crate) fn surface_layer_intensity(reference_height: f32, roughness: f32) -> f32 {
    1.0 / ln(reference_height / roughness)
}

/// `max(0, ln(h/z0))`, finite for every input (`+∞` height is capped at `f32::MAX`).
pub(crate) fn log_ratio(height: f32, roughness: f32) -> f32 {
    if height > roughness {
        (ln(height.min(f32::MAX)) - ln(roughness)).max(0.0)
    } else {
        0.0
    }
}

/// The natural logarithm of the log law, in one place: the crate's portable `ln` (the same
/// bits on every machine and in the browser, where glibc's `logf` may differ in the last bit;
/// and the one the lanes of a batched read take).
#[inline]
pub(crate) fn ln(x: f32) -> f32 {
    ln_lanes(x)
}

/// [`ln`] for one number or for lanes.
#[inline(always)]
pub(crate) fn ln_lanes<L: crate::portable::lane::Lane>(x: L) -> L {
    crate::portable::transcendental::ln(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_law_round_trips_the_reference() {
        let u_star = friction_velocity(4.0, 10.0, 0.3);
        assert!((log_law(u_star, 0.3, 10.0) - 4.0).abs() < 1e-5);
        // u* = 0.4 · 4 / ln(33.3) = 0.456 m/s
        assert!((u_star - 0.4562).abs() < 1e-3);
    }

    #[test]
    fn no_wind_at_or_below_roughness_and_finite_everywhere() {
        let u_star = friction_velocity(4.0, 10.0, 0.3);
        for h in [0.3, 0.1, 0.0, -5.0, f32::NEG_INFINITY, f32::NAN] {
            assert_eq!(log_law(u_star, 0.3, h), 0.0, "h = {h}");
        }
        assert!(log_law(u_star, 0.3, f32::INFINITY).is_finite());
        assert!(log_law(u_star, 0.3, f32::MAX).is_finite());
    }

    #[test]
    fn default_intensity_gives_two_and_a_half_u_star() {
        let (h, z0, u) = (10.0, 0.3, 6.0);
        let sigma_u = surface_layer_intensity(h, z0) * u;
        assert!((sigma_u / friction_velocity(u, h, z0) - 2.5).abs() < 1e-4);
    }

    #[test]
    fn height_factor_is_one_at_the_plane() {
        assert!((height_factor(10.0, 10.0, 0.3) - 1.0).abs() < 1e-6);
        assert_eq!(height_factor(0.2, 10.0, 0.3), 0.0);
    }
}
