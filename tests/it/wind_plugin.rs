//! The wind's ECS glue: the plugin clock, opt-in plugins, background rebuilds.
use crate::common;

use bevy::prelude::*;
use bevy_windfall::prelude::*;
use common::{STEP, headless_app, ready};

fn config() -> WindConfig {
    WindConfig {
        reference_speed: 5.0,
        seed: 21,
        ..default()
    }
}

#[test]
fn plugin_advances_wind_time_on_the_fixed_step_and_can_pause_or_scale() {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config()));
    ready(&mut app);
    let step = STEP.as_secs_f32();
    let time = |app: &App| app.world().resource::<WindField>().time();
    assert_eq!(time(&app), 0.0, "the first update advances zero time");
    for _ in 0..10 {
        app.update();
    }
    assert!((time(&app) - 10.0 * step).abs() < 1e-5);
    app.world_mut().resource_mut::<WindField>().paused = true;
    app.update();
    assert!((time(&app) - 10.0 * step).abs() < 1e-5);
    {
        let mut wind = app.world_mut().resource_mut::<WindField>();
        wind.paused = false;
        wind.time_scale = 2.0;
    }
    app.update();
    assert!((time(&app) - 12.0 * step).abs() < 1e-5);
    // The clock in full.
    let wind = app.world().resource::<WindField>();
    assert!((wind.time_f64() - 12.0 * STEP.as_secs_f64()).abs() < 1e-6);
    assert_eq!(wind.time(), wind.time_f64() as f32);
}

#[test]
fn plugins_are_opt_in() {
    let mut app = headless_app();
    app.add_plugins(WindfallPlugins::default().build().disable::<WindPlugin>());
    ready(&mut app);
    assert!(!app.world().contains_resource::<WindField>());

    let mut app = headless_app();
    app.add_plugins(WindfallPlugins::default());
    ready(&mut app);
    assert_eq!(
        app.world().resource::<WindField>().config(),
        &WindConfig::default()
    );

    // A field inserted by the user is kept.
    let mut app = headless_app();
    app.insert_resource(WindField::new(config()).unwrap());
    app.add_plugins(WindPlugin::default());
    ready(&mut app);
    assert_eq!(
        app.world().resource::<WindField>().config().reference_speed,
        5.0
    );
}

#[test]
fn a_background_rebuild_lands_at_its_step_and_keeps_the_clock() {
    use bevy_windfall::wind::{WindRebuild, WindRebuilt};
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config()));
    ready(&mut app);
    for _ in 0..5 {
        app.update();
    }
    // A bad configuration is refused at once, by name, and nothing starts.
    let bad = WindConfig {
        beta: -1.0,
        ..config()
    };
    assert_eq!(
        WindRebuild::start(bad).err().map(|e| e.field()),
        Some("beta")
    );
    let time_scale = 0.5;
    app.world_mut().resource_mut::<WindField>().time_scale = time_scale;
    let old = app
        .world()
        .resource::<WindField>()
        .velocity(Vec3::new(3.0, 2.0, 1.0));
    let next = WindConfig {
        grid: [256, 256],
        seed: 99,
        beta: 3.0,
        ..config()
    };
    app.insert_resource(WindRebuild::start(next.clone()).unwrap().with_steps(12));
    // Frames keep coming while it builds; each advances the old clock. It lands at its step.
    for step in 1..=12 {
        app.update();
        let landed = !app.world().contains_resource::<WindRebuild>();
        assert_eq!(landed, step == 12, "step {step}");
    }
    let wind = app.world().resource::<WindField>();
    assert_eq!(wind.config(), &next);
    // The clock went on: 5 steps at full speed, then 12 at half.
    let expected = STEP.as_secs_f32() * (5.0 + time_scale * 12.0);
    assert!(
        (wind.time() - expected).abs() < 1e-4,
        "{} vs {expected}",
        wind.time()
    );
    assert_eq!(wind.time_scale, time_scale);
    assert_ne!(wind.velocity(Vec3::new(3.0, 2.0, 1.0)), old);
    let messages = app.world().resource::<Messages<WindRebuilt>>();
    assert_eq!(messages.iter_current_update_messages().count(), 1);
}

/// An app with the wind, one fixed step per update, its settings' speed read back.
fn settings_app() -> App {
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(config()));
    ready(&mut app);
    app
}

#[test]
fn settings_apply_speed_at_once_and_the_rest_by_a_rebuild_that_keeps_later_edits() {
    let mut app = settings_app();
    // Speed and direction: on the next step.
    {
        let mut s = app.world_mut().resource_mut::<WindSettings>();
        s.reference_speed = 9.0;
        s.direction = Vec2::new(0.0, 1.0);
    }
    app.update();
    let wind = app.world().resource::<WindField>();
    assert_eq!(wind.config().reference_speed, 9.0);
    assert!((wind.direction() - Vec3::Z).length() < 1e-6);
    // β needs a rebuild; while it builds, the speed changes twice (settings, then directly).
    app.world_mut().resource_mut::<WindSettings>().beta = 3.0;
    app.update();
    assert!(
        app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    app.world_mut()
        .resource_mut::<WindSettings>()
        .reference_speed = 3.0;
    app.update();
    assert_eq!(
        app.world().resource::<WindField>().config().reference_speed,
        3.0
    );
    app.world_mut()
        .resource_mut::<WindField>()
        .set_reference_speed(4.0)
        .unwrap();
    // A second turbulence edit while the first builds: the last one wins.
    app.world_mut().resource_mut::<WindSettings>().seed = 77;
    for _ in 0..2 * bevy_windfall::wind::WindRebuild::DEFAULT_STEPS {
        app.update();
    }
    let wind = app.world().resource::<WindField>();
    assert_eq!(wind.config().beta, 3.0);
    assert_eq!(wind.config().seed, 77);
    assert_eq!(
        wind.config().reference_speed,
        4.0,
        "the direct edit is kept"
    );
    assert!((wind.direction() - Vec3::Z).length() < 1e-6);
    // Nothing writes into the settings: they hold what was set there.
    let settings = app.world().resource::<WindSettings>();
    assert_eq!(settings.reference_speed, 3.0);
    assert_eq!((settings.beta, settings.seed), (3.0, 77));
}

#[test]
fn a_bad_setting_is_refused_and_the_wind_keeps_blowing() {
    let mut app = settings_app();
    app.world_mut().resource_mut::<WindSettings>().roughness = -1.0;
    for _ in 0..3 {
        app.update();
    }
    assert!(
        !app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    assert_eq!(app.world().resource::<WindField>().config(), &config());
    // And a plugin given a bad configuration logs it and inserts no field: no panic.
    let mut app = headless_app();
    app.add_plugins(WindPlugin::new(WindConfig {
        beta: f32::NAN,
        ..config()
    }));
    ready(&mut app);
    assert!(!app.world().contains_resource::<WindField>());
}

/// The velocity bits at a point after `steps` steps, with a rebuild requested at step 3.
fn rebuilt_run(slow: bool) -> Vec<u32> {
    let mut app = settings_app();
    let mut bits = Vec::new();
    for step in 0..60 {
        if step == 3 {
            app.world_mut().resource_mut::<WindSettings>().seed = 5;
        }
        if slow && step == 4 {
            // A slow frame: the rebuild is ready long before its step; it still lands then.
            std::thread::sleep(std::time::Duration::from_millis(300));
        }
        app.update();
        let v = app
            .world()
            .resource::<WindField>()
            .velocity(Vec3::new(1.0, 3.0, 2.0));
        bits.extend(v.to_array().map(f32::to_bits));
    }
    bits
}

#[test]
fn rebuilds_land_at_the_same_step_however_long_frames_take() {
    assert_eq!(rebuilt_run(false), rebuilt_run(true));
}

#[test]
fn a_field_inserted_during_a_rebuild_wins() {
    let mut app = settings_app();
    app.world_mut().resource_mut::<WindSettings>().beta = 2.5;
    app.update();
    let mine = WindField::new(WindConfig {
        seed: 1234,
        ..config()
    })
    .unwrap();
    app.insert_resource(mine);
    for _ in 0..2 * bevy_windfall::wind::WindRebuild::DEFAULT_STEPS {
        app.update();
    }
    assert_eq!(app.world().resource::<WindField>().config().seed, 1234);
}

/// Runs `app` until no rebuild is in flight (at most two rebuilds' steps).
fn until_landed(app: &mut App) {
    for _ in 0..2 * bevy_windfall::wind::WindRebuild::DEFAULT_STEPS {
        app.update();
        if !app
            .world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
        {
            return;
        }
    }
    panic!("the rebuild never landed");
}

#[test]
fn a_pulse_set_while_a_rebuild_builds_survives_its_landing() {
    // Through the settings, and on the field directly.
    for direct in [false, true] {
        let mut app = settings_app();
        app.world_mut().resource_mut::<WindSettings>().beta = 2.5;
        app.update();
        let pulse = bevy_windfall::wind::Pulse::new(0.5, 0.25);
        if direct {
            let mut field = app.world_mut().resource_mut::<WindField>();
            field.set_pulse(pulse).unwrap();
        } else {
            app.world_mut().resource_mut::<WindSettings>().pulse = pulse;
        }
        until_landed(&mut app);
        app.update();
        let field = app.world().resource::<WindField>();
        assert_eq!(field.config().beta, 2.5, "direct: {direct}");
        assert_eq!(field.config().pulse, pulse, "direct: {direct}");
        // The settings hold what was set there, never what the field was set to directly.
        let settings = app.world().resource::<WindSettings>().pulse;
        let expected = if direct { Default::default() } else { pulse };
        assert_eq!(settings, expected, "direct: {direct}");
    }
}

#[test]
fn a_rebuild_replaces_the_turbulence_and_keeps_the_live_mean_wind() {
    use bevy_windfall::wind::WindRebuild;
    let mut app = settings_app();
    // Its own speed and direction are not used: the field goes on with its mean wind.
    let next = WindConfig {
        reference_speed: 7.0,
        direction: Vec2::new(0.0, 1.0),
        beta: 3.0,
        ..config()
    };
    app.insert_resource(WindRebuild::start(next).unwrap().with_steps(4));
    until_landed(&mut app);
    app.update();
    let field = app.world().resource::<WindField>();
    assert_eq!(field.config().beta, 3.0);
    assert_eq!(field.config().reference_speed, config().reference_speed);
    assert_eq!(field.config().direction, config().direction);
    assert_eq!(app.world().resource::<WindSettings>().config, config());
    // An edit of the live field made while it builds is kept when it lands.
    let next = WindConfig {
        beta: 2.0,
        ..config()
    };
    app.insert_resource(WindRebuild::start(next).unwrap().with_steps(4));
    app.update();
    app.world_mut()
        .resource_mut::<WindField>()
        .set_reference_speed(11.0)
        .unwrap();
    until_landed(&mut app);
    let field = app.world().resource::<WindField>();
    assert_eq!(field.config().reference_speed, 11.0);
    assert_eq!(field.config().beta, 2.0);
}

/// Hostile input, round 4, item 14: a rebuild inserted, then the live field's speed and
/// direction set in the same frame: the later edits win when the rebuild lands.
#[test]
fn edits_of_the_field_after_a_rebuild_request_win_whatever_the_frame() {
    use bevy_windfall::wind::WindRebuild;
    let mut app = settings_app();
    let job = WindRebuild::start(WindConfig {
        beta: 3.0,
        ..config()
    })
    .unwrap();
    app.insert_resource(job);
    {
        let mut field = app.world_mut().resource_mut::<WindField>();
        field.set_reference_speed(20.0).unwrap();
        field.set_direction(Vec2::new(0.0, 1.0)).unwrap();
    }
    until_landed(&mut app);
    let field = app.world().resource::<WindField>();
    assert_eq!(field.config().beta, 3.0);
    assert_eq!(field.config().reference_speed, 20.0);
    assert!((field.direction() - Vec3::Z).length() < 1e-6);
}

/// Hostile input, round 4, item 7: a clone of the field (same generation) inserted five steps
/// after a rebuild was requested wins over the rebuild.
#[test]
fn a_saved_field_put_back_after_a_rebuild_request_wins() {
    let mut app = settings_app();
    let saved = app.world().resource::<WindField>().clone();
    app.world_mut().resource_mut::<WindSettings>().beta = 3.0;
    for _ in 0..5 {
        app.update();
    }
    assert!(
        app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    app.insert_resource(saved);
    for _ in 0..2 * bevy_windfall::wind::WindRebuild::DEFAULT_STEPS {
        app.update();
    }
    assert!(
        !app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    assert_eq!(
        app.world().resource::<WindField>().config().beta,
        config().beta
    );
}

#[test]
fn setting_the_turbulence_back_drops_the_rebuild_in_flight() {
    let mut app = settings_app();
    app.world_mut().resource_mut::<WindSettings>().seed = 99;
    app.update();
    assert!(
        app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    app.world_mut().resource_mut::<WindSettings>().seed = config().seed;
    app.update();
    assert!(
        !app.world()
            .contains_resource::<bevy_windfall::wind::WindRebuild>()
    );
    for _ in 0..40 {
        app.update();
    }
    assert_eq!(
        app.world().resource::<WindField>().config().seed,
        config().seed
    );
}

#[test]
fn a_pulse_edit_in_the_settings_keeps_an_easing() {
    let mut app = settings_app();
    app.world_mut()
        .resource_mut::<WindField>()
        .ease_to(12.0, Vec2::new(0.0, 1.0), 2.0)
        .unwrap();
    app.update();
    app.world_mut().resource_mut::<WindSettings>().pulse =
        bevy_windfall::wind::Pulse::new(0.3, 0.5);
    app.update();
    let field = app.world().resource::<WindField>();
    assert!(field.easing().is_some(), "the easing goes on");
    assert_eq!(
        field.config().pulse,
        bevy_windfall::wind::Pulse::new(0.3, 0.5)
    );
    // A speed edit in the settings ends it.
    app.world_mut()
        .resource_mut::<WindSettings>()
        .reference_speed = 6.0;
    app.update();
    let field = app.world().resource::<WindField>();
    assert!(field.easing().is_none());
    assert_eq!(field.config().reference_speed, 6.0);
}

#[test]
fn a_field_inserted_with_a_settings_edit_in_the_same_frame_takes_the_edit() {
    let mut app = settings_app();
    let mine = WindField::new(WindConfig {
        seed: 1234,
        ..config()
    })
    .unwrap();
    app.insert_resource(mine);
    app.world_mut()
        .resource_mut::<WindSettings>()
        .reference_speed = 8.0;
    app.update();
    let field = app.world().resource::<WindField>();
    assert_eq!(field.config().seed, 1234, "the inserted field blows");
    assert_eq!(field.config().reference_speed, 8.0, "with the edit");
}

#[test]
fn settings_inserted_again_apply_what_differs() {
    let mut app = settings_app();
    app.insert_resource(WindSettings::new(WindConfig {
        reference_speed: 2.0,
        ..config()
    }));
    app.update();
    assert_eq!(
        app.world().resource::<WindField>().config().reference_speed,
        2.0
    );
}

#[test]
fn between_a_rebuild_and_a_field_inserted_in_the_same_frame_the_later_request_wins() {
    use bevy_windfall::wind::WindRebuild;
    let rebuilt = WindConfig {
        seed: 77,
        ..config()
    };
    let mine = || {
        WindField::new(WindConfig {
            seed: 1234,
            ..config()
        })
        .unwrap()
    };
    // The field is made after the rebuild is requested: the field wins.
    let mut app = settings_app();
    let job = WindRebuild::start(rebuilt.clone()).unwrap();
    app.insert_resource(job);
    app.insert_resource(mine());
    for _ in 0..2 * WindRebuild::DEFAULT_STEPS {
        app.update();
    }
    assert_eq!(app.world().resource::<WindField>().config().seed, 1234);
    // The field is made first, the rebuild requested after: the rebuild lands over it.
    let mut app = settings_app();
    let field = mine();
    let job = WindRebuild::start(rebuilt).unwrap();
    app.insert_resource(field);
    app.insert_resource(job);
    until_landed(&mut app);
    assert_eq!(app.world().resource::<WindField>().config().seed, 77);
}
