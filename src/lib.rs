//! Wind for the [Bevy](https://bevy.org) game engine, from three papers: a wind field with
//! log-law mean wind and 1/f^β turbulence, falling leaves, paper and coins that move the way the
//! free-fall paper describes, flags and curtains that flap with travelling waves, and per-face
//! lift and drag for rigid plates, particle cloth and avian3d bodies. Equations are cited by
//! their number in the papers: the free-fall paper (Xie and Miyata, *Realistic Motion
//! Simulations of Objects in Free Fall*), the cloth paper (Tynystanova and Chiba, *Fourier
//! Descriptor Animation of Cloth Flapping in Wind*) and the lift-and-drag paper (its
//! *Aerodynamics* section, after Stam and Fiume 1992).
//!
//! # Contents
//!
//! - [Getting started](#getting-started)
//! - [The wind](#the-wind): [`wind`]
//! - [Falling objects](#falling-objects): [`freefall`]
//! - [Cloth](#cloth): [`cloth`]
//! - [Aerodynamic bodies](#aerodynamic-bodies): [`aero`]
//! - [Scheduling and smooth motion](#scheduling-and-smooth-motion)
//! - [Live settings, reflection and the inspector](#live-settings-reflection-and-the-inspector)
//! - [Errors](#errors)
//! - [Determinism and multiplayer](#determinism-and-multiplayer)
//! - [Browsers (wasm)](#browsers-wasm)
//! - [Cargo features](#cargo-features)
//! - [FAQ](#faq): nothing moves, leaves stutter, too slow
//! - [How the crate is laid out](#how-the-crate-is-laid-out)
//!
//! # Getting started
//!
//! Add [`WindfallPlugins`] after `DefaultPlugins` and spawn what the
//! wind should move; everything is positioned by its
//! [`Transform`](bevy::transform::components::Transform) and, with the default feature `render`,
//! drawn with a default look (a leaf its preset's outline and colours, a cloth a fabric) unless
//! you give it your own mesh and material:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_windfall::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, WindfallPlugins::default()))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), Transform::from_xyz(0.0, 2.0, 8.0)));
//!         commands.spawn((DirectionalLight::default(), Transform::from_xyz(2.0, 8.0, 6.0)));
//!         commands.spawn((FallPreset::MapleLeaf.object(), Transform::from_xyz(0.0, 3.0, 5.0)));
//!         commands.spawn(LeafCloud { count: 2_000, ..default() });
//!         commands.spawn((Cloth::default(), Transform::from_xyz(-2.0, 3.0, 0.0)));
//!         commands.spawn((PhysicalCloth::default(), Transform::from_xyz(1.0, 3.0, 0.0)));
//!     })
//!     .run();
//! ```
//!
//! Headless (a server, a test), the same components simulate without drawing:
//!
//! ```
//! use bevy::prelude::*;
//! use bevy_windfall::prelude::*;
//!
//! let mut app = App::new();
//! app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
//! // A maple leaf let go from a branch and a flag on a pole, 5 m/s of wind at 10 m.
//! app.world_mut().resource_mut::<WindSettings>().reference_speed = 5.0;
//! let leaf = app
//!     .world_mut()
//!     .spawn((FallPreset::MapleLeaf.object(), Transform::from_xyz(0.0, 5.0, 0.0)))
//!     .id();
//! app.world_mut().spawn((
//!     Cloth { params: ClothPreset::FlagFlappingFrozen.params(), ..default() },
//!     Transform::from_xyz(2.0, 6.0, 0.0),
//! ));
//! app.update();
//! // Set up in the frame it was spawned: its regime and first motion are known.
//! let state = app.world().get::<FallState>(leaf).unwrap();
//! assert!(state.motion().is_some());
//! ```
//!
//! Every plugin is opt-in: add the group, a single plugin, or
//! `WindfallPlugins::default().build().disable::<ClothPlugin>()`. The repository's examples each show one
//! topic (`cargo run --example falling_leaves`, `flag`, `leaf_cloud`, …); the showcase tours them
//! all (`cargo run --example showcase --features egui`).
//!
//! # The wind
//!
//! [`WindField`](wind::WindField) is a resource: U(h) = (u*/κ) ln(h/z0) (eq. 10) plus
//! turbulence with a 1/f^β spectrum (eq. 11, 13) synthesised by inverse FFT, with per-axis
//! amplitudes 1 : 0.88 : 0.55 (eq. 12), frozen (Taylor) or evolving, carried to other heights by
//! eq. 14. Anything can sample it: `wind.velocity(p)`, `wind.velocity_at(p, t)`, or many points
//! at once with `wind.velocities_at(&points, t, &mut out)`. [`WindPlugin`](wind::WindPlugin)
//! inserts it and advances its clock; [`WindSettings`](wind::WindSettings) changes it live.
//!
//! Local wind: a [`WindSource`](wind::WindSource) component (a sphere, a fan, a vortex, a blast)
//! adds its velocity to the field where it is, from the next fixed step on; everything that
//! samples the field feels it (falling objects, cloth, plates, avian bodies), and a strong enough
//! gust lifts a resting leaf again ([`FallRelease::LIFT_OFF_FACTOR`](crate::freefall::FallRelease::LIFT_OFF_FACTOR)). A
//! [`WindShelter`](wind::WindShelter) calms the lee of a wall or the inside of a room;
//! [`WindField::ease_to`](wind::WindField::ease_to) builds a storm up or veers the wind without a
//! jump; [`WindConfig::beaufort`](wind::WindConfig::beaufort) gives the wind of a Beaufort force.
//!
//! On the GPU (feature `render`): `render::WindGpuPlugin` uploads the field, and the WESL module
//! `bevy_windfall::wind` samples it exactly as [`WindField::velocity_at`](wind::WindField::velocity_at)
//! does (sources and shelters included), so grass and foliage (`render::WindSway`, a material
//! extension) sway in the same gusts that carry the leaves.
//!
//! # Falling objects
//!
//! [`FallingObject`](freefall::FallingObject) (with [`FallPreset`](freefall::FallPreset)s for
//! coins, paper, leaves, cards and samaras): the Reynolds number and I* place it in the paper's
//! phase diagram (Fig. 2), its main motion bounds a Markov chain over the six primitive motions
//! (§2.1), fluttering, chaotic and tumbling swings come from a clustered trajectory database of
//! eq. 5 segments searched as §2.3 describes, helix and spiral from eq. 6, and the wind carries
//! it through its own response time (§4.3). [`FallState`](freefall::FallState) tells its
//! motion; [`Landed`](freefall::Landed) is sent when it reaches the ground.
//!
//! For storms of them, a [`LeafCloud`](freefall::LeafCloud) holds up to millions of leaves of one
//! description in one entity: each the same fall, stored in one array, stepped in parallel with
//! the same bits on any thread count, with levels of detail around a
//! [`LodFocus`](lod::LodFocus) and (feature `render`) one draw call
//! (`render::LeafCloudRenderPlugin`). Single objects take the same levels of detail with
//! [`FallLod`](freefall::FallLod), cloths with [`ClothLod`](cloth::ClothLod) (a coarser grid far
//! away); see [`lod`].
//!
//! # Cloth
//!
//! [`Cloth`](cloth::Cloth): flags, banners and curtains whose yarns are P-type Fourier
//! descriptors driven by 1/f^β noise (§3–4 of the cloth paper), with every row of Table 1 as a
//! [`ClothPreset`](cloth::ClothPreset). The mesh is written in place each frame.
//!
//! # Aerodynamic bodies
//!
//! [`AeroBody`](aero::AeroBody) (a rigid plate), [`PhysicalCloth`](aero::PhysicalCloth) (XPBD
//! particle cloth) and, with the `avian` feature, `AvianAero` on avian3d rigid bodies, all moved
//! by the per-face lift and drag law [`face_force`](aero::face_force) (eq. 3.1 of the aero
//! paper).
//!
//! # Scheduling and smooth motion
//!
//! The simulation runs in [`FixedUpdate`](bevy::app::FixedUpdate), or in the schedule given to
//! [`WindfallPlugins::new`] (each single plugin takes one too, as avian's do: `new(schedule)`,
//! or `WindPlugin::new(config).in_schedule(schedule)`), in
//! public sets you can order your own systems against ([`WindfallSystems`], in [`schedule`]):
//! `Prepare` (before the fixed loop: live settings are taken in), `Wind` (the wind clock),
//! `Simulate` (everything the wind moves, one domain after another: [`SimulateSystems`]
//! `Falls`, `Clouds`, `Cloth`, `Aero`; in `Update`, skipped on frames whose time does not move) and
//! `WriteBack` (in [`PostUpdate`](bevy::app::PostUpdate), before transform
//! propagation: new objects are released, bodies posed, meshes written). Bodies moved on the
//! fixed step are posed between their last two steps by the frame's overstep, as avian
//! interpolates, so motion is smooth at any frame rate; the pose lags the simulation by up to
//! one fixed step. An entity spawned in a frame is set up by an observer the moment its
//! component is inserted.
//!
//! ```
//! use bevy::prelude::*;
//! use bevy_windfall::prelude::*;
//!
//! fn my_fan(wind: Res<WindField>) { /* sample the wind after its clock advanced */ }
//!
//! App::new()
//!     .add_plugins((MinimalPlugins, WindfallPlugins::default()))
//!     .add_systems(FixedUpdate, my_fan.in_set(WindfallSystems::Simulate));
//!
//! // Between two domains: after the leaves, before the cloth.
//! fn between_leaves_and_cloth() {}
//! App::new()
//!     .add_plugins((MinimalPlugins, WindfallPlugins::default()))
//!     .add_systems(
//!         FixedUpdate,
//!         between_leaves_and_cloth
//!             .after(SimulateSystems::Clouds)
//!             .before(SimulateSystems::Cloth),
//!     );
//! ```
//!
//! # Live settings, reflection and the inspector
//!
//! Every user-facing component and resource derives `Reflect` (with `ReflectComponent` or
//! `ReflectResource`, `Default` and `Debug` where they apply) and is registered by its plugin,
//! so editors, inspectors and scene files see them. Settings are data the plugins follow:
//! edit [`WindSettings`](wind::WindSettings) (speed and direction apply at once, turbulence
//! changes rebuild in the background and land a fixed number of steps later, edits made
//! meanwhile are merged), a [`FallingObject`](freefall::FallingObject) (it is released again)
//! or a [`Cloth`](cloth::Cloth) (it is rebuilt). Debug drawing is in `WindfallDebugPlugin`
//! (feature `gizmos`), off until enabled in the `GizmoConfigStore`; a drop-in egui panel is in
//! `inspector::WindfallInspectorPlugin` (feature `egui`).
//!
//! # Errors
//!
//! A bad value is a typed error that names the field: constructors return
//! [`WindError`](wind::WindError), [`FallError`](freefall::FallError),
//! [`ClothError`](cloth::ClothError), [`AeroError`](aero::AeroError) or
//! [`SpectrumError`](spectrum::SpectrumError). Validation checks what is used (the log ratio
//! ln(h/z0), the unit direction, the node mass), not only the raw fields, and every allocation
//! sized by user input has a documented budget checked before allocating
//! ([`Synthesizer::MAX_NODES`](crate::spectrum::Synthesizer::MAX_NODES), [`ClothSim::MAX_NOISE_CELLS`](crate::cloth::ClothSim::MAX_NOISE_CELLS), [`ClothGrid::MAX_NODES`](crate::cloth::ClothGrid::MAX_NODES),
//! [`TanabeKaneko::MAX_TRAJECTORY_STEPS`](crate::freefall::ode::TanabeKaneko::MAX_TRAJECTORY_STEPS)). A bad component, or a transform that is not finite
//! or lies beyond ±[`MAX_COORDINATE`], gets an `…Invalid` component holding its error
//! ([`FallingObjectInvalid`](freefall::FallingObjectInvalid),
//! [`AeroBodyInvalid`](aero::AeroBodyInvalid), [`ClothInvalid`](cloth::ClothInvalid),
//! [`PhysicalClothInvalid`](aero::PhysicalClothInvalid)), logged once with `warn!`, and holds
//! still; fixing it clears the component. Bad tiers on a `FallLod` or `ClothLod` get a
//! [`LodInvalid`](lod::LodInvalid) the same way but only fall back to full detail. Runtime
//! knobs clamp instead (a step, a wind speed, the wind clock, solver iterations), as their docs
//! say. A plugin never panics on bad settings or a removed resource: it logs and leaves the
//! part out.
//!
//! # Determinism and multiplayer
//!
//! Randomness comes from seeded PCG streams and the FFT from rustfft's scalar planner, so a
//! seed gives the same bits on every machine and thread count; the simulation steps on the fixed
//! timestep; a background wind rebuild lands at a fixed step, whatever the machine. With the
//! `serde` feature a [`WindSnapshot`](wind::WindSnapshot) (settings, seed and clock) sent to a
//! client rebuilds the same wind, bit for bit.
//!
//! # Browsers (wasm)
//!
//! The library builds for `wasm32-unknown-unknown` (checked in CI): it reads no clock but Bevy's
//! `Time`, no file and no OS randomness, and needs no threads. One difference: a wind rebuild
//! runs on Bevy's task pool, which in a browser cannot be waited for, so a rebuild that is late
//! lands at the first fixed step after it is ready instead of at its fixed step.
//!
//! # Cargo features
//!
//! | feature | adds |
//! |---|---|
//! | `render` (default) | drawing: default looks, leaf clouds in one draw call, the wind on the GPU (`render`: the WESL module `bevy_windfall::wind`, the `WindSway` material); nothing in an app without Bevy's renderer |
//! | *(no default features)* | everything above, headless; Bevy with `default-features = false` |
//! | `gizmos` | `WindfallDebugPlugin`: wind arrows, fall trails, cloth yarns |
//! | `egui` | `inspector::WindfallInspectorPlugin`, a tuning panel (bevy_egui 0.43) |
//! | `serde` | `Serialize`/`Deserialize` for the wind settings and [`WindSnapshot`](wind::WindSnapshot) |
//! | `avian` | `AvianAero` and `AvianAeroPlugin` (in the group) for avian3d 0.8 |
//!
//! # FAQ
//!
//! **Nothing moves.** The part's plugin must be added (the group [`WindfallPlugins`] adds them
//! all; a single plugin needs the `WindPlugin` too) and the entity needs a `Transform`. An
//! entity whose numbers or transform are bad gets an `…Invalid` component naming the field
//! ([`FallingObjectInvalid`](freefall::FallingObjectInvalid), `ClothInvalid`, …) and a warning
//! once: query for it. Headless, the fixed step only runs when time advances (`MinimalPlugins`
//! with a `TimeUpdateStrategy`, as the tests do). A flag with no wind hangs, and a landed leaf
//! stays down until the wind at its place is faster than
//! [`FallRelease::LIFT_OFF_FACTOR`](freefall::FallRelease::LIFT_OFF_FACTOR) times its descent
//! speed.
//!
//! **Leaves stutter.** Falls are simulated on the fixed step and drawn between their last two
//! steps in `WriteBack`; a system of yours that writes their `Transform` after that (or in
//! `FixedUpdate` without the sets) overrides the pose: order it against [`WindfallSystems`].
//! Far leaves with [`FallLod`](freefall::FallLod) or a cloud's tiers step every second or
//! fourth step and are eased, not frozen, in between.
//!
//! **Too slow.** For hundreds of leaves or more use one [`LeafCloud`](freefall::LeafCloud)
//! instead of entities (one mesh, a structure-of-arrays store stepped in SIMD lanes), give it
//! tiers ([`LodTiers`](lod::LodTiers)) and put [`LodFocus`](lod::LodFocus) on the camera; give
//! many single objects [`FallLod`](freefall::FallLod) and cloth `ClothLod`; build with
//! optimisation (`[profile.dev.package.bevy_windfall] opt-level = 3` in a game's Cargo.toml);
//! `docs/performance.md` says what each part costs.
//!
//! # How the crate is laid out
//!
//! In layers, each using only those below it: [`InvalidValue`], the guards and [`schedule`] at
//! the bottom; [`spectrum`]; [`wind`]; [`lod`]; [`freefall`] and [`cloth`]; [`aero`]; `render` and
//! `inspector`; the plugin group; and this facade, which nothing imports. Each domain keeps its
//! components, its models (free of the ECS, usable on their own) and its plugin in files of their
//! own; limits are associated with the types they bound. `docs/architecture.md` in the
//! repository has the map and where a new kind of object or wind source goes.
#![cfg_attr(docsrs, feature(doc_cfg))]

/// The README's code blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The code blocks of docs/live.md (the headless start among them), compiled and run.
#[cfg(doctest)]
#[doc = include_str!("../docs/live.md")]
pub struct LiveDoctests;

pub mod aero;
pub mod cloth;
mod error;
pub mod freefall;
mod guard;
#[cfg(feature = "egui")]
pub mod inspector;
mod lifecycle;
pub mod lod;
mod portable;
#[cfg(feature = "render")]
pub mod render;
#[doc(hidden)]
pub use portable::{set_lane_width, set_lanes, widest_lanes};
mod plugins;
pub mod schedule;
pub mod spectrum;
pub mod wind;

pub use error::InvalidValue;
pub use guard::MAX_COORDINATE;
#[cfg(feature = "gizmos")]
pub use plugins::WindfallDebugPlugin;
pub use plugins::WindfallPlugins;
pub use schedule::{SimulateSystems, WindfallSchedule, WindfallSystems};

/// What a game spawns and configures: the plugins, the components, the wind and its settings.
/// The papers' machinery (trajectory databases, the Tanabe–Kaneko model, descriptors, spectra)
/// stays in its module.
pub mod prelude {
    #[cfg(feature = "gizmos")]
    pub use crate::WindfallDebugPlugin;
    pub use crate::aero::{
        AeroBody, AeroCoefficients, AeroPlugin, AeroState, PhysicalCloth, RigidPlate,
    };
    pub use crate::cloth::{
        Cloth, ClothAttachment, ClothGrid, ClothParams, ClothPlugin, ClothPreset, ClothState,
    };
    pub use crate::freefall::{
        CloudRegion, FallLod, FallPlugin, FallPreset, FallSettings, FallState, FallStore,
        FallingObject, Fluid, Landed, LeafCloud, LeafCloudPlugin, LeafCloudState, PrimitiveMotion,
        Shape,
    };
    pub use crate::lod::{LodFocus, LodTiers, LodView};
    pub use crate::wind::{
        SpatialMode, TemporalMode, WindConfig, WindError, WindField, WindMover, WindPlugin,
        WindSettings, WindShelter, WindSource,
    };
    pub use crate::{SimulateSystems, WindfallPlugins, WindfallSchedule, WindfallSystems};
}
