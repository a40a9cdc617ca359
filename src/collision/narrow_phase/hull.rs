//! Convex hulls against spheres, capsules and planes, and what the hull–hull test
//! (`hull_hull.rs`) shares: a placed polyhedron (`Poly`, also a box seen as the unit-box hull
//! scaled per axis), support functions for GJK, candidate points and their reduction to four.
//!
//! Rounded hulls: every test works on the cores (the polyhedra) and subtracts the radii;
//! a point lies midway between the two surfaces, which sit `radius` out from the cores
//! along the normal.
//!
//! * sphere–hull: inside the core, the face of largest separation; outside, GJK's closest
//!   point. One point.
//! * capsule–hull: the separating-axis test over the hull's faces and its edges crossed
//!   with the segment (an edge counts only when its arc on the Gauss map crosses the
//!   segment's great circle); a face axis clips the segment to the face's side planes (two
//!   points), an edge axis gives the closest points of the two segments. Separated cores
//!   whose true distance (GJK) exceeds the best axis (a corner is closest) give GJK's one
//!   point.
//! * hull–plane: the vertices of the face most anti-parallel to the plane's normal, and the
//!   deepest vertex, within the speculative distance, reduced to four.
//!
//! Feature ids are hashes of the features (face, vertex, edge, clip plane): equal while the
//! same features touch.

use super::geom::push_point;
use super::{Manifold, MAX_MANIFOLD_POINTS};
use crate::collision::gjk::{self, Support};
use crate::collision::hull::{ConvexHull, Plane};
use crate::math::{Mat3, Quat, Transform, Vec3};
use glam::Mat3A;
use std::sync::OnceLock;

/// A hull placed in world space.
#[derive(Clone, Copy)]
pub(crate) struct Poly<'a> {
    pub hull: &'a ConvexHull,
    pub rot: Mat3,
    pub pos: Vec3,
    /// Scale along the hull's axes: uniform for hull shapes; per axis for a box (the unit-box
    /// hull, whose face normals are the axes, so the scaling keeps every normal).
    pub scale: Vec3,
    pub uniform: bool,
    /// Convex radius of the placed shape.
    pub radius: f32,
}

/// The hull of the cube `[-0.5, 0.5]³`, built once: a box is this hull scaled per axis.
pub(crate) fn unit_box() -> &'static ConvexHull {
    static UNIT_BOX: OnceLock<ConvexHull> = OnceLock::new();
    UNIT_BOX.get_or_init(|| {
        let corners: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 != 0 { 0.5 } else { -0.5 },
                    if i & 2 != 0 { 0.5 } else { -0.5 },
                    if i & 4 != 0 { 0.5 } else { -0.5 },
                )
            })
            .collect();
        crate::collision::hull::builder::build(&corners, &Default::default()).expect("the unit cube is a valid hull")
    })
}

impl<'a> Poly<'a> {
    #[inline]
    pub fn hull(h: &'a ConvexHull, local: &Transform, scale: f32, xf: &Transform) -> Poly<'a> {
        Poly {
            hull: h,
            rot: Mat3::from_quat(xf.q * local.q),
            pos: xf.apply(local.p),
            scale: Vec3::splat(scale),
            uniform: true,
            radius: h.radius() * scale,
        }
    }

    #[inline]
    pub fn boxed(center: Vec3, rotation: Quat, half: Vec3, xf: &Transform) -> Poly<'static> {
        Poly {
            hull: unit_box(),
            rot: Mat3::from_quat(xf.q * rotation),
            pos: xf.apply(center),
            scale: 2.0 * half,
            uniform: false,
            radius: 0.0,
        }
    }

    /// Vertex `i` in the placed hull's own (scaled) frame.
    #[inline(always)]
    pub fn vertex(&self, i: usize) -> Vec3 {
        self.hull.vertices[i] * self.scale
    }

    /// Face plane `f` in the placed hull's own (scaled) frame.
    #[inline(always)]
    pub fn plane(&self, f: usize) -> Plane {
        let p = self.hull.planes[f];
        let k = if self.uniform {
            self.scale.x
        } else {
            (p.normal * self.scale).length()
        };
        Plane {
            normal: p.normal,
            offset: p.offset * k,
        }
    }

    /// Index of the vertex furthest along `d` (own frame).
    #[inline(always)]
    pub fn support_index(&self, d: Vec3) -> usize {
        self.hull.support_index(d * self.scale)
    }

    #[inline]
    pub fn local_point(&self, p: Vec3) -> Vec3 {
        self.rot.transpose() * (p - self.pos)
    }

    #[inline]
    pub fn world_point(&self, p: Vec3) -> Vec3 {
        self.rot * p + self.pos
    }

    /// A bound of the core's vertices' distance from its own origin (m): the bounding
    /// sphere about the centre of mass, moved out by the centre's distance, scaled by the
    /// largest scale (a box's unit-hull corners scale per axis).
    #[inline]
    pub fn reach(&self) -> f32 {
        self.scale.max_element() * (self.hull.unit_mass.center.length() + self.hull.bound_radius)
    }

    /// Centre of the core in its own frame.
    #[inline]
    pub fn center(&self) -> Vec3 {
        0.5 * (self.hull.min + self.hull.max) * self.scale
    }
}

/// A polyhedron in its own frame, for GJK.
pub(crate) struct Own<'p, 'a>(pub &'p Poly<'a>);

impl Support for Own<'_, '_> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        self.0.vertex(self.0.support_index(d))
    }
    fn center(&self) -> Vec3 {
        self.0.center()
    }
}

/// B's frame seen from A's: `x_a = r x_b + t`.
///
/// The rotations are `Mat3A`s (SIMD columns): glam's `Mat3A` products take the same
/// products and sums in the same order as `Mat3`'s, lane by lane, so every value is the
/// bit-identical `Mat3` result, in fewer instructions.
#[derive(Clone, Copy)]
pub(crate) struct Relative {
    pub r: Mat3A,
    pub rt: Mat3A,
    pub t: Vec3,
}

impl Relative {
    #[inline]
    pub fn new(a: &Poly, b: &Poly) -> Relative {
        let at = Mat3A::from(a.rot.transpose());
        let r = at * Mat3A::from(b.rot);
        Relative {
            r,
            rt: r.transpose(),
            t: at * (b.pos - a.pos),
        }
    }
}

/// Polyhedron B placed in A's frame, for GJK.
pub(crate) struct InA<'p, 'a> {
    pub poly: &'p Poly<'a>,
    pub rel: Relative,
}

impl Support for InA<'_, '_> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        self.rel.r * self.poly.vertex(self.poly.support_index(self.rel.rt * d)) + self.rel.t
    }
    fn center(&self) -> Vec3 {
        self.rel.r * self.poly.center() + self.rel.t
    }
}

/// A candidate contact point (midway between the surfaces) in some frame.
#[derive(Clone, Copy, Default, Debug)]
pub(crate) struct Candidate {
    pub p: Vec3,
    pub sep: f32,
    pub id: u32,
}

/// Candidates before reduction; when full, reduced to four in place and filled on.
pub(crate) struct Candidates {
    pub c: [Candidate; CANDIDATE_CAP],
    pub n: usize,
    /// Contact normal in the candidates' frame (for the reduction's areas).
    pub normal: Vec3,
}

pub(crate) const CANDIDATE_CAP: usize = 24;

impl Candidates {
    #[inline]
    pub fn new(normal: Vec3) -> Candidates {
        Candidates {
            c: [Candidate::default(); CANDIDATE_CAP],
            n: 0,
            normal,
        }
    }

    #[inline]
    pub fn push(&mut self, c: Candidate) {
        if self.n == CANDIDATE_CAP {
            let (keep, k) = reduce(&self.c[..self.n], self.normal);
            let old = self.c;
            for (j, &i) in keep[..k].iter().enumerate() {
                self.c[j] = old[i];
            }
            self.n = k;
        }
        self.c[self.n] = c;
        self.n += 1;
    }

    /// The manifold: at most four points by area, mapped by `to_world` (points) with the
    /// world normal `normal`.
    pub fn finish(&self, normal: Vec3, to_world: impl Fn(Vec3) -> Vec3) -> Manifold {
        let mut m = Manifold {
            normal,
            ..Manifold::EMPTY
        };
        let (keep, k) = reduce(&self.c[..self.n], self.normal);
        for &i in &keep[..k] {
            let c = self.c[i];
            push_point(&mut m, to_world(c.p), c.sep, c.id);
        }
        m
    }
}

/// Depth difference (m) under which points count as equally deep (lowest id wins), so
/// the choice does not flicker between frames.
const REDUCE_DEPTH_TOL: f32 = 1.0e-4;

/// At most four of `c` spanning the largest area about `n`: the deepest, the farthest
/// from it, the one making the largest triangle, then the one farthest outside that
/// triangle (Box2D/Jolt style).
pub(crate) fn reduce(c: &[Candidate], n: Vec3) -> ([usize; MAX_MANIFOLD_POINTS], usize) {
    let mut out = [0usize; MAX_MANIFOLD_POINTS];
    if c.len() <= MAX_MANIFOLD_POINTS {
        for (i, o) in out.iter_mut().enumerate().take(c.len()) {
            *o = i;
        }
        return (out, c.len());
    }
    let mut i0 = 0;
    for i in 1..c.len() {
        let (a, b) = (c[i], c[i0]);
        if a.sep < b.sep - REDUCE_DEPTH_TOL || (a.sep <= b.sep + REDUCE_DEPTH_TOL && a.id < b.id) {
            i0 = i;
        }
    }
    let p0 = c[i0].p;
    let mut i1 = i0;
    let mut best = -1.0;
    for (i, x) in c.iter().enumerate() {
        let d = (x.p - p0).length_squared();
        if d > best {
            best = d;
            i1 = i;
        }
    }
    let p1 = c[i1].p;
    let mut i2 = i0;
    let mut best = -1.0;
    let mut sign = 1.0;
    for (i, x) in c.iter().enumerate() {
        let a = (p1 - p0).cross(x.p - p0).dot(n);
        if a.abs() > best {
            best = a.abs();
            i2 = i;
            sign = if a >= 0.0 { 1.0 } else { -1.0 };
        }
    }
    let p2 = c[i2].p;
    // Orient the triangle counter-clockwise about n; the fourth point is the one most
    // outside one of its edges.
    let (q0, q1, q2) = if sign > 0.0 { (p0, p1, p2) } else { (p0, p2, p1) };
    let mut i3 = usize::MAX;
    let mut best = 0.0;
    for (i, x) in c.iter().enumerate() {
        if i == i0 || i == i1 || i == i2 {
            continue;
        }
        let e0 = (q1 - q0).cross(x.p - q0).dot(n);
        let e1 = (q2 - q1).cross(x.p - q1).dot(n);
        let e2 = (q0 - q2).cross(x.p - q2).dot(n);
        let a = -(e0.min(e1).min(e2));
        if a > best {
            best = a;
            i3 = i;
        }
    }
    out[0] = i0;
    let mut k = 1;
    for i in [i1, i2, i3] {
        if i != usize::MAX && !out[..k].contains(&i) {
            out[k] = i;
            k += 1;
        }
    }
    (out, k)
}

/// A 32-bit feature id from small parts (FNV-1a over their bytes).
#[inline]
pub(crate) fn feature_id(parts: [u32; 4]) -> u32 {
    let mut h: u32 = 0x811c_9dc5;
    for p in parts {
        for b in p.to_le_bytes() {
            h ^= b as u32;
            h = h.wrapping_mul(0x0100_0193);
        }
    }
    h
}

/// The one point between two cores at closest points `ca` (on A) and `cb` (on B), unit
/// normal `n` from A to B and core distance `dist`, as a manifold in world space.
#[allow(clippy::too_many_arguments)]
pub(crate) fn one_point(
    ca: Vec3,
    cb: Vec3,
    n: Vec3,
    dist: f32,
    ra: f32,
    rb: f32,
    id: u32,
    speculative: f32,
) -> Manifold {
    let sep = dist - ra - rb;
    if sep > speculative {
        return Manifold::EMPTY;
    }
    let mut m = Manifold {
        normal: n,
        ..Manifold::EMPTY
    };
    push_point(&mut m, 0.5 * ((ca + n * ra) + (cb - n * rb)), sep, id);
    m
}

/// Sphere A (world centre, radius) against hull B.
pub(crate) fn sphere_hull(center: Vec3, radius: f32, b: &Poly, speculative: f32) -> Manifold {
    let c = b.local_point(center);
    let (mut best, mut face) = (f32::MIN, 0);
    for f in 0..b.hull.planes.len() {
        let s = b.plane(f).distance(c);
        if s > best {
            best = s;
            face = f;
        }
    }
    let limit = speculative + radius + b.radius;
    if best > limit {
        return Manifold::EMPTY;
    }
    let (q, u, dist) = if best <= 0.0 {
        let n = b.plane(face).normal;
        (c - n * best, n, best)
    } else {
        let g = gjk::distance_from(&Own(b), &gjk::Point(c), b.plane(face).normal);
        if g.overlap || g.distance <= 0.0 {
            let n = b.plane(face).normal;
            (c - n * best, n, best)
        } else {
            (g.point_a, g.normal, g.distance)
        }
    };
    // `u` points from the hull (B) to the sphere (A): the manifold normal is the opposite.
    one_point(
        center,
        b.world_point(q),
        -(b.rot * u),
        dist,
        radius,
        b.radius,
        0,
        speculative,
    )
}

/// Capsule A (world segment `p`–`q`, radius) against hull B.
pub(crate) fn capsule_hull(p: Vec3, q: Vec3, radius: f32, b: &Poly, speculative: f32) -> Manifold {
    let (p, q) = (b.local_point(p), b.local_point(q));
    let r = radius + b.radius;
    let limit = speculative + r;
    let (mut sep_f, mut face) = (f32::MIN, 0);
    for f in 0..b.hull.planes.len() {
        let pl = b.plane(f);
        let s = pl.distance(p).min(pl.distance(q));
        if s > limit {
            return Manifold::EMPTY;
        }
        if s > sep_f {
            sep_f = s;
            face = f;
        }
    }
    // Edges crossed with the segment: an edge counts when its Gauss arc crosses the great
    // circle of directions perpendicular to the segment.
    let e = q - p;
    let (mut sep_e, mut edge, mut edge_axis) = (f32::MIN, usize::MAX, Vec3::ZERO);
    for (k, g) in b.hull.edge_gauss.iter().enumerate() {
        let (s1, s2) = (g.n1.dot(e), g.n2.dot(e));
        if s1 * s2 >= 0.0 {
            continue;
        }
        let (v0, v1) = (b.vertex(g.v0 as usize), b.vertex(g.v1 as usize));
        let axis = (v1 - v0).cross(e);
        let l2 = axis.length_squared();
        if l2 < 1.0e-12 * (v1 - v0).length_squared() * e.length_squared() {
            continue;
        }
        let mut axis = axis / l2.sqrt();
        if axis.dot(g.n1 + g.n2) < 0.0 {
            axis = -axis;
        }
        let s = axis.dot(p - v0);
        if s > limit {
            return Manifold::EMPTY;
        }
        if s > sep_e {
            sep_e = s;
            edge = k;
            edge_axis = axis;
        }
    }
    let use_edge = edge != usize::MAX && sep_e > sep_f + 0.05 * sep_f.abs() + 0.001;
    let best = if use_edge { sep_e } else { sep_f };
    if best > 0.0 {
        // Separated cores: the best axis is exact only when a face or an edge pair is
        // closest; GJK decides.
        let seg = gjk::Segment(p, q);
        let start = if use_edge { edge_axis } else { b.plane(face).normal };
        let g = gjk::distance_from(&Own(b), &seg, start);
        if !g.overlap && g.distance > best + 1.0e-3 + 0.02 * best {
            let n = b.rot * g.normal;
            return one_point(
                b.world_point(g.point_b),
                b.world_point(g.point_a),
                -n,
                g.distance,
                radius,
                b.radius,
                feature_id([3, 0, 0, 0]),
                speculative,
            );
        }
    }
    if use_edge {
        let gs = b.hull.edge_gauss[edge];
        let (v0, v1) = (b.vertex(gs.v0 as usize), b.vertex(gs.v1 as usize));
        let (s, t) = super::geom::closest_segment_segment(v0, v1, p, q);
        let ch = v0 + (v1 - v0) * s;
        let cc = p + e * t;
        let n = b.rot * edge_axis;
        return one_point(
            b.world_point(cc),
            b.world_point(ch),
            -n,
            sep_e,
            radius,
            b.radius,
            feature_id([2, edge as u32, 0, 0]),
            speculative,
        );
    }
    // Face: clip the segment to the face's side planes.
    let pl = b.plane(face);
    let n = pl.normal;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    let fc = b.hull.faces[face];
    for k in 0..fc.count as usize {
        let he = &b.hull.half_edges[fc.first as usize..(fc.first + fc.count) as usize];
        let a0 = b.vertex(he[k].origin as usize);
        let a1 = b.vertex(he[(k + 1) % fc.count as usize].origin as usize);
        let m = (a1 - a0).cross(n);
        let (dp, dq) = (m.dot(p - a0), m.dot(q - a0));
        if dp > 0.0 && dq > 0.0 {
            t0 = 1.0;
            t1 = 0.0;
            break;
        }
        if dp > 0.0 {
            t0 = t0.max(dp / (dp - dq));
        } else if dq > 0.0 {
            t1 = t1.min(dp / (dp - dq));
        }
    }
    let mut m = Manifold {
        normal: -(b.rot * n),
        ..Manifold::EMPTY
    };
    if t0 > t1 {
        // The segment passes beside the face: its deepest end.
        let x = if pl.distance(p) <= pl.distance(q) { p } else { q };
        t0 = if x == p { 0.0 } else { 1.0 };
        t1 = t0;
    }
    for (k, t) in [t0, t1].into_iter().enumerate() {
        if k == 1 && t1 <= t0 {
            break;
        }
        let x = p + e * t;
        let s = pl.distance(x);
        let sep = s - r;
        if sep > speculative {
            continue;
        }
        let on_capsule = x - n * radius;
        let on_hull = x - n * s + n * b.radius;
        push_point(
            &mut m,
            b.world_point(0.5 * (on_capsule + on_hull)),
            sep,
            feature_id([1, face as u32, k as u32, 0]),
        );
    }
    m
}

/// Hull A against plane B (world unit normal `n`, offset `d`): the vertices of the hull's
/// face most anti-parallel to the plane normal (the incident face) within reach, and the
/// deepest vertex, reduced to four. Ids are vertex indices.
pub(crate) fn hull_plane(a: &Poly, n: Vec3, d: f32, speculative: f32) -> Manifold {
    let nl = a.rot.transpose() * n;
    let dl = d - n.dot(a.pos);
    let limit = speculative + a.radius;
    let deepest = a.support_index(-nl);
    if nl.dot(a.vertex(deepest)) - dl > limit {
        return Manifold::EMPTY;
    }
    let (mut face, mut best) = (0usize, f32::MAX);
    for (f, p) in a.hull.planes.iter().enumerate() {
        let x = p.normal.dot(nl);
        if x < best {
            best = x;
            face = f;
        }
    }
    let mut cands = Candidates::new(-nl);
    let mut add = |i: usize| {
        let v = a.vertex(i);
        let s = nl.dot(v) - dl;
        if s <= limit {
            cands.push(Candidate {
                p: v - nl * (0.5 * (s + a.radius)),
                sep: s - a.radius,
                id: i as u32,
            });
        }
    };
    let mut has_deepest = false;
    for i in a.hull.face_vertices(face) {
        has_deepest |= i as usize == deepest;
        add(i as usize);
    }
    if !has_deepest {
        add(deepest);
    }
    cands.finish(-n, |p| a.world_point(p))
}
