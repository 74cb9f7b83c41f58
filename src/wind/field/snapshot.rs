//! A field's snapshot taken, and a field rebuilt from one (see [`WindSnapshot`]).

use super::WindField;
use crate::error::InvalidValue;
use crate::wind::error::WindError;
use crate::wind::snapshot::WindSnapshot;

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
            taken_in: self.taken_in.clone(),
            settings: None,
            rebuild: None,
            rebuild_steps_left: 0,
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
            InvalidValue::check(value.is_finite(), field, value as f32, "must be finite")?;
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
        field.taken_in.clone_from(&snapshot.taken_in);
        Ok(field)
    }
}
