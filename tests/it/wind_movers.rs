//! `WindMover`: the air a moving body pushes. Its flow against potential flow round a sphere
//! (the values, no flow through the body, no divergence), the ground as a mirror, the wake's
//! momentum and decay, its velocity from its transform (none standing still, on its first step
//! or after a teleport), leaves lifted on its path and not beside it, and bad input.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::freefall::FallState;
use bevy_windfall::prelude::*;
use bevy_windfall::wind::WindMoverInvalid;
use common::{STEP, headless_app, ready};

/// Still air: what blows is the movers.
fn still() -> WindConfig {
    WindConfig {
        reference_speed: 0.0,
        grid: [16, 16],
        ..default()
    }
}

/// Moves its entity at this velocity every fixed step, before the wind is placed.
#[derive(Component, Clone, Copy)]
struct Walk(Vec3);

fn walk(time: Res<Time>, mut walkers: Query<(&Walk, &mut Transform)>) {
    for (walk, mut t) in &mut walkers {
        t.translation += walk.0 * time.delta_secs();
    }
}

fn app_with<M>(plugins: impl bevy::app::Plugins<M>) -> App {
    let mut app = headless_app();
    app.add_plugins(plugins)
        .add_systems(FixedUpdate, walk.before(WindfallSystems::Wind));
    ready(&mut app);
    app
}

fn wind_app() -> App {
    app_with(WindPlugin::new(still()))
}

fn wind(app: &App, p: Vec3) -> Vec3 {
    app.world().resource::<WindField>().velocity(p)
}

fn centre(app: &App, e: Entity) -> Vec3 {
    app.world().get::<Transform>(e).unwrap().translation
}

/// Potential flow round a sphere of radius `r` moving at `v`, at `d` from its centre (Lamb,
/// Hydrodynamics §92): the velocity potential φ = −(R³ / 2 r²) v · r̂.
fn potential(d: Vec3, v: Vec3, r: f32) -> Vec3 {
    let (length, n) = (d.length(), d.normalize());
    (n * (3.0 * v.dot(n)) - v) * (0.5 * (r / length).powi(3))
}

/// A mover of `radius` walking at `v` from `at`, high above any ground, after `steps` steps.
fn walking(radius: f32, v: Vec3, at: Vec3, steps: usize) -> (App, Entity) {
    let mut app = wind_app();
    let mover = WindMover {
        radius,
        ground: f32::NEG_INFINITY,
        ..default()
    };
    let e = app
        .world_mut()
        .spawn((mover, Walk(v), Transform::from_translation(at)))
        .id();
    for _ in 0..steps {
        app.update();
    }
    (app, e)
}

#[test]
fn in_front_and_at_the_sides_the_flow_is_potential_flow_round_a_sphere() {
    let (radius, v) = (0.5, Vec3::new(6.0, 0.0, 2.0));
    let (app, e) = walking(radius, v, Vec3::new(0.0, 20.0, 0.0), 4);
    let c = centre(&app, e);
    let ahead = v.normalize();
    let side = ahead.cross(Vec3::Y);
    // Ahead, 45° and 70° off the path, at the side (level and below), at 2, 3 and 5 radii.
    let directions = [
        ahead,
        (ahead + side).normalize(),
        (ahead * 0.34 + Vec3::NEG_Y * 0.94).normalize(),
        side,
        Vec3::NEG_Y,
        (side - Vec3::Y).normalize(),
    ];
    for n in directions {
        for k in [2.0, 3.0, 5.0] {
            let d = n * (k * radius);
            let (got, want) = (wind(&app, c + d), potential(d, v, radius));
            assert!(
                (got - want).length() <= 0.1 * want.length(),
                "{n} at {k} radii: {got} against potential flow {want}"
            );
        }
    }
    // The air slips round the body: on its surface it moves with the body across it
    // (u · n = v · n) in front and at the sides.
    for n in directions {
        let u = wind(&app, c + n * radius);
        assert!(
            (u - v).dot(n).abs() <= 1e-3 * v.length(),
            "{n}: u·n {} against v·n {}",
            u.dot(n),
            v.dot(n)
        );
    }
    // Incompressible: no divergence at 1.5–5 radii (central differences over 1 % of a radius).
    let h = 0.01 * radius;
    for n in directions {
        for k in [1.5, 2.5, 4.0] {
            let p = c + n * (k * radius);
            let derivative =
                |axis: Vec3| (wind(&app, p + axis * h) - wind(&app, p - axis * h)) / (2.0 * h);
            let (dx, dy, dz) = (
                derivative(Vec3::X),
                derivative(Vec3::Y),
                derivative(Vec3::Z),
            );
            let divergence = dx.x + dy.y + dz.z;
            let scale = dx.abs().max(dy.abs()).max(dz.abs()).max_element();
            assert!(
                divergence.abs() <= 0.02 * scale,
                "{n} at {k} radii: div u = {divergence} (gradients up to {scale})"
            );
        }
    }
}

#[test]
fn the_ground_is_a_mirror_no_air_goes_through_it_and_the_flow_along_it_doubles() {
    let (radius, v) = (0.4, Vec3::new(7.0, 0.0, 0.0));
    let run = |ground: f32| {
        let mut app = wind_app();
        let mover = WindMover {
            radius,
            ground,
            ..default()
        };
        // Its lowest point a hand-width (10 cm) above the ground at 0.
        let e = app
            .world_mut()
            .spawn((mover, Walk(v), Transform::from_xyz(0.0, radius + 0.1, 0.0)))
            .id();
        for _ in 0..4 {
            app.update();
        }
        (app, e)
    };
    let (floor, e) = run(0.0);
    let (open, _) = run(f32::NEG_INFINITY);
    let c = centre(&floor, e);
    for x in [-1.5f32, -0.6, 0.0, 0.3, 0.5, 0.8, 1.2] {
        for z in [0.0f32, 0.3, 0.9] {
            let p = Vec3::new(c.x + x, 0.0, z);
            let (on, off) = (wind(&floor, p), wind(&open, p));
            assert!(
                on.y.abs() <= 1e-4 * v.length(),
                "{p}: through the ground {on}"
            );
            if x >= 0.0 {
                // Under the body and in front of it (no wake there): the flow along the
                // ground doubles.
                let along = Vec3::new(on.x, 0.0, on.z);
                let without = Vec3::new(off.x, 0.0, off.z);
                assert!(
                    (along - 2.0 * without).length() <= 0.02 * without.length() + 1e-5,
                    "{p}: {along} with the ground, {without} without"
                );
            }
        }
    }
}

#[test]
fn behind_the_body_the_wake_carries_its_drag_and_decays() {
    let (radius, speed) = (0.5, 8.0);
    let v = Vec3::new(speed, 0.0, 0.0);
    let (app, e) = walking(radius, v, Vec3::new(0.0, 30.0, 0.0), 4);
    let c = centre(&app, e);
    let diameter = 2.0 * radius;
    // The momentum the wake carries through a plane across it, ∫ u_x dA (midpoint rule over a
    // disk of 6 radii), at 4, 5 and 6 diameters behind (past the dipole's reach).
    let flux = |behind: f32| {
        let (rings, spokes, outer) = (120, 64, 6.0 * radius);
        let mut sum = 0.0f64;
        for i in 0..rings {
            let rho = (i as f32 + 0.5) * outer / rings as f32;
            for j in 0..spokes {
                let angle = std::f32::consts::TAU * j as f32 / spokes as f32;
                let p = c + Vec3::new(-behind, rho * angle.cos(), rho * angle.sin());
                let area = rho * (outer / rings as f32) * std::f32::consts::TAU / spokes as f32;
                sum += f64::from(wind(&app, p).x * area);
            }
        }
        sum as f32
    };
    // A sphere's drag ½ ρ U² C_D π R² (C_D ≈ 0.47 at Re 10⁴–10⁵) is the wake's momentum
    // ρ U ∫ u dA: ∫ u dA = ½ U C_D π R².
    let drag = 0.5 * speed * 0.47 * std::f32::consts::PI * radius * radius;
    let fluxes: Vec<f32> = [4.0, 5.0, 6.0].map(|k| flux(k * diameter)).to_vec();
    println!("wake momentum at 4, 5, 6 diameters: {fluxes:?} m³/s (drag's {drag})");
    for (k, f) in [4.0, 5.0, 6.0].iter().zip(&fluxes) {
        assert!(
            (f - drag).abs() <= 0.1 * drag,
            "{k} diameters behind: {f} m³/s against the drag's {drag}"
        );
    }
    // The centre line slows as x^−2/3 (a virtual origin within a diameter or so).
    let centre_line = |k: f32| wind(&app, c - v.normalize() * (k * diameter)).x;
    let (near, far) = (centre_line(4.0), centre_line(6.0));
    let slope = (far / near).ln() / (6.0f32 / 4.0).ln();
    println!("centre line {near} → {far} m/s: slope {slope}");
    assert!(near > 0.05 * speed && far < near, "{near} {far}");
    assert!(
        (-0.8..=-0.4).contains(&slope),
        "centre line {near} → {far}: slope {slope}"
    );
    // Along the body's path, never backward; and nothing at all 21 radii away.
    for k in 1..40 {
        let u = wind(&app, c - Vec3::X * (k as f32 * 0.5 * radius));
        assert!(u.x >= -1e-6, "{k}: {u}");
    }
    assert_eq!(wind(&app, c - Vec3::X * (21.0 * radius)), Vec3::ZERO);
}

#[test]
fn standing_still_on_its_first_step_and_after_a_teleport_it_makes_no_wind() {
    let mut app = wind_app();
    let mover = WindMover {
        radius: 0.5,
        ..default()
    };
    let e = app
        .world_mut()
        .spawn((
            mover,
            Walk(Vec3::new(5.0, 0.0, 0.0)),
            Transform::from_xyz(0.0, 1.0, 0.0),
        ))
        .id();
    let near = |app: &App| wind(app, centre(app, e) + Vec3::new(0.0, 0.0, 1.0));
    app.update();
    // Its first step: nowhere to have come from.
    assert_eq!(app.world().resource::<WindField>().mover_count(), 0);
    assert_eq!(near(&app), Vec3::ZERO);
    app.update();
    assert_eq!(app.world().resource::<WindField>().mover_count(), 1);
    assert!(near(&app).length() > 0.1, "{}", near(&app));
    // A jump of 100 m in one step: no wind, then it blows again from there.
    app.world_mut()
        .get_mut::<Transform>(e)
        .unwrap()
        .translation
        .x += 100.0;
    app.update();
    assert_eq!(near(&app), Vec3::ZERO);
    app.update();
    assert!(near(&app).length() > 0.1);
    // Stopping: after two still steps, exactly nothing anywhere.
    app.world_mut().entity_mut(e).remove::<Walk>();
    app.update();
    app.update();
    assert_eq!(app.world().resource::<WindField>().mover_count(), 0);
    for k in 0..20 {
        let p = centre(&app, e) + Vec3::new(k as f32 * 0.3 - 3.0, 0.2, 0.1);
        assert_eq!(wind(&app, p), Vec3::ZERO);
    }
}

/// `count` maple leaves dropped on the ground along z = 0 … (a row across x), landed in still
/// air, then a body of `radius` passing along +X at `speed` with its lowest point `clearance`
/// above them, `beside` m to the side of the row. Returns for each leaf whether it left the
/// ground.
fn leaves_after_a_pass(speed: f32, beside: f32) -> Vec<bool> {
    let mut app = app_with(WindfallPlugins::default().set(WindPlugin::new(still())));
    let leaves: Vec<Entity> = (0..12)
        .map(|i| {
            let leaf = FallingObject {
                seed: i,
                ..FallPreset::MapleLeaf.object()
            };
            let at = Transform::from_xyz(i as f32 * 0.5, 0.05, 0.0);
            app.world_mut().spawn((leaf, at)).id()
        })
        .collect();
    for _ in 0..90 {
        app.update();
    }
    let state = |app: &App, e: Entity| app.world().get::<FallState>(e).unwrap().clone();
    assert!(leaves.iter().all(|&e| state(&app, e).landed()));
    let rest: Vec<Vec3> = leaves.iter().map(|&e| centre(&app, e)).collect();
    // A dog-sized body, 10 cm clear of the ground.
    let radius = 0.3;
    let mover = WindMover {
        radius,
        ..default()
    };
    app.world_mut().spawn((
        mover,
        Walk(Vec3::new(speed, 0.0, 0.0)),
        Transform::from_xyz(-3.0, radius + 0.1, rest[0].z + beside),
    ));
    let mut lifted = vec![false; leaves.len()];
    for _ in 0..((10.0 / speed.max(1.0)) / STEP.as_secs_f32()) as usize {
        app.update();
        for (l, &e) in lifted.iter_mut().zip(&leaves) {
            *l |= !state(&app, e).landed();
        }
    }
    lifted
}

#[test]
fn a_running_body_lifts_the_leaves_on_its_path_and_none_beside_it() {
    // A running dog (8 m/s) over the row: every leaf under it goes up.
    let over = leaves_after_a_pass(8.0, 0.0);
    assert!(over.iter().all(|l| *l), "on the path: {over:?}");
    // Five radii to the side: none.
    let beside = leaves_after_a_pass(8.0, 1.5);
    assert!(beside.iter().all(|l| !*l), "beside the path: {beside:?}");
    // Walking slowly over them (1 m/s): the air it pushes is too weak to lift a leaf.
    let slow = leaves_after_a_pass(1.0, 0.0);
    assert!(slow.iter().all(|l| !*l), "a slow walk: {slow:?}");
}

#[test]
fn a_cart_through_a_cloud_of_resting_leaves_lifts_those_on_its_path() {
    let mut app = app_with(WindfallPlugins::default().set(WindPlugin::new(still())));
    let cloud = app
        .world_mut()
        .spawn(LeafCloud {
            object: FallPreset::MapleLeaf.object(),
            count: 1500,
            seed: 9,
            region: CloudRegion {
                min: Vec3::new(-8.0, 0.5, -8.0),
                max: Vec3::new(8.0, 1.0, 8.0),
            },
            lod: LodTiers::default(),
            recycle_after: None,
        })
        .id();
    let resting = |app: &App| {
        let state = app.world().get::<LeafCloudState>(cloud).unwrap();
        state.leaves().unwrap().resting()
    };
    for _ in 0..(10.0 / STEP.as_secs_f32()) as usize {
        app.update();
    }
    assert_eq!(resting(&app), 1500, "every leaf is down");
    let poses = |app: &App| -> Vec<Vec3> {
        let state = app.world().get::<LeafCloudState>(cloud).unwrap();
        state.poses().iter().map(|p| p.position).collect()
    };
    let before = poses(&app);
    // A cart a metre across at 7 m/s along z = 0, 10 cm clear of the leaves.
    let radius = 0.5;
    app.world_mut().spawn((
        WindMover {
            radius,
            ..default()
        },
        Walk(Vec3::new(7.0, 0.0, 0.0)),
        Transform::from_xyz(-12.0, radius + 0.1, 0.0),
    ));
    let mut moved = vec![false; before.len()];
    for _ in 0..(4.0 / STEP.as_secs_f32()) as usize {
        app.update();
        for (m, (now, then)) in moved.iter_mut().zip(poses(&app).iter().zip(&before)) {
            *m |= now.distance(*then) > 0.01;
        }
    }
    let on_path = |p: &Vec3| p.z.abs() < 0.1 && p.x.abs() < 9.0;
    let far = |p: &Vec3| p.z.abs() > 5.0 * radius;
    let (path, stirred): (usize, usize) = before
        .iter()
        .zip(&moved)
        .filter(|(p, _)| on_path(p))
        .fold((0, 0), |(n, s), (_, m)| (n + 1, s + usize::from(*m)));
    assert!(path >= 3, "{path} leaves on the path");
    assert_eq!(
        stirred, path,
        "{stirred} of the {path} leaves on its path moved"
    );
    let wide = before
        .iter()
        .zip(&moved)
        .filter(|(p, m)| far(p) && **m)
        .count();
    assert_eq!(wide, 0, "{wide} leaves far to the side moved");
}

#[test]
fn bad_movers_make_no_wind_and_say_why() {
    let mut app = wind_app();
    let spawn = |app: &mut App, mover: WindMover, at: Transform| {
        app.world_mut()
            .spawn((mover, Walk(Vec3::new(4.0, 0.0, 0.0)), at))
            .id()
    };
    let at = Transform::from_xyz(0.0, 2.0, 0.0);
    let bad = [
        (
            "radius",
            WindMover {
                radius: 0.0,
                ..default()
            },
            at,
        ),
        (
            "radius",
            WindMover {
                radius: -1.0,
                ..default()
            },
            at,
        ),
        (
            "radius",
            WindMover {
                radius: 1e9,
                ..default()
            },
            at,
        ),
        (
            "radius",
            WindMover {
                radius: f32::NAN,
                ..default()
            },
            at,
        ),
        (
            "strength",
            WindMover {
                strength: f32::INFINITY,
                ..default()
            },
            at,
        ),
        (
            "ground",
            WindMover {
                ground: f32::NAN,
                ..default()
            },
            at,
        ),
        (
            "transform",
            WindMover::default(),
            Transform::from_xyz(f32::NAN, 0.0, 0.0),
        ),
        (
            "transform",
            WindMover::default(),
            Transform::from_xyz(f32::INFINITY, 0.0, 0.0),
        ),
    ];
    let entities: Vec<(&str, Entity)> = bad
        .iter()
        .map(|(field, mover, at)| (*field, spawn(&mut app, *mover, *at)))
        .collect();
    // 10 000 movers at one point, all walking, and one that goes halfway through.
    let crowd: Vec<Entity> = (0..10_000)
        .map(|_| {
            spawn(
                &mut app,
                WindMover::default(),
                Transform::from_xyz(3.0, 1.0, 3.0),
            )
        })
        .collect();
    for step in 0..5 {
        app.update();
        if step == 2 {
            app.world_mut().despawn(crowd[17]);
        }
    }
    for (field, e) in &entities {
        let marker = app.world().get::<WindMoverInvalid>(*e);
        assert_eq!(marker.map(|m| m.0.field()), Some(*field), "{field}");
    }
    assert_eq!(app.world().resource::<WindField>().mover_count(), 9_999);
    for k in 0..200 {
        let p = Vec3::new(
            3.0 + (k % 20) as f32 * 0.1 - 1.0,
            1.0,
            3.0 + (k / 20) as f32 * 0.2 - 1.0,
        );
        let u = wind(&app, p);
        assert!(u.is_finite(), "{p}: {u}");
    }
    // A fixed mover stops being invalid.
    let (_, zero) = entities[0];
    app.world_mut().get_mut::<WindMover>(zero).unwrap().radius = 0.5;
    app.update();
    assert!(app.world().get::<WindMoverInvalid>(zero).is_none());
}
