//! The integration tests, one binary (one link of Bevy instead of one per file): each module
//! tests one area through the public API. Run one area with a filter:
//! `cargo test --test it -- hostile_apps::`. Shared helpers live in `common`.

mod common;

mod aero;
#[cfg(feature = "avian")]
mod aero_avian;
mod bevy_integration;
mod cloth;
mod cloth_lod;
mod cloth_waves;
mod cloud;
mod determinism;
mod freefall;
mod freefall_motion;
mod freefall_ode;
mod freefall_plugin;
mod freefall_presets;
#[cfg(feature = "render")]
mod gpu_wind;
mod hostile;
mod hostile_aero;
mod hostile_apps;
mod hostile_cloth;
mod hostile_falls;
mod hostile_lifecycle;
mod hostile_weather;
mod hostile_wind;
mod lod;
mod measurements;
mod physical_flag;
mod schedule_order;
mod screenshots;
mod spectrum;
mod stability;
mod wind;
mod wind_movers;
mod wind_plugin;
#[cfg(feature = "serde")]
mod wind_serde;
mod wind_shelter;
mod wind_sources;
mod wind_weather;
