//! FallPlugin in a headless app: landing, wind, still fluid, determinism, errors, release.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::freefall::*;
use bevy_windfall::wind::{WindConfig, WindField, WindPlugin};
use common::{STEP, headless_app, paper_coin as coin, ready};

fn fall_app(
    wind: Option<WindConfig>,
    objects: &[FallingObject],
    ground: f32,
) -> (App, Vec<Entity>) {
    let mut app = headless_app();
    if let Some(config) = wind {
        app.add_plugins(WindPlugin {
            config: Some(config),
            ..default()
        });
    }
    app.add_plugins(FallPlugin::default())
        .insert_resource(FallSettings {
            ground_height: ground,
        });
    let entities = objects
        .iter()
        .map(|o| {
            app.world_mut()
                .spawn((o.clone(), Transform::from_xyz(0.0, 2.0, 0.0)))
                .id()
        })
        .collect();
    ready(&mut app);
    (app, entities)
}

#[test]
fn objects_land_once_and_stay() {
    let (mut app, entities) = fall_app(None, &[coin()], 1.5);
    let mut landed = Vec::new();
    for _ in 0..600 {
        app.update();
        let messages = app.world().resource::<Messages<Landed>>();
        landed.extend(messages.iter_current_update_messages().copied());
    }
    assert_eq!(landed.len(), 1, "{landed:?}");
    let state = app.world().get::<FallState>(entities[0]).unwrap();
    assert!(state.landed());
    let fall = app
        .world()
        .resource::<FallStore>()
        .fall(entities[0])
        .unwrap();
    assert_eq!(fall.position().y, 1.5);
    // 0.5 m at U ≈ 0.1585 m/s: about 3.2 s.
    assert!(
        (landed[0].flight_time - 0.5 / 0.1585).abs() < 0.35,
        "{}",
        landed[0].flight_time
    );
    let transform = app.world().get::<Transform>(entities[0]).unwrap();
    assert!((transform.translation.y - 1.5).abs() < 1e-6);
}

#[test]
fn uniform_wind_carries_objects_after_their_response_time() {
    let calm = WindConfig {
        reference_speed: 3.0,
        turbulence_intensity: Some(0.0),
        ..default()
    };
    let (mut app, entities) = fall_app(Some(calm), &[coin()], f32::NEG_INFINITY);
    let field = app.world().resource::<WindField>().clone();
    for _ in 0..120 {
        app.update();
    }
    let path = app
        .world()
        .resource::<FallStore>()
        .fall(entities[0])
        .unwrap();
    let drift = path.position() - Vec3::new(0.0, 2.0, 0.0) - path.still_displacement();
    // Mean wind along +X at the object's height (it falls slowly through the log profile).
    let t = path.time();
    assert!((t - 120.0 * STEP.as_secs_f32()).abs() < 1e-3);
    // dv/dt = (u − v)/τ from rest: x = ∫u dt − u τ (1 − e^(−t/τ)); the coin in water has
    // τ ≈ 0.03 s. The wind it meets slows as it sinks through the log profile.
    let tau = path.scales().response_time(0.0);
    let u = path.scales().descent_speed;
    let steps = 120;
    let dt = t / steps as f32;
    let carried: f32 = (0..steps)
        .map(|i| field.mean_speed_at(2.0 - u * (i as f32 + 0.5) * dt) * dt)
        .sum();
    let expected = carried - field.mean_speed_at(2.0 - u * t) * tau * (1.0 - (-t / tau).exp());
    assert!(
        (drift.x / expected - 1.0).abs() < 0.02,
        "drift {drift:?}, expected {expected}"
    );
    assert!(drift.z.abs() < 1e-4 && drift.y.abs() < 1e-4);
}

#[test]
fn without_wind_objects_fall_in_still_fluid() {
    let (mut app, entities) = fall_app(None, &[coin()], f32::NEG_INFINITY);
    for _ in 0..60 {
        app.update();
    }
    let path = app
        .world()
        .resource::<FallStore>()
        .fall(entities[0])
        .unwrap();
    let diff = path.position() - (Vec3::new(0.0, 2.0, 0.0) + path.still_displacement());
    assert!(diff.length() < 1e-5, "{diff:?}");
}

fn poses(seed: u64) -> Vec<[u32; 7]> {
    let objects: Vec<FallingObject> = (0..8)
        .map(|i| FallingObject {
            seed: seed + i,
            ..FallingObject::default()
        })
        .collect();
    let (mut app, entities) = fall_app(
        Some(WindConfig {
            grid: [32, 32],
            ..default()
        }),
        &objects,
        0.0,
    );
    for _ in 0..90 {
        app.update();
    }
    entities
        .iter()
        .map(|e| {
            let t = app.world().get::<Transform>(*e).unwrap();
            let (p, q) = (t.translation, t.rotation);
            [p.x, p.y, p.z, q.x, q.y, q.z, q.w].map(f32::to_bits)
        })
        .collect()
}

#[test]
fn same_seed_same_fall_bit_for_bit() {
    let a = poses(40);
    assert_eq!(a, poses(40));
    assert_ne!(a, poses(41));
}

#[test]
fn invalid_objects_report_their_error_and_stay_put() {
    let mut bad = coin();
    bad.density = 500.0;
    let (mut app, entities) = fall_app(None, &[bad], 0.0);
    app.update();
    let state = app.world().get::<FallState>(entities[0]).unwrap();
    let invalid = app
        .world()
        .get::<FallingObjectInvalid>(entities[0])
        .unwrap();
    assert_eq!(invalid.0.field(), "density");
    assert!(!state.falls());
    assert!(
        app.world()
            .resource::<FallStore>()
            .fall(entities[0])
            .is_none()
    );
    assert_eq!(
        app.world()
            .get::<Transform>(entities[0])
            .unwrap()
            .translation
            .y,
        2.0
    );
    // Fixed, it falls and the error goes.
    app.world_mut()
        .get_mut::<FallingObject>(entities[0])
        .unwrap()
        .density = 8_000.0;
    // Released at the next write-back; shown one fixed step behind (interpolation).
    for _ in 0..3 {
        app.update();
    }
    assert!(
        app.world()
            .get::<FallingObjectInvalid>(entities[0])
            .is_none()
    );
    let y = app
        .world()
        .get::<Transform>(entities[0])
        .unwrap()
        .translation
        .y;
    assert!(y < 2.0, "{y}");
}

#[test]
fn changing_the_component_releases_again_from_the_transform() {
    let (mut app, entities) = fall_app(None, &[coin()], 1.9);
    for _ in 0..120 {
        app.update();
    }
    assert!(app.world().get::<FallState>(entities[0]).unwrap().landed());
    let mut entity = app.world_mut().entity_mut(entities[0]);
    entity.get_mut::<Transform>().unwrap().translation = Vec3::new(5.0, 3.0, 0.0);
    entity.get_mut::<FallingObject>().unwrap().seed += 1;
    app.update();
    let path = app
        .world()
        .resource::<FallStore>()
        .fall(entities[0])
        .unwrap();
    assert!(!path.landed());
    assert!(
        (path.position() - Vec3::new(5.0, 3.0, 0.0)).length() < 0.05,
        "{:?}",
        path.position()
    );
}
