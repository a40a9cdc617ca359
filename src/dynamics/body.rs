//! Rigid bodies: type, state, mass properties and the per-body lists (shapes, contacts).

use crate::collision::shape::MassProperties;
use crate::error::{check_non_negative, check_quat, check_vec, Result};
use crate::math::{Mat3, Transform, Vec3};
use crate::pool::Handle;

pub type BodyHandle = Handle;
pub type ShapeHandle = Handle;
pub type ContactHandle = Handle;

/// Sentinel for "not in a list".
pub const NONE: u32 = u32::MAX;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyType {
    /// Never moves; infinite mass.
    Static,
    /// Moved by its velocity (or a target transform); infinite mass, pushes dynamic bodies.
    Kinematic,
    /// Moved by forces and contacts; mass from its shapes.
    Dynamic,
}

/// Everything needed to create a body.
#[derive(Clone, Copy, Debug)]
pub struct BodyDef {
    pub body_type: BodyType,
    pub transform: Transform,
    pub linear_velocity: Vec3,
    pub angular_velocity: Vec3,
    pub linear_damping: f32,
    pub angular_damping: f32,
    pub gravity_scale: f32,
    pub allow_sleep: bool,
    pub awake: bool,
    pub user_data: u64,
}

impl Default for BodyDef {
    fn default() -> Self {
        BodyDef {
            body_type: BodyType::Static,
            transform: Transform::IDENTITY,
            linear_velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            linear_damping: 0.0,
            angular_damping: 0.0,
            gravity_scale: 1.0,
            allow_sleep: true,
            awake: true,
            user_data: 0,
        }
    }
}

impl BodyDef {
    /// Range-checks every number and returns the def with its rotation normalised.
    pub fn validated(&self) -> Result<BodyDef> {
        let mut d = *self;
        check_vec("transform.position", d.transform.p)?;
        d.transform.q = check_quat("transform.rotation", d.transform.q)?;
        check_vec("linear_velocity", d.linear_velocity)?;
        check_vec("angular_velocity", d.angular_velocity)?;
        check_non_negative("linear_damping", d.linear_damping)?;
        check_non_negative("angular_damping", d.angular_damping)?;
        crate::error::check_finite("gravity_scale", d.gravity_scale)?;
        Ok(d)
    }
}

pub struct Body {
    pub body_type: BodyType,
    /// Transform of the body origin.
    pub xf: Transform,
    /// Centre of mass in world space.
    pub center: Vec3,
    /// Centre of mass in the body frame.
    pub local_center: Vec3,
    pub v: Vec3,
    pub w: Vec3,
    /// Accumulated force and torque (about the centre of mass), cleared after each step.
    pub force: Vec3,
    pub torque: Vec3,
    pub mass: f32,
    pub inv_mass: f32,
    /// Inertia about the centre of mass in the body frame.
    pub inertia_local: Mat3,
    pub inv_inertia_local: Mat3,
    /// The inertia is a multiple of the identity: it looks the same in every orientation.
    pub isotropic: bool,
    /// World-space inverse inertia, refreshed at the start of every step.
    pub inv_inertia_world: Mat3,
    pub linear_damping: f32,
    pub angular_damping: f32,
    pub gravity_scale: f32,
    pub allow_sleep: bool,
    pub awake: bool,
    /// Recency-weighted motion (v² + ω²), the seed's sleep measure.
    pub motion: f32,
    /// Seconds the motion has stayed below the sleep threshold.
    pub sleep_time: f32,
    pub user_data: u64,
    pub shapes: Vec<ShapeHandle>,
    /// Every contact this body takes part in (the per-body contact list).
    pub contacts: Vec<u32>,
    /// Position in the world's awake list, or `NONE`.
    pub awake_index: u32,
    /// The sleeping island this body belongs to while asleep.
    pub sleep_island: Handle,
    /// Index of this body's state in the solver for the current step.
    pub solver_index: u32,
    /// Kinematic target: reach this transform by the end of the next step.
    pub kinematic_target: Option<Transform>,
}

impl Body {
    pub fn new(def: &BodyDef) -> Body {
        let mut b = Body {
            body_type: def.body_type,
            xf: def.transform,
            center: def.transform.p,
            local_center: Vec3::ZERO,
            v: if def.body_type == BodyType::Static {
                Vec3::ZERO
            } else {
                def.linear_velocity
            },
            w: if def.body_type == BodyType::Static {
                Vec3::ZERO
            } else {
                def.angular_velocity
            },
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            mass: 0.0,
            inv_mass: 0.0,
            inertia_local: Mat3::ZERO,
            inv_inertia_local: Mat3::ZERO,
            isotropic: true,
            inv_inertia_world: Mat3::ZERO,
            linear_damping: def.linear_damping,
            angular_damping: def.angular_damping,
            gravity_scale: def.gravity_scale,
            allow_sleep: def.allow_sleep,
            awake: false,
            motion: 0.0,
            sleep_time: 0.0,
            user_data: def.user_data,
            shapes: Vec::new(),
            contacts: Vec::new(),
            awake_index: NONE,
            sleep_island: Handle::NULL,
            solver_index: 0,
            kinematic_target: None,
        };
        b.set_mass_properties(MassProperties::ZERO);
        b
    }

    #[inline]
    pub fn is_dynamic(&self) -> bool {
        self.body_type == BodyType::Dynamic
    }

    #[inline]
    pub fn is_static(&self) -> bool {
        self.body_type == BodyType::Static
    }

    /// Sets mass, centre and inertia (dynamic bodies; others keep infinite mass). A dynamic
    /// body without mass (no shapes, or only massless ones) gets 1 kg and unit inertia so
    /// it still falls.
    pub fn set_mass_properties(&mut self, mp: MassProperties) {
        self.mass = 0.0;
        self.inv_mass = 0.0;
        self.inertia_local = Mat3::ZERO;
        self.inv_inertia_local = Mat3::ZERO;
        self.local_center = Vec3::ZERO;
        if self.body_type == BodyType::Dynamic {
            let mp = if mp.mass > 0.0 {
                mp
            } else {
                MassProperties {
                    mass: 1.0,
                    center: Vec3::ZERO,
                    inertia: Mat3::IDENTITY,
                }
            };
            self.mass = mp.mass;
            self.inv_mass = 1.0 / mp.mass;
            self.local_center = mp.center;
            self.inertia_local = mp.inertia;
            // In f64: the determinant of a millimetre body's inertia (~1e-40 kg³m⁶) is below
            // f32's normal range, and an f32 inverse came out infinite (then NaN).
            let inertia = mp.inertia.as_dmat3();
            let det = inertia.determinant();
            let inverse = inertia.inverse().as_mat3();
            self.inv_inertia_local = if det > 0.0 && det.is_finite() && inverse.is_finite() {
                inverse
            } else {
                Mat3::ZERO
            };
        }
        let i = self.inertia_local;
        let d = i.x_axis.x;
        let tol = 1e-6 * d.abs().max(f32::MIN_POSITIVE);
        let off = [i.x_axis.y, i.x_axis.z, i.y_axis.x, i.y_axis.z, i.z_axis.x, i.z_axis.y];
        self.isotropic =
            (i.y_axis.y - d).abs() <= tol && (i.z_axis.z - d).abs() <= tol && off.iter().all(|x| x.abs() <= tol);
        self.center = self.xf.apply(self.local_center);
        self.update_world_inertia();
    }

    /// Refreshes the world-space inverse inertia `R · I⁻¹ · Rᵀ` (unchanged by rotation when
    /// the inertia is isotropic: spheres, cubes).
    #[inline]
    pub fn update_world_inertia(&mut self) {
        if self.isotropic {
            self.inv_inertia_world = self.inv_inertia_local;
            return;
        }
        let r = Mat3::from_quat(self.xf.q);
        self.inv_inertia_world = r * self.inv_inertia_local * r.transpose();
    }

    /// Moves the origin so the centre of mass sits at `center` with rotation `q`.
    #[inline]
    pub fn set_center_rotation(&mut self, center: Vec3, q: glam::Quat) {
        self.center = center;
        self.xf.q = q;
        self.xf.p = center - q * self.local_center;
    }

    pub fn set_transform(&mut self, xf: Transform) {
        self.xf = xf;
        self.center = xf.apply(self.local_center);
        self.update_world_inertia();
    }

    /// Velocity of a world point attached to the body.
    #[inline]
    pub fn point_velocity(&self, p: Vec3) -> Vec3 {
        self.v + self.w.cross(p - self.center)
    }

    /// World-space angular momentum about the centre of mass.
    pub fn angular_momentum(&self) -> Vec3 {
        let r = Mat3::from_quat(self.xf.q);
        r * (self.inertia_local * (r.transpose() * self.w))
    }

    pub fn kinetic_energy(&self) -> f32 {
        0.5 * self.mass * self.v.length_squared() + 0.5 * self.w.dot(self.angular_momentum())
    }
}
