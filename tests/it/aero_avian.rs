//! AeroBody forces on avian3d rigid bodies (feature `avian`): a thin plate body with
//! `AvianAero` falls at the closed-form terminal speed, and a feather-light one in a gale is not
//! flung past the wind.

use crate::common;

use avian3d::prelude::*;
use bevy::prelude::*;
use bevy_windfall::aero::*;
use bevy_windfall::wind::{WindConfig, WindPlugin};
use common::{headless_app, ready};

fn avian_app(wind: Option<WindConfig>, mass: f32) -> (App, Entity) {
    let mut app = headless_app();
    app.add_plugins((
        bevy::asset::AssetPlugin::default(),
        bevy::mesh::MeshPlugin,
        PhysicsPlugins::default(),
        AvianAeroPlugin::default(),
    ));
    if let Some(config) = wind {
        app.add_plugins(WindPlugin {
            config: Some(config),
            ..default()
        });
    }
    let mesh = Mesh::from(Plane3d::default().mesh().size(0.1, 0.1));
    let aero = AvianAero::from_mesh(&mesh, AeroCoefficients::default()).unwrap();
    let body = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Collider::cuboid(0.1, 0.001, 0.1),
            Mass(mass),
            aero,
            Transform::from_xyz(0.0, 50.0, 0.0),
        ))
        .id();
    ready(&mut app);
    (app, body)
}

#[test]
fn avian_plate_reaches_terminal_velocity() {
    let mass = 2e-3;
    let (mut app, body) = avian_app(None, mass);
    for _ in 0..600 {
        app.update();
    }
    let v = app.world().get::<LinearVelocity>(body).unwrap().0;
    let c = AeroCoefficients::default();
    let terminal = (2.0 * mass * 9.81 / (c.density * c.drag * 0.01)).sqrt();
    assert!((-v.y / terminal - 1.0).abs() < 0.02, "{v:?} vs {terminal}");
}

#[test]
fn avian_feather_in_a_gale_is_not_flung_past_the_wind() {
    let gale = WindConfig {
        reference_speed: 70.0,
        reference_height: 50.0,
        turbulence_intensity: Some(0.0),
        ..default()
    };
    let (mut app, body) = avian_app(Some(gale), 1e-4);
    for _ in 0..120 {
        app.update();
        let v = app.world().get::<LinearVelocity>(body).unwrap().0;
        assert!(v.is_finite() && v.x <= 70.5, "{v:?}");
    }
    let v = app.world().get::<LinearVelocity>(body).unwrap().0;
    assert!(v.x > 30.0, "{v:?}");
}

#[test]
fn avian_bodies_feel_local_wind_sources() {
    // Still air, and a 40 m sphere blowing 8 m/s along −Z around the falling plate.
    let still = WindConfig {
        reference_speed: 0.0,
        ..default()
    };
    let (mut app, body) = avian_app(Some(still), 2e-3);
    app.world_mut().spawn((
        bevy_windfall::wind::WindSource::sphere(40.0, Vec3::NEG_Z * 8.0),
        Transform::from_xyz(0.0, 45.0, 0.0),
    ));
    for _ in 0..90 {
        app.update();
    }
    let v = app.world().get::<LinearVelocity>(body).unwrap().0;
    assert!(v.z < -2.0 && v.x.abs() < 0.5, "{v:?}");
}
