#![doc = include_str!("../README.md")]

use bevy::app::{App, FixedUpdate, PluginGroup, PluginGroupBuilder};
use bevy::ecs::schedule::{IntoScheduleConfigs, SystemSet};

pub mod aero;
pub mod cloth;
pub mod freefall;
pub mod spectrum;
pub mod wind;

/// The most used types.
pub mod prelude {
    pub use crate::aero::{AeroBody, AeroCoefficients, AeroPlugin, AeroState, RigidPlate};
    pub use crate::cloth::{
        Cloth, ClothAttachment, ClothGrid, ClothParams, ClothPlugin, ClothPreset, ClothState,
    };
    pub use crate::freefall::{
        FallState, FallingObject, Fluid, FreeFallPlugin, FreeFallSettings, Landed, PrimitiveMotion,
        Shape,
    };
    pub use crate::spectrum::fbm;
    pub use crate::wind::{
        SpatialMode, TemporalMode, WindConfig, WindError, WindField, WindPlugin,
    };
    pub use crate::{WindfallPlugins, WindfallSystems};
}

/// All of bevy_windfall's plugins. Add the group, a single plugin, or disable one:
/// `WindfallPlugins.build().disable::<WindPlugin>()`.
///
/// [`WindPlugin`]: wind::WindPlugin
pub struct WindfallPlugins;

impl PluginGroup for WindfallPlugins {
    fn build(self) -> PluginGroupBuilder {
        let group = PluginGroupBuilder::start::<Self>()
            .add(wind::WindPlugin::default())
            .add(freefall::FreeFallPlugin)
            .add(aero::AeroPlugin)
            .add(cloth::ClothPlugin);
        #[cfg(feature = "gizmos")]
        let group = group
            .add(wind::WindGizmosPlugin)
            .add(freefall::FallGizmosPlugin)
            .add(cloth::ClothGizmosPlugin);
        group
    }
}

/// System sets of the simulation, run in this order in `FixedUpdate`.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WindfallSystems {
    /// Advance the wind clock.
    Wind,
    /// Move the objects the wind acts on.
    Simulate,
}

/// Orders the sets; idempotent, so every plugin may call it.
fn configure_sets(app: &mut App) {
    app.configure_sets(
        FixedUpdate,
        (WindfallSystems::Wind, WindfallSystems::Simulate).chain(),
    );
}
