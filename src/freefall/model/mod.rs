//! The free-fall paper's models, pure math (no systems): what falls and through what ([`body`]),
//! its regime and main motion (§2.1, [`regime`]), the plate's equations of motion (eq. 4,
//! [`ode`]), the trajectory database of eq. 5 swings (§2.2, [`database`]), the swing search and
//! amplitudes (§2.3, [`motion`]), a piece of motion (eq. 5–6, [`piece`]), the Markov chain
//! (§3, [`markov`]), the wind's tilt of eq. 15 ([`tilt`]), where a fall starts ([`release`]),
//! and [`FallModel`], what every fall shares: the database and the chain. A fall synthesised
//! from them in the wind (§4) is a slot of a fall store (`freefall::store`).

pub(crate) mod body;
pub(crate) mod database;
pub(crate) mod error;
pub(crate) mod markov;
pub(crate) mod motion;
pub mod ode;
pub(crate) mod piece;
pub(crate) mod random;
pub(crate) mod regime;
pub(crate) mod release;
pub(crate) mod tilt;

use std::sync::Arc;

use bevy::ecs::reflect::ReflectResource;
use bevy::ecs::resource::Resource;
use bevy::reflect::Reflect;

use database::TrajectoryDatabase;
use markov::{BoundedChain, MarkovChain};
use regime::PrimitiveMotion;

/// The trajectory database and the Markov chain, bounded once per main motion (eq. 9) so that a
/// fall only carries its main motion. A resource of the
/// [`FallPlugin`](super::FallPlugin); replace it to use another database or chain.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::freefall::{FallModel, MarkovChain};
/// use bevy_windfall::prelude::*;
///
/// // Start in any motion; stay 3 s in each on average; then move on to the next one.
/// let next = std::array::from_fn(|i| std::array::from_fn(|j| if j == i + 1 { 1.0 } else { 0.0 }));
/// let dwell = [3.0, 3.0, 3.0, 3.0, 3.0, f32::INFINITY];
/// let calm = MarkovChain::from_dwell_times([1.0; 6], dwell, next).unwrap();
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, WindfallPlugins::default()));
/// app.world_mut().resource_mut::<FallModel>().set_chain(calm);
/// ```
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(opaque, Resource, Debug)]
pub struct FallModel {
    database: TrajectoryDatabase,
    chain: MarkovChain,
    bounded: [Arc<BoundedChain>; 6],
}

impl Default for FallModel {
    fn default() -> Self {
        Self::new(TrajectoryDatabase::default(), MarkovChain::default())
    }
}

impl FallModel {
    /// A model from a database and a (validated) chain.
    pub fn new(database: TrajectoryDatabase, chain: MarkovChain) -> Self {
        Self {
            database,
            chain,
            bounded: PrimitiveMotion::ALL.map(|main| Arc::new(chain.bounded(main))),
        }
    }

    /// The trajectory database.
    pub fn database(&self) -> &TrajectoryDatabase {
        &self.database
    }

    /// The Markov chain.
    pub fn chain(&self) -> &MarkovChain {
        &self.chain
    }

    /// Replaces the chain; falls released from now on follow it.
    pub fn set_chain(&mut self, chain: MarkovChain) {
        self.chain = chain;
        self.bounded = PrimitiveMotion::ALL.map(|main| Arc::new(chain.bounded(main)));
    }

    /// The chain limited to L1..`main`, shared (what a fall holds).
    pub(crate) fn bounded_shared(&self, main: PrimitiveMotion) -> Arc<BoundedChain> {
        Arc::clone(&self.bounded[main.index()])
    }
}
