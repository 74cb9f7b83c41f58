//! Hostile input, third round, on local wind: a source with a non-finite or huge number set by
//! hand blows nothing (or a bounded amount) and never cancels the valid sources beside it; a
//! blast never blows inward, whatever the sign of its strength or speed; sizes beyond the world
//! are refused by name (`validate` and the `WindSourceInvalid` marker) and blow nothing.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::{
    ShelterKind, SourceShape, WindShelter, WindShelterInvalid, WindSource, WindSourceInvalid,
};
use common::{headless_app, ready};

/// Still air: what blows is the sources.
fn still_app() -> App {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(WindConfig {
        reference_speed: 0.0,
        grid: [16, 16],
        ..default()
    }));
    ready(&mut app);
    app
}

fn wind(app: &App, p: Vec3) -> Vec3 {
    app.world().resource::<WindField>().velocity(p)
}

/// A valid 5 m/s sphere at the origin, and `bad` (if any) 1 m beside it; the wind at three
/// points the two share, after two steps.
fn beside(bad: Option<WindSource>) -> Vec<Vec3> {
    let mut app = still_app();
    app.world_mut().spawn((
        WindSource::sphere(3.0, Vec3::X * 5.0),
        Transform::from_xyz(0.0, 2.0, 0.0),
    ));
    if let Some(bad) = bad {
        app.world_mut()
            .spawn((bad, Transform::from_xyz(1.0, 2.0, 0.0)));
    }
    app.update();
    app.update();
    [
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(0.5, 2.2, 0.3),
        Vec3::new(1.2, 1.9, -0.4),
    ]
    .map(|p| wind(&app, p))
    .to_vec()
}

#[test]
fn one_bad_source_never_cancels_the_others() {
    let alone = beside(None);
    assert!(alone[0].x > 4.9, "the valid sphere blows: {:?}", alone);
    let with = |shape| WindSource {
        shape,
        ..WindSource::default()
    };
    // Numbers no constructor gives, set in the public fields: they blow nothing.
    let silent = [
        with(SourceShape::Sphere {
            radius: 3.0,
            velocity: Vec3::new(f32::NAN, 0.0, 0.0),
        }),
        with(SourceShape::Fan {
            range: 5.0,
            half_angle: 0.5,
            speed: f32::NAN,
        }),
        with(SourceShape::Vortex {
            radius: 4.0,
            peak_speed: f32::INFINITY,
            updraft: 0.0,
        }),
        with(SourceShape::Vortex {
            radius: 4.0,
            peak_speed: 5.0,
            updraft: f32::NAN,
        }),
        with(SourceShape::Gust {
            strength: f32::NAN,
            front_speed: 2.0,
            width: 2.0,
            range: 10.0,
        }),
    ];
    for bad in silent {
        assert_eq!(beside(Some(bad)), alone, "{bad:?}");
    }
    // Huge but finite: bounded, added to the valid one (both blow along +X).
    let huge = [
        WindSource {
            strength: f32::MAX,
            ..WindSource::sphere(3.0, Vec3::X)
        },
        WindSource::sphere(3.0, Vec3::X * f32::MAX),
    ];
    for bad in huge {
        for (v, lone) in beside(Some(bad)).iter().zip(&alone) {
            assert!(v.is_finite(), "{bad:?}: {v}");
            assert!(v.x >= lone.x, "{bad:?}: {v} beside {lone}");
        }
    }
}

#[test]
fn two_huge_sources_sum_to_a_finite_wind() {
    let mut app = still_app();
    for _ in 0..2 {
        app.world_mut().spawn((
            WindSource::sphere(3.0, Vec3::X * f32::MAX),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ));
    }
    app.update();
    let v = wind(&app, Vec3::new(0.2, 2.0, 0.0));
    assert!(v.is_finite() && v.x > 1e5, "{v}");
}

#[test]
fn a_blast_never_blows_inward() {
    let inverted = [
        WindSource {
            strength: -1.0,
            ..WindSource::blast(20.0, 10.0, 8.0)
        },
        WindSource {
            strength: -0.5,
            ..WindSource::blast(20.0, 10.0, 8.0).with_pulse(0.9, 2.0)
        },
        WindSource {
            shape: SourceShape::Blast {
                peak_speed: -20.0,
                front_speed: 10.0,
                radius: 8.0,
            },
            ..WindSource::default()
        },
    ];
    for blast in inverted {
        let mut app = still_app();
        let centre = Vec3::new(0.0, 1.0, 0.0);
        app.world_mut()
            .spawn((blast, Transform::from_translation(centre)));
        for step in 0..60 {
            app.update();
            for dir in [Vec3::X, Vec3::new(-1.0, 0.4, 0.2).normalize(), Vec3::NEG_Z] {
                for i in 1..=80 {
                    let r = 0.1 * i as f32;
                    let v = wind(&app, centre + dir * r);
                    assert!(
                        v.dot(dir) >= -1e-5,
                        "{blast:?}: inward {v} at {r} m, step {step}"
                    );
                }
            }
        }
    }
}

#[test]
fn sizes_beyond_the_world_are_refused_by_name() {
    let far = 2.4e38;
    let field = |s: WindSource| s.validate().unwrap_err().field();
    assert_eq!(field(WindSource::gust(1.0, 1.0, 1.0, far)), "shape.range");
    assert_eq!(field(WindSource::gust(1.0, 1.0, far, 1.0)), "shape.width");
    assert_eq!(field(WindSource::sphere(1e8, Vec3::X)), "shape.radius");
    assert_eq!(field(WindSource::fan(f32::MAX, 0.5, 1.0)), "shape.range");
    assert_eq!(field(WindSource::vortex(1e30, 1.0)), "shape.radius");
    assert_eq!(field(WindSource::blast(1.0, 1.0, 1e30)), "shape.radius");
    // Spawned, such a source blows nothing and is marked; one at the world's edge blows.
    let mut app = still_app();
    let refused = app
        .world_mut()
        .spawn((
            WindSource::sphere(f32::MAX, Vec3::X * 3.0),
            Transform::from_xyz(0.0, 2.0, 0.0),
        ))
        .id();
    app.update();
    assert_eq!(wind(&app, Vec3::new(1.0, 2.0, 0.0)), Vec3::ZERO);
    let marker = app
        .world()
        .get::<WindSourceInvalid>(refused)
        .expect("marked");
    assert_eq!(marker.0.field(), "shape.radius");
    let mut app = still_app();
    app.world_mut().spawn((
        WindSource::sphere(bevy_windfall::MAX_COORDINATE, Vec3::X * 3.0),
        Transform::from_xyz(0.0, 2.0, 0.0),
    ));
    app.update();
    let v = wind(&app, Vec3::new(1.0, 2.0, 0.0));
    assert!((v.x - 3.0).abs() < 1e-3, "{v}");
}

/// Wind the sources blow at `p` a step after they are spawned, in a field whose own wind is
/// `speed` m/s.
fn app_at(speed: f32) -> App {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(WindConfig {
        reference_speed: speed,
        grid: [16, 16],
        ..default()
    }));
    ready(&mut app);
    app
}

#[test]
fn scale_neither_removes_nor_turns_a_source_or_a_shelter() {
    let scales = [
        Vec3::ZERO,
        Vec3::splat(1e-25),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::splat(1e20),
        Vec3::splat(1e30),
        Vec3::new(1.0, 1.0, -1.0),
        Vec3::splat(-1.0),
        Vec3::splat(-2.5),
    ];
    for scale in scales {
        let mut app = still_app();
        let at = |x: f32| Transform::from_xyz(x, 2.0, 0.0).with_scale(scale);
        app.world_mut()
            .spawn((WindSource::sphere(3.0, Vec3::X * 5.0), at(0.0)));
        // A fan facing +X (its forward), and a vortex with an updraft.
        let fan = at(20.0).looking_to(Vec3::X, Vec3::Y);
        app.world_mut().spawn((WindSource::fan(6.0, 0.5, 5.0), fan));
        app.world_mut()
            .spawn((WindSource::vortex(4.0, 6.0).with_updraft(2.0), at(-20.0)));
        app.update();
        let sphere = wind(&app, Vec3::new(0.0, 2.0, 0.0));
        assert!(
            (sphere.x - 5.0).abs() < 1e-3,
            "scale {scale}: sphere {sphere}"
        );
        let ahead = wind(&app, Vec3::new(22.0, 2.0, 0.0));
        let behind = wind(&app, Vec3::new(18.0, 2.0, 0.0));
        assert!(
            ahead.x > 1.0 && behind == Vec3::ZERO,
            "scale {scale}: fan {ahead}, {behind}"
        );
        // Right-handed about +Y: at local +X the wind blows toward −Z; the updraft lifts.
        let swirl = wind(&app, Vec3::new(-19.6, 2.0, 0.0));
        assert!(
            swirl.z < -1.0 && swirl.y > 0.0,
            "scale {scale}: vortex {swirl}"
        );
    }
    // A room keeps the wind out at any scale.
    for scale in scales {
        let mut app = app_at(6.0);
        let room = Transform::from_xyz(0.0, 2.0, 0.0).with_scale(scale);
        app.world_mut()
            .spawn((WindShelter::indoor(Vec3::splat(2.0)), room));
        app.update();
        let inside = wind(&app, Vec3::new(0.0, 2.0, 0.0));
        let outside = wind(&app, Vec3::new(0.0, 2.0, 30.0));
        assert!(
            inside.length() < 1e-3 && outside.length() > 1.0,
            "scale {scale}: {inside}"
        );
    }
}

#[test]
fn a_parented_source_blows_where_its_parent_puts_it_from_its_first_step() {
    let mut app = still_app();
    let parent = app
        .world_mut()
        .spawn((Transform::from_xyz(50.0, 0.0, 0.0), Visibility::default()))
        .id();
    let child = app
        .world_mut()
        .spawn((
            WindSource::sphere(2.0, Vec3::X * 4.0),
            Transform::from_xyz(0.0, 2.0, 0.0),
            ChildOf(parent),
        ))
        .id();
    app.update();
    assert!((wind(&app, Vec3::new(50.0, 2.0, 0.0)).x - 4.0).abs() < 1e-4);
    assert_eq!(wind(&app, Vec3::new(0.0, 2.0, 0.0)), Vec3::ZERO);
    // Moved: it blows at the new place the next step, and no longer at the old one.
    app.world_mut()
        .get_mut::<Transform>(parent)
        .unwrap()
        .translation
        .x = 80.0;
    app.update();
    assert!((wind(&app, Vec3::new(80.0, 2.0, 0.0)).x - 4.0).abs() < 1e-4);
    assert_eq!(wind(&app, Vec3::new(50.0, 2.0, 0.0)), Vec3::ZERO);
    // A zero-scale parent still places it (at its own origin, the child's offset scaled away).
    app.world_mut().get_mut::<Transform>(parent).unwrap().scale = Vec3::ZERO;
    app.update();
    assert!((wind(&app, Vec3::new(80.0, 0.0, 0.0)).x - 4.0).abs() < 1e-4);
    assert!(app.world().get::<WindSourceInvalid>(child).is_none());
}

#[test]
fn bad_sources_and_shelters_are_marked_and_blow_nothing() {
    let mut app = app_at(6.0);
    let wall = app
        .world_mut()
        .spawn((
            WindShelter {
                kind: ShelterKind::Wall {
                    lee_heights: 8.0,
                    depth: f32::NAN,
                },
                half_extents: Vec3::new(0.1, 1.0, 3.0),
            },
            Transform::from_xyz(0.0, 1.0, 0.0),
        ))
        .id();
    let shape = SourceShape::Fan {
        range: 5.0,
        half_angle: 0.5,
        speed: f32::NAN,
    };
    let fan = app
        .world_mut()
        .spawn((
            WindSource { shape, ..default() },
            Transform::from_xyz(0.0, 1.0, 5.0),
        ))
        .id();
    let lost = app
        .world_mut()
        .spawn((
            WindSource::default(),
            Transform::from_xyz(f32::NAN, 1.0, 0.0),
        ))
        .id();
    app.update();
    let field_of =
        |e: Entity, app: &App| app.world().get::<WindSourceInvalid>(e).map(|i| i.0.field());
    // A shelter reports through its own marker.
    let shelter_field = app
        .world()
        .get::<WindShelterInvalid>(wall)
        .map(|i| i.0.field());
    assert_eq!(shelter_field, Some("kind.depth"));
    assert!(app.world().get::<WindSourceInvalid>(wall).is_none());
    assert_eq!(field_of(fan, &app), Some("shape.speed"));
    assert_eq!(field_of(lost, &app), Some("transform"));
    for p in [
        Vec3::new(0.2, 1.9, 0.0),
        Vec3::new(1.0, 1.0, 0.5),
        Vec3::new(0.0, 1.0, 4.0),
    ] {
        let v = wind(&app, p);
        assert!(v.is_finite() && v.length() > 1.0, "{p}: {v}");
    }
    // Fixed: the marker goes, the wall shelters again.
    app.world_mut().get_mut::<WindShelter>(wall).unwrap().kind = ShelterKind::Wall {
        lee_heights: 8.0,
        depth: 0.85,
    };
    app.update();
    assert!(app.world().get::<WindShelterInvalid>(wall).is_none());
}

#[test]
fn a_finished_one_shot_stays_finished_when_the_field_is_replaced() {
    let config = WindConfig {
        reference_speed: 0.0,
        grid: [16, 16],
        ..default()
    };
    let mut app = still_app();
    app.world_mut().spawn((
        WindSource::blast(20.0, 20.0, 4.0),
        Transform::from_xyz(0.0, 1.0, 0.0),
    ));
    app.world_mut().spawn((
        WindSource::gust(5.0, 10.0, 2.0, 6.0),
        Transform::from_xyz(0.0, 1.0, 20.0).looking_to(Vec3::NEG_Z, Vec3::Y),
    ));
    // Both pass within a second.
    for _ in 0..90 {
        app.update();
    }
    // A field inserted by hand starts its clock at 0 again: the one-shots must not fire again.
    app.world_mut()
        .insert_resource(WindField::new(config).unwrap());
    for step in 0..30 {
        app.update();
        for p in [
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(2.5, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 18.0),
        ] {
            assert_eq!(wind(&app, p), Vec3::ZERO, "step {step} at {p}");
        }
    }
}

/// A one-shot refused by its checks is not counted finished: fixed in place, it loses its marker
/// and fires (a refused blast used to count as finished at once and keep its marker for good).
#[test]
fn a_refused_blast_fixed_in_place_fires() {
    let mut app = still_app();
    let blast = app
        .world_mut()
        .spawn((
            WindSource::blast(20.0, f32::INFINITY, 8.0),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ))
        .id();
    for _ in 0..5 {
        app.update();
    }
    let marker = app.world().get::<WindSourceInvalid>(blast).expect("marked");
    assert_eq!(marker.0.field(), "shape.front_speed");
    *app.world_mut().get_mut::<WindSource>(blast).unwrap() = WindSource::blast(20.0, 10.0, 8.0);
    let mut strongest = 0.0f32;
    for _ in 0..30 {
        app.update();
        for r in [1.0, 2.0, 3.0, 4.0] {
            strongest = strongest.max(wind(&app, Vec3::new(r, 1.0, 0.0)).x);
        }
    }
    assert!(app.world().get::<WindSourceInvalid>(blast).is_none());
    assert!(
        strongest > 5.0,
        "the fixed blast blew {strongest} m/s at most"
    );
}
