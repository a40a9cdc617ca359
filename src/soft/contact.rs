//! Contacts of soft-body vertices with rigid shapes and planes: found once per step, solved
//! in every sub-step of `solver.rs`.
//!
//! **Finding.** Each vertex is a sphere of the vertex radius. Once per step it keeps two
//! contact planes (normal out of the shape), each the deepest of its kind found within
//! reach: one against *fixed* geometry (a world plane, a static, kinematic or sleeping
//! body: something the soft body cannot move) and one against an awake dynamic body, kept
//! in the body's frame so it moves and turns with the body through the sub-steps (and the
//! body is coupled to the stage).
//!
//! **Solving**, per vertex and sub-step, the body first and the fixed geometry last, so
//! fixed geometry wins:
//!
//! 1. Against the dynamic body: the vertex and the body are projected apart in proportion
//!    to their inverse masses (the body's effective inverse mass at the contact,
//!    `1/m + (r×n)·I⁻¹(r×n)`); static friction undoes a slide shorter than
//!    `friction × depth` (Müller et al., XPBD rigid bodies, §3.5: velocity friction alone
//!    drags the light vertex along and a heavy box crept down a slope of vertices); then
//!    the relative velocity loses its approaching normal part (plus restitution) and,
//!    Coulomb-bounded, part of its tangential part, by an impulse shared the same way.
//! 2. Against fixed geometry: the vertex alone is projected out, with the same friction
//!    and velocity rules.
//! 3. **The fixed geometry holds** (shock propagation, one layer deep): a vertex that
//!    touches fixed geometry and a dynamic body at once cannot give way into the fixed
//!    geometry, whatever the mass of the body. After step 2, the overlap and approach the
//!    fixed contact brought back are resolved again with the vertex's inverse mass along
//!    the body's normal reduced to what the fixed surface leaves it (`w (1 − c²)`, `c` the
//!    cosine between the body's push and the fixed normal; zero when pushed straight in:
//!    the body alone moves, as against the ground). A 40 kg box on a 2 kg ball (a vertex
//!    weighs 3 g) thus squeezes the skin against the ground without pushing it through.
//!
//! A projection does not change velocities: the velocity rules see the motion of the
//! sub-step as it was.

use super::solver::{couple, Coupled, SoftScratch};
use super::{SoftBody, VertexContact};
use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::narrow_phase::collide;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::{Body, NONE};
use crate::math::{Quat, Transform, Vec3};
use crate::pool::Pool;

/// Extra distance (m) within which contacts are found before touching.
const MARGIN: f32 = crate::step::SPECULATIVE_DISTANCE;

/// Finds each vertex's deepest contact plane with fixed geometry and with a dynamic body
/// for this step (`pass`: the soft body's position in the live list), then the face
/// contacts of a closed skin (`face.rs`).
#[allow(clippy::too_many_arguments)]
pub(super) fn find_contacts(
    s: &mut SoftBody,
    bodies: &Pool<Body>,
    shapes: &Pool<Shape>,
    geometry: &GeometryStore,
    broad: &crate::collision::broad_phase::BroadPhase,
    sc: &mut SoftScratch,
    dt: f32,
    pass: u32,
) {
    for c in s.contacts.iter_mut().chain(s.body_contacts.iter_mut()) {
        c.active = false;
    }
    s.face_contacts.clear();
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
    // Gravity adds at most g·dt of speed over the step; each shape adds its own speed.
    let reach = r + MARGIN + (max_speed + 10.0 * dt) * dt;
    let bb = bb.expanded(reach);
    sc.candidates.clear();
    let candidates = &mut sc.candidates;
    broad.tree.query(&bb, |_, si| {
        // Sensors never push (events.rs).
        if !shapes.at(si).def.is_sensor {
            candidates.push(si);
        }
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
        let mut fixed = VertexContact::default();
        let mut fixed_depth = f32::MAX;
        let mut moving = VertexContact::default();
        let mut moving_depth = f32::MAX;
        // Slot of the awake dynamic body of `moving`, coupled once the deepest is known.
        let mut dynamic = NONE;
        for &(n, d, si) in &sc.planes {
            let gap = n.dot(x) - d - r;
            if gap < reach && gap < fixed_depth {
                let shape = shapes.at(si);
                fixed_depth = gap;
                fixed = VertexContact {
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
            let xf = Transform::new(x, Quat::IDENTITY);
            for &si in sc.candidates.iter() {
                let shape = shapes.at(si);
                let body = bodies.at(shape.body);
                let reach = reach + closing(body, shape) * dt;
                if !shape
                    .fat_aabb
                    .overlaps(&Aabb::from_center_extents(x, Vec3::splat(reach)))
                {
                    continue;
                }
                let awake_dynamic = body.is_dynamic() && body.awake;
                let m = collide(geometry, &sphere, &xf, &shape.geometry, &body.xf, reach);
                for mp in m.points() {
                    let depth = if awake_dynamic { moving_depth } else { fixed_depth };
                    if mp.separation >= depth {
                        continue;
                    }
                    // `m.normal` points from the vertex into the shape.
                    let n = -m.normal;
                    let surface = x + m.normal * (r + mp.separation);
                    let c = VertexContact {
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
                    if awake_dynamic {
                        moving_depth = mp.separation;
                        moving = c;
                        dynamic = shape.body;
                    } else {
                        fixed_depth = mp.separation;
                        fixed = c;
                    }
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
            moving.coupled = k;
            moving.point = inv * (moving.point - b.c0);
            moving.n = inv * moving.n;
        }
        s.contacts[i] = fixed;
        s.body_contacts[i] = moving;
    }
    // A pinned vertex is held where its pin is; it does not collide (with the body it is
    // pinned to, it would fight the pin).
    for pin in &s.pins {
        s.contacts[pin.vertex as usize].active = false;
        s.body_contacts[pin.vertex as usize].active = false;
    }
    super::face::find_face_contacts(s, bodies, shapes, geometry, sc, reach, dt, pass);
}

/// The fastest a point of `shape` moves (m/s): a contact is found if the shape can reach
/// the vertex within the step, whichever of the two moves.
#[inline]
pub(super) fn closing(body: &Body, shape: &Shape) -> f32 {
    if body.body_type == crate::BodyType::Static {
        0.0
    } else {
        body.v.length() + body.w.length() * shape.extent
    }
}

/// What the contact stage of a sub-step needs besides the soft body.
pub(super) struct ContactStep<'a> {
    pub coupled: &'a mut [Coupled],
    pub bodies: &'a Pool<Body>,
    pub wake: &'a mut Vec<u32>,
    pub h: f32,
    /// Relative speed (m/s) below which contacts do not bounce.
    pub threshold: f32,
    pub sleep_threshold: f32,
}

/// The contacts of every free vertex for one sub-step (see the module documentation).
pub(super) fn solve_contacts(s: &mut SoftBody, cx: &mut ContactStep) {
    let r = s.def.vertex_radius;
    let faces = !s.face_contacts.is_empty();
    if faces {
        super::face::solve_face_contacts(s, cx.coupled, cx.bodies, cx.h);
    }
    for i in 0..s.pos.len() {
        s.held[i] = Vec3::ZERO;
        let w1 = s.w[i];
        if w1 == 0.0 {
            continue;
        }
        let moving = s.body_contacts[i];
        if moving.active {
            body_contact(s, i, &moving, cx, r);
        }
        let fixed = s.contacts[i];
        if fixed.active && fixed_contact(s, i, &fixed, cx, r) {
            s.held[i] = fixed.n;
            if moving.active {
                hold_body(s, i, &moving, cx, r);
            }
        }
    }
    if faces {
        super::face::hold_face_bodies(s, cx.coupled);
        // Holding a face may have moved a vertex that did not touch fixed geometry into
        // it: fixed geometry has the last word.
        for i in 0..s.pos.len() {
            let c = &s.contacts[i];
            if c.active && s.w[i] > 0.0 {
                let depth = c.offset + r - c.n.dot(s.pos[i]);
                if depth > 0.0 {
                    s.pos[i] += c.n * depth;
                }
            }
        }
    }
}

/// Vertex `i` against its dynamic body: both move (module documentation, step 1).
fn body_contact(s: &mut SoftBody, i: usize, c: &VertexContact, cx: &mut ContactStep, r: f32) {
    let (h, inv_h) = (cx.h, 1.0 / cx.h);
    let w1 = s.w[i];
    let b = &mut cx.coupled[c.coupled as usize];
    let cn = b.q * c.n;
    let offset = cn.dot(b.center + b.q * c.point);
    let depth = offset + r - cn.dot(s.pos[i]);
    if depth <= 0.0 {
        return;
    }
    // Projection, then static friction: if the vertex slid over the surface this sub-step
    // by less than `friction × depth`, the slide is undone, positions and velocities alike,
    // so a box rests on a slope of vertices instead of creeping.
    let limit = c.friction * depth;
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
    let mut stuck = false;
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
    let vb = b.v + b.w.cross(arm);
    let p = velocity_change(s, i, c, cn, vb, depth, stuck, h, cx.threshold) / (w1 + w2);
    s.vel[i] -= p * w1;
    b.push(arm, p);
}

/// Vertex `i` against fixed geometry: the vertex alone moves (module documentation,
/// step 2). Returns whether it touched.
fn fixed_contact(s: &mut SoftBody, i: usize, c: &VertexContact, cx: &mut ContactStep, r: f32) -> bool {
    let (h, inv_h) = (cx.h, 1.0 / cx.h);
    let depth = c.offset + r - c.n.dot(s.pos[i]);
    if depth <= 0.0 {
        return false;
    }
    let cn = c.n;
    let limit = c.friction * depth;
    s.pos[i] += cn * depth;
    let vb = if c.body != NONE {
        cx.bodies.at(c.body).point_velocity(s.pos[i])
    } else {
        Vec3::ZERO
    };
    let slide = s.prev[i] + vb * h - s.pos[i];
    let slide = slide - cn * cn.dot(slide);
    let l = slide.length();
    let mut stuck = false;
    if l > 0.0 && l < limit {
        s.pos[i] += slide;
        s.vel[i] += slide * inv_h;
        stuck = true;
    }
    let vn = cn.dot(s.vel[i] - vb);
    let dv = velocity_change(s, i, c, cn, vb, depth, stuck, h, cx.threshold);
    s.vel[i] -= dv;
    if c.sleeper != NONE && vn < -cx.sleep_threshold && !cx.wake.contains(&c.sleeper) {
        cx.wake.push(c.sleeper);
    }
    true
}

/// The change of relative velocity a contact asks for (to subtract from the vertex, shared
/// by inverse masses against a body): the approaching normal part, restitution on the
/// approach speed the sub-step began with, and Coulomb friction bounded by friction times
/// the normal change (the overlap removed this sub-step, or the approach stopped).
#[allow(clippy::too_many_arguments)]
#[inline]
fn velocity_change(
    s: &SoftBody,
    i: usize,
    c: &VertexContact,
    cn: Vec3,
    vb: Vec3,
    depth: f32,
    stuck: bool,
    h: f32,
    threshold: f32,
) -> Vec3 {
    let vr = s.vel[i] - vb;
    let vn = cn.dot(vr);
    let vt = vr - cn * vn;
    let lt = vt.length();
    let mut dv = Vec3::ZERO;
    if lt > 0.0 && !stuck {
        let normal = (depth / h).max(-vn);
        dv += vt * (c.friction * normal / lt).min(1.0);
    }
    if vn < 0.0 {
        dv += cn * vn;
    }
    let vn_old = cn.dot(s.old[i] - vb);
    if vn_old < -threshold {
        dv += cn * (c.restitution * vn_old);
    }
    dv
}

/// Speed (m/s) above which a vertex moves away from the fixed surface it touches: the
/// surface then does not hold it against a body's push (it is slowed first).
pub(super) const LEAVING: f32 = 1.0e-3;

/// How a vertex of inverse mass `w` can move when pushed along `push` (unit): its inverse
/// mass along `push` and the direction it moves. A vertex held by fixed geometry (normal
/// `held`, zero if not held; friction `friction`) cannot move into it: it slides along it,
/// with inverse mass `w (1 − c²)` along the push (`c` the cosine between push and normal).
/// Pushed in more steeply than its friction cone (`tan < friction`, a seed squeezed between
/// two near-parallel surfaces) it does not slide at all: it is wedged, and squirting it out
/// sideways at `1 / sin` times the push would put energy in.
#[inline]
pub(super) fn mobility(w: f32, held: Vec3, friction: f32, push: Vec3) -> (f32, Vec3) {
    let c = push.dot(held);
    if c < 0.0 {
        let s2 = 1.0 - c * c;
        if s2 <= friction * friction * c * c {
            (0.0, Vec3::ZERO)
        } else {
            (w * s2, push - held * c)
        }
    } else {
        (w, push)
    }
}

/// Vertex `i` is held by fixed geometry: against its dynamic body it now has only the
/// mobility the fixed geometry leaves it (none when the body pushes it straight in), and
/// the overlap and approach the fixed contact brought back are resolved with that (module
/// documentation, step 3).
fn hold_body(s: &mut SoftBody, i: usize, c: &VertexContact, cx: &mut ContactStep, r: f32) {
    let b = &mut cx.coupled[c.coupled as usize];
    let cn = b.q * c.n;
    let offset = cn.dot(b.center + b.q * c.point);
    let depth = offset + r - cn.dot(s.pos[i]);
    if depth <= 0.0 {
        return;
    }
    let arm = s.pos[i] - b.center;
    let (w1, t) = mobility(s.w[i], s.held[i], s.contacts[i].friction, cn);
    let w = w1 + b.inv_mass_at(arm, cn);
    if w <= 0.0 {
        return;
    }
    let lambda = depth / w;
    s.pos[i] += t * (s.w[i] * lambda);
    b.shift(arm, -cn * lambda);
    let arm = s.pos[i] - b.center;
    // The vertex's own motion towards the body is its own light momentum (step 1 shared
    // it): held, it only stops the body from closing in, it does not throw it.
    let vn = cn.dot(s.vel[i]).max(0.0) - cn.dot(b.v + b.w.cross(arm));
    if vn < 0.0 {
        // A vertex leaving the fixed surface is not held by it: the body may slow it.
        let (w1, t) = if s.vel[i].dot(s.held[i]) > LEAVING {
            (s.w[i], cn)
        } else {
            (w1, t)
        };
        let w = w1 + b.inv_mass_at(arm, cn);
        let j = vn / w;
        s.vel[i] -= t * (s.w[i] * j);
        b.push(arm, cn * j);
    }
}
