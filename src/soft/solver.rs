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
//! 3. **Collision detection.** The vertices' box, grown by the motion of the step, is
//!    queried in the broad-phase tree (read-only) for shapes, and tested against the
//!    world's planes; each vertex keeps the deepest contact it finds as a plane (normal out
//!    of the shape), found by `crate::collision::narrow_phase::collide` with a sphere of the vertex
//!    radius. Against an awake dynamic body the plane is kept in the body's frame and the
//!    body is coupled.
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
//!    more than 100 %; two passes hang it within 0.2 %), one over the bending springs, the
//!    volume constraint;
//!    attachments of pins to coupled bodies; then tethers (each free vertex stays within its
//!    rest distance of its nearest pins, so a hanging cloth does not stretch under its own
//!    weight). A correction on a coupled body moves it as the position impulse `λ n` at the
//!    arm would (`Δx = λ n / m`, `Δθ = I⁻¹ (r × λ n)`), the vertex the opposite way.
//! 4. **Velocities** `v = (x − x_prev) / h`; coupled bodies add their attachment and tether
//!    corrections divided by `h` (momentum is exchanged exactly). Deformation damping moves
//!    every vertex velocity towards the soft body's rigid motion (centre velocity plus
//!    `I⁻¹ L` about the centre), keeping momentum and angular momentum.
//! 5. **Contacts.** A vertex below its contact plane is projected onto it (against a
//!    coupled body both move, in proportion to their inverse masses; a projection does not
//!    change velocities). If it slid over the surface this sub-step by less than
//!    `friction × depth`, the slide is undone (static friction, Müller et al. §3.5),
//!    positions and velocities alike: velocity friction alone only drags the light vertex
//!    along, and a heavy box crept down any slope of vertices. Then the relative velocity at the contact loses its approaching
//!    normal part (plus restitution) and, with the position-based Coulomb friction of
//!    Müller et al. (XPBD rigid bodies, §3.6), part of its tangential part, by an impulse
//!    `p = Δv / (w_vertex + w_body)` with the body's effective inverse mass at the contact
//!    (`1/m + (r×n)·I⁻¹(r×n)`); the equal and opposite impulse goes to the body's linear
//!    and angular velocity.
//!
//! No allocation in a steady step: every per-vertex array lives in the soft body, the
//! candidate, plane and coupled-body lists in `SoftScratch` with capacity kept.

use super::{SoftBody, VertexContact};
use crate::collision::aabb::Aabb;
use crate::collision::broad_phase::world_plane;
use crate::collision::narrow_phase::collide;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::{Body, NONE};
use crate::hash::IntMap;
use crate::math::{integrate_rotation, Mat3, Quat, Transform, Vec3};
use crate::pool::{Handle, Pool};
use crate::world::World;

/// Scratch of the stage, capacity kept between steps.
#[derive(Default)]
pub struct SoftScratch {
    /// The world's planes this step: (normal, offset, shape slot).
    planes: Vec<(Vec3, f32, u32)>,
    /// Shapes near the soft body being prepared.
    candidates: Vec<u32>,
    /// Bodies to wake after the stage.
    wake: Vec<u32>,
    /// Dynamic bodies the soft bodies act on this step.
    coupled: Vec<Coupled>,
    /// Body slot -> index in `coupled`.
    coupled_index: IntMap<u32, u32>,
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
struct Coupled {
    slot: u32,
    inv_mass: f32,
    inv_i: Mat3,
    /// Pose when the stage began: contacts found against it are kept relative to it.
    c0: Vec3,
    q0: Quat,
    center: Vec3,
    q: Quat,
    v: Vec3,
    w: Vec3,
    /// Velocities the body has already moved with this step (rigid solve, earlier soft
    /// bodies): a soft body's pass moves it by what it changes.
    base_v: Vec3,
    base_w: Vec3,
    /// Pose when the current sub-step began.
    c_prev: Vec3,
    q_prev: Quat,
    /// Corrections of the current sub-step that become velocity (attachments, tethers).
    dx: Vec3,
    dtheta: Vec3,
    /// Gravity integrated in this stage instead of the rigid solve.
    gravity: Vec3,
    /// Its pose was set back to the start of the step: the first soft body acting on it
    /// moves it with its whole velocity.
    rewound: bool,
    /// Soft bodies acting on it this step; each integrates an equal share of `gravity`.
    passes: u32,
    /// The last soft body (position in the live list) counted in `passes`.
    last: u32,
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
    fn inv_mass_at(&self, arm: Vec3, n: Vec3) -> f32 {
        let rn = arm.cross(n);
        self.inv_mass + rn.dot(self.inv_i * rn)
    }

    /// Moves the body as the position impulse `p` at `arm` would; returns the move.
    #[inline]
    fn shift(&mut self, arm: Vec3, p: Vec3) -> (Vec3, Vec3) {
        let dx = p * self.inv_mass;
        let dtheta = self.inv_i * arm.cross(p);
        self.center += dx;
        self.q = turn(self.q, dtheta);
        (dx, dtheta)
    }

    /// Applies the velocity impulse `p` at `arm`.
    #[inline]
    fn push(&mut self, arm: Vec3, p: Vec3) {
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
fn couple(
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

/// Extra distance (m) within which contacts are found before touching.
const MARGIN: f32 = crate::step::SPECULATIVE_DISTANCE;

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
            find_contacts(s, bodies, shapes, broad, &mut sc, dt, k as u32);
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

/// Finds each vertex's deepest contact plane for this step.
#[allow(clippy::too_many_arguments)]
fn find_contacts(
    s: &mut SoftBody,
    bodies: &Pool<Body>,
    shapes: &Pool<Shape>,
    broad: &crate::collision::broad_phase::BroadPhase,
    sc: &mut SoftScratch,
    dt: f32,
    pass: u32,
) {
    for c in s.contacts.iter_mut() {
        c.active = false;
    }
    if !s.def.collide {
        return;
    }
    let r = s.def.vertex_radius;
    let mut bb = Aabb::EMPTY;
    let mut max_speed: f32 = 0.0;
    for (p, v) in s.pos.iter().zip(&s.vel) {
        bb = bb.union(&Aabb::from_center_extents(*p, Vec3::ZERO));
        max_speed = max_speed.max(v.length());
    }
    // Gravity adds at most g·dt of speed over the step.
    let reach = r + MARGIN + (max_speed + 10.0 * dt) * dt;
    let bb = bb.expanded(reach);
    sc.candidates.clear();
    let candidates = &mut sc.candidates;
    broad.tree.query(&bb, |_, si| {
        candidates.push(si);
        true
    });
    candidates.sort_unstable();
    let near_plane = sc
        .planes
        .iter()
        .any(|&(n, d, _)| n.dot(bb.center()) - n.abs().dot(bb.extents()) <= d);
    if sc.candidates.is_empty() && !near_plane {
        return;
    }
    let friction = s.def.friction;
    let restitution = s.def.restitution;
    let sphere = Geometry::Sphere {
        center: Vec3::ZERO,
        radius: r,
    };
    for i in 0..s.pos.len() {
        let x = s.pos[i];
        let mut best = VertexContact::default();
        let mut depth = f32::MAX;
        // Slot of the awake dynamic body of `best`, coupled once the deepest is known.
        let mut dynamic = NONE;
        for &(n, d, si) in &sc.planes {
            let gap = n.dot(x) - d - r;
            if gap < reach && gap < depth {
                let shape = shapes.at(si);
                depth = gap;
                dynamic = NONE;
                best = VertexContact {
                    n,
                    offset: d,
                    friction: (friction * shape.def.static_friction).sqrt(),
                    restitution: restitution.max(shape.def.restitution),
                    active: true,
                    ..Default::default()
                };
            }
        }
        if !sc.candidates.is_empty() {
            let vb = Aabb::from_center_extents(x, Vec3::splat(reach));
            let xf = Transform::new(x, Quat::IDENTITY);
            for &si in sc.candidates.iter() {
                let shape = shapes.at(si);
                if !shape.fat_aabb.overlaps(&vb) {
                    continue;
                }
                let body = bodies.at(shape.body);
                let m = collide(&sphere, &xf, &shape.geometry, &body.xf, reach);
                for mp in m.points() {
                    if mp.separation >= depth {
                        continue;
                    }
                    // `m.normal` points from the vertex into the shape.
                    let n = -m.normal;
                    let surface = x + m.normal * (r + mp.separation);
                    depth = mp.separation;
                    let awake_dynamic = body.is_dynamic() && body.awake;
                    dynamic = if awake_dynamic { shape.body } else { NONE };
                    best = VertexContact {
                        n,
                        offset: n.dot(surface),
                        point: surface,
                        body: if body.body_type == crate::BodyType::Kinematic {
                            shape.body
                        } else {
                            NONE
                        },
                        sleeper: if body.is_dynamic() && !body.awake {
                            shape.body
                        } else {
                            NONE
                        },
                        friction: (friction * shape.def.static_friction).sqrt(),
                        restitution: restitution.max(shape.def.restitution),
                        active: true,
                        ..Default::default()
                    };
                }
            }
        }
        if dynamic != NONE {
            // Kept in the body's frame, relative to its centre, to move with it.
            let k = couple(
                &mut sc.coupled,
                &mut sc.coupled_index,
                bodies,
                dynamic,
                pass,
                &mut s.touching,
            );
            let b = &sc.coupled[k as usize];
            let inv = b.q0.conjugate();
            best.coupled = k;
            best.point = inv * (best.point - b.c0);
            best.n = inv * best.n;
        }
        s.contacts[i] = best;
    }
    // A pinned vertex is held where its pin is; it does not collide (with the body it is
    // pinned to, it would fight the pin).
    for pin in &s.pins {
        s.contacts[pin.vertex as usize].active = false;
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
    let inv_h2 = inv_h * inv_h;
    let g = settings.gravity * s.def.gravity_scale;
    let damp = 1.0 / (1.0 + h * s.def.damping);
    let relax = 1.0 - 1.0 / (1.0 + h * s.def.deformation_damping);
    let max_speed = settings.max_linear_speed;
    let threshold = settings.restitution_threshold;
    let r = s.def.vertex_radius;
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
        for _ in 0..s.def.iterations {
            solve_springs(&mut s.pos, &s.w, &s.edges, s.def.edge_compliance * inv_h2);
        }
        if s.def.bend_compliance.is_finite() {
            solve_springs(&mut s.pos, &s.w, &s.bends, s.def.bend_compliance * inv_h2);
        }
        if s.def.preserve_volume && !s.triangles.is_empty() {
            solve_volume(s, s.def.volume_compliance * inv_h2);
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
        for i in 0..n {
            if s.w[i] == 0.0 {
                continue;
            }
            let v_old = s.old[i];
            let c = s.contacts[i];
            if !c.active {
                continue;
            }
            let w1 = s.w[i];
            let (cn, offset) = if c.coupled != NONE {
                let b = &coupled[c.coupled as usize];
                let cn = b.q * c.n;
                (cn, cn.dot(b.center + b.q * c.point))
            } else {
                (c.n, c.offset)
            };
            let depth = offset + r - cn.dot(s.pos[i]);
            if depth <= 0.0 {
                continue;
            }
            // Projection (shared by inverse mass against a coupled body; no velocity
            // change), then static friction: if the vertex slid over the surface this
            // sub-step by less than `friction × depth`, the slide is undone, positions and
            // velocities alike, so a box rests on a slope of vertices instead of creeping.
            let limit = c.friction * depth;
            let mut stuck = false;
            let (vb, w2, arm) = if c.coupled != NONE {
                let b = &mut coupled[c.coupled as usize];
                let arm = s.pos[i] - b.center;
                let w2 = b.inv_mass_at(arm, cn);
                let lambda = depth / (w1 + w2);
                s.pos[i] += cn * (w1 * lambda);
                b.shift(arm, -cn * lambda);
                let arm = s.pos[i] - b.center;
                // Where the body's point under the vertex was when the sub-step began.
                let was = b.c_prev + b.q_prev * (b.q.conjugate() * arm);
                // The vertex's slide relative to that point.
                let slide = was - s.prev[i];
                let slide = slide - cn * cn.dot(slide);
                let l = slide.length();
                if l > 0.0 && l < limit {
                    let t = slide / l;
                    let p = slide / (w1 + b.inv_mass_at(arm, t));
                    s.pos[i] -= p * w1;
                    s.vel[i] -= p * (w1 * inv_h);
                    b.shift(arm, p);
                    b.push(arm, p * inv_h);
                    stuck = true;
                }
                let arm = s.pos[i] - b.center;
                (b.v + b.w.cross(arm), w2, arm)
            } else {
                s.pos[i] += cn * depth;
                let vb = if c.body != NONE {
                    bodies.at(c.body).point_velocity(s.pos[i])
                } else {
                    Vec3::ZERO
                };
                let slide = s.prev[i] + vb * h - s.pos[i];
                let slide = slide - cn * cn.dot(slide);
                let l = slide.length();
                if l > 0.0 && l < limit {
                    s.pos[i] += slide;
                    s.vel[i] += slide * inv_h;
                    stuck = true;
                }
                (vb, 0.0, Vec3::ZERO)
            };
            let vr = s.vel[i] - vb;
            let vn = cn.dot(vr);
            let vt = vr - cn * vn;
            let lt = vt.length();
            let mut dv = Vec3::ZERO;
            if lt > 0.0 && !stuck {
                // Coulomb: the tangential change is bounded by friction times the normal
                // one (the overlap removed this sub-step, or the approach stopped).
                let normal = (depth * inv_h).max(-vn);
                dv += vt * (c.friction * normal / lt).min(1.0);
            }
            if vn < 0.0 {
                dv += cn * vn;
            }
            let vn_old = cn.dot(v_old - vb);
            if vn_old < -threshold {
                dv += cn * (c.restitution * vn_old);
            }
            let p = dv / (w1 + w2);
            s.vel[i] -= p * w1;
            if c.coupled != NONE {
                coupled[c.coupled as usize].push(arm, p);
            } else if c.sleeper != NONE && vn < -settings.sleep_threshold && !wake.contains(&c.sleeper) {
                wake.push(c.sleeper);
            }
        }
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
        if l < 1.0e-9 {
            continue;
        }
        let corr = d * ((l - e.rest) / (l * (wsum + alpha)));
        pos[a] += w[a] * corr;
        pos[b] -= w[b] * corr;
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
