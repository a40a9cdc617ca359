//! Shared geometry exports: convex hulls, triangle meshes and heightfields, built once and
//! instanced by any number of shapes (`hearth_shape_create_hull`, `_mesh`, `_heightfield`
//! in `shape.rs`), each with its own placement and scale.

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_ref, HearthWorld};
use crate::collision::heightfield::MAX_SAMPLES;
use crate::collision::hull::builder::HullSettings;
use crate::math::Vec3;

/// Most points accepted by `hearth_hull_create` (the hull keeps at most 255 vertices).
pub const HEARTH_MAX_HULL_POINTS: u32 = 1048576;
/// Most vertices accepted by `hearth_mesh_create`.
pub const HEARTH_MAX_MESH_VERTICES: u32 = 67108864;
/// Most indices (three per triangle) accepted by `hearth_mesh_create`.
pub const HEARTH_MAX_MESH_INDICES: u32 = 201326592;
/// Most samples along either side of a heightfield.
pub const HEARTH_MAX_HEIGHTFIELD_SAMPLES: u32 = 32768;
const _: () = assert!(HEARTH_MAX_HEIGHTFIELD_SAMPLES == MAX_SAMPLES);

/// How a convex hull is built. Get one from `hearth_hull_def_default()`, then edit it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthHullDef {
    /// Convex radius (m, >= 0): the shape is the hull of the points grown by this much
    /// (rounded edges and corners). Default 0.
    pub convex_radius: f32,
    /// Points within this fraction of the cloud's bounding-box diagonal of the hull are
    /// welded onto it, and faces within it of one plane are merged (0 ..= 0.1).
    /// Default 0.001.
    pub weld_tolerance: f32,
    /// Set by `hearth_hull_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: no convex radius, weld tolerance 0.1 % of the cloud's size.
#[no_mangle]
pub extern "C" fn hearth_hull_def_default() -> HearthHullDef {
    let d = HullSettings::default();
    HearthHullDef {
        convex_radius: d.convex_radius,
        weld_tolerance: d.weld_tolerance,
        internal_value: DEF_COOKIE,
    }
}

/// A caller array of `count` elements (non-NULL, `count` in `1..=max`).
///
/// # Safety
/// `ptr` must be NULL or readable for `count` elements.
unsafe fn array<'a, T>(
    ptr: *const T,
    count: usize,
    max: u32,
    what: &str,
    count_name: &str,
) -> Result<&'a [T], Failure> {
    if ptr.is_null() {
        return Err(Failure::null(what));
    }
    if count == 0 || count > max as usize {
        return Err(Failure::invalid(format!(
            "{count_name} must be in 1..={max}, got {count}"
        )));
    }
    Ok(std::slice::from_raw_parts(ptr, count))
}

/// Builds a convex hull of `point_count` points (m, in the hull's own frame; copied) and
/// stores it in the world for shapes to use (`hearth_shape_create_hull`). Points inside
/// the hull are dropped; more than 255 hull vertices are simplified to 255; coplanar faces
/// are merged into polygons. Mass, centre of mass and inertia of shapes using it are exact
/// for the polyhedron (and for the rounded shape's volume when `def.convex_radius > 0`).
///
/// Errors (nothing is stored): `HEARTH_ERROR_NULL_POINTER` (world, def, points,
/// out_hull), `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_hull_def_default()`,
/// convex_radius negative or not finite, weld_tolerance outside 0..=0.1, `point_count` under
/// 4 or above `HEARTH_MAX_HULL_POINTS`, a NaN or infinite point, points spanning under
/// 1 mm, or collinear or coplanar points), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `points` must hold `point_count` vectors; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_hull_create(
    world: *mut HearthWorld,
    def: *const HearthHullDef,
    points: *const HearthVec3,
    point_count: usize,
    out_hull: *mut HearthHullId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        validate::cookie(d.internal_value, "hearth_hull_def")?;
        let pts = array(points, point_count, HEARTH_MAX_HULL_POINTS, "points", "point_count")?;
        let out = validate::output(out_hull, "out_hull")?;
        let pts: Vec<Vec3> = pts.iter().map(|&p| p.into()).collect();
        let settings = HullSettings {
            convex_radius: d.convex_radius,
            weld_tolerance: d.weld_tolerance,
        };
        *out = w.create_convex_hull(&pts, &settings)?.into();
        Ok(())
    })
}

/// Frees a convex hull. Refused while shapes use it: `HEARTH_ERROR_INVALID_ARGUMENT`, the
/// message giving the number of shapes (destroy them, or their bodies, first).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (null, destroyed or
/// another world's hull), `HEARTH_ERROR_INVALID_ARGUMENT` (in use),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_hull_destroy(world: *mut HearthWorld, hull: HearthHullId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_convex_hull(hull.into())?))
}

/// Reads the number of vertices of a convex hull (at most 255).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_hull_get_vertex_count(
    world: *const HearthWorld,
    hull: HearthHullId,
    out_count: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let n = w.convex_hull(hull.into())?.vertices().len() as u32;
        *validate::output(out_count, "out_count")? = n;
        Ok(())
    })
}

/// Builds a triangle mesh from `vertex_count` vertices (m, in the mesh's own frame) and
/// `index_count` vertex indices, three per triangle, counter-clockwise seen from the front
/// (triangles are one-sided). Both arrays are copied. Degenerate triangles (a repeated
/// index, or no area) are skipped and counted (`hearth_mesh_get_degenerate_count`). A mesh
/// is level geometry: shapes using it go on static or kinematic bodies only.
///
/// Errors (nothing is stored): `HEARTH_ERROR_NULL_POINTER` (world, vertices, indices,
/// out_mesh), `HEARTH_ERROR_INVALID_ARGUMENT` (`vertex_count` 0 or above
/// `HEARTH_MAX_MESH_VERTICES`, `index_count` 0, not a multiple of 3 or above
/// `HEARTH_MAX_MESH_INDICES`, an index >= `vertex_count`, a NaN or infinite vertex, every
/// triangle degenerate), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `vertices` must hold `vertex_count` vectors and `indices` `index_count` indices; other
/// pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_mesh_create(
    world: *mut HearthWorld,
    vertices: *const HearthVec3,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    out_mesh: *mut HearthMeshId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let v = array(
            vertices,
            vertex_count,
            HEARTH_MAX_MESH_VERTICES,
            "vertices",
            "vertex_count",
        )?;
        let idx = array(indices, index_count, HEARTH_MAX_MESH_INDICES, "indices", "index_count")?;
        if index_count % 3 != 0 {
            return Err(Failure::invalid(format!(
                "index_count must be a multiple of 3 (three per triangle), got {index_count}"
            )));
        }
        let out = validate::output(out_mesh, "out_mesh")?;
        let v: Vec<Vec3> = v.iter().map(|&p| p.into()).collect();
        let t: Vec<[u32; 3]> = idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        *out = w.create_mesh(&v, &t)?.into();
        Ok(())
    })
}

/// Frees a triangle mesh. Refused while shapes use it (`HEARTH_ERROR_INVALID_ARGUMENT`,
/// the message giving the number of shapes).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (in use), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_mesh_destroy(world: *mut HearthWorld, mesh: HearthMeshId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_mesh(mesh.into())?))
}

/// Reads the number of triangles a mesh kept (those given minus the degenerate ones).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_mesh_get_triangle_count(
    world: *const HearthWorld,
    mesh: HearthMeshId,
    out_count: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let n = w.mesh(mesh.into())?.triangle_count() as u32;
        *validate::output(out_count, "out_count")? = n;
        Ok(())
    })
}

/// Reads the number of triangles skipped at creation as degenerate (a repeated index, or
/// twice the area under 1e-5 of the longest edge squared).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_mesh_get_degenerate_count(
    world: *const HearthWorld,
    mesh: HearthMeshId,
    out_count: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let n = w.mesh(mesh.into())?.degenerate_count();
        *validate::output(out_count, "out_count")? = n;
        Ok(())
    })
}

/// Builds a heightfield of `rows × columns` samples (each 2..=
/// `HEARTH_MAX_HEIGHTFIELD_SAMPLES`) from row-major `heights` (`rows · columns` finite
/// values; copied): sample `(row, column)` is `heights[row · columns + column]` at
/// `(column, height, row)` in the heightfield's own frame, so samples are one unit apart;
/// the shape's scale gives the spacing (`scale.x`, `scale.z`, m) and multiplies the heights
/// (`scale.y`). `holes` is NULL (no holes) or `(rows − 1) · (columns − 1)` row-major cell
/// flags, 1 for a hole (no ground), 0 for ground; copied. Level geometry: shapes using it
/// go on static or kinematic bodies only.
///
/// Errors (nothing is stored): `HEARTH_ERROR_NULL_POINTER` (world, heights, out_heightfield),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (rows or columns out of range, a NaN or infinite height,
/// a hole flag other than 0 or 1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `heights` must hold `rows · columns` floats and `holes` (if not NULL)
/// `(rows − 1) · (columns − 1)` bytes; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_heightfield_create(
    world: *mut HearthWorld,
    rows: u32,
    columns: u32,
    heights: *const f32,
    holes: *const u8,
    out_heightfield: *mut HearthHeightfieldId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        for (name, n) in [("rows", rows), ("columns", columns)] {
            if !(2..=MAX_SAMPLES).contains(&n) {
                return Err(Failure::invalid(format!(
                    "{name} must be in 2..={MAX_SAMPLES}, got {n}"
                )));
            }
        }
        if heights.is_null() {
            return Err(Failure::null("heights"));
        }
        let h = std::slice::from_raw_parts(heights, rows as usize * columns as usize);
        let holes = if holes.is_null() {
            None
        } else {
            let cells = (rows as usize - 1) * (columns as usize - 1);
            let flags = std::slice::from_raw_parts(holes, cells);
            if let Some(i) = flags.iter().position(|&f| f > 1) {
                validate::flag(flags[i], &format!("holes[{i}]"))?;
            }
            Some(flags.iter().map(|&f| f == 1).collect::<Vec<bool>>())
        };
        let out = validate::output(out_heightfield, "out_heightfield")?;
        *out = w.create_heightfield(rows, columns, h, holes.as_deref())?.into();
        Ok(())
    })
}

/// Frees a heightfield. Refused while shapes use it (`HEARTH_ERROR_INVALID_ARGUMENT`, the
/// message giving the number of shapes).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (in use), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_heightfield_destroy(
    world: *mut HearthWorld,
    heightfield: HearthHeightfieldId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_heightfield(heightfield.into())?))
}
