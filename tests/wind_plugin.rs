//! The wind's ECS glue: the plugin clock, opt-in plugins, background rebuilds.
mod common;

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
}

#[test]
fn plugins_are_opt_in() {
    let mut app = headless_app();
    app.add_plugins(WindfallPlugins.build().disable::<WindPlugin>());
    ready(&mut app);
    assert!(!app.world().contains_resource::<WindField>());

    let mut app = headless_app();
    app.add_plugins(WindfallPlugins);
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
fn a_background_rebuild_swaps_in_the_new_field_and_keeps_the_clock() {
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
    app.insert_resource(WindRebuild::start(next.clone()).unwrap());
    // Frames keep coming while it builds; each advances the old clock.
    let mut frames = 0;
    while app.world().contains_resource::<WindRebuild>() {
        app.update();
        frames += 1;
        assert!(frames < 10_000, "the rebuild never finished");
    }
    let wind = app.world().resource::<WindField>();
    assert_eq!(wind.config(), &next);
    // The clock went on: 5 steps at full speed, then `frames` at half.
    let expected = STEP.as_secs_f32() * (5.0 + time_scale * frames as f32);
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
