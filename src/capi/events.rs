//! Event exports: contact, sensor and body events read after a step, and the pair-filter and
//! pre-solve callbacks run inside it (`events.rs` in the core says when each fires).
//!
//! The events of a step are copied into C-layer storage (`EventScratch`, outside `World`)
//! at its end and handed out as pointer + count, valid until the next step or destroy; the
//! callbacks are run by `hearth_world_step` between the core's stages like the user
//! generators (`capi/world.rs` explains the lock), reads only.

use std::os::raw::c_void;

use super::error::*;
use super::types::*;
use super::validate;
use super::world::{world_mut, world_ref, HearthWorld, PHASE_CORE, PHASE_FILTER};
use crate::events::{ContactEvent, SensorEvent};
use crate::world::World;

/// Two shapes (and their bodies) that started or stopped touching.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthContactEvent {
    /// The first shape.
    pub shape_a: HearthShapeId,
    /// The second shape.
    pub shape_b: HearthShapeId,
    /// The body of `shape_a`.
    pub body_a: HearthBodyId,
    /// The body of `shape_b`.
    pub body_b: HearthBodyId,
}

/// Two shapes that met faster than the world's `hit_event_threshold`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthContactHitEvent {
    /// The first shape.
    pub shape_a: HearthShapeId,
    /// The second shape.
    pub shape_b: HearthShapeId,
    /// The body of `shape_a`.
    pub body_a: HearthBodyId,
    /// The body of `shape_b`.
    pub body_b: HearthBodyId,
    /// Where they met (world, m): the fastest approaching point.
    pub point: HearthVec3,
    /// Unit normal from A to B.
    pub normal: HearthVec3,
    /// Approach speed along the normal at impact (m/s): the relative normal speed at the
    /// start of the step carried over the gap still open by gravity (exact for a free fall).
    pub approach_speed: f32,
}

/// The contact events of the last step. The arrays belong to the world and stay valid until
/// the next `hearth_world_step` or `hearth_world_destroy` of this world; do not free them.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthContactEvents {
    /// Pairs that started touching (a manifold point within `linear_slop`), in a
    /// deterministic order.
    pub begin: *const HearthContactEvent,
    /// Entries in `begin`.
    pub begin_count: usize,
    /// Pairs that stopped touching (no manifold point left: further apart than the
    /// speculative distance, 2 cm plus the step's relative motion), whose bounds parted, or
    /// whose shape or body was destroyed (since the step before; those ids are no longer
    /// live).
    pub end: *const HearthContactEvent,
    /// Entries in `end`.
    pub end_count: usize,
    /// Contacts that the solver pushed after an approach faster than the threshold.
    pub hit: *const HearthContactHitEvent,
    /// Entries in `hit`.
    pub hit_count: usize,
}

/// A sensor shape and a shape that started or stopped overlapping it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthSensorEvent {
    /// The sensor.
    pub sensor_shape: HearthShapeId,
    /// The other shape.
    pub visitor_shape: HearthShapeId,
    /// The sensor's body.
    pub sensor_body: HearthBodyId,
    /// The other shape's body.
    pub visitor_body: HearthBodyId,
}

/// The sensor events of the last step; arrays owned by the world as in
/// `HearthContactEvents`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSensorEvents {
    /// Overlaps that began.
    pub begin: *const HearthSensorEvent,
    /// Entries in `begin`.
    pub begin_count: usize,
    /// Overlaps that ended, or whose sensor, visitor or body was destroyed.
    pub end: *const HearthSensorEvent,
    /// Entries in `end`.
    pub end_count: usize,
}

/// A body that moved in the last step, or fell asleep in it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBodyMoveEvent {
    /// The body.
    pub body: HearthBodyId,
    /// Its transform after the step.
    pub transform: HearthTransform,
    /// Its `user_data`.
    pub user_data: u64,
    /// 1 when it fell asleep in this step (it then stays put until woken), else 0.
    pub fell_asleep: u8,
}

/// The body events of the last step; arrays owned by the world as in
/// `HearthContactEvents`. Joint break events are read with `hearth_world_get_broken_joints`
/// (same lifetime).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBodyEvents {
    /// One event per body with `enable_move_events` whose transform changed in the step (or
    /// since it was last reported), and one per such body that fell asleep; awake bodies
    /// first, in the order of the world's awake list.
    pub moves: *const HearthBodyMoveEvent,
    /// Entries in `moves`.
    pub move_count: usize,
}

/// A contact manifold point.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthManifoldPoint {
    /// World point midway between the surfaces (m).
    pub point: HearthVec3,
    /// Signed distance along the normal (m): negative overlapping, positive a gap.
    pub separation: f32,
}

/// What the pre-solve callback sees: a touching contact and its manifold. Valid only during
/// the call.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthPreSolveContact {
    /// The first shape.
    pub shape_a: HearthShapeId,
    /// The second shape.
    pub shape_b: HearthShapeId,
    /// The body of `shape_a`.
    pub body_a: HearthBodyId,
    /// The body of `shape_b`.
    pub body_b: HearthBodyId,
    /// Unit normal from A to B.
    pub normal: HearthVec3,
    /// The manifold points (`point_count` of them, 1..=4). A shape against a mesh or
    /// heightfield may touch along several normals; these are of its first manifold with
    /// points.
    pub points: *const HearthManifoldPoint,
    /// Entries in `points`.
    pub point_count: u32,
}

/// A pair-filter callback: called during `hearth_world_step` (on its thread, after the
/// force generators) for every pair of shapes the broad phase would make a new contact for.
/// Return 0 to keep the pair from ever touching until it is proposed again, any other value
/// to let it. A pair is proposed again when either shape's broad-phase box is refit (its body
/// moved past the box's 0.1 m margin, was teleported, or got a shape), so a rejected pair of
/// shapes that both stay put is not asked about again. It may read the world; changes return
/// `HEARTH_ERROR_WORLD_LOCKED`. It must return normally (no longjmp, no C++ exception).
pub type HearthPairFilterCallback = Option<
    unsafe extern "C" fn(
        user_data: *mut c_void,
        world: *mut HearthWorld,
        shape_a: HearthShapeId,
        shape_b: HearthShapeId,
    ) -> u8,
>;

/// A pre-solve callback: called during `hearth_world_step` (on its thread, after the narrow
/// phase and the contact generators, before the solver) once for every touching contact with
/// an awake body, sensors excepted. Return 0 to disable the contact for this step (it does
/// not push; a one-way platform, for one), any other value to keep it. Contact begin and end
/// events follow the shapes' geometry whether or not the contact is disabled. It may read the
/// world; changes return `HEARTH_ERROR_WORLD_LOCKED`. It must return normally (no longjmp, no
/// C++ exception). `contact` is valid only during the call.
pub type HearthPreSolveCallback = Option<
    unsafe extern "C" fn(user_data: *mut c_void, world: *mut HearthWorld, contact: *const HearthPreSolveContact) -> u8,
>;

type PairFilterFn = unsafe extern "C" fn(*mut c_void, *mut HearthWorld, HearthShapeId, HearthShapeId) -> u8;
type PreSolveFn = unsafe extern "C" fn(*mut c_void, *mut HearthWorld, *const HearthPreSolveContact) -> u8;

/// C-layer storage for events and callbacks (outside `World`, so pointers given to C never
/// point into memory a `&mut World` covers).
#[derive(Default)]
pub(crate) struct EventScratch {
    pair_filter: Option<(PairFilterFn, usize)>,
    pre_solve: Option<(PreSolveFn, usize)>,
    contact_begin: Vec<HearthContactEvent>,
    contact_end: Vec<HearthContactEvent>,
    contact_hit: Vec<HearthContactHitEvent>,
    sensor_begin: Vec<HearthSensorEvent>,
    sensor_end: Vec<HearthSensorEvent>,
    moves: Vec<HearthBodyMoveEvent>,
}

fn contact(e: &ContactEvent) -> HearthContactEvent {
    HearthContactEvent {
        shape_a: e.shape_a.into(),
        shape_b: e.shape_b.into(),
        body_a: e.body_a.into(),
        body_b: e.body_b.into(),
    }
}

fn sensor(e: &SensorEvent) -> HearthSensorEvent {
    HearthSensorEvent {
        sensor_shape: e.sensor_shape.into(),
        visitor_shape: e.visitor_shape.into(),
        sensor_body: e.sensor_body.into(),
        visitor_body: e.visitor_body.into(),
    }
}

/// Copies the step's events into the C arrays (called by `hearth_world_step` at its end).
pub(crate) fn publish(w: &World, s: &mut EventScratch) {
    let ev = w.events();
    s.contact_begin.clear();
    s.contact_begin.extend(ev.contact_begin.iter().map(contact));
    s.contact_end.clear();
    s.contact_end.extend(ev.contact_end.iter().map(contact));
    s.contact_hit.clear();
    s.contact_hit
        .extend(ev.contact_hit.iter().map(|e| HearthContactHitEvent {
            shape_a: e.shape_a.into(),
            shape_b: e.shape_b.into(),
            body_a: e.body_a.into(),
            body_b: e.body_b.into(),
            point: e.point.into(),
            normal: e.normal.into(),
            approach_speed: e.speed,
        }));
    s.sensor_begin.clear();
    s.sensor_begin.extend(ev.sensor_begin.iter().map(sensor));
    s.sensor_end.clear();
    s.sensor_end.extend(ev.sensor_end.iter().map(sensor));
    s.moves.clear();
    s.moves.extend(ev.body_moves.iter().map(|e| HearthBodyMoveEvent {
        body: e.body.into(),
        transform: e.transform.into(),
        user_data: e.user_data,
        fell_asleep: e.fell_asleep as u8,
    }));
}

/// Runs the pair filter over the broad phase's candidates (between `find_pairs` and
/// `collide_pairs`), holding no reference to the world while C runs.
///
/// # Safety
/// `world` must be a live, locked world between those stages.
pub(crate) unsafe fn run_pair_filter(world: *mut HearthWorld) {
    let handle = &*world;
    let Some((f, user_data)) = (*handle.events.get()).pair_filter else {
        return;
    };
    let core: *mut World = handle.world.get();
    let n = (*core).pair_candidate_count();
    handle.phase.set(PHASE_FILTER);
    for i in 0..n {
        let (a, b) = (*core).pair_candidate(i);
        let keep = f(user_data as *mut c_void, world, a.into(), b.into()) != 0;
        (*core).keep_pair_candidate(i, keep);
    }
    handle.phase.set(PHASE_CORE);
}

/// Runs the pre-solve callback over the touching contacts (before `finish_step`).
///
/// # Safety
/// `world` must be a live, locked world between those stages.
pub(crate) unsafe fn run_pre_solve(world: *mut HearthWorld) {
    let handle = &*world;
    let Some((f, user_data)) = (*handle.events.get()).pre_solve else {
        return;
    };
    let core: *mut World = handle.world.get();
    let n = (*core).pre_solve_count();
    handle.phase.set(PHASE_FILTER);
    for i in 0..n {
        let c = (*core).pre_solve_contact(i);
        let mut points = [HearthManifoldPoint::default(); 4];
        for (o, p) in points.iter_mut().zip(c.manifold.points()) {
            *o = HearthManifoldPoint {
                point: p.point.into(),
                separation: p.separation,
            };
        }
        let contact = HearthPreSolveContact {
            shape_a: c.shape_a.into(),
            shape_b: c.shape_b.into(),
            body_a: c.body_a.into(),
            body_b: c.body_b.into(),
            normal: c.manifold.normal.into(),
            points: points.as_ptr(),
            point_count: c.manifold.count as u32,
        };
        if f(user_data as *mut c_void, world, &contact) == 0 {
            (*core).disable_pre_solve_contact(i);
        }
    }
    handle.phase.set(PHASE_CORE);
}

/// Sets (or with a NULL `callback` clears) the pair-filter callback
/// (`HearthPairFilterCallback`); `user_data` is passed to it as is. Replaces any earlier one;
/// pairs that already have a contact keep it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world; the callback must stay callable and `user_data`
/// valid for it while it is set.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_set_pair_filter_callback(
    world: *mut HearthWorld,
    callback: HearthPairFilterCallback,
    user_data: *mut c_void,
) -> HearthResult {
    guard(|| {
        world_mut(world)?;
        (*(*world).events.get()).pair_filter = callback.map(|f| (f, user_data as usize));
        Ok(())
    })
}

/// Sets (or with a NULL `callback` clears) the pre-solve callback (`HearthPreSolveCallback`);
/// `user_data` is passed to it as is. Replaces any earlier one.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world; the callback must stay callable and `user_data`
/// valid for it while it is set.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_set_pre_solve_callback(
    world: *mut HearthWorld,
    callback: HearthPreSolveCallback,
    user_data: *mut c_void,
) -> HearthResult {
    guard(|| {
        world_mut(world)?;
        (*(*world).events.get()).pre_solve = callback.map(|f| (f, user_data as usize));
        Ok(())
    })
}

/// Reads the contact events of the last step (`HearthContactEvents`; empty before the first
/// step). Shapes report them as their `enable_contact_events` and `enable_hit_events` say.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_events` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_contact_events(
    world: *const HearthWorld,
    out_events: *mut HearthContactEvents,
) -> HearthResult {
    guard(|| {
        world_ref(world)?;
        let out = validate::output(out_events, "out_events")?;
        let s = &*(*world).events.get();
        *out = HearthContactEvents {
            begin: s.contact_begin.as_ptr(),
            begin_count: s.contact_begin.len(),
            end: s.contact_end.as_ptr(),
            end_count: s.contact_end.len(),
            hit: s.contact_hit.as_ptr(),
            hit_count: s.contact_hit.len(),
        };
        Ok(())
    })
}

/// Reads the sensor events of the last step (`HearthSensorEvents`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_events` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_sensor_events(
    world: *const HearthWorld,
    out_events: *mut HearthSensorEvents,
) -> HearthResult {
    guard(|| {
        world_ref(world)?;
        let out = validate::output(out_events, "out_events")?;
        let s = &*(*world).events.get();
        *out = HearthSensorEvents {
            begin: s.sensor_begin.as_ptr(),
            begin_count: s.sensor_begin.len(),
            end: s.sensor_end.as_ptr(),
            end_count: s.sensor_end.len(),
        };
        Ok(())
    })
}

/// Reads the body move events of the last step (`HearthBodyEvents`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_events` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_body_events(
    world: *const HearthWorld,
    out_events: *mut HearthBodyEvents,
) -> HearthResult {
    guard(|| {
        world_ref(world)?;
        let out = validate::output(out_events, "out_events")?;
        let s = &*(*world).events.get();
        *out = HearthBodyEvents {
            moves: s.moves.as_ptr(),
            move_count: s.moves.len(),
        };
        Ok(())
    })
}
