//! Hostile apps (see `hostile.rs`): entities spawned with NaN, infinite, far-away or
//! degenerate transforms report the crate's runtime error once and recover when fixed; removing
//! the crate's resources mid-run is survivable; and probes that would abort (allocation
//! failure), overflow or hang if a size budget were missing run in a child process under a
//! memory cap and a timeout, so a regression fails a test instead of killing the runner.

use crate::common;

use bevy::prelude::*;
use bevy_windfall::aero::{
    AeroBodyInvalid, AeroCoefficients, ParticleCloth, PhysicalCloth, PhysicalClothInvalid, Pinning,
    PlateState,
};
use bevy_windfall::cloth::{ClothInvalid, ClothSim, ClothWindModel};
use bevy_windfall::freefall::ode::{Integrator, OdeState, TanabeKaneko};
use bevy_windfall::freefall::{FallModel, FallRelease, FallingObjectInvalid};
use bevy_windfall::prelude::*;
use bevy_windfall::spectrum::fbm;
use common::hostile::{TILT, finite};
use common::{headless_app_with_meshes, paper_coin, ready};

/// The kinds of entity the app test spawns.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
enum Kind {
    Fall,
    Body,
    Cloth,
    Physical,
}

#[test]
fn apps_with_hostile_transforms_report_once_and_recover() {
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default());
    ready(&mut app);
    let transforms = [
        ("nan translation", Transform::from_xyz(f32::NAN, 2.0, 0.0)),
        (
            "infinite translation",
            Transform::from_xyz(0.0, f32::INFINITY, 0.0),
        ),
        ("far away", Transform::from_xyz(3e7, 2.0, 0.0)),
        (
            "zero quaternion",
            Transform::from_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
        ),
        (
            "nan rotation",
            Transform::from_rotation(Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0)),
        ),
        ("zero scale", Transform::from_scale(Vec3::ZERO)),
    ];
    let small = ClothGrid {
        rows: 4,
        columns: 6,
        ..default()
    };
    let mut spawned = Vec::new();
    for (what, t) in transforms {
        let world = app.world_mut();
        spawned.push((
            what,
            world.spawn((Kind::Fall, FallingObject::default(), t)).id(),
        ));
        spawned.push((what, world.spawn((Kind::Body, AeroBody::default(), t)).id()));
        let cloth = Cloth {
            grid: small,
            ..default()
        };
        spawned.push((what, world.spawn((Kind::Cloth, cloth, t)).id()));
        let physical = PhysicalCloth {
            grid: small,
            ..default()
        };
        spawned.push((what, world.spawn((Kind::Physical, physical, t)).id()));
    }
    for _ in 0..10 {
        app.update();
    }
    let world = app.world();
    for &(what, entity) in &spawned {
        let kind = *world.get::<Kind>(entity).unwrap();
        let field = match kind {
            Kind::Fall => world
                .get::<FallingObjectInvalid>(entity)
                .map(|e| e.0.field()),
            Kind::Body => world.get::<AeroBodyInvalid>(entity).map(|e| e.0.field()),
            Kind::Cloth => world.get::<ClothInvalid>(entity).map(|e| e.0.field()),
            Kind::Physical => world
                .get::<PhysicalClothInvalid>(entity)
                .map(|e| e.0.field()),
        };
        // Scale does not matter to a fall or a rigid body; it matters to a cloth's frame. A
        // zero quaternion is no rotation to a fall or a body, but Bevy's transform propagation
        // turns it into the identity matrix, which the cloth then uses as Bevy draws it.
        let body = matches!(kind, Kind::Fall | Kind::Body);
        let harmless = (what == "zero scale" && body) || (what == "zero quaternion" && !body);
        if harmless {
            assert_eq!(field, None, "{kind:?} with {what}");
            assert!(
                world
                    .get::<Transform>(entity)
                    .unwrap()
                    .translation
                    .is_finite()
            );
        } else {
            let expected = match kind {
                Kind::Fall => ["release.position", "release.rotation"],
                Kind::Body => ["state.position", "state.rotation"],
                Kind::Cloth | Kind::Physical => ["transform", "transform"],
            };
            assert!(
                field.is_some_and(|f| expected.contains(&f)),
                "{kind:?} with {what}: {field:?}"
            );
        }
    }
    // Every cloth state stays finite while it holds still.
    let mut cloths = app.world_mut().query::<&ClothState>();
    for state in cloths.iter(app.world()) {
        assert!(state.sim.positions().iter().all(|p| p.is_finite()));
    }
    // Fixed, everything moves again and the reports go.
    for &(_, entity) in &spawned {
        let mut e = app.world_mut().entity_mut(entity);
        *e.get_mut::<Transform>().unwrap() = Transform::from_xyz(0.0, 2.0, 0.0);
        if let Some(mut object) = e.get_mut::<FallingObject>() {
            object.seed += 1;
        }
        if let Some(mut state) = e.get_mut::<bevy_windfall::aero::AeroState>() {
            state.state = PlateState {
                position: Vec3::new(0.0, 2.0, 0.0),
                ..default()
            };
        }
    }
    for _ in 0..10 {
        app.update();
    }
    let world = app.world();
    for &(what, entity) in &spawned {
        let e = world.entity(entity);
        assert!(
            !e.contains::<FallingObjectInvalid>()
                && !e.contains::<AeroBodyInvalid>()
                && !e.contains::<ClothInvalid>()
                && !e.contains::<PhysicalClothInvalid>(),
            "{what}: still reported after the fix"
        );
        let t = e.get::<Transform>().unwrap();
        assert!(t.translation.is_finite() && t.rotation.is_finite());
        if matches!(*e.get::<Kind>().unwrap(), Kind::Fall | Kind::Body) {
            assert!(t.translation.y < 2.0, "{what}: it falls again");
        }
    }
}

#[test]
fn removing_resources_mid_run_is_survivable() {
    let mut app = headless_app_with_meshes();
    app.add_plugins(WindfallPlugins::default());
    ready(&mut app);
    let coin = app
        .world_mut()
        .spawn((paper_coin(), Transform::from_xyz(0.0, 5.0, 0.0)))
        .id();
    let y = |app: &App| app.world().get::<Transform>(coin).unwrap().translation.y;
    for _ in 0..5 {
        app.update();
    }
    let world = app.world_mut();
    world.remove_resource::<FallModel>();
    world.remove_resource::<FallSettings>();
    world.remove_resource::<WindField>();
    world.remove_resource::<WindSettings>();
    app.update();
    let held = y(&app);
    for _ in 0..10 {
        app.update();
    }
    assert_eq!(y(&app), held, "without a model the fall waits");
    app.world_mut().insert_resource(FallModel::default());
    for _ in 0..10 {
        app.update();
    }
    assert!(y(&app) < held, "with the model back it falls on");
}

/// Probes that would abort (allocation failure), overflow or hang if a budget were missing.
const PROBES: [&str; 8] = [
    "fbm 2^40",
    "fbm 2^20 x 2^20",
    "wind grid 2^20 x 2^20",
    "cloth frames 2^40",
    "cloth 1 x 2^20 frozen",
    "ode dt 1e-12",
    "particle cloth iterations usize::MAX",
    "fall step of a year",
];

fn run_probe(name: &str) {
    match name {
        "fbm 2^40" => assert!(fbm(&[1 << 40], 1.0, 0).is_err()),
        "fbm 2^20 x 2^20" => assert!(fbm(&[1 << 20, 1 << 20], 1.0, 0).is_err()),
        "wind grid 2^20 x 2^20" => {
            let config = WindConfig {
                grid: [1 << 20, 1 << 20],
                ..default()
            };
            assert_eq!(WindField::new(config).unwrap_err().field(), "grid");
        }
        "cloth frames 2^40" => {
            let params = ClothParams {
                model: ClothWindModel::Evolving { frames: 1 << 40 },
                ..default()
            };
            let e = ClothSim::new(ClothGrid::default(), params, ClothAttachment::Pole);
            assert_eq!(e.err().unwrap().field(), "params.model.frames");
        }
        "cloth 1 x 2^20 frozen" => {
            let grid = ClothGrid {
                rows: 1,
                columns: 1 << 20,
                ..default()
            };
            // Within the node budget: it must build in linear time and stay finite.
            let mut sim = ClothSim::new(grid, ClothParams::default(), ClothAttachment::Pole)
                .expect("a valid grid");
            sim.advance(1.0 / 50.0, 2.0);
            sim.rebuild();
            assert!(sim.positions().iter().all(|p| p.is_finite()));
        }
        "ode dt 1e-12" => {
            let run =
                TanabeKaneko::FLUTTER.trajectory(OdeState::default(), 1e-12, 1.0, Integrator::Rk4);
            assert_eq!(run.unwrap_err().field(), "dt");
        }
        "particle cloth iterations usize::MAX" => {
            let grid = ClothGrid {
                rows: 6,
                columns: 8,
                ..default()
            };
            let mut cloth =
                ParticleCloth::new(grid, 0.15, AeroCoefficients::default(), Pinning::PoleColumn)
                    .unwrap();
            cloth.iterations = usize::MAX;
            cloth.min_substeps = u32::MAX;
            cloth.step(1.0 / 60.0, Vec3::new(0.0, -9.81, 0.0), &|_| Vec3::X * 5.0);
            assert!(cloth.positions().iter().all(|p| p.is_finite()));
        }
        "fall step of a year" => {
            let model = FallModel::default();
            let mut path = FallingObject::default()
                .path(&model, FallRelease::at(Vec3::new(0.0, 1e6, 0.0), 0.0))
                .unwrap();
            path.advance(&model, 3.15e7, Vec3::X, &TILT);
            finite(path.position(), "a year");
        }
        other => panic!("unknown probe {other}"),
    }
}

/// Runs one probe when this test binary is re-executed as a child (a no-op otherwise).
#[test]
fn probe_child() {
    if let Ok(name) = std::env::var("WINDFALL_PROBE") {
        run_probe(&name);
    }
}

#[cfg(unix)]
#[test]
fn huge_inputs_fail_fast_under_a_memory_cap() {
    use std::process::{Command, Stdio};
    use std::time::{Duration, Instant};
    let exe = std::env::current_exe().unwrap();
    // The child runs this module's `probe_child` alone, named as libtest names it.
    let child_test = module_path!()
        .split_once("::")
        .map_or("", |(_, m)| m)
        .to_owned()
        + "::probe_child";
    for name in PROBES {
        let start = Instant::now();
        // 4 GiB of address space: a missing budget aborts (allocation failure) instead of
        // paging the machine to death; 60 s: a missing cap hangs.
        let mut child = Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 4194304 && exec \"$0\" \"$@\"")
            .arg(&exe)
            .args(["--exact", &child_test, "--test-threads=1", "--nocapture"])
            .env("WINDFALL_PROBE", name)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if start.elapsed() > Duration::from_secs(60) {
                child.kill().ok();
                panic!("probe `{name}` hangs (over 60 s)");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let (mut stdout, mut stderr) = (String::new(), String::new());
        std::io::Read::read_to_string(&mut child.stdout.take().unwrap(), &mut stdout).ok();
        std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).ok();
        assert!(
            status.success(),
            "probe `{name}` failed: {status}\n{stderr}"
        );
        // A filter that matched nothing would pass without running the probe.
        assert!(
            stdout.contains("1 passed"),
            "probe `{name}` did not run `{child_test}`:\n{stdout}"
        );
        println!(
            "probe `{name}`: ok in {:.2} s",
            start.elapsed().as_secs_f32()
        );
    }
}
