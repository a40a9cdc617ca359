//! Rigid bodies: type, state, mass properties and the per-body lists (shapes, contacts).

use crate::collision::shape::MassProperties;
use crate::error::{
    check_angular_velocity, check_damping, check_gravity_scale, check_position, check_quat, check_velocity, Result,
};
use crate::math::{clamp_length_f64, Mat3, Transform, Vec3};
use crate::pool::Handle;

pub type BodyHandle = Handle;
pub type ShapeHandle = Handle;
pub type ContactHandle = Handle;

/// Sentinel for "not in a list".
pub const NONE: u32 = u32::MAX;

/// Locked-axis bits (`Body::locked_axes`), in world axes: a locked linear axis keeps the
/// centre of mass from moving along it, a locked angular axis keeps the body from turning
/// about it (2.5D games lock linear Z and angular X and Y; upright characters lock every
/// angular axis).
pub const LOCK_LINEAR_X: u8 = 1;
pub const LOCK_LINEAR_Y: u8 = 2;
pub const LOCK_LINEAR_Z: u8 = 4;
pub const LOCK_ANGULAR_X: u8 = 8;
pub const LOCK_ANGULAR_Y: u8 = 16;
pub const LOCK_ANGULAR_Z: u8 = 32;
/// Every defined lock bit.
pub const LOCK_ALL: u8 = 63;

/// Whether each world axis is free (1.0) or locked (0.0), from three lock bits.
#[inline]
fn free_axes(bits: u8) -> Vec3 {
    Vec3::new(
        if bits & 1 == 0 { 1.0 } else { 0.0 },
        if bits & 2 == 0 { 1.0 } else { 0.0 },
        if bits & 4 == 0 { 1.0 } else { 0.0 },
    )
}

/// `v` with the locked linear components (bits 0..3 of `locks`) set to exactly zero.
#[inline]
pub fn lock_linear(v: Vec3, locks: u8) -> Vec3 {
    if locks & 7 == 0 {
        v
    } else {
        Vec3::select(free_axes(locks).cmpeq(Vec3::ZERO), Vec3::ZERO, v)
    }
}

/// `w` with the locked angular components (bits 3..6 of `locks`) set to exactly zero.
#[inline]
pub fn lock_angular(w: Vec3, locks: u8) -> Vec3 {
    if locks & 56 == 0 {
        w
    } else {
        Vec3::select(free_axes(locks >> 3).cmpeq(Vec3::ZERO), Vec3::ZERO, w)
    }
}

/// The inverse inertia of a body that may turn only about its free world axes (`locks`,
/// bits 3..6), from its world inertia `inertia` (about the centre of mass): `W = Pᵀ (P I Pᵀ)⁻¹ P`,
/// with `P` selecting the free axes. The inertia restricted to the free axes is inverted, so an
/// angular impulse `L` turns the body by `W L`, the motion of the reduced equations
/// `P I Pᵀ ω̇ = P τ`; the rows and columns of the locked axes are exactly zero.
///
/// Zeroing the locked rows and columns of the full inverse `I⁻¹` instead (`P I⁻¹ Pᵀ`) is the same
/// only while the inertia does not couple locked and free axes: a rod locked about world X
/// that has turned about Z couples X and Y, and `P I⁻¹ Pᵀ` turned it about Y up to five
/// times too easily. Constraints projected velocities in that wrong metric and put energy in
/// (a three-link hinge chain locked in linear Z and angular X flew apart by 130 m).
pub fn reduced_inverse_inertia(inertia: glam::DMat3, locks: u8) -> Mat3 {
    let free: [usize; 3] = [0, 1, 2];
    let mut idx = [0usize; 3];
    let mut n = 0;
    for k in free {
        if locks & (8 << k) == 0 {
            idx[n] = k;
            n += 1;
        }
    }
    let at = |r: usize, c: usize| inertia.col(c)[r];
    let mut out = [[0.0f64; 3]; 3];
    match n {
        0 => {}
        1 => {
            let a = idx[0];
            let d = at(a, a);
            if d > 0.0 && d.is_finite() {
                out[a][a] = 1.0 / d;
            }
        }
        2 => {
            let (a, b) = (idx[0], idx[1]);
            let (p, q, r) = (at(a, a), 0.5 * (at(a, b) + at(b, a)), at(b, b));
            let det = p * r - q * q;
            if det > 0.0 && det.is_finite() {
                out[a][a] = r / det;
                out[b][b] = p / det;
                out[a][b] = -q / det;
                out[b][a] = -q / det;
            }
        }
        _ => {
            let det = inertia.determinant();
            if det > 0.0 && det.is_finite() {
                let inv = inertia.inverse();
                for (c, o) in out.iter_mut().enumerate() {
                    for (r, x) in o.iter_mut().enumerate() {
                        *x = inv.col(c)[r];
                    }
                }
            }
        }
    }
    // `out[c][r]`: column c, row r (symmetric).
    Mat3::from_cols_array_2d(&out.map(|c| c.map(|x| x as f32)))
}

/// The world inertia `R I Rᵀ` of a body with local inertia `local` and rotation `q` (f64).
#[inline]
pub fn world_inertia(local: &Mat3, q: glam::Quat) -> glam::DMat3 {
    let r = glam::DMat3::from_quat(q.as_dquat());
    r * local.as_dmat3() * r.transpose()
}

/// An isotropic (diagonal, turn-invariant) inverse inertia with the locked axes' entries
/// zeroed: for such an inertia this is `reduced_inverse_inertia` exactly.
#[inline]
fn lock_isotropic(m: Mat3, locks: u8) -> Mat3 {
    if locks & 56 == 0 {
        return m;
    }
    let f = free_axes(locks >> 3);
    let col = |c: Vec3, k: f32| if k == 0.0 { Vec3::ZERO } else { lock_angular(c, locks) };
    Mat3::from_cols(col(m.x_axis, f.x), col(m.y_axis, f.y), col(m.z_axis, f.z))
}

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
    /// Report this body in move events (`events.rs`). Default on.
    pub enable_move_events: bool,
    /// Locked axes, `LOCK_*` bits. Default 0 (none).
    pub locked_axes: u8,
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
            enable_move_events: true,
            locked_axes: 0,
        }
    }
}

impl BodyDef {
    /// Range-checks every number (README "Supported ranges"; velocities against the world's
    /// `max_linear_speed` and `max_angular_speed`) and returns the def with its rotation
    /// normalised.
    pub fn validated(&self, max_linear_speed: f32, max_angular_speed: f32) -> Result<BodyDef> {
        let mut d = *self;
        check_position("transform.position", d.transform.p)?;
        d.transform.q = check_quat("transform.rotation", d.transform.q)?;
        check_velocity("linear_velocity", d.linear_velocity, max_linear_speed)?;
        check_angular_velocity("angular_velocity", d.angular_velocity, max_angular_speed)?;
        check_damping("linear_damping", d.linear_damping)?;
        check_damping("angular_damping", d.angular_damping)?;
        check_gravity_scale("gravity_scale", d.gravity_scale)?;
        check_locked_axes("locked_axes", d.locked_axes as u32)?;
        Ok(d)
    }
}

/// Lock bits: only `LOCK_ALL`'s bits may be set.
pub fn check_locked_axes(name: &str, bits: u32) -> Result<()> {
    if bits & !(LOCK_ALL as u32) != 0 {
        return Err(crate::error::invalid(format!(
            "{name} has unknown bits {:#x} (only the six LOCK_* bits, 0x3f, are defined)",
            bits & !(LOCK_ALL as u32)
        )));
    }
    Ok(())
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
    /// Recency-weighted v² + ω² (half-life 0.1 s), the sleep measure (`dynamics/island.rs`).
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
    /// The next body of its sleeping island (`NONE` after the last): islands are linked lists
    /// through their bodies, so falling asleep and waking need no storage of their own.
    pub island_next: u32,
    /// Index of this body's state in the solver for the current step.
    pub solver_index: u32,
    /// Kinematic target: reach this transform by the end of the next step.
    pub kinematic_target: Option<Transform>,
    /// A kinematic body reached its target in the last step: its velocities still read as
    /// those it moved with, and it stops at the start of the next step unless given a new
    /// target or velocity.
    pub kinematic_stop: bool,
    /// Report this body in move events.
    pub enable_move_events: bool,
    /// The transform last reported in a move event (or at creation).
    pub reported_xf: Transform,
    /// Mass, centre of mass and inertia set by the host (`World::set_mass_data`), used
    /// instead of the shapes' until `World::reset_mass_data`.
    pub mass_override: Option<MassProperties>,
    /// False while disabled (`World::disable_body`): out of the broad phase, no contacts, not
    /// simulated, its joints inactive; its state is kept.
    pub enabled: bool,
    /// Locked axes (`LOCK_*` bits, world axes): the velocity along each is kept exactly zero.
    pub locked_axes: u8,
}

/// The inverse of an inertia tensor, or zero when it is singular. The supported masses and
/// sizes give inertias from 1e-18 to 1e26 kg·m², whose determinants (their cubes) underflow
/// or overflow f32 at the ends: those are inverted at unit scale.
fn inverse_inertia(i: &Mat3) -> Mat3 {
    let det = i.determinant();
    if det > 0.0 && det.is_normal() {
        return i.inverse();
    }
    let scale = i.x_axis.x.abs().max(i.y_axis.y.abs()).max(i.z_axis.z.abs());
    if !(scale > 0.0 && scale.is_finite()) {
        return Mat3::ZERO;
    }
    let unit = *i * (1.0 / scale);
    let det = unit.determinant();
    if det > 0.0 && det.is_finite() {
        unit.inverse() * (1.0 / scale)
    } else {
        Mat3::ZERO
    }
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
            island_next: NONE,
            solver_index: 0,
            kinematic_target: None,
            kinematic_stop: false,
            enable_move_events: def.enable_move_events,
            reported_xf: def.transform,
            mass_override: None,
            enabled: true,
            locked_axes: def.locked_axes,
        };
        b.v = lock_linear(b.v, b.locks());
        b.w = lock_angular(b.w, b.locks());
        b.set_mass_properties(MassProperties::ZERO);
        b
    }

    /// The locks in force: a dynamic body's `locked_axes`; none for static and kinematic
    /// bodies, which move as told.
    #[inline]
    pub fn locks(&self) -> u8 {
        if self.body_type == BodyType::Dynamic {
            self.locked_axes
        } else {
            0
        }
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
            self.inv_inertia_local = inverse_inertia(&mp.inertia);
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
    /// With locked angular axes it is the reduced inverse of the world inertia
    /// (`reduced_inverse_inertia`; for isotropic inertia, the free part of `I⁻¹`).
    #[inline]
    pub fn update_world_inertia(&mut self) {
        let locks = self.locks();
        if self.isotropic {
            self.inv_inertia_world = lock_isotropic(self.inv_inertia_local, locks);
            return;
        }
        if locks & 56 != 0 {
            self.inv_inertia_world = reduced_inverse_inertia(world_inertia(&self.inertia_local, self.xf.q), locks);
            return;
        }
        let r = Mat3::from_quat(self.xf.q);
        self.inv_inertia_world = crate::math::turned_inertia(r, self.inv_inertia_local);
    }

    /// Moves the origin so the centre of mass sits at `center` with rotation `q`.
    /// A dynamic body's locked linear coordinates of the centre of mass stay as they were, and
    /// with every angular axis locked so does its rotation (the stages that move bodies
    /// outside the solver, particles and soft bodies, push positions directly).
    #[inline]
    pub fn set_center_rotation(&mut self, center: Vec3, q: glam::Quat) {
        let locks = self.locks();
        let (center, q) = if locks == 0 {
            (center, q)
        } else {
            let keep = glam::BVec3::new(locks & 1 != 0, locks & 2 != 0, locks & 4 != 0);
            let q = if locks & 56 == 56 { self.xf.q } else { q };
            (Vec3::select(keep, self.center, center), q)
        };
        self.center = center;
        self.xf.q = q;
        self.xf.p = center - q * self.local_center;
    }

    pub fn set_transform(&mut self, xf: Transform) {
        self.xf = xf;
        self.center = xf.apply(self.local_center);
        self.update_world_inertia();
    }

    /// Adds a force (N) at world point `point` to the accumulators: the force and its
    /// moment about the centre of mass. Both saturate at `±f32::MAX` per component, so
    /// any number of finite forces (f64, so products of large parameters do not overflow
    /// first) accumulate to finite values (the step then scales a
    /// drive that would pass the speed limits within a sub-step, `solver::bounded_drive`).
    pub fn add_force_at(&mut self, force: glam::DVec3, point: Vec3) {
        let arm = point.as_dvec3() - self.center.as_dvec3();
        self.add_force_torque(force, arm.cross(force));
    }

    /// Adds a force (N) at the centre of mass and a torque (N·m), saturating like
    /// `add_force_at`.
    pub fn add_force_torque(&mut self, force: glam::DVec3, torque: glam::DVec3) {
        let max = glam::DVec3::splat(f32::MAX as f64);
        self.force = (self.force.as_dvec3() + force).clamp(-max, max).as_vec3();
        self.torque = (self.torque.as_dvec3() + torque).clamp(-max, max).as_vec3();
    }

    /// Changes the velocities by an impulse `j` (N·s) at the centre of mass and an angular
    /// impulse `l` (N·m·s), capped at the speed limits (m/s, rad/s).
    pub fn apply_impulses(&mut self, j: glam::DVec3, l: glam::DVec3, limits: (f32, f32)) {
        let v = self.v.as_dvec3() + j * self.inv_mass as f64;
        let w = self.w.as_dvec3() + self.inv_inertia_world.as_dmat3() * l;
        self.v = lock_linear(clamp_length_f64(v, limits.0), self.locks());
        self.w = lock_angular(clamp_length_f64(w, limits.1), self.locks());
    }

    /// Sets the velocities, capped at the speed limits (m/s, rad/s): the write-back of the
    /// stages that move bodies outside the solver (particles, soft bodies).
    pub fn set_velocities_capped(&mut self, v: Vec3, w: Vec3, limits: (f32, f32)) {
        self.v = lock_linear(crate::math::clamp_length(v, limits.0), self.locks());
        self.w = lock_angular(crate::math::clamp_length(w, limits.1), self.locks());
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
