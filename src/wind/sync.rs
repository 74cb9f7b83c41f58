//! The two systems that keep the wind's settings and its field in step: [`apply_wind_settings`]
//! (before the fixed loop, what the settings changed applies to the field) and
//! [`land_wind_rebuild`] (in the fixed step, a field rebuilt in the background is swapped in).

use bevy::ecs::prelude::*;
use bevy::log::{info, warn};
use bevy::tasks::{block_on, futures::check_ready};

use super::config::WindConfig;
use super::field::WindField;
use super::rebuild::{Mean, WindRebuild, WindRebuilt, hand_over, start_rebuild};
use super::settings::{WindSettings, needs_rebuild};

/// Follows [`WindSettings`]: what changed in them since the last step applies, speed and
/// direction (and pulse) at once, the rest by a background rebuild. A field changed directly
/// ([`WindField::set_reference_speed`], [`WindField::set_direction`],
/// [`WindField::set_pulse`], a newly inserted field) is
/// reflected back into the settings, so neither kind of edit overwrites the other.
pub fn apply_wind_settings(
    mut commands: Commands,
    settings: Option<ResMut<WindSettings>>,
    field: Option<ResMut<WindField>>,
    rebuild: Option<Res<WindRebuild>>,
    mut seen: Local<Option<WindConfig>>,
) {
    let (Some(mut settings), Some(mut field)) = (settings, field) else {
        return;
    };
    let seen = seen.get_or_insert_with(|| settings.config.clone());
    if settings.is_changed() && settings.config != *seen {
        let target = settings.config.clone();
        let mut refused = None;
        if target.reference_speed != seen.reference_speed
            && let Err(e) = field.set_reference_speed(target.reference_speed)
        {
            refused = Some(e);
        }
        if target.direction != seen.direction
            && let Err(e) = field.set_direction(target.direction)
        {
            refused = Some(e);
        }
        if target.pulse != seen.pulse
            && let Err(e) = field.set_pulse(target.pulse)
        {
            refused = Some(e);
        }
        if needs_rebuild(seen, &target) {
            // The mean wind applies at once (above) and the field leads it (a direct edit the
            // settings have not seen yet included): the rebuild starts from the field's.
            let mut build = target.clone();
            let live = field.config();
            build.reference_speed = live.reference_speed;
            build.direction = live.direction;
            build.pulse = live.pulse;
            match start_rebuild(build, Some((field.generation(), Mean::of(&field)))) {
                Ok(job) => {
                    commands.insert_resource(job);
                }
                Err(e) => refused = Some(e),
            }
        }
        if let Some(e) = refused {
            warn!("WindSettings: {e}; the wind keeps what it had");
        }
        *seen = target;
    }
    // The field leads where it was changed directly: its speed and direction always, the rest
    // when nothing is building (a field inserted by hand).
    let live = field.config();
    let mut synced = settings.config.clone();
    synced.reference_speed = live.reference_speed;
    synced.direction = live.direction;
    synced.pulse = live.pulse;
    if rebuild.is_none() && !settings.is_changed() {
        synced = live.clone();
    }
    if synced != settings.config {
        seen.reference_speed = synced.reference_speed;
        seen.direction = synced.direction;
        seen.pulse = synced.pulse;
        if rebuild.is_none() && !settings.is_changed() {
            *seen = synced.clone();
        }
        settings.bypass_change_detection().config = synced;
    }
}

/// Counts the [`WindRebuild`] in flight down by one fixed step; at its step, swaps in the new
/// field (waiting for it if it is late) with the old clock and the merged mean wind
/// ([`hand_over`]). A field made after the request, or any other field than the one the rebuild
/// replaces, wins and the rebuild is dropped.
pub fn land_wind_rebuild(
    mut commands: Commands,
    rebuild: Option<ResMut<WindRebuild>>,
    old: Option<Res<WindField>>,
    mut rebuilt: MessageWriter<WindRebuilt>,
) {
    let Some(mut rebuild) = rebuild else {
        return;
    };
    let later = match (rebuild.replaces, old.as_deref()) {
        (None, Some(live)) if live.generation() >= rebuild.requested => true,
        (None, Some(live)) => {
            rebuild.replaces = Some((live.generation(), Mean::of(live)));
            false
        }
        (Some((replaced, _)), Some(live)) => replaced != live.generation(),
        (_, None) => false,
    };
    if later {
        info!("a WindField was inserted after a rebuild was requested: the rebuild is dropped");
        commands.remove_resource::<WindRebuild>();
        return;
    }
    rebuild.elapsed += 1;
    if rebuild.elapsed < rebuild.steps {
        return;
    }
    let Some(task) = rebuild.task.as_mut() else {
        commands.remove_resource::<WindRebuild>();
        return;
    };
    let field = if cfg!(target_arch = "wasm32") {
        match check_ready(task) {
            Some(field) => field,
            None => return,
        }
    } else {
        block_on(task)
    };
    rebuild.task = None;
    let mut field = field;
    if let Some(old) = old.as_deref() {
        let base = rebuild
            .replaces
            .map_or_else(|| Mean::of(old), |(_, base)| base);
        if let Err(e) = hand_over(&mut field, old, base) {
            warn!("WindRebuild: {e}; the rebuilt field keeps its own mean wind");
            field.continue_clock_of(old);
        }
    }
    rebuilt.write(WindRebuilt {
        config: field.config().clone(),
    });
    commands.insert_resource(field);
    commands.remove_resource::<WindRebuild>();
}
