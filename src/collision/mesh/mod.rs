//! Triangle meshes: static level geometry (floors, ramps, stairs, props' collision meshes)
//! for static and kinematic bodies, built once and instanced by shapes through the world's
//! [`GeometryStore`](crate::collision::geometry_store::GeometryStore).
//!
//! Building copies the caller's vertices and triangles, then:
//!
//! 1. rejects bad input (`InvalidArgument` naming the vertex or triangle): a non-finite
//!    vertex, an index out of range, no triangles;
//! 2. skips *degenerate* triangles — a repeated index, or an area that is not finite or
//!    under `DEGENERATE_RATIO` of its longest edge squared — and counts them
//!    ([`TriangleMesh::degenerate_count`]); a mesh whose every triangle is degenerate is
//!    refused;
//! 3. finds each edge's neighbour (vertices welded by exact position, so an unindexed
//!    triangle soup works too) and marks which edges are active (`edges.rs`);
//! 4. builds the BVH (`bvh.rs`: binned SAH, 32-byte nodes) and reorders the triangles into
//!    leaf order, keeping each one's index in the caller's array.
//!
//! Triangles are one-sided: their front is where `(v1 − v0) × (v2 − v0)` points
//! (counter-clockwise seen from the front); bodies behind a triangle do not touch it.

pub mod bvh;
pub mod edges;

use crate::collision::aabb::Aabb;
use crate::error::{invalid, Result};
use crate::math::Vec3;
use bvh::Node;

/// A triangle is degenerate when twice its area is below this fraction of its longest
/// edge squared (its height under 1e-5 of its length), or not finite.
pub const DEGENERATE_RATIO: f32 = 1.0e-5;

/// A triangle mesh with its BVH and edge flags, immutable once built.
#[derive(Clone, Debug)]
pub struct TriangleMesh {
    vertices: Vec<Vec3>,
    /// Vertex indices per triangle, in leaf order.
    triangles: Vec<[u32; 3]>,
    /// Active-edge bits per triangle (`edges.rs`), in leaf order.
    flags: Vec<u8>,
    /// Index in the caller's triangle array, per triangle in leaf order.
    original: Vec<u32>,
    nodes: Vec<Node>,
    degenerate: u32,
    bounds: Aabb,
}

impl TriangleMesh {
    /// Builds a mesh from vertices and triangles (three vertex indices each, counter-
    /// clockwise seen from the front). See the module doc.
    pub fn new(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<TriangleMesh> {
        if triangles.is_empty() {
            return Err(invalid("a triangle mesh needs at least one triangle"));
        }
        if triangles.len() >= (1 << 31) {
            return Err(invalid(format!(
                "a triangle mesh holds fewer than 2^31 triangles, got {}",
                triangles.len()
            )));
        }
        for (i, v) in vertices.iter().enumerate() {
            if !v.is_finite() {
                return Err(invalid(format!("mesh vertex {i} must be finite, got {v}")));
            }
        }
        let n = vertices.len();
        for (t, tri) in triangles.iter().enumerate() {
            for (k, &i) in tri.iter().enumerate() {
                if i as usize >= n {
                    return Err(invalid(format!(
                        "mesh triangle {t} index {k} is {i}, but there are only {n} vertices"
                    )));
                }
            }
        }
        let kept: Vec<u32> = (0..triangles.len() as u32)
            .filter(|&t| !is_degenerate(vertices, &triangles[t as usize]))
            .collect();
        if kept.is_empty() {
            return Err(invalid(format!(
                "every one of the mesh's {} triangles is degenerate (zero area or repeated indices)",
                triangles.len()
            )));
        }
        let degenerate = (triangles.len() - kept.len()) as u32;
        let tris: Vec<[u32; 3]> = kept.iter().map(|&t| triangles[t as usize]).collect();
        let flags = edge_flags(vertices, &tris);
        let tri_bounds: Vec<Aabb> = tris.iter().map(|t| triangle_bounds(vertices, t)).collect();
        let (nodes, order) = bvh::build(&tri_bounds);
        let bounds = nodes[0].bounds();
        Ok(TriangleMesh {
            vertices: vertices.to_vec(),
            triangles: order.iter().map(|&i| tris[i as usize]).collect(),
            flags: order.iter().map(|&i| flags[i as usize]).collect(),
            original: order.iter().map(|&i| kept[i as usize]).collect(),
            nodes,
            degenerate,
            bounds,
        })
    }

    /// Triangles kept (degenerate ones are not).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Triangles skipped at creation as degenerate.
    pub fn degenerate_count(&self) -> u32 {
        self.degenerate
    }

    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Bounds of the triangles in the mesh's own frame.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Heap and inline bytes the mesh occupies.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.vertices.capacity() * std::mem::size_of::<Vec3>()
            + self.triangles.capacity() * std::mem::size_of::<[u32; 3]>()
            + self.flags.capacity()
            + self.original.capacity() * 4
            + self.nodes.capacity() * std::mem::size_of::<Node>()
    }

    /// Vertices of triangle `t` (leaf order), in the mesh's frame.
    #[inline]
    pub fn triangle(&self, t: u32) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[t as usize];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// Active-edge bits of triangle `t` (`edges.rs`).
    #[inline]
    pub fn edge_flags(&self, t: u32) -> u8 {
        self.flags[t as usize]
    }

    /// Index in the caller's triangle array of triangle `t` (leaf order).
    pub fn original_index(&self, t: u32) -> u32 {
        self.original[t as usize]
    }

    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Calls `visit(t)` for every triangle (leaf order) whose bounds overlap `b` (mesh
    /// frame); `visit` returns false to stop.
    #[inline]
    pub fn query(&self, b: &Aabb, mut visit: impl FnMut(u32) -> bool) {
        bvh::query(&self.nodes, b, |first, count| {
            for t in first..first + count {
                let [p, q, r] = self.triangle(t);
                let (lo, hi) = (p.min(q).min(r), p.max(q).max(r));
                if lo.x <= b.max.x
                    && hi.x >= b.min.x
                    && lo.y <= b.max.y
                    && hi.y >= b.min.y
                    && lo.z <= b.max.z
                    && hi.z >= b.min.z
                    && !visit(t)
                {
                    return false;
                }
            }
            true
        });
    }
}

fn is_degenerate(v: &[Vec3], t: &[u32; 3]) -> bool {
    if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
        return true;
    }
    let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
    let twice_area = (b - a).cross(c - a).length();
    let longest = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let kept = twice_area.is_finite() && longest.is_finite() && twice_area > DEGENERATE_RATIO * longest;
    !kept
}

pub(crate) fn triangle_bounds(v: &[Vec3], t: &[u32; 3]) -> Aabb {
    let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
    Aabb::new(a.min(b).min(c), a.max(b).max(c))
}

/// Unit normal of a (non-degenerate) triangle.
#[inline]
pub fn triangle_normal(a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    (b - a).cross(c - a).normalize()
}

/// Active-edge bits of every triangle (`edges.rs`): an edge shared by exactly two
/// triangles that run it in opposite directions is active when it is convex and bent by
/// more than `edges::ACTIVE_EDGE_ANGLE`; any other edge is open, hence active.
fn edge_flags(vertices: &[Vec3], tris: &[[u32; 3]]) -> Vec<u8> {
    // Weld by exact position (−0.0 equals 0.0) so a triangle soup finds its neighbours.
    let key = |v: Vec3| (v + Vec3::ZERO).to_array().map(f32::to_bits);
    let mut by_pos: Vec<u32> = (0..vertices.len() as u32).collect();
    by_pos.sort_unstable_by_key(|&i| (key(vertices[i as usize]), i));
    let mut weld = vec![0u32; vertices.len()];
    let mut k = 0;
    while k < by_pos.len() {
        let first = by_pos[k];
        let kf = key(vertices[first as usize]);
        while k < by_pos.len() && key(vertices[by_pos[k] as usize]) == kf {
            weld[by_pos[k] as usize] = first;
            k += 1;
        }
    }
    // Half-edges sorted by their undirected welded edge.
    let mut half: Vec<(u64, u32)> = Vec::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (weld[tri[e] as usize], weld[tri[(e + 1) % 3] as usize]);
            let k = (a.min(b) as u64) << 32 | a.max(b) as u64;
            half.push((k, 3 * t as u32 + e as u32));
        }
    }
    half.sort_unstable();
    let mut flags = vec![edges::ALL_EDGES; tris.len()];
    let mut s = 0;
    while s < half.len() {
        let mut e = s + 1;
        while e < half.len() && half[e].0 == half[s].0 {
            e += 1;
        }
        if e - s == 2 {
            let (h0, h1) = (half[s].1, half[s + 1].1);
            let (t0, e0) = ((h0 / 3) as usize, (h0 % 3) as usize);
            let (t1, e1) = ((h1 / 3) as usize, (h1 % 3) as usize);
            let (a0, b0) = (weld[tris[t0][e0] as usize], weld[tris[t0][(e0 + 1) % 3] as usize]);
            let a1 = weld[tris[t1][e1] as usize];
            // Consistent winding: the neighbour runs the edge the other way.
            if a0 != a1 && t0 != t1 {
                let p = |t: usize, i: usize| vertices[tris[t][i % 3] as usize];
                let n0 = triangle_normal(p(t0, 0), p(t0, 1), p(t0, 2));
                let active = edges::edge_active(n0, vertices[a0 as usize], vertices[b0 as usize], p(t1, e1 + 2));
                if !active {
                    flags[t0] &= !(1 << e0);
                    flags[t1] &= !(1 << e1);
                }
            }
        }
        s = e;
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat `n × n` grid of unit cells in the XZ plane, facing +Y.
    pub(crate) fn grid(n: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let mut v = Vec::new();
        for z in 0..=n {
            for x in 0..=n {
                v.push(Vec3::new(x as f32, 0.0, z as f32));
            }
        }
        let mut t = Vec::new();
        let id = |x: u32, z: u32| z * (n + 1) + x;
        for z in 0..n {
            for x in 0..n {
                t.push([id(x, z), id(x, z + 1), id(x + 1, z + 1)]);
                t.push([id(x, z), id(x + 1, z + 1), id(x + 1, z)]);
            }
        }
        (v, t)
    }

    #[test]
    fn flat_grid_inner_edges_inactive_border_active() {
        let (v, t) = grid(4);
        let m = TriangleMesh::new(&v, &t).unwrap();
        assert_eq!(m.triangle_count(), 32);
        for k in 0..m.triangle_count() as u32 {
            let tri = m.triangle(k);
            let n = triangle_normal(tri[0], tri[1], tri[2]);
            assert!((n - Vec3::Y).length() < 1e-6);
            for e in 0..3 {
                let (a, b) = (tri[e], tri[(e + 1) % 3]);
                let border = |c: fn(Vec3) -> f32, x: f32| c(a) == x && c(b) == x;
                let on_border =
                    border(|p| p.x, 0.0) || border(|p| p.x, 4.0) || border(|p| p.z, 0.0) || border(|p| p.z, 4.0);
                assert_eq!(m.edge_flags(k) & (1 << e) != 0, on_border, "tri {k} edge {e}");
            }
        }
    }

    #[test]
    fn soup_is_welded() {
        let (v, t) = grid(2);
        let soup: Vec<Vec3> = t.iter().flat_map(|tri| tri.map(|i| v[i as usize])).collect();
        let tris: Vec<[u32; 3]> = (0..t.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
        let a = TriangleMesh::new(&v, &t).unwrap();
        let b = TriangleMesh::new(&soup, &tris).unwrap();
        let flags = |m: &TriangleMesh| {
            let mut f: Vec<(u32, u8)> = (0..m.triangle_count() as u32)
                .map(|k| (m.original_index(k), m.edge_flags(k)))
                .collect();
            f.sort();
            f
        };
        assert_eq!(flags(&a), flags(&b));
    }

    #[test]
    fn ridge_is_active_valley_is_not() {
        // Two triangles sharing the edge (0,0,0)-(0,0,1), bent 30° down (ridge) or up (valley).
        for (dy, active) in [(-0.577f32, true), (0.577, false)] {
            let v = vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
                Vec3::new(1.0, dy, 0.5),
                Vec3::new(-1.0, dy, 0.5),
            ];
            let t = vec![[0, 1, 2], [1, 0, 3]];
            let m = TriangleMesh::new(&v, &t).unwrap();
            for k in 0..2 {
                let o = m.original_index(k);
                assert_eq!(m.edge_flags(k) & 1 != 0, active, "dy {dy} tri {o}");
                assert_eq!(m.edge_flags(k) & 0b110, 0b110);
            }
        }
    }

    #[test]
    fn bad_input_and_degenerates() {
        let v = vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(2.0, 0.0, 0.0)];
        let e = TriangleMesh::new(&v, &[[0, 1, 4]]).unwrap_err();
        assert!(e.to_string().contains("triangle 0 index 2 is 4"), "{e}");
        let mut bad = v.clone();
        bad[1].y = f32::NAN;
        assert!(TriangleMesh::new(&bad, &[[0, 2, 1]])
            .unwrap_err()
            .to_string()
            .contains("vertex 1"));
        assert!(TriangleMesh::new(&v, &[]).is_err());
        // Repeated index, collinear (zero area), and one good triangle.
        let m = TriangleMesh::new(&v, &[[0, 0, 1], [0, 1, 3], [0, 2, 1]]).unwrap();
        assert_eq!((m.triangle_count(), m.degenerate_count()), (1, 2));
        assert_eq!(m.original_index(0), 2);
        assert!(TriangleMesh::new(&v, &[[0, 1, 3]])
            .unwrap_err()
            .to_string()
            .contains("degenerate"));
    }
}

crate::snap_struct!(TriangleMesh {
    vertices,
    triangles,
    flags,
    original,
    nodes,
    degenerate,
    bounds,
});
