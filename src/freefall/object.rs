//! [`FallingObject`] (what a game spawns), its runtime [`FallState`] and [`FallingObjectInvalid`]
//! marker, the [`Landed`] message, the shared [`FallSettings`], and how an object is let go
//! (its lifecycle).

use std::sync::Arc;

use bevy::asset::RenderAssetUsages;
use bevy::color::Color;
use bevy::ecs::prelude::*;
use bevy::math::{Vec2, Vec3};
use bevy::mesh::{Indices, Mesh, PrimitiveTopology};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::transform::components::Transform;

use super::fall_lod::FallLod;
use super::fall_store::FallStore;
use super::look::{AUTUMN, SINGLE_POINTS, extent, fold, mix, outline};
use super::model::FallModel;
use super::model::body::{Fluid, Shape};
use super::model::error::FallError;
use super::model::markov::MarkovChain;
use super::model::motion::FallScales;
use super::model::regime::{PrimitiveMotion, Regime};
use super::model::release::FallRelease;
use super::presets::FallPreset;
use super::store::cold::FallStart;
use super::store::path::FallPath;
use crate::error::InvalidValue;
use crate::lifecycle::Described;

/// A leaf, a sheet of paper, a coin: anything thin that falls through air or water.
///
/// It falls from where its [`Transform`] is, turned as it is, when the component is added
/// (released at once by an observer, moved from the next fixed step on). The plate lies in
/// the entity's local XZ plane with its long axis along local Z (the axis it tumbles about).
/// Change it (for example `seed += 1`) to release it again from its current transform; a fall
/// released in mid-air keeps its velocity. An invalid description gets a
/// [`FallingObjectInvalid`] holding the typed error (logged once with `warn!`) and the entity
/// stays still. [`FallPreset`](super::presets::FallPreset) has real
/// objects.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// // A sheet of paper let go 2 m up, turned 30° about its long axis.
/// let sheet = app
///     .world_mut()
///     .spawn((
///         FallingObject {
///             shape: Shape::Rectangle { length: 0.297, width: 0.21, thickness: 1e-4 },
///             density: 800.0,
///             seed: 3,
///             ..default()
///         },
///         Transform::from_xyz(0.0, 2.0, 0.0).with_rotation(Quat::from_rotation_z(0.5)),
///     ))
///     .id();
/// app.update();
/// let regime = *app.world().get::<FallState>(sheet).unwrap().regime().unwrap();
/// assert_eq!(regime.main, PrimitiveMotion::Tumbling);
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Default, Debug)]
#[require(Transform, FallState)]
pub struct FallingObject {
    /// Outline and sizes.
    pub shape: Shape,
    /// ρ_s, kg/m³ (above the fluid's).
    pub density: f32,
    /// The fluid it falls in.
    pub fluid: Fluid,
    /// g, m/s².
    pub gravity: f32,
    /// Seed of this object's random stream (Markov steps, search-tree choices, heading).
    pub seed: u64,
    /// Use this main motion instead of the phase diagram's.
    pub main_motion: Option<PrimitiveMotion>,
    /// k of eq. 7, the deviation coefficient (1 = the paper's amplitudes).
    pub deviation: f32,
    /// W of eq. 15: the largest tilt the wind gives, rad.
    pub wind_tilt: f32,
    /// The Markov chain of its motions (`None`: the [`FallModel`]'s).
    pub markov: Option<MarkovChain>,
    /// What it is drawn as (outline and colours, see [`mesh`](Self::mesh)):
    /// [`FallPreset::object`](super::presets::FallPreset::object) sets its preset; `None` draws
    /// its [`Shape`] in autumn colours. Only the look: changing it does not let the object go
    /// again.
    pub look: Option<FallPreset>,
}

impl Default for FallingObject {
    /// A 7.3 × 4.2 cm leaf, 0.3 mm thick, density 500 kg/m³, in air.
    fn default() -> Self {
        Self {
            shape: Shape::Ellipse {
                major: 0.073,
                minor: 0.042,
                thickness: 3.0e-4,
            },
            density: 500.0,
            fluid: Fluid::AIR,
            gravity: 9.81,
            seed: 0,
            main_motion: None,
            deviation: 1.0,
            wind_tilt: 0.6,
            markov: None,
            look: None,
        }
    }
}

impl FallingObject {
    /// Re, I*, U and the main motion (the phase diagram's, or [`FallingObject::main_motion`]).
    pub fn regime(&self) -> Result<Regime, FallError> {
        InvalidValue::check(
            (0.0..=100.0).contains(&self.deviation),
            "deviation",
            self.deviation,
            "must be in [0, 100]",
        )?;
        InvalidValue::check(
            self.wind_tilt.abs() <= std::f32::consts::PI,
            "wind_tilt",
            self.wind_tilt,
            "must be an angle in [−π, π]",
        )?;
        let mut r = Regime::new(&self.shape, self.density, &self.fluid, self.gravity)?;
        if let Some(main) = self.main_motion {
            r.main = main;
        }
        Ok(r)
    }

    /// The sizes of its fall (U, Ω = 2π St U / a, L, a, k, ℓ = ρ_s b / ρ_f, I*).
    pub fn scales(&self, regime: &Regime) -> FallScales {
        let (length, chord, thickness) = self.shape.lengths();
        FallScales {
            descent_speed: regime.descent_speed,
            swing_rate: (std::f32::consts::TAU * FallScales::STROUHAL * regime.descent_speed
                / chord)
                .max(1e-6),
            length,
            chord,
            deviation: self.deviation,
            drag_length: (f64::from(self.density) * f64::from(thickness)
                / f64::from(self.fluid.density)) as f32,
            inertia: regime.inertia,
        }
    }

    /// Its fall let go as `release` says, with its own chain or the model's.
    ///
    /// # Errors
    /// What [`Self::regime`] or [`FallRelease::validate`] reject.
    pub fn path(&self, model: &FallModel, release: FallRelease) -> Result<FallPath, FallError> {
        let start = self.start(model, release, None)?;
        Ok(FallPath::release(
            model,
            start.scales,
            start.chain,
            start.seed,
            start.release,
        ))
    }

    /// What lets its fall go as `release` says, with levels of detail `lod`.
    pub(crate) fn start(
        &self,
        model: &FallModel,
        release: FallRelease,
        lod: Option<crate::lod::LodTiers>,
    ) -> Result<FallStart, FallError> {
        let regime = self.regime()?;
        release.validate()?;
        let chain = match &self.markov {
            Some(chain) => Arc::new(chain.bounded(regime.main)),
            None => model.bounded_shared(regime.main),
        };
        Ok(FallStart {
            scales: self.scales(&regime),
            chain,
            seed: self.seed,
            release,
            max_angle: self.wind_tilt,
            lod,
        })
    }
}

/// Runtime state of a [`FallingObject`] (required component): its regime (Re, I*, U, the main
/// motion), what it is doing, and which fall of the app's [`FallStore`] is its own (read the
/// fall itself there, with [`FallStore::fall`]). Changed when it is let go, when its motion
/// changes and when it lands or is lifted, not on every step.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // Count what the falling objects are doing.
/// fn census(objects: Query<&FallState>) -> [usize; 6] {
///     let mut counts = [0; 6];
///     for motion in objects.iter().filter_map(FallState::motion) {
///         counts[motion.index()] += 1;
///     }
///     counts
/// }
/// # let _ = census;
/// ```
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct FallState {
    regime: Option<Regime>,
    #[reflect(ignore)]
    motion: Option<PrimitiveMotion>,
    landed: bool,
    /// Its fall in the app's store.
    #[reflect(ignore)]
    pub(super) handle: Option<u32>,
}

impl FallState {
    /// Re, I*, U, mass and main motion, once the object is set up.
    pub fn regime(&self) -> Option<&Regime> {
        self.regime.as_ref()
    }

    /// The current primitive motion (Markov state), once it falls.
    pub fn motion(&self) -> Option<PrimitiveMotion> {
        self.motion
    }

    /// True once on the ground (until a strong enough wind lifts it).
    pub fn landed(&self) -> bool {
        self.landed
    }

    /// Whether it has a fall (a valid description, set up).
    pub fn falls(&self) -> bool {
        self.handle.is_some()
    }

    /// Takes in what its fall is doing now.
    pub(super) fn mirror(&mut self, motion: PrimitiveMotion, landed: bool) {
        self.motion = Some(motion);
        self.landed = landed;
    }
}

/// Why a [`FallingObject`] does not fall: its description is invalid (the error names the
/// field), or where it was let go is (checked by [`FallRelease::validate`]): a `Transform`
/// whose translation is not finite or beyond ±[`MAX_COORDINATE`](crate::MAX_COORDINATE)
/// (`release.position`), a zero or non-finite rotation (`release.rotation`), or a
/// [`FallSettings::ground_height`] that is not finite (`release.ground`). Inserted in place
/// of a fall (logged once), removed once the component is changed and valid; the crate's one
/// convention for runtime failures, as [`ClothInvalid`](crate::cloth::ClothInvalid),
/// [`PhysicalClothInvalid`](crate::aero::PhysicalClothInvalid) and
/// [`AeroBodyInvalid`](crate::aero::AeroBodyInvalid).
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// use bevy_windfall::freefall::FallingObjectInvalid;
///
/// let mut app = App::new();
/// app.add_plugins((MinimalPlugins, TransformPlugin, WindfallPlugins::default()));
/// // Lighter than air: it cannot fall.
/// let balloon = app
///     .world_mut()
///     .spawn(FallingObject { density: 0.5, ..default() })
///     .id();
/// app.update();
/// let invalid = app.world().get::<FallingObjectInvalid>(balloon).unwrap();
/// assert_eq!(invalid.0.field(), "density");
/// ```
#[derive(Component, Clone, Debug, PartialEq, Reflect)]
#[reflect(Component, Debug)]
pub struct FallingObjectInvalid(pub FallError);

crate::lifecycle::invalid_marker!(FallingObjectInvalid, FallError);

/// Sent when a [`FallingObject`] reaches the ground.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// fn rustle(mut landed: MessageReader<Landed>) {
///     for l in landed.read() {
///         info!("{} landed at {} after {:.1} s", l.entity, l.position, l.flight_time);
///     }
/// }
/// App::new()
///     .add_plugins((MinimalPlugins, WindfallPlugins::default()))
///     .add_systems(Update, rustle);
/// ```
#[derive(Message, Clone, Copy, Debug, PartialEq)]
pub struct Landed {
    /// The object.
    pub entity: Entity,
    /// Where it came to rest.
    pub position: Vec3,
    /// Seconds since it was released.
    pub flight_time: f32,
}

/// Shared settings of every fall.
///
/// # Example
///
/// ```
/// use bevy::prelude::*;
/// use bevy_windfall::prelude::*;
///
/// // A table top 0.75 m up.
/// App::new()
///     .add_plugins((MinimalPlugins, WindfallPlugins::default()))
///     .insert_resource(FallSettings { ground_height: 0.75 });
/// ```
#[derive(Resource, Clone, Debug, PartialEq, Default, Reflect)]
#[reflect(Resource, Default, Debug)]
pub struct FallSettings {
    /// Height of the ground, m: objects stop there.
    pub ground_height: f32,
}

/// How it is drawn: its colours and its mesh (its outlines are drawn by the private `look` module).
impl FallingObject {
    /// The colours it is drawn in: its [`look`](Self::look)'s palette, autumn without one.
    pub fn palette(&self) -> &'static [Color] {
        self.look.map_or(&AUTUMN, FallPreset::palette)
    }

    /// Its colour: one of its [`palette`](Self::palette), chosen by its seed.
    pub fn color(&self) -> Color {
        self.palette()[self.color_index()]
    }

    /// Which colour of its palette it takes.
    pub(crate) fn color_index(&self) -> usize {
        (mix(self.seed) % self.palette().len() as u64) as usize
    }

    /// Its mesh at its size: the plate in the local XZ plane (long axis Z, faces toward ±Y, as
    /// it falls), outlined as its [`look`](Self::look) (a maple, oak or birch leaf, …) or, without
    /// one, as its [`Shape`]; leaves are folded a little along the midrib so that light shows
    /// their shape from either side. Flat normals; draw it with a two-sided material.
    pub fn mesh(&self) -> Mesh {
        let (centre, outline) = outline(self.look, &self.shape, SINGLE_POINTS);
        let (_, major) = extent(&self.shape);
        let fold = fold(self.look, &self.shape);
        // The fold along the midrib, and the tip and stalk curling up a little.
        let lift = |p: Vec2| {
            let curl = if fold > 0.0 {
                0.3 * p.y * p.y / major
            } else {
                0.0
            };
            Vec3::new(p.x, fold * p.x.abs() + curl, p.y)
        };
        let mut positions = vec![lift(centre)];
        positions.extend(outline.iter().map(|&p| lift(p)));
        let n = outline.len() as u32;
        let indices = (0..n).flat_map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        let mut mesh = Mesh::new(
            PrimitiveTopology::TriangleList,
            RenderAssetUsages::default(),
        )
        .with_inserted_attribute(
            Mesh::ATTRIBUTE_POSITION,
            positions.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
        )
        .with_inserted_indices(Indices::U32(indices));
        mesh.duplicate_vertices();
        mesh.compute_flat_normals();
        mesh
    }
}

/// The objects of the presets (here, beside the component, so that the presets need not know it).
impl FallPreset {
    /// The object: shape, density, fluid, main motion and chain, drawn as this preset; seed 0,
    /// the default k, W.
    pub fn object(self) -> FallingObject {
        let (shape, density, fluid, main_motion) = self.body();
        FallingObject {
            shape,
            density,
            fluid,
            main_motion,
            markov: Some(self.chain()),
            look: Some(self),
            ..FallingObject::default()
        }
    }
}

impl From<FallPreset> for FallingObject {
    fn from(preset: FallPreset) -> Self {
        preset.object()
    }
}

impl Described for FallingObject {
    type Invalid = FallingObjectInvalid;
    type Key = FallingObject;
    type Data = (
        &'static Transform,
        &'static mut FallState,
        Option<&'static FallLod>,
    );
    type Context = (
        Option<Res<'static, FallSettings>>,
        Option<Res<'static, FallModel>>,
        Option<ResMut<'static, FallStore>>,
    );
    const SUBJECT: &'static str = "FallingObject";
    const CONSEQUENCE: &'static str = "it does not fall";

    /// The object without its look: a new look redraws it, it does not let it go again.
    fn key(&self) -> FallingObject {
        FallingObject {
            look: None,
            ..self.clone()
        }
    }

    /// Lets the object go from its transform, in its own slot of the app's [`FallStore`]; a
    /// fall released again in mid-air keeps the velocity the fluid gave it. Without a model or
    /// a store (removed by the user) nothing is released.
    fn set_up(
        &self,
        entity: Entity,
        (transform, mut state, lod): (&Transform, Mut<FallState>, Option<&FallLod>),
        (settings, model, store): &mut (
            Option<Res<FallSettings>>,
            Option<Res<FallModel>>,
            Option<ResMut<FallStore>>,
        ),
        _: &mut Commands,
    ) -> Option<Result<(), FallError>> {
        let model = model.as_deref()?;
        let store = store.as_deref_mut()?;
        let velocity = store
            .fall(entity)
            .filter(|f| !f.landed())
            .map_or(Vec3::ZERO, |f| f.drift());
        let release = FallRelease {
            position: transform.translation,
            rotation: Some(transform.rotation),
            velocity,
            ground: settings.as_ref().map_or(0.0, |s| s.ground_height),
        };
        let lod = lod.map(|l| l.0).filter(|l| l.check().is_ok());
        let fall = self
            .regime()
            .and_then(|regime| Ok((regime, self.start(model, release, lod)?)));
        Some(match fall {
            Ok((regime, start)) => {
                let handle = store.set_up(entity, model, &start);
                let motion = store.fall(entity).map(|f| f.motion());
                *state = FallState {
                    regime: Some(regime),
                    motion,
                    landed: false,
                    handle: Some(handle),
                };
                Ok(())
            }
            Err(error) => {
                store.remove(entity);
                *state = FallState::default();
                Err(error)
            }
        })
    }
}
