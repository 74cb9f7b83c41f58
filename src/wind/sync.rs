//! The two systems that keep the wind's settings and its field in step: [`apply_wind_settings`]
//! (before the fixed loop, what the settings changed applies to the field) and
//! [`land_wind_rebuild`] (in the fixed step, a field rebuilt in the background is swapped in).

use bevy::ecs::prelude::*;
use bevy::log::{info, warn};
use bevy::tasks::{block_on, futures::check_ready};

use super::config::WindConfig;
use super::field::WindField;
use super::rebuild::{WindRebuild, WindRebuilt, start_rebuild};
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
            match start_rebuild(target.clone(), Some(field.generation())) {
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
/// field (waiting for it if it is late), with the old clock and the live speed and direction.
pub fn land_wind_rebuild(
    mut commands: Commands,
    rebuild: Option<ResMut<WindRebuild>>,
    old: Option<Res<WindField>>,
    settings: Option<Res<WindSettings>>,
    mut rebuilt: MessageWriter<WindRebuilt>,
) {
    let Some(mut rebuild) = rebuild else {
        return;
    };
    let current = old.as_ref().map(|f| f.generation());
    match (rebuild.replaces, current) {
        (None, _) => rebuild.replaces = current,
        (Some(a), Some(b)) if a != b => {
            info!("a WindField was inserted while a rebuild was building: the rebuild is dropped");
            commands.remove_resource::<WindRebuild>();
            return;
        }
        _ => {}
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
        // Speed and direction changed while it built (directly or through the settings).
        let (speed, direction) = match settings.as_deref() {
            Some(s) => (s.reference_speed, s.direction),
            None => (old.config().reference_speed, old.config().direction),
        };
        if let Err(e) = field
            .set_reference_speed(speed)
            .and_then(|()| field.set_direction(direction))
        {
            warn!("WindRebuild: {e}; the rebuilt field keeps its own speed and direction");
        }
        field.continue_clock_of(old);
    }
    rebuilt.write(WindRebuilt {
        config: field.config().clone(),
    });
    commands.insert_resource(field);
    commands.remove_resource::<WindRebuild>();
}
