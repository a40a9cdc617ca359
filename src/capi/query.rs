//! Query and filter exports: collision filters of shapes, ray casts (closest, callback,
//! batch), shape casts and overlap queries (shape, box, point).

use std::os::raw::c_void;

use super::error::*;
use super::shape::HearthHullShape;
use super::types::*;
use super::validate;
use super::world::{world_mut, world_ref, HearthWorld, PHASE_CORE};
use crate::collision::aabb::Aabb;
use crate::collision::filter::{Filter, QueryFilter};
use crate::collision::query::QueryHit;
use crate::collision::shape::Geometry;
use crate::math::{Transform, Vec3};
use crate::pool::Handle;

/// A shape's collision filter (Box2D v3's rules). Two shapes with the same non-zero
/// `group_index` always collide when it is positive and never when it is negative;
/// otherwise they collide when each one's `category_bits` share a bit with the other's
/// `mask_bits`. Shapes of one body never collide with each other, and joints with
/// `collide_connected` off filter their bodies as before.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HearthFilter {
    /// The categories this shape belongs to (usually one bit). Default 1.
    pub category_bits: u64,
    /// The categories this shape collides with. Default every bit.
    pub mask_bits: u64,
    /// Collision group: shapes sharing a positive group always collide, a negative one
    /// never; 0 (default) is no group.
    pub group_index: i32,
}

impl From<HearthFilter> for Filter {
    fn from(f: HearthFilter) -> Filter {
        Filter {
            category_bits: f.category_bits,
            mask_bits: f.mask_bits,
            group_index: f.group_index,
        }
    }
}

impl From<Filter> for HearthFilter {
    fn from(f: Filter) -> HearthFilter {
        HearthFilter {
            category_bits: f.category_bits,
            mask_bits: f.mask_bits,
            group_index: f.group_index,
        }
    }
}

/// The filter of a query: it reports a shape when `category_bits` shares a bit with the
/// shape's `mask_bits` and the shape's `category_bits` share a bit with `mask_bits`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HearthQueryFilter {
    /// The query's categories. Default 1.
    pub category_bits: u64,
    /// The shape categories the query reports. Default every bit.
    pub mask_bits: u64,
}

impl From<HearthQueryFilter> for QueryFilter {
    fn from(f: HearthQueryFilter) -> QueryFilter {
        QueryFilter {
            category_bits: f.category_bits,
            mask_bits: f.mask_bits,
        }
    }
}

/// One ray: from `origin` along `translation` (the ray ends at `origin + translation`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthRayInput {
    /// Start of the ray (world, m).
    pub origin: HearthVec3,
    /// The ray's direction and length: it ends at `origin + translation` (fraction 1).
    pub translation: HearthVec3,
}

/// A ray's or shape cast's hit. When nothing was hit, `shape` and `body` are the null id
/// (all zero), `fraction` is 1, `point` is the end of the ray (a shape cast: its end
/// position) and `normal` is zero.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthRayHit {
    /// The shape hit.
    pub shape: HearthShapeId,
    /// Its body.
    pub body: HearthBodyId,
    /// World point on the hit surface.
    pub point: HearthVec3,
    /// Unit surface normal at `point`, facing the ray (or the moving shape).
    pub normal: HearthVec3,
    /// Fraction of the translation at the hit, 0..=1.
    pub fraction: f32,
}

/// A query shape kind: a sphere.
pub const HEARTH_QUERY_SHAPE_SPHERE: u32 = 0;
/// A query shape kind: a capsule.
pub const HEARTH_QUERY_SHAPE_CAPSULE: u32 = 1;
/// A query shape kind: a box.
pub const HEARTH_QUERY_SHAPE_BOX: u32 = 2;
/// A query shape kind: a convex hull.
pub const HEARTH_QUERY_SHAPE_HULL: u32 = 3;

/// A shape for shape casts and overlap queries: `type` (`HEARTH_QUERY_SHAPE_*`) says which
/// member is used; the others are ignored. The shape is placed by the transform passed
/// with it, as a body places its shapes. Sizes are checked as for shape creation.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthQueryShape {
    /// `HEARTH_QUERY_SHAPE_SPHERE`, `_CAPSULE`, `_BOX` or `_HULL`.
    pub r#type: u32,
    /// The sphere, with `HEARTH_QUERY_SHAPE_SPHERE`.
    pub sphere: HearthSphere,
    /// The capsule, with `HEARTH_QUERY_SHAPE_CAPSULE`.
    pub capsule: HearthCapsule,
    /// The box, with `HEARTH_QUERY_SHAPE_BOX`.
    pub r#box: HearthBox,
    /// The hull instance, with `HEARTH_QUERY_SHAPE_HULL`.
    pub hull: HearthHullShape,
}

/// Called for each hit of `hearth_world_cast_ray`, with the hit (valid during the call).
/// Returns how to go on (Box2D v3's protocol): -1 (any negative value, or NaN) ignores this
/// hit, 0 stops the cast, a fraction in (0, 1] clips the ray there (return `hit->fraction`
/// to end with the closest hit), 1 (or more) continues unclipped. Runs on the calling
/// thread during the call; it may call read functions and queries, while changes to the
/// world return `HEARTH_ERROR_WORLD_LOCKED`.
pub type HearthRayCallback = Option<unsafe extern "C" fn(user_data: *mut c_void, hit: *const HearthRayHit) -> f32>;

fn miss(end: Vec3) -> HearthRayHit {
    HearthRayHit {
        shape: Handle::NULL.into(),
        body: Handle::NULL.into(),
        point: end.into(),
        normal: Vec3::ZERO.into(),
        fraction: 1.0,
    }
}

fn to_c(h: &QueryHit) -> HearthRayHit {
    HearthRayHit {
        shape: h.shape.into(),
        body: h.body.into(),
        point: h.point.into(),
        normal: h.normal.into(),
        fraction: h.fraction,
    }
}

fn query_shape(s: &HearthQueryShape) -> Result<Geometry, Failure> {
    Ok(match s.r#type {
        HEARTH_QUERY_SHAPE_SPHERE => Geometry::Sphere {
            center: s.sphere.center.into(),
            radius: s.sphere.radius,
        },
        HEARTH_QUERY_SHAPE_CAPSULE => Geometry::Capsule {
            a: s.capsule.a.into(),
            b: s.capsule.b.into(),
            radius: s.capsule.radius,
        },
        HEARTH_QUERY_SHAPE_BOX => Geometry::Box {
            center: s.r#box.center.into(),
            rotation: s.r#box.rotation.into(),
            half_extents: s.r#box.half_extents.into(),
        },
        HEARTH_QUERY_SHAPE_HULL => Geometry::Hull {
            hull: s.hull.hull.into(),
            local: s.hull.local.into(),
            scale: s.hull.scale,
        },
        t => {
            return Err(Failure::invalid(format!(
                "shape type must be a HEARTH_QUERY_SHAPE_* constant (0..=3), got {t}"
            )))
        }
    })
}

/// Runs `f` with the world locked against changes and out of any callback phase, so a host
/// callback called by `f` can read and query but not change the world that `f` is reading.
///
/// # Safety
/// `world` must be a live world.
unsafe fn locked_for_callbacks<R>(world: *const HearthWorld, f: impl FnOnce() -> R) -> R {
    struct Restore<'a>(&'a HearthWorld, bool, u8);
    impl Drop for Restore<'_> {
        fn drop(&mut self) {
            self.0.locked.set(self.1);
            self.0.phase.set(self.2);
        }
    }
    let h = &*world;
    let _restore = Restore(h, h.locked.get(), h.phase.get());
    h.locked.set(true);
    h.phase.set(PHASE_CORE);
    f()
}

/// The default shape filter: category 1, every mask bit, group 0 (collides with every
/// shape with the default filter).
#[no_mangle]
pub extern "C" fn hearth_filter_default() -> HearthFilter {
    Filter::DEFAULT.into()
}

/// The default query filter: category 1, every mask bit (sees every shape whose mask has
/// bit 0, so every shape with the default filter). A query that must see every shape
/// whatever its filter sets both fields to all ones.
#[no_mangle]
pub extern "C" fn hearth_query_filter_default() -> HearthQueryFilter {
    HearthQueryFilter {
        category_bits: QueryFilter::DEFAULT.category_bits,
        mask_bits: QueryFilter::DEFAULT.mask_bits,
    }
}

/// Changes a shape's filter. Existing contacts the new filter forbids are removed at once
/// (their bodies woken); pairs it newly allows are found at the next step (the shape's body
/// is woken). Every bit pattern and group is valid.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_filter(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    filter: HearthFilter,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_shape_filter(shape.into(), filter.into())?))
}

/// Reads a shape's filter.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_filter` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_filter(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out_filter: *mut HearthFilter,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_filter, "out_filter")?;
        *out = w.shape_filter(shape.into())?.into();
        Ok(())
    })
}

/// Casts the ray from `origin` along `translation` and writes its nearest hit to
/// `*out_hit` (with null ids when nothing is hit). Every shape kind is hit, on static,
/// kinematic, dynamic and sleeping bodies alike, when `filter` accepts it. A ray starting
/// inside a solid shape (sphere, box, capsule, hull, or below a plane) does not hit that
/// shape (Box2D v3's rule: a ray cast from inside a character sees past it); triangle
/// meshes and heightfields are surfaces, hit from either side. The normal faces the ray.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, filter, out_hit),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (origin not finite or beyond ±1e5 m; translation not
/// finite, zero, or longer than 1e6 m).
///
/// # Safety
/// `world` must be NULL or a live world; `filter` NULL or readable; `out_hit` NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_cast_ray_closest(
    world: *const HearthWorld,
    origin: HearthVec3,
    translation: HearthVec3,
    filter: *const HearthQueryFilter,
    out_hit: *mut HearthRayHit,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        let out = validate::output(out_hit, "out_hit")?;
        let (o, t): (Vec3, Vec3) = (origin.into(), translation.into());
        let hit = w.cast_ray_closest(o, t, &filter)?;
        *out = hit.as_ref().map_or_else(|| miss(o + t), to_c);
        Ok(())
    })
}

/// Casts the ray from `origin` along `translation` and calls `callback(user_data, hit)` for
/// the hits of shapes `filter` accepts (each shape's nearest hit, in no particular order),
/// going on as the callback returns (see `HearthRayCallback`). Hit rules as
/// `hearth_world_cast_ray_closest`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, filter, callback),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (as `hearth_world_cast_ray_closest`; checked before any
/// callback runs).
///
/// # Safety
/// `world` must be NULL or a live world; `filter` NULL or readable; `callback` safe to call
/// with `user_data`.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_cast_ray(
    world: *const HearthWorld,
    origin: HearthVec3,
    translation: HearthVec3,
    filter: *const HearthQueryFilter,
    callback: HearthRayCallback,
    user_data: *mut c_void,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        let cb = callback.ok_or_else(|| Failure::null("callback"))?;
        let (o, t): (Vec3, Vec3) = (origin.into(), translation.into());
        crate::collision::query::check_ray(o, t)?;
        locked_for_callbacks(world, || {
            w.cast_ray(o, t, &filter, |h| {
                let c = to_c(h);
                cb(user_data, &c)
            })
        })?;
        Ok(())
    })
}

/// Casts `count` rays (caller-owned `rays`) and writes each one's nearest hit to the
/// caller-owned `out_hits[i]` (null ids for a miss), as `hearth_world_cast_ray_closest`
/// would one by one. Every ray is checked first; on any error nothing is written. `count`
/// 0 succeeds and may pass NULL arrays.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, filter, or an array with `count > 0`),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a ray as in `hearth_world_cast_ray_closest`; the
/// message names its index).
///
/// # Safety
/// `rays` must hold `count` rays and `out_hits` room for `count` hits.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_cast_rays(
    world: *const HearthWorld,
    rays: *const HearthRayInput,
    count: usize,
    filter: *const HearthQueryFilter,
    out_hits: *mut HearthRayHit,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        if count == 0 {
            return Ok(());
        }
        let rays = std::slice::from_raw_parts(validate::input(rays, "rays")?, count);
        let out = validate::output(out_hits, "out_hits")?;
        for (i, r) in rays.iter().enumerate() {
            crate::collision::query::check_ray(r.origin.into(), r.translation.into())
                .map_err(|e| Failure::invalid(format!("rays[{i}]: {}", Failure::from(e).message)))?;
        }
        let out = std::slice::from_raw_parts_mut(out, count);
        for (o, r) in out.iter_mut().zip(rays) {
            let (a, t): (Vec3, Vec3) = (r.origin.into(), r.translation.into());
            *o = w
                .cast_ray_closest(a, t, &filter)?
                .as_ref()
                .map_or_else(|| miss(a + t), to_c);
        }
        Ok(())
    })
}

/// Moves a sphere, capsule, box or hull (`shape`, placed by `transform`) along
/// `translation` and writes the first shape it touches to `*out_hit` (null ids when it
/// touches none): the fraction of the translation at first contact (0 when it overlaps a
/// shape at the start), the point on the hit surface and the surface normal facing the
/// moving shape. The fraction is never past the true time of impact and at most 0.1 mm
/// (along the normal) before it. Shapes as for the ray casts, `filter` likewise.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, shape, transform, filter, out_hit),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (unknown shape type, a size as shape creation refuses
/// it, NaN/infinite or zero-quaternion transform, translation as for rays),
/// `HEARTH_ERROR_INVALID_ID` (a hull id not of this world).
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_cast_shape(
    world: *const HearthWorld,
    shape: *const HearthQueryShape,
    transform: *const HearthTransform,
    translation: HearthVec3,
    filter: *const HearthQueryFilter,
    out_hit: *mut HearthRayHit,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let g = query_shape(validate::input(shape, "shape")?)?;
        let xf: Transform = (*validate::input(transform, "transform")?).into();
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        let out = validate::output(out_hit, "out_hit")?;
        let t: Vec3 = translation.into();
        let hit = w.cast_shape(&g, &xf, t, &filter)?;
        *out = hit.as_ref().map_or_else(|| miss(xf.p + t), to_c);
        Ok(())
    })
}

/// The count-then-fill protocol of the overlap queries: count the matches, then (capacity
/// permitting) fill.
unsafe fn overlap_ids(
    out_shapes: *mut HearthShapeId,
    capacity: usize,
    out_count: *mut usize,
    run: impl Fn(&mut dyn FnMut(Handle) -> bool) -> Result<(), Failure>,
) -> Result<(), Failure> {
    let count = validate::output(out_count, "out_count")?;
    let mut n = 0usize;
    run(&mut |_| {
        n += 1;
        true
    })?;
    if let Some(out) = validate::counted_output(out_shapes, capacity, n, "out_shapes")? {
        let mut k = 0;
        run(&mut |h| {
            out[k] = h.into();
            k += 1;
            k < n
        })?;
    }
    *count = n;
    Ok(())
}

/// Writes the ids of the shapes that overlap or touch a sphere, capsule, box or hull
/// (`shape` placed by `transform`), exactly (each shape's own geometry; meshes and
/// heightfields triangle by triangle), into the caller-owned `out_shapes`, and their number
/// to `*out_count`. Pass `capacity` 0 (and `out_shapes` NULL) to ask for the count only.
/// When `capacity` is not 0 but too small, `HEARTH_ERROR_BUFFER_TOO_SMALL` is returned and
/// nothing is written (as every bulk read: ask for the count first). Order: planes first,
/// then the tree's.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, shape, transform, filter, out_count, or
/// out_shapes with `capacity > 0`), `HEARTH_ERROR_INVALID_ARGUMENT` (as
/// `hearth_world_cast_shape`), `HEARTH_ERROR_INVALID_ID` (hull), `HEARTH_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `out_shapes` must be NULL or hold `capacity` ids; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_overlap_shape(
    world: *const HearthWorld,
    shape: *const HearthQueryShape,
    transform: *const HearthTransform,
    filter: *const HearthQueryFilter,
    out_shapes: *mut HearthShapeId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let g = query_shape(validate::input(shape, "shape")?)?;
        let xf: Transform = (*validate::input(transform, "transform")?).into();
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        overlap_ids(out_shapes, capacity, out_count, |f| {
            Ok(w.overlap_shape(&g, &xf, &filter, f)?)
        })
    })
}

/// Writes the ids of the shapes whose bounds overlap the box `min`..`max` into the
/// caller-owned `out_shapes`, count and capacity as `hearth_world_overlap_shape`. The test
/// uses each shape's tight world bounds as of the last step (or its creation or teleport),
/// not its geometry, so a shape near a corner of the box may be reported without touching
/// it; a plane is reported when the box reaches into its half-space.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, filter, out_count, or out_shapes with
/// `capacity > 0`), `HEARTH_ERROR_INVALID_ARGUMENT` (a corner not finite or beyond ±1e5 m, or
/// `min` above `max` on an axis), `HEARTH_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `out_shapes` must be NULL or hold `capacity` ids; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_overlap_aabb(
    world: *const HearthWorld,
    min: HearthVec3,
    max: HearthVec3,
    filter: *const HearthQueryFilter,
    out_shapes: *mut HearthShapeId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        let bb = Aabb {
            min: min.into(),
            max: max.into(),
        };
        overlap_ids(
            out_shapes,
            capacity,
            out_count,
            |f| Ok(w.overlap_aabb(&bb, &filter, f)?),
        )
    })
}

/// Writes the ids of the solid shapes containing `point` (on the surface counts; triangle
/// meshes and heightfields contain no point) into the caller-owned `out_shapes`, count and
/// capacity as `hearth_world_overlap_shape`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, filter, out_count, or out_shapes with
/// `capacity > 0`), `HEARTH_ERROR_INVALID_ARGUMENT` (point not finite or beyond ±1e5 m),
/// `HEARTH_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `out_shapes` must be NULL or hold `capacity` ids; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_overlap_point(
    world: *const HearthWorld,
    point: HearthVec3,
    filter: *const HearthQueryFilter,
    out_shapes: *mut HearthShapeId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let filter: QueryFilter = (*validate::input(filter, "filter")?).into();
        let p: Vec3 = point.into();
        overlap_ids(out_shapes, capacity, out_count, |f| Ok(w.overlap_point(p, &filter, f)?))
    })
}
