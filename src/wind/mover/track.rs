//! Following each [`WindMover`] from fixed step to fixed step: its velocity from where its
//! transform puts it, and its flow placed in the [`WindField`].

use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::time::Time;

use super::super::field::WindField;
use super::super::placement::{Hierarchy, in_entity_order, world_place};
use super::{MoverFlow, WindMover, WindMoverInvalid};
use crate::lifecycle::mark_on_change;

/// Where a [`WindMover`] was at the last two fixed steps (latest first); `None` before it was
/// seen, after a teleport or where its transform placed it nowhere.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct MoverTrail {
    seen: [Option<Vec3>; 2],
}

impl MoverTrail {
    /// Records the centre `at` (None: nowhere) after a fixed step of `dt` seconds and returns
    /// the velocity: over the last two steps where both moves were steps of at most
    /// `teleport` m, over the last one just after it appeared or teleported, zero on the
    /// first step and after a teleport.
    pub(crate) fn record(&mut self, at: Option<Vec3>, dt: f32, teleport: f32) -> Vec3 {
        if !(dt > 0.0 && dt.is_finite()) {
            return Vec3::ZERO;
        }
        let Some(at) = at else {
            self.seen = [None, None];
            return Vec3::ZERO;
        };
        let [last, before] = self.seen;
        let step = last.map(|last| at - last);
        let Some(step) = step.filter(|s| s.length() <= teleport) else {
            self.seen = [Some(at), None];
            return Vec3::ZERO;
        };
        self.seen = [Some(at), last];
        let velocity = match before {
            Some(before) => (at - before) / (2.0 * dt),
            None => step / dt,
        };
        if velocity.is_finite() {
            velocity
        } else {
            Vec3::ZERO
        }
    }
}

/// What following a mover reads.
type MoverParts = (
    Entity,
    &'static WindMover,
    &'static mut MoverTrail,
    Option<&'static WindMoverInvalid>,
);

/// Whether [`place_wind_movers`] has work: a field, and a mover to follow or placed flows to
/// clear.
pub(crate) fn anything_moving(
    movers: Query<(), With<WindMover>>,
    wind: Option<Res<WindField>>,
) -> bool {
    wind.is_some_and(|w| !(movers.is_empty() && w.mover_count() == 0))
}

/// Follows every [`WindMover`] over this fixed step (of the schedule's clock) and places the
/// flows of those that move in the [`WindField`], in entity order. One that cannot be placed
/// gets a [`WindMoverInvalid`] and makes no wind (its motion is counted afresh once it can).
pub(crate) fn place_wind_movers(
    mut commands: Commands,
    time: Res<Time>,
    mut wind: ResMut<WindField>,
    mut movers: Query<MoverParts>,
    hierarchy: Hierarchy,
) {
    let dt = time.delta_secs();
    let mut placed: Vec<(Entity, MoverFlow)> = Vec::new();
    for (entity, mover, mut trail, invalid) in &mut movers {
        let place = mover
            .validate()
            .and_then(|()| world_place(entity, &hierarchy));
        let centre = place.as_ref().ok().map(|p| Vec3::from(p.origin));
        mark_on_change(
            &mut commands,
            entity,
            place.map(|_| ()),
            invalid,
            "WindMover",
            "it makes no wind",
        );
        let teleport = WindMover::TELEPORT_RADII * mover.radius;
        let velocity = trail.record(centre, dt, teleport);
        if let Some(flow) = centre.and_then(|c| mover.flow(c, velocity)) {
            placed.push((entity, flow));
        }
    }
    if placed.is_empty() && wind.mover_count() == 0 {
        return;
    }
    wind.set_movers(in_entity_order(placed));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn velocity_from_two_steps_none_at_first_none_after_a_teleport() {
        let mut trail = MoverTrail::default();
        let dt = 0.02;
        assert_eq!(trail.record(Some(Vec3::ZERO), dt, 1.0), Vec3::ZERO);
        let v = trail.record(Some(Vec3::new(0.1, 0.0, 0.0)), dt, 1.0);
        assert!((v.x - 5.0).abs() < 1e-5, "{v}");
        // Uneven steps (a frame rate unlike the fixed rate): the two-step mean.
        let v = trail.record(Some(Vec3::new(0.3, 0.0, 0.0)), dt, 1.0);
        assert!((v.x - 7.5).abs() < 1e-4, "{v}");
        // Standing still for two steps: exactly no wind.
        trail.record(Some(Vec3::new(0.3, 0.0, 0.0)), dt, 1.0);
        assert_eq!(
            trail.record(Some(Vec3::new(0.3, 0.0, 0.0)), dt, 1.0),
            Vec3::ZERO
        );
        // A jump past the limit makes none, and the next step counts from there.
        assert_eq!(
            trail.record(Some(Vec3::new(50.0, 0.0, 0.0)), dt, 1.0),
            Vec3::ZERO
        );
        let v = trail.record(Some(Vec3::new(50.1, 0.0, 0.0)), dt, 1.0);
        assert!((v.x - 5.0).abs() < 1e-3, "{v}");
        assert_eq!(trail.record(None, dt, 1.0), Vec3::ZERO);
        assert_eq!(trail.record(Some(Vec3::ONE), 0.0, 1.0), Vec3::ZERO);
    }
}
