//! Soft-body exports (issue 6): the def and its defaults, create from a triangle mesh or
//! from the helpers (icosphere, box lattice, cloth grid), destroy, bulk read-back of vertex
//! positions, normals and triangle indices into caller-owned arrays, pins, impulses,
//! pressure and volume, and the settings that may change after creation (stiffness,
//! damping, gas, materials, sub-steps).

use super::error::*;
use super::generator::is_null_body;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_ref, HearthWorld};
use crate::math::Vec3;
use crate::pool::Handle;
use crate::soft::{mesh, SoftBody, SoftBodyDef, SoftBodySettings, SoftMesh, MAX_SOFT_VERTICES};
use crate::world::World;

/// Id of a soft body inside its world. All-zero is the null id. Ids of destroyed soft
/// bodies and of other worlds are rejected with `HEARTH_ERROR_INVALID_ID`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthSoftBodyId {
    /// Slot of the soft body.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

impl From<HearthSoftBodyId> for Handle {
    fn from(id: HearthSoftBodyId) -> Handle {
        Handle {
            index: id.index,
            generation: id.generation,
        }
    }
}

impl From<Handle> for HearthSoftBodyId {
    fn from(h: Handle) -> HearthSoftBodyId {
        HearthSoftBodyId {
            index: h.index,
            generation: h.generation,
        }
    }
}

/// How to create a soft body (everything except its mesh). Get one from
/// `hearth_soft_body_def_default()`, then edit it.
///
/// The solver is XPBD with sub-steps: stiffness is given as compliance (the inverse of
/// stiffness), does not depend on the time step, and any value is stable.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSoftBodyDef {
    /// Placement of the mesh: its vertices (given in the mesh's own frame) are rotated,
    /// then moved by `transform.position` (m). Default: identity.
    pub transform: HearthTransform,
    /// Initial velocity of every vertex (m/s). Default 0.
    pub velocity: HearthVec3,
    /// Total mass (kg, > 0), shared equally by the vertices unless per-vertex masses are
    /// given to `hearth_soft_body_create_mesh`. Default 1.
    pub mass: f32,
    /// Compliance of the stretch springs along the mesh edges (m/N, >= 0; 0 is
    /// inextensible). Default 0. The edges of a skin (a closed mesh with no inner springs:
    /// an icosphere, a closed host mesh) resist stretching only, as a membrane does; an
    /// inextensible skin also keeps its total area at most its rest area, so its gas does
    /// not stretch it (the default ball stays within 1 % of its rest edge lengths up to
    /// nRT 1600 J).
    pub edge_compliance: f32,
    /// Compliance of the bending springs across edges shared by two triangles (m/N, >= 0;
    /// `INFINITY` disables bending). Default 0.01.
    pub bend_compliance: f32,
    /// 1 keeps the enclosed volume at its rest value (closed, outward-wound meshes); 0
    /// (default) does not.
    pub preserve_volume: u8,
    /// Compliance of the volume constraint (>= 0; 0 is incompressible). Default 0.
    pub volume_compliance: f32,
    /// Gas pressure as n·R·T (J = Pa·m³, >= 0): each face is pushed out along its normal by
    /// `nRT / V · area`, V the current enclosed volume. 0 (default) is no gas.
    pub pressure: f32,
    /// Linear damping of the vertices (1/s, >= 0): slows every motion, like air drag.
    /// Default 0.5.
    pub damping: f32,
    /// Damping of deformation (1/s, >= 0): each vertex's velocity relaxes at this rate
    /// towards the rigid motion of the whole soft body, so wobbling and bouncing on the gas
    /// die out while flight and spin are untouched. Default 2.
    pub deformation_damping: f32,
    /// Coulomb friction against shapes (>= 0; the pair uses the geometric mean with the
    /// shape's static friction). Default 0.5.
    pub friction: f32,
    /// Bounce against shapes (>= 0; the pair uses the larger of the two). Default 0.
    pub restitution: f32,
    /// Radius of each vertex for collision (m, >= 0). Default 0.01.
    pub vertex_radius: f32,
    /// Multiplier of world gravity (finite). Default 1.
    pub gravity_scale: f32,
    /// XPBD sub-steps per world step (1..=64). Default 20.
    pub substeps: u32,
    /// Gauss–Seidel passes over the stretch springs per sub-step (1..=16). Default 2 (one
    /// pass rings and stretches a large cloth).
    pub iterations: u32,
    /// 1 (default) collides with rigid shapes and planes; 0 passes through everything.
    pub collide: u8,
    /// Host data, returned by `hearth_soft_body_get_user_data`.
    pub user_data: u64,
    /// Set by `hearth_soft_body_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: at the origin, at rest, 1 kg, inextensible edges, bend compliance 0.01, no
/// volume constraint, no gas, damping 0.5, deformation damping 2, friction 0.5, no bounce,
/// vertex radius 0.01 m, full gravity, 20 sub-steps of 2 stretch passes, collides.
#[no_mangle]
pub extern "C" fn hearth_soft_body_def_default() -> HearthSoftBodyDef {
    let d = SoftBodyDef::default();
    HearthSoftBodyDef {
        transform: d.transform.into(),
        velocity: d.velocity.into(),
        mass: d.mass,
        edge_compliance: d.edge_compliance,
        bend_compliance: d.bend_compliance,
        preserve_volume: d.preserve_volume as u8,
        volume_compliance: d.volume_compliance,
        pressure: d.pressure,
        damping: d.damping,
        deformation_damping: d.deformation_damping,
        friction: d.friction,
        restitution: d.restitution,
        vertex_radius: d.vertex_radius,
        gravity_scale: d.gravity_scale,
        substeps: d.substeps,
        iterations: d.iterations,
        collide: d.collide as u8,
        user_data: d.user_data,
        internal_value: DEF_COOKIE,
    }
}

fn soft_def(d: &HearthSoftBodyDef) -> Result<SoftBodyDef, Failure> {
    validate::cookie(d.internal_value, "hearth_soft_body_def")?;
    let def = SoftBodyDef {
        transform: d.transform.into(),
        velocity: d.velocity.into(),
        mass: d.mass,
        edge_compliance: d.edge_compliance,
        bend_compliance: d.bend_compliance,
        preserve_volume: validate::flag(d.preserve_volume, "preserve_volume")?,
        volume_compliance: d.volume_compliance,
        pressure: d.pressure,
        damping: d.damping,
        deformation_damping: d.deformation_damping,
        friction: d.friction,
        restitution: d.restitution,
        vertex_radius: d.vertex_radius,
        gravity_scale: d.gravity_scale,
        substeps: d.substeps,
        iterations: d.iterations,
        collide: validate::flag(d.collide, "collide")?,
        user_data: d.user_data,
    };
    def.validate()?;
    Ok(def)
}

/// Shared tail of the create functions: checks world, def and output, builds the mesh
/// (only after every check passed) and creates the body.
///
/// # Safety
/// Pointers must be NULL or valid.
unsafe fn create(
    world: *mut HearthWorld,
    def: *const HearthSoftBodyDef,
    out: *mut HearthSoftBodyId,
    masses: Option<&[f32]>,
    mesh: impl FnOnce() -> Result<SoftMesh, Failure>,
) -> Result<(), Failure> {
    let w = world_mut(world)?;
    let def = soft_def(validate::input(def, "def")?)?;
    let out = validate::output(out, "out_soft_body")?;
    let mesh = mesh()?;
    *out = w.create_soft_body(&def, &mesh, masses)?.into();
    Ok(())
}

/// Creates a soft body from a triangle mesh given in its own frame (`def.transform`
/// places it): `vertex_count` positions (m) and `index_count` vertex indices, three per
/// triangle. A closed mesh must be wound counter-clockwise seen from outside for its
/// volume, pressure and volume constraint to push outwards. Every unique edge becomes a
/// stretch spring and every pair of triangles sharing an edge a bending spring. `masses`
/// (kg, `vertex_count` values, each > 0) gives per-vertex masses and replaces the equal
/// split of `def.mass`; NULL uses `def.mass`. The arrays are copied; the caller keeps them.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, def, vertices, indices, out_soft_body),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_soft_body_def_default()` or out of
/// range, `vertex_count` 0 or above 1048576, `index_count` 0 or not a multiple of 3 or above
/// 6 × 1048576, an index >= `vertex_count`, a triangle repeating a vertex, a NaN or
/// infinite vertex, a mass <= 0 or not finite, a `def.transform.position` that moves a
/// vertex out of the float range), `HEARTH_ERROR_WORLD_LOCKED`. Nothing is created on
/// error.
///
/// # Safety
/// `vertices` must hold `vertex_count` vectors, `indices` `index_count` indices and
/// `masses` (if not NULL) `vertex_count` floats; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_create_mesh(
    world: *mut HearthWorld,
    def: *const HearthSoftBodyDef,
    vertices: *const HearthVec3,
    vertex_count: usize,
    indices: *const u32,
    index_count: usize,
    masses: *const f32,
    out_soft_body: *mut HearthSoftBodyId,
) -> HearthResult {
    guard(|| {
        if vertices.is_null() {
            return Err(Failure::null("vertices"));
        }
        if indices.is_null() {
            return Err(Failure::null("indices"));
        }
        if vertex_count == 0 || vertex_count > MAX_SOFT_VERTICES {
            return Err(Failure::invalid(format!(
                "vertex_count must be in 1..={MAX_SOFT_VERTICES}, got {vertex_count}"
            )));
        }
        if index_count == 0 || index_count % 3 != 0 || index_count > 6 * MAX_SOFT_VERTICES {
            return Err(Failure::invalid(format!(
                "index_count must be a positive multiple of 3 (three per triangle) up to {}, got {index_count}",
                6 * MAX_SOFT_VERTICES
            )));
        }
        let masses = if masses.is_null() {
            None
        } else {
            Some(std::slice::from_raw_parts(masses, vertex_count))
        };
        create(world, def, out_soft_body, masses, || {
            let v = std::slice::from_raw_parts(vertices, vertex_count);
            let idx = std::slice::from_raw_parts(indices, index_count);
            Ok(SoftMesh {
                vertices: v.iter().map(|&p| Vec3::from(p)).collect(),
                triangles: idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
                extra_edges: Vec::new(),
            })
        })
    })
}

/// Creates a soft ball: an icosphere of `radius` (m, 0.001..=10000) centred on
/// `def.transform`, an icosahedron whose triangles are split in four `subdivisions` times
/// (0..=6). Vertex counts: 12, 42, 162, 642, 2562, 10242, 40962. Give it `def.pressure` (a
/// balloon) or `def.preserve_volume` to hold its shape. It is a skin (see
/// `HearthSoftBodyDef::edge_compliance`): rigid shapes are kept out of its faces as well as
/// its vertices, and static geometry wins over a dynamic body squeezing it (a 40 kg box
/// dropped 0.3 m on a 2 kg, 642-vertex ball of nRT 400 J pushes no vertex more than 1 cm
/// into the ground and gets no point more than 1.5 cm inside the skin).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def as for
/// `hearth_soft_body_create_mesh`; `radius` NaN, infinite or outside 0.001..=10000;
/// `subdivisions` above 6), `HEARTH_ERROR_WORLD_LOCKED`. The message names the parameter.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_create_icosphere(
    world: *mut HearthWorld,
    def: *const HearthSoftBodyDef,
    radius: f32,
    subdivisions: u32,
    out_soft_body: *mut HearthSoftBodyId,
) -> HearthResult {
    guard(|| {
        create(world, def, out_soft_body, None, || {
            Ok(mesh::try_icosphere(radius, subdivisions)?)
        })
    })
}

/// Creates a soft box of `half_extents` (m, each 0.001..=10000) centred on
/// `def.transform`, filled with a lattice of `cells_x × cells_y × cells_z` cells (each
/// 1..=64): a vertex at every
/// lattice point, springs along every cell edge, face diagonal and body diagonal (so it
/// keeps its shape without gas), and the outer faces as triangles (wound outwards). Vertex
/// count: `(cells_x + 1)(cells_y + 1)(cells_z + 1)`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def as for
/// `hearth_soft_body_create_mesh`; a half extent NaN, infinite or outside 0.001..=10000; a
/// cell count outside 1..=64), `HEARTH_ERROR_WORLD_LOCKED`. The message names the
/// parameter (`half_extents.x`, `cells_y`, ...).
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_create_box(
    world: *mut HearthWorld,
    def: *const HearthSoftBodyDef,
    half_extents: HearthVec3,
    cells_x: u32,
    cells_y: u32,
    cells_z: u32,
    out_soft_body: *mut HearthSoftBodyId,
) -> HearthResult {
    guard(|| {
        create(world, def, out_soft_body, None, || {
            Ok(mesh::try_lattice(half_extents.into(), [cells_x, cells_y, cells_z])?)
        })
    })
}

/// Creates an open cloth of `width × height` (m, each 0.001..=10000) in the XZ plane of
/// `def.transform` (normal +Y), with `columns × rows` cells (each 1..=1024, and at most
/// 1048576 vertices in all). Vertex
/// `(i, j)` has index `i + (columns + 1) · j`, `i` along +X from `-width/2`, `j` along +Z
/// from `-height/2`: pin corners 0 and `columns` to hang it by its edge at z = -height/2.
/// Vertex count: `(columns + 1)(rows + 1)`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def as for
/// `hearth_soft_body_create_mesh`; `width` or `height` NaN, infinite or outside
/// 0.001..=10000; `columns` or `rows` outside 1..=1024; `(columns + 1)(rows + 1)` above
/// 1048576), `HEARTH_ERROR_WORLD_LOCKED`. The message names the parameter.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_create_cloth(
    world: *mut HearthWorld,
    def: *const HearthSoftBodyDef,
    width: f32,
    height: f32,
    columns: u32,
    rows: u32,
    out_soft_body: *mut HearthSoftBodyId,
) -> HearthResult {
    guard(|| {
        create(world, def, out_soft_body, None, || {
            Ok(mesh::try_cloth(width, height, columns, rows)?)
        })
    })
}

/// Destroys a soft body: its id becomes stale. Bodies it was pinned to are unaffected.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_destroy(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_soft_body(soft_body.into())?))
}

/// Shared body of the getters: checks world, output pointer and id; writes on success.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
unsafe fn get<T>(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut T,
    read: impl FnOnce(&SoftBody) -> Result<T, Failure>,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out, "out")?;
        *out = read(w.soft_body(soft_body.into())?)?;
        Ok(())
    })
}

/// Reads the number of live soft bodies in the world.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_soft_body_count(
    world: *const HearthWorld,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_count, "out_count")?;
        *out = w.soft_body_count();
        Ok(())
    })
}

/// Reads the number of vertices of a soft body (fixed at creation): the size the arrays of
/// `hearth_soft_body_get_positions` and `hearth_soft_body_get_normals` need.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_vertex_count(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_count: *mut usize,
) -> HearthResult {
    get(world, soft_body, out_count, |s| Ok(s.vertex_count()))
}

/// Reads the number of triangles of a soft body (fixed at creation);
/// `hearth_soft_body_get_indices` needs three times as many indices.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_triangle_count(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_count: *mut usize,
) -> HearthResult {
    get(world, soft_body, out_count, |s| Ok(s.triangles.len()))
}

/// Shared body of the bulk reads: `n` elements written by `fill` into the caller's array
/// of `capacity`. `capacity == 0` only asks for the count.
///
/// # Safety
/// `out` must be NULL or hold `capacity` elements; `out_count` NULL or writable.
#[allow(clippy::too_many_arguments)]
unsafe fn bulk<T>(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut T,
    capacity: usize,
    out_count: *mut usize,
    what: &str,
    len: impl FnOnce(&SoftBody) -> usize,
    fill: impl FnOnce(&SoftBody, &mut [T]),
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let count = validate::output(out_count, "out_count")?;
        let s = w.soft_body(soft_body.into())?;
        let n = len(s);
        if let Some(out) = validate::counted_output(out, capacity, n, what)? {
            fill(s, out);
        }
        *count = n;
        Ok(())
    })
}

/// Reads every vertex position (m, world space) of a soft body into the caller-owned
/// `out_positions`, in vertex order, one call per frame to rebuild a render mesh.
/// `*out_count` receives the vertex count. Pass `out_positions = NULL` and `capacity = 0`
/// to ask for the count only.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, out_count, or `out_positions` with
/// `capacity > 0`), `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity`
/// not 0 and below the vertex count; nothing is written).
///
/// # Safety
/// `out_positions` must be NULL or hold `capacity` vectors; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_positions(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_positions: *mut HearthVec3,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    bulk(
        world,
        soft_body,
        out_positions,
        capacity,
        out_count,
        "out_positions",
        |s| s.vertex_count(),
        |s, out| {
            for (o, p) in out.iter_mut().zip(&s.pos) {
                *o = (*p).into();
            }
        },
    )
}

/// Reads every vertex normal of a soft body into the caller-owned `out_normals`, in vertex
/// order: unit vectors, the area-weighted average of the normals of the vertex's triangles
/// (counter-clockwise winding; outwards on the helpers' closed meshes, +Y on a flat cloth),
/// or zero for a vertex in no triangle. Computed from the current positions. Count and
/// capacity as for `hearth_soft_body_get_positions`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, out_count, or `out_normals` with
/// `capacity > 0`), `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity`
/// not 0 and below the vertex count; nothing is written).
///
/// # Safety
/// `out_normals` must be NULL or hold `capacity` vectors; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_normals(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_normals: *mut HearthVec3,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    bulk(
        world,
        soft_body,
        out_normals,
        capacity,
        out_count,
        "out_normals",
        |s| s.vertex_count(),
        |s, out| {
            // Accumulated in place (no allocation): the same sum as `SoftBody::normals_into`.
            for o in out.iter_mut() {
                *o = HearthVec3::default();
            }
            for t in &s.triangles {
                let [a, b, c] = t.map(|i| s.pos[i as usize]);
                let n = (b - a).cross(c - a);
                for &i in t {
                    let o = &mut out[i as usize];
                    *o = (Vec3::from(*o) + n).into();
                }
            }
            for o in out.iter_mut() {
                *o = Vec3::from(*o).normalize_or_zero().into();
            }
        },
    )
}

/// Reads the triangle indices of a soft body into the caller-owned `out_indices`, three
/// per triangle (counter-clockwise from outside for closed meshes): the mesh given to
/// `hearth_soft_body_create_mesh`, or the one a helper built. `*out_count` receives the
/// number of indices (3 × triangle count). Pass `out_indices = NULL` and `capacity = 0` to
/// ask for the count only.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, out_count, or `out_indices` with
/// `capacity > 0`), `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity`
/// not 0 and below the index count; nothing is written).
///
/// # Safety
/// `out_indices` must be NULL or hold `capacity` indices; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_indices(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_indices: *mut u32,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    bulk(
        world,
        soft_body,
        out_indices,
        capacity,
        out_count,
        "out_indices",
        |s| 3 * s.triangles.len(),
        |s, out| {
            for (o, t) in out.chunks_exact_mut(3).zip(&s.triangles) {
                o.copy_from_slice(t);
            }
        },
    )
}

fn vertex_of(s: &SoftBody, vertex: u32) -> Result<usize, Failure> {
    let i = vertex as usize;
    if i < s.vertex_count() {
        Ok(i)
    } else {
        Err(Failure::invalid(format!(
            "vertex {vertex} out of range (the soft body has {} vertices)",
            s.vertex_count()
        )))
    }
}

/// Reads one vertex's position (m, world space).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (vertex out of range).
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_vertex_position(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.pos[vertex_of(s, vertex)?].into()))
}

/// Reads one vertex's velocity (m/s).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (vertex out of range).
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_vertex_velocity(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.vel[vertex_of(s, vertex)?].into()))
}

/// Reads the mass-weighted centre of a soft body's vertices (m, world space).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_center(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.center().into()))
}

/// Reads the total mass of a soft body (kg).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_mass(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut f32,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.total_mass()))
}

/// Reads the volume a soft body encloses now (m³): the signed sum over its triangles, so
/// meaningful for closed, outward-wound meshes (an open cloth gives an arbitrary number).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_volume(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut f32,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.volume()))
}

/// Reads the volume a soft body enclosed when it was created (m³), the target of the
/// volume constraint.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_rest_volume(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut f32,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.rest_volume))
}

/// Reads the gas pressure n·R·T (J).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_pressure(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut f32,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.def.pressure))
}

/// Reads the `user_data` given at creation.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_user_data(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out: *mut u64,
) -> HearthResult {
    get(world, soft_body, out, |s| Ok(s.def.user_data))
}

/// Sets the gas pressure n·R·T (J = Pa·m³, >= 0); takes effect at the next step. Each face
/// is pushed out by `nRT / V · area`, V the current enclosed volume.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (negative, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_set_pressure(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    pressure: f32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_soft_pressure(soft_body.into(), pressure)?))
}

/// Pins `vertex` where it is now: to the world when `body` is the null id (it stays at
/// that point), or to `body` at the point it has in the body's frame now. A static or
/// kinematic body carries the vertex along; a dynamic body is held to it two-way, solved in
/// the soft-body sub-steps: the body feels the soft body's pull (a flag drags its pole,
/// a cloth holds a weight), momentum is kept. Free vertices are tethered to their two
/// nearest pins so a large cloth does not stretch. A pinned vertex does not collide.
/// Pinning a pinned vertex moves its pin. Destroying the body frees the vertices pinned to
/// it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (soft body, or a body
/// that is not null and not live in this world), `HEARTH_ERROR_INVALID_ARGUMENT` (vertex
/// out of range), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_pin_vertex(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
    body: HearthBodyId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let body = if is_null_body(&body) { None } else { Some(body.into()) };
        Ok(w.pin_soft_vertex(soft_body.into(), vertex, body)?)
    })
}

/// Frees a pinned vertex (a vertex that is not pinned is left as it is: `HEARTH_OK`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (vertex out of range), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_unpin_vertex(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.unpin_soft_vertex(soft_body.into(), vertex)?))
}

/// Reads whether `vertex` is pinned (to the world or to a body).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (vertex out of range).
///
/// # Safety
/// `world` must be NULL or a live world; `out_pinned` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_is_vertex_pinned(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
    out_pinned: *mut bool,
) -> HearthResult {
    guard(|| {
        let w: &World = world_ref(world)?;
        let out = validate::output(out_pinned, "out_pinned")?;
        *out = w.soft_vertex_is_pinned(soft_body.into(), vertex)?;
        Ok(())
    })
}

/// Applies an impulse (N·s) to one vertex: its velocity changes by `impulse / mass` at the
/// start of the next step. A pinned vertex ignores it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (vertex out of range, impulse NaN, infinite or longer
/// than 1e10 N·s),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_apply_impulse(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    vertex: u32,
    impulse: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.apply_soft_impulse(soft_body.into(), Some(vertex), impulse.into())?))
}

/// Applies an impulse (N·s) to the whole soft body, spread over its vertices in
/// proportion to mass: every vertex's velocity changes by `impulse / total mass` at the
/// start of the next step (pinned vertices ignore it).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (impulse NaN, infinite or longer than 1e10 N·s),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_apply_impulse_all(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    impulse: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.apply_soft_impulse(soft_body.into(), None, impulse.into())?))
}

/// The settings of a soft body that may change after creation: the fields of
/// `HearthSoftBodyDef` with the same names, units, ranges and defaults. Read them with
/// `hearth_soft_body_get_settings`, edit, write them back with
/// `hearth_soft_body_set_settings`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSoftBodySettings {
    /// Compliance of the stretch springs (m/N, >= 0; 0 is inextensible).
    pub edge_compliance: f32,
    /// Compliance of the bending springs (m/N, >= 0; `INFINITY` disables bending).
    pub bend_compliance: f32,
    /// 1 keeps the enclosed volume at its rest value, 0 does not.
    pub preserve_volume: u8,
    /// Compliance of the volume constraint (>= 0; 0 is incompressible).
    pub volume_compliance: f32,
    /// Gas pressure as n·R·T (J, >= 0).
    pub pressure: f32,
    /// Linear damping of the vertices (1/s, >= 0).
    pub damping: f32,
    /// Damping of deformation towards the rigid motion of the whole body (1/s, >= 0).
    pub deformation_damping: f32,
    /// Coulomb friction against shapes (>= 0).
    pub friction: f32,
    /// Bounce against shapes (>= 0).
    pub restitution: f32,
    /// Radius of each vertex for collision (m, >= 0).
    pub vertex_radius: f32,
    /// Multiplier of world gravity (finite).
    pub gravity_scale: f32,
    /// XPBD sub-steps per world step (1..=64).
    pub substeps: u32,
    /// Passes over the stretch springs per sub-step (1..=16).
    pub iterations: u32,
    /// 1 collides with rigid shapes and planes, 0 passes through everything.
    pub collide: u8,
}

impl From<SoftBodySettings> for HearthSoftBodySettings {
    fn from(s: SoftBodySettings) -> Self {
        HearthSoftBodySettings {
            edge_compliance: s.edge_compliance,
            bend_compliance: s.bend_compliance,
            preserve_volume: s.preserve_volume as u8,
            volume_compliance: s.volume_compliance,
            pressure: s.pressure,
            damping: s.damping,
            deformation_damping: s.deformation_damping,
            friction: s.friction,
            restitution: s.restitution,
            vertex_radius: s.vertex_radius,
            gravity_scale: s.gravity_scale,
            substeps: s.substeps,
            iterations: s.iterations,
            collide: s.collide as u8,
        }
    }
}

fn settings_from(s: &HearthSoftBodySettings) -> Result<SoftBodySettings, Failure> {
    Ok(SoftBodySettings {
        edge_compliance: s.edge_compliance,
        bend_compliance: s.bend_compliance,
        preserve_volume: validate::flag(s.preserve_volume, "preserve_volume")?,
        volume_compliance: s.volume_compliance,
        pressure: s.pressure,
        damping: s.damping,
        deformation_damping: s.deformation_damping,
        friction: s.friction,
        restitution: s.restitution,
        vertex_radius: s.vertex_radius,
        gravity_scale: s.gravity_scale,
        substeps: s.substeps,
        iterations: s.iterations,
        collide: validate::flag(s.collide, "collide")?,
    })
}

/// Reads the settings a soft body runs with now (those given at creation or set since).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_settings` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_get_settings(
    world: *const HearthWorld,
    soft_body: HearthSoftBodyId,
    out_settings: *mut HearthSoftBodySettings,
) -> HearthResult {
    get(world, soft_body, out_settings, |s| Ok(s.def.settings().into()))
}

/// Replaces a soft body's settings (stiffness, damping, gas, materials, sub-steps); they
/// take effect at the next step. Every field is checked as at creation; nothing changes on
/// error.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, settings), `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a number NaN, infinite where not allowed, negative or
/// out of range; a flag not 0 or 1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world; `settings` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_set_settings(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    settings: *const HearthSoftBodySettings,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let settings = settings_from(validate::input(settings, "settings")?)?;
        Ok(w.set_soft_body_settings(soft_body.into(), &settings)?)
    })
}

/// Sets the three compliances of a soft body (the inverse of stiffness, >= 0; XPBD: any
/// value is stable and the stiffness does not depend on the time step): `edge` of the
/// stretch springs (m/N, 0 inextensible), `bend` of the bending springs (m/N, `INFINITY`
/// disables bending), `volume` of the volume constraint (0 incompressible; used when the
/// body preserves its volume). Takes effect at the next step.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (negative or NaN; `edge` or `volume` infinite),
/// `HEARTH_ERROR_WORLD_LOCKED`. Nothing changes on error.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_soft_body_set_compliance(
    world: *mut HearthWorld,
    soft_body: HearthSoftBodyId,
    edge: f32,
    bend: f32,
    volume: f32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let settings = SoftBodySettings {
            edge_compliance: edge,
            bend_compliance: bend,
            volume_compliance: volume,
            ..w.soft_body_settings(soft_body.into())?
        };
        Ok(w.set_soft_body_settings(soft_body.into(), &settings)?)
    })
}
