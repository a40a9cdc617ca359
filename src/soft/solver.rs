//! The soft-body stage of the step (after the particle stage): extended position-based
//! dynamics (XPBD) in sub-steps, after Jolt's soft bodies, with dynamic rigid bodies taking
//! part in the sub-steps as a second body of every contact and pin.
//!
//! Once per step, for every soft body first:
//!
//! 1. **Impulses** the host applied since the last step change the vertex velocities.
//! 2. **Pins.** A pin to the world, to a static or kinematic body or to a sleeping one is
//!    *fixed*: its vertex gets no mass in the solve and is carried to the pin. A pin to an
//!    awake dynamic body *couples* the body (below): the vertex keeps its mass and is held
//!    to the body's point by a two-body attachment.
//! 3. **Collision detection** (`contact.rs`, `face.rs`). The vertices' box, grown by the
//!    motion of the step, is queried in the broad-phase tree (read-only) for shapes, and
//!    tested against the world's planes; each vertex keeps its deepest contact with fixed
//!    geometry and its deepest with an awake dynamic body (the body is then coupled), each
//!    a plane (normal out of the shape) found by `crate::collision::narrow_phase::collide`
//!    with a sphere of the vertex radius within reach of both the vertex's and the
//!    shape's motion over the step. A skin also finds where shapes reach through its faces
//!    between its vertices (box corners and edges, thin capsules).
//!
//! **Coupled bodies.** A dynamic body a soft body touches or is pinned to is copied into
//! the stage: pose, velocities, inverse mass and world inverse inertia. A body that soft
//! bodies acted on in the last step and that touches no rigid shape is *carried*: its
//! gravity is taken out of the rigid solve (`defer_soft_gravity`, stage 2), and here its pose
//! is set back to where it was when the step began and it moves through the soft sub-steps
//! with its velocity, in step with the vertices under it (a box moved a whole step ahead by
//! the rigid solve made its vertices push a step early, which pumped a box bobbing on a
//! ball instead of damping it, and blew up a light body pinned to a cloth). Any other
//! coupled body already moved in the rigid solve and moves here by what the soft body
//! changes (`x += (v − v_before) h`). A body several soft bodies act on gets an equal share
//! of its gravity in each of their passes. After the stage the bodies take their new
//! velocities and poses.
//!
//! Then `substeps` times, with `h = dt / substeps`:
//!
//! 1. **Pressure.** With the enclosed volume `V`, every face pushes its three vertices
//!    along its normal with the impulse `nRT / V · area · h / 3` each (ideal gas,
//!    `P = nRT / V`).
//! 2. **Predict.** `v += g h`, damping `v /= 1 + h·damping`, `x_prev = x`, `x += v h`;
//!    coupled bodies: their share of deferred gravity, then pose. Fixed pins move their
//!    vertex to the pin (a kinematic body's pin along a straight line over the sub-steps).
//! 3. **Constraints** (Gauss–Seidel XPBD, compliance `α / h²`, so stiffness does not depend
//!    on the step): `iterations` passes over the stretch springs (one pass is not enough
//!    on a large mesh: a 64×64 cloth hung by its corners rang ever harder and stretched by
//!    more than 100 %; two passes hang it within 0.5 %), each after the area of an
//!    inextensible skin (below); one pass over the bending springs, the volume constraint;
//!    attachments of pins to coupled bodies; then tethers (each free vertex stays within its
//!    rest distance of its nearest pins, so a hanging cloth does not stretch under its own
//!    weight). A correction on a coupled body moves it as the position impulse `λ n` at the
//!    arm would (`Δx = λ n / m`, `Δθ = I⁻¹ (r × λ n)`), the vertex the opposite way.
//! 4. **Velocities** `v = (x − x_prev) / h`; coupled bodies add their attachment and tether
//!    corrections divided by `h` (momentum is exchanged exactly). Deformation damping moves
//!    every vertex velocity towards the soft body's rigid motion (centre velocity plus
//!    `I⁻¹ L` about the centre), keeping momentum and angular momentum.
//! 5. **Contacts** (`contact.rs`, `face.rs`): faces of a skin against shapes, then each
//!    vertex against its dynamic body and then against fixed geometry, which wins: a
//!    vertex squeezed between the two does not give way into the fixed geometry, the body
//!    does. Projections (shared by inverse mass against a coupled body; they do not
//!    change velocities), static friction that undoes short slides, then the approaching
//!    normal velocity (plus restitution) and Coulomb friction by impulses with the body's
//!    effective inverse mass at the contact (`1/m + (r×n)·I⁻¹(r×n)`).
//!
//! **The skin** (a closed mesh with no inner springs, `SoftBody::skin`). The gas pushes every
//! vertex out each sub-step and the stretch springs must pull it back, but a spring pass
//! barely moves a uniform stretch (each edge pulls its vertices along the surface, only
//! its small inward component shrinks the ball), so with two passes the default ball
//! stood 1.2 % larger than its rest (3.9 % on its worst edge) at nRT 400 J and 15 % on its
//! worst edge at 1,600 J. A skin is a membrane under uniform tension, so
//! before each pass one constraint bounds its total area by the rest area: a single
//! Lagrange multiplier that moves every vertex along its area gradient, which on a sphere
//! is the gas's own push (both go as `w ∇V` and `w ∇A = 2 w ∇V / R`), and removes the
//! uniform stretch in one projection whatever the mesh's resolution. And a skin's stretch
//! springs resist stretching only: a membrane buckles under compression (bending springs
//! give it its shape); a flattened contact patch needs compression, and stretch springs
//! that also resisted it stretched the patch's rim by 1.3 %. The default ball now stays
//! within 0.8 % of its rest edge lengths at nRT 400 J and 0.4 % at 1,600 J, landing and at
//! rest.
//!
//! No allocation in a steady step: every per-vertex array lives in the soft body, the
//! candidate, plane and coupled-body lists in `SoftScratch` with capacity kept.

use super::SoftBody;
use crate::collision::broad_phase::world_plane;
use crate::dynamics::body::Body;
use crate::hash::IntMap;
use crate::math::{integrate_rotation, Mat3, Quat, Vec3};
use crate::pool::{Handle, Pool};
use crate::world::World;

/// Scratch of the stage, capacity kept between steps.
#[derive(Default)]
pub struct SoftScratch {
    /// The world's planes this step: (normal, offset, shape slot).
    pub(super) planes: Vec<(Vec3, f32, u32)>,
    /// Shapes near the soft body being prepared.
    pub(super) candidates: Vec<u32>,
    /// Bodies to wake after the stage.
    wake: Vec<u32>,
    /// Dynamic bodies the soft bodies act on this step.
    pub(super) coupled: Vec<Coupled>,
    /// Body slot -> index in `coupled`.
    pub(super) coupled_index: IntMap<u32, u32>,
    /// Dynamic bodies the soft bodies acted on in the last step.
    carried: Vec<Handle>,
    /// Bodies whose gravity and motion this step's soft stage integrates: slot, gravity,
    /// and the pose (centre, rotation) they had when the step began.
    pub(crate) deferred: Vec<(u32, Vec3, Vec3, Quat)>,
}

/// How a pin holds its vertex this step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PinAt {
    /// The vertex has no mass in the solve and is carried to this point (world space, where
    /// the pin is at the end of the step).
    Fixed(Vec3),
    /// Held to the coupled body `k` at `arm` (body frame, from the centre of mass).
    Body { k: u32, arm: Vec3 },
}

/// A dynamic, awake body the soft bodies act on this step (contacts or pins), copied for
/// the stage and written back after it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Coupled {
    pub(super) slot: u32,
    pub(super) inv_mass: f32,
    pub(super) inv_i: Mat3,
    /// Pose when the stage began: contacts found against it are kept relative to it.
    pub(super) c0: Vec3,
    pub(super) q0: Quat,
    pub(super) center: Vec3,
    pub(super) q: Quat,
    pub(super) v: Vec3,
    pub(super) w: Vec3,
    /// Velocities the body has already moved with this step (rigid solve, earlier soft
    /// bodies): a soft body's pass moves it by what it changes.
    pub(super) base_v: Vec3,
    pub(super) base_w: Vec3,
    /// Pose when the current sub-step began.
    pub(super) c_prev: Vec3,
    pub(super) q_prev: Quat,
    /// Corrections of the current sub-step that become velocity (attachments, tethers).
    pub(super) dx: Vec3,
    pub(super) dtheta: Vec3,
    /// Gravity integrated in this stage instead of the rigid solve.
    pub(super) gravity: Vec3,
    /// Its pose was set back to the start of the step: the first soft body acting on it
    /// moves it with its whole velocity.
    pub(super) rewound: bool,
    /// Soft bodies acting on it this step; each integrates an equal share of `gravity`.
    pub(super) passes: u32,
    /// The last soft body (position in the live list) counted in `passes`.
    pub(super) last: u32,
}

impl Coupled {
    fn new(b: &Body, slot: u32) -> Coupled {
        Coupled {
            slot,
            inv_mass: b.inv_mass,
            inv_i: b.inv_inertia_world,
            c0: b.center,
            q0: b.xf.q,
            center: b.center,
            q: b.xf.q,
            v: b.v,
            w: b.w,
            base_v: b.v,
            base_w: b.w,
            c_prev: b.center,
            q_prev: b.xf.q,
            dx: Vec3::ZERO,
            dtheta: Vec3::ZERO,
            gravity: Vec3::ZERO,
            rewound: false,
            passes: 0,
            last: u32::MAX,
        }
    }

    /// Effective inverse mass at `arm` (world, from the centre) along the unit `n`.
    #[inline]
    pub(super) fn inv_mass_at(&self, arm: Vec3, n: Vec3) -> f32 {
        let rn = arm.cross(n);
        self.inv_mass + rn.dot(self.inv_i * rn)
    }

    /// Moves the body as the position impulse `p` at `arm` would; returns the move.
    #[inline]
    pub(super) fn shift(&mut self, arm: Vec3, p: Vec3) -> (Vec3, Vec3) {
        let dx = p * self.inv_mass;
        let dtheta = self.inv_i * arm.cross(p);
        self.center += dx;
        self.q = turn(self.q, dtheta);
        (dx, dtheta)
    }

    /// Applies the velocity impulse `p` at `arm`.
    #[inline]
    pub(super) fn push(&mut self, arm: Vec3, p: Vec3) {
        self.v += p * self.inv_mass;
        self.w += self.inv_i * arm.cross(p);
    }
}

/// `q` turned by the small rotation vector `dtheta`.
#[inline]
fn turn(q: Quat, dtheta: Vec3) -> Quat {
    let dq = Quat::from_xyzw(dtheta.x, dtheta.y, dtheta.z, 0.0) * q;
    Quat::from_xyzw(q.x + 0.5 * dq.x, q.y + 0.5 * dq.y, q.z + 0.5 * dq.z, q.w + 0.5 * dq.w).normalize()
}

/// The coupled index of body `slot`, added on first use; counts soft body `pass` once
/// and records the body in its `touching` list.
pub(super) fn couple(
    coupled: &mut Vec<Coupled>,
    index: &mut IntMap<u32, u32>,
    bodies: &Pool<Body>,
    slot: u32,
    pass: u32,
    touching: &mut Vec<u32>,
) -> u32 {
    let k = *index.entry(slot).or_insert_with(|| {
        coupled.push(Coupled::new(bodies.at(slot), slot));
        (coupled.len() - 1) as u32
    });
    let c = &mut coupled[k as usize];
    if c.last != pass {
        c.last = pass;
        c.passes += 1;
        touching.push(k);
    }
    k
}

impl World {
    /// Stage 2, after the force generators (and after `defer_coupled_gravity` of the
    /// particle stage): a dynamic body that soft bodies acted on in the last step and that
    /// touches no rigid shape has its gravity taken out of the rigid solve and integrated
    /// in the soft stage, in the sub-steps of the vertices that carry it.
    pub(crate) fn defer_soft_gravity(&mut self) {
        let World {
            soft_bodies,
            bodies,
            contacts,
            particles,
            settings,
            ..
        } = self;
        let s = &mut soft_bodies.scratch;
        s.deferred.clear();
        for &h in &s.carried {
            let Some(b) = bodies.get_mut(h) else { continue };
            if !b.is_dynamic() || !b.awake || b.contacts.iter().any(|&c| contacts.at(c).touching) {
                continue;
            }
            if particles.scratch.deferred.iter().any(|&(slot, _)| slot == h.index) {
                continue;
            }
            let g = settings.gravity * b.gravity_scale;
            b.force -= g * b.mass;
            s.deferred.push((h.index, g, b.center, b.xf.q));
        }
    }

    /// The soft-body stage of the step (see the module documentation).
    pub(crate) fn step_soft_bodies(&mut self, dt: f32) {
        let World {
            soft_bodies,
            bodies,
            shapes,
            broad,
            settings,
            geometry,
            ..
        } = self;
        let mut sc = std::mem::take(&mut soft_bodies.scratch);
        if soft_bodies.live.is_empty() && sc.deferred.is_empty() {
            sc.carried.clear();
            soft_bodies.scratch = sc;
            return;
        }
        sc.wake.clear();
        sc.planes.clear();
        sc.coupled.clear();
        sc.coupled_index.clear();
        for &p in &broad.planes {
            let shape = shapes.at(p);
            let (n, d) = world_plane(&shape.geometry, &bodies.at(shape.body).xf);
            sc.planes.push((n, d, p));
        }
        for &(slot, g, center, q) in &sc.deferred {
            // Back to where it was when the step began: it moves through the soft
            // sub-steps in step with the vertices under it. Moved a step ahead by the rigid
            // solve, its contacts would push a step early, which pumps a box bobbing on a
            // ball instead of damping it.
            let b = bodies.at_mut(slot);
            b.set_center_rotation(center, q);
            b.update_world_inertia();
            let k = sc.coupled.len();
            let mut c = Coupled::new(b, slot);
            c.gravity = g;
            c.rewound = true;
            sc.coupled.push(c);
            sc.coupled_index.insert(slot, k as u32);
        }
        // Every soft body's impulses, pins and contacts first, so a coupled body knows how
        // many soft bodies act on it before any of them moves it.
        for k in 0..soft_bodies.live.len() {
            let s = soft_bodies.pool.at_mut(soft_bodies.live[k]);
            if s.has_impulses {
                for i in 0..s.pos.len() {
                    if s.w[i] > 0.0 {
                        s.vel[i] += s.inv_mass[i] * s.impulses[i];
                    }
                    s.impulses[i] = Vec3::ZERO;
                }
                s.has_impulses = false;
            }
            s.touching.clear();
            prepare_pins(s, bodies, &mut sc, k as u32);
            super::contact::find_contacts(s, bodies, shapes, geometry, broad, &mut sc, dt, k as u32);
        }
        for k in 0..soft_bodies.live.len() {
            let s = soft_bodies.pool.at_mut(soft_bodies.live[k]);
            solve(s, &mut sc.coupled, bodies, settings, &mut sc.wake, dt);
        }
        // Write-back. A body whose gravity was deferred but that no soft body touched this
        // step (it moved away, or its soft body was destroyed) falls by itself.
        sc.carried.clear();
        for c in sc.coupled.iter_mut() {
            let limits = (settings.max_linear_speed, settings.max_angular_speed);
            if c.passes == 0 {
                c.v = crate::math::clamp_length(c.v + c.gravity * dt, limits.0);
                c.center += c.v * dt;
                c.q = integrate_rotation(c.q, c.w, dt);
            }
            let b = bodies.at_mut(c.slot);
            b.set_velocities_capped(c.v, c.w, limits);
            b.set_center_rotation(c.center, c.q.normalize());
            b.update_world_inertia();
            if c.passes > 0 {
                sc.carried.extend(bodies.handle_at(c.slot));
                // Soft bodies act on it: it must not sleep under them (it would stop
                // loading them, they would push back and wake it, again and again).
                sc.wake.push(c.slot);
            }
        }
        let mut wake = std::mem::take(&mut sc.wake);
        for &b in &wake {
            self.wake_body(b);
        }
        wake.clear();
        sc.wake = wake;
        self.soft_bodies.scratch = sc;
    }
}

/// Solve masses and pin modes of one soft body for this step (`pass`: its position in the
/// live list); couples the awake dynamic bodies it is pinned to.
fn prepare_pins(s: &mut SoftBody, bodies: &Pool<Body>, sc: &mut SoftScratch, pass: u32) {
    s.pin_at.clear();
    if s.pins.is_empty() {
        return;
    }
    s.w.copy_from_slice(&s.inv_mass);
    for pin in &s.pins {
        let v = pin.vertex as usize;
        let at = if pin.body.is_null() {
            PinAt::Fixed(pin.local)
        } else {
            match bodies.get(pin.body) {
                Some(b) if b.is_dynamic() && b.awake => {
                    let k = couple(
                        &mut sc.coupled,
                        &mut sc.coupled_index,
                        bodies,
                        pin.body.index,
                        pass,
                        &mut s.touching,
                    );
                    PinAt::Body {
                        k,
                        arm: pin.local - b.local_center,
                    }
                }
                Some(b) => {
                    if b.is_dynamic() && !sc.wake.contains(&pin.body.index) {
                        // Asleep: fixed for this step, woken to feel the pull from the next.
                        sc.wake.push(pin.body.index);
                    }
                    PinAt::Fixed(b.xf.apply(pin.local))
                }
                None => PinAt::Fixed(s.pos[v]),
            }
        };
        if let PinAt::Fixed(_) = at {
            s.w[v] = 0.0;
        }
        s.pin_at.push(at);
    }
}

/// The XPBD sub-steps of one soft body.
fn solve(
    s: &mut SoftBody,
    coupled: &mut [Coupled],
    bodies: &Pool<Body>,
    settings: &crate::world::WorldSettings,
    wake: &mut Vec<u32>,
    dt: f32,
) {
    let n_sub = s.def.substeps.max(1);
    let h = dt / n_sub as f32;
    let inv_h = 1.0 / h;
    if !inv_h.is_finite() {
        // A sub-step too short for its inverse to be a float (dt below about 1e-37 s):
        // nothing moves in it.
        return;
    }
    let inv_h2 = inv_h * inv_h;
    // XPBD's time-scaled compliance α / h². Zero stays zero (inextensible) even when h² is
    // so small that 1 / h² overflows (0 · ∞ would make every spring NaN); a positive
    // compliance then becomes infinite, which a spring reads as "no correction".
    let tilde = |alpha: f32| if alpha == 0.0 { 0.0 } else { alpha * inv_h2 };
    let g = settings.gravity * s.def.gravity_scale;
    let damp = 1.0 / (1.0 + h * s.def.damping);
    let relax = 1.0 - 1.0 / (1.0 + h * s.def.deformation_damping);
    let max_speed = settings.max_linear_speed;
    let n = s.pos.len();
    for &k in &s.touching {
        let b = &mut coupled[k as usize];
        (b.base_v, b.base_w) = if b.rewound {
            (Vec3::ZERO, Vec3::ZERO)
        } else {
            (b.v, b.w)
        };
        b.rewound = false;
    }
    for sub in 0..n_sub {
        // 1. Pressure.
        if s.def.pressure > 0.0 && !s.triangles.is_empty() {
            let v = s.volume();
            if v > 1.0e-9 {
                // |(b−a)×(c−a)| is twice the area; a third of the face impulse per vertex.
                let k = s.def.pressure * h / v / 6.0;
                for t in &s.triangles {
                    let [a, b, c] = t.map(|i| s.pos[i as usize]);
                    let j = (b - a).cross(c - a) * k;
                    for &i in t {
                        s.vel[i as usize] += s.w[i as usize] * j;
                    }
                }
            }
        }
        // 2. Predict.
        for i in 0..n {
            s.prev[i] = s.pos[i];
            if s.w[i] > 0.0 {
                let mut v = (s.vel[i] + g * h) * damp;
                let s2 = v.length_squared();
                if s2 > max_speed * max_speed {
                    v *= max_speed / s2.sqrt();
                }
                s.vel[i] = v;
                s.pos[i] += v * h;
            }
        }
        for &k in &s.touching {
            let b = &mut coupled[k as usize];
            b.v += b.gravity * (h / b.passes as f32);
            b.c_prev = b.center;
            b.q_prev = b.q;
            b.center += (b.v - b.base_v) * h;
            b.q = integrate_rotation(b.q, b.w - b.base_w, h);
            b.dx = Vec3::ZERO;
            b.dtheta = Vec3::ZERO;
        }
        let left = (n_sub - sub) as f32;
        for (pin, at) in s.pins.iter().zip(&s.pin_at) {
            if let PinAt::Fixed(t) = *at {
                let x = &mut s.pos[pin.vertex as usize];
                *x += (t - *x) / left;
            }
        }
        // 3. Constraints.
        let skin = s.skin && s.def.edge_compliance == 0.0;
        for _ in 0..s.def.iterations {
            if skin {
                solve_area(s);
            }
            solve_springs(&mut s.pos, &s.w, &s.edges, tilde(s.def.edge_compliance));
        }
        if s.def.bend_compliance.is_finite() {
            solve_springs(&mut s.pos, &s.w, &s.bends, tilde(s.def.bend_compliance));
        }
        if s.def.preserve_volume && !s.triangles.is_empty() {
            solve_volume(s, tilde(s.def.volume_compliance));
        }
        for (pin, at) in s.pins.iter().zip(&s.pin_at) {
            if let PinAt::Body { k, arm } = *at {
                let b = &mut coupled[k as usize];
                let i = pin.vertex as usize;
                let r = b.q * arm;
                let d = s.pos[i] - (b.center + r);
                let l = d.length();
                if l < 1.0e-9 {
                    continue;
                }
                let n = d / l;
                let w1 = s.w[i];
                let lambda = l / (w1 + b.inv_mass_at(r, n));
                s.pos[i] -= n * (w1 * lambda);
                let (dx, dtheta) = b.shift(r, n * lambda);
                b.dx += dx;
                b.dtheta += dtheta;
            }
        }
        for t in &s.tethers {
            let i = t.vertex as usize;
            match s.pin_at[t.pin as usize] {
                PinAt::Fixed(_) => {
                    let a = s.pos[s.pins[t.pin as usize].vertex as usize];
                    let d = s.pos[i] - a;
                    let l2 = d.length_squared();
                    if l2 > t.max * t.max {
                        s.pos[i] = a + d * (t.max / l2.sqrt());
                    }
                }
                PinAt::Body { k, arm } => {
                    let b = &mut coupled[k as usize];
                    let r = b.q * arm;
                    let d = s.pos[i] - (b.center + r);
                    let l = d.length();
                    if l <= t.max {
                        continue;
                    }
                    let n = d / l;
                    let w1 = s.w[i];
                    let lambda = (l - t.max) / (w1 + b.inv_mass_at(r, n));
                    s.pos[i] -= n * (w1 * lambda);
                    let (dx, dtheta) = b.shift(r, n * lambda);
                    b.dx += dx;
                    b.dtheta += dtheta;
                }
            }
        }
        // 4. Velocities.
        for &k in &s.touching {
            let b = &mut coupled[k as usize];
            b.v += b.dx * inv_h;
            b.w += b.dtheta * inv_h;
        }
        for i in 0..n {
            s.old[i] = s.vel[i];
            s.vel[i] = (s.pos[i] - s.prev[i]) * inv_h;
        }
        if relax > 0.0 {
            damp_deformation(s, relax);
        }
        // 5. Contacts.
        super::contact::solve_contacts(
            s,
            &mut super::contact::ContactStep {
                coupled,
                bodies,
                wake,
                h,
                threshold: settings.restitution_threshold,
                sleep_threshold: settings.sleep_threshold,
            },
        );
        // 6. The speed limit, as the prediction applies it: the velocities from the
        // constraints' and contacts' corrections (a vertex pushed out from deep under a plane,
        // or pulled by a tether or a pin to a far body) were written back uncapped
        // (34,000 m/s with a 400 m/s limit, fuzzer seed 2).
        for v in s.vel.iter_mut() {
            *v = crate::math::clamp_length(*v, max_speed);
        }
    }
}

/// Moves every free vertex's velocity the fraction `f` of the way to the soft body's rigid
/// motion (the velocity of its centre of mass plus the angular velocity `I⁻¹ L` about it):
/// deformation is damped, translation and rotation are not (momentum and angular
/// momentum are kept).
fn damp_deformation(s: &mut SoftBody, f: f32) {
    let mut m = 0.0;
    let mut c = Vec3::ZERO;
    let mut p = Vec3::ZERO;
    for i in 0..s.pos.len() {
        if s.w[i] > 0.0 {
            let mi = 1.0 / s.w[i];
            m += mi;
            c += s.pos[i] * mi;
            p += s.vel[i] * mi;
        }
    }
    if m == 0.0 {
        return;
    }
    c /= m;
    let v_cm = p / m;
    let mut l = Vec3::ZERO;
    let mut inertia = Mat3::ZERO;
    for i in 0..s.pos.len() {
        if s.w[i] > 0.0 {
            let mi = 1.0 / s.w[i];
            let r = s.pos[i] - c;
            l += r.cross(s.vel[i]) * mi;
            inertia += (Mat3::from_diagonal(Vec3::splat(r.length_squared())) - outer(r, r)) * mi;
        }
    }
    let det = inertia.determinant();
    let omega = if det.abs() > 1.0e-12 {
        inertia.inverse() * l
    } else {
        Vec3::ZERO
    };
    for i in 0..s.pos.len() {
        if s.w[i] > 0.0 {
            let rigid = v_cm + omega.cross(s.pos[i] - c);
            let v = s.vel[i];
            s.vel[i] = v + (rigid - v) * f;
        }
    }
}

#[inline]
fn outer(a: Vec3, b: Vec3) -> Mat3 {
    Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// One XPBD pass over distance springs with compliance `alpha` (already divided by h²).
fn solve_springs(pos: &mut [Vec3], w: &[f32], springs: &[super::Spring], alpha: f32) {
    for e in springs {
        let (a, b) = (e.a as usize, e.b as usize);
        let wsum = w[a] + w[b];
        if wsum == 0.0 {
            continue;
        }
        let d = pos[b] - pos[a];
        let l = d.length();
        if l < 1.0e-9 || (e.tension_only && l <= e.rest) {
            continue;
        }
        let corr = d * ((l - e.rest) / (l * (wsum + alpha)));
        pos[a] += w[a] * corr;
        pos[b] -= w[b] * corr;
    }
}

/// The skin's total area may not exceed its rest area: one Lagrange multiplier for the
/// whole surface, the uniform tension of an inflated membrane.
fn solve_area(s: &mut SoftBody) {
    for g in s.grad.iter_mut() {
        *g = Vec3::ZERO;
    }
    let mut area2 = 0.0;
    for t in &s.triangles {
        let [a, b, c] = t.map(|i| s.pos[i as usize]);
        let cr = (b - a).cross(c - a);
        let l = cr.length();
        if l < 1.0e-12 {
            continue;
        }
        area2 += l;
        let n = cr / l;
        // dA/da = n × (c − b) / 2, and cyclically.
        s.grad[t[0] as usize] += n.cross(c - b) * 0.5;
        s.grad[t[1] as usize] += n.cross(a - c) * 0.5;
        s.grad[t[2] as usize] += n.cross(b - a) * 0.5;
    }
    let c = 0.5 * area2 - s.rest_area;
    if c <= 0.0 {
        return;
    }
    let mut denom = 0.0;
    for (g, &w) in s.grad.iter().zip(&s.w) {
        denom += w * g.length_squared();
    }
    if denom < 1.0e-12 {
        return;
    }
    let lambda = -c / denom;
    for i in 0..s.pos.len() {
        s.pos[i] += s.w[i] * lambda * s.grad[i];
    }
}

/// One XPBD step of the global volume constraint `V − V0 = 0`.
fn solve_volume(s: &mut SoftBody, alpha: f32) {
    for g in s.grad.iter_mut() {
        *g = Vec3::ZERO;
    }
    let mut v6 = 0.0;
    for t in &s.triangles {
        let [a, b, c] = t.map(|i| s.pos[i as usize]);
        v6 += a.dot(b.cross(c));
        s.grad[t[0] as usize] += b.cross(c);
        s.grad[t[1] as usize] += c.cross(a);
        s.grad[t[2] as usize] += a.cross(b);
    }
    let c = v6 / 6.0 - s.rest_volume;
    let mut denom = alpha;
    for (g, &w) in s.grad.iter_mut().zip(&s.w) {
        *g /= 6.0;
        denom += w * g.length_squared();
    }
    if denom < 1.0e-12 {
        return;
    }
    let lambda = -c / denom;
    for i in 0..s.pos.len() {
        s.pos[i] += s.w[i] * lambda * s.grad[i];
    }
}

// Snapshots keep what one step hands the next: the bodies soft bodies acted on and their
// deferred gravity. Everything else is rewritten by each step before it is read.
crate::snap_struct!(SoftScratch {
    carried,
    deferred;
    skip planes,
    candidates,
    wake,
    coupled,
    coupled_index,
});
