//! [`WindMover`]: a body that pushes the air as it moves (a player, a cart, a projectile, an
//! avian body), felt by everything that reads the [`WindField`](super::WindField).

use bevy::ecs::component::Component;
use bevy::ecs::reflect::ReflectComponent;
use bevy::math::Vec3;
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

use super::error::WindError;
use crate::error::InvalidValue;
use crate::guard::MAX_COORDINATE;

mod flow;
mod track;

pub(crate) use flow::MoverFlow;
pub(crate) use track::{MoverTrail, anything_moving, place_wind_movers};

/// A body that pushes the air: the entity's motion between fixed steps (its global transform's
/// translation) makes the flow round a sphere of `radius` moving that fast, added to the wind
/// like a [`WindSource`](super::WindSource)'s, so grass, leaves, cloth, aero bodies and
/// [`WindField::velocity`](super::WindField::velocity) all feel it, on the CPU and in the
/// shaders alike.
///
/// The flow (see `src/wind/mover/flow.rs` for the equations and sources): potential flow round
/// the sphere in front and at the sides (the air pushed ahead of it and slipping back past its
/// sides, falling as 1/r³), the ground as a mirror (the flow along the ground under a low body
/// doubled, none through it), and a turbulent wake dragged along behind it, decaying as
/// x^−2/3 over ten body lengths and carrying the momentum of a sphere's drag. Nothing at all
/// beyond 20.5 radii, so far bodies cost one distance test per read (and a batched read, a
/// cloud's, skips them a few hundred points at a time). |u| ≤ 2.25 |v| everywhere.
///
/// Its velocity is the motion of its centre over the last two fixed steps (over the first one,
/// just after it appeared; none on the very first step): standing still it makes no wind at
/// all. A move of more than [`WindMover::TELEPORT_RADII`] radii in one fixed step is a
/// teleport: it makes no wind and the motion is counted afresh from there (so a small fast body
/// needs a radius of at least a quarter of its step: a 0.1 m projectile above 26 m/s at 64 Hz
/// counts as teleporting; give it a larger radius). Move it in
/// `FixedUpdate` (or let a physics engine move it) for a steady wind; moving it in `Update`
/// at a frame rate unlike the fixed rate still works, the two-step window smoothing most of the
/// stutter.
///
/// A radius that is not a positive finite number up to
/// [`MAX_COORDINATE`](crate::guard::MAX_COORDINATE), a non-finite `strength` or `ground`
/// (−∞ is allowed: no ground), or a transform that places it nowhere, makes no wind and gets a
/// [`WindMoverInvalid`] naming the field.
///
/// On the GPU, movers share the 64 places of the local sources (after the sources).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// #[derive(Component)]
/// struct Player;
///
/// fn setup(mut commands: Commands) {
///     // A player half a metre across: running through the meadow, it parts the grass.
///     commands.spawn((Player, WindMover { radius: 0.5, ..default() }, Transform::from_xyz(0.0, 0.6, 0.0)));
/// }
/// App::new()
///     .add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()))
///     .add_systems(Startup, setup)
///     .update();
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform, MoverTrail)]
pub struct WindMover {
    /// The body's radius, m: the size of the sphere the air flows round.
    pub radius: f32,
    /// Multiplies the flow: 0 switches it off, 0.5 for a body that parts the air less (a thin
    /// pole), 1 the sphere's.
    pub strength: f32,
    /// Height of the ground the air cannot flow through, m (−∞: none).
    pub ground: f32,
}

impl Default for WindMover {
    /// A body 0.4 m across (a person's chest or a dog), over the ground at height 0.
    fn default() -> Self {
        Self {
            radius: 0.4,
            strength: 1.0,
            ground: 0.0,
        }
    }
}

impl WindMover {
    /// A move further than this many radii in one fixed step is a teleport, not motion.
    pub const TELEPORT_RADII: f32 = 4.0;

    /// Checks what the plugin places: `radius` finite, > 0 and ≤
    /// [`MAX_COORDINATE`](crate::guard::MAX_COORDINATE), `strength` finite, `ground` finite or
    /// −∞.
    ///
    /// # Errors
    /// The first field that fails, named (`radius`, `strength`, `ground`).
    pub fn validate(&self) -> Result<(), WindError> {
        let r = self.radius;
        InvalidValue::check(
            r > 0.0 && r <= MAX_COORDINATE,
            "radius",
            r,
            "must be finite, > 0 and ≤ MAX_COORDINATE",
        )?;
        InvalidValue::check(
            self.strength.is_finite(),
            "strength",
            self.strength,
            "must be finite",
        )?;
        let g = self.ground;
        InvalidValue::check(
            g.is_finite() || g == f32::NEG_INFINITY,
            "ground",
            g,
            "must be finite, or −∞ for no ground",
        )?;
        Ok(())
    }

    /// The flow of this body at `centre` moving at `velocity`, or `None` where it makes none.
    pub(crate) fn flow(&self, centre: Vec3, velocity: Vec3) -> Option<MoverFlow> {
        MoverFlow::new(centre, velocity * self.strength, self.radius, self.ground)
    }
}

/// Why a [`WindMover`] makes no wind: a field out of range (see [`WindMover::validate`]) or,
/// with field `transform`, a transform that places it nowhere. Inserted when the problem
/// appears (logged once), removed once it is gone.
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct WindMoverInvalid(pub WindError);

crate::lifecycle::invalid_marker!(WindMoverInvalid, WindError);
