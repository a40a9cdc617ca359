//! A convex shape against a triangle mesh or heightfield: several manifolds.
//!
//! The triangles under the shape's box (grown by the speculative distance) come from the
//! mesh's BVH or straight from the heightfield's grid, are placed in the *target* frame
//! (world space for spheres and capsules, the shape's own frame for boxes and hulls) and
//! meet the shape one by one (`triangle.rs`). Their points are folded into *groups* by
//! normal, Jolt's manifold reduction: a triangle's contact joins the group whose normal is
//! within `MERGE_ANGLE` of its own, else starts one (at most `MAX_MESH_MANIFOLDS`; beyond
//! that it joins the closest). Within a group a point at the same place (`DEDUPE_DISTANCE`)
//! or with the same id as one already there is kept once, the deeper; a full group is
//! reduced to four points. Each group becomes one manifold of at most four points (the
//! deepest, then the points spanning the largest area, chosen among the points that bear
//! load before the speculative ones: `reduce_in_place`), and one solver constraint.
//!
//! A box resting on a flat floor of many triangles therefore gets one four-point manifold,
//! like on a plane; in a V-shaped crease it gets one per side.

use super::triangle::{
    capsule_triangle, polytope_plane_rejects, polytope_triangle, sphere_triangle, LocalBox, TriContact, Triangle,
};
use super::{Manifold, ManifoldPoint, MAX_MANIFOLD_POINTS};
use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::shape::Geometry;
use crate::math::{Mat3, Transform, Vec3};

/// Most manifolds one shape has against one mesh or heightfield.
pub const MAX_MESH_MANIFOLDS: usize = 8;
/// Contacts whose normals differ by less than this (degrees) share a manifold.
pub const MERGE_ANGLE: f32 = 5.0;
const MERGE_COS: f32 = 0.996_194_7;
/// Points of a group closer than this (m) are one point.
pub const DEDUPE_DISTANCE: f32 = 1.0e-3;
/// Points a group holds before it is reduced to four.
const GROUP_CAP: usize = 16;
/// Depth difference (m) under which reduction treats points as equally deep.
const REDUCE_DEPTH_TOL: f32 = 0.001;

/// The manifolds of one shape against a mesh or heightfield (normals from the shape, A, to
/// the mesh, B), in the order their groups formed.
#[derive(Clone, Copy, Debug)]
pub struct MeshManifolds {
    pub manifolds: [Manifold; MAX_MESH_MANIFOLDS],
    pub count: usize,
}

impl MeshManifolds {
    pub const EMPTY: MeshManifolds = MeshManifolds {
        manifolds: [Manifold::EMPTY; MAX_MESH_MANIFOLDS],
        count: 0,
    };

    pub fn as_slice(&self) -> &[Manifold] {
        &self.manifolds[..self.count]
    }
}

#[derive(Clone, Copy)]
struct Group {
    /// From the triangles to the shape, target frame: the normal of the deepest contact.
    normal: Vec3,
    deepest: f32,
    points: [ManifoldPoint; GROUP_CAP],
    count: usize,
}

struct Groups {
    groups: [Group; MAX_MESH_MANIFOLDS],
    count: usize,
}

impl Groups {
    fn new() -> Groups {
        Groups {
            groups: [Group {
                normal: Vec3::ZERO,
                deepest: f32::MAX,
                points: [ManifoldPoint::default(); GROUP_CAP],
                count: 0,
            }; MAX_MESH_MANIFOLDS],
            count: 0,
        }
    }

    fn add(&mut self, c: &TriContact) {
        if c.count == 0 {
            return;
        }
        let (mut best, mut best_cos) = (usize::MAX, f32::MIN);
        for (i, g) in self.groups[..self.count].iter().enumerate() {
            let cos = g.normal.dot(c.normal);
            if cos > best_cos {
                (best, best_cos) = (i, cos);
            }
        }
        let gi = if best_cos >= MERGE_COS || self.count == MAX_MESH_MANIFOLDS {
            best
        } else {
            self.groups[self.count].count = 0;
            self.groups[self.count].deepest = f32::MAX;
            self.groups[self.count].normal = c.normal;
            self.count += 1;
            self.count - 1
        };
        let g = &mut self.groups[gi];
        let deepest = c.points[..c.count].iter().fold(f32::MAX, |m, p| m.min(p.separation));
        if deepest < g.deepest {
            (g.deepest, g.normal) = (deepest, c.normal);
        }
        for p in &c.points[..c.count] {
            g.insert(*p);
        }
    }
}

impl Group {
    fn insert(&mut self, p: ManifoldPoint) {
        let d2 = DEDUPE_DISTANCE * DEDUPE_DISTANCE;
        if let Some(q) = self.points[..self.count]
            .iter_mut()
            .find(|q| q.id == p.id || (q.point - p.point).length_squared() <= d2)
        {
            if p.separation < q.separation {
                *q = p;
            }
            return;
        }
        if self.count == GROUP_CAP {
            self.count = reduce_in_place(&mut self.points, self.normal);
        }
        self.points[self.count] = p;
        self.count += 1;
    }
}

#[inline]
fn cross_n(o: Vec3, a: Vec3, b: Vec3, n: Vec3) -> f32 {
    (a - o).cross(b - o).dot(n)
}

/// Keeps at most four of `points` (normal `n`) at the front of the slice and returns how
/// many. Points that bear load — touching, overlapping or within `SUPPORT_GAP` of it — come
/// first: with four or more of them the four are chosen among those alone
/// (`reduce_supporting`) and the speculative points (gaps up to the speculative distance)
/// are dropped; with fewer, all are kept and the speculative points farthest from them fill
/// the rest.
///
/// A group merges triangles up to `MERGE_ANGLE` apart, so on a curved terrain a box face
/// meets a few triangle vertices or a ridge line and hangs centimetres above the rest: the
/// area rule alone kept the corners in the air and dropped the second ridge point, and the
/// box rocked on the one point left for ever (measured: a box across a 1° ridge never
/// slept; of the 1,000-body drop on the hilly terrain, 70 of the 250 boxes and 48 of the 250
/// hulls were still awake after 20 s, against 4 and 1 now).
pub fn reduce_in_place(points: &mut [ManifoldPoint], n: Vec3) -> usize {
    let count = points.len();
    if count <= MAX_MANIFOLD_POINTS {
        return count;
    }
    // Supporting points to the front, in their order.
    let mut supporting = 0;
    for i in 0..count {
        if points[i].separation <= SUPPORT_GAP {
            points[supporting..=i].rotate_right(1);
            supporting += 1;
        }
    }
    if supporting >= MAX_MANIFOLD_POINTS {
        return reduce_supporting(&mut points[..supporting], n);
    }
    // Fewer than four bear load: keep them, then add the speculative point farthest (in the
    // contact plane) from those kept, until four.
    let mut kept = supporting;
    while kept < MAX_MANIFOLD_POINTS {
        let (mut best, mut best_d) = (usize::MAX, f32::NEG_INFINITY);
        for i in kept..count {
            let d = points[..kept].iter().fold(f32::MAX, |m, q| {
                m.min((points[i].point - q.point).reject_from_normalized(n).length_squared())
            });
            let d = if kept == 0 { -points[i].separation } else { d };
            if d > best_d {
                (best, best_d) = (i, d);
            }
        }
        points.swap(kept, best);
        kept += 1;
    }
    kept
}

/// Gap (m) under which a point counts as bearing load in `reduce_in_place` (resting contacts
/// sit about `linear_slop` deep).
const SUPPORT_GAP: f32 = 0.001;

/// The four of `points` spanning the most: the deepest (points within `REDUCE_DEPTH_TOL` of
/// it count as equally deep, and the one farthest from the centroid wins), the farthest from
/// it, the one making the largest triangle with them, then the one adding the most area
/// outside that triangle.
fn reduce_supporting(points: &mut [ManifoldPoint], n: Vec3) -> usize {
    let count = points.len();
    if count <= MAX_MANIFOLD_POINTS {
        return count;
    }
    let c = points.iter().fold(Vec3::ZERO, |s, p| s + p.point) / count as f32;
    let min_sep = points.iter().fold(f32::MAX, |m, p| m.min(p.separation));
    let mut i0 = 0;
    let mut best = -1.0f32;
    for (i, p) in points.iter().enumerate() {
        if p.separation <= min_sep + REDUCE_DEPTH_TOL {
            let d = (p.point - c).reject_from_normalized(n).length_squared();
            if d > best {
                (i0, best) = (i, d);
            }
        }
    }
    let p0 = points[i0].point;
    let (mut i1, mut best) = (usize::MAX, 1.0e-10f32);
    for (i, p) in points.iter().enumerate() {
        let d = (p.point - p0).reject_from_normalized(n).length_squared();
        if d > best {
            (i1, best) = (i, d);
        }
    }
    let keep = if i1 == usize::MAX {
        [i0, usize::MAX, usize::MAX, usize::MAX]
    } else {
        let p1 = points[i1].point;
        let (mut i2, mut best, mut area) = (usize::MAX, 1.0e-10f32, 0.0f32);
        for (i, p) in points.iter().enumerate() {
            let a = cross_n(p0, p1, p.point, n);
            if a.abs() > best {
                (i2, best, area) = (i, a.abs(), a);
            }
        }
        if i2 == usize::MAX {
            [i0, i1, usize::MAX, usize::MAX]
        } else {
            let p2 = points[i2].point;
            let orient = if area >= 0.0 { 1.0 } else { -1.0 };
            let (mut i3, mut best) = (usize::MAX, 1.0e-10f32);
            for (i, p) in points.iter().enumerate() {
                let out = (-orient * cross_n(p0, p1, p.point, n))
                    .max(-orient * cross_n(p1, p2, p.point, n))
                    .max(-orient * cross_n(p2, p0, p.point, n));
                if out > best {
                    (i3, best) = (i, out);
                }
            }
            [i0, i1, i2, i3]
        }
    };
    let kept: [Option<ManifoldPoint>; 4] = keep.map(|i| (i != usize::MAX).then(|| points[i]));
    let mut k = 0;
    for p in kept.into_iter().flatten() {
        points[k] = p;
        k += 1;
    }
    k
}

/// The placement of a mesh or heightfield: world = `r · (scale ∘ x) + p`.
struct Placement {
    r: Mat3,
    p: Vec3,
    scale: Vec3,
}

/// The shape's frame for the triangle tests: target = `rot_t · (world − origin)`.
#[derive(Clone, Copy)]
struct Target {
    rot_t: Mat3,
    origin: Vec3,
}

impl Target {
    fn world() -> Target {
        Target {
            rot_t: Mat3::IDENTITY,
            origin: Vec3::ZERO,
        }
    }
}

/// The convex shape in its target frame.
enum Convex<'a> {
    Sphere(Vec3, f32),
    Capsule(Vec3, Vec3, f32),
    Box(LocalBox),
    Hull(super::hull_view::HullView<'a>),
}

impl Convex<'_> {
    #[inline]
    fn collide(&self, t: &Triangle, speculative: f32, out: &mut TriContact) -> bool {
        match self {
            Convex::Sphere(c, r) => sphere_triangle(*c, *r, t, speculative, out),
            Convex::Capsule(a, b, r) => capsule_triangle(*a, *b, *r, t, speculative, out),
            Convex::Box(b) => polytope_triangle(b, 0.0, t, speculative, out),
            Convex::Hull(h) => polytope_triangle(h, h.radius(), t, speculative, out),
        }
    }

    /// Whether `collide` returns false for a triangle with corner `v0` and normal `n` on its
    /// first test, which reads neither the edge flags nor `out` (boxes and hulls:
    /// `polytope_plane_rejects`; spheres and capsules are always tested in full).
    #[inline]
    fn rejects_by_plane(&self, v0: Vec3, n: Vec3, speculative: f32) -> bool {
        match self {
            Convex::Box(b) => polytope_plane_rejects(b, 0.0, v0, n, speculative),
            Convex::Hull(h) => polytope_plane_rejects(h, h.radius(), v0, n, speculative),
            Convex::Sphere(..) | Convex::Capsule(..) => false,
        }
    }
}

/// Shape A (convex, at `xf_a`) against mesh or heightfield B (at `xf_b`): the manifolds,
/// normals from A to B, points in world space.
pub fn collide_triangles(
    store: &GeometryStore,
    a: &Geometry,
    xf_a: &Transform,
    b: &Geometry,
    xf_b: &Transform,
    speculative: f32,
    out: &mut MeshManifolds,
) {
    out.count = 0;
    let (convex, target) = match *a {
        Geometry::Sphere { center, radius } => (Convex::Sphere(xf_a.apply(center), radius), Target::world()),
        Geometry::Capsule { a: p, b: q, radius } => {
            (Convex::Capsule(xf_a.apply(p), xf_a.apply(q), radius), Target::world())
        }
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => (
            Convex::Box(LocalBox(half_extents)),
            Target {
                rot_t: Mat3::from_quat(xf_a.q * rotation).transpose(),
                origin: xf_a.apply(center),
            },
        ),
        Geometry::Hull { hull, local, scale } => (
            Convex::Hull(super::hull_view::HullView::new(store.hull_at(hull.index), scale)),
            Target {
                rot_t: Mat3::from_quat(xf_a.q * local.q).transpose(),
                origin: xf_a.apply(local.p),
            },
        ),
        _ => return,
    };
    let query = a.aabb(store, xf_a).expanded(speculative);
    let mut groups = Groups::new();
    let mut contact = TriContact::EMPTY;
    match *b {
        Geometry::Mesh { mesh, local, scale } => {
            let place = placement(xf_b, &local, scale);
            let m = store.mesh_at(mesh.index);
            // Mesh frame (unscaled) to target frame.
            let to_target = target.rot_t * place.r * Mat3::from_diagonal(place.scale);
            let offset = target.rot_t * (place.p - target.origin);
            // Element by element rather than `array::map`, whose closure the compiler may
            // leave out of line (a call per vertex); the same arithmetic.
            let placed =
                |[a, b, c]: [Vec3; 3]| [to_target * a + offset, to_target * b + offset, to_target * c + offset];
            m.query(&local_box(&query, &place), |t| {
                let v = placed(m.triangle(t));
                let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
                if !n.is_finite() {
                    return true;
                }
                let tri = Triangle {
                    v,
                    n,
                    flags: m.edge_flags(t),
                    index: t,
                };
                if convex.collide(&tri, speculative, &mut contact) {
                    groups.add(&contact);
                }
                true
            });
        }
        Geometry::Heightfield {
            heightfield,
            local,
            scale,
        } => {
            let place = placement(xf_b, &local, scale);
            let hf = store.heightfield_at(heightfield.index);
            // Scaled heightfield frame to target frame.
            let to_target = target.rot_t * place.r;
            let offset = target.rot_t * (place.p - target.origin);
            let columns = hf.columns() - 1;
            let placed =
                |[a, b, c]: [Vec3; 3]| [to_target * a + offset, to_target * b + offset, to_target * c + offset];
            hf.query(&local_box(&query, &place), |row, column| {
                for k in 0..2 {
                    let (v, n) = hf.triangle_plane(row, column, k, place.scale);
                    let (tv, tn) = (placed(v), to_target * n);
                    // A triangle the shape's first test rejects needs no edge flags (the
                    // test does not read them, and it would return nothing).
                    if convex.rejects_by_plane(tv[0], tn, speculative) {
                        continue;
                    }
                    let tri = Triangle {
                        v: tv,
                        n: tn,
                        flags: hf.triangle_flags(row, column, k, place.scale, &v, n),
                        index: 2 * (row * columns + column) + k,
                    };
                    if convex.collide(&tri, speculative, &mut contact) {
                        groups.add(&contact);
                    }
                }
                true
            });
        }
        _ => return,
    }
    // Groups to world-space manifolds, normals from A (the shape) to B (the triangles).
    let rot = target.rot_t.transpose();
    for g in groups.groups[..groups.count].iter_mut() {
        let kept = reduce_in_place(&mut g.points[..g.count], g.normal);
        let m = &mut out.manifolds[out.count];
        *m = Manifold::EMPTY;
        m.normal = -(rot * g.normal).normalize();
        for p in &g.points[..kept] {
            m.points[m.count] = ManifoldPoint {
                point: rot * p.point + target.origin,
                ..*p
            };
            m.count += 1;
        }
        out.count += 1;
    }
}

fn placement(xf: &Transform, local: &Transform, scale: Vec3) -> Placement {
    Placement {
        r: Mat3::from_quat(xf.q * local.q),
        p: xf.apply(local.p),
        scale,
    }
}

/// A world box in the mesh's (or heightfield's) own unscaled frame.
fn local_box(b: &Aabb, place: &Placement) -> Aabb {
    let rt = place.r.transpose();
    let c = rt * (b.center() - place.p);
    let e = b.extents();
    let e = Vec3::new(rt.row(0).abs().dot(e), rt.row(1).abs().dot(e), rt.row(2).abs().dot(e));
    Aabb::from_center_extents(c / place.scale, e / place.scale)
}

/// The deepest of the manifolds (one manifold for callers that take one: particles, soft
/// bodies), or an empty one.
pub fn deepest(m: &MeshManifolds) -> Manifold {
    let mut best = Manifold::EMPTY;
    let mut best_sep = f32::MAX;
    for x in m.as_slice() {
        let s = x.points().iter().fold(f32::MAX, |a, p| a.min(p.separation));
        if s < best_sep {
            (best, best_sep) = (*x, s);
        }
    }
    best
}
