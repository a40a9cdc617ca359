//! The forces stage: at the start of a step every built-in force generator adds forces and
//! torques to the accumulators of its bodies and particles (cleared after the step).
//!
//! Sleep: gravity, drag and buoyancy leave sleeping objects alone (like world gravity); a
//! spring acts when either end is awake and then wakes the other; an explosion wakes what
//! it pushes.

use super::springs::{BodySpring, Kind, SpringEnd};
use super::{End, Generator, GeneratorDef, Spring};
use crate::dynamics::body::Body;
use crate::math::Vec3;
use crate::particles::Particles;
use crate::pool::{Handle, Pool};
use crate::world::World;
use glam::DVec3;

/// Reused storage of the generator stages.
#[derive(Default)]
pub struct GeneratorScratch {
    pub(crate) order: Vec<Handle>,
    pub(crate) wake: Vec<u32>,
    pub(crate) slots: Vec<u32>,
}

/// Something a force acts on.
#[derive(Clone, Copy, Debug)]
enum Obj {
    /// Body slot index and the attachment point in the body frame.
    Body(u32, Vec3),
    /// Particle dense index.
    Particle(usize),
    /// A fixed world point.
    Fixed(Vec3),
}

/// Where an object is and how it moves at its attachment point.
#[derive(Clone, Copy, Debug)]
struct State {
    point: Vec3,
    velocity: Vec3,
    /// Centre of mass, its velocity, the angular velocity and the arm from the centre to the
    /// point (a particle or a fixed point: the point itself, no spin, no arm).
    center: Vec3,
    center_velocity: Vec3,
    spin: Vec3,
    arm: Vec3,
    /// Can receive forces (a dynamic body or a finite-mass particle).
    movable: bool,
    awake: bool,
    /// kg; infinite when not movable.
    mass: f32,
    /// The most the point's velocity changes per unit impulse in any direction (1/kg): the
    /// largest eigenvalue of `1/m + [r]ᵀ I⁻¹ [r]` at the arm `r` (a particle: `1/m`; not
    /// movable: 0). An off-centre point of a light body moves much more than `1/m` says.
    mobility: f32,
}

impl State {
    /// The point `t` seconds ahead along the current motion, the arm turned with the body.
    fn ahead(&self, t: f32) -> (Vec3, Vec3) {
        let angle = self.spin * t;
        let arm = if angle == Vec3::ZERO {
            self.arm
        } else {
            crate::math::Quat::from_scaled_axis(angle) * self.arm
        };
        (self.center + self.center_velocity * t + arm, arm)
    }
}

/// `State::mobility` of a body point at arm `r`.
fn body_mobility(body: &Body, r: Vec3) -> f32 {
    super::springs::mobility(body.inv_mass, &body.inv_inertia_world, r)
}

struct Ctx<'a> {
    bodies: &'a mut Pool<Body>,
    particles: &'a mut Particles,
    wake: &'a mut Vec<u32>,
    sleep_threshold: f32,
    /// Springs between bodies and world points, for the solver's sub-steps.
    springs: &'a mut Vec<BodySpring>,
}

impl Ctx<'_> {
    fn state(&self, o: Obj) -> State {
        match o {
            Obj::Body(b, local) => {
                let body = self.bodies.at(b);
                let point = body.xf.apply(local);
                let dynamic = body.is_dynamic();
                State {
                    point,
                    velocity: body.point_velocity(point),
                    center: body.center,
                    center_velocity: body.v,
                    spin: body.w,
                    arm: point - body.center,
                    movable: dynamic,
                    awake: body.awake,
                    mass: if dynamic { body.mass } else { f32::INFINITY },
                    mobility: if dynamic {
                        body_mobility(body, point - body.center)
                    } else {
                        0.0
                    },
                }
            }
            Obj::Particle(i) => {
                let p = &*self.particles;
                let movable = p.inv_mass[i] > 0.0;
                State {
                    point: p.pos[i],
                    velocity: p.vel[i],
                    center: p.pos[i],
                    center_velocity: p.vel[i],
                    spin: Vec3::ZERO,
                    arm: Vec3::ZERO,
                    movable,
                    awake: p.is_awake(i),
                    mass: if movable { 1.0 / p.inv_mass[i] } else { f32::INFINITY },
                    mobility: p.inv_mass[i],
                }
            }
            Obj::Fixed(point) => State {
                point,
                velocity: Vec3::ZERO,
                center: point,
                center_velocity: Vec3::ZERO,
                spin: Vec3::ZERO,
                arm: Vec3::ZERO,
                movable: false,
                awake: false,
                mass: f32::INFINITY,
                mobility: 0.0,
            },
        }
    }

    /// Adds force `f` (N, f64: products of large parameters do not overflow before they are
    /// saturated) at world point `p`, waking the object if asleep.
    fn add(&mut self, o: Obj, f: DVec3, p: Vec3) {
        match o {
            Obj::Body(b, _) => {
                let body = self.bodies.at_mut(b);
                if !body.is_dynamic() || !body.enabled {
                    return;
                }
                body.add_force_at(f, p);
                if !body.awake {
                    self.wake.push(b);
                }
            }
            Obj::Particle(i) => {
                if self.particles.inv_mass[i] > 0.0 {
                    if !self.particles.is_awake(i) {
                        self.particles.wake(i, self.sleep_threshold);
                    }
                    let max = DVec3::splat(f32::MAX as f64);
                    let sum = self.particles.force[i].as_dvec3() + f;
                    self.particles.force[i] = sum.clamp(-max, max).as_vec3();
                }
            }
            Obj::Fixed(_) => {}
        }
    }

    /// Wakes a sleeping dynamic body or particle (a spring from an awake object pulls it).
    fn wake_obj(&mut self, o: Obj) {
        match o {
            Obj::Body(b, _) => {
                let body = self.bodies.at(b);
                if body.is_dynamic() && !body.awake {
                    self.wake.push(b);
                }
            }
            Obj::Particle(i) => {
                if self.particles.inv_mass[i] > 0.0 && !self.particles.is_awake(i) {
                    self.particles.wake(i, self.sleep_threshold);
                }
            }
            Obj::Fixed(_) => {}
        }
    }

    /// The end as a sub-step spring end, when it is a body or a world point.
    fn spring_end(o: Obj) -> Option<SpringEnd> {
        match o {
            Obj::Body(b, local) => Some(SpringEnd::Body(b, local)),
            Obj::Fixed(p) => Some(SpringEnd::World(p)),
            Obj::Particle(_) => None,
        }
    }

    fn end(&self, e: &End) -> Option<Obj> {
        match *e {
            End::World(p) => Some(Obj::Fixed(p)),
            End::Body { body, local } => self.bodies.get(body).map(|_| Obj::Body(body.index, local)),
            End::Particle(h) => self.particles.index(h).map(Obj::Particle),
        }
    }
}

/// Look-ahead `β` (in steps) at which spring-like forces are evaluated.
///
/// A force computed at the start of a step and held over `n` semi-implicit sub-steps gives
/// `v' = v + dt a`, `x' = x + dt v + s dt² a` with `s = (n + 1) / 2n`. For a spring
/// `a = -k x` that map has determinant `1 + (1 - s) k dt²`: it gains energy every step
/// (only `s = 1`, one sub-step, is symplectic). Evaluating the spring at the extension
/// predicted `β dt` ahead, `a = -k (x + β dt v)`, gives determinant
/// `1 + (1 - s - β) k dt²`, so `β = 1 - s = (n - 1) / 2n` makes the step area-preserving
/// again (the trace, and so the frequency, is that of symplectic Euler).
pub fn spring_lookahead(substeps: u32) -> f32 {
    let n = substeps.max(1) as f32;
    (n - 1.0) / (2.0 * n)
}

/// Weights `(T, Δ)` of the exact step: the trace and determinant of the one-step transition
/// matrix of `x'' = -k x - c x'` (per unit mass) over `dt`, for any finite `k, c >= 0`.
/// Overdamped, the trace is `e^(-(c - s) dt / 2) + e^(-(c + s) dt / 2)` with
/// `s = sqrt(c² - 4k)`, each exponent formed without cancellation; the product
/// `e^(-c dt / 2) · 2 cosh(s dt / 2)` it replaces was `0 · ∞ = NaN` past `c dt ≈ 1400`.
fn exact_step_invariants(k: f64, c: f64, dt: f32) -> (f64, f64) {
    let dt = dt as f64;
    let disc = c * c - 4.0 * k;
    let trace = if disc < 0.0 {
        2.0 * (-0.5 * c * dt).exp() * (0.5 * (-disc).sqrt() * dt).cos()
    } else {
        let s = disc.sqrt();
        // (c - s) / 2 = 2k / (c + s), exact where s is close to c.
        let slow = if c + s > 0.0 { 2.0 * k / (c + s) } else { 0.0 };
        (-slow * dt).exp() + (-0.5 * (c + s) * dt).exp()
    };
    (trace, (-c * dt).exp())
}

/// Gains `(K, D)` of the stiff spring: an acceleration `-K x - D v`, held constant over a
/// step integrated by semi-implicit Euler in `n` sub-steps, gives a one-step map whose
/// eigenvalues are exactly `exp(λ dt)` of the damped oscillator `x'' = -k x - c x'`: the
/// discrete motion has the continuous frequency and decay, for any stiffness.
///
/// With `a` constant, `v' = v + dt a` and `x' = x + dt v + s dt² a`, `s = (n + 1) / 2n`.
/// Matching the trace `T` and determinant `Δ` of that map gives
/// `K = (1 - T + Δ) / dt²` and `D = (2 - T - s (1 - T + Δ)) / dt`.
///
/// `k` and `c` are per unit mass (stiffness and damping times the ends' mobility) and come
/// in f64: any finite f32 stiffness times the mobility of the lightest particle (1e9 1/kg) or
/// of an off-centre point of a light body overflowed f32 and made the gains NaN. `K` and `D`
/// stay of the order of `1 / dt²` and `1 / dt` whatever the inputs.
pub fn stiff_spring_gains(k: f64, c: f64, dt: f32, substeps: u32) -> (f32, f32) {
    let (t, det) = exact_step_invariants(k, c, dt);
    let n = substeps.max(1) as f64;
    let s = (n + 1.0) / (2.0 * n);
    let dt = dt as f64;
    let kk = (1.0 - t + det) / (dt * dt);
    let dd = (2.0 - t - s * (1.0 - t + det)) / dt;
    (kk as f32, dd as f32)
}

impl World {
    /// Stage 2 of the step: built-in force generators add to the accumulators.
    pub(crate) fn apply_force_generators(&mut self, dt: f32) {
        self.prune_particle_attachments();
        self.body_springs.list.clear();
        if self.generators.is_empty() {
            return;
        }
        let mut scratch = std::mem::take(&mut self.generator_scratch);
        scratch.order.clear();
        scratch.order.extend(self.generators.iter().map(|(h, _)| h));
        scratch.wake.clear();
        let gravity = self.settings.gravity;
        let substeps = self.settings.substeps;
        {
            let World {
                generators,
                bodies,
                particles,
                settings,
                body_springs,
                ..
            } = self;
            let mut ctx = Ctx {
                bodies,
                particles,
                wake: &mut scratch.wake,
                sleep_threshold: settings.sleep_threshold,
                springs: &mut body_springs.list,
            };
            for &h in &scratch.order {
                let g = generators.get_mut(h).expect("live generator");
                if !g.broken {
                    run(g, &mut ctx, &mut scratch.slots, gravity, substeps, dt);
                }
                g.elapsed += dt;
            }
        }
        for k in 0..scratch.wake.len() {
            self.wake_body(scratch.wake[k]);
        }
        self.generator_scratch = scratch;
    }
}

/// Every live attached object, as `Obj`s with the generator's attachment point.
fn for_each_attached(g: &Generator, ctx: &mut Ctx, local: Vec3, mut f: impl FnMut(&mut Ctx, Obj)) {
    for &b in g.bodies.handles() {
        if ctx.bodies.contains(b) {
            f(ctx, Obj::Body(b.index, local));
        }
    }
    for &p in g.particles.handles() {
        if let Some(i) = ctx.particles.index(p) {
            f(ctx, Obj::Particle(i));
        }
    }
}

fn run(g: &Generator, ctx: &mut Ctx, slots: &mut Vec<u32>, gravity: Vec3, substeps: u32, dt: f32) {
    use GeneratorDef as G;
    match g.def {
        G::Gravity { acceleration } => for_each_attached(g, ctx, Vec3::ZERO, |ctx, o| {
            let s = ctx.state(o);
            if s.movable && s.awake {
                ctx.add(o, acceleration.as_dvec3() * s.mass as f64, s.point);
            }
        }),
        G::Drag { k1, k2 } => for_each_attached(g, ctx, Vec3::ZERO, |ctx, o| {
            let s = ctx.state(o);
            let speed = s.velocity.length() as f64;
            if s.movable && s.awake && speed > 0.0 {
                // Held over the step, drag may stop the point within it but never turn it
                // back (an explicit drag with k·dt/m > 2 pumped a body's speed up).
                let stop = speed / (s.mobility as f64 * dt as f64);
                let magnitude = (k1 as f64 * speed + k2 as f64 * speed * speed).min(stop);
                ctx.add(o, -(s.velocity.as_dvec3() / speed) * magnitude, s.point);
            }
        }),
        G::Spring(sp) => spring(g, ctx, &sp, false, spring_lookahead(substeps) * dt, dt),
        G::Bungee(sp) => spring(g, ctx, &sp, true, spring_lookahead(substeps) * dt, dt),
        G::StiffSpring {
            anchor,
            local_point,
            stiffness,
            damping,
        } => {
            let Some(a) = ctx.end(&anchor) else { return };
            for_each_attached(g, ctx, local_point, |ctx, o| {
                let (s, sa) = (ctx.state(o), ctx.state(a));
                if !s.movable || (!s.awake && !sa.awake) || s.mobility <= 0.0 {
                    return;
                }
                if let (Some(end), Some(anchor)) = (Ctx::spring_end(o), Ctx::spring_end(a)) {
                    ctx.wake_obj(o);
                    ctx.springs
                        .push(BodySpring::new(Kind::Stiff, end, anchor, 0.0, stiffness, damping));
                    return;
                }
                // The exact-step gains for the point's mobility: a particle or a point at
                // the centre of mass moves as its mass says; an off-centre point of a light
                // body moves more (the body turns), and gains made for the mass alone
                // overdrove the turn into a spin.
                let m = 1.0 / s.mobility as f64;
                let (kk, dd) = stiff_spring_gains(
                    stiffness as f64 * s.mobility as f64,
                    damping as f64 * s.mobility as f64,
                    dt,
                    substeps,
                );
                let accel =
                    -(kk as f64) * (s.point - sa.point).as_dvec3() - dd as f64 * (s.velocity - sa.velocity).as_dvec3();
                ctx.add(o, accel * m, s.point);
            })
        }
        G::Buoyancy {
            normal,
            surface,
            max_depth,
            volume,
            liquid_density,
            local_point,
        } => {
            let weight = liquid_density as f64 * volume as f64 * gravity.length() as f64;
            // The partly submerged range is a spring: evaluated ahead (`spring_lookahead`).
            let ahead = spring_lookahead(substeps) * dt;
            for_each_attached(g, ctx, local_point, |ctx, o| {
                let s = ctx.state(o);
                if !s.movable || !s.awake {
                    return;
                }
                let (point, _) = s.ahead(ahead);
                let depth = surface - normal.dot(point);
                let fraction = ((depth + max_depth) / (2.0 * max_depth)).clamp(0.0, 1.0);
                if fraction > 0.0 {
                    ctx.add(o, normal.as_dvec3() * (weight * fraction as f64), s.point);
                }
            })
        }
        G::Explosion {
            center,
            blast_radius,
            blast_impulse,
            shock_speed,
            shock_thickness,
            shock_force,
            max_radius,
            affect_all,
        } => {
            let t = g.elapsed;
            let blast = t == 0.0 && blast_radius > 0.0 && blast_impulse > 0.0;
            let shell = shock_speed * t;
            let half = 0.5 * shock_thickness;
            let shock = shock_force > 0.0 && half > 0.0 && shell <= max_radius;
            if !blast && !shock {
                return;
            }
            let push = |ctx: &mut Ctx, o: Obj| {
                let s = ctx.state(o);
                if !s.movable {
                    return;
                }
                let d = s.point - center;
                let dist = d.length();
                let dir = if dist > 1.0e-6 { d / dist } else { Vec3::Y };
                let mut f = 0.0f64;
                if blast && dist < blast_radius {
                    f += blast_impulse as f64 * (1.0 - dist / blast_radius) as f64 / dt as f64;
                }
                let off = (dist - shell).abs();
                if shock && off < half {
                    f += shock_force as f64 * (1.0 - off / half) as f64;
                }
                if f > 0.0 {
                    ctx.add(o, dir.as_dvec3() * f, s.point);
                }
            };
            if affect_all {
                slots.clear();
                slots.extend(ctx.bodies.iter().filter(|(_, b)| b.is_dynamic()).map(|(h, _)| h.index));
                for &b in slots.iter() {
                    let c = ctx.bodies.at(b).local_center;
                    push(ctx, Obj::Body(b, c));
                }
                for i in 0..ctx.particles.len() {
                    push(ctx, Obj::Particle(i));
                }
            } else {
                for &b in g.bodies.handles() {
                    if let Some(body) = ctx.bodies.get(b) {
                        let c = body.local_center;
                        push(ctx, Obj::Body(b.index, c));
                    }
                }
                for &p in g.particles.handles() {
                    if let Some(i) = ctx.particles.index(p) {
                        push(ctx, Obj::Particle(i));
                    }
                }
            }
        }
        // Links are contact generators; external generators are run by the step's driver.
        G::Rod { .. } | G::Cable { .. } | G::ExternalForce { .. } | G::ExternalContact { .. } => {}
    }
}

/// Largest `k · m⁻¹ · dt²` (and `c · m⁻¹ · dt`) a spring acts with, where `m⁻¹` is the sum of
/// its ends' mobilities: past it the spring acts as if it were that stiff (and damped). The
/// look-ahead step is stable up to 4; at 1 (one radian per step) the energy it keeps within
/// a step stays within a quarter of the spring's.
pub const MAX_SPRING_STEP_STIFFNESS: f32 = 1.0;

/// Hooke's law along the spring, evaluated `ahead` seconds ahead (see `spring_lookahead`):
/// both ends where they will be, each body's arm turned with it, so every mode of the
/// bodies — their turning included — sees the look-ahead that keeps the step from adding
/// energy. Evaluated along the line between the ends now, with the arms as they are, the
/// torque of a spring 3 m off a light capsule's centre pumped it to 3,000 rad/s. Stiffness
/// and damping are capped by [`MAX_SPRING_STEP_STIFFNESS`], so any value is stable.
fn spring(g: &Generator, ctx: &mut Ctx, sp: &Spring, bungee: bool, ahead: f32, dt: f32) {
    let Some(other) = ctx.end(&sp.other) else { return };
    for_each_attached(g, ctx, sp.local_point, |ctx, o| {
        let (s, so) = (ctx.state(o), ctx.state(other));
        if !((s.awake && s.movable) || (so.awake && so.movable)) {
            return;
        }
        if let (Some(a), Some(b)) = (Ctx::spring_end(o), Ctx::spring_end(other)) {
            // Bodies and world points: every sub-step, in the solver (`springs.rs`).
            ctx.wake_obj(o);
            ctx.wake_obj(other);
            let kind = if bungee { Kind::Bungee } else { Kind::Spring };
            ctx.springs
                .push(BodySpring::new(kind, a, b, sp.rest_length, sp.stiffness, sp.damping));
            return;
        }
        let ((p, arm), (q, arm_o)) = (s.ahead(ahead), so.ahead(ahead));
        let d = (p - q).as_dvec3();
        let len = d.length();
        if len < 1.0e-9 {
            return;
        }
        let n = d / len;
        let stretch = len - sp.rest_length as f64;
        if bungee && stretch <= 0.0 {
            return;
        }
        let mobility = (s.mobility + so.mobility) as f64;
        let dt = dt as f64;
        let limit = MAX_SPRING_STEP_STIFFNESS as f64 / (mobility * dt);
        let stiffness = (sp.stiffness as f64).min(limit / dt);
        let damping = (sp.damping as f64).min(limit);
        let rate = (s.velocity - so.velocity).as_dvec3().dot(n);
        let mut magnitude = stiffness * stretch + damping * rate;
        if bungee {
            magnitude = magnitude.max(0.0); // pulls only
        }
        // At the arms turned ahead, about the centres now.
        let f = -magnitude * n;
        ctx.add(o, f, s.center + arm);
        ctx.add(other, -f, so.center + arm_o);
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The step map with the gains has the continuous eigenvalues.
    #[test]
    fn stiff_spring_gains_reproduce_the_exact_decay() {
        for &(k, c, dt, n) in &[
            (100.0f32, 1.0f32, 1.0 / 60.0, 4u32),
            (1.0e4, 20.0, 1.0 / 60.0, 1),
            (25.0, 30.0, 0.02, 8),
        ] {
            let (kk, dd) = stiff_spring_gains(k as f64, c as f64, dt, n);
            let s = (n as f32 + 1.0) / (2.0 * n as f32);
            // x' = (1 - s dt² K) x + (dt - s dt² D) v; v' = -dt K x + (1 - dt D) v
            let (a, b) = (1.0 - s * dt * dt * kk, dt - s * dt * dt * dd);
            let (cc, d) = (-dt * kk, 1.0 - dt * dd);
            let det = a * d - b * cc;
            assert!((det as f64 - (-(c as f64) * dt as f64).exp()).abs() < 1e-4, "det {det}");
            let (t, _) = exact_step_invariants(k as f64, c as f64, dt);
            assert!(((a + d) as f64 - t).abs() < 1e-4);
        }
    }
}
