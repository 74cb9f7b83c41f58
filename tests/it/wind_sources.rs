//! Local wind sources: the public contract of `WindSource` (sphere, fan, vortex, blast), their
//! life in an app (next step on, despawn, move, parent), bad arguments, and every consumer
//! feeling them.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::aero::{PhysicalCloth, PhysicalClothState};
use bevy_windfall::freefall::FallRelease;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindSource;
use common::{STEP, headless_app, headless_app_with_meshes, ready};

/// Still air: no mean wind and no turbulence, so what blows is the sources.
fn still() -> WindConfig {
    WindConfig {
        reference_speed: 0.0,
        grid: [16, 16],
        ..default()
    }
}

fn app_with(config: WindConfig) -> App {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config));
    ready(&mut app);
    app
}

fn wind(app: &App, p: Vec3) -> Vec3 {
    app.world().resource::<WindField>().velocity(p)
}

#[test]
fn a_sphere_blows_its_velocity_at_the_centre_and_fades_to_nothing_at_its_radius() {
    let mut app = app_with(still());
    let centre = Vec3::new(5.0, 2.0, -1.0);
    let v = Vec3::new(0.0, 1.0, 4.0);
    app.world_mut().spawn((
        WindSource::sphere(3.0, v),
        Transform::from_translation(centre),
    ));
    assert_eq!(
        wind(&app, centre),
        Vec3::ZERO,
        "not before the next fixed step"
    );
    app.update();
    assert!((wind(&app, centre) - v).length() < 1e-5);
    // Monotone fade along any ray, continuous (no step of 1 cm changes it by more than 1 %).
    for dir in [Vec3::X, Vec3::NEG_Y, Vec3::new(1.0, 1.0, -1.0).normalize()] {
        let mut last = wind(&app, centre).length();
        for i in 1..=320 {
            let r = i as f32 * 0.01;
            let s = wind(&app, centre + dir * r).length();
            assert!(s <= last + 1e-6, "{dir} at {r}: {s} after {last}");
            assert!(
                last - s <= 0.01 * v.length(),
                "{dir} at {r}: jump {last} → {s}"
            );
            if r >= 3.0 {
                assert_eq!(s, 0.0, "{dir} at {r}");
            }
            last = s;
        }
    }
}

#[test]
fn a_fan_blows_forward_inside_its_cone_and_nowhere_else() {
    let mut app = app_with(still());
    // Facing +X: Transform::forward is local −Z turned to +X.
    let fan = Transform::from_xyz(0.0, 1.0, 0.0).looking_to(Vec3::X, Vec3::Y);
    app.world_mut()
        .spawn((WindSource::fan(10.0, 0.4, 6.0), fan));
    app.update();
    let at = |x: f32, y: f32, z: f32| wind(&app, Vec3::new(x, 1.0 + y, z));
    let axis = at(2.0, 0.0, 0.0);
    assert!(
        axis.x > 3.0 && axis.y.abs() < 1e-4 && axis.z.abs() < 1e-4,
        "{axis}"
    );
    assert!(at(5.0, 0.0, 0.0).x < axis.x, "weaker further along");
    assert!(at(5.0, 0.0, 0.0).x > 0.0);
    assert_eq!(at(-1.0, 0.0, 0.0), Vec3::ZERO, "nothing behind");
    assert_eq!(
        at(2.0, 0.0, 2.0),
        Vec3::ZERO,
        "nothing outside the cone (45° > 0.4 rad)"
    );
    assert_eq!(at(10.5, 0.0, 0.0), Vec3::ZERO, "nothing beyond its range");
    // Inside the cone the jet spreads outward, never against the fan's direction.
    for (y, z) in [(0.3, 0.0), (0.0, -0.5), (-0.4, 0.4)] {
        let v = at(3.0, y, z);
        assert!(v.x > 0.0, "{v}");
    }
}

#[test]
fn a_vortex_swirls_right_handed_about_local_y_with_a_rankine_core() {
    for (peak, tilt) in [(9.0f32, 0.0f32), (-9.0, 0.0), (9.0, 0.6)] {
        let mut app = app_with(still());
        let frame = Transform::from_xyz(2.0, 1.0, 3.0).with_rotation(Quat::from_rotation_x(tilt));
        app.world_mut()
            .spawn((WindSource::vortex(5.0, peak), frame));
        app.update();
        let world = |local: Vec3| frame.transform_point(local);
        let local_wind = |local: Vec3| frame.rotation.inverse() * wind(&app, world(local));
        // At local +X the wind blows toward local −Z (reversed for a negative peak).
        let at_x = local_wind(Vec3::new(1.0, 0.0, 0.0));
        assert!(at_x.z * peak.signum() < 0.0, "{peak} {tilt}: {at_x}");
        assert!(
            at_x.x.abs() < 1e-4 && at_x.y.abs() < 1e-4,
            "horizontal: {at_x}"
        );
        assert_eq!(local_wind(Vec3::ZERO), Vec3::ZERO, "calm on the axis");
        // Peaks at |peak| (at the core's edge) and falls off outside it.
        let speeds: Vec<f32> = (1..50)
            .map(|i| local_wind(Vec3::new(i as f32 * 0.1, 0.0, 0.0)).length())
            .collect();
        let max = speeds.iter().copied().fold(0.0, f32::max);
        assert!((max - peak.abs()).abs() < 0.05 * peak.abs(), "peak {max}");
        let at_peak = speeds.iter().position(|&s| s == max).unwrap();
        assert!(speeds[..at_peak].windows(2).all(|w| w[1] >= w[0]));
        assert!(speeds[at_peak..].windows(2).all(|w| w[1] <= w[0]));
        for far in [
            Vec3::new(5.01, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -6.0),
            Vec3::new(3.0, 4.5, 0.0),
        ] {
            assert_eq!(local_wind(far), Vec3::ZERO, "nothing beyond the radius");
        }
    }
}

#[test]
fn a_blast_runs_outward_once_and_is_gone() {
    let mut app = app_with(still());
    let centre = Vec3::new(0.0, 1.0, 0.0);
    let (peak, front, radius) = (20.0, 10.0, 8.0);
    app.world_mut().spawn((
        WindSource::blast(peak, front, radius),
        Transform::from_translation(centre),
    ));
    let dt = STEP.as_secs_f32();
    let mut fronts = Vec::new();
    for step in 0..120 {
        app.update();
        let age = step as f32 * dt;
        // After n steps the front is n steps out, blowing its peak right behind it.
        let front_now = (step + 1) as f32 * dt * front;
        if front_now > 0.2 && front_now < 0.5 * radius {
            let at_front = wind(&app, centre + Vec3::Z * (front_now - 0.01));
            assert!(at_front.length() > 0.95 * peak, "{front_now} m: {at_front}");
            assert_eq!(
                wind(&app, centre + Vec3::Z * (front_now + 0.01)),
                Vec3::ZERO
            );
        }
        // The strongest point along a ray, and no inward wind anywhere on three rays.
        let mut best = (0.0f32, 0.0f32);
        for dir in [Vec3::X, Vec3::new(-1.0, 0.5, 0.3).normalize(), Vec3::NEG_Z] {
            for i in 1..=100 {
                let r = i as f32 * 0.1;
                let v = wind(&app, centre + dir * r);
                assert!(v.dot(dir) >= -1e-5, "inward at {r} at {age} s: {v}");
                assert!(v.length() <= peak * 1.0001);
                if dir == Vec3::X && v.length() > best.1 {
                    best = (r, v.length());
                }
            }
        }
        if best.1 > 0.0 {
            fronts.push((age, best.0, best.1));
        } else if age > 0.2 {
            // Over once the front has passed the radius.
            assert!(
                age * front > radius,
                "calm at {age} s before its front reached {radius} m"
            );
        }
    }
    // The front travels at front_speed (the peak sits a tenth of the radius behind it).
    let (t0, r0, _) = fronts[10];
    let (t1, r1, _) = fronts[fronts.len() / 2];
    let speed = (r1 - r0) / (t1 - t0);
    assert!((speed - front).abs() < 0.1 * front, "front speed {speed}");
    let strongest = fronts.iter().map(|f| f.2).fold(0.0, f32::max);
    assert!(strongest > 0.9 * peak, "peak {strongest}");
    let last = fronts.last().unwrap();
    assert!(
        last.0 * front <= radius * 1.25,
        "still blowing at {} s",
        last.0
    );
    assert_eq!(wind(&app, centre + Vec3::X * 2.0), Vec3::ZERO);
}

#[test]
fn sources_follow_their_entity_and_stop_when_despawned() {
    let mut app = app_with(still());
    let source = app
        .world_mut()
        .spawn((
            WindSource::sphere(2.0, Vec3::X * 3.0),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ))
        .id();
    app.update();
    assert!(wind(&app, Vec3::new(0.0, 1.0, 0.0)).x > 2.9);
    // Moved: it blows where it is now from the next step.
    app.world_mut()
        .get_mut::<Transform>(source)
        .unwrap()
        .translation = Vec3::new(10.0, 1.0, 0.0);
    app.update();
    assert_eq!(wind(&app, Vec3::new(0.0, 1.0, 0.0)), Vec3::ZERO);
    assert!(wind(&app, Vec3::new(10.0, 1.0, 0.0)).x > 2.9);
    // Parented: carried by its parent's global transform.
    let parent = app
        .world_mut()
        .spawn(Transform::from_xyz(-20.0, 0.0, 0.0))
        .id();
    app.world_mut()
        .entity_mut(source)
        .insert((ChildOf(parent), Transform::from_xyz(0.0, 1.0, 0.0)));
    app.update();
    app.update();
    assert!(wind(&app, Vec3::new(-20.0, 1.0, 0.0)).x > 2.9);
    app.world_mut().despawn(source);
    app.update();
    assert_eq!(wind(&app, Vec3::new(-20.0, 1.0, 0.0)), Vec3::ZERO);
    assert_eq!(app.world().resource::<WindField>().source_count(), 0);
}

#[test]
fn sources_add_to_the_global_wind_in_every_sampler() {
    let mut app = app_with(WindConfig {
        grid: [16, 16],
        ..default()
    });
    app.world_mut().spawn((
        WindSource::sphere(50.0, Vec3::Y * 2.0),
        Transform::from_xyz(0.0, 5.0, 0.0),
    ));
    app.update();
    let field = app.world().resource::<WindField>();
    let p = Vec3::new(0.0, 5.0, 0.0);
    let t = field.time();
    let global = field.global_velocity_at(p, t);
    let total = field.velocity_at(p, t);
    assert!((total - global - Vec3::Y * 2.0).length() < 1e-4);
    assert_eq!(field.velocity(p), total);
    let mut out = Vec::new();
    field.velocities_at(&[p, p + Vec3::X * 100.0], t, &mut out);
    assert_eq!(out[0], total);
    assert_eq!(out[1], field.global_velocity_at(p + Vec3::X * 100.0, t));
}

#[test]
fn bad_arguments_are_named_never_nan() {
    // One constructor per shape keeps what it is given; `validate` (and the plugin, with a
    // `WindSourceInvalid`) names the first bad field.
    let e = |s: WindSource| s.validate().unwrap_err().field();
    assert_eq!(e(WindSource::sphere(-1.0, Vec3::X)), "shape.radius");
    assert_eq!(e(WindSource::sphere(1.0, Vec3::NAN)), "shape.velocity");
    assert_eq!(
        e(WindSource::sphere(1.0, Vec3::new(0.0, f32::NAN, 1.0))),
        "shape.velocity"
    );
    assert_eq!(e(WindSource::fan(f32::INFINITY, 0.3, 1.0)), "shape.range");
    assert_eq!(e(WindSource::fan(3.0, 2.0, 1.0)), "shape.half_angle");
    assert_eq!(e(WindSource::fan(3.0, -0.1, 1.0)), "shape.half_angle");
    assert_eq!(e(WindSource::fan(3.0, 0.3, f32::NAN)), "shape.speed");
    assert_eq!(e(WindSource::vortex(f32::NAN, 1.0)), "shape.radius");
    assert_eq!(
        e(WindSource::vortex(1.0, f32::INFINITY)),
        "shape.peak_speed"
    );
    assert_eq!(
        e(WindSource::vortex(1.0, 1.0).with_updraft(f32::NAN)),
        "shape.updraft"
    );
    assert_eq!(e(WindSource::blast(-5.0, 1.0, 1.0)), "shape.peak_speed");
    assert_eq!(
        e(WindSource::blast(5.0, f32::NAN, 1.0)),
        "shape.front_speed"
    );
    assert_eq!(e(WindSource::blast(5.0, 1.0, -1.0)), "shape.radius");
    assert_eq!(
        e(WindSource::gust(f32::NAN, 1.0, 1.0, 1.0)),
        "shape.strength"
    );
    assert_eq!(
        e(WindSource::gust(5.0, -1.0, 1.0, 1.0)),
        "shape.front_speed"
    );
    assert_eq!(
        e(WindSource::gust(5.0, 1.0, f32::INFINITY, 1.0)),
        "shape.width"
    );
    assert_eq!(e(WindSource::gust(5.0, 1.0, 1.0, -3.0)), "shape.range");
    for good in [
        WindSource::sphere(3.0, Vec3::X),
        WindSource::fan(3.0, 0.3, 1.0),
        WindSource::fan(3.0, std::f32::consts::FRAC_PI_2, -1.0),
        WindSource::vortex(3.0, -4.0).with_updraft(2.0),
        WindSource::blast(5.0, 1.0, 1.0),
        WindSource::gust(-5.0, 1.0, 1.0, 1.0),
    ] {
        assert!(good.validate().is_ok(), "{good:?}");
    }
    // Every hostile argument gives a finite field: what is refused blows nothing.
    let hostile = [
        f32::NAN,
        f32::INFINITY,
        -f32::INFINITY,
        -1.0,
        0.0,
        1e-45,
        1e30,
        f32::MAX,
    ];
    let mut app = app_with(still());
    for &a in &hostile {
        for &b in &hostile {
            let world = app.world_mut();
            world.spawn(WindSource::sphere(a, Vec3::splat(b)));
            world.spawn(WindSource::fan(a, b, a));
            world.spawn(WindSource::vortex(a, b).with_updraft(a));
            world.spawn(WindSource::blast(a, b, 3.0));
            world.spawn(WindSource::gust(a, b, a, b));
        }
    }
    for _ in 0..3 {
        app.update();
        for p in [
            Vec3::ZERO,
            Vec3::new(0.5, 0.1, -0.2),
            Vec3::splat(1e20),
            Vec3::NAN,
        ] {
            assert!(wind(&app, p).is_finite(), "{p}");
        }
    }
}

#[test]
fn every_consumer_feels_a_source() {
    // Each consumer twice, in still air: once inside a sphere blowing 6 m/s along +X, once
    // outside it; inside, it must move (or flap) downwind.
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(still())));
    ready(&mut app);
    let blow = Vec3::X * 6.0;
    let world = app.world_mut();
    world.spawn((
        WindSource::sphere(6.0, blow),
        Transform::from_xyz(0.0, 3.0, 0.0),
    ));
    let mut pairs = Vec::new();
    for x in [0.0, 40.0] {
        let at = Transform::from_xyz(x, 3.0, 0.0);
        let fall = world.spawn((FallingObject::default(), at)).id();
        let body = world.spawn((AeroBody::default(), at)).id();
        let cloth = world
            .spawn((
                Cloth {
                    grid: ClothGrid {
                        rows: 4,
                        columns: 6,
                        ..default()
                    },
                    ..default()
                },
                at,
            ))
            .id();
        let physical = world
            .spawn((
                PhysicalCloth {
                    grid: ClothGrid {
                        rows: 4,
                        columns: 6,
                        width: 1.0,
                        height: 0.6,
                    },
                    ..default()
                },
                at,
            ))
            .id();
        pairs.push([fall, body, cloth, physical]);
    }
    for _ in 0..120 {
        app.update();
    }
    let world = app.world();
    let drift = |e: Entity, x0: f32| world.get::<Transform>(e).unwrap().translation.x - x0;
    let [fall_in, body_in, cloth_in, physical_in] = pairs[0];
    let [fall_out, body_out, cloth_out, physical_out] = pairs[1];
    // Same seed and start: the difference is the wind's doing.
    let fall = drift(fall_in, 0.0) - drift(fall_out, 40.0);
    assert!(fall > 0.05, "falling object: {fall}");
    let body = drift(body_in, 0.0) - drift(body_out, 40.0);
    assert!(body > 0.2, "aero body: {body}");
    let speed = |e: Entity| world.get::<ClothState>(e).unwrap().wind_steps_per_frame;
    let (inside, outside) = (speed(cloth_in), speed(cloth_out));
    assert!(
        inside > 0.5 && outside == 0.0,
        "cloth |v|: {inside} against {outside}"
    );
    // The particle flag's free edge streams downwind (+X) inside, hangs outside (by centimetres
    // in these 2 s: a hanging sheet takes the wind up through the pressure on its folds).
    let tip_x = |e: Entity| {
        let cloth = &world.get::<PhysicalClothState>(e).unwrap().0;
        let g = cloth.grid();
        // The free edge's mean distance from the pole.
        let edge = (0..g.rows).map(|k| cloth.positions()[k * g.columns + g.columns - 1].x);
        edge.sum::<f32>() / g.rows as f32
    };
    assert!(
        tip_x(physical_in) > tip_x(physical_out) + 0.02,
        "particle cloth: {} against {}",
        tip_x(physical_in),
        tip_x(physical_out)
    );
}

#[test]
fn a_strong_enough_wind_lifts_resting_objects_again() {
    use bevy_windfall::freefall::FallState;
    let mut app = headless_app();
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(still())));
    ready(&mut app);
    // Leaves dropped from 5 cm: they come to rest on the ground (height 0).
    let leaves: Vec<Entity> = (0..6)
        .map(|i| {
            let leaf = FallingObject {
                seed: i,
                ..default()
            };
            let at = Transform::from_xyz(i as f32 * 3.0, 0.05, 0.0);
            app.world_mut().spawn((leaf, at)).id()
        })
        .collect();
    for _ in 0..60 {
        app.update();
    }
    let state = |app: &App, e: Entity| app.world().get::<FallState>(e).unwrap().clone();
    assert!(leaves.iter().all(|&e| state(&app, e).landed()));
    let u = state(&app, leaves[0]).regime().unwrap().descent_speed;
    // Just below the threshold on the first three leaves, just above on the others (a sphere of
    // 1 m around each: its centre is where the leaf lies).
    for (i, &e) in leaves.iter().enumerate() {
        let factor = if i < 3 { 0.9 } else { 1.1 } * FallRelease::LIFT_OFF_FACTOR;
        let at = app.world().get::<Transform>(e).unwrap().translation;
        app.world_mut().spawn((
            WindSource::sphere(1.0, Vec3::X * factor * u),
            Transform::from_translation(at),
        ));
    }
    let start: Vec<Vec3> = leaves
        .iter()
        .map(|&e| app.world().get::<Transform>(e).unwrap().translation)
        .collect();
    let mut highest = [0.0f32; 6];
    for _ in 0..30 {
        app.update();
        for (i, &e) in leaves.iter().enumerate() {
            highest[i] = highest[i].max(app.world().get::<Transform>(e).unwrap().translation.y);
        }
    }
    for i in 0..3 {
        assert!(
            state(&app, leaves[i]).landed() && highest[i] == 0.0,
            "{i}: {highest:?}"
        );
    }
    // Above it they skitter downwind in hops (a leaf follows the air within a few
    // hundredths of a second, so a level wind lifts it only a little).
    for i in 3..6 {
        assert!(highest[i] > 0.005, "leaf {i} was not lifted: {highest:?}");
        let moved = app.world().get::<Transform>(leaves[i]).unwrap().translation - start[i];
        assert!(moved.x > 0.05, "leaf {i} moved {moved}");
    }
}

#[test]
fn a_blast_sweeps_leaves_off_the_ground_but_not_a_coin() {
    let mut app = headless_app();
    app.add_plugins(WindfallPlugins::default().set(WindPlugin::new(still())));
    ready(&mut app);
    let coin = FallingObject {
        fluid: bevy_windfall::freefall::Fluid::AIR,
        ..common::paper_coin()
    };
    let leaves: Vec<Entity> = (0..8)
        .map(|i| {
            let a = i as f32 * std::f32::consts::TAU / 8.0;
            let at = Transform::from_xyz(2.0 * a.cos(), 0.02, 2.0 * a.sin());
            let leaf = FallingObject {
                seed: i,
                ..default()
            };
            app.world_mut().spawn((leaf, at)).id()
        })
        .collect();
    let coin = app
        .world_mut()
        .spawn((coin, Transform::from_xyz(0.0, 0.02, -1.2)))
        .id();
    for _ in 0..60 {
        app.update();
    }
    let at = |app: &App, e: Entity| app.world().get::<Transform>(e).unwrap().translation;
    let before: Vec<Vec3> = leaves.iter().map(|&e| at(&app, e)).collect();
    let coin_before = at(&app, coin);
    // A burst at ground level: its centre a metre down, so the flow leaves the ground upward
    // and outward, as from a real explosion.
    app.world_mut().spawn((
        WindSource::blast(15.0, 12.0, 6.0),
        Transform::from_xyz(0.0, -1.0, 0.0),
    ));
    let mut highest = 0.0f32;
    for _ in 0..120 {
        app.update();
        for &e in &leaves {
            highest = highest.max(at(&app, e).y);
        }
    }
    assert!(highest > 0.3, "leaves rose to {highest} m");
    for (&e, b) in leaves.iter().zip(&before) {
        let moved = at(&app, e) - *b;
        // Swept outward, away from the blast.
        let outward = Vec3::new(b.x, 0.0, b.z).normalize();
        assert!(moved.dot(outward) > 0.2, "leaf at {b} moved {moved}");
    }
    assert_eq!(
        at(&app, coin),
        coin_before,
        "a 15 m/s blast does not lift a coin"
    );
}

#[test]
fn a_gust_front_sweeps_downwind_once() {
    let mut app = app_with(still());
    // Pointed along +X (its forward), from x = 0: 6 m/s, front at 8 m/s, 3 m thick, 40 m.
    let start = Transform::from_xyz(0.0, 1.0, 0.0).looking_to(Vec3::X, Vec3::Y);
    app.world_mut()
        .spawn((WindSource::gust(6.0, 8.0, 3.0, 40.0), start));
    let probe = Vec3::new(20.0, 1.0, 2.0);
    let dt = STEP.as_secs_f32();
    let mut felt = Vec::new();
    for step in 0..400 {
        app.update();
        let v = wind(&app, probe);
        assert!(v.y.abs() < 1e-5 && v.z.abs() < 1e-5 && v.x >= 0.0, "{v}");
        felt.push((step as f32 * dt, v.x));
        // Nothing behind the start or beyond its range.
        assert_eq!(wind(&app, Vec3::new(-1.0, 1.0, 0.0)), Vec3::ZERO);
        assert_eq!(wind(&app, Vec3::new(41.0, 1.0, 0.0)), Vec3::ZERO);
    }
    let arrived = felt.iter().find(|f| f.1 > 0.0).unwrap().0;
    let left = felt.iter().rev().find(|f| f.1 > 0.0).unwrap().0;
    // It reaches x = 20 at 20 / 8 = 2.5 s and takes 3 / 8 s to pass.
    assert!((arrived - 2.5).abs() < 0.05, "arrived at {arrived} s");
    assert!(
        (left - arrived - 3.0 / 8.0).abs() < 0.05,
        "passed in {} s",
        left - arrived
    );
    let strongest = felt.iter().map(|f| f.1).fold(0.0, f32::max);
    // At 2 m off its centre line (of 20 m half-width) it is a little under its strength.
    assert!(strongest > 0.9 * 6.0 && strongest <= 6.0, "{strongest}");
    assert!(felt.last().unwrap().1 == 0.0);
}

#[test]
fn a_pulsing_source_swells_from_when_it_starts() {
    let mut app = app_with(still());
    let v = Vec3::new(6.0, 0.0, 0.0);
    // ±50 % once every 60 steps, so a quarter period is 15 steps.
    let dt = STEP.as_secs_f32();
    let rate = 2.0 * std::f32::consts::PI / (60.0 * dt); // rad/s
    app.world_mut().spawn((
        WindSource::sphere(4.0, v).with_pulse(0.5, 1.0 / (60.0 * dt)),
        Transform::default(),
    ));
    let mut speeds = Vec::new();
    for _ in 0..64 {
        app.update();
        speeds.push(wind(&app, Vec3::ZERO).x);
    }
    // Full strength when it starts (speeds[k] is k + 1 steps in), the peak a quarter period
    // later, the trough at three quarters.
    assert!(
        (speeds[0] - 6.0).abs() <= 3.0 * rate * dt * 1.01,
        "{}",
        speeds[0]
    );
    let (peak, trough) = (speeds[14], speeds[44]);
    assert!((peak - 9.0).abs() < 0.02, "{peak}");
    assert!((trough - 3.0).abs() < 0.02, "{trough}");
    let largest = speeds.iter().cloned().fold(0.0, f32::max);
    assert!((largest - 9.0).abs() < 0.01);
    // Smooth: no step changes it by more than its largest rate, 3 m/s × ω × dt.
    for w in speeds.windows(2) {
        assert!((w[1] - w[0]).abs() <= 3.0 * rate * dt * 1.01);
    }
    // Out-of-range pulses are clamped, never NaN.
    let wild = WindSource::sphere(1.0, v).with_pulse(f32::NAN, f32::INFINITY);
    assert!(!wild.pulse.is_active());
    let clamped = WindSource::sphere(1.0, v).with_pulse(7.0, 1e9);
    assert!(clamped.pulse.validate().is_ok());
}
