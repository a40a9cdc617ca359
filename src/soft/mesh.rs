//! Mesh helpers for soft bodies: an icosphere, a box lattice and a cloth grid, each centred
//! on the origin; and the topology a soft body derives from a triangle mesh (unique edges,
//! bending pairs across edges).

use crate::error::{invalid, Result};
use crate::hash::IntMap;
use crate::math::Vec3;

/// Smallest size (m) the helpers accept for a radius, half extent, width or height.
pub const MIN_SIZE: f32 = 1.0e-3;
/// Largest size (m) the helpers accept for a radius, half extent, width or height.
pub const MAX_SIZE: f32 = 1.0e4;
/// Most icosphere subdivisions (40,962 vertices).
pub const MAX_SUBDIVISIONS: u32 = 6;
/// Most lattice cells along each axis of a box.
pub const MAX_LATTICE_CELLS: u32 = 64;
/// Most cloth cells along each side (the vertex count `(columns + 1)(rows + 1)` is also
/// bounded by `MAX_SOFT_VERTICES`).
pub const MAX_CLOTH_CELLS: u32 = 1024;

/// A helper size must be finite and in `MIN_SIZE..=MAX_SIZE`.
fn check_size(name: &str, x: f32) -> Result<()> {
    if x.is_finite() && (MIN_SIZE..=MAX_SIZE).contains(&x) {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be in {MIN_SIZE}..={MAX_SIZE} m, got {x}")))
    }
}

fn check_count(name: &str, x: u32, lo: u32, hi: u32) -> Result<()> {
    if (lo..=hi).contains(&x) {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be in {lo}..={hi}, got {x}")))
    }
}

/// `icosphere` after checking its parameters: `radius` in `MIN_SIZE..=MAX_SIZE`,
/// `subdivisions` in `0..=MAX_SUBDIVISIONS`; errors name the parameter.
pub fn try_icosphere(radius: f32, subdivisions: u32) -> Result<SoftMesh> {
    check_size("radius", radius)?;
    check_count("subdivisions", subdivisions, 0, MAX_SUBDIVISIONS)?;
    Ok(icosphere(radius, subdivisions))
}

/// `lattice` after checking its parameters: each half extent in `MIN_SIZE..=MAX_SIZE`,
/// each cell count in `1..=MAX_LATTICE_CELLS`; errors name the parameter
/// (`half_extents.x`, `cells_x`, ...).
pub fn try_lattice(half_extents: Vec3, cells: [u32; 3]) -> Result<SoftMesh> {
    for (axis, (h, n)) in ["x", "y", "z"]
        .iter()
        .zip(half_extents.to_array().into_iter().zip(cells))
    {
        check_size(&format!("half_extents.{axis}"), h)?;
        check_count(&format!("cells_{axis}"), n, 1, MAX_LATTICE_CELLS)?;
    }
    Ok(lattice(half_extents, cells))
}

/// `cloth` after checking its parameters: `width` and `height` in `MIN_SIZE..=MAX_SIZE`,
/// `columns` and `rows` in `1..=MAX_CLOTH_CELLS` with at most `MAX_SOFT_VERTICES`
/// vertices in all; errors name the parameter.
pub fn try_cloth(width: f32, height: f32, columns: u32, rows: u32) -> Result<SoftMesh> {
    check_size("width", width)?;
    check_size("height", height)?;
    check_count("columns", columns, 1, MAX_CLOTH_CELLS)?;
    check_count("rows", rows, 1, MAX_CLOTH_CELLS)?;
    let vertices = (columns as usize + 1) * (rows as usize + 1);
    if vertices > super::MAX_SOFT_VERTICES {
        return Err(invalid(format!(
            "columns × rows = {columns} × {rows} makes {vertices} vertices, more than {}",
            super::MAX_SOFT_VERTICES
        )));
    }
    Ok(cloth(width, height, columns, rows))
}

/// A triangle mesh (counter-clockwise seen from outside for closed meshes) plus optional
/// extra springs that are not triangle edges (the inner springs of a lattice).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SoftMesh {
    pub vertices: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub extra_edges: Vec<[u32; 2]>,
}

/// An icosphere of `radius` (m): an icosahedron whose triangles are split in four
/// `subdivisions` times (0..=6), vertices pushed onto the sphere. Vertex counts: 12, 42,
/// 162, 642, 2562, ...
pub fn icosphere(radius: f32, subdivisions: u32) -> SoftMesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut vertices: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut mid: IntMap<u64, u32> = IntMap::default();
        let mut next = Vec::with_capacity(triangles.len() * 4);
        let mut midpoint = |a: u32, b: u32, vertices: &mut Vec<Vec3>| -> u32 {
            let key = ((a.min(b) as u64) << 32) | a.max(b) as u64;
            *mid.entry(key).or_insert_with(|| {
                let p = ((vertices[a as usize] + vertices[b as usize]) * 0.5).normalize();
                vertices.push(p);
                vertices.len() as u32 - 1
            })
        };
        for &[a, b, c] in &triangles {
            let ab = midpoint(a, b, &mut vertices);
            let bc = midpoint(b, c, &mut vertices);
            let ca = midpoint(c, a, &mut vertices);
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    for v in &mut vertices {
        *v *= radius;
    }
    SoftMesh {
        vertices,
        triangles,
        extra_edges: Vec::new(),
    }
}

/// A box of `half_extents` (m) filled with a lattice of `n[0] × n[1] × n[2]` cells (each
/// 1..=64): vertices on the grid, springs along every cell edge, face diagonal and body
/// diagonal (so it keeps its shape), and the outer faces as triangles.
pub fn lattice(half_extents: Vec3, n: [u32; 3]) -> SoftMesh {
    let [nx, ny, nz] = n.map(|k| k as usize);
    let id = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    let mut vertices = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let f = Vec3::new(i as f32 / nx as f32, j as f32 / ny as f32, k as f32 / nz as f32);
                vertices.push(-half_extents + 2.0 * half_extents * f);
            }
        }
    }
    // Springs: every pair of corners of every cell (edges, face and body diagonals);
    // duplicates are removed when the body is built.
    let mut extra_edges = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let corners: [u32; 8] = std::array::from_fn(|c| id(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)));
                for a in 0..8 {
                    for b in a + 1..8 {
                        extra_edges.push([corners[a], corners[b]]);
                    }
                }
            }
        }
    }
    // Surface triangles, counter-clockwise from outside.
    let mut triangles = Vec::new();
    let mut quad = |a: u32, b: u32, c: u32, d: u32| {
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    };
    for j in 0..ny {
        for i in 0..nx {
            // z = -h (normal -z) and z = +h (normal +z).
            quad(id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0));
            quad(id(i, j, nz), id(i + 1, j, nz), id(i + 1, j + 1, nz), id(i, j + 1, nz));
        }
    }
    for k in 0..nz {
        for i in 0..nx {
            // y = -h and y = +h.
            quad(id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1));
            quad(id(i, ny, k), id(i, ny, k + 1), id(i + 1, ny, k + 1), id(i + 1, ny, k));
        }
    }
    for k in 0..nz {
        for j in 0..ny {
            // x = -h and x = +h.
            quad(id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k));
            quad(id(nx, j, k), id(nx, j + 1, k), id(nx, j + 1, k + 1), id(nx, j, k + 1));
        }
    }
    SoftMesh {
        vertices,
        triangles,
        extra_edges,
    }
}

/// An open cloth of `width × height` (m) in the XZ plane (normal +Y), with `columns × rows`
/// cells (each 1..=1024); vertex `(i, j)` is `i + (columns + 1) · j`, `i` along +X from
/// `-width/2`, `j` along +Z from `-height/2`.
pub fn cloth(width: f32, height: f32, columns: u32, rows: u32) -> SoftMesh {
    let (nx, nz) = (columns as usize, rows as usize);
    let id = |i: usize, j: usize| (i + (nx + 1) * j) as u32;
    let mut vertices = Vec::with_capacity((nx + 1) * (nz + 1));
    for j in 0..=nz {
        for i in 0..=nx {
            vertices.push(Vec3::new(
                width * (i as f32 / nx as f32 - 0.5),
                0.0,
                height * (j as f32 / nz as f32 - 0.5),
            ));
        }
    }
    let mut triangles = Vec::with_capacity(2 * nx * nz);
    for j in 0..nz {
        for i in 0..nx {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            // Alternate the diagonal so the cloth has no preferred shear direction.
            if (i + j) % 2 == 0 {
                triangles.push([a, c, b]);
                triangles.push([a, d, c]);
            } else {
                triangles.push([a, d, b]);
                triangles.push([b, d, c]);
            }
        }
    }
    SoftMesh {
        vertices,
        triangles,
        extra_edges: Vec::new(),
    }
}

/// Unique edges of the triangles and extra edges, and the bending pairs: for every edge
/// shared by exactly two triangles, the two vertices opposite it. Sorted, so the order
/// (and hence the solve) is deterministic.
pub(crate) fn topology(triangles: &[[u32; 3]], extra: &[[u32; 2]]) -> (Vec<[u32; 2]>, Vec<[u32; 2]>) {
    let key = |a: u32, b: u32| ((a.min(b) as u64) << 32) | a.max(b) as u64;
    // Edge -> (count, first opposite vertex, second opposite vertex).
    let mut map: IntMap<u64, (u32, u32, u32)> = IntMap::default();
    for t in triangles {
        for e in 0..3 {
            let (a, b, o) = (t[e], t[(e + 1) % 3], t[(e + 2) % 3]);
            let entry = map.entry(key(a, b)).or_insert((0, u32::MAX, u32::MAX));
            if entry.0 == 0 {
                entry.1 = o;
            } else if entry.0 == 1 {
                entry.2 = o;
            }
            entry.0 += 1;
        }
    }
    let mut edges: Vec<u64> = map.keys().copied().collect();
    edges.extend(extra.iter().filter(|e| e[0] != e[1]).map(|e| key(e[0], e[1])));
    edges.sort_unstable();
    edges.dedup();
    let mut bends: Vec<[u32; 2]> = map
        .values()
        .filter(|&&(count, a, b)| count == 2 && a != b)
        .map(|&(_, a, b)| [a.min(b), a.max(b)])
        .collect();
    bends.sort_unstable();
    bends.dedup();
    let edges = edges.iter().map(|&k| [(k >> 32) as u32, k as u32]).collect();
    (edges, bends)
}

/// For a closed surface (`is_closed`), each triangle's three neighbours: entry `j` is the
/// triangle across the edge opposite its vertex `j`.
pub(crate) fn neighbours(triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let key = |a: u32, b: u32| ((a as u64) << 32) | b as u64;
    let mut by_edge: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for e in 0..3 {
            by_edge.push((key(tri[e], tri[(e + 1) % 3]), t as u32));
        }
    }
    by_edge.sort_unstable();
    triangles
        .iter()
        .map(|tri| {
            std::array::from_fn(|j| {
                // The edge opposite vertex j runs from tri[j+1] to tri[j+2]; its neighbour has
                // it the other way round.
                let k = key(tri[(j + 2) % 3], tri[(j + 1) % 3]);
                let at = by_edge.partition_point(|&(e, _)| e < k);
                by_edge[at].1
            })
        })
        .collect()
}

/// Whether the triangles close a surface: every edge is used once in each direction, so
/// each is shared by exactly two triangles wound the same way.
pub(crate) fn is_closed(triangles: &[[u32; 3]]) -> bool {
    if triangles.is_empty() {
        return false;
    }
    let mut directed: Vec<u64> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |e| ((t[e] as u64) << 32) | t[(e + 1) % 3] as u64))
        .collect();
    directed.sort_unstable();
    if directed.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    directed
        .iter()
        .all(|&k| directed.binary_search(&k.rotate_right(32)).is_ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn volume(m: &SoftMesh) -> f32 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.vertices[i as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn icosphere_has_642_vertices_at_three_subdivisions_and_the_sphere_volume() {
        let m = icosphere(1.0, 3);
        assert_eq!(m.vertices.len(), 642);
        assert_eq!(m.triangles.len(), 1280);
        let v = volume(&m);
        assert!((v - 4.0 / 3.0 * std::f32::consts::PI).abs() < 0.05, "{v}");
        let (edges, bends) = topology(&m.triangles, &[]);
        assert_eq!(edges.len(), 1920);
        assert_eq!(bends.len(), 1920);
    }

    #[test]
    fn lattice_surface_is_closed_and_outward() {
        let m = lattice(Vec3::new(0.5, 1.0, 1.5), [2, 3, 4]);
        assert_eq!(m.vertices.len(), 3 * 4 * 5);
        assert!((volume(&m) - 6.0).abs() < 1e-4, "{}", volume(&m));
        let (edges, bends) = topology(&m.triangles, &m.extra_edges);
        assert!(edges.len() > m.vertices.len());
        // One pair per surface edge, fewer where two edges share their opposite pair.
        assert!(!bends.is_empty() && bends.len() <= 3 * m.triangles.len() / 2);
    }

    #[test]
    fn neighbours_of_a_closed_surface_share_an_edge() {
        let m = icosphere(1.0, 1);
        assert!(is_closed(&m.triangles));
        let nb = neighbours(&m.triangles);
        for (t, tri) in m.triangles.iter().enumerate() {
            for j in 0..3 {
                let other = m.triangles[nb[t][j] as usize];
                let (a, b) = (tri[(j + 1) % 3], tri[(j + 2) % 3]);
                assert!(nb[t][j] as usize != t && other.contains(&a) && other.contains(&b));
            }
        }
        assert!(!is_closed(&cloth(1.0, 1.0, 2, 2).triangles));
        assert!(is_closed(&lattice(Vec3::ONE, [2, 1, 3]).triangles));
    }

    #[test]
    fn checked_helpers_name_the_parameter_out_of_range() {
        let message = |r: Result<SoftMesh>| r.unwrap_err().to_string();
        assert!(message(try_lattice(Vec3::new(1.0, f32::MAX, 1.0), [1, 1, 1])).contains("half_extents.y"));
        assert!(message(try_lattice(Vec3::ONE, [1, 65, 1])).contains("cells_y"));
        assert!(message(try_icosphere(f32::NAN, 1)).contains("radius"));
        assert!(message(try_icosphere(1.0, 7)).contains("subdivisions"));
        assert!(message(try_cloth(1.0, 1.0e-4, 1, 1)).contains("height"));
        assert!(message(try_cloth(1.0, 1.0, 1024, 1024)).contains("columns × rows"));
        assert_eq!(try_icosphere(MIN_SIZE, 0).unwrap().vertices.len(), 12);
        assert_eq!(try_lattice(Vec3::splat(MAX_SIZE), [1, 1, 1]).unwrap().vertices.len(), 8);
        assert_eq!(try_cloth(MAX_SIZE, MIN_SIZE, 1024, 1).unwrap().vertices.len(), 2050);
    }

    #[test]
    fn cloth_grid_counts() {
        let m = cloth(2.0, 1.0, 4, 2);
        assert_eq!(m.vertices.len(), 15);
        assert_eq!(m.triangles.len(), 16);
        let (edges, _) = topology(&m.triangles, &[]);
        // 4·3 + 5·2 grid edges and one diagonal per cell.
        assert_eq!(edges.len(), 12 + 10 + 8);
    }
}
