//! A convex shape against one triangle of a mesh or heightfield.
//!
//! Everything here works in one frame (the *target* frame chosen by `mesh.rs`: world space
//! for spheres and capsules, the shape's own frame for boxes and hulls). A triangle is
//! one-sided: its front is where its normal `n` points, and a shape entirely behind it does
//! not touch it. The normal a routine reports points from the triangle to the shape.
//!
//! **Internal edges.** A contact found on a triangle's edge or vertex takes that feature's
//! own normal only when the feature is *active* (`mesh/edges.rs`: a convex edge bent by more
//! than 5°, or an open edge); on an inactive (flat or concave) one the face normal is used
//! instead, with the separation measured along it — the neighbouring triangle owns that
//! contact, so a body sliding over a seam sees one flat surface (Jolt's active edges). For
//! boxes and hulls the same rule decides which separating axes may give the normal: an axis
//! other than the face normal is allowed only if it points to the front and the triangle
//! feature it touches is active.
//!
//! **Feature ids.** A point at a vertex of the convex shape (the sphere's centre, a capsule
//! end, a box corner, a hull vertex) has that vertex's index as id, so it keeps its warm
//! start while sliding from triangle to triangle. Any other point has bit 31 set, the
//! triangle's index in bits 8..30 and a code for the features in bits 0..7.

use super::geom::closest_segment_segment;
use super::ManifoldPoint;
use crate::collision::mesh::edges::vertex_active;
use crate::math::Vec3;
use crate::simd::{Lanes, F4};

/// Most points a triangle contributes (a hull face clipped by a triangle may have more; the
/// extra ones are reduced away, see `TriContact::push`).
pub const TRI_MAX_POINTS: usize = 16;

/// Capsule axis against the triangle: largest |cos| to the face normal that still lies flat.
const FLAT_AXIS_COS: f32 = 0.2;
/// Two clipped capsule points closer than this (m) collapse into one.
const MIN_POINT_SPACING: f32 = 0.005;
/// A polytope face replaces the triangle's face axis only when better by this slack, an
/// edge axis only when better than both by its slack (stable features at rest).
const FACE_REL_TOL: f32 = 0.02;
const FACE_ABS_TOL: f32 = 0.001;
const EDGE_REL_TOL: f32 = 0.05;
const EDGE_ABS_TOL: f32 = 0.002;
/// An axis this close to the face normal (cos) is the face normal.
const FACE_AXIS_COS: f32 = 0.9999;
/// Triangle vertices within this (m) of the extreme projection count as touching.
const FEATURE_TOL: f32 = 1.0e-4;
/// Polygon capacity while clipping.
pub const CLIP_CAP: usize = 24;

/// A triangle in the target frame.
#[derive(Clone, Copy, Debug)]
pub struct Triangle {
    pub v: [Vec3; 3],
    /// Unit normal (the front).
    pub n: Vec3,
    /// Active-edge bits (`mesh/edges.rs`).
    pub flags: u8,
    /// Index for feature ids (mesh: leaf order; heightfield: `2·cell + k`).
    pub index: u32,
}

/// The points of one convex shape against one triangle, with one normal (target frame,
/// from the triangle to the shape).
#[derive(Clone, Copy, Debug)]
pub struct TriContact {
    pub normal: Vec3,
    pub points: [ManifoldPoint; TRI_MAX_POINTS],
    pub count: usize,
}

impl TriContact {
    pub const EMPTY: TriContact = TriContact {
        normal: Vec3::ZERO,
        points: [ManifoldPoint {
            point: Vec3::ZERO,
            separation: 0.0,
            id: 0,
        }; TRI_MAX_POINTS],
        count: 0,
    };

    #[inline]
    fn push(&mut self, point: Vec3, separation: f32, id: u32) {
        if self.count == TRI_MAX_POINTS {
            self.count = super::mesh::reduce_in_place(&mut self.points[..], self.normal);
        }
        self.points[self.count] = ManifoldPoint { point, separation, id };
        self.count += 1;
    }
}

/// Id of a point that is not a vertex of the convex shape.
#[inline]
pub fn triangle_id(tri: u32, code: u32) -> u32 {
    1 << 31 | (tri & 0x7F_FFFF) << 8 | (code & 0xFF)
}

/// The feature of a triangle a closest point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Feature {
    Vertex(usize),
    /// Edge `i` runs from vertex `i` to vertex `i + 1`.
    Edge(usize),
    Face,
}

impl Feature {
    /// May a contact on this feature have a normal of its own?
    #[inline]
    pub fn active(self, flags: u8) -> bool {
        match self {
            Feature::Vertex(i) => vertex_active(flags, i),
            Feature::Edge(i) => flags & (1 << i) != 0,
            Feature::Face => true,
        }
    }

    fn code(self) -> u32 {
        match self {
            Feature::Vertex(i) => i as u32,
            Feature::Edge(i) => 3 + i as u32,
            Feature::Face => 6,
        }
    }
}

/// Closest point of triangle `v` to `p` and the feature it lies on (Ericson, *Real-Time
/// Collision Detection* 5.1.5).
pub fn closest_on_triangle(p: Vec3, v: &[Vec3; 3]) -> (Vec3, Feature) {
    let (a, b, c) = (v[0], v[1], v[2]);
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Feature::Vertex(0));
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (a + ab * (d1 / (d1 - d3)), Feature::Edge(0));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (a + ac * (d2 / (d2 - d6)), Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), Feature::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    (a + ab * (vb * denom) + ac * (vc * denom), Feature::Face)
}

/// Sphere (centre `c`, radius `r`) against a triangle.
pub fn sphere_triangle(c: Vec3, r: f32, t: &Triangle, speculative: f32, out: &mut TriContact) -> bool {
    let height = t.n.dot(c - t.v[0]);
    if height < -r {
        return false;
    }
    let (q, f) = closest_on_triangle(c, &t.v);
    let d = c - q;
    let dist_sq = d.length_squared();
    let reach = r + speculative;
    if dist_sq > reach * reach {
        return false;
    }
    if f != Feature::Face && height > 0.0 && f.active(t.flags) && dist_sq > 1.0e-12 {
        let dist = dist_sq.sqrt();
        let normal = d / dist;
        let sep = dist - r;
        out.normal = normal;
        out.count = 0;
        out.push(q + (0.5 * sep) * normal, sep, 0);
        return true;
    }
    let sep = height - r;
    if sep > speculative {
        return false;
    }
    out.normal = t.n;
    out.count = 0;
    out.push(c - (r + 0.5 * sep) * t.n, sep, 0);
    true
}

/// Closest points of segment `p0`–`p1` and triangle `t`: the segment parameter, the two
/// points and the triangle feature.
fn segment_triangle_closest(p0: Vec3, p1: Vec3, t: &Triangle) -> (f32, Vec3, Vec3, Feature) {
    let (h0, h1) = (t.n.dot(p0 - t.v[0]), t.n.dot(p1 - t.v[0]));
    if (h0 <= 0.0) != (h1 <= 0.0) || h0 == 0.0 {
        // The segment crosses the plane: inside the triangle, the distance is zero.
        let s = if h0 == h1 { 0.0 } else { h0 / (h0 - h1) };
        let x = p0 + s * (p1 - p0);
        if inside_prism(x, t) {
            return (s, x, x, Feature::Face);
        }
    }
    let mut best = {
        let (q, f) = closest_on_triangle(p0, &t.v);
        ((p0 - q).length_squared(), 0.0, p0, q, f)
    };
    let (q, f) = closest_on_triangle(p1, &t.v);
    let d = (p1 - q).length_squared();
    if d < best.0 {
        best = (d, 1.0, p1, q, f);
    }
    for e in 0..3 {
        let (a, b) = (t.v[e], t.v[(e + 1) % 3]);
        let (s, u) = closest_segment_segment(p0, p1, a, b);
        let (x, q) = (p0 + s * (p1 - p0), a + u * (b - a));
        let d = (x - q).length_squared();
        if d < best.0 {
            let f = if u <= 0.0 {
                Feature::Vertex(e)
            } else if u >= 1.0 {
                Feature::Vertex((e + 1) % 3)
            } else {
                Feature::Edge(e)
            };
            best = (d, s, x, q, f);
        }
    }
    (best.1, best.2, best.3, best.4)
}

/// Is `x` inside the prism over the triangle (on the inner side of its three edges)?
#[inline]
fn inside_prism(x: Vec3, t: &Triangle) -> bool {
    (0..3).all(|i| t.n.cross(t.v[(i + 1) % 3] - t.v[i]).dot(x - t.v[i]) >= 0.0)
}

/// Capsule (segment `p0`–`p1`, radius `r`) against a triangle: one point, or two (the
/// segment clipped to the triangle) when the capsule lies flat on its face.
pub fn capsule_triangle(p0: Vec3, p1: Vec3, r: f32, t: &Triangle, speculative: f32, out: &mut TriContact) -> bool {
    let (h0, h1) = (t.n.dot(p0 - t.v[0]), t.n.dot(p1 - t.v[0]));
    if h0 < -r && h1 < -r {
        return false;
    }
    let (s, x, q, f) = segment_triangle_closest(p0, p1, t);
    let d = x - q;
    let dist_sq = d.length_squared();
    let reach = r + speculative;
    if dist_sq > reach * reach {
        return false;
    }
    out.count = 0;
    let end_id = |s: f32, code: u32| {
        if s <= 0.0 {
            0
        } else if s >= 1.0 {
            1
        } else {
            triangle_id(t.index, code)
        }
    };
    if f != Feature::Face && t.n.dot(d) > 0.0 && f.active(t.flags) && dist_sq > 1.0e-12 {
        let dist = dist_sq.sqrt();
        let normal = d / dist;
        let sep = dist - r;
        out.normal = normal;
        out.push(q + (0.5 * sep) * normal, sep, end_id(s, 8 + f.code()));
        return true;
    }
    // Face normal: the segment clipped to the prism over the triangle.
    out.normal = t.n;
    let axis = p1 - p0;
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    let (mut lo_code, mut hi_code) = (u32::MAX, u32::MAX);
    for i in 0..3 {
        let m = t.n.cross(t.v[(i + 1) % 3] - t.v[i]);
        let (f0, fd) = (m.dot(p0 - t.v[i]), m.dot(axis));
        if fd.abs() <= 1.0e-12 {
            if f0 < 0.0 {
                (lo, hi) = (1.0, 0.0);
            }
            continue;
        }
        let u = -f0 / fd;
        if fd > 0.0 {
            if u > lo {
                (lo, lo_code) = (u, i as u32);
            }
        } else if u < hi {
            (hi, hi_code) = (u, i as u32);
        }
    }
    let flat = axis.length_squared() > 1.0e-12 && t.n.dot(axis).abs() < FLAT_AXIS_COS * axis.length();
    let mut add = |u: f32, code: u32| {
        let p = p0 + u * axis;
        let sep = t.n.dot(p - t.v[0]) - r;
        if sep <= speculative {
            let id = if code == u32::MAX {
                end_id(u, 0)
            } else {
                triangle_id(t.index, 16 + code)
            };
            out.push(p - (r + 0.5 * sep) * t.n, sep, id);
        }
    };
    if lo <= hi {
        if flat && (hi - lo) * axis.length() > MIN_POINT_SPACING {
            add(lo, lo_code);
            add(hi, hi_code);
        } else if t.n.dot(axis) <= 0.0 {
            // The deeper end of the clipped segment.
            add(hi, hi_code);
        } else {
            add(lo, lo_code);
        }
    } else {
        // Beside the triangle over an inactive edge: the closest point, along the face normal.
        let sep = t.n.dot(x - t.v[0]) - r;
        if sep <= speculative {
            out.push(x - (r + 0.5 * sep) * t.n, sep, end_id(s, 24));
        }
    }
    out.count > 0
}

/// A convex polyhedron seen by the separating-axis test, in its own frame.
pub trait Polytope {
    /// Interval of the core's projection onto `a`.
    fn interval(&self, a: Vec3) -> (f32, f32);
    /// `interval` along four axes at once (lane k: `(ax, ay, az)`'s lane k), the same
    /// values lane by lane.
    #[inline]
    fn interval4(&self, ax: F4, ay: F4, az: F4) -> (F4, F4) {
        let (x, y, z) = (ax.to_floats(), ay.to_floats(), az.to_floats());
        let r = [0, 1, 2, 3].map(|k| self.interval(Vec3::new(x[k], y[k], z[k])));
        (F4::from_fn(|k| r[k].0), F4::from_fn(|k| r[k].1))
    }
    fn face_count(&self) -> usize;
    /// Outward unit normal and offset of face `f` (`dot(normal, x) <= offset` inside).
    fn face_plane(&self, f: usize) -> (Vec3, f32);
    /// Face `f`'s vertices, counter-clockwise seen from outside, with their vertex ids.
    fn face_polygon(&self, f: usize, out: &mut [(Vec3, u32); CLIP_CAP]) -> usize;
    /// The face whose normal is most anti-parallel to `d`.
    fn incident_face(&self, d: Vec3) -> usize;
    fn edge_direction_count(&self) -> usize;
    fn edge_direction(&self, i: usize) -> Vec3;
    /// An edge parallel to direction `i` that is furthest along `a`: its end points.
    fn support_edge(&self, a: Vec3, i: usize) -> (Vec3, Vec3);
    /// A point inside (orients edge axes).
    fn center(&self) -> Vec3;
}

/// A box centred at the origin of its frame.
pub struct LocalBox(pub Vec3);

impl Polytope for LocalBox {
    #[inline]
    fn interval(&self, a: Vec3) -> (f32, f32) {
        let r = self.0.dot(a.abs());
        (-r, r)
    }
    fn face_count(&self) -> usize {
        6
    }
    #[inline]
    fn face_plane(&self, f: usize) -> (Vec3, f32) {
        let (k, s) = (f / 2, if f % 2 == 0 { 1.0 } else { -1.0 });
        let mut n = Vec3::ZERO;
        n[k] = s;
        (n, self.0[k])
    }
    fn face_polygon(&self, f: usize, out: &mut [(Vec3, u32); CLIP_CAP]) -> usize {
        let (k, s) = (f / 2, if f % 2 == 0 { 1.0f32 } else { -1.0 });
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        // Counter-clockwise seen from outside: (u, v) turn positively about +k.
        let corners = [(1.0f32, 1.0f32), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
        for (i, &(cu, cv)) in corners.iter().enumerate() {
            let cv = cv * s;
            let mut p = Vec3::ZERO;
            p[k] = s * self.0[k];
            p[u] = cu * self.0[u];
            p[v] = cv * self.0[v];
            let id = (p.x > 0.0) as u32 | ((p.y > 0.0) as u32) << 1 | ((p.z > 0.0) as u32) << 2;
            out[i] = (p, id);
        }
        4
    }
    #[inline]
    fn incident_face(&self, d: Vec3) -> usize {
        let a = d.abs();
        let k = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        // Most anti-parallel: the face on the side opposite to d.
        2 * k + (d[k] > 0.0) as usize
    }
    fn edge_direction_count(&self) -> usize {
        3
    }
    #[inline]
    fn edge_direction(&self, i: usize) -> Vec3 {
        let mut e = Vec3::ZERO;
        e[i] = 1.0;
        e
    }
    fn support_edge(&self, a: Vec3, i: usize) -> (Vec3, Vec3) {
        let mut p = Vec3::ZERO;
        for j in 0..3 {
            if j != i {
                p[j] = if a[j] >= 0.0 { self.0[j] } else { -self.0[j] };
            }
        }
        let (mut lo, mut hi) = (p, p);
        lo[i] = -self.0[i];
        hi[i] = self.0[i];
        (lo, hi)
    }
    fn center(&self) -> Vec3 {
        Vec3::ZERO
    }
}

#[derive(Clone, Copy, PartialEq, Debug)]
enum Axis {
    Triangle,
    Face(usize),
    Edge(usize, usize),
}

/// May an axis `a` (unit, from the triangle to the shape) other than the face normal give
/// the contact normal? It must point to the front, and the triangle's vertices furthest
/// along it (the feature it touches) must be active.
fn axis_allowed(a: Vec3, t: &Triangle) -> bool {
    let c = a.dot(t.n);
    if c >= FACE_AXIS_COS {
        return true;
    }
    if c < 0.0 {
        return false;
    }
    let p = t.v.map(|v| v.dot(a));
    let top = p[0].max(p[1]).max(p[2]);
    let on: [bool; 3] = p.map(|x| x >= top - FEATURE_TOL);
    let feature = match on {
        [true, true, false] => Feature::Edge(0),
        [false, true, true] => Feature::Edge(1),
        [true, false, true] => Feature::Edge(2),
        [true, false, false] => Feature::Vertex(0),
        [false, true, false] => Feature::Vertex(1),
        [false, false, true] => Feature::Vertex(2),
        _ => return true,
    };
    feature.active(t.flags)
}

/// The first test of `polytope_triangle`: the core's interval `(lo, hi)` along the
/// triangle's normal lies behind the triangle's plane (at `d0`) or beyond `speculative`
/// in front of it.
#[inline(always)]
fn plane_rejects(lo: f32, hi: f32, d0: f32, radius: f32, speculative: f32) -> bool {
    hi + radius < d0 || lo - d0 - radius > speculative
}

/// Whether `polytope_triangle` returns false on its first test for a triangle with corner
/// `v0` and unit normal `n` — before it reads the edge flags or writes `out`, so a caller
/// can leave out the flags of such a triangle (and the call).
#[inline(always)]
pub fn polytope_plane_rejects<P: Polytope>(p: &P, radius: f32, v0: Vec3, n: Vec3, speculative: f32) -> bool {
    let (lo, hi) = p.interval(n);
    plane_rejects(lo, hi, n.dot(v0), radius, speculative)
}

/// A convex polyhedron `p` (rounded by `radius`) against a triangle, both in `p`'s frame:
/// separating axes (the triangle's normal, `p`'s faces, edge pairs), then the reference
/// face clipped by the incident one, or one point between two edges.
pub fn polytope_triangle<P: Polytope>(
    p: &P,
    radius: f32,
    t: &Triangle,
    speculative: f32,
    out: &mut TriContact,
) -> bool {
    let n = t.n;
    let d0 = n.dot(t.v[0]);
    let (lo, hi) = p.interval(n);
    if plane_rejects(lo, hi, d0, radius, speculative) {
        return false;
    }
    let sep_tri = lo - d0 - radius;
    // Best allowed face of p.
    let (mut sep_face, mut face) = (f32::MIN, usize::MAX);
    for f in 0..p.face_count() {
        let (m, off) = p.face_plane(f);
        let tmin = t.v[0].dot(m).min(t.v[1].dot(m)).min(t.v[2].dot(m));
        let s = tmin - off - radius;
        if s > speculative {
            return false;
        }
        if s > sep_face && axis_allowed(-m, t) {
            (sep_face, face) = (s, f);
        }
    }
    // Best allowed edge pair: p's edge direction `i` crossed with the triangle's edge `e`,
    // for the pairs `j = 3i + e` four at a time (`F4` lanes, each lane the scalar form's
    // operations in its order: `edge_axes_match_one_at_a_time`). Any axis separating the
    // shapes ends the test whatever its place; the best allowed one is then picked in pair
    // order, so ties go as one pair at a time.
    let (mut sep_edge, mut edge, mut edge_axis) = (f32::MIN, (0, 0), Vec3::ZERO);
    let center = p.center();
    let te: [Vec3; 3] = [0, 1, 2].map(|e| t.v[(e + 1) % 3] - t.v[e]);
    let parallel: [f32; 3] = te.map(|x| 1.0e-10 * x.length_squared());
    let to_center: [Vec3; 3] = [0, 1, 2].map(|e| center - t.v[e]);
    let tv = t.v.map(|v| (F4::splat(v.x), F4::splat(v.y), F4::splat(v.z)));
    let (radius4, speculative4) = (F4::splat(radius), F4::splat(speculative));
    let pairs = 3 * p.edge_direction_count();
    let mut j0 = 0;
    while j0 < pairs {
        let live = (pairs - j0).min(4);
        // Lane k: pair j0 + k (padding lanes repeat the last pair and are masked out).
        let pairs4: [(usize, usize); 4] =
            [0, 1, 2, 3].map(|k| ((j0 + k.min(live - 1)) / 3, (j0 + k.min(live - 1)) % 3));
        let pair = |k: usize| pairs4[k];
        let d: [Vec3; 4] = [0, 1, 2, 3].map(|k| p.edge_direction(pair(k).0));
        let (dx, dy, dz) = (
            F4::from_fn(|k| d[k].x),
            F4::from_fn(|k| d[k].y),
            F4::from_fn(|k| d[k].z),
        );
        let (ex, ey, ez) = (
            F4::from_fn(|k| te[pair(k).1].x),
            F4::from_fn(|k| te[pair(k).1].y),
            F4::from_fn(|k| te[pair(k).1].z),
        );
        // d × te (glam's cross), its squared length, and the parallel test.
        let (ax, ay, az) = (dy * ez - ey * dz, dz * ex - ez * dx, dx * ey - ex * dy);
        let len_sq = ax * ax + ay * ay + az * az;
        let skip = F4::from_fn(|k| parallel[pair(k).1]).gt(len_sq).bits();
        let valid = !skip & ((1u32 << live) - 1);
        let len = len_sq.sqrt();
        let (ax, ay, az) = (ax / len, ay / len, az / len);
        // Oriented from the triangle towards p's centre.
        let (cx, cy, cz) = (
            F4::from_fn(|k| to_center[pair(k).1].x),
            F4::from_fn(|k| to_center[pair(k).1].y),
            F4::from_fn(|k| to_center[pair(k).1].z),
        );
        // Negated exactly (a product by −1 flips the sign of a zero too, as `-a` does).
        let flip = F4::zero().gt(ax * cx + ay * cy + az * cz);
        let neg = F4::splat(-1.0);
        let (ax, ay, az) = (
            F4::select(flip, neg * ax, ax),
            F4::select(flip, neg * ay, ay),
            F4::select(flip, neg * az, az),
        );
        let (plo, phi) = p.interval4(ax, ay, az);
        let tp = tv.map(|(x, y, z)| x * ax + y * ay + z * az);
        let min = |a: F4, b: F4| F4::select(a.gt(b), b, a);
        let max = |a: F4, b: F4| F4::select(b.gt(a), b, a);
        let (tlo, thi) = (min(min(tp[0], tp[1]), tp[2]), max(max(tp[0], tp[1]), tp[2]));
        // Oriented from the triangle to p; the reverse orientation (p behind) only
        // matters for separation.
        let s = plo - thi - radius4;
        let s_rev = tlo - phi - radius4;
        if s.gt(speculative4).or(s_rev.gt(speculative4)).bits() & valid != 0 {
            return false;
        }
        let (s, ax, ay, az) = (s.to_floats(), ax.to_floats(), ay.to_floats(), az.to_floats());
        for k in (0..live).filter(|k| valid >> k & 1 != 0) {
            let (i, e) = pair(k);
            let a = Vec3::new(ax[k], ay[k], az[k]);
            if s[k] > sep_edge && t.flags & (1 << e) != 0 && a.dot(n) >= 0.0 && a.dot(n) < FACE_AXIS_COS {
                (sep_edge, edge, edge_axis) = (s[k], (i, e), a);
            }
        }
        j0 += 4;
    }
    let separations = Separations {
        triangle: sep_tri,
        face: (sep_face, face),
        edge: (sep_edge, edge, edge_axis),
    };
    manifold_from_best_axis(p, radius, t, speculative, &separations, out)
}

/// The best separation found along each kind of axis: the triangle's normal, a face of the
/// polytope (`usize::MAX` when none), an edge pair (polytope edge direction, triangle edge)
/// with its axis.
struct Separations {
    triangle: f32,
    face: (f32, usize),
    edge: (f32, (usize, usize), Vec3),
}

/// Picks the reference axis (the triangle's normal unless a face, then an edge pair,
/// separates clearly more) and builds the manifold on it.
fn manifold_from_best_axis<P: Polytope>(
    p: &P,
    radius: f32,
    t: &Triangle,
    speculative: f32,
    sep: &Separations,
    out: &mut TriContact,
) -> bool {
    let (sep_tri, (sep_face, face), (sep_edge, edge, edge_axis)) = (sep.triangle, sep.face, sep.edge);
    let mut best = (sep_tri, Axis::Triangle);
    if face != usize::MAX && sep_face > sep_tri + FACE_REL_TOL * sep_tri.abs() + FACE_ABS_TOL {
        best = (sep_face, Axis::Face(face));
    }
    if sep_edge > best.0 + EDGE_REL_TOL * best.0.abs() + EDGE_ABS_TOL {
        best = (sep_edge, Axis::Edge(edge.0, edge.1));
    }
    out.count = 0;
    match best.1 {
        Axis::Triangle => triangle_reference(p, radius, t, speculative, out),
        Axis::Face(f) => face_reference(p, f, radius, t, speculative, out),
        Axis::Edge(i, e) => {
            let (a0, a1) = p.support_edge(-edge_axis, i);
            let (b0, b1) = (t.v[e], t.v[(e + 1) % 3]);
            let (s, u) = closest_segment_segment(a0, a1, b0, b1);
            let (pa, pb) = (a0 + s * (a1 - a0), b0 + u * (b1 - b0));
            let sep = (pa - pb).dot(edge_axis) - radius;
            if sep <= speculative {
                out.normal = edge_axis;
                let code = 128 + (3 * i as u32 + e as u32) % 128;
                out.push(pb + (0.5 * sep) * edge_axis, sep, triangle_id(t.index, code));
            }
        }
    }
    out.count > 0
}

/// Sutherland–Hodgman: keeps the part of `input` with `dot(m, x − o) >= 0`. Each vertex
/// carries a code; a vertex made by the cut gets `cut`.
fn clip(input: &[(Vec3, u32)], out: &mut [(Vec3, u32); CLIP_CAP], m: Vec3, o: Vec3, cut: u32) -> usize {
    let mut k = 0;
    let count = input.len();
    for i in 0..count {
        let (a, ia) = input[i];
        let (b, _) = input[(i + 1) % count];
        let (da, db) = (m.dot(a - o), m.dot(b - o));
        if da >= 0.0 && k < CLIP_CAP {
            out[k] = (a, ia);
            k += 1;
        }
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) && k < CLIP_CAP {
            out[k] = (a + (da / (da - db)) * (b - a), cut);
            k += 1;
        }
    }
    k
}

/// Bit marking a clip code (not a vertex id of the polygon).
const CUT: u32 = 1 << 30;

/// The triangle is the reference face: `p`'s incident face clipped by the triangle's sides.
fn triangle_reference<P: Polytope>(p: &P, radius: f32, t: &Triangle, speculative: f32, out: &mut TriContact) {
    let n = t.n;
    let mut bufs = [[(Vec3::ZERO, 0u32); CLIP_CAP]; 2];
    let mut count = p.face_polygon(p.incident_face(n), &mut bufs[0]);
    for i in 0..3 {
        let m = n.cross(t.v[(i + 1) % 3] - t.v[i]);
        let [src, dst] = &mut bufs;
        let (src, dst) = if i % 2 == 0 { (src, dst) } else { (dst, src) };
        count = clip(&src[..count], dst, m, t.v[i], CUT | i as u32);
        if count == 0 {
            return;
        }
    }
    out.normal = n;
    let d0 = n.dot(t.v[0]);
    for (k, &(x, id)) in bufs[1][..count].iter().enumerate() {
        let sep = n.dot(x) - d0 - radius;
        if sep > speculative {
            continue;
        }
        let id = if id & CUT != 0 {
            triangle_id(t.index, 32 + (id & 3) * 16 + (k as u32 & 15))
        } else {
            id
        };
        out.push(x - (radius + 0.5 * sep) * n, sep, id);
    }
}

/// Face `f` of `p` is the reference face: the triangle clipped by its sides.
fn face_reference<P: Polytope>(p: &P, f: usize, radius: f32, t: &Triangle, speculative: f32, out: &mut TriContact) {
    let (m, off) = p.face_plane(f);
    let mut poly = [(Vec3::ZERO, 0u32); CLIP_CAP];
    let sides = p.face_polygon(f, &mut poly);
    let mut bufs = [[(Vec3::ZERO, 0u32); CLIP_CAP]; 2];
    for (i, v) in t.v.iter().enumerate() {
        bufs[0][i] = (*v, i as u32);
    }
    let mut count = 3;
    for i in 0..sides {
        let (v0, v1) = (poly[i].0, poly[(i + 1) % sides].0);
        let inward = m.cross(v1 - v0);
        let [src, dst] = &mut bufs;
        let (src, dst) = if i % 2 == 0 { (src, dst) } else { (dst, src) };
        count = clip(&src[..count], dst, inward, v0, CUT | (i as u32 & 0xFF));
        if count == 0 {
            return;
        }
    }
    out.normal = -m;
    for (k, &(x, id)) in bufs[sides % 2][..count].iter().enumerate() {
        let sep = m.dot(x) - off - radius;
        if sep > speculative {
            continue;
        }
        let code = if id & CUT != 0 {
            64 + (id & 31) * 2 + (k as u32 & 1)
        } else {
            96 + id
        };
        out.push(x - (0.5 * sep) * m, sep, triangle_id(t.index, code));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `polytope_triangle` as it was, one edge pair at a time (the reference of
    /// `edge_axes_match_one_at_a_time`).
    fn polytope_triangle_scalar<P: Polytope>(
        p: &P,
        radius: f32,
        t: &Triangle,
        speculative: f32,
        out: &mut TriContact,
    ) -> bool {
        let n = t.n;
        let d0 = n.dot(t.v[0]);
        let (lo, hi) = p.interval(n);
        if hi + radius < d0 {
            return false;
        }
        let sep_tri = lo - d0 - radius;
        if sep_tri > speculative {
            return false;
        }
        let (mut sep_face, mut face) = (f32::MIN, usize::MAX);
        for f in 0..p.face_count() {
            let (m, off) = p.face_plane(f);
            let tmin = t.v[0].dot(m).min(t.v[1].dot(m)).min(t.v[2].dot(m));
            let s = tmin - off - radius;
            if s > speculative {
                return false;
            }
            if s > sep_face && axis_allowed(-m, t) {
                (sep_face, face) = (s, f);
            }
        }
        let (mut sep_edge, mut edge, mut edge_axis) = (f32::MIN, (0, 0), Vec3::ZERO);
        let center = p.center();
        for i in 0..p.edge_direction_count() {
            let d = p.edge_direction(i);
            for e in 0..3 {
                let te = t.v[(e + 1) % 3] - t.v[e];
                let mut a = d.cross(te);
                let len_sq = a.length_squared();
                if len_sq < 1.0e-10 * te.length_squared() {
                    continue;
                }
                a /= len_sq.sqrt();
                if a.dot(center - t.v[e]) < 0.0 {
                    a = -a;
                }
                let (plo, phi) = p.interval(a);
                let tp = t.v.map(|v| v.dot(a));
                let (tlo, thi) = (tp[0].min(tp[1]).min(tp[2]), tp[0].max(tp[1]).max(tp[2]));
                let s = plo - thi - radius;
                let s_rev = tlo - phi - radius;
                if s.max(s_rev) > speculative {
                    return false;
                }
                if s > sep_edge && t.flags & (1 << e) != 0 && a.dot(n) >= 0.0 && a.dot(n) < FACE_AXIS_COS {
                    (sep_edge, edge, edge_axis) = (s, (i, e), a);
                }
            }
        }
        let separations = Separations {
            triangle: sep_tri,
            face: (sep_face, face),
            edge: (sep_edge, edge, edge_axis),
        };
        manifold_from_best_axis(p, radius, t, speculative, &separations, out)
    }

    /// The edge pairs four at a time change nothing: random boxes and hulls (rounded or
    /// not, scaled) against random triangles around them — resting, overlapping, apart,
    /// edge-on, with every combination of active edges, and triangles with an edge along
    /// one of the shape's edge directions (parallel pairs) — give the same answer and the
    /// same contact, bit for bit, as one pair at a time, edge contacts among them.
    #[test]
    fn edge_axes_match_one_at_a_time() {
        use super::super::hull_view::HullView;
        use crate::collision::hull::builder::{build, HullSettings};
        let mut rnd = crate::math::test_rnd::Rnd(0xa54f_f53a_5f1d_36f1);
        let (mut hits, mut edges) = (0, 0);
        for trial in 0..20_000 {
            let pts: Vec<Vec3> = (0..6 + trial % 13)
                .map(|_| rnd.point(Vec3::new(0.5, 0.4, 0.45)))
                .collect();
            let hull = build(&pts, &HullSettings::default()).unwrap();
            let half = Vec3::new(0.1 + rnd.f(), 0.1 + rnd.f(), 0.1 + rnd.f()) * 0.5;
            let c = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.8, rnd.f() - 0.5);
            let mut v = [0, 1, 2].map(|_| c + 1.5 * Vec3::new(rnd.f() - 0.5, 0.3 * (rnd.f() - 0.5), rnd.f() - 0.5));
            if trial % 7 == 0 {
                // An edge along the box's x axis (parallel to one of its edge directions).
                v[1] = v[0] + Vec3::new(0.8, 0.0, 0.0);
            }
            let nrm = (v[1] - v[0]).cross(v[2] - v[0]);
            if nrm.length() < 1e-4 {
                continue;
            }
            let t = Triangle {
                v,
                n: nrm.normalize(),
                flags: (trial % 8) as u8,
                index: trial as u32,
            };
            let radius = if trial % 3 == 0 { 0.02 } else { 0.0 };
            let speculative = [0.0, 0.02, 0.1][trial % 3];
            let (mut a, mut b) = (TriContact::EMPTY, TriContact::EMPTY);
            let (ra, rb) = if trial % 2 == 0 {
                let view = HullView::new(&hull, 0.5 + rnd.f());
                (
                    polytope_triangle(&view, radius, &t, speculative, &mut a),
                    polytope_triangle_scalar(&view, radius, &t, speculative, &mut b),
                )
            } else {
                let bx = LocalBox(half);
                (
                    polytope_triangle(&bx, radius, &t, speculative, &mut a),
                    polytope_triangle_scalar(&bx, radius, &t, speculative, &mut b),
                )
            };
            assert_eq!(ra, rb, "trial {trial}");
            if ra {
                assert_eq!(format!("{a:?}"), format!("{b:?}"), "trial {trial}");
                let bits = |c: &TriContact| c.normal.to_array().map(f32::to_bits);
                assert_eq!(bits(&a), bits(&b), "trial {trial}");
                hits += 1;
                edges += (a.count == 1 && a.points[0].id & (1 << 31) != 0 && (a.points[0].id & 0xff) >= 128) as usize;
            }
        }
        assert!(hits > 3000 && edges > 50, "{hits} contacts, {edges} edge contacts");
    }

    /// `polytope_plane_rejects` (the test `mesh.rs` runs before working out a heightfield
    /// triangle's edge flags) rejects only triangles `polytope_triangle` returns false for,
    /// whatever their flags, and leaves it nothing to write: random boxes and hulls (some
    /// rounded) against random triangles above, through and below them.
    #[test]
    fn plane_rejection_is_the_first_test() {
        use super::super::hull_view::HullView;
        use crate::collision::hull::builder::{build, HullSettings};
        let mut rnd = crate::math::test_rnd::Rnd(0x9b05_688c_2b3e_6c1f);
        let (mut rejected, mut kept) = (0, 0);
        for trial in 0..5000 {
            let pts: Vec<Vec3> = (0..6 + trial % 13)
                .map(|_| rnd.point(Vec3::new(0.5, 0.4, 0.45)))
                .collect();
            let hull = build(&pts, &HullSettings::default()).unwrap();
            let half = Vec3::new(0.1 + rnd.f(), 0.1 + rnd.f(), 0.1 + rnd.f()) * 0.5;
            let c = Vec3::new(rnd.f() - 0.5, 1.2 * (rnd.f() - 0.5), rnd.f() - 0.5);
            let v = [0, 1, 2].map(|_| c + 1.5 * Vec3::new(rnd.f() - 0.5, 0.3 * (rnd.f() - 0.5), rnd.f() - 0.5));
            let nrm = (v[1] - v[0]).cross(v[2] - v[0]);
            if nrm.length() < 1e-4 {
                continue;
            }
            let radius = if trial % 3 == 0 { 0.02 } else { 0.0 };
            let speculative = [0.0, 0.02, 0.1][trial % 3];
            for flags in [0, 0b111] {
                let t = Triangle {
                    v,
                    n: nrm.normalize(),
                    flags,
                    index: trial as u32,
                };
                let mut out = TriContact::EMPTY;
                let (rejects, hit) = if trial % 2 == 0 {
                    let view = HullView::new(&hull, 0.5 + rnd.f());
                    (
                        polytope_plane_rejects(&view, radius, t.v[0], t.n, speculative),
                        polytope_triangle(&view, radius, &t, speculative, &mut out),
                    )
                } else {
                    let bx = LocalBox(half);
                    (
                        polytope_plane_rejects(&bx, radius, t.v[0], t.n, speculative),
                        polytope_triangle(&bx, radius, &t, speculative, &mut out),
                    )
                };
                if rejects {
                    assert!(!hit, "trial {trial}: rejected triangle touches");
                    assert_eq!(format!("{out:?}"), format!("{:?}", TriContact::EMPTY), "trial {trial}");
                    rejected += 1;
                } else {
                    kept += 1;
                }
            }
        }
        assert!(
            rejected > 2000 && kept > 2000,
            "{rejected} rejected, {kept} tested in full"
        );
    }

    fn flat(flags: u8) -> Triangle {
        Triangle {
            v: [Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0)],
            n: Vec3::Y,
            flags,
            index: 7,
        }
    }

    #[test]
    fn closest_point_features() {
        let t = flat(0);
        assert_eq!(
            closest_on_triangle(Vec3::new(-1.0, 1.0, -1.0), &t.v).1,
            Feature::Vertex(0)
        );
        assert_eq!(closest_on_triangle(Vec3::new(-1.0, 1.0, 0.5), &t.v).1, Feature::Edge(0));
        assert_eq!(closest_on_triangle(Vec3::new(0.5, 1.0, 2.0), &t.v).1, Feature::Edge(1));
        assert_eq!(closest_on_triangle(Vec3::new(0.5, 1.0, 0.0), &t.v).1, Feature::Edge(2));
        let (q, f) = closest_on_triangle(Vec3::new(0.2, 1.0, 0.7), &t.v);
        assert_eq!(f, Feature::Face);
        assert!((q - Vec3::new(0.2, 0.0, 0.7)).length() < 1e-6);
    }

    #[test]
    fn sphere_on_inactive_edge_gets_face_normal() {
        let mut out = TriContact::EMPTY;
        // Centre beyond edge 0 (x < 0), 0.3 above the plane; radius 0.5.
        let c = Vec3::new(-0.1, 0.3, 0.5);
        assert!(sphere_triangle(c, 0.5, &flat(0), 0.0, &mut out));
        assert!((out.normal - Vec3::Y).length() < 1e-6);
        assert!((out.points[0].separation + 0.2).abs() < 1e-6);
        // Active edge: the edge's own normal, separation from the edge.
        assert!(sphere_triangle(c, 0.5, &flat(0b111), 0.0, &mut out));
        let d = Vec3::new(-0.1, 0.3, 0.0);
        assert!((out.normal - d.normalize()).length() < 1e-6);
        assert!((out.points[0].separation - (d.length() - 0.5)).abs() < 1e-6);
        // Behind the triangle: nothing.
        assert!(!sphere_triangle(
            Vec3::new(0.3, -0.6, 0.6),
            0.5,
            &flat(0),
            0.0,
            &mut out
        ));
    }

    #[test]
    fn box_resting_on_triangle_corner_ids() {
        let mut out = TriContact::EMPTY;
        // A small box (half 0.1) resting inside the triangle, 1 mm deep.
        let t = Triangle {
            v: [
                Vec3::new(-1.0, -0.099, -1.0),
                Vec3::new(-1.0, -0.099, 3.0),
                Vec3::new(3.0, -0.099, -1.0),
            ],
            n: Vec3::Y,
            flags: 0,
            index: 3,
        };
        assert!(polytope_triangle(&LocalBox(Vec3::splat(0.1)), 0.0, &t, 0.01, &mut out));
        assert_eq!(out.count, 4);
        assert!((out.normal - Vec3::Y).length() < 1e-6);
        let mut ids: Vec<u32> = out.points[..4].iter().map(|p| p.id).collect();
        ids.sort();
        assert_eq!(ids, [0, 1, 4, 5]);
        for p in &out.points[..4] {
            assert!((p.separation + 0.001).abs() < 1e-5, "{}", p.separation);
        }
    }

    #[test]
    fn box_over_flat_seam_keeps_face_normal() {
        // The box, 1 cm deep, overlaps the triangle by 2 mm past an inactive edge: the box's
        // side face (2 mm) would beat the face normal (1 cm) but is not allowed there.
        let mut out = TriContact::EMPTY;
        let t = Triangle {
            v: [
                Vec3::new(0.098, -0.09, -1.0),
                Vec3::new(0.098, -0.09, 1.0),
                Vec3::new(2.0, -0.09, 0.0),
            ],
            n: Vec3::Y,
            flags: 0,
            index: 0,
        };
        assert!(polytope_triangle(&LocalBox(Vec3::splat(0.1)), 0.0, &t, 0.01, &mut out));
        assert!((out.normal - Vec3::Y).length() < 1e-6);
        assert!(out.count >= 2);
        for p in &out.points[..out.count] {
            assert!((p.separation + 0.01).abs() < 1e-5);
            assert!(p.point.x >= 0.098 - 1e-5);
        }
        // With the edge active (an open border), the side contact wins: normal −x, 2 mm.
        let active = Triangle { flags: 0b111, ..t };
        assert!(polytope_triangle(
            &LocalBox(Vec3::splat(0.1)),
            0.0,
            &active,
            0.01,
            &mut out
        ));
        assert!((out.normal - Vec3::NEG_X).length() < 1e-6, "{}", out.normal);
        assert!(out.points[..out.count]
            .iter()
            .all(|p| (p.separation + 0.002).abs() < 1e-5));
    }
}
