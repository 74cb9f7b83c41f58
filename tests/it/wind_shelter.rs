//! Shelter: `WindShelter` walls calm their lee and rooms keep the global wind out, while local
//! sources still blow.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::{WindShelter, WindSource};
use common::{headless_app, ready};

fn app_with(config: WindConfig) -> App {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config));
    ready(&mut app);
    app
}

/// A steady wind of 6 m/s along +X at 10 m (no turbulence), for the shelters.
fn steady() -> WindConfig {
    WindConfig {
        reference_speed: 6.0,
        turbulence_intensity: Some(0.0),
        grid: [16, 16],
        ..default()
    }
}

#[test]
fn a_wall_calms_its_lee_and_the_wind_recovers_downwind() {
    let mut app = app_with(steady());
    // A wall 2 m high and 10 m long across the wind, its downwind face at x = 0.1.
    app.world_mut().spawn((
        WindShelter::wall(Vec3::new(0.1, 1.0, 5.0)),
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    let open = |app: &App, p: Vec3| app.world().resource::<WindField>().velocity(p).x;
    let before = open(&app, Vec3::new(3.0, 1.0, 0.0));
    app.update();
    assert_eq!(app.world().resource::<WindField>().shelter_count(), 1);
    // Behind the wall, below its top: calm right behind, recovering monotonically by 8 heights.
    let mut last = 0.0;
    for i in 1..=40 {
        let x = 0.1 + i as f32 * 0.4;
        let u = open(&app, Vec3::new(x, 1.0, 0.0));
        let free = app.world().resource::<WindField>().mean_speed_at(1.0);
        assert!(
            u >= last - 1e-5,
            "recovers monotonically: {last} → {u} at {x}"
        );
        if x <= 2.0 {
            assert!(u < 0.5 * free, "calm at {x}: {u} of {free}");
        }
        if x >= 16.1 {
            assert!((u - free).abs() < 1e-4, "recovered at {x}: {u} of {free}");
        }
        last = u;
    }
    assert!(before > 0.0);
    // Upwind, well above the wall, and beyond its end: the open wind.
    for p in [
        Vec3::new(-2.0, 1.0, 0.0),
        Vec3::new(2.0, 4.0, 0.0),
        Vec3::new(2.0, 1.0, 8.0),
    ] {
        let free = app.world().resource::<WindField>().mean_speed_at(p.y);
        assert!((open(&app, p) - free).abs() < 1e-4, "{p}");
    }
    // Turned with the wind along the wall, it shelters nothing a wall-height beside its end.
    let field = app.world_mut().resource_mut::<WindField>().into_inner();
    field.set_direction(Vec2::new(0.0, 1.0)).unwrap();
    app.update();
    let p = Vec3::new(3.0, 1.0, 7.0);
    let v = app.world().resource::<WindField>().velocity(p);
    let free = app.world().resource::<WindField>().mean_speed_at(1.0);
    assert!((v.z - free).abs() < 1e-4, "{v}");
}

#[test]
fn no_global_wind_indoors_but_a_fan_still_blows() {
    let mut app = app_with(steady());
    app.world_mut().spawn((
        WindShelter::indoor(Vec3::new(3.0, 1.5, 3.0)),
        Transform::from_xyz(0.0, 1.5, 0.0),
    ));
    let fan = Transform::from_xyz(0.0, 1.0, 2.0).looking_to(Vec3::NEG_Z, Vec3::Y);
    app.world_mut().spawn((WindSource::fan(3.0, 0.5, 4.0), fan));
    app.update();
    let field = app.world().resource::<WindField>();
    assert_eq!(
        field.velocity(Vec3::new(-2.0, 1.0, -2.0)),
        Vec3::ZERO,
        "calm room"
    );
    let blown = field.velocity(Vec3::new(0.0, 1.0, 1.0));
    assert!(
        blown.z < -2.0 && blown.x.abs() < 1e-4,
        "the fan indoors: {blown}"
    );
    // Outside, a quarter of a metre past the walls, the open wind.
    let out = field.velocity(Vec3::new(0.0, 1.0, -3.3));
    assert!((out.x - field.mean_speed_at(1.0)).abs() < 1e-4, "{out}");
    // Continuous through the wall's transition.
    let mut last = 0.0;
    for i in 0..=30 {
        let z = -3.0 - i as f32 * 0.01;
        let u = field.velocity(Vec3::new(0.0, 1.0, z)).x;
        assert!(
            u >= last && u - last < 0.2 * field.mean_speed_at(1.0),
            "{z}: {last} → {u}"
        );
        last = u;
    }
}

#[test]
fn shelters_refuse_bad_sizes_as_sources_do() {
    // One constructor per kind keeps what it is given; `validate` names the first bad side.
    let good = Vec3::new(0.1, 1.0, 5.0);
    assert!(WindShelter::wall(good).validate().is_ok());
    assert!(WindShelter::indoor(good).validate().is_ok());
    assert!(
        WindShelter::wall(Vec3::ZERO).validate().is_ok(),
        "a zero box is a valid nothing"
    );
    for (bad, field) in [
        (Vec3::new(-1.0, 1.0, 1.0), "half_extents.x"),
        (Vec3::new(1.0, f32::NAN, 1.0), "half_extents.y"),
        (Vec3::new(1.0, 1.0, f32::INFINITY), "half_extents.z"),
        (Vec3::new(1.0, 1.0, 1e30), "half_extents.z"),
        (Vec3::new(1.0, -0.5, f32::NAN), "half_extents.y"),
    ] {
        for shelter in [WindShelter::wall(bad), WindShelter::indoor(bad)] {
            let error = shelter.validate().expect_err("refused");
            assert_eq!(error.field(), field, "{bad}: {error}");
        }
    }
    // A source's size is checked by the same rule.
    let error = WindSource::sphere(1e30, Vec3::X)
        .validate()
        .expect_err("refused");
    assert_eq!(error.field(), "shape.radius");
}
