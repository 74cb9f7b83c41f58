//! [`FallingObject`] (what a game spawns), its runtime [`FallState`] and [`FallingObjectInvalid`]
//! marker, the [`Landed`] message, the shared [`FallSettings`], and how an object is let go
//! (its lifecycle); the presets, [`FallPreset`].
//!
//! # Presets
//!
//! Named falling objects with real sizes and densities, each with the Markov chain that gives it
//! a believable sequence of motions.
//!
//! Sizes and densities: the paper's three objects of §5 (Fig. 15) as it states them; tree leaves
//! from the usual blade sizes of field guides (Norway maple 7–14 cm, about as wide as long;
//! pedunculate oak 7–14 cm; silver birch 3–7 cm) with autumn leaf mass per area of 50–90 g/m²
//! (Niinemets & Kull 1994 give 69 g/m² on average over 85 woody species) and thicknesses of
//! 0.15–0.25 mm; office paper of 80 g/m² (0.1 mm, 800 kg/m³); a poker card 88.9 × 63.5 mm of
//! 1.8 g; an elm samara of 6.5 mg and 1.5 × 1.2 cm.
//!
//! **Main motions.** With those sizes the phase diagram puts every object in air near or above
//! the tumbling boundary (I* ∝ ρ_s / ρ_f ≈ 500 in air), where the paper reports spiral and helix
//! for its paper and leaf (§5 prints I* values its sizes cannot give: see the README). Presets
//! whose main motion is the paper's report or a designer's choice say so and force it through
//! [`FallingObject::main_motion`]; the others use the phase diagram.
//!
//! **Chains.** Each preset starts where the paper's Fig. 15 (or common sight) starts and climbs
//! the hypothesis of §3.1 at the dwell times in [`FallPreset::dwell_times`], seconds on average
//! in each motion before the next. The measured seconds per motion are in the report.

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
use super::look::{AUTUMN, Outline, SINGLE_POINTS, extent, fold, mix, outline};
use super::model::FallModel;
use super::model::body::{Fluid, Shape};
use super::model::error::FallError;
use super::model::markov::MarkovChain;
use super::model::motion::FallScales;
use super::model::regime::{PrimitiveMotion, Regime};
use super::model::release::FallRelease;
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
/// stays still. [`FallPreset`] has real objects.
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
    /// [`FallPreset::object`] sets its preset; `None` draws
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
            phase: 0.0,
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

    /// How it is outlined: its [`look`](Self::look)'s outline, ovate without one.
    pub(crate) fn outline(&self) -> Outline {
        self.look.map_or(Outline::Ovate, FallPreset::outline)
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
        let (centre, outline) = outline(self.outline(), &self.shape, SINGLE_POINTS);
        let (_, major) = extent(&self.shape);
        let fold = fold(self.outline(), &self.shape);
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

/// A named object: shape, density, fluid, main motion and Markov chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Reflect)]
pub enum FallPreset {
    /// The paper's coin (Fig. 15a): aluminium, 2 cm across, 1.5 mm thick, in water. Steady at
    /// first, then fluttering (the phase diagram's main motion).
    Coin,
    /// The paper's sheet (Fig. 15b): an ellipse of 80 g/m² paper, 8 × 2 cm, 0.1 mm, in air.
    /// Tumbles, then spirals (the paper's report; forced).
    PaperSheet,
    /// The paper's leaf (Fig. 15c): 7.3 × 4.2 cm, 0.3 mm, 500 kg/m³. Steady, tumbling, then a
    /// helix (the paper's report; forced).
    Leaf,
    /// A Norway maple leaf in autumn: 11 × 10 cm, 0.2 mm, 300 kg/m³ (60 g/m²). Steady,
    /// fluttering, then chaotic (the phase diagram's I* ≈ 0.027).
    MapleLeaf,
    /// An oak leaf in autumn: 10 × 5 cm, 0.25 mm, 350 kg/m³ (88 g/m²). Steady, fluttering,
    /// chaotic, then tumbling (the phase diagram's).
    OakLeaf,
    /// A silver birch leaf in autumn: 5 × 3.5 cm, 0.15 mm, 400 kg/m³ (60 g/m²). Steady,
    /// fluttering, then a helix (designer's choice; the phase diagram says tumbling).
    BirchLeaf,
    /// A poker card, 88.9 × 63.5 mm, 0.3 mm, 1.8 g. Flutters, then tumbles end over end (the
    /// phase diagram's I* ≈ 3.5; Mahadevan et al. 1999).
    PlayingCard,
    /// An elm samara, a light winged seed: 1.5 × 1.2 cm, 0.1 mm, 460 kg/m³ (6.5 mg). Flutters,
    /// then spirals down (designer's choice).
    Samara,
}

impl FallPreset {
    /// Every preset.
    pub const ALL: [Self; 8] = [
        Self::Coin,
        Self::PaperSheet,
        Self::Leaf,
        Self::MapleLeaf,
        Self::OakLeaf,
        Self::BirchLeaf,
        Self::PlayingCard,
        Self::Samara,
    ];

    /// A short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Coin => "coin (Fig. 15a)",
            Self::PaperSheet => "paper sheet (Fig. 15b)",
            Self::Leaf => "leaf (Fig. 15c)",
            Self::MapleLeaf => "maple leaf",
            Self::OakLeaf => "oak leaf",
            Self::BirchLeaf => "birch leaf",
            Self::PlayingCard => "playing card",
            Self::Samara => "elm samara",
        }
    }

    /// Shape, density (kg/m³), fluid and forced main motion.
    pub(super) fn body(self) -> (Shape, f32, Fluid, Option<PrimitiveMotion>) {
        use PrimitiveMotion::*;
        let ellipse = |major, minor, thickness| Shape::Ellipse {
            major,
            minor,
            thickness,
        };
        match self {
            Self::Coin => (
                Shape::Disk {
                    diameter: 0.02,
                    thickness: 0.0015,
                },
                2700.0,
                Fluid::WATER,
                None,
            ),
            Self::PaperSheet => (ellipse(0.08, 0.02, 1.0e-4), 800.0, Fluid::AIR, Some(Spiral)),
            Self::Leaf => (
                ellipse(0.073, 0.042, 3.0e-4),
                500.0,
                Fluid::AIR,
                Some(Helix),
            ),
            Self::MapleLeaf => (ellipse(0.11, 0.10, 2.0e-4), 300.0, Fluid::AIR, None),
            Self::OakLeaf => (ellipse(0.10, 0.05, 2.5e-4), 350.0, Fluid::AIR, None),
            Self::BirchLeaf => (ellipse(0.05, 0.035, 1.5e-4), 400.0, Fluid::AIR, Some(Helix)),
            Self::PlayingCard => (
                Shape::Rectangle {
                    length: 0.0889,
                    width: 0.0635,
                    thickness: 3.0e-4,
                },
                1060.0,
                Fluid::AIR,
                None,
            ),
            Self::Samara => (
                ellipse(0.015, 0.012, 1.0e-4),
                460.0,
                Fluid::AIR,
                Some(Spiral),
            ),
        }
    }

    /// Where a fall starts (weights over L1..L6), the mean seconds it stays in each motion, and
    /// the weights of the motions it goes to next (only higher ones count; the main motion,
    /// the last, holds).
    pub fn dwell_times(self) -> ([f32; 6], [f32; 6]) {
        const F: f32 = f32::INFINITY;
        match self {
            Self::Coin => ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.5, F, F, F, F, F]),
            Self::PaperSheet => ([0.3, 0.0, 0.0, 0.7, 0.0, 0.0], [0.3, F, F, 1.2, F, F]),
            Self::Leaf => ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.6, F, F, 1.2, F, F]),
            Self::MapleLeaf => ([0.6, 0.4, 0.0, 0.0, 0.0, 0.0], [0.5, 1.2, F, F, F, F]),
            Self::OakLeaf => ([0.6, 0.4, 0.0, 0.0, 0.0, 0.0], [0.4, 0.8, 1.0, F, F, F]),
            Self::BirchLeaf => ([0.5, 0.5, 0.0, 0.0, 0.0, 0.0], [0.5, 1.2, F, F, F, F]),
            Self::PlayingCard => ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], [F, 0.5, 0.6, F, F, F]),
            Self::Samara => ([0.3, 0.7, 0.0, 0.0, 0.0, 0.0], [0.3, 0.8, F, F, F, F]),
        }
    }

    /// The motions a fall of this preset goes through, in order (the paper's sequence).
    pub fn sequence(self) -> &'static [PrimitiveMotion] {
        use PrimitiveMotion::*;
        match self {
            Self::Coin => &[SteadyDescent, Fluttering],
            Self::PaperSheet => &[SteadyDescent, Tumbling, Spiral],
            Self::Leaf => &[SteadyDescent, Tumbling, Helix],
            Self::MapleLeaf => &[SteadyDescent, Fluttering, Chaotic],
            Self::OakLeaf => &[SteadyDescent, Fluttering, Chaotic, Tumbling],
            Self::BirchLeaf => &[SteadyDescent, Fluttering, Helix],
            Self::PlayingCard => &[Fluttering, Chaotic, Tumbling],
            Self::Samara => &[SteadyDescent, Fluttering, Spiral],
        }
    }

    /// The preset's chain: from [`FallPreset::dwell_times`], each motion going on to the next
    /// one of [`FallPreset::sequence`].
    pub fn chain(self) -> MarkovChain {
        let (initial, dwell) = self.dwell_times();
        let sequence = self.sequence();
        let mut next = [[0.0f32; 6]; 6];
        for pair in sequence.windows(2) {
            next[pair[0].index()][pair[1].index()] = 1.0;
        }
        MarkovChain::from_dwell_times(initial, dwell, next)
            .expect("every preset's chain is a valid upper-triangular matrix")
    }

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

    /// How it is outlined: leaves by their own outlines, paper, cards and coins round.
    pub(crate) fn outline(self) -> Outline {
        match self {
            Self::MapleLeaf => Outline::Maple,
            Self::OakLeaf => Outline::Oak,
            Self::BirchLeaf => Outline::Birch,
            Self::Coin | Self::PaperSheet | Self::PlayingCard => Outline::Round,
            Self::Leaf | Self::Samara => Outline::Ovate,
        }
    }

    /// The colours objects of this preset are drawn in (sRGB); each object takes one by its seed.
    pub fn palette(self) -> &'static [Color] {
        const COIN: [Color; 2] = [Color::srgb(0.80, 0.81, 0.83), Color::srgb(0.70, 0.72, 0.75)];
        const PAPER: [Color; 2] = [Color::srgb(0.96, 0.95, 0.91), Color::srgb(0.93, 0.93, 0.96)];
        const GREEN: [Color; 3] = [
            Color::srgb(0.33, 0.55, 0.14),
            Color::srgb(0.45, 0.62, 0.18),
            Color::srgb(0.56, 0.64, 0.16),
        ];
        const MAPLE: [Color; 4] = [
            Color::srgb(0.82, 0.20, 0.06),
            Color::srgb(0.92, 0.45, 0.08),
            Color::srgb(0.72, 0.12, 0.05),
            Color::srgb(0.95, 0.62, 0.12),
        ];
        const OAK: [Color; 4] = [
            Color::srgb(0.58, 0.34, 0.12),
            Color::srgb(0.66, 0.44, 0.16),
            Color::srgb(0.48, 0.28, 0.10),
            Color::srgb(0.72, 0.52, 0.20),
        ];
        const BIRCH: [Color; 3] = [
            Color::srgb(0.96, 0.78, 0.15),
            Color::srgb(0.90, 0.68, 0.10),
            Color::srgb(0.86, 0.80, 0.26),
        ];
        const CARD: [Color; 2] = [Color::srgb(0.97, 0.97, 0.95), Color::srgb(0.80, 0.10, 0.12)];
        const SAMARA: [Color; 2] = [Color::srgb(0.80, 0.74, 0.44), Color::srgb(0.70, 0.66, 0.38)];
        match self {
            Self::Coin => &COIN,
            Self::PaperSheet => &PAPER,
            Self::Leaf => &GREEN,
            Self::MapleLeaf => &MAPLE,
            Self::OakLeaf => &OAK,
            Self::BirchLeaf => &BIRCH,
            Self::PlayingCard => &CARD,
            Self::Samara => &SAMARA,
        }
    }
}
