//! Shape exports: material defaults and one create function per geometry.

use super::error::*;
use super::query::HearthFilter;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_ref, HearthWorld};
use crate::collision::shape::{Geometry, ShapeDef};

/// Material of a shape. Get one from `hearth_shape_def_default()`, then edit it. Where two
/// shapes touch, friction combines as the geometric mean; restitution, rolling resistance and
/// torsional friction as the maximum.
///
/// Sizes: shapes down to the smallest (radius or half extent 1 mm) rest like large ones; a
/// resting shape overlaps what it rests on by about 0.2 mm, or a fiftieth of its radius or smallest half extent when that is under
/// 1 cm (a 1 cm shape rests 0.11 mm deep, 1.1 % of its size; a 2 mm one 0.028 mm, 1.4 %).
/// Mass ratios between touching bodies: see `HearthBodyDef`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthShapeDef {
    /// kg/m³: 0 (a massless shape) or 0.001..=1e5. Default 1000 (water).
    pub density: f32,
    /// Coulomb friction coefficient while the surfaces stick (>= 0). Default 0.6.
    pub static_friction: f32,
    /// Coulomb friction coefficient while they slide (>= 0; the pair uses at most the
    /// static value). Default 0.6.
    pub dynamic_friction: f32,
    /// Bounciness: 0 none, 1 elastic (0..=1). Default 0.
    pub restitution: f32,
    /// Host data.
    pub user_data: u64,
    /// Set by `hearth_shape_def_default()`; do not change.
    pub internal_value: u32,
    /// Rolling resistance, 0..=1 (Box2D v3's `rollingResistance`). Default 0.05. Where the
    /// shapes touch, a torque against their relative rolling of up to
    /// `rolling_resistance × radius × normal force`, `radius` being the larger sphere or
    /// capsule radius of the two (boxes and planes have none: two of them never roll). A
    /// solid ball rolling on a level floor slows at `5/7 · rolling_resistance · g` (at the
    /// default, a ball at 2 m/s stops after 5.7 m) while friction can keep it rolling
    /// (`rolling_resistance` up to 1.4 × friction; above, it slides and slows at
    /// `friction · g`), and rests on slopes up to `atan(rolling_resistance)` where friction
    /// holds it too. Added after `internal_value`, so earlier fields keep their offsets.
    pub rolling_resistance: f32,
    /// Torsional (spin) friction, 0..=1. Default 0.05. A torque against the relative spin
    /// about the contact normal of up to `torsional_friction × radius × normal force`
    /// (`radius` as above), on top of the friction of a contact patch's own width. A solid
    /// ball spinning in place on a level floor slows at `5/2 · torsional_friction · g /
    /// radius` rad/s².
    pub torsional_friction: f32,
    /// Which shapes this one collides with and which queries see it (`HearthFilter`).
    /// Default: category 1, every mask bit, group 0 (collides with everything). Change it
    /// later with `hearth_shape_set_filter`.
    pub filter: HearthFilter,
    /// 1 makes the shape a sensor: it reports overlaps with non-sensor shapes (exact shapes)
    /// as sensor events (`hearth_world_get_sensor_events`) and never pushes, never makes a
    /// solver contact, adds no mass (its density is ignored), and particles and soft bodies
    /// pass through it. Sensors see shapes on bodies of every type (not two static ones, not
    /// other sensors) and never wake a body; overlaps with a sleeping body are kept while it
    /// sleeps. A plane cannot be a sensor. Default 0.
    pub is_sensor: u8,
    /// 1 (default): this shape's contacts report begin and end events
    /// (`hearth_world_get_contact_events`); both shapes must enable them.
    pub enable_contact_events: u8,
    /// 1: this shape's contacts report hit events (approach faster than the world's
    /// `hit_event_threshold`); either shape may enable them. Default 0.
    pub enable_hit_events: u8,
    /// 1 (default): a sensor reports, and sensors see this shape; both shapes must enable
    /// them.
    pub enable_sensor_events: u8,
}

/// Defaults: density 1000 kg/m³, friction 0.6 (static and dynamic), no bounce, rolling
/// resistance and torsional friction 0.05, the default filter (`hearth_filter_default()`).
#[no_mangle]
pub extern "C" fn hearth_shape_def_default() -> HearthShapeDef {
    let d = ShapeDef::default();
    HearthShapeDef {
        density: d.density,
        static_friction: d.static_friction,
        dynamic_friction: d.dynamic_friction,
        restitution: d.restitution,
        user_data: d.user_data,
        internal_value: DEF_COOKIE,
        rolling_resistance: d.rolling_resistance,
        torsional_friction: d.torsional_friction,
        filter: d.filter.into(),
        is_sensor: 0,
        enable_contact_events: 1,
        enable_hit_events: 0,
        enable_sensor_events: 1,
    }
}

fn shape_def(d: &HearthShapeDef) -> Result<ShapeDef, Failure> {
    validate::cookie(d.internal_value, "hearth_shape_def")?;
    Ok(ShapeDef {
        density: d.density,
        static_friction: d.static_friction,
        dynamic_friction: d.dynamic_friction,
        restitution: d.restitution,
        user_data: d.user_data,
        rolling_resistance: d.rolling_resistance,
        torsional_friction: d.torsional_friction,
        filter: d.filter.into(),
        is_sensor: validate::flag(d.is_sensor, "is_sensor")?,
        enable_contact_events: validate::flag(d.enable_contact_events, "enable_contact_events")?,
        enable_hit_events: validate::flag(d.enable_hit_events, "enable_hit_events")?,
        enable_sensor_events: validate::flag(d.enable_sensor_events, "enable_sensor_events")?,
    })
}

/// Shared body of the create functions.
///
/// # Safety
/// Pointers must be NULL or valid.
unsafe fn create<G>(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    geometry: *const G,
    out_shape: *mut HearthShapeId,
    to_geometry: impl FnOnce(&G) -> Geometry,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let def = shape_def(validate::input(def, "def")?)?;
        let g = to_geometry(validate::input(geometry, "geometry")?);
        let out = validate::output(out_shape, "out_shape")?;
        *out = w.create_shape(body.into(), &def, &g)?.into();
        Ok(())
    })
}

/// Adds a sphere to a body; the body's mass, centre of mass and inertia are recomputed.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (body),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_shape_def_default()`, a size or
/// placement outside its range, NaN/infinite numbers, density, friction or restitution out
/// of range), `HEARTH_ERROR_WORLD_LOCKED`. The def is checked before the body id.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_sphere(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    sphere: *const HearthSphere,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, sphere, out_shape, |s| Geometry::Sphere {
        center: s.center.into(),
        radius: s.radius,
    })
}

/// Adds a box to a body. Errors as `hearth_shape_create_sphere`, plus half extents outside
/// 0.001..=1e4 and a zero rotation.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_box(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    box_: *const HearthBox,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, box_, out_shape, |b| Geometry::Box {
        center: b.center.into(),
        rotation: b.rotation.into(),
        half_extents: b.half_extents.into(),
    })
}

/// Adds a capsule to a body. Errors as `hearth_shape_create_sphere`, plus a segment longer
/// than 1e4 m.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_capsule(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    capsule: *const HearthCapsule,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, capsule, out_shape, |c| Geometry::Capsule {
        a: c.a.into(),
        b: c.b.into(),
        radius: c.radius,
    })
}

/// Adds a plane (a static half-space) to a static body. Errors as
/// `hearth_shape_create_sphere`, plus a zero normal, an offset over the normal's length
/// outside ±1e5 m, and `HEARTH_ERROR_INVALID_ARGUMENT` for a body that is not static.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_plane(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    plane: *const HearthPlane,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, plane, out_shape, |p| Geometry::Plane {
        normal: p.normal.into(),
        offset: p.offset,
    })
}

/// A convex hull instanced by a shape: the hull's points are scaled uniformly by `scale`
/// (> 0; also the convex radius), then placed by `local` in the body frame.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthHullShape {
    /// The hull, from `hearth_hull_create`.
    pub hull: HearthHullId,
    /// Placement of the hull's frame in the body frame.
    pub local: HearthTransform,
    /// Uniform scale (> 0; the scaled hull must span at least 1 mm).
    pub scale: f32,
}

/// A triangle mesh instanced by a shape: scaled per axis by `scale` (each >= 1e-4) in the
/// mesh's own frame, then placed by `local` in the body frame.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthMeshShape {
    /// The mesh, from `hearth_mesh_create`.
    pub mesh: HearthMeshId,
    /// Placement of the mesh's frame in the body frame.
    pub local: HearthTransform,
    /// Per-axis scale (each >= 1e-4; negative scales, mirroring, are not supported).
    pub scale: HearthVec3,
}

/// A heightfield instanced by a shape: `scale.x` and `scale.z` are the sample spacing (m)
/// along columns and rows, `scale.y` multiplies the heights (each >= 1e-4); then placed by
/// `local` in the body frame.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthHeightfieldShape {
    /// The heightfield, from `hearth_heightfield_create`.
    pub heightfield: HearthHeightfieldId,
    /// Placement of the heightfield's frame in the body frame.
    pub local: HearthTransform,
    /// Spacing in x and z (m) and height scale in y (each >= 1e-4).
    pub scale: HearthVec3,
}

/// Adds a shape instancing a convex hull (any body type); the body's mass, centre of mass
/// and inertia are recomputed (exact for the polyhedron). Any number of shapes may use one
/// hull; the hull cannot be destroyed while they exist.
///
/// Errors: as `hearth_shape_create_sphere`, plus `HEARTH_ERROR_INVALID_ID` (hull null,
/// destroyed or from another world), `HEARTH_ERROR_INVALID_ARGUMENT` (scale not finite or
/// <= 0, or making the hull under 1 mm across; NaN/infinite or zero-quaternion `local`).
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_hull(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    hull: *const HearthHullShape,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, hull, out_shape, |h| Geometry::Hull {
        hull: h.hull.into(),
        local: h.local.into(),
        scale: h.scale,
    })
}

/// Adds a shape instancing a triangle mesh to a static or kinematic body. A mesh is a
/// surface without volume, so it gives no mass: on a dynamic body it is refused with
/// `HEARTH_ERROR_INVALID_ARGUMENT` (use hulls or primitives for moving bodies).
///
/// Errors: as `hearth_shape_create_sphere`, plus `HEARTH_ERROR_INVALID_ID` (mesh null,
/// destroyed or from another world), `HEARTH_ERROR_INVALID_ARGUMENT` (dynamic body, a scale
/// component under 1e-4 or not finite, NaN/infinite or zero-quaternion `local`).
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_mesh(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    mesh: *const HearthMeshShape,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, mesh, out_shape, |m| Geometry::Mesh {
        mesh: m.mesh.into(),
        local: m.local.into(),
        scale: m.scale.into(),
    })
}

/// Adds a shape instancing a heightfield to a static or kinematic body; refused on a
/// dynamic body as for `hearth_shape_create_mesh`.
///
/// Errors: as `hearth_shape_create_mesh`, with the heightfield's id.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_create_heightfield(
    world: *mut HearthWorld,
    body: HearthBodyId,
    def: *const HearthShapeDef,
    heightfield: *const HearthHeightfieldShape,
    out_shape: *mut HearthShapeId,
) -> HearthResult {
    create(world, body, def, heightfield, out_shape, |h| Geometry::Heightfield {
        heightfield: h.heightfield.into(),
        local: h.local.into(),
        scale: h.scale.into(),
    })
}

/// Removes a shape from its body; the body's mass is recomputed and touching bodies woken.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_destroy(world: *mut HearthWorld, shape: HearthShapeId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_shape(shape.into())?))
}

/// Reads the body a shape belongs to.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_body` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_body(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out_body: *mut HearthBodyId,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let s = w.shape(shape.into())?;
        let out = validate::output(out_body, "out_body")?;
        *out = w.bodies.handle_at(s.body).expect("shape's body is live").into();
        Ok(())
    })
}
