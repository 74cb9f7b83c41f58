//! ECS glue: [`AeroBody`] (a rigid plate moved by gravity, lift and drag), its [`AeroState`],
//! and the [`AeroPlugin`].

use bevy::app::{App, FixedUpdate, Plugin};
use bevy::ecs::prelude::*;
use bevy::math::Vec3;
use bevy::time::{Fixed, Time};
use bevy::transform::components::Transform;

use super::plate::{PlateState, RigidPlate};
use crate::WindfallSystems;
use crate::wind::WindField;

/// A physically driven rigid plate (a leaf, card or coin): gravity plus per-face lift and drag
/// in the [`WindField`] (still air without one). It starts from its [`Transform`] at rest;
/// set [`AeroState::state`] for another start. The transform follows the body every fixed step.
#[derive(Component, Clone, Debug)]
#[require(Transform, AeroState)]
pub struct AeroBody {
    /// Faces, mass, inertia and coefficients.
    pub plate: RigidPlate,
    /// m/s².
    pub gravity: Vec3,
}

impl AeroBody {
    /// A body under standard gravity.
    pub fn new(plate: RigidPlate) -> Self {
        Self {
            plate,
            gravity: Vec3::new(0.0, -9.81, 0.0),
        }
    }
}

/// Runtime state of an [`AeroBody`] (required component).
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct AeroState {
    /// Position, velocity, orientation and spin.
    pub state: PlateState,
    started: bool,
}

impl AeroState {
    /// Starts the body from `state` instead of its transform at rest.
    pub fn new(state: PlateState) -> Self {
        Self {
            state,
            started: true,
        }
    }
}

/// Moves every [`AeroBody`] on the fixed timestep.
pub struct AeroPlugin;

impl Plugin for AeroPlugin {
    fn build(&self, app: &mut App) {
        crate::configure_sets(app);
        app.add_systems(FixedUpdate, step_bodies.in_set(WindfallSystems::Simulate));
    }
}

fn step_bodies(
    mut bodies: Query<(&AeroBody, &mut AeroState, &mut Transform)>,
    wind: Option<Res<WindField>>,
    time: Res<Time<Fixed>>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    bodies
        .par_iter_mut()
        .for_each(|(body, mut state, mut transform)| {
            if !state.started {
                state.started = true;
                state.state.position = transform.translation;
                state.state.rotation = transform.rotation;
            }
            let s = &mut state.state;
            match wind {
                Some(w) => body
                    .plate
                    .step(s, dt, body.gravity, &|p| w.velocity(p), false),
                None => body.plate.step(s, dt, body.gravity, &|_| Vec3::ZERO, true),
            }
            transform.translation = s.position;
            transform.rotation = s.rotation;
        });
}
