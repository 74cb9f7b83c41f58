//! Lift and drag on avian3d rigid bodies (feature `avian`).

use crate::error::InvalidValue;
use avian3d::prelude::ReadRigidBodyForces;
use avian3d::prelude::{ComputedCenterOfMass, ComputedMass, Forces, WriteRigidBodyForces};
use bevy::app::{App, FixedPostUpdate, Plugin};
use bevy::asset::Assets;
use bevy::ecs::prelude::*;
use bevy::ecs::schedule::{InternedScheduleLabel, ScheduleLabel};
use bevy::math::Vec3;
use bevy::mesh::{Indices, Mesh, Mesh3d, VertexAttributeValues};
use bevy::reflect::Reflect;
use bevy::reflect::std_traits::ReflectDefault;
use bevy::time::Time;

use super::coefficients::AeroCoefficients;
use super::error::AeroError;
use super::force::face_force;
use super::plate::Face;
use crate::wind::WindField;

/// Per-face lift and drag for an avian3d rigid body: put it beside `RigidBody::Dynamic` and a
/// collider; [`AvianAeroPlugin`] applies the summed force and torque through avian's
/// [`Forces`] each fixed step, from the [`WindField`] (still air without one).
///
/// Avian integrates forces explicitly, which is unstable for light bodies in strong wind
/// (dt × ρ C_D A |v_rel| / m above about 2). The plugin therefore caps the aerodynamic force so
/// that in one step it can change the body's velocity by at most its velocity relative to the
/// air at its centre of mass: drag can stop a body relative to the wind, never fling it past.
///
/// # Example
///
/// ```
/// use avian3d::prelude::*;
/// use bevy::prelude::*;
/// use bevy_windfall::aero::{AeroCoefficients, AvianAero};
///
/// // A 40 × 40 cm kite-like board that avian moves and the wind lifts.
/// let mesh = Mesh::from(Plane3d::default().mesh().size(0.4, 0.4));
/// let board = (
///     RigidBody::Dynamic,
///     Collider::cuboid(0.4, 0.005, 0.4),
///     AvianAero::from_mesh(&mesh, AeroCoefficients::default())?,
///     Transform::from_xyz(0.0, 10.0, 0.0),
/// );
/// # let _ = board;
/// # Ok::<(), bevy_windfall::aero::AeroError>(())
/// ```
///
/// Or take the faces from the mesh the entity is drawn with: spawn [`AvianAero::default()`] (no
/// faces) beside a `Mesh3d`, and the plugin fills them in once the mesh has loaded.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component, Default, Debug)]
pub struct AvianAero {
    /// Faces in the body's local frame (empty beside a `Mesh3d`: taken from that mesh).
    pub faces: Vec<Face>,
    /// Coefficients and fluid.
    pub coefficients: AeroCoefficients,
}

impl AvianAero {
    /// One face per triangle of `mesh` (a triangle list with positions). The face law is
    /// two-sided: build from one side of a double-sided mesh, or the area counts twice.
    pub fn from_mesh(mesh: &Mesh, coefficients: AeroCoefficients) -> Result<Self, AeroError> {
        coefficients.validate()?;
        let no_positions =
            AeroError::from(InvalidValue::new("mesh", 0.0, "needs Float32x3 positions"));
        let Some(VertexAttributeValues::Float32x3(positions)) =
            mesh.attribute(Mesh::ATTRIBUTE_POSITION)
        else {
            return Err(no_positions);
        };
        let corners: Vec<usize> = match mesh.indices() {
            Some(Indices::U16(i)) => i.iter().map(|&k| usize::from(k)).collect(),
            Some(Indices::U32(i)) => i.iter().map(|&k| k as usize).collect(),
            None => (0..positions.len()).collect(),
        };
        let faces = corners
            .chunks_exact(3)
            .filter_map(|t| {
                let [a, b, c] =
                    [t[0], t[1], t[2]].map(|k| positions.get(k).map(|&p| Vec3::from(p)));
                let (a, b, c) = (a?, b?, c?);
                let cross = (b - a).cross(c - a);
                let area = 0.5 * cross.length();
                (area > 0.0 && area.is_finite()).then(|| Face {
                    center: (a + b + c) / 3.0,
                    normal: cross / (2.0 * area),
                    area,
                })
            })
            .collect();
        Ok(Self {
            faces,
            coefficients,
        })
    }
}

/// Applies [`AvianAero`] forces right before avian's physics step: in avian's schedule
/// (`FixedPostUpdate`, as `PhysicsPlugins::default()`), in `PhysicsSystems::First`, and after the
/// wind's clock has advanced ([`WindfallSystems::Wind`](crate::schedule::WindfallSystems::Wind) runs in `FixedUpdate`, earlier in the
/// same fixed step). Add it beside `PhysicsPlugins`; if you run avian in another schedule, use
/// [`AvianAeroPlugin::new`] with the same one.
pub struct AvianAeroPlugin {
    schedule: InternedScheduleLabel,
}

impl Default for AvianAeroPlugin {
    fn default() -> Self {
        Self::new(FixedPostUpdate)
    }
}

impl AvianAeroPlugin {
    /// Forces applied in `schedule`, the one avian's `PhysicsPlugins::new` was given.
    pub fn new(schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: schedule.intern(),
        }
    }
}

impl Plugin for AvianAeroPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<AvianAero>().add_systems(
            self.schedule,
            (faces_from_meshes, apply_aero)
                .chain()
                .in_set(avian3d::schedule::PhysicsSystems::First),
        );
    }
}

/// Fills in the faces of an [`AvianAero`] without any from its entity's `Mesh3d`, once loaded.
fn faces_from_meshes(
    mut bodies: Query<(&mut AvianAero, &Mesh3d)>,
    meshes: Option<Res<Assets<Mesh>>>,
) {
    let Some(meshes) = meshes else {
        return;
    };
    for (mut aero, handle) in &mut bodies {
        if !aero.faces.is_empty() {
            continue;
        }
        let Some(mesh) = meshes.get(&handle.0) else {
            continue;
        };
        match AvianAero::from_mesh(mesh, aero.coefficients) {
            Ok(built) if !built.faces.is_empty() => aero.faces = built.faces,
            _ => {}
        }
    }
}

fn apply_aero(
    mut bodies: Query<(&AvianAero, Forces, &ComputedCenterOfMass, &ComputedMass)>,
    wind: Option<Res<WindField>>,
    time: Res<Time>,
) {
    let dt = time.delta_secs();
    let wind = wind.as_deref();
    let air = |p: Vec3| wind.map_or(Vec3::ZERO, |w| w.velocity(p));
    for (aero, mut forces, com, mass) in &mut bodies {
        let position = forces.position();
        let rotation = forces.rotation();
        let (v, w) = (forces.linear_velocity(), forces.angular_velocity());
        let centre = position + rotation * com.0;
        let c = &aero.coefficients;
        let mut total = Vec3::ZERO;
        let mut torque = Vec3::ZERO;
        for face in &aero.faces {
            let point = position + rotation * face.center;
            let arm = point - centre;
            let rel = v + w.cross(arm) - air(point);
            let f = face_force(
                rel,
                rotation * face.normal,
                face.area,
                c.drag,
                c.lift,
                c.density,
            );
            total += f;
            torque += arm.cross(f);
        }
        // The cap: |F| dt / m ≤ |v − u| at the centre of mass.
        let m = mass.value();
        let limit = m * (v - air(centre)).length() / dt.max(1e-6);
        let k = if total.length() > limit && total.length() > 0.0 {
            limit / total.length()
        } else {
            1.0
        };
        if (total * k).is_finite() && (torque * k).is_finite() {
            forces.apply_force(total * k);
            forces.apply_torque(torque * k);
        }
    }
}
