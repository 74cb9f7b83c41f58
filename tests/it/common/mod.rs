//! Shared helpers of the integration tests: a headless, deterministic app and the paper's coin.
#![allow(dead_code)] // each test file uses a different subset

pub mod hostile;
pub mod measure;

use std::time::Duration;

use bevy::app::App;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;

/// Fixed timestep of the test apps: 60 Hz.
pub const STEP: Duration = Duration::from_micros(16_667);

/// A headless app: `MinimalPlugins`, a 60 Hz fixed timestep, and exactly one fixed step per
/// `app.update()` (the first update advances zero time). Add plugins, then call [`ready`].
pub fn headless_app() -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(Time::<Fixed>::from_duration(STEP))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app
}

/// [`headless_app`] plus assets and meshes (no renderer), for parts that write meshes.
pub fn headless_app_with_meshes() -> App {
    let mut app = headless_app();
    app.add_plugins((bevy::asset::AssetPlugin::default(), bevy::mesh::MeshPlugin));
    app
}

/// Finishes plugin setup and runs the first (zero-time) update.
pub fn ready(app: &mut App) {
    app.finish();
    app.cleanup();
    app.update();
}

/// A Markov chain that starts in `motion` and stays there.
pub fn only(
    motion: bevy_windfall::freefall::PrimitiveMotion,
) -> bevy_windfall::freefall::MarkovChain {
    let mut initial = [0.0; 6];
    initial[motion.index()] = 1.0;
    let mut transitions = [[0.0; 6]; 6];
    for (i, row) in transitions.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    bevy_windfall::freefall::MarkovChain::new(initial, transitions).unwrap()
}

/// The free-fall paper's coin: aluminium, radius 1.0 cm, 1.5 mm thick, in water.
pub fn paper_coin() -> bevy_windfall::freefall::FallingObject {
    use bevy_windfall::freefall::{FallingObject, Fluid, Shape};
    FallingObject {
        shape: Shape::Disk {
            diameter: 0.02,
            thickness: 0.0015,
        },
        density: 2700.0,
        fluid: Fluid::WATER,
        ..FallingObject::default()
    }
}
