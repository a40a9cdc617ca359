//! The sub-stepped solver: body states, velocity and position integration (semi-implicit
//! Euler with an implicit gyroscopic term, or RK4 for unconstrained bodies), and the stage
//! list of a step (after Box2D v3's soft step):
//!
//! prepare contacts → per sub-step { integrate velocities, warm start, solve (with bias),
//! integrate positions, relax (without bias) } → restitution → store impulses.

use crate::body::Body;
use crate::contact_solver::{self, ContactConstraint};
use crate::math::{integrate_rotation, Mat3, Quat, Vec3};
use crate::world::{Integrator, World};

/// Velocity and accumulated motion of one awake body during a step. Index 0 is a shared
/// static dummy with zero velocity and infinite mass.
#[derive(Clone, Copy, Debug)]
pub struct BodyState {
    pub v: Vec3,
    pub w: Vec3,
    /// Translation of the centre of mass since the start of the step.
    pub dp: Vec3,
    /// Rotation since the start of the step.
    pub dq: Quat,
    pub inv_mass: f32,
    pub inv_i: Mat3,
}

impl BodyState {
    pub const STATIC: BodyState = BodyState {
        v: Vec3::ZERO,
        w: Vec3::ZERO,
        dp: Vec3::ZERO,
        dq: Quat::IDENTITY,
        inv_mass: 0.0,
        inv_i: Mat3::ZERO,
    };
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
    pub dynamic: bool,
    /// Integrated by RK4 this step (no constraints touch it).
    pub rk4: bool,
}

#[derive(Default)]
pub struct SolverScratch {
    pub states: Vec<BodyState>,
    pub sims: Vec<BodySim>,
    pub constraints: Vec<ContactConstraint>,
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

#[inline]
fn skew(v: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, v.z, -v.y),
        Vec3::new(-v.z, 0.0, v.x),
        Vec3::new(v.y, -v.x, 0.0),
    )
}

/// One Newton step of the implicit gyroscopic update in the body frame (Catto, GDC 2015):
/// solves `I(ω' − ω) + h ω' × Iω' = 0`. Conserves angular momentum to first order and never
/// adds energy, so a body spun about its intermediate axis tumbles and stays bounded.
#[inline]
pub fn gyroscopic_step(w: Vec3, q: Quat, inertia: &Mat3, h: f32) -> Vec3 {
    let wb = q.conjugate() * w;
    let iw = *inertia * wb;
    let f = h * wb.cross(iw);
    let j = *inertia + h * (skew(wb) * *inertia - skew(iw));
    let det = j.determinant();
    if det.abs() < 1e-20 || !det.is_finite() {
        return w;
    }
    q * (wb - j.inverse() * f)
}

/// Builds the solver's body arrays for the awake bodies. Returns nothing; sets
/// `body.solver_index` on each awake body (static bodies use state 0).
pub fn prepare_bodies(world: &mut World, dt: f32) {
    let gravity = world.settings.gravity;
    let scratch = &mut world.solver;
    scratch.states.clear();
    scratch.sims.clear();
    scratch.states.push(BodyState::STATIC);
    scratch.sims.push(BodySim {
        body: u32::MAX,
        lin_accel: Vec3::ZERO,
        torque: Vec3::ZERO,
        lin_damping: 0.0,
        ang_damping: 0.0,
        q0: Quat::IDENTITY,
        inertia: Mat3::ZERO,
        inv_inertia: Mat3::ZERO,
        gyroscopic: false,
        dynamic: false,
        rk4: false,
    });
    for &bi in &world.awake_bodies {
        let body: &mut Body = world.bodies.at_mut(bi);
        body.solver_index = scratch.states.len() as u32;
        let dynamic = body.is_dynamic();
        if !dynamic {
            if let Some(target) = body.kinematic_target.take() {
                // Velocities that reach the target in one step.
                let c_target = target.apply(body.local_center);
                body.v = (c_target - body.center) / dt;
                let mut dq = target.q * body.xf.q.conjugate();
                if dq.w < 0.0 {
                    dq = -dq;
                }
                let (axis, angle) = dq.to_axis_angle();
                body.w = if angle.is_finite() && angle.abs() > 0.0 {
                    axis * (angle / dt)
                } else {
                    Vec3::ZERO
                };
            }
        }
        body.update_world_inertia();
        scratch.states.push(BodyState {
            v: body.v,
            w: body.w,
            dp: Vec3::ZERO,
            dq: Quat::IDENTITY,
            inv_mass: body.inv_mass,
            inv_i: body.inv_inertia_world,
        });
        scratch.sims.push(BodySim {
            body: bi,
            lin_accel: if dynamic {
                gravity * body.gravity_scale + body.inv_mass * body.force
            } else {
                Vec3::ZERO
            },
            torque: if dynamic { body.torque } else { Vec3::ZERO },
            lin_damping: body.linear_damping,
            ang_damping: body.angular_damping,
            q0: body.xf.q,
            inertia: body.inertia_local,
            inv_inertia: body.inv_inertia_local,
            gyroscopic: dynamic && has_gyroscopic_term(&body.inertia_local),
            dynamic,
            rk4: false,
        });
    }
}

fn integrate_velocities(states: &mut [BodyState], sims: &[BodySim], h: f32, max_speed: f32) {
    for (s, sim) in states.iter_mut().zip(sims).skip(1) {
        if !sim.dynamic || sim.rk4 {
            continue;
        }
        let mut v = s.v + h * sim.lin_accel;
        let mut w = s.w + h * (s.inv_i * sim.torque);
        if sim.gyroscopic {
            w = gyroscopic_step(w, s.dq * sim.q0, &sim.inertia, h);
        }
        v *= 1.0 / (1.0 + h * sim.lin_damping);
        w *= 1.0 / (1.0 + h * sim.ang_damping);
        let speed2 = v.length_squared();
        if speed2 > max_speed * max_speed {
            v *= max_speed / speed2.sqrt();
        }
        s.v = v;
        s.w = w;
    }
}

fn integrate_positions(states: &mut [BodyState], sims: &[BodySim], h: f32) {
    for (s, sim) in states.iter_mut().zip(sims).skip(1) {
        if sim.rk4 {
            rk4_step(s, sim, h);
            continue;
        }
        s.dp += h * s.v;
        s.dq = integrate_rotation(s.dq, s.w, h);
    }
}

/// Classical RK4 over the free rigid-body equations for one sub-step: position, orientation,
/// linear velocity and world angular momentum, with continuous damping.
fn rk4_step(s: &mut BodyState, sim: &BodySim, h: f32) {
    #[derive(Clone, Copy)]
    struct Y {
        p: Vec3,
        q: Quat,
        v: Vec3,
        l: Vec3,
    }
    let omega = |q: Quat, l: Vec3| -> Vec3 {
        let r = Mat3::from_quat(q.normalize());
        r * (sim.inv_inertia * (r.transpose() * l))
    };
    let deriv = |y: &Y| -> Y {
        let w = omega(y.q, y.l);
        let dq = Quat::from_xyzw(w.x, w.y, w.z, 0.0) * y.q * 0.5;
        Y {
            p: y.v,
            q: dq,
            v: sim.lin_accel - sim.lin_damping * y.v,
            l: sim.torque - sim.ang_damping * y.l,
        }
    };
    let add = |y: &Y, k: &Y, t: f32| Y {
        p: y.p + k.p * t,
        q: Quat::from_vec4(Into::<glam::Vec4>::into(y.q) + Into::<glam::Vec4>::into(k.q) * t),
        v: y.v + k.v * t,
        l: y.l + k.l * t,
    };
    let q_start = s.dq * sim.q0;
    let r = Mat3::from_quat(q_start);
    let l0 = r * (sim.inertia * (r.transpose() * s.w));
    let y0 = Y {
        p: s.dp,
        q: q_start,
        v: s.v,
        l: l0,
    };
    let k1 = deriv(&y0);
    let k2 = deriv(&add(&y0, &k1, 0.5 * h));
    let k3 = deriv(&add(&y0, &k2, 0.5 * h));
    let k4 = deriv(&add(&y0, &k3, h));
    let sum = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| (a + 2.0 * b + 2.0 * c + d) * (h / 6.0);
    let p = y0.p + sum(k1.p, k2.p, k3.p, k4.p);
    let v = y0.v + sum(k1.v, k2.v, k3.v, k4.v);
    let l = y0.l + sum(k1.l, k2.l, k3.l, k4.l);
    let qv: glam::Vec4 = Into::<glam::Vec4>::into(y0.q)
        + (Into::<glam::Vec4>::into(k1.q)
            + 2.0 * Into::<glam::Vec4>::into(k2.q)
            + 2.0 * Into::<glam::Vec4>::into(k3.q)
            + Into::<glam::Vec4>::into(k4.q))
            * (h / 6.0);
    let q = Quat::from_vec4(qv).normalize();
    s.dp = p;
    s.v = v;
    s.w = omega(q, l);
    s.dq = (q * sim.q0.conjugate()).normalize();
}

/// Runs the sub-stepped solve over awake bodies and touching contacts, then writes the new
/// velocities and transforms back to the bodies.
pub fn solve(world: &mut World, dt: f32) {
    prepare_bodies(world, dt);
    let substeps = world.settings.substeps;
    let h = dt / substeps as f32;
    contact_solver::prepare(world, h);

    let settings = world.settings;
    let scratch = &mut world.solver;
    if settings.integrator == Integrator::Rk4 {
        // Bodies no constraint touches this step are integrated by RK4.
        for sim in scratch.sims.iter_mut() {
            sim.rk4 = sim.dynamic;
        }
        for c in &scratch.constraints {
            scratch.sims[c.a as usize].rk4 = false;
            scratch.sims[c.b as usize].rk4 = false;
        }
    }
    let states = &mut scratch.states;
    let sims = &scratch.sims;
    let constraints = &mut scratch.constraints;
    let inv_h = 1.0 / h;
    for _ in 0..substeps {
        integrate_velocities(states, sims, h, settings.max_linear_speed);
        contact_solver::warm_start(states, constraints);
        contact_solver::solve(
            states,
            constraints,
            inv_h,
            settings.contact_push_max_velocity,
            settings.linear_slop,
            true,
        );
        integrate_positions(states, sims, h);
        contact_solver::solve(
            states,
            constraints,
            inv_h,
            settings.contact_push_max_velocity,
            settings.linear_slop,
            false,
        );
    }
    contact_solver::apply_restitution(states, constraints, settings.restitution_threshold);
    contact_solver::store_impulses(world);
    finalize_bodies(world);
}

/// Writes solver results back: transforms, velocities, world inertia; clears forces.
fn finalize_bodies(world: &mut World) {
    let scratch = &world.solver;
    for (s, sim) in scratch.states.iter().zip(&scratch.sims).skip(1) {
        let body = world.bodies.at_mut(sim.body);
        body.v = s.v;
        body.w = s.w;
        let q = (s.dq * sim.q0).normalize();
        body.set_center_rotation(body.center + s.dp, q);
        body.update_world_inertia();
        body.force = Vec3::ZERO;
        body.torque = Vec3::ZERO;
    }
}
