//! Convex hulls: a polyhedron built once from a point cloud (`builder`, quickhull) and
//! instanced by any number of shapes through the world's [`GeometryStore`].
//!
//! Layout (one hull, all arrays small and contiguous):
//!
//! * `vertices` — at most [`MAX_HULL_VERTICES`] points in the hull's own frame;
//! * `planes` — one outward unit normal and offset per face (`dot(n, p) <= offset` inside);
//!   every vertex satisfies every plane (offsets are the support values of the vertices);
//! * `faces` — each face is a run `first .. first + count` of `half_edges`, in
//!   counter-clockwise order seen from outside; the next half-edge of a face is the
//!   following one in its run (wrapping), so no `next` index is stored;
//! * `half_edges` — `origin` vertex, `twin` half-edge and `face`;
//! * `edges` — one half-edge per undirected edge, for the separating-axis test;
//! * `edge_directions` — the distinct edge directions (unit, parallel ones once);
//! * `radius` — the convex radius: the shape is the polyhedron Minkowski-summed with a
//!   sphere of this radius (a rounded hull).
//!
//! Mass properties are integrated once at creation (`mass`) at unit density.
//!
//! [`GeometryStore`]: crate::collision::geometry_store::GeometryStore

pub mod builder;
pub mod mass;

use crate::collision::shape::MassProperties;
use crate::math::{Mat3, Vec3};
use crate::simd::{Lanes, F4};

/// Most vertices a hull keeps (indices fit a byte, as in Box2D's and Jolt's hulls).
pub const MAX_HULL_VERTICES: usize = 255;

/// A face plane: `dot(normal, p) <= offset` inside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub normal: Vec3,
    pub offset: f32,
}

impl Plane {
    #[inline]
    pub fn distance(&self, p: Vec3) -> f32 {
        self.normal.dot(p) - self.offset
    }
}

/// A face: its half-edges are `half_edges[first .. first + count]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Face {
    pub first: u16,
    pub count: u16,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HalfEdge {
    /// Vertex the half-edge starts at.
    pub origin: u16,
    /// The opposite half-edge (same edge, other face).
    pub twin: u16,
    pub face: u16,
}

/// An edge for the separating-axis test: its end points (vertex indices) and the normals of
/// its two faces, which bound the edge's arc on the Gauss map, with their cross product
/// `n2 × n1` (parallel to the edge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeGauss {
    pub n1: Vec3,
    pub n2: Vec3,
    pub n2_x_n1: Vec3,
    pub v0: u16,
    pub v1: u16,
}

/// A convex polyhedron (optionally rounded), immutable once built.
#[derive(Clone, Debug)]
pub struct ConvexHull {
    pub(crate) vertices: Vec<Vec3>,
    pub(crate) planes: Vec<Plane>,
    pub(crate) faces: Vec<Face>,
    pub(crate) half_edges: Vec<HalfEdge>,
    pub(crate) edges: Vec<u16>,
    pub(crate) edge_directions: Vec<Vec3>,
    /// Per entry of `edges`: end points and face normals (`EdgeGauss`).
    pub(crate) edge_gauss: Vec<EdgeGauss>,
    pub(crate) radius: f32,
    /// Mass properties at density 1 about the hull's own origin frame (centre in that frame).
    pub(crate) unit_mass: MassProperties,
    /// Surface area of the core polyhedron (m²).
    pub(crate) area: f32,
    /// Local bounds of the core: min and max corner.
    pub(crate) min: Vec3,
    pub(crate) max: Vec3,
    /// Radius about `unit_mass.center` that bounds the core.
    pub(crate) bound_radius: f32,
    /// The vertices again, four at a time by coordinate (the last block padded with copies
    /// of the last vertex), for `min_dot`.
    pub(crate) lanes: Vec<VertexLanes>,
    /// `edge_gauss`'s arcs again, four edges at a time by coordinate (the last block padded
    /// with zero normals, which no arc crosses), for the hull–hull edge loop.
    pub(crate) edge_lanes: Vec<EdgeLanes>,
}

/// Four edges' Gauss-map arcs by coordinate: the two face normals (`n1`, `n2`) and
/// `n2 × n1` of `EdgeGauss`, as `[x, y, z]` of four lanes each.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct EdgeLanes {
    pub n1: [[f32; 4]; 3],
    pub n2: [[f32; 4]; 3],
    pub n2_x_n1: [[f32; 4]; 3],
}

/// Four vertices by coordinate.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VertexLanes {
    pub x: [f32; 4],
    pub y: [f32; 4],
    pub z: [f32; 4],
}

impl ConvexHull {
    /// Builds the hull's half-edge structure, planes and mass properties from a closed
    /// convex polyhedron: `vertices` and faces given as counter-clockwise (seen from
    /// outside) vertex index loops. The builder (`builder.rs`) is the only caller; it hands
    /// in a valid polyhedron. Returns `None` when the loops do not close into a manifold
    /// surface (an edge without exactly one opposite half-edge).
    pub(crate) fn from_polyhedron(vertices: Vec<Vec3>, face_loops: &[Vec<u16>], radius: f32) -> Option<ConvexHull> {
        let mut faces = Vec::with_capacity(face_loops.len());
        let mut half_edges: Vec<HalfEdge> = Vec::new();
        for (f, lp) in face_loops.iter().enumerate() {
            if lp.len() < 3 {
                return None;
            }
            faces.push(Face {
                first: half_edges.len() as u16,
                count: lp.len() as u16,
            });
            for &v in lp {
                half_edges.push(HalfEdge {
                    origin: v,
                    twin: u16::MAX,
                    face: f as u16,
                });
            }
        }
        if half_edges.len() >= u16::MAX as usize {
            return None;
        }
        // Twins: the half-edge b→a for each a→b.
        let mut by_ends: Vec<(u32, u16)> = Vec::with_capacity(half_edges.len());
        for (f, face) in faces.iter().enumerate() {
            let _ = f;
            for k in 0..face.count {
                let e = face.first + k;
                let n = face.first + (k + 1) % face.count;
                let (a, b) = (half_edges[e as usize].origin, half_edges[n as usize].origin);
                by_ends.push((((a as u32) << 16) | b as u32, e));
            }
        }
        by_ends.sort_unstable();
        if by_ends.windows(2).any(|w| w[0].0 == w[1].0) {
            return None;
        }
        let mut edges = Vec::new();
        for &(key, e) in &by_ends {
            let (a, b) = (key >> 16, key & 0xffff);
            let twin_key = (b << 16) | a;
            let t = by_ends.binary_search_by_key(&twin_key, |x| x.0).ok()?;
            half_edges[e as usize].twin = by_ends[t].1;
            if a < b {
                edges.push(e);
            }
        }
        edges.sort_unstable();
        let mut hull = ConvexHull {
            vertices,
            planes: Vec::new(),
            faces,
            half_edges,
            edges,
            edge_directions: Vec::new(),
            edge_gauss: Vec::new(),
            radius,
            unit_mass: MassProperties::ZERO,
            area: 0.0,
            min: Vec3::ZERO,
            max: Vec3::ZERO,
            bound_radius: 0.0,
            lanes: Vec::new(),
            edge_lanes: Vec::new(),
        };
        hull.lanes = hull
            .vertices
            .chunks(4)
            .map(|c| {
                let at = |k: usize| c[k.min(c.len() - 1)];
                VertexLanes {
                    x: [at(0).x, at(1).x, at(2).x, at(3).x],
                    y: [at(0).y, at(1).y, at(2).y, at(3).y],
                    z: [at(0).z, at(1).z, at(2).z, at(3).z],
                }
            })
            .collect();
        hull.planes = (0..hull.faces.len()).map(|f| hull.fit_plane(f)).collect();
        hull.edge_directions = hull.distinct_edge_directions();
        hull.edge_gauss = hull
            .edges
            .iter()
            .map(|&e| {
                let he = hull.half_edges[e as usize];
                let twin = hull.half_edges[he.twin as usize];
                let n1 = hull.planes[he.face as usize].normal;
                let n2 = hull.planes[twin.face as usize].normal;
                EdgeGauss {
                    n1,
                    n2,
                    n2_x_n1: n2.cross(n1),
                    v0: he.origin,
                    v1: twin.origin,
                }
            })
            .collect();
        hull.edge_lanes = hull
            .edge_gauss
            .chunks(4)
            .map(|c| {
                let mut l = EdgeLanes::default();
                for (k, g) in c.iter().enumerate() {
                    for (axis, (n1, (n2, n))) in
                        l.n1.iter_mut()
                            .zip(l.n2.iter_mut().zip(l.n2_x_n1.iter_mut()))
                            .enumerate()
                    {
                        n1[k] = g.n1[axis];
                        n2[k] = g.n2[axis];
                        n[k] = g.n2_x_n1[axis];
                    }
                }
                l
            })
            .collect();
        let (mp, area) = mass::polyhedron_mass(&hull.vertices, &hull.face_loops_iter());
        hull.area = area;
        hull.unit_mass = if radius > 0.0 {
            mass::rounded_mass(&hull, mp, area)
        } else {
            mp
        };
        hull.min = hull.vertices.iter().fold(Vec3::splat(f32::MAX), |m, v| m.min(*v));
        hull.max = hull.vertices.iter().fold(Vec3::splat(-f32::MAX), |m, v| m.max(*v));
        let c = hull.unit_mass.center;
        hull.bound_radius = hull.vertices.iter().map(|v| (*v - c).length()).fold(0.0, f32::max);
        Some(hull)
    }

    /// Face vertex loops (indices), for integration and export.
    pub(crate) fn face_loops_iter(&self) -> Vec<Vec<u16>> {
        (0..self.faces.len()).map(|f| self.face_vertices(f).collect()).collect()
    }

    /// Vertex indices of face `f`, counter-clockwise seen from outside.
    #[inline]
    pub fn face_vertices(&self, f: usize) -> impl Iterator<Item = u16> + '_ {
        let face = self.faces[f];
        self.half_edges[face.first as usize..(face.first + face.count) as usize]
            .iter()
            .map(|e| e.origin)
    }

    /// Newell's normal of face `f` (the sum of `v_i × v_(i+1)`: twice the area vector),
    /// offset from the support of all vertices, so every
    /// vertex lies on or under every plane.
    fn fit_plane(&self, f: usize) -> Plane {
        let idx: Vec<u16> = self.face_vertices(f).collect();
        let mut n = glam::DVec3::ZERO;
        for k in 0..idx.len() {
            let a = self.vertices[idx[k] as usize].as_dvec3();
            let b = self.vertices[idx[(k + 1) % idx.len()] as usize].as_dvec3();
            n += a.cross(b);
        }
        let normal = n.normalize_or_zero().as_vec3();
        let offset = self.vertices.iter().map(|v| normal.dot(*v)).fold(f32::MIN, f32::max);
        Plane { normal, offset }
    }

    fn distinct_edge_directions(&self) -> Vec<Vec3> {
        let mut out: Vec<Vec3> = Vec::new();
        for &e in &self.edges {
            let (a, b) = self.edge_points(e as usize);
            let d = (b - a).normalize_or_zero();
            if d == Vec3::ZERO {
                continue;
            }
            if !out.iter().any(|o| o.cross(d).length_squared() < 1.0e-8) {
                out.push(d);
            }
        }
        out
    }

    /// End points of half-edge `e` (origin, then the origin of the next half-edge).
    #[inline]
    pub fn edge_points(&self, e: usize) -> (Vec3, Vec3) {
        let he = self.half_edges[e];
        let twin = self.half_edges[he.twin as usize];
        (self.vertices[he.origin as usize], self.vertices[twin.origin as usize])
    }

    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    pub fn planes(&self) -> &[Plane] {
        &self.planes
    }

    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    pub fn half_edges(&self) -> &[HalfEdge] {
        &self.half_edges
    }

    /// One half-edge per undirected edge.
    pub fn edges(&self) -> &[u16] {
        &self.edges
    }

    pub fn edge_gauss(&self) -> &[EdgeGauss] {
        &self.edge_gauss
    }

    pub fn edge_directions(&self) -> &[Vec3] {
        &self.edge_directions
    }

    /// The convex radius (m): the shape is the polyhedron grown by this much.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Volume of the (rounded) shape, m³.
    pub fn volume(&self) -> f32 {
        self.unit_mass.mass
    }

    /// Mass properties at `density` (kg/m³) in the hull's frame.
    pub fn mass_properties(&self, density: f32) -> MassProperties {
        MassProperties {
            mass: self.unit_mass.mass * density,
            center: self.unit_mass.center,
            inertia: self.unit_mass.inertia * density,
        }
    }

    /// Index of the vertex furthest along `d` (the core's support point): the first vertex
    /// (lowest index) of largest `v · d`.
    ///
    /// The vertices are taken four at a time (`lanes`), each lane keeping its first
    /// largest value and its index, then the lanes are merged by value with ties to the
    /// lower index: the same vertex as one vertex at a time in index order, with the same
    /// products (`x·dx + y·dy + z·dz`, no FMA). The last block's padding lanes copy the
    /// last vertex, so they tie with it and lose to its lower index.
    ///
    /// Two passes over the lanes (`F4` registers): the largest product (`max` keeps the
    /// lane's value over a NaN product), then the first vertex whose product, computed the
    /// same way, reaches it (a product at least the largest equals it; NaN never does): the
    /// lowest index of the largest value, without tracking indices per block. When the
    /// largest is `f32::MIN` (every product NaN, or that value itself) the lanes track
    /// their indices as one at a time ties them (`support_index_tracked`).
    #[inline]
    pub fn support_index(&self, d: Vec3) -> usize {
        let (dx, dy, dz) = (F4::splat(d.x), F4::splat(d.y), F4::splat(d.z));
        let dot = |b: &VertexLanes| dx * F4::load(&b.x) + dy * F4::load(&b.y) + dz * F4::load(&b.z);
        let mut m = F4::splat(f32::MIN);
        for b in &self.lanes {
            m = dot(b).max(m);
        }
        let top = m.max(m.swap_halves());
        let top = top.max(top.swap_pairs());
        if top.first() > f32::MIN {
            for (k, b) in self.lanes.iter().enumerate() {
                let hit = dot(b).ge(top).bits();
                if hit != 0 {
                    return 4 * k + hit.trailing_zeros() as usize;
                }
            }
        }
        self.support_index_tracked(d)
    }

    /// `support_index` with each lane keeping its first largest value and its index (as a
    /// float, exact below 2²⁴; one select per block), the lanes then merged by value with
    /// ties to the lower index.
    #[inline(never)]
    fn support_index_tracked(&self, d: Vec3) -> usize {
        let (dx, dy, dz) = (F4::splat(d.x), F4::splat(d.y), F4::splat(d.z));
        let (mut m, mut at) = (F4::splat(f32::MIN), F4::load(&[0.0, 1.0, 2.0, 3.0]));
        let mut base = at;
        for b in &self.lanes {
            let x = dx * F4::load(&b.x) + dy * F4::load(&b.y) + dz * F4::load(&b.z);
            let more = x.gt(m);
            // `x` where `x > m`, else `m` (also for NaN): the select by `more`.
            m = x.max(m);
            at = F4::select(more, base, at);
            base = base + F4::splat(4.0);
        }
        // The lanes merged in the registers: the largest value over the lanes (none holds
        // NaN: `max` keeps `m` for a NaN product), then the lowest index among the lanes
        // holding it — the lanes picked by value with ties to the lower index, in any order.
        // A lane that saw nothing above `f32::MIN` (NaN products) keeps its own number, and
        // such lanes tie: all-NaN gives 0, as one at a time.
        let top = m.max(m.swap_halves());
        let top = top.max(top.swap_pairs());
        let at = F4::select(m.ge(top), at, F4::splat(f32::MAX));
        let at = at.min(at.swap_halves());
        at.min(at.swap_pairs()).first() as usize
    }

    /// Smallest `d · v` over the vertices: the support distance along `−d`, negated. The
    /// vertices are taken four at a time in independent lanes (vectorised), each lane
    /// keeping its own minimum; a minimum does not depend on the order, so the result is
    /// the same on every path.
    #[inline]
    pub(crate) fn min_dot(&self, d: Vec3) -> f32 {
        let (dx, dy, dz) = (F4::splat(d.x), F4::splat(d.y), F4::splat(d.z));
        let mut m = F4::splat(f32::MAX);
        for b in &self.lanes {
            let x = dx * F4::load(&b.x) + dy * F4::load(&b.y) + dz * F4::load(&b.z);
            // `x` where `x < m`, else `m`.
            m = x.min(m);
        }
        let m = m.to_floats();
        let lo = if m[1] < m[0] { m[1] } else { m[0] };
        let hi = if m[3] < m[2] { m[3] } else { m[2] };
        if hi < lo {
            hi
        } else {
            lo
        }
    }

    /// Smallest and largest `v · d` over the vertices (the core's extent along `d`), four
    /// vertices at a time in independent lanes as `min_dot`, with the one-at-a-time
    /// products (`x·dx + y·dy + z·dz`): a minimum and a maximum do not depend on the order,
    /// so the values are those of one vertex at a time (`interval_matches_one_at_a_time`).
    #[inline]
    pub(crate) fn dot_interval(&self, d: Vec3) -> (f32, f32) {
        let (dx, dy, dz) = (F4::splat(d.x), F4::splat(d.y), F4::splat(d.z));
        let (mut lo, mut hi) = (F4::splat(f32::MAX), F4::splat(f32::MIN));
        for b in &self.lanes {
            let x = F4::load(&b.x) * dx + F4::load(&b.y) * dy + F4::load(&b.z) * dz;
            lo = x.min(lo);
            hi = x.max(hi);
        }
        let (lo, hi) = (lo.to_floats(), hi.to_floats());
        let min = |a: f32, b: f32| if b < a { b } else { a };
        let max = |a: f32, b: f32| if b > a { b } else { a };
        (
            min(min(lo[0], lo[1]), min(lo[2], lo[3])),
            max(max(hi[0], hi[1]), max(hi[2], hi[3])),
        )
    }

    /// Bounds of the vertices turned and scaled by `m` (`m * v`), four vertices at a time in
    /// independent lanes, each coordinate with glam's products and sums in glam's order
    /// (`(m.x_axis·x + m.y_axis·y) + m.z_axis·z`): a minimum and a maximum do not depend on
    /// the order, so the bounds are those of one vertex at a time (`Geometry::aabb`; see
    /// `transformed_bounds_match_one_at_a_time`).
    #[inline]
    pub(crate) fn transformed_bounds(&self, m: &Mat3) -> (Vec3, Vec3) {
        // The three rows in one pass over the vertices, in `F4` registers (`x < lo` picks
        // `x`, as `min` does; `x > hi` likewise `max`).
        let row = |r: usize| (F4::splat(m.x_axis[r]), F4::splat(m.y_axis[r]), F4::splat(m.z_axis[r]));
        let rows = [row(0), row(1), row(2)];
        let (mut lo, mut hi) = ([F4::splat(f32::MAX); 3], [F4::splat(f32::MIN); 3]);
        for l in &self.lanes {
            let (x, y, z) = (F4::load(&l.x), F4::load(&l.y), F4::load(&l.z));
            for (r, &(a, b, c)) in rows.iter().enumerate() {
                let v = a * x + b * y + c * z;
                lo[r] = v.min(lo[r]);
                hi[r] = v.max(hi[r]);
            }
        }
        let min = |a: f32, b: f32| if b < a { b } else { a };
        let max = |a: f32, b: f32| if b > a { b } else { a };
        let out: [(f32, f32); 3] = std::array::from_fn(|r| {
            let (lo, hi) = (lo[r].to_floats(), hi[r].to_floats());
            (
                min(min(lo[0], lo[1]), min(lo[2], lo[3])),
                max(max(hi[0], hi[1]), max(hi[2], hi[3])),
            )
        });
        (
            Vec3::new(out[0].0, out[1].0, out[2].0),
            Vec3::new(out[0].1, out[1].1, out[2].1),
        )
    }

    /// Radius about the centre of mass that bounds the core.
    pub fn bound_radius(&self) -> f32 {
        self.bound_radius
    }

    /// Bounds of the core in the hull's frame.
    pub fn local_bounds(&self) -> (Vec3, Vec3) {
        (self.min, self.max)
    }
}

#[cfg(test)]
mod tests {
    use super::builder::{build, HullSettings};
    use super::*;

    /// One vertex at a time in index order: the first vertex of largest `v · d`.
    fn support_index_scalar(h: &ConvexHull, d: Vec3) -> usize {
        let mut best = 0;
        let mut best_d = f32::MIN;
        for (i, v) in h.vertices.iter().enumerate() {
            let x = v.dot(d);
            if x > best_d {
                best_d = x;
                best = i;
            }
        }
        best
    }

    /// `transformed_bounds` gives the bounds of `m * v` one vertex at a time (glam's
    /// product, `Vec3::min`/`max`), bit for bit: random hulls of 4 to 40 points under random
    /// turns and scales, the identity and quarter turns (where products tie or vanish).
    #[test]
    fn transformed_bounds_match_one_at_a_time() {
        let mut r = crate::math::test_rnd::Rnd(0x5be0_cd19_137e_2179);
        for n in 0..600 {
            let pts: Vec<Vec3> = (0..4 + n % 37).map(|_| r.point(Vec3::new(0.6, 0.4, 0.5))).collect();
            let h = build(&pts, &HullSettings::default()).unwrap();
            let q = match n % 5 {
                0 => crate::math::Quat::IDENTITY,
                1 => crate::math::Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
                _ => r.quat(),
            };
            let m = Mat3::from_quat(q) * (0.1 + 3.0 * r.f());
            let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
            for v in h.vertices() {
                let w = m * *v;
                lo = lo.min(w);
                hi = hi.max(w);
            }
            let (l, u) = h.transformed_bounds(&m);
            // Equal values; a zero may differ only in its sign, which no bound comparison sees.
            for (a, b) in [(l, lo), (u, hi)] {
                for k in 0..3 {
                    assert!(
                        a[k] == b[k] && (a[k] == 0.0 || a[k].to_bits() == b[k].to_bits()),
                        "{a} {b}"
                    );
                }
            }
        }
    }

    /// The four-lane `support_index` picks the vertex one at a time does: random clouds
    /// of 4 to 40 points (every padding of the last block) along random directions, the
    /// axes and diagonals (ties on a cube and on hulls of grid points), zero, NaN and
    /// infinite directions.
    #[test]
    fn support_index_matches_one_at_a_time() {
        let mut r = crate::math::test_rnd::Rnd(0x1234_5678_9abc_def1);
        let mut rnd = move || r.f() - 0.5;
        let mut dirs: Vec<Vec3> = vec![
            Vec3::ZERO,
            Vec3::splat(f32::NAN),
            Vec3::new(f32::NAN, 1.0, 0.0),
            // Infinite products, and NaN ones (∞·0, ∞ − ∞) among them.
            Vec3::new(f32::INFINITY, 0.0, 0.0),
            Vec3::new(f32::INFINITY, f32::NEG_INFINITY, 1.0),
            Vec3::new(f32::MAX, f32::MAX, f32::MAX),
        ];
        for x in -1..=1 {
            for y in -1..=1 {
                for z in -1..=1 {
                    dirs.push(Vec3::new(x as f32, y as f32, z as f32));
                }
            }
        }
        let mut hulls = Vec::new();
        for n in 4..=40 {
            let pts: Vec<Vec3> = (0..n).map(|_| Vec3::new(rnd(), rnd(), rnd())).collect();
            hulls.push(build(&pts, &HullSettings::default()).unwrap());
            // Points on a coarse grid: many equal projections along the axes.
            let grid: Vec<Vec3> = (0..n)
                .map(|_| Vec3::new(rnd(), rnd(), rnd()).map(|c| (c * 4.0).round() * 0.25))
                .collect();
            if let Ok(h) = build(&grid, &HullSettings::default()) {
                hulls.push(h);
            }
        }
        let mut padded = 0;
        for h in &hulls {
            padded += (h.vertices.len() % 4 != 0) as usize;
            for d in dirs
                .iter()
                .copied()
                .chain((0..64).map(|_| Vec3::new(rnd(), rnd(), rnd())))
            {
                assert_eq!(
                    h.support_index(d),
                    support_index_scalar(h, d),
                    "{} vertices along {d}",
                    h.vertices.len()
                );
            }
        }
        assert!(
            hulls.len() > 60 && padded > 20,
            "{} hulls, {padded} padded",
            hulls.len()
        );
    }
}
