//! Contacts of rigid shapes with the faces of a closed skin: what vertex contacts miss.
//!
//! Vertex contacts (`contact.rs`) keep every vertex out of every shape, but a shape can
//! still reach through a skin *between* its vertices: a box corner or edge pokes through
//! a triangle whose three vertices all lie outside the box (a 40 kg box on the default
//! ball had its corners 7 cm inside the skin), and a thin capsule slips between two
//! vertices. So once per step, for every triangle of a closed skin near a shape (other
//! than a plane, whose half-space vertex contacts already cover), the part of the shape
//! deepest along the triangle's inward normal `−n` (a sphere's point, a capsule's segment
//! offset by its radius, up to three faces of a box) is clipped to the triangle's prism
//! (the triangle swept along `n`); its deepest point, if it lies within reach of the
//! triangle's thickened plane (`n · (p − a) < r + reach`) and not at one of the triangle's
//! vertices (a vertex contact holds those), becomes a contact. A shape whose centre lies
//! behind the triangle's plane is not in front of that face (it is behind another part of
//! the skin, or has passed through) and is left to the vertex contacts.
//!
//! In each sub-step, with the triangle's current normal and the point `x_β = Σ βᵢ xᵢ` at
//! the contact's barycentric weights, the constraint `n · (p − x_β) ≥ r` is projected with
//! the generalised inverse mass `Σ βᵢ² wᵢ + w_body` (the triangle moves along `−n`, a
//! dynamic body along `n`), and the approaching normal velocity is removed with a
//! Coulomb-bounded share of the tangential one. After the vertex contacts, a face whose
//! vertices are held by fixed geometry resolves its contact again with their reduced
//! mobility, as a held vertex does (`contact.rs`, step 3).
//!
//! Only closed skins: their outward normals say which side a shape belongs on; an open
//! cloth has no inside.

use super::contact::{mobility, LEAVING};
use super::solver::{couple, Coupled, SoftScratch};
use super::SoftBody;
use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::{Body, NONE};
use crate::math::{Mat3, Vec3};
use crate::pool::Pool;

/// A shape's point held out of a triangle of the skin this step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceContact {
    /// Index of the triangle.
    pub triangle: u32,
    /// Barycentric weights of the triangle's vertices at the contact.
    pub bary: Vec3,
    /// The shape's point: relative to the centre of mass in the body's frame as the stage
    /// found it for a coupled body, world space otherwise.
    pub point: Vec3,
    /// Index of the coupled dynamic body in the stage, else `NONE`.
    pub coupled: u32,
    /// Kinematic body slot whose velocity the point moves with, else `NONE`.
    pub body: u32,
    pub friction: f32,
}

/// Points of a polygon being clipped (a box face has 4, each of 3 clip planes adds at
/// most one).
const MAX_POLY: usize = 8;

#[derive(Clone, Copy)]
struct Poly {
    p: [Vec3; MAX_POLY],
    n: usize,
}

impl Poly {
    fn new(points: &[Vec3]) -> Poly {
        let mut p = [Vec3::ZERO; MAX_POLY];
        p[..points.len()].copy_from_slice(points);
        Poly { p, n: points.len() }
    }

    /// Keeps the part with `m · (x − o) >= 0` (Sutherland–Hodgman; a segment is a
    /// two-point polygon, a point a one-point polygon).
    fn clip(&self, m: Vec3, o: Vec3) -> Poly {
        let mut out = Poly {
            p: [Vec3::ZERO; MAX_POLY],
            n: 0,
        };
        if self.n == 1 {
            if m.dot(self.p[0] - o) >= 0.0 {
                out.p[0] = self.p[0];
                out.n = 1;
            }
            return out;
        }
        if self.n == 2 {
            let (a, b) = (self.p[0], self.p[1]);
            let (da, db) = (m.dot(a - o), m.dot(b - o));
            if da >= 0.0 {
                out.p[out.n] = a;
                out.n += 1;
            }
            if (da >= 0.0) != (db >= 0.0) {
                out.p[out.n] = a + (b - a) * (da / (da - db));
                out.n += 1;
            }
            if db >= 0.0 {
                out.p[out.n] = b;
                out.n += 1;
            }
            return out;
        }
        for k in 0..self.n {
            let a = self.p[k];
            let b = self.p[(k + 1) % self.n];
            let da = m.dot(a - o);
            let db = m.dot(b - o);
            if da >= 0.0 && out.n < MAX_POLY {
                out.p[out.n] = a;
                out.n += 1;
            }
            if (da >= 0.0) != (db >= 0.0) && out.n < MAX_POLY {
                out.p[out.n] = a + (b - a) * (da / (da - db));
                out.n += 1;
            }
        }
        out
    }
}

/// The parts of a shape deepest along `d` (world, unit), each a polygon, and the shape's
/// centre. Planes have none.
fn support(geometry: &Geometry, store: &GeometryStore, body: &Body, d: Vec3, out: &mut [Poly; 3]) -> (usize, Vec3) {
    let xf = &body.xf;
    match *geometry {
        Geometry::Hull { hull, local, scale } => {
            // The deepest vertex, pushed out by the convex radius.
            let h = store.hull_at(hull.index);
            let to_world = xf.mul(&local);
            let v = h.vertices()[h.support_index(to_world.q.conjugate() * d)];
            let c = to_world.apply(h.vertices().iter().copied().sum::<Vec3>() / h.vertices().len() as f32 * scale);
            out[0] = Poly::new(&[to_world.apply(v * scale) + d * (h.radius() * scale)]);
            (1, c)
        }
        // Static and kinematic only: their triangles meet the skin's vertices, which their
        // vertex contacts keep out.
        Geometry::Mesh { .. } | Geometry::Heightfield { .. } => (0, Vec3::ZERO),
        Geometry::Sphere { center, radius } => {
            let c = xf.apply(center);
            out[0] = Poly::new(&[c + d * radius]);
            (1, c)
        }
        Geometry::Capsule { a, b, radius } => {
            let (a, b) = (xf.apply(a), xf.apply(b));
            out[0] = Poly::new(&[a + d * radius, b + d * radius]);
            (1, (a + b) * 0.5)
        }
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => {
            let rot = Mat3::from_quat(xf.q * rotation);
            let centre = xf.apply(center);
            let axes = [rot.x_axis, rot.y_axis, rot.z_axis];
            let local = Vec3::new(axes[0].dot(d), axes[1].dot(d), axes[2].dot(d));
            let h = half_extents.to_array();
            let mut count = 0;
            for i in 0..3 {
                if local[i].abs() < 1.0e-6 {
                    continue;
                }
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let c = centre + axes[i] * (h[i] * local[i].signum());
                let (u, v) = (axes[j] * h[j], axes[k] * h[k]);
                out[count] = Poly::new(&[c - u - v, c + u - v, c + u + v, c - u + v]);
                count += 1;
            }
            (count, centre)
        }
        Geometry::Plane { .. } => (0, Vec3::ZERO),
    }
}

/// Barycentric weights of `p` (in the triangle's plane) in triangle `a b c`, clamped to
/// the triangle.
fn barycentric(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    clamp_weights(weights(p, a, b, c))
}

/// Barycentric weights clamped to the triangle (non-negative, summing to 1).
fn clamp_weights(w: Vec3) -> Vec3 {
    let w = w.max(Vec3::ZERO);
    let sum = w.x + w.y + w.z;
    if sum > 0.0 {
        w / sum
    } else {
        Vec3::new(1.0, 0.0, 0.0)
    }
}

/// Barycentric weights of `p` (in the triangle's plane) in triangle `a b c`, negative
/// outside it.
fn weights(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (v2.dot(v0), v2.dot(v1));
    let den = d00 * d11 - d01 * d01;
    if den.abs() < 1.0e-20 {
        return Vec3::new(1.0, 0.0, 0.0);
    }
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    Vec3::new(1.0 - v - w, v, w)
}

/// Follows face contact `c` to the triangle under the shape's point `p` now: a shape
/// sliding over the skin leaves the triangle it was found over within the step, and would
/// poke through the next one. Walks across the edge the point left by (at most a few
/// triangles), then sets the weights. Returns the triangle's unit normal and the skin's
/// point `x_β`, or `None` for a degenerate triangle.
fn locate(s: &SoftBody, c: &mut FaceContact, p: Vec3) -> Option<(Vec3, Vec3)> {
    for hop in 0..=MAX_HOPS {
        let tri = s.triangles[c.triangle as usize];
        let [a, b, cc] = tri.map(|i| s.pos[i as usize]);
        let cr = (b - a).cross(cc - a);
        let len = cr.length();
        if len < 1.0e-12 {
            return None;
        }
        let n = cr / len;
        let w = weights(p - n * n.dot(p - a), a, b, cc);
        let (j, least) = if w.x <= w.y && w.x <= w.z {
            (0, w.x)
        } else if w.y <= w.z {
            (1, w.y)
        } else {
            (2, w.z)
        };
        if least < 0.0 && hop < MAX_HOPS && !s.neighbours.is_empty() {
            c.triangle = s.neighbours[c.triangle as usize][j];
            continue;
        }
        let beta = clamp_weights(w);
        c.bary = beta;
        return Some((n, a * beta.x + b * beta.y + cc * beta.z));
    }
    None
}

/// Most triangles a face contact walks across in one sub-step.
const MAX_HOPS: usize = 3;

/// Weight above which the contact point is at a vertex of the triangle.
const AT_VERTEX: f32 = 0.99;

/// Spread of depth (m) under which a shape's part lies flat on a triangle.
const FLAT: f32 = 1.0e-3;

/// Finds the face contacts of a closed skin for this step (module documentation); the
/// candidate shapes are those `find_contacts` gathered.
#[allow(clippy::too_many_arguments)]
pub(super) fn find_face_contacts(
    s: &mut SoftBody,
    bodies: &Pool<Body>,
    shapes: &Pool<Shape>,
    geometry: &GeometryStore,
    sc: &mut SoftScratch,
    reach: f32,
    dt: f32,
    pass: u32,
) {
    s.face_contacts.clear();
    if !s.skin || !s.def.collide || sc.candidates.is_empty() {
        return;
    }
    let r = s.def.vertex_radius;
    let mut polys = [Poly::new(&[]); 3];
    for ci in 0..sc.candidates.len() {
        let shape = shapes.at(sc.candidates[ci]);
        if matches!(shape.geometry, Geometry::Plane { .. }) {
            continue;
        }
        let body = bodies.at(shape.body);
        let reach = reach + super::contact::closing(body, shape) * dt;
        let bound = shape.fat_aabb.expanded(reach);
        for (t, tri) in s.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| s.pos[i as usize]);
            let tb = Aabb {
                min: a.min(b).min(c),
                max: a.max(b).max(c),
            };
            if !tb.overlaps(&bound) {
                continue;
            }
            let cr = (b - a).cross(c - a);
            let len = cr.length();
            if len < 1.0e-12 {
                continue;
            }
            let n = cr / len;
            let (count, centre) = support(&shape.geometry, geometry, body, -n, &mut polys);
            if count == 0 || n.dot(centre - a) <= 0.0 {
                continue;
            }
            let mut best = f32::MAX;
            let mut point = Vec3::ZERO;
            // Whether the part holding the deepest point lies flat on the triangle over one
            // of its vertices: then vertex contacts hold it (with their static friction).
            let mut flat = false;
            for poly in &polys[..count] {
                let clipped = poly
                    .clip(n.cross(b - a), a)
                    .clip(n.cross(c - b), b)
                    .clip(n.cross(a - c), c);
                let (mut low, mut high, mut at) = (f32::MAX, f32::MIN, Vec3::ZERO);
                let mut over_vertex = false;
                for &p in &clipped.p[..clipped.n] {
                    let d = n.dot(p - a);
                    if d < low {
                        low = d;
                        at = p;
                    }
                    high = high.max(d);
                    over_vertex |= barycentric(p - n * d, a, b, c).max_element() > AT_VERTEX;
                }
                if low < best {
                    best = low;
                    point = at;
                    flat = over_vertex && high - low < FLAT;
                }
            }
            if flat {
                continue;
            }
            // Deeper than half the skin's longest rest edge plus the reach (how far the shape
            // and the skin can close within a step), the shape is not poking through this
            // face: it is behind another part of a folded skin (or went through). The reach
            // counts inside as it does outside: a heavy corner moving fast gets that far into
            // a face within one step while its contact holds, and dropping the contact then
            // let it through (a tumbling 40 kg box's corner at 2.8 m/s went 44 mm into the
            // skin).
            if best >= r + reach || best < -(0.5 * s.longest_edge + reach) {
                continue;
            }
            let bary = barycentric(point - n * best, a, b, c);
            if bary.max_element() > AT_VERTEX {
                continue;
            }
            let friction = (s.def.friction * shape.def.static_friction).sqrt();
            let mut fc = FaceContact {
                triangle: t as u32,
                bary,
                point,
                coupled: NONE,
                body: if body.body_type == crate::BodyType::Kinematic {
                    shape.body
                } else {
                    NONE
                },
                friction,
            };
            if body.is_dynamic() && body.awake {
                let k = couple(
                    &mut sc.coupled,
                    &mut sc.coupled_index,
                    bodies,
                    shape.body,
                    pass,
                    &mut s.touching,
                );
                let cb = &sc.coupled[k as usize];
                fc.coupled = k;
                fc.point = cb.q0.conjugate() * (point - cb.c0);
            }
            s.face_contacts.push(fc);
        }
    }
}

/// The shape's point of face contact `c` in world space now, and its velocity.
#[inline]
fn point_of(c: &FaceContact, coupled: &[Coupled], bodies: &Pool<Body>) -> (Vec3, Vec3) {
    if c.coupled != NONE {
        let b = &coupled[c.coupled as usize];
        let p = b.center + b.q * c.point;
        (p, b.v + b.w.cross(p - b.center))
    } else if c.body != NONE {
        (c.point, bodies.at(c.body).point_velocity(c.point))
    } else {
        (c.point, Vec3::ZERO)
    }
}

/// The face contacts of one sub-step (before the vertex contacts).
pub(super) fn solve_face_contacts(s: &mut SoftBody, coupled: &mut [Coupled], bodies: &Pool<Body>, h: f32) {
    let r = s.def.vertex_radius;
    for k in 0..s.face_contacts.len() {
        let mut c = s.face_contacts[k];
        let (p, _) = point_of(&c, coupled, bodies);
        let Some((n, x)) = locate(s, &mut c, p) else { continue };
        s.face_contacts[k] = c;
        let tri = s.triangles[c.triangle as usize];
        let beta = c.bary.to_array();
        let depth = r - n.dot(p - x);
        if depth <= 0.0 {
            continue;
        }
        let mut w_tri = 0.0;
        for (j, &i) in tri.iter().enumerate() {
            w_tri += beta[j] * beta[j] * s.w[i as usize];
        }
        let w_body = if c.coupled != NONE {
            let body = &coupled[c.coupled as usize];
            body.inv_mass_at(p - body.center, n)
        } else {
            0.0
        };
        let wsum = w_tri + w_body;
        if wsum <= 0.0 {
            continue;
        }
        // Projection: the triangle along −n, the body along n.
        let lambda = depth / wsum;
        for (j, &i) in tri.iter().enumerate() {
            let i = i as usize;
            s.pos[i] -= n * (beta[j] * s.w[i] * lambda);
        }
        if c.coupled != NONE {
            let body = &mut coupled[c.coupled as usize];
            body.shift(p - body.center, n * lambda);
        }
        // Static friction, as for a vertex: if the shape's point slid over the face this
        // sub-step by less than `friction × depth`, the slide is undone, positions and
        // velocities alike (a box on a slope of faces would creep otherwise).
        let (p, _) = point_of(&c, coupled, bodies);
        let mut moved = Vec3::ZERO;
        for (j, &i) in tri.iter().enumerate() {
            moved += (s.pos[i as usize] - s.prev[i as usize]) * beta[j];
        }
        let was = if c.coupled != NONE {
            let body = &coupled[c.coupled as usize];
            body.c_prev + body.q_prev * c.point
        } else {
            p
        };
        let slide = (p - was) - moved;
        let slide = slide - n * n.dot(slide);
        let l = slide.length();
        let mut stuck = false;
        if l > 0.0 && l < c.friction * depth {
            let t = slide / l;
            let w_t = w_tri
                + if c.coupled != NONE {
                    let body = &coupled[c.coupled as usize];
                    body.inv_mass_at(p - body.center, t)
                } else {
                    0.0
                };
            let q = slide / w_t;
            for (j, &i) in tri.iter().enumerate() {
                let i = i as usize;
                s.pos[i] += q * (beta[j] * s.w[i]);
                s.vel[i] += q * (beta[j] * s.w[i] / h);
            }
            if c.coupled != NONE {
                let body = &mut coupled[c.coupled as usize];
                let arm = p - body.center;
                body.shift(arm, -q);
                body.push(arm, -q / h);
            }
            stuck = true;
        }
        // Velocity: no approach, Coulomb-bounded friction.
        let (p, vp) = point_of(&c, coupled, bodies);
        let mut vx = Vec3::ZERO;
        for (j, &i) in tri.iter().enumerate() {
            vx += s.vel[i as usize] * beta[j];
        }
        let vr = vp - vx;
        let vn = n.dot(vr);
        let vt = vr - n * vn;
        let lt = vt.length();
        let mut dv = Vec3::ZERO;
        if vn < 0.0 {
            dv += n * vn;
        }
        if lt > 0.0 && !stuck {
            let normal = (depth / h).max(-vn);
            dv += vt * (c.friction * normal / lt).min(1.0);
        }
        // Impulse on the body (the triangle takes the opposite).
        let j = -dv / wsum;
        for (k2, &i) in tri.iter().enumerate() {
            let i = i as usize;
            s.vel[i] -= j * (beta[k2] * s.w[i]);
        }
        if c.coupled != NONE {
            let body = &mut coupled[c.coupled as usize];
            body.push(p - body.center, j);
        }
    }
}

/// After the vertex contacts: a face with vertices held by fixed geometry this sub-step
/// resolves its overlap and approach again with those vertices' reduced mobility
/// (`contact::mobility`): a face pressed straight into the ground does not give way, its
/// dynamic body alone moves.
pub(super) fn hold_face_bodies(s: &mut SoftBody, coupled: &mut [Coupled]) {
    let r = s.def.vertex_radius;
    for k in 0..s.face_contacts.len() {
        let c = s.face_contacts[k];
        if c.coupled == NONE {
            continue;
        }
        let tri = s.triangles[c.triangle as usize];
        if tri.iter().all(|&i| s.held[i as usize] == Vec3::ZERO) {
            continue;
        }
        let [a, b, cc] = tri.map(|i| s.pos[i as usize]);
        let cr = (b - a).cross(cc - a);
        let len = cr.length();
        if len < 1.0e-12 {
            continue;
        }
        let n = cr / len;
        let beta = c.bary.to_array();
        let x = a * beta[0] + b * beta[1] + cc * beta[2];
        let body = &mut coupled[c.coupled as usize];
        let p = body.center + body.q * c.point;
        let depth = r - n.dot(p - x);
        if depth <= 0.0 {
            continue;
        }
        let arm = p - body.center;
        let mut moves = [(0.0, Vec3::ZERO); 3];
        let w_body = body.inv_mass_at(arm, n);
        let mut w = w_body;
        for j in 0..3 {
            let i = tri[j] as usize;
            moves[j] = mobility(s.w[i], s.held[i], s.contacts[i].friction, -n);
            w += beta[j] * beta[j] * moves[j].0;
        }
        if w <= 0.0 {
            continue;
        }
        let mut lambda = depth / w;
        // A free vertex this would push into the fixed geometry it is about to touch is
        // held by it too.
        let mut again = false;
        for j in 0..3 {
            let i = tri[j] as usize;
            let f = &s.contacts[i];
            if s.held[i] == Vec3::ZERO && f.active {
                let to = s.pos[i] + moves[j].1 * (beta[j] * s.w[i] * lambda);
                if f.offset + r - f.n.dot(to) > 0.0 {
                    moves[j] = mobility(s.w[i], f.n, f.friction, -n);
                    again = true;
                }
            }
        }
        if again {
            w = w_body;
            for j in 0..3 {
                w += beta[j] * beta[j] * moves[j].0;
            }
            if w <= 0.0 {
                continue;
            }
            lambda = depth / w;
        }
        for j in 0..3 {
            let i = tri[j] as usize;
            s.pos[i] += moves[j].1 * (beta[j] * s.w[i] * lambda);
        }
        body.shift(arm, n * lambda);
        let mut vx = Vec3::ZERO;
        for (j, &i) in tri.iter().enumerate() {
            vx += s.vel[i as usize] * beta[j];
        }
        // The face's own motion towards the body is its own light momentum: held, it only
        // stops the body from closing in, it does not throw it.
        let vn = n.dot(body.v + body.w.cross(arm)) - n.dot(vx).min(0.0);
        if vn < 0.0 {
            // Vertices leaving the fixed surface are not held by it: the body may slow them.
            let mut w = body.inv_mass_at(arm, n);
            for j in 0..3 {
                let i = tri[j] as usize;
                if s.vel[i].dot(s.held[i]) > LEAVING {
                    moves[j] = (s.w[i], -n);
                }
                w += beta[j] * beta[j] * moves[j].0;
            }
            let jn = -vn / w;
            for j in 0..3 {
                let i = tri[j] as usize;
                s.vel[i] += moves[j].1 * (beta[j] * s.w[i] * jn);
            }
            body.push(arm, n * jn);
        }
    }
}
