//! Everything that decides the wind's velocities, as one value to save or send.

use crate::error::InvalidValue;
use bevy::math::DVec2;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use super::config::WindConfig;
use super::ease::WindEasing;
use super::error::WindError;
use super::field::WindField;

/// The wind's settings (seed included) and its clock: all a second machine needs to blow the
/// same wind, bit for bit, as [`WindField::from_snapshot`] rebuilds it. With the `serde`
/// feature it serialises, so a game server can send it to its clients once (and again when the
/// settings change); velocities then agree without sending any (the crate's determinism is what
/// lockstep and rollback need). With serde_json enable its `float_roundtrip` feature, or the
/// clock may come back one bit off.
///
/// # Example
///
/// ```
/// use bevy::math::Vec3;
/// use bevy_windfall::wind::{WindConfig, WindField};
///
/// let mut server = WindField::new(WindConfig { grid: [32, 32], ..Default::default() })?;
/// server.advance(12.5);
/// server.ease_to(9.0, bevy::math::Vec2::Y, 3.0)?; // a storm building up, veering
/// server.advance(1.0);
/// let client = WindField::from_snapshot(&server.snapshot())?;
/// let p = Vec3::new(3.0, 2.0, -7.0);
/// assert_eq!(client.velocity(p), server.velocity(p));
/// let (mut server, mut client) = (server, client);
/// server.advance(0.5);
/// client.advance(0.5);
/// assert_eq!(client.velocity(p), server.velocity(p));
/// # Ok::<(), bevy_windfall::wind::WindError>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Reflect)]
#[reflect(Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WindSnapshot {
    /// The settings, seed included.
    pub config: WindConfig,
    /// The wind clock, s ([`WindField::time_f64`]).
    pub time: f64,
    /// [`WindField::time_scale`].
    pub time_scale: f32,
    /// [`WindField::paused`].
    pub paused: bool,
    /// How far the turbulence pattern had travelled (x, z, m at the reference speed) when the
    /// mean wind last changed speed or direction.
    #[cfg_attr(feature = "serde", serde(default))]
    pub drift: DVec2,
    /// The wind time of that change, s.
    #[cfg_attr(feature = "serde", serde(default))]
    pub drift_since: f64,
    /// A [`WindField::ease_to`] in progress.
    #[cfg_attr(feature = "serde", serde(default))]
    pub easing: Option<WindEasing>,
}

impl WindField {
    /// The field's settings and clock (see [`WindSnapshot`]).
    pub fn snapshot(&self) -> WindSnapshot {
        WindSnapshot {
            config: self.config().clone(),
            time: self.time_f64(),
            time_scale: self.time_scale,
            paused: self.paused,
            drift: self.drift_base,
            drift_since: self.drift_since,
            easing: self.easing(),
        }
    }

    /// Rebuilds the field a [`WindSnapshot`] describes: same velocities, bit for bit, at every
    /// point and time. A bad configuration or a non-finite clock is a typed error naming it.
    pub fn from_snapshot(snapshot: &WindSnapshot) -> Result<Self, WindError> {
        for (field, value) in [
            ("time", snapshot.time),
            ("time_scale", f64::from(snapshot.time_scale)),
            ("drift", snapshot.drift.x + snapshot.drift.y),
            ("drift_since", snapshot.drift_since),
        ] {
            if !value.is_finite() {
                return Err(WindError::Invalid(InvalidValue {
                    field,
                    value: value as f32,
                    reason: "must be finite",
                }));
            }
        }
        let mut field = WindField::new(snapshot.config.clone())?;
        field.set_clock(snapshot.time);
        field.time_scale = snapshot.time_scale;
        field.paused = snapshot.paused;
        field.drift_base = snapshot.drift;
        field.drift_since = snapshot.drift_since;
        if let Some(easing) = &snapshot.easing {
            field.resume_easing(easing)?;
        }
        Ok(field)
    }
}
