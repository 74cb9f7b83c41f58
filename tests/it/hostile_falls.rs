//! Hostile input, third round, on falls: one ground check shared by single objects and clouds,
//! the path API refusing what the plugin refuses, and eq. 4's integrator finite for any step
//! and any parameters.

use bevy::math::Vec3;
use bevy_windfall::freefall::ode::{Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{
    CloudRegion, FallModel, FallPath, FallRelease, FallingObject, LeafCloud, WindTilt,
};

#[test]
fn a_cloud_refuses_the_ground_a_single_object_refuses() {
    let model = FallModel::default();
    let cloud = LeafCloud {
        count: 10,
        ..Default::default()
    };
    let object = FallingObject::default();
    for ground in [2e7, -2e7, 1e30, f32::MAX, f32::INFINITY, f32::NAN] {
        let refused = cloud.leaves(&model, ground).unwrap_err();
        assert_eq!(refused.field(), "release.ground", "cloud on {ground}");
        let release = FallRelease::at(Vec3::new(0.0, 5.0, 0.0), ground);
        let single = object.path(&model, release).unwrap_err();
        assert_eq!(
            single.field(),
            "release.ground",
            "single object on {ground}"
        );
    }
    // The valid range, to its edges.
    for ground in [-1e7, -3.0, 0.0, 1e7] {
        let leaves = cloud
            .leaves(&model, ground)
            .expect("a ground within the world");
        assert_eq!(leaves.len(), 10);
    }
}

#[test]
fn the_path_api_refuses_the_releases_the_plugin_refuses() {
    let model = FallModel::default();
    let object = FallingObject::default();
    let regime = object.regime().unwrap();
    for position in [
        Vec3::new(1e38, 2.0, -1e38),
        Vec3::new(1.2e38, 9.95, 0.0),
        Vec3::new(0.0, 2e7, 0.0),
        Vec3::new(-1.0000001e7, 0.0, 0.0),
        Vec3::new(f32::NAN, 0.0, 0.0),
        Vec3::new(0.0, f32::INFINITY, 0.0),
    ] {
        // Every public way to start a fall: a described object's path, a bare path ...
        let refused = object
            .path(&model, FallRelease::at(position, 0.0))
            .unwrap_err();
        assert_eq!(refused.field(), "release.position", "{position}");
        let refused = FallPath::new(
            &model,
            object.scales(&regime),
            regime.main,
            1,
            position,
            0.0,
        )
        .unwrap_err();
        assert_eq!(refused.field(), "release.position", "{position}");
        // ... and a cloud's region.
        let cloud = LeafCloud {
            region: CloudRegion {
                min: position,
                max: position,
            },
            count: 10,
            ..LeafCloud::default()
        };
        let refused = cloud.leaves(&model, 0.0).unwrap_err();
        assert!(
            refused.field().starts_with("region."),
            "{position}: {refused}"
        );
    }
    // The ground too, and at the edge of the bounds a fall starts and stays finite.
    let refused = FallPath::new(
        &model,
        object.scales(&regime),
        regime.main,
        1,
        Vec3::ZERO,
        1e30,
    )
    .unwrap_err();
    assert_eq!(refused.field(), "release.ground");
    let edge = Vec3::new(1.0e7, 1.0e7, -1.0e7);
    let mut path = FallPath::new(
        &model,
        object.scales(&regime),
        regime.main,
        1,
        edge,
        f32::NEG_INFINITY,
    )
    .unwrap();
    let tilt = WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    };
    for _ in 0..600 {
        path.advance(&model, 1.0 / 60.0, Vec3::new(30.0, 0.0, 0.0), &tilt);
        let (p, q) = path.smoothed(0.5);
        assert!(p.is_finite() && q.is_finite(), "{p} {q}");
    }
}

#[test]
fn eq_4_stays_finite_for_any_step_and_parameters() {
    let values = [
        1e300,
        -1e300,
        1e6,
        -1e6,
        4.1,
        0.0,
        -0.5,
        f64::NAN,
        f64::INFINITY,
    ];
    let methods = [
        Integrator::Euler,
        Integrator::Midpoint,
        Integrator::Rk4,
        Integrator::SemiImplicit,
    ];
    let start = OdeState {
        v: -1.0,
        theta: 0.3,
        ..Default::default()
    };
    for (k, &value) in values.iter().enumerate() {
        // Each parameter in turn, and all of them at once.
        for which in 0..6 {
            let mut p = TanabeKaneko::FLUTTER;
            let slots = [
                &mut p.a_perp,
                &mut p.a_par,
                &mut p.lift,
                &mut p.torque,
                &mut p.gravity,
            ];
            match which {
                5 => slots.into_iter().for_each(|s| *s = value),
                i => *slots.into_iter().nth(i).unwrap() = value,
            }
            for dt in [1e300, 1e30, 60.0, 1.0 / 60.0, 1e-300] {
                for method in methods {
                    let next = p.step(start, dt, method);
                    assert!(
                        next.is_finite(),
                        "value {k} in slot {which}, dt {dt}, {method:?}: {next:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_fall_let_go_high_up_moves_at_its_speed() {
    use bevy_windfall::freefall::WindTilt;
    // The same object let go 10 m and 1e6–9.9e6 m up (inside the world's ±1e7 m), stepped 4 s at
    // 60 Hz with the ground far below: it comes down as far up high as low down, to within one
    // f32 spacing of the height (where a 1/60 s step is below that spacing, it is carried over).
    let model = FallModel::default();
    let object = FallingObject::default();
    let tilt = WindTilt {
        max_angle: 0.6,
        reference_speed: 4.0,
    };
    let fall = |height: f32| {
        let release = FallRelease::at(Vec3::new(0.0, height, 0.0), height - 1000.0);
        let mut path = object.path(&model, release).unwrap();
        for _ in 0..240 {
            path.advance(&model, 1.0 / 60.0, Vec3::ZERO, &tilt);
        }
        path.position() - Vec3::new(0.0, height, 0.0)
    };
    let low = fall(10.0);
    assert!(low.y < -1.0, "the low fall came down only {low}");
    for height in [1e6f32, 5e6, 9.9e6] {
        let high = fall(height);
        let spacing = f32::EPSILON * height;
        assert!(
            (high - low).abs().max_element() <= 2.0 * spacing,
            "let go at {height} m: moved {high}, low down {low} (spacing {spacing} m)"
        );
    }
}

/// The value a refusal names, as `InvalidValue` promises: the offending component (NaN for a
/// NaN), not another component of the same vector.
fn refused_value(error: bevy_windfall::freefall::FallError) -> (&'static str, f32) {
    match error {
        bevy_windfall::freefall::FallError::Invalid(invalid) => (invalid.field, invalid.value),
        other => panic!("{other}"),
    }
}

fn same(a: f32, b: f32) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

/// A NaN anywhere in a release's velocity is refused (glam's `max_element` passes over a NaN, and
/// the fall started with no drift); a region's refusal names its offending component.
#[test]
fn refusals_name_the_offending_component() {
    let model = FallModel::default();
    let object = FallingObject::default();
    for (velocity, value) in [
        (Vec3::new(f32::NAN, 1.0, 0.0), f32::NAN),
        (Vec3::new(0.5, 0.0, f32::NAN), f32::NAN),
        (Vec3::new(1.0, -2e4, 3.0), -2e4),
        (Vec3::new(f32::INFINITY, 1.0, 0.0), f32::INFINITY),
    ] {
        let release = FallRelease {
            velocity,
            ..FallRelease::at(Vec3::new(0.0, 5.0, 0.0), 0.0)
        };
        for error in [
            release.validate().unwrap_err(),
            object.path(&model, release).unwrap_err(),
        ] {
            let (field, got) = refused_value(error);
            assert_eq!(field, "release.velocity", "{velocity}");
            assert!(same(got, value), "{velocity}: named {got}");
        }
    }
    let region = |min: Vec3, max: Vec3| LeafCloud {
        count: 10,
        region: CloudRegion { min, max },
        ..LeafCloud::default()
    };
    for (cloud, field, value) in [
        (
            region(Vec3::new(f32::NAN, 2.0, 2.0), Vec3::splat(3.0)),
            "region.min",
            f32::NAN,
        ),
        (
            region(Vec3::new(-2e7, 2.0, 2.0), Vec3::splat(3.0)),
            "region.min",
            -2e7,
        ),
        (
            region(Vec3::new(0.0, 2.0, 10.0), Vec3::new(1.0, 3.0, -40.0)),
            "region.max",
            -40.0,
        ),
        (
            region(Vec3::ZERO, Vec3::new(1.0, f32::INFINITY, 2.0)),
            "region.max",
            f32::INFINITY,
        ),
    ] {
        let (got_field, got) = refused_value(cloud.leaves(&model, 0.0).unwrap_err());
        assert_eq!(got_field, field);
        assert!(same(got, value), "{field}: named {got}, not {value}");
    }
}
