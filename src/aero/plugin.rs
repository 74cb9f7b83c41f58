//! The [`AeroPlugin`]: moves every [`AeroBody`] and [`PhysicalCloth`] on the fixed timestep.

use bevy::app::{App, Plugin, PostUpdate};
use bevy::ecs::prelude::*;

use super::body::{AeroBody, AeroBodyInvalid, AeroState, pose_bodies, step_bodies};
use super::physical_cloth::{
    PhysicalCloth, PhysicalClothInvalid, PhysicalClothState, step_cloths, write_cloth_meshes,
};
use crate::lifecycle::set_up_changed;
use crate::schedule::{SimulateSystems, WindfallSystems};

crate::schedule::simulation_plugin!(
    /// Moves every [`AeroBody`] and [`PhysicalCloth`] on the fixed timestep.
    AeroPlugin
);

impl Plugin for AeroPlugin {
    fn build(&self, app: &mut App) {
        let schedule = self.configure(app);
        crate::lifecycle::observe::<PhysicalCloth>(app);
        app.register_type::<AeroBody>()
            .register_type::<AeroState>()
            .register_type::<AeroBodyInvalid>()
            .register_type::<PhysicalCloth>()
            .register_type::<PhysicalClothInvalid>()
            // Each only with something to move (a system with nothing to do still costs a
            // wake-up).
            .add_systems(
                schedule,
                (
                    step_bodies.run_if(any_with_component::<AeroState>),
                    step_cloths.run_if(any_with_component::<PhysicalClothState>),
                )
                    .in_set(SimulateSystems::Aero),
            )
            // Set up in the frame the cloth is added (or changed), before its mesh is written.
            .add_systems(
                PostUpdate,
                (
                    (set_up_changed::<PhysicalCloth>, write_cloth_meshes)
                        .chain()
                        .run_if(any_with_component::<PhysicalCloth>),
                    pose_bodies.run_if(any_with_component::<AeroState>),
                )
                    .in_set(WindfallSystems::WriteBack),
            );
    }
}
