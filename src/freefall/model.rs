//! What every fall shares: the trajectory database and the Markov chain.

use bevy::ecs::reflect::ReflectResource;
use bevy::reflect::Reflect;
use std::sync::Arc;

use bevy::ecs::resource::Resource;

use super::database::TrajectoryDatabase;
use super::markov::{BoundedChain, MarkovChain};
use super::regime::PrimitiveMotion;

/// The trajectory database and the Markov chain, bounded once per main motion (eq. 9) so that a
/// [`FallPath`](super::path::FallPath) only carries its main motion. A resource of the
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
/// app.add_plugins((MinimalPlugins, WindfallPlugins));
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

    /// The chain limited to L1..`main`, shared (what a [`FallPath`](super::path::FallPath) holds).
    pub(crate) fn bounded_shared(&self, main: PrimitiveMotion) -> Arc<BoundedChain> {
        Arc::clone(&self.bounded[main.index()])
    }
}
