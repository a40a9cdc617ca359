//! Debug draw from C: `HearthDebugDraw` (callbacks, flags, user data) adapted to the core's
//! `DebugDraw` trait, and `hearth_world_draw`.

use std::os::raw::c_void;

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_ref, HearthWorld, PHASE_DRAW};
use crate::debug_draw::{DebugDraw, DrawFlags};
use crate::math::{Transform, Vec3};

/// Draws a segment from `a` to `b` (world space, m). `color` is `0xRRGGBBAA`.
pub type HearthDrawSegment =
    Option<unsafe extern "C" fn(user_data: *mut c_void, a: *const HearthVec3, b: *const HearthVec3, color: u32)>;
/// Draws a convex planar polygon (a face; three vertices for a triangle), its `count`
/// vertices in order. The array is valid only during the call.
pub type HearthDrawPolygon =
    Option<unsafe extern "C" fn(user_data: *mut c_void, vertices: *const HearthVec3, count: u32, color: u32)>;
/// Draws a sphere.
pub type HearthDrawSphere =
    Option<unsafe extern "C" fn(user_data: *mut c_void, center: *const HearthVec3, radius: f32, color: u32)>;
/// Draws the segment `a`–`b` swept by `radius`.
pub type HearthDrawCapsule = Option<
    unsafe extern "C" fn(user_data: *mut c_void, a: *const HearthVec3, b: *const HearthVec3, radius: f32, color: u32),
>;
/// Draws a frame: its origin and axes (a centre of mass and the body's orientation).
pub type HearthDrawTransform = Option<unsafe extern "C" fn(user_data: *mut c_void, transform: *const HearthTransform)>;
/// Draws a point of `size` (m): a contact point or a joint anchor.
pub type HearthDrawPoint =
    Option<unsafe extern "C" fn(user_data: *mut c_void, point: *const HearthVec3, size: f32, color: u32)>;

/// Debug draw: callbacks for each primitive (any may be NULL: that primitive is skipped),
/// what to draw, and `user_data` handed to every callback. Get one from
/// `hearth_debug_draw_default()` (every flag 0, no callbacks), then edit it. The pointers a
/// callback receives are valid only during that call. Callbacks run on the calling thread,
/// inside `hearth_world_draw`; the world is locked meanwhile (reads work; changes, steps and
/// destroying the world are refused).
///
/// Colours (`0xRRGGBBAA`): shapes by their body's state — static 0x8C8C8CFF, kinematic
/// 0x4C8CE6FF, awake dynamic 0xE68C33FF, sleeping dynamic 0x8C7359FF; AABBs 0xCC33CCFF;
/// contact points 0xE63333FF, normals 0x33CC33FF, impulses 0xE6E633FF; joints 0x33CCCCFF.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthDebugDraw {
    /// Draws a segment (AABB edges, contact normals and impulses, joint links), or NULL.
    pub draw_segment: HearthDrawSegment,
    /// Draws a filled convex polygon (box and hull faces, triangles, the plane patch), or NULL.
    pub draw_polygon: HearthDrawPolygon,
    /// Draws a sphere shape, or NULL.
    pub draw_sphere: HearthDrawSphere,
    /// Draws a capsule shape, or NULL.
    pub draw_capsule: HearthDrawCapsule,
    /// Draws a frame (centres of mass, joint frames), or NULL.
    pub draw_transform: HearthDrawTransform,
    /// Draws a point (contact points, joint anchors), or NULL.
    pub draw_point: HearthDrawPoint,
    /// Passed to every callback.
    pub user_data: *mut c_void,
    /// 1: every shape of every enabled body (disabled bodies are not drawn): a sphere as a
    /// sphere, a capsule as a capsule, a box as its six faces (polygons), a plane as a square
    /// polygon 20 m across centred on the plane's point nearest the origin, a hull as its
    /// faces, a triangle mesh as its triangles, a heightfield as two triangles per cell
    /// without a hole (all of them: a large heightfield draws many).
    pub draw_shapes: u8,
    /// 1: each bounded shape's tight bounding box as 12 segments.
    pub draw_aabbs: u8,
    /// 1: each point of each touching contact: a point, its normal as a segment 0.25 m long,
    /// and its normal impulse of the last step as a segment along the normal of 0.1 m per N·s
    /// (when positive).
    pub draw_contacts: u8,
    /// 1: each unbroken joint between enabled bodies: its anchors (points), the segment between
    /// them, and a segment from each body's centre of mass to its anchor.
    pub draw_joints: u8,
    /// 1: each dynamic body's centre of mass and orientation (a transform).
    pub draw_centers_of_mass: u8,
    /// Set by `hearth_debug_draw_default()`; do not change.
    pub internal_value: u32,
}

/// No callbacks, nothing drawn, `user_data` NULL.
#[no_mangle]
pub extern "C" fn hearth_debug_draw_default() -> HearthDebugDraw {
    HearthDebugDraw {
        draw_segment: None,
        draw_polygon: None,
        draw_sphere: None,
        draw_capsule: None,
        draw_transform: None,
        draw_point: None,
        user_data: std::ptr::null_mut(),
        draw_shapes: 0,
        draw_aabbs: 0,
        draw_contacts: 0,
        draw_joints: 0,
        draw_centers_of_mass: 0,
        internal_value: DEF_COOKIE,
    }
}

/// The core's `DebugDraw` calling the C callbacks.
struct CDraw<'a> {
    d: &'a HearthDebugDraw,
    /// Polygon vertices in C layout, reused across polygons.
    scratch: Vec<HearthVec3>,
}

impl DebugDraw for CDraw<'_> {
    fn segment(&mut self, a: Vec3, b: Vec3, color: u32) {
        if let Some(f) = self.d.draw_segment {
            let (a, b): (HearthVec3, HearthVec3) = (a.into(), b.into());
            unsafe { f(self.d.user_data, &a, &b, color) }
        }
    }
    fn polygon(&mut self, vertices: &[Vec3], color: u32) {
        if let Some(f) = self.d.draw_polygon {
            self.scratch.clear();
            self.scratch.extend(vertices.iter().map(|&v| HearthVec3::from(v)));
            unsafe {
                f(
                    self.d.user_data,
                    self.scratch.as_ptr(),
                    self.scratch.len() as u32,
                    color,
                )
            }
        }
    }
    fn sphere(&mut self, center: Vec3, radius: f32, color: u32) {
        if let Some(f) = self.d.draw_sphere {
            let c: HearthVec3 = center.into();
            unsafe { f(self.d.user_data, &c, radius, color) }
        }
    }
    fn capsule(&mut self, a: Vec3, b: Vec3, radius: f32, color: u32) {
        if let Some(f) = self.d.draw_capsule {
            let (a, b): (HearthVec3, HearthVec3) = (a.into(), b.into());
            unsafe { f(self.d.user_data, &a, &b, radius, color) }
        }
    }
    fn transform(&mut self, xf: Transform) {
        if let Some(f) = self.d.draw_transform {
            let t: HearthTransform = xf.into();
            unsafe { f(self.d.user_data, &t) }
        }
    }
    fn point(&mut self, p: Vec3, size: f32, color: u32) {
        if let Some(f) = self.d.draw_point {
            let p: HearthVec3 = p.into();
            unsafe { f(self.d.user_data, &p, size, color) }
        }
    }
}

/// Restores the world's lock and phase when drawing ends.
struct Unlock<'a> {
    world: &'a HearthWorld,
    locked: bool,
    phase: u8,
}

impl Drop for Unlock<'_> {
    fn drop(&mut self) {
        self.world.locked.set(self.locked);
        self.world.phase.set(self.phase);
    }
}

/// Draws the world through `draw`'s callbacks as its flags ask (see `HearthDebugDraw`). The
/// world is locked while the callbacks run. May be called from another callback (reads).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, draw), `HEARTH_ERROR_INVALID_ARGUMENT` (draw
/// not from `hearth_debug_draw_default()`, a flag not 0 or 1; nothing is drawn).
///
/// # Safety
/// `world` must be NULL or a live world; `draw` NULL or readable, its callbacks NULL or
/// callable with its `user_data`.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_draw(world: *const HearthWorld, draw: *const HearthDebugDraw) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let d = validate::input(draw, "draw")?;
        validate::cookie(d.internal_value, "hearth_debug_draw")?;
        let flags = DrawFlags {
            shapes: validate::flag(d.draw_shapes, "draw_shapes")?,
            aabbs: validate::flag(d.draw_aabbs, "draw_aabbs")?,
            contacts: validate::flag(d.draw_contacts, "draw_contacts")?,
            joints: validate::flag(d.draw_joints, "draw_joints")?,
            centers_of_mass: validate::flag(d.draw_centers_of_mass, "draw_centers_of_mass")?,
        };
        let handle = &*world;
        let _unlock = Unlock {
            world: handle,
            locked: handle.locked.replace(true),
            phase: handle.phase.replace(PHASE_DRAW),
        };
        let mut c = CDraw { d, scratch: Vec::new() };
        w.draw(&mut c, flags);
        Ok(())
    })
}
