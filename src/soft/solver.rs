//! The soft-body stage of the step (after the particle stage): extended position-based
//! dynamics (XPBD) in sub-steps, after Jolt's soft bodies.
//!
//! Once per step, per soft body:
//!
//! 1. **Impulses** the host applied since the last step change the vertex velocities.
//! 2. **Collision detection.** The vertices' box, grown by the motion of the step, is
//!    queried in the broad-phase tree (read-only) for shapes, and tested against the
//!    world's planes; each vertex keeps the deepest contact it finds as a plane
//!    `n · x = offset` (normal out of the shape) for the whole step, found by
//!    `crate::collision::collide` with a sphere of the vertex radius.
//!
//! Then `substeps` times, with `h = dt / substeps`:
//!
//! 1. **Pressure.** With the enclosed volume `V`, every face pushes its three vertices
//!    along its normal with the impulse `nRT / V · area · h / 3` each (ideal gas,
//!    `P = nRT / V`).
//! 2. **Predict.** `v += g h`, damping `v /= 1 + h·damping`, `x_prev = x`, `x += v h`.
//!    Pinned vertices move to their pin (a body pin follows the body along a straight line
//!    over the sub-steps).
//! 3. **Constraints** (one Gauss–Seidel pass of XPBD, compliance `α / h²`, so stiffness does
//!    not depend on the step): stretch springs, bending springs, the volume constraint,
//!    then tethers (each free vertex stays within its rest distance of its nearest pinned
//!    vertex, so a hanging cloth does not stretch under its own weight).
//! 4. **Velocities** `v = (x − x_prev) / h`, then **contacts**: a vertex below its
//!    contact plane is projected onto it; its velocity relative to the shape loses its
//!    approaching normal part (plus restitution) and, with the position-based Coulomb
//!    friction of Müller et al. (XPBD rigid bodies, §3.6), part of its tangential part.
//!    With an awake dynamic body that change is an impulse `p = Δv / (w_vertex + w_body)`
//!    with the body's effective mass at the contact (`1/m + (r×n)·I⁻¹(r×n)`), the equal and
//!    opposite of which goes to the body's linear and angular velocity: two-way coupling.
//!    The body moves with its new velocity in the next rigid solve.
//!
//! No allocation in a steady step: every per-vertex array lives in the soft body, the
//! candidate and plane lists in `SoftScratch` with capacity kept.

use super::{SoftBody, VertexContact};
use crate::aabb::Aabb;
use crate::body::{Body, NONE};
use crate::broad_phase::world_plane;
use crate::collision::collide;
use crate::math::{Quat, Transform, Vec3};
use crate::shape::Geometry;
use crate::world::World;

/// Scratch of the stage, capacity kept between steps.
#[derive(Default)]
pub struct SoftScratch {
    /// The world's planes this step: (normal, offset, shape slot).
    planes: Vec<(Vec3, f32, u32)>,
    /// Shapes near the soft body being solved.
    candidates: Vec<u32>,
    /// Sleeping bodies to wake after the stage.
    wake: Vec<u32>,
}

/// Extra distance (m) within which contacts are found before touching.
const MARGIN: f32 = crate::step::SPECULATIVE_DISTANCE;

impl World {
    /// The soft-body stage of the step (see the module documentation).
    pub(crate) fn step_soft_bodies(&mut self, dt: f32) {
        if self.soft_bodies.live.is_empty() {
            return;
        }
        let World {
            soft_bodies,
            bodies,
            shapes,
            broad,
            settings,
            ..
        } = self;
        let mut scratch = std::mem::take(&mut soft_bodies.scratch);
        scratch.wake.clear();
        scratch.planes.clear();
        for &p in &broad.planes {
            let shape = shapes.at(p);
            let (n, d) = world_plane(&shape.geometry, &bodies.at(shape.body).xf);
            scratch.planes.push((n, d, p));
        }
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
            find_contacts(s, bodies, shapes, broad, &mut scratch, dt);
            solve(s, bodies, settings, &mut scratch.wake, dt);
        }
        let mut wake = std::mem::take(&mut scratch.wake);
        for &b in &wake {
            self.wake_body(b);
        }
        wake.clear();
        scratch.wake = wake;
        self.soft_bodies.scratch = scratch;
    }
}

/// Finds each vertex's deepest contact plane for this step.
fn find_contacts(
    s: &mut SoftBody,
    bodies: &crate::pool::Pool<Body>,
    shapes: &crate::pool::Pool<crate::shape::Shape>,
    broad: &crate::broad_phase::BroadPhase,
    scratch: &mut SoftScratch,
    dt: f32,
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
    scratch.candidates.clear();
    let candidates = &mut scratch.candidates;
    broad.tree.query(&bb, |_, si| {
        candidates.push(si);
        true
    });
    candidates.sort_unstable();
    let near_plane = scratch
        .planes
        .iter()
        .any(|&(n, d, _)| n.dot(bb.center()) - n.abs().dot(bb.extents()) <= d);
    if candidates.is_empty() && !near_plane {
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
        for &(n, d, si) in &scratch.planes {
            let gap = n.dot(x) - d - r;
            if gap < reach && gap < depth {
                let shape = shapes.at(si);
                depth = gap;
                best = VertexContact {
                    n,
                    offset: d,
                    body: NONE,
                    sleeper: NONE,
                    friction: (friction * shape.def.static_friction).sqrt(),
                    restitution: restitution.max(shape.def.restitution),
                    active: true,
                };
            }
        }
        if !candidates.is_empty() {
            let vb = Aabb::from_center_extents(x, Vec3::splat(reach));
            let xf = Transform::new(x, Quat::IDENTITY);
            for &si in candidates.iter() {
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
                    let dynamic = body.is_dynamic();
                    best = VertexContact {
                        n,
                        offset: n.dot(surface),
                        body: if dynamic && body.awake || body.body_type == crate::BodyType::Kinematic {
                            shape.body
                        } else {
                            NONE
                        },
                        sleeper: if dynamic && !body.awake { shape.body } else { NONE },
                        friction: (friction * shape.def.static_friction).sqrt(),
                        restitution: restitution.max(shape.def.restitution),
                        active: true,
                    };
                }
            }
        }
        s.contacts[i] = best;
    }
}

/// The XPBD sub-steps of one soft body.
fn solve(
    s: &mut SoftBody,
    bodies: &mut crate::pool::Pool<Body>,
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
    let max_speed = settings.max_linear_speed;
    let threshold = settings.restitution_threshold;
    let r = s.def.vertex_radius;
    let n = s.pos.len();
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
        let left = (n_sub - sub) as f32;
        for pin in &s.pins {
            if let Some(t) = pin_target(pin, bodies) {
                let x = &mut s.pos[pin.vertex as usize];
                *x += (t - *x) / left;
            }
        }
        // 3. Constraints.
        solve_springs(&mut s.pos, &s.w, &s.edges, s.def.edge_compliance * inv_h2);
        solve_springs(&mut s.pos, &s.w, &s.bends, s.def.bend_compliance * inv_h2);
        if s.def.preserve_volume && !s.triangles.is_empty() {
            solve_volume(s, s.def.volume_compliance * inv_h2);
        }
        for t in &s.tethers {
            let a = s.pos[t.anchor as usize];
            let d = s.pos[t.vertex as usize] - a;
            let l2 = d.length_squared();
            if l2 > t.max * t.max {
                s.pos[t.vertex as usize] = a + d * (t.max / l2.sqrt());
            }
        }
        // 4. Velocities and contacts.
        for i in 0..n {
            let v_old = s.vel[i];
            s.vel[i] = (s.pos[i] - s.prev[i]) * inv_h;
            if s.w[i] == 0.0 {
                continue;
            }
            let c = s.contacts[i];
            if !c.active {
                continue;
            }
            let depth = c.offset + r - c.n.dot(s.pos[i]);
            if depth <= 0.0 {
                continue;
            }
            s.pos[i] += c.n * depth;
            let (vb, w2, arm) = if c.body != NONE {
                let b = bodies.at(c.body);
                let arm = s.pos[i] - b.center;
                let rn = arm.cross(c.n);
                let w2 = if b.is_dynamic() {
                    b.inv_mass + rn.dot(b.inv_inertia_world * rn)
                } else {
                    0.0
                };
                (b.point_velocity(s.pos[i]), w2, arm)
            } else {
                (Vec3::ZERO, 0.0, Vec3::ZERO)
            };
            let vr = s.vel[i] - vb;
            let vn = c.n.dot(vr);
            let vt = vr - c.n * vn;
            let lt = vt.length();
            let mut dv = Vec3::ZERO;
            if lt > 0.0 {
                dv += vt * (c.friction * depth / (lt * h)).min(1.0);
            }
            if vn < 0.0 {
                dv += c.n * vn;
            }
            let vn_old = c.n.dot(v_old - vb);
            if vn_old < -threshold {
                dv += c.n * (c.restitution * vn_old);
            }
            let w1 = s.w[i];
            let p = dv / (w1 + w2);
            s.vel[i] -= p * w1;
            if w2 > 0.0 {
                let b = bodies.at_mut(c.body);
                b.v += p * b.inv_mass;
                b.w += b.inv_inertia_world * arm.cross(p);
                if sub == 0 && !wake.contains(&c.body) {
                    // Pressed by a soft body: it must not fall asleep on it.
                    wake.push(c.body);
                }
            } else if c.sleeper != NONE && vn < -settings.sleep_threshold && !wake.contains(&c.sleeper) {
                wake.push(c.sleeper);
            }
        }
    }
}

/// Where a pin is at the end of the step (None: its body is gone).
fn pin_target(pin: &super::Pin, bodies: &crate::pool::Pool<Body>) -> Option<Vec3> {
    if pin.body.is_null() {
        Some(pin.local)
    } else {
        bodies.get(pin.body).map(|b| b.xf.apply(pin.local))
    }
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
