//! The sub-stepped solver: body states, velocity and position integration (semi-implicit
//! Euler, anisotropic bodies turning by a symplectic free-rotation splitting, or RK4 for
//! unconstrained bodies), and the stage
//! list of a step (after Box2D v3's soft step):
//!
//! prepare contacts and joints → per sub-step { integrate velocities, warm start (joints,
//! then contacts, each batch refreshed first), solve with bias (joints, then contacts),
//! integrate positions, relax without bias (joints, then contacts) } → restitution → store
//! impulses.
//!
//! Plain and kinematic bodies are integrated in SIMD lanes (`integrate_wide.rs`); bodies with
//! torque, gyroscopic motion or RK4 take the scalar path here, the gyroscopic ones' position
//! update four at a time in f64 lanes with the same result (`free_rotation_lanes.rs`).

use crate::dynamics::body::{lock_angular, lock_linear, reduced_inverse_inertia, world_inertia, Body};
use crate::dynamics::contact_solver::{self, ContactRef, Sources};
use crate::dynamics::contact_wide;
use crate::dynamics::integrate_wide;
use crate::math::{clamp_length, clamp_length_f64, integrate_rotation, Mat3, Quat, Vec3};
use crate::parallel::Disjoint;
use crate::world::{Integrator, World};
use glam::{DMat3, DQuat, DVec3};

/// Linear and angular velocity of one awake body: the only data the velocity sweeps touch.
/// Padded to two rows of four floats so four bodies load and transpose into SIMD lanes.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
pub struct Velocity {
    pub v: Vec3,
    pad_v: f32,
    pub w: Vec3,
    pad_w: f32,
}

impl Velocity {
    #[inline]
    pub fn new(v: Vec3, w: Vec3) -> Velocity {
        Velocity {
            v,
            pad_v: 0.0,
            w,
            pad_w: 0.0,
        }
    }

    /// The two rows: `[v.x, v.y, v.z, 0]` and `[w.x, w.y, w.z, 0]`.
    #[inline(always)]
    pub fn rows(&self) -> &[[f32; 4]; 2] {
        // SAFETY: `#[repr(C)]` of four-byte floats with no padding between fields (glam's
        // `Vec3` is three `f32`), 32 bytes in all, 16-byte aligned.
        unsafe { &*(self as *const Velocity as *const [[f32; 4]; 2]) }
    }

    #[inline(always)]
    pub fn rows_mut(&mut self) -> &mut [[f32; 4]; 2] {
        // SAFETY: as `rows`; every bit pattern is a valid float.
        unsafe { &mut *(self as *mut Velocity as *mut [[f32; 4]; 2]) }
    }
}

/// Motion of one awake body since the start of the step, and its inverse mass. Index 0 of
/// every solver array is a shared static dummy with infinite mass that is never written.
#[derive(Clone, Copy, Debug)]
pub struct BodyState {
    pub inv_mass: f32,
    /// The body's locked axes (`body::LOCK_*` bits; 0 for most bodies).
    pub locks: u8,
    /// A body with locked axes: the mean of its inverse inertia's principal values as if
    /// nothing were locked (turn-invariant), the size against which joints judge how much of
    /// a row the locks leave free (`joints::rows::Spd`). Zero otherwise.
    pub free_inv_i: f32,
    /// As rows of four floats, so that lanes of bodies load with transposes: translation
    /// since the start of the step, rotation since the start of the step as a quaternion
    /// (x, y, z, w), the columns of the world inverse inertia, and the rotation since the
    /// start of the step as a rotation vector.
    pub rows: [[f32; 4]; 6],
}

impl BodyState {
    pub const STATIC: BodyState = BodyState {
        inv_mass: 0.0,
        locks: 0,
        free_inv_i: 0.0,
        rows: [[0.0; 4], [0.0, 0.0, 0.0, 1.0], [0.0; 4], [0.0; 4], [0.0; 4], [0.0; 4]],
    };

    fn new(inv_mass: f32, inv_i: Mat3, locks: u8) -> BodyState {
        let mut s = BodyState {
            inv_mass,
            locks,
            ..BodyState::STATIC
        };
        s.set_inv_i(inv_i);
        s
    }

    /// Translation since the start of the step.
    #[inline]
    pub fn dp(&self) -> Vec3 {
        Vec3::from_slice(&self.rows[0][..3])
    }

    /// Rotation since the start of the step.
    #[inline]
    pub fn dq(&self) -> Quat {
        Quat::from_array(self.rows[1])
    }

    /// World inverse inertia.
    #[inline]
    pub fn inv_i(&self) -> Mat3 {
        let c = |r: &[f32; 4]| Vec3::from_slice(&r[..3]);
        Mat3::from_cols(c(&self.rows[2]), c(&self.rows[3]), c(&self.rows[4]))
    }

    #[inline]
    fn set_dp(&mut self, dp: Vec3) {
        self.rows[0] = dp.extend(0.0).to_array();
    }

    #[inline]
    fn set_rotation(&mut self, dq: Quat) {
        // The contact refresh turns the quaternion into a matrix only when it needs one.
        self.rows[1] = dq.to_array();
        // Rotation vector to first order (it only gauges and updates small motions).
        let v = 2.0 * dq.w.signum() * Vec3::new(dq.x, dq.y, dq.z);
        self.rows[5] = v.extend(0.0).to_array();
    }

    #[inline]
    fn set_inv_i(&mut self, m: Mat3) {
        for (row, col) in self.rows[2..5].iter_mut().zip([m.x_axis, m.y_axis, m.z_axis]) {
            *row = col.extend(0.0).to_array();
        }
    }
}

/// How the sub-steps integrate a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// The static dummy: never moves.
    Fixed,
    /// Kinematic: moves at its velocity; no forces.
    Kinematic,
    /// Dynamic with isotropic inertia and no torque: velocities change by the step's constant
    /// acceleration and damping only, so it is integrated in lanes (`integrate_wide`).
    Plain,
    /// Dynamic with torque, gyroscopic motion or RK4 (`BodySim`).
    General,
}

/// What the sub-steps read per body, kept small so the integration loops stream through it.
#[derive(Clone, Copy, Debug)]
pub struct Drive {
    /// As rows of four floats (see `integrate_wide`): the velocity change per sub-step from
    /// gravity and applied force (`h·a`) and what damping keeps of the linear velocity per
    /// sub-step, 1 / (1 + h·damping); then what it keeps of the angular velocity.
    pub rows: [[f32; 4]; 2],
    pub path: Path,
}

impl Drive {
    const FIXED: Drive = Drive {
        rows: [[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]],
        path: Path::Fixed,
    };

    #[inline]
    fn dv(&self) -> Vec3 {
        Vec3::from_slice(&self.rows[0][..3])
    }

    #[inline]
    fn lin_keep(&self) -> f32 {
        self.rows[0][3]
    }

    #[inline]
    fn ang_keep(&self) -> f32 {
        self.rows[1][0]
    }
}

/// Per-body data the integrator needs each sub-step, fixed for the step.
#[derive(Clone, Copy, Debug)]
pub struct BodySim {
    pub body: u32,
    /// Acceleration from gravity and applied force (m/s²).
    pub lin_accel: Vec3,
    /// Applied torque (N·m), world frame.
    pub torque: Vec3,
    pub lin_damping: f32,
    pub ang_damping: f32,
    pub q0: Quat,
    /// Inertia in the body frame; used for gyroscopic motion and RK4.
    pub inertia: Mat3,
    pub inv_inertia: Mat3,
    /// Inertia is not isotropic: the gyroscopic term matters.
    pub gyroscopic: bool,
    /// Anisotropic with some (not all) angular axes locked: turns about the free axes with the
    /// reduced inertia, refreshed every sub-step (`integrate_general_positions`).
    pub reduced: bool,
    /// Principal frame (body frame from principal frame) and moments, for the free
    /// rotation of gyroscopic bodies (`free_rotation`).
    pub principal: DQuat,
    pub moments: DVec3,
    pub dynamic: bool,
    /// Integrated by RK4 this step (no constraints touch it).
    pub rk4: bool,
    /// A kinematic body that reaches its target transform this step: placed on it and
    /// stopped after the step.
    pub arrive: bool,
}

#[derive(Default)]
pub struct SolverScratch {
    pub vel: Vec<Velocity>,
    pub states: Vec<BodyState>,
    pub sims: Vec<BodySim>,
    pub drives: Vec<Drive>,
    pub paths: Paths,
    /// This step's contacts (`contact_solver::prepare`).
    pub refs: Vec<ContactRef>,
    /// Per chunk of awake contacts, its refs (joined into `refs`; `contact_solver::prepare`).
    pub ref_chunks: Vec<Vec<ContactRef>>,
    /// Some contact has restitution.
    pub bounces: bool,
    /// Solver indices of the bodies with locked axes this step.
    pub locked: Vec<u32>,
    pub batches: contact_wide::Batches,
    /// The sub-steps as stages for several workers (`solver_stages`).
    pub stages: crate::dynamics::solver_stages::Stages,
}

/// Soft constraint coefficients (Box2D v3 `b2Softness`), for a sub-step of `h` seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Softness {
    pub bias_rate: f32,
    pub mass_scale: f32,
    pub impulse_scale: f32,
}

impl Softness {
    pub fn new(hertz: f32, zeta: f32, h: f32) -> Softness {
        if hertz == 0.0 {
            return Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            };
        }
        let omega = 2.0 * std::f32::consts::PI * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

fn has_gyroscopic_term(i: &Mat3) -> bool {
    let d = Vec3::new(i.x_axis.x, i.y_axis.y, i.z_axis.z);
    let off = i.x_axis.y.abs() + i.x_axis.z.abs() + i.y_axis.z.abs();
    let scale = d.max_element().max(f32::MIN_POSITIVE);
    off > 1e-6 * scale || (d.max_element() - d.min_element()) > 1e-6 * scale
}

/// `principal_axes(i)`, taken from `prev` when it was computed there for the same inertia
/// bit for bit (the same result: `principal_axes` depends on nothing else).
#[inline]
fn cached_principal_axes(i: &Mat3, prev: &BodySim) -> (DQuat, DVec3) {
    let bits = |m: &Mat3| m.to_cols_array().map(f32::to_bits);
    if prev.gyroscopic && bits(&prev.inertia) == bits(i) {
        (prev.principal, prev.moments)
    } else {
        principal_axes(i)
    }
}

/// Principal axes of a symmetric inertia: the rotation `P` (body frame from principal
/// frame) and the principal moments, `I = P diag(m) Pᵀ` (cyclic Jacobi, f64).
fn principal_axes(i: &Mat3) -> (DQuat, DVec3) {
    let m = i.as_dmat3();
    let mut a = [[0.0f64; 3]; 3];
    for (c, col) in [m.x_axis, m.y_axis, m.z_axis].into_iter().enumerate() {
        for r in 0..3 {
            a[r][c] = col[r];
        }
    }
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0f64]];
    for _ in 0..16 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-15 * diag {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            a[p][p] -= t * apq;
            a[q][q] += t * apq;
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            let r = 3 - p - q;
            let (arp, arq) = (a[r][p], a[r][q]);
            a[r][p] = c * arp - s * arq;
            a[p][r] = a[r][p];
            a[r][q] = s * arp + c * arq;
            a[q][r] = a[r][q];
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let col = |k: usize| DVec3::new(v[0][k], v[1][k], v[2][k]);
    let (x, y, mut z) = (col(0), col(1), col(2));
    if x.cross(y).dot(z) < 0.0 {
        z = -z;
    }
    let p = DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize();
    (p, DVec3::new(a[0][0], a[1][1], a[2][2]))
}

/// The free rotation of a body over `h`: attitude `q` (world from principal frame) and
/// angular velocity `w` (world) evolve as a torque-free rigid body with principal moments
/// `m`. Dullweber–Leimkuhler–McLachlan's splitting: five exact turns about the principal
/// axes (x h/2, y h/2, z h, y h/2, x h/2), each turning the attitude one way and the
/// body-frame angular momentum the other. Symplectic and time-reversible, it keeps |L|
/// exactly and the energy to within O(h²) with no drift — also when a torque that depends
/// on the attitude (an off-centre spring) kicks in between, where the former implicit
/// midpoint on Euler's equations with a separate attitude update drifted: a capsule on a
/// spring 3 m off its centre gained half its energy in 10 s.
///
/// Each turn about principal axis `k` by `φ` is written out for that axis (the quaternion
/// `(sin φ/2 · e_k, cos φ/2)` multiplied in, the momentum's two other components rotated
/// back by `φ`) instead of general quaternion products, and `sin`/`cos` of the half angle
/// come from `half_turn`'s series: a third of the instructions of the general form, the
/// same turns to within f64 rounding.
fn free_rotation(q: DQuat, w: DVec3, m: DVec3, h: f64) -> (DQuat, DVec3) {
    let l0 = m * (q.conjugate() * w);
    let mut q = [q.x, q.y, q.z, q.w];
    let mut l = [l0.x, l0.y, l0.z];
    let m_arr = [m.x, m.y, m.z];
    for (k, t) in [(0usize, 0.5 * h), (1, 0.5 * h), (2, h), (1, 0.5 * h), (0, 0.5 * h)] {
        if m_arr[k] <= 0.0 {
            continue;
        }
        let (s, c) = half_turn(0.5 * (t * l[k] / m_arr[k]));
        // The other two axes in cyclic order: (k, i, j) is a right-handed permutation.
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        // q ⊗ (s e_k, c).
        let (qk, qi, qj, qw) = (q[k], q[i], q[j], q[3]);
        q[k] = qw * s + qk * c;
        q[i] = qi * c + qj * s;
        q[j] = qj * c - qi * s;
        q[3] = qw * c - qk * s;
        // The momentum in the body frame turns the other way: by −φ about e_k.
        let (cos, sin) = (c * c - s * s, 2.0 * s * c);
        let (li, lj) = (l[i], l[j]);
        l[i] = cos * li + sin * lj;
        l[j] = cos * lj - sin * li;
    }
    let q = DQuat::from_xyzw(q[0], q[1], q[2], q[3]).normalize();
    let l = DVec3::from_array(l);
    let w = q * DVec3::select(m.cmpgt(DVec3::ZERO), l / m, DVec3::ZERO);
    (q, w)
}

/// `half_turn`'s series: sin x = x + x·x²·S(x²), cos x = 1 + x²·C(x²).
const HALF_TURN_SIN: [f64; 7] = [
    -1.0 / 6.0,
    1.0 / 120.0,
    -1.0 / 5040.0,
    1.0 / 362_880.0,
    -1.0 / 39_916_800.0,
    1.0 / 6_227_020_800.0,
    -1.0 / 1_307_674_368_000.0,
];
const HALF_TURN_COS: [f64; 8] = [
    -1.0 / 2.0,
    1.0 / 24.0,
    -1.0 / 720.0,
    1.0 / 40_320.0,
    -1.0 / 3_628_800.0,
    1.0 / 479_001_600.0,
    -1.0 / 87_178_291_200.0,
    1.0 / 20_922_789_888_000.0,
];

/// `(sin x, cos x)`. Below π/4 (a half turn of one of six sub-steps at 60 Hz: spins up to
/// about 560 rad/s about the axis) by their Taylor series to x¹⁵ and x¹⁶, whose remainders
/// are under 1e-16 relative there: the library's values to within f64 rounding, in far
/// fewer instructions, and the same on every platform. Beyond, the library's.
#[inline]
fn half_turn(x: f64) -> (f64, f64) {
    // NaN takes the library path too.
    if x.abs().partial_cmp(&std::f64::consts::FRAC_PI_4) != Some(std::cmp::Ordering::Less) {
        return x.sin_cos();
    }
    const S: [f64; 7] = HALF_TURN_SIN;
    const C: [f64; 8] = HALF_TURN_COS;
    let x2 = x * x;
    let ps = S.iter().rev().fold(0.0, |acc, &k| acc * x2 + k);
    let pc = C.iter().rev().fold(0.0, |acc, &k| acc * x2 + k);
    (x + x * x2 * ps, 1.0 + x2 * pc)
}

/// Largest velocity change (as a multiple of the speed limit) one sub-step's applied
/// acceleration may make. Any larger change reaches the limit within the sub-step anyway.
const MAX_DRIVE_PER_SUBSTEP: f64 = 4.0;

/// A dynamic body's acceleration (gravity and applied force) and applied torque for the
/// step, computed in f64 and scaled down where one sub-step of them would change the speed
/// by more than [`MAX_DRIVE_PER_SUBSTEP`] times the limit. Any finite force, torque and
/// gravity scale then give finite velocities: in f32 a torque of 3e38 N·m on a light body
/// overflowed to an infinite spin, and the speed cap turned it into NaN.
fn bounded_drive(body: &Body, gravity: Vec3, h: f32, max_v: f32, max_w: f32) -> (Vec3, Vec3) {
    // The usual case in f32, as always computed.
    let a = gravity * body.gravity_scale + body.inv_mass * body.force;
    let limit = MAX_DRIVE_PER_SUBSTEP as f32;
    if a.is_finite()
        && h * a.length() <= limit * max_v
        && (body.inv_inertia_world * body.torque).is_finite()
        && h * (body.inv_inertia_world * body.torque).length() <= limit * max_w
    {
        return (a, body.torque);
    }
    let h = h as f64;
    let a = gravity.as_dvec3() * body.gravity_scale as f64 + body.force.as_dvec3() * body.inv_mass as f64;
    let dv = h * a.length();
    let a = if dv > MAX_DRIVE_PER_SUBSTEP * max_v as f64 {
        a * (MAX_DRIVE_PER_SUBSTEP * max_v as f64 / dv)
    } else {
        a
    };
    let t = body.torque.as_dvec3();
    let dw = h * (body.inv_inertia_world.as_dmat3() * t).length();
    let t = if dw > MAX_DRIVE_PER_SUBSTEP * max_w as f64 {
        t * (MAX_DRIVE_PER_SUBSTEP * max_w as f64 / dw)
    } else {
        t
    };
    (a.as_vec3(), t.as_vec3())
}

/// Builds the solver's body arrays for the awake bodies. Returns nothing; sets
/// `body.solver_index` on each awake body (static bodies use state 0).
pub fn prepare_bodies(world: &mut World, dt: f32, h: f32) {
    let gravity = world.settings.gravity;
    let (max_v, max_w) = (world.settings.max_linear_speed, world.settings.max_angular_speed);
    let scratch = &mut world.solver;
    let n = world.awake_bodies.len();
    let static_sim = BodySim {
        body: u32::MAX,
        lin_accel: Vec3::ZERO,
        torque: Vec3::ZERO,
        lin_damping: 0.0,
        ang_damping: 0.0,
        q0: Quat::IDENTITY,
        inertia: Mat3::ZERO,
        inv_inertia: Mat3::ZERO,
        gyroscopic: false,
        reduced: false,
        principal: DQuat::IDENTITY,
        moments: DVec3::ZERO,
        dynamic: false,
        rk4: false,
        arrive: false,
    };
    // Slot 0 is the static state every static body shares; slots 1..=n, one per awake body,
    // are all written in parallel below. The arrays keep their length from step to step, so
    // only slots new this step are filled first: no serial pass over every slot.
    fit(&mut scratch.states, n + 1, BodyState::STATIC);
    fit(&mut scratch.vel, n + 1, Velocity::default());
    fit(&mut scratch.sims, n + 1, static_sim);
    fit(&mut scratch.drives, n + 1, Drive::FIXED);
    scratch.locked.clear();
    let any_locked = std::sync::atomic::AtomicBool::new(false);
    let World {
        bodies,
        awake_bodies,
        tasks,
        ..
    } = world;
    let bodies = bodies.disjoint();
    let awake_bodies = &*awake_bodies;
    let slots = (
        Disjoint::new(&mut scratch.states[1..]),
        Disjoint::new(&mut scratch.vel[1..]),
        Disjoint::new(&mut scratch.sims[1..]),
        Disjoint::new(&mut scratch.drives[1..]),
    );
    crate::parallel::run(&**tasks, n as u32, BODY_MIN_RANGE, &|start, end, _| {
        let start = start as usize;
        for (j, &bi) in awake_bodies[start..end as usize].iter().enumerate() {
            let k = start + j;
            // SAFETY: the awake list holds each body once; `k` is this task's own slot.
            let (body, state, vel, sim, drive) = unsafe {
                (
                    bodies.at_mut(bi),
                    slots.0.at(k),
                    slots.1.at(k),
                    slots.2.at(k),
                    slots.3.at(k),
                )
            };
            // The slot's last step (`fit` keeps the arrays) may hold this inertia's
            // principal axes already.
            let prev = *sim;
            (*state, *vel, *sim, *drive) = prepare_body(body, bi, k as u32 + 1, gravity, dt, h, (max_v, max_w), &prev);
            if state.locks != 0 {
                any_locked.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        }
    });
    // The bodies with locked axes, in solver order (empty in a world without locks).
    if any_locked.into_inner() {
        for (k, state) in scratch.states.iter().enumerate().skip(1) {
            if state.locks != 0 {
                scratch.locked.push(k as u32);
            }
        }
    }
}

/// `v` at length `len` (truncated, or grown with copies of `first`), with `first` in slot 0.
fn fit<T: Clone>(v: &mut Vec<T>, len: usize, first: T) {
    v.resize(len, first.clone());
    v[0] = first;
}

/// Awake bodies per task, at least, in the per-body stages.
const BODY_MIN_RANGE: u32 = 64;
/// Solver bodies per worker from which the sub-steps run stage by stage even without
/// contact batches: a sub-step's integration stages cost about 100 instructions per body,
/// against a few microseconds per stage to hand blocks out and wait.
const STAGED_BODIES_PER_WORKER: usize = 256;

/// Refreshes one awake body for the step and gives its solver state, velocity, simulation
/// data and drive (`solver_index` is its slot). `prev` is what the slot held in the last
/// step: a gyroscopic body of the same inertia there (bit for bit; usually this body)
/// lends its principal axes, which are a function of the inertia alone, instead of a new
/// Jacobi iteration.
#[allow(clippy::too_many_arguments)]
fn prepare_body(
    body: &mut Body,
    bi: u32,
    solver_index: u32,
    gravity: Vec3,
    dt: f32,
    h: f32,
    (max_v, max_w): (f32, f32),
    prev: &BodySim,
) -> (BodyState, Velocity, BodySim, Drive) {
    body.solver_index = solver_index;
    let dynamic = body.is_dynamic();
    if body.kinematic_stop && body.kinematic_target.is_none() {
        // It reached its target in the last step and was given nothing new: it stays.
        body.v = Vec3::ZERO;
        body.w = Vec3::ZERO;
    }
    body.kinematic_stop = false;
    let arrive = !dynamic && kinematic_target_velocity(body, dt, max_v, max_w);
    body.update_world_inertia();
    let locks = body.locks();
    let mut state = BodyState::new(body.inv_mass, body.inv_inertia_world, locks);
    if locks != 0 {
        let i = &body.inv_inertia_local;
        state.free_inv_i = (i.x_axis.x + i.y_axis.y + i.z_axis.z) / 3.0;
    }
    let vel = Velocity::new(body.v, body.w);
    let (lin_accel, torque) = if dynamic {
        let (a, t) = bounded_drive(body, gravity, h, max_v, max_w);
        (lock_linear(a, locks), t)
    } else {
        (Vec3::ZERO, Vec3::ZERO)
    };
    // A body with a locked angular axis turns only about the free ones: no gyroscopic
    // free rotation (it would carry spin into a locked axis). An anisotropic one keeps the
    // free components of its world angular momentum through each sub-step's turn, with its
    // reduced inverse inertia refreshed (`integrate_general_positions`).
    let gyroscopic = dynamic && locks & 56 == 0 && has_gyroscopic_term(&body.inertia_local);
    let reduced = dynamic && locks & 56 != 0 && locks & 56 != 56 && !body.isotropic;
    let (principal, moments) = if gyroscopic {
        cached_principal_axes(&body.inertia_local, prev)
    } else {
        (DQuat::IDENTITY, DVec3::ZERO)
    };
    let drive = Drive {
        rows: [
            (h * lin_accel).extend(1.0 / (1.0 + h * body.linear_damping)).to_array(),
            [1.0 / (1.0 + h * body.angular_damping), 0.0, 0.0, 0.0],
        ],
        path: match (dynamic, gyroscopic || reduced || torque != Vec3::ZERO) {
            (false, _) => Path::Kinematic,
            (true, false) => Path::Plain,
            (true, true) => Path::General,
        },
    };
    let sim = BodySim {
        body: bi,
        lin_accel,
        torque,
        lin_damping: body.linear_damping,
        ang_damping: body.angular_damping,
        q0: body.xf.q,
        inertia: body.inertia_local,
        inv_inertia: body.inv_inertia_local,
        gyroscopic,
        reduced,
        principal,
        moments,
        dynamic,
        rk4: false,
        arrive,
    };
    (state, vel, sim, drive)
}

/// Sets a kinematic body's velocities to reach its target transform by the end of a step of
/// `dt`, capped at the speed limits. Returns whether it arrives this step (no cap bit): it is
/// then placed exactly on the target and stopped after the step (`finalize_bodies`); else it
/// keeps the target and goes on at the limit in the next steps.
fn kinematic_target_velocity(body: &mut Body, dt: f32, max_v: f32, max_w: f32) -> bool {
    let Some(target) = body.kinematic_target else {
        return false;
    };
    // f64: a jump across the whole f32 range overflows the difference.
    let c_target = target.apply(body.local_center).as_dvec3();
    let v = (c_target - body.center.as_dvec3()) / dt as f64;
    let mut dq = target.q * body.xf.q.conjugate();
    if dq.w < 0.0 {
        dq = -dq;
    }
    let (axis, angle) = dq.to_axis_angle();
    let w = if angle.is_finite() && angle.abs() > 0.0 {
        axis.as_dvec3() * (angle as f64 / dt as f64)
    } else {
        glam::DVec3::ZERO
    };
    let arrive = v.length() <= max_v as f64 && w.length() <= max_w as f64;
    body.v = clamp_length_f64(v, max_v);
    body.w = clamp_length_f64(w, max_w);
    arrive
}

/// Velocity update of a body with torque or gyroscopic motion (RK4 bodies are integrated in
/// `integrate_general_positions`).
pub(crate) fn integrate_general_velocities(
    vel: &mut [Velocity],
    drives: &[Drive],
    states: &[BodyState],
    sims: &[BodySim],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    for &k in bodies {
        let (u, d, s, sim) = (
            &mut vel[k as usize],
            &drives[k as usize],
            &states[k as usize],
            &sims[k as usize],
        );
        if sim.rk4 {
            continue;
        }
        let v = u.v + d.dv();
        let mut w = u.w;
        if sim.torque != Vec3::ZERO {
            w += h * (s.inv_i() * sim.torque);
        }
        // The gyroscopic motion is the free rotation of the position update.
        u.v = clamp_length(v * d.lin_keep(), limits.0);
        u.w = clamp_length(w * d.ang_keep(), limits.1);
    }
}

/// Moves the bodies with torque, gyroscopic motion or RK4 by their velocities, capped at the
/// speed limits before and after (RK4's stiff damping is split out, see `rk4_step`). The
/// gyroscopic ones (most of these: every body with anisotropic inertia) go four at a time
/// through `free_rotation_lanes`, with the same result bit for bit; bodies are independent,
/// so the order does not matter.
pub(crate) fn integrate_general_positions(
    vel: &mut [Velocity],
    states: &mut [BodyState],
    sims: &[BodySim],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    let mut lanes = [0u32; 64];
    let mut n = 0;
    for &k in bodies {
        let sim = &sims[k as usize];
        if sim.gyroscopic && !sim.rk4 {
            lanes[n] = k;
            n += 1;
            if n == lanes.len() {
                free_rotation_lanes::gyroscopic_positions(vel, states, sims, &lanes, h, limits);
                n = 0;
            }
        } else {
            integrate_general_position(&mut vel[k as usize], &mut states[k as usize], sim, h, limits);
        }
    }
    free_rotation_lanes::gyroscopic_positions(vel, states, sims, &lanes[..n], h, limits);
}

/// One body of `integrate_general_positions`.
#[inline]
fn integrate_general_position(u: &mut Velocity, s: &mut BodyState, sim: &BodySim, h: f32, limits: (f32, f32)) {
    // The solve may have pushed past the limits: no body moves faster than them.
    u.v = clamp_length(u.v, limits.0);
    u.w = clamp_length(u.w, limits.1);
    let dq = if sim.rk4 {
        let dq = rk4_step(u, s, sim, h);
        u.v = clamp_length(u.v, limits.0);
        u.w = clamp_length(u.w, limits.1);
        dq
    } else if sim.gyroscopic {
        s.set_dp(s.dp() + h * u.v);
        let q = (s.dq() * sim.q0).as_dquat().normalize() * sim.principal;
        let (q, w) = free_rotation(q, u.w.as_dvec3(), sim.moments, h as f64);
        u.w = clamp_length(w.as_vec3(), limits.1);
        (q * sim.principal.conjugate() * sim.q0.as_dquat().conjugate())
            .normalize()
            .as_quat()
    } else if sim.reduced {
        // Locked angular axes: the constraint torque that keeps them is along them, so the
        // free components of the world angular momentum `I ω` stay through the free turn;
        // the velocity follows from them with the turned body's reduced inertia.
        s.set_dp(s.dp() + h * u.v);
        let momentum = world_inertia(&sim.inertia, s.dq() * sim.q0) * u.w.as_dvec3();
        let dq = integrate_rotation(s.dq(), u.w, h);
        let inv_i = reduced_inverse_inertia(world_inertia(&sim.inertia, dq * sim.q0), s.locks);
        s.set_inv_i(inv_i);
        u.w = clamp_length((inv_i.as_dmat3() * momentum).as_vec3(), limits.1);
        dq
    } else {
        s.set_dp(s.dp() + h * u.v);
        integrate_rotation(s.dq(), u.w, h)
    };
    s.set_rotation(dq);
    if sim.gyroscopic {
        // Anisotropic inertia turns with the body: keep the world inverse current.
        let r = Mat3::from_quat(dq * sim.q0);
        s.set_inv_i(crate::math::turned_inertia(r, sim.inv_inertia));
    }
}

/// The awake bodies by how the sub-steps integrate them (solver indices).
#[derive(Default)]
pub struct Paths {
    /// Dynamic, plain (`Path::Plain`): velocities in lanes.
    pub(crate) plain: Vec<u32>,
    /// Plain or kinematic: positions in lanes.
    pub(crate) moving: Vec<u32>,
    /// `Path::General`: the scalar path.
    pub(crate) general: Vec<u32>,
    /// Kinematic (in `moving` too). Every solver slot but the static dummy's is in `plain`,
    /// `general` or here.
    pub(crate) kinematic: Vec<u32>,
}

impl Paths {
    fn sort(&mut self, drives: &[Drive]) {
        self.plain.clear();
        self.moving.clear();
        self.general.clear();
        self.kinematic.clear();
        for (k, d) in drives.iter().enumerate() {
            let k = k as u32;
            match d.path {
                Path::Fixed => {}
                Path::Kinematic => {
                    self.moving.push(k);
                    self.kinematic.push(k);
                }
                Path::Plain => {
                    self.plain.push(k);
                    self.moving.push(k);
                }
                Path::General => self.general.push(k),
            }
        }
    }
}

/// Classical RK4 over the free rigid-body equations for one sub-step: position, orientation,
/// linear velocity and world angular momentum, with continuous damping. Computed in f64 so
/// rounding does not show as energy drift over long spins. Damping stiffer than one per
/// sub-step (c·h > 1), where explicit RK4 loses accuracy (and past c·h ≈ 2.8 blows up), is
/// taken out of the RK4 stages and applied exactly instead, as e^(−c·h/2) before and after
/// them (Strang splitting).
fn rk4_step(u: &mut Velocity, s: &mut BodyState, sim: &BodySim, h: f32) -> Quat {
    use glam::{DMat3, DQuat, DVec3, DVec4};
    #[derive(Clone, Copy)]
    struct Y {
        p: DVec3,
        q: DVec4,
        v: DVec3,
        l: DVec3,
    }
    let h = h as f64;
    let (inertia, inv_inertia) = (sim.inertia.as_dmat3(), sim.inv_inertia.as_dmat3());
    let (accel, torque) = (sim.lin_accel.as_dvec3(), sim.torque.as_dvec3());
    let (mut lin_d, mut ang_d) = (sim.lin_damping as f64, sim.ang_damping as f64);
    let (mut lin_half, mut ang_half) = (1.0, 1.0);
    if lin_d * h > 1.0 {
        lin_half = (-0.5 * lin_d * h).exp();
        lin_d = 0.0;
    }
    if ang_d * h > 1.0 {
        ang_half = (-0.5 * ang_d * h).exp();
        ang_d = 0.0;
    }
    let omega = |q: DVec4, l: DVec3| -> DVec3 {
        let r = DMat3::from_quat(DQuat::from_vec4(q).normalize());
        r * (inv_inertia * (r.transpose() * l))
    };
    let deriv = |y: &Y| -> Y {
        let w = omega(y.q, y.l);
        let dq = DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * DQuat::from_vec4(y.q) * 0.5;
        Y {
            p: y.v,
            q: DVec4::from(dq),
            v: accel - lin_d * y.v,
            l: torque - ang_d * y.l,
        }
    };
    let add = |y: &Y, k: &Y, t: f64| Y {
        p: y.p + k.p * t,
        q: y.q + k.q * t,
        v: y.v + k.v * t,
        l: y.l + k.l * t,
    };
    let q_start = (s.dq() * sim.q0).as_dquat().normalize();
    let r = DMat3::from_quat(q_start);
    let y0 = Y {
        p: s.dp().as_dvec3(),
        q: DVec4::from(q_start),
        v: u.v.as_dvec3() * lin_half,
        l: r * (inertia * (r.transpose() * u.w.as_dvec3())) * ang_half,
    };
    let k1 = deriv(&y0);
    let k2 = deriv(&add(&y0, &k1, 0.5 * h));
    let k3 = deriv(&add(&y0, &k2, 0.5 * h));
    let k4 = deriv(&add(&y0, &k3, h));
    let y = Y {
        p: y0.p + (k1.p + 2.0 * k2.p + 2.0 * k3.p + k4.p) * (h / 6.0),
        q: y0.q + (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q) * (h / 6.0),
        v: (y0.v + (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v) * (h / 6.0)) * lin_half,
        l: (y0.l + (k1.l + 2.0 * k2.l + 2.0 * k3.l + k4.l) * (h / 6.0)) * ang_half,
    };
    let q = DQuat::from_vec4(y.q).normalize();
    s.set_dp(y.p.as_vec3());
    u.v = y.v.as_vec3();
    u.w = omega(y.q, y.l).as_vec3();
    (q * sim.q0.as_dquat().conjugate()).normalize().as_quat()
}

/// Runs the sub-stepped solve over awake bodies and touching contacts, then writes the new
/// velocities and transforms back to the bodies.
pub fn solve(world: &mut World, dt: f32) {
    let substeps = world.settings.substeps;
    let h = dt / substeps as f32;
    prepare_bodies(world, dt, h);
    contact_solver::prepare(world);
    crate::dynamics::joints::solver::prepare(world, h);

    let settings = world.settings;
    let joints = &mut world.joints.constraints;
    let scratch = &mut world.solver;
    let springs = &mut world.body_springs;
    crate::generators::springs::prepare(springs, &world.bodies, h);
    if settings.integrator == Integrator::Rk4 {
        // Bodies no constraint touches this step are integrated by RK4.
        for (sim, st) in scratch.sims.iter_mut().zip(&scratch.states) {
            // RK4 integrates the full rigid-body equations: locked bodies stay on the
            // sub-stepped path, which keeps their locked axes exact.
            sim.rk4 = sim.dynamic && st.locks == 0;
        }
        for r in &scratch.refs {
            scratch.sims[r.a as usize].rk4 = false;
            scratch.sims[r.b as usize].rk4 = false;
        }
        for s in springs.list.iter() {
            for k in s.solver_indices() {
                scratch.sims[k as usize].rk4 = false;
            }
        }
        crate::dynamics::joints::solver::mark_constrained(joints, &mut scratch.sims);
        for (d, sim) in scratch.drives.iter_mut().zip(&scratch.sims) {
            if sim.rk4 {
                d.path = Path::General;
            }
        }
    }
    let sources = Sources {
        contacts: &world.contacts,
        bodies: &world.bodies,
        generated: &world.generated_contacts,
        states: &scratch.states,
        vel: &scratch.vel,
    };
    scratch.batches.build(&scratch.refs, &sources, &*world.tasks);
    scratch.paths.sort(&scratch.drives);
    let eight = scratch.batches.lanes() == 8;
    let (vel, states, sims, drives) = (&mut scratch.vel, &mut scratch.states, &scratch.sims, &scratch.drives);
    let locked = &scratch.locked;
    let paths = &scratch.paths;
    let batches = &mut scratch.batches;
    let inv_h = 1.0 / h;
    // Contacts stiffer than a quarter of the sub-step rate make Gauss–Seidel unstable.
    let hertz = settings.contact_hertz.min(0.25 / h);
    let soft = contact_wide::SoftSweep {
        soft: Softness::new(hertz, settings.contact_damping_ratio, h),
        soft_static: Softness::new(2.0 * hertz, settings.contact_damping_ratio, h),
        max_push: settings.contact_push_max_velocity,
        slop: settings.linear_slop,
    };
    contact_wide::set_softness(batches, &soft, inv_h);
    let limits = (settings.max_linear_speed, settings.max_angular_speed);
    let runner = &*world.tasks;
    // On several workers, stage by stage (`solver_stages`), when there are enough batches
    // or bodies to share (bodies alone: a pile in free fall, whose six sub-steps of
    // integration and guards would otherwise run on this thread); the results are those
    // of the loop below, bit for bit.
    let workers = runner.worker_count();
    let staged = workers > 1
        && (batches.len() >= (8 * workers) as usize || vel.len() >= STAGED_BODIES_PER_WORKER * workers as usize);
    if staged {
        use crate::dynamics::solver_stages::{substeps as staged, Sweep, Written};
        use crate::parallel::SharedMut;
        let sweep = Sweep {
            substeps,
            iterations: settings.velocity_iterations,
            h,
            inv_h,
            eight,
            limits,
            soft: &soft,
            sims,
            drives,
            paths,
            locked,
        };
        let written = Written {
            vel: SharedMut::new(&mut vel[..]),
            states: SharedMut::new(&mut states[..]),
            batches: SharedMut::new(batches),
            joints: SharedMut::new(joints),
            springs: SharedMut::new(springs),
        };
        staged(runner, &mut scratch.stages, &sweep, &written);
    }
    // Otherwise (and then only) the sub-steps run here.
    // The guard after a sub-step's relax sweep is made by the next sub-step's velocity
    // integration, body by body before it integrates, when nothing comes between them.
    let fused = guard_fuses(springs, locked);
    for sub in 0..if staged { 0 } else { substeps } {
        // Springs between bodies kick first, from the poses at the start of the sub-step.
        crate::generators::springs::apply(springs, vel, states, h);
        if fused && sub > 0 {
            guard_list(vel, limits, &paths.plain);
            guard_list(vel, limits, &paths.general);
            guard_list(vel, limits, &paths.kinematic);
        }
        integrate_wide::velocities(eight, vel, drives, &paths.plain, limits);
        integrate_general_velocities(vel, drives, states, sims, &paths.general, h, limits);
        // Joints warm start first, then each contact batch is refreshed and warm started.
        crate::dynamics::joints::solver::warm_start(joints, vel, states, limits);
        contact_wide::refresh_warm_start(states, vel, batches, sub == 0);
        lock_velocities(vel, states, locked);
        // Soft, biased sweeps push overlap out and damp; positions move; a rigid relax sweep
        // removes the push velocity. Sweeps alternate direction through each manifold's points.
        crate::dynamics::joints::solver::solve(joints, vel, states, h, true);
        crate::dynamics::joints::solver::guard(joints, vel, limits);
        lock_velocities(vel, states, locked);
        for k in 0..settings.velocity_iterations {
            contact_wide::solve(vel, batches, inv_h, (sub + k) % 2 == 0, Some(&soft));
            lock_velocities(vel, states, locked);
        }
        // The guard before the position update, body by body (every slot is in `moving` or
        // `general`).
        guard_list(vel, limits, &paths.moving);
        integrate_wide::positions(eight, vel, states, &paths.moving, h, limits);
        guard_list(vel, limits, &paths.general);
        integrate_general_positions(vel, states, sims, &paths.general, h, limits);
        crate::dynamics::joints::solver::solve(joints, vel, states, h, false);
        crate::dynamics::joints::solver::guard(joints, vel, limits);
        lock_velocities(vel, states, locked);
        contact_wide::solve(vel, batches, inv_h, sub % 2 == 1, None);
        if !fused || sub + 1 == substeps {
            guard_velocities(vel, limits);
        }
        lock_velocities(vel, states, locked);
    }
    if scratch.bounces {
        contact_wide::refresh(states, batches, false);
        contact_wide::restitution(vel, batches, settings.restitution_threshold);
        lock_velocities(vel, &scratch.states, &scratch.locked);
    }
    contact_wide::store(batches, &scratch.refs, &mut world.contacts, &*world.tasks);
    crate::dynamics::joints::solver::store(world, h);
    finalize_bodies(world);
}

/// Sets the locked velocity components of the bodies with locked axes to exactly zero, after
/// each stage that changes velocities. Contacts and joints already leave locked axes alone:
/// angular impulses go through a world inverse inertia with the locked rows and columns zeroed
/// (`body::reduced_inverse_inertia`), linear ones through per-axis inverse masses (zero along locked
/// axes; `contact_wide::linear_term`, `joints::solver::Bodies::ma`), which also give the rows
/// their reduced effective masses. What is left to take out comes from the other stages
/// (springs between bodies) and rounding, and taking it out only removes kinetic energy.
/// Worlds without locks pay an empty loop.
pub(crate) fn lock_velocities(vel: &mut [Velocity], states: &[BodyState], locked: &[u32]) {
    for &k in locked {
        let locks = states[k as usize].locks;
        let u = &mut vel[k as usize];
        *u = Velocity::new(lock_linear(u.v, locks), lock_angular(u.w, locks));
    }
}

/// After the contact sweeps: a body whose inertia is nearly singular in f32 (a 10 km capsule
/// 1 mm thick: its two inertias differ by 1e13) can feed its twist and rolling rows back into
/// its normal rows until the sweep diverges (2e34 N·s, then NaN; API fuzzer seed 17). Such a
/// body (non-finite, or past 100 times the speed limits) is brought back within the limits
/// (NaN components dropped); velocities merely past the limits are left to the integration's
/// caps, as capping inside the solve would bias it. One pass over the bodies per sweep group.
fn guard_velocities(vel: &mut [Velocity], limits: (f32, f32)) {
    let all = 1..vel.len();
    guard_range(vel, limits, all);
}

/// Whether the guard after a sub-step's relax sweep may wait for the next sub-step's velocity
/// integration (`guard_list` there, body by body): nothing comes between them, no body springs
/// kicking velocities and no locked axes zeroing them.
pub(crate) fn guard_fuses(springs: &crate::generators::springs::BodySprings, locked: &[u32]) -> bool {
    springs.list.is_empty() && locked.is_empty()
}

/// `guard_velocities` over the listed solver slots.
#[inline]
pub(crate) fn guard_list(vel: &mut [Velocity], limits: (f32, f32), slots: &[u32]) {
    let (v2, w2) = ((100.0 * limits.0).powi(2), (100.0 * limits.1).powi(2));
    for &k in slots {
        guard_one(&mut vel[k as usize], v2, w2, limits);
    }
}

/// Caps a velocity whose speeds are beyond 100 times the limits (squared: `v2`, `w2`) or not
/// finite at the limits.
#[inline(always)]
fn guard_one(u: &mut Velocity, v2: f32, w2: f32, limits: (f32, f32)) {
    let sane = |x: f32, max: f32| x.is_finite() && x <= max;
    if !sane(u.v.length_squared(), v2) || !sane(u.w.length_squared(), w2) {
        *u = Velocity::new(clamp_length(u.v, limits.0), clamp_length(u.w, limits.1));
    }
}

/// `guard_velocities` over the solver slots of `range` (the static dummy, slot 0, excluded).
pub(crate) fn guard_range(vel: &mut [Velocity], limits: (f32, f32), range: std::ops::Range<usize>) {
    let (v2, w2) = ((100.0 * limits.0).powi(2), (100.0 * limits.1).powi(2));
    for u in vel[range.start.max(1)..range.end].iter_mut() {
        guard_one(u, v2, w2, limits);
    }
}

/// Writes solver results back: transforms, velocities, world inertia; clears forces.
/// A kinematic body that reached its target is placed exactly on it (the sub-steps' rotation
/// update is first order, so a large turn ends a little short); its velocities keep reading
/// as those it moved with, and it stops at the start of the next step unless given a new
/// target (`kinematic_stop`).
/// Velocities are capped at the limits once more: the last relax sweep and restitution
/// come after the last position update.
fn finalize_bodies(world: &mut World) {
    let World {
        solver: scratch,
        bodies,
        settings,
        tasks,
        ..
    } = world;
    let limits = (settings.max_linear_speed, settings.max_angular_speed);
    let bodies = bodies.disjoint();
    let n = scratch.sims.len() - 1;
    let (states, vel, sims) = (&scratch.states[1..], &scratch.vel[1..], &scratch.sims[1..]);
    crate::parallel::run(&**tasks, n as u32, BODY_MIN_RANGE, &|start, end, _| {
        for k in start as usize..end as usize {
            let (s, u, sim) = (&states[k], &vel[k], &sims[k]);
            // SAFETY: each solver slot belongs to a distinct awake body.
            let body = unsafe { bodies.at_mut(sim.body) };
            body.v = clamp_length(u.v, limits.0);
            body.w = clamp_length(u.w, limits.1);
            let q = (s.dq() * sim.q0).normalize();
            body.set_center_rotation(body.center + s.dp(), q);
            if sim.arrive {
                if let Some(target) = body.kinematic_target.take() {
                    body.set_transform(target);
                    body.kinematic_stop = true;
                }
            }
            body.update_world_inertia();
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
    });
}

#[path = "free_rotation_lanes.rs"]
mod free_rotation_lanes;

#[cfg(test)]
#[path = "free_rotation_tests.rs"]
mod free_rotation_tests;
