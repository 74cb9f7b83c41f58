//! Everything that decides the wind's velocities, as one value to save or send.

use bevy::math::DVec2;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;

use bevy::ecs::world::World;

use super::config::WindConfig;
use super::ease::WindEasing;
use super::error::WindError;
use super::field::WindField;
use super::rebuild::WindRebuild;
use super::settings::WindSettings;

/// The wind's settings (seed included) and its clock: all a second machine needs to blow the
/// same wind, bit for bit, as [`WindField::from_snapshot`] rebuilds it. With the `serde`
/// feature it serialises, so a game server can send it to its clients once (and again when the
/// settings change); velocities then agree without sending any (the crate's determinism is what
/// lockstep and rollback need). With serde_json enable its `float_roundtrip` feature, or the
/// clock may come back one bit off.
///
/// In an app, [`WindSnapshot::capture`] also takes the [`WindSettings`] and a [`WindRebuild`] in
/// flight, and [`WindSnapshot::restore`] puts all three into another app: a client restored in
/// the same frame as the server captured (lockstep) lands the same rebuild at the same step and
/// takes in a settings edit not yet applied at the same step as the server.
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
    /// The settings as the field last took them in (what a later settings edit is compared
    /// with).
    #[cfg_attr(feature = "serde", serde(default))]
    pub taken_in: Option<WindConfig>,
    /// The app's [`WindSettings`] ([`WindSnapshot::capture`]; `None` from
    /// [`WindField::snapshot`]).
    #[cfg_attr(feature = "serde", serde(default))]
    pub settings: Option<WindConfig>,
    /// A [`WindRebuild`] in flight: the configuration it builds ...
    #[cfg_attr(feature = "serde", serde(default))]
    pub rebuild: Option<WindConfig>,
    /// ... and the fixed steps until it lands.
    #[cfg_attr(feature = "serde", serde(default))]
    pub rebuild_steps_left: u32,
}

impl WindSnapshot {
    /// The wind of an app: its field, settings and rebuild in flight (`None` without a field).
    pub fn capture(world: &World) -> Option<Self> {
        let mut snapshot = world.get_resource::<WindField>()?.snapshot();
        snapshot.settings = world
            .get_resource::<WindSettings>()
            .map(|s| s.config.clone());
        if let Some(rebuild) = world.get_resource::<WindRebuild>() {
            snapshot.rebuild = Some(rebuild.config().clone());
            snapshot.rebuild_steps_left = rebuild.steps_left();
        }
        Some(snapshot)
    }

    /// Puts this wind into an app: its field, then its rebuild in flight (or none), then its
    /// settings. Nothing is changed if any part is refused.
    ///
    /// # Errors
    /// What [`WindField::from_snapshot`] or [`WindRebuild::start`] refuse, named.
    pub fn restore(&self, world: &mut World) -> Result<(), WindError> {
        let field = WindField::from_snapshot(self)?;
        let rebuild = match &self.rebuild {
            Some(config) => {
                Some(WindRebuild::start(config.clone())?.with_steps(self.rebuild_steps_left))
            }
            None => None,
        };
        world.insert_resource(field);
        match rebuild {
            Some(rebuild) => world.insert_resource(rebuild),
            None => {
                world.remove_resource::<WindRebuild>();
            }
        }
        if let Some(settings) = &self.settings {
            world.insert_resource(WindSettings::new(settings.clone()));
        }
        Ok(())
    }
}
