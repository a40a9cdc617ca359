//! World exports: defaults, create, destroy, step, settings, bulk read-back; and the lock
//! that makes host callbacks sound.
//!
//! # Callbacks and the world lock
//!
//! User force and contact generators are C functions called during `hearth_world_step`,
//! with the world's own `HearthWorld *`, through which they read state and apply forces.
//! Rust must then never hold a `&mut World` while C code runs, or the C code's reads
//! (`&World`) and forces (`&mut World`) would alias it. So the core's step is split into
//! stages (`World::begin_step`, `collide_step`, `finish_step`) and `hearth_world_step` drives
//! them itself: each stage borrows the world mutably for its own duration only, and the
//! callbacks run between stages while the driver holds nothing but the raw pointer
//! (`capi/callback.rs`, `run_force_callbacks` / `run_contact_callbacks`). Every export a
//! callback calls forms its own short borrow from that pointer, so at any moment there is at
//! most one `&mut World`, or only `&World`s. The arrays a callback is given live in
//! C-layer storage outside `World` (`CallbackScratch`, the contact sink).
//!
//! While a step runs the world is `locked` and in a `phase`:
//! * reads (`hearth_*_get_*`, `hearth_world_get_*`) work in every phase;
//! * in the force phase (`PHASE_FORCES`, user force generators) `hearth_body_apply_force`,
//!   `hearth_body_apply_torque`, `hearth_body_apply_force_at_point` and
//!   `hearth_particle_apply_force` work too;
//! * in the contact phase (`PHASE_CONTACTS`) `hearth_contact_sink_add` works;
//! * in the record phase (`PHASE_RECORD`, a recording's write callback after the core's
//!   stages, `capi/record.rs`) only reads work;
//! * in the filter phase (`PHASE_FILTER`, the pair-filter and pre-solve callbacks,
//!   `capi/events.rs`) only reads work;
//! * every other mutation (create, destroy, set, attach, step) returns
//!   `HEARTH_ERROR_WORLD_LOCKED` before any `&mut` to the world is formed, and
//!   `hearth_world_destroy` is ignored.

use std::cell::{Cell, UnsafeCell};
use std::panic::{catch_unwind, AssertUnwindSafe};

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use crate::world::{Integrator, World, WorldSettings};

/// Semi-implicit (symplectic) Euler integration (default).
pub const HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER: u32 = 0;
/// Fourth-order Runge–Kutta for bodies that no contact touches during the step.
pub const HEARTH_INTEGRATOR_RK4: u32 = 1;

/// Settings of a world. Get one from `hearth_world_def_default()`, then edit it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthWorldDef {
    /// Gravity (m/s², length up to 1e4). Default (0, -9.81, 0).
    pub gravity: HearthVec3,
    /// Solver sub-steps per step, 1..=64. Default 6.
    pub substeps: u32,
    /// `HEARTH_INTEGRATOR_*`. Default semi-implicit Euler.
    pub integrator: u32,
    /// 1 to let still islands sleep (default), 0 to keep everything awake.
    pub enable_sleep: u8,
    /// Speed (m/s and rad/s, 0..=1e4) below which a body counts as still: an average of its
    /// v² + ω² over the last 0.1 s (half-life) under its square, and its current speed under
    /// twice it. Default 0.05.
    pub sleep_threshold: f32,
    /// Seconds an island must stay still before it sleeps (finite, >= 0). Default 0.5.
    pub time_to_sleep: f32,
    /// Contact stiffness (Hz, 1e-3..=1e6), capped at a quarter of the sub-step rate. Default
    /// 120.
    pub contact_hertz: f32,
    /// Contact damping ratio (0..=1000). Default 10.
    pub contact_damping_ratio: f32,
    /// Fastest speed at which overlapping bodies are pushed apart (m/s, 1e-6..=1e4). Default 3.
    pub contact_push_max_velocity: f32,
    /// Approach speed below which contacts do not bounce (m/s, 0..=1e4). Default 1.
    pub restitution_threshold: f32,
    /// Largest speed a body or particle may reach (m/s, 1e-3..=1e4). Default 400. The solver
    /// caps every velocity it produces (forces, impulses, contacts, joints, particles, soft
    /// bodies, kinematic targets) at it, keeping the direction; velocities a host sets must not
    /// exceed it.
    pub max_linear_speed: f32,
    /// Soft velocity sweeps per sub-step (each sub-step also runs one rigid relax sweep),
    /// 1..=64. Default 1: more sub-steps converge better than more sweeps.
    pub velocity_iterations: u32,
    /// Set by `hearth_world_def_default()`; do not change.
    pub internal_value: u32,
    /// Largest angular speed a body may reach (rad/s, 1e-3..=1e4). Default 100π ≈ 314.16 (50
    /// turns a second). Capped like `max_linear_speed`; angular velocities a host sets must
    /// not exceed it. (After `internal_value`: fields are only ever appended, so existing
    /// offsets stay.)
    pub max_angular_speed: f32,
    /// Approach speed above which a contact whose shapes enable hit events reports a hit
    /// (m/s, 0..=1e4). Default 1.
    pub hit_event_threshold: f32,
    /// Threads a step may use, 1..=64. Default 1: everything on the stepping thread. Above 1,
    /// the parallel stages (the narrow phase, bodies into and out of the solver) run on the
    /// host's job system when `enqueue_task` and `finish_task` are set, else on
    /// `worker_count − 1` threads the world starts and parks between steps. Results are bit
    /// for bit the same at every count, on any threads, in any order
    /// (`hearth_world_get_hash`).
    pub worker_count: u32,
    /// The host's enqueue callback (`HearthEnqueueTaskFn`), or NULL (default). Set both
    /// `enqueue_task` and `finish_task`, or neither. Both are called on the stepping thread;
    /// the ranges they run may call no Hearth function.
    pub enqueue_task: super::tasks::HearthEnqueueTaskFn,
    /// The host's finish callback (`HearthFinishTaskFn`), or NULL (default).
    pub finish_task: super::tasks::HearthFinishTaskFn,
    /// Passed to `enqueue_task` and `finish_task` as `user_context`; Hearth never reads it.
    /// Default NULL.
    pub user_task_context: *mut std::os::raw::c_void,
}

/// The world handle: opaque to C. Owns everything in the world. One thread at a time.
pub struct HearthWorld {
    /// Set while a step runs; mutations from callbacks see it and fail with
    /// `HEARTH_ERROR_WORLD_LOCKED` before any `&mut` to the world is formed.
    pub(crate) locked: Cell<bool>,
    /// Which callbacks are running (`PHASE_*`), so each may do its phase's own operations.
    pub(crate) phase: Cell<u8>,
    /// Set when a step panicked: the state may be broken, so no more steps.
    pub(crate) poisoned: Cell<bool>,
    pub(crate) world: UnsafeCell<World>,
    /// C-layer storage for callback contexts and the expired report (outside `World`).
    pub(crate) scratch: UnsafeCell<super::callback::CallbackScratch>,
    /// The contact sink handed to user contact generators.
    pub(crate) sink: UnsafeCell<super::callback::HearthContactSink>,
    /// The running recording, if any (`capi/record.rs`).
    pub(crate) recording: UnsafeCell<Option<super::record::Recording>>,
    /// Published events and the pair-filter and pre-solve callbacks (`capi/events.rs`).
    pub(crate) events: UnsafeCell<super::events::EventScratch>,
}

/// Not stepping.
pub(crate) const PHASE_IDLE: u8 = 0;
/// Inside the core's stages: no host code runs.
pub(crate) const PHASE_CORE: u8 = 1;
/// User force generators run: forces may be applied.
pub(crate) const PHASE_FORCES: u8 = 2;
/// User contact generators run: contacts may be added to the sink.
pub(crate) const PHASE_CONTACTS: u8 = 3;
/// A recording's write callback runs: reads only.
pub(crate) const PHASE_RECORD: u8 = 4;
/// The pair-filter or pre-solve callback runs: reads only (`capi/events.rs`).
pub(crate) const PHASE_FILTER: u8 = 5;
/// A debug-draw callback runs (`hearth_world_draw`): reads only.
pub(crate) const PHASE_DRAW: u8 = 6;

/// Shared access for reads.
///
/// # Safety
/// `ptr` must be NULL or a live world from `hearth_world_create`.
pub(crate) unsafe fn world_ref<'a>(ptr: *const HearthWorld) -> Result<&'a World, Failure> {
    let w = ptr.as_ref().ok_or_else(|| Failure::null("world"))?;
    Ok(&*w.world.get())
}

/// Exclusive access for mutations; refused while the world is stepping.
///
/// # Safety
/// `ptr` must be NULL or a live world from `hearth_world_create`.
pub(crate) unsafe fn world_mut<'a>(ptr: *mut HearthWorld) -> Result<&'a mut World, Failure> {
    let w = ptr.as_ref().ok_or_else(|| Failure::null("world"))?;
    if w.locked.get() {
        return Err(Failure::new(
            HEARTH_ERROR_WORLD_LOCKED,
            "the world is locked: it is stepping (called from a callback)",
        ));
    }
    Ok(&mut *w.world.get())
}

/// Exclusive access for the operations of one phase: allowed when the world is not
/// stepping, or when it is in `phase` (a callback doing its phase's own work). No other
/// reference to the world is alive then: the step driver holds none while callbacks run.
///
/// # Safety
/// `ptr` must be NULL or a live world from `hearth_world_create`.
pub(crate) unsafe fn world_mut_in_phase<'a>(ptr: *mut HearthWorld, phase: u8) -> Result<&'a mut World, Failure> {
    let w = ptr.as_ref().ok_or_else(|| Failure::null("world"))?;
    if w.locked.get() && w.phase.get() != phase {
        return Err(Failure::new(
            HEARTH_ERROR_WORLD_LOCKED,
            "the world is locked: it is stepping, and this call is not allowed in the running callback",
        ));
    }
    Ok(&mut *w.world.get())
}

pub(crate) fn settings_from_def(def: &HearthWorldDef) -> Result<WorldSettings, Failure> {
    validate::cookie(def.internal_value, "hearth_world_def")?;
    let integrator = match def.integrator {
        HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER => Integrator::SemiImplicitEuler,
        HEARTH_INTEGRATOR_RK4 => Integrator::Rk4,
        v => {
            return Err(Failure::invalid(format!(
                "integrator must be a HEARTH_INTEGRATOR_* code, got {v}"
            )))
        }
    };
    let s = WorldSettings {
        gravity: def.gravity.into(),
        substeps: def.substeps,
        integrator,
        enable_sleep: validate::flag(def.enable_sleep, "enable_sleep")?,
        sleep_threshold: def.sleep_threshold,
        time_to_sleep: def.time_to_sleep,
        contact_hertz: def.contact_hertz,
        contact_damping_ratio: def.contact_damping_ratio,
        contact_push_max_velocity: def.contact_push_max_velocity,
        restitution_threshold: def.restitution_threshold,
        max_linear_speed: def.max_linear_speed,
        max_angular_speed: def.max_angular_speed,
        velocity_iterations: def.velocity_iterations,
        hit_event_threshold: def.hit_event_threshold,
        worker_count: def.worker_count,
        ..WorldSettings::default()
    };
    s.validate()?;
    Ok(s)
}

/// The default world settings: gravity (0, -9.81, 0), 6 sub-steps, sleep on.
#[no_mangle]
pub extern "C" fn hearth_world_def_default() -> HearthWorldDef {
    let s = WorldSettings::default();
    HearthWorldDef {
        gravity: s.gravity.into(),
        substeps: s.substeps,
        integrator: HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER,
        enable_sleep: 1,
        sleep_threshold: s.sleep_threshold,
        time_to_sleep: s.time_to_sleep,
        contact_hertz: s.contact_hertz,
        contact_damping_ratio: s.contact_damping_ratio,
        contact_push_max_velocity: s.contact_push_max_velocity,
        restitution_threshold: s.restitution_threshold,
        max_linear_speed: s.max_linear_speed,
        velocity_iterations: s.velocity_iterations,
        internal_value: DEF_COOKIE,
        max_angular_speed: s.max_angular_speed,
        hit_event_threshold: s.hit_event_threshold,
        worker_count: s.worker_count,
        enqueue_task: None,
        finish_task: None,
        user_task_context: std::ptr::null_mut(),
    }
}

/// Creates a world. On success `*out_world` owns it until `hearth_world_destroy`. Every world
/// gets a tag no other live world has, carried in the ids it hands out, so ids of one world
/// are never accepted by another while both live.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (def or out_world NULL),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_world_def_default()`, a field out
/// of range, `worker_count` outside 1..=64, or only one of `enqueue_task` and `finish_task`
/// set), `HEARTH_ERROR_LIMIT_REACHED` (4,095 worlds are alive, or the world's worker
/// threads could not be started). `*out_world` is written
/// only on success.
///
/// # Safety
/// `def` must be NULL or point to a `HearthWorldDef`; `out_world` must be NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_create(
    def: *const HearthWorldDef,
    out_world: *mut *mut HearthWorld,
) -> HearthResult {
    guard(|| {
        let def = validate::input(def, "def")?;
        let out = validate::output(out_world, "out_world")?;
        let settings = settings_from_def(def)?;
        let host = super::tasks::HostTasks::from_def(
            def.enqueue_task,
            def.finish_task,
            def.user_task_context,
            settings.worker_count,
        )?;
        let world = match host {
            // The host's job system replaces the world's own threads: none are started.
            Some(host) => {
                let mut world = World::new(WorldSettings {
                    worker_count: 1,
                    ..settings
                })?;
                world.set_task_runner(Box::new(host))?;
                world
            }
            None => World::new(settings)?,
        };
        let boxed = Box::new(HearthWorld {
            locked: Cell::new(false),
            phase: Cell::new(PHASE_IDLE),
            poisoned: Cell::new(false),
            world: UnsafeCell::new(world),
            scratch: UnsafeCell::new(Default::default()),
            sink: UnsafeCell::new(Default::default()),
            recording: UnsafeCell::new(None),
            events: UnsafeCell::new(Default::default()),
        });
        *out = Box::into_raw(boxed);
        Ok(())
    })
}

/// Destroys a world and everything in it. NULL is a no-op. Must not be called from a
/// callback of the same world (it is then ignored).
///
/// # Safety
/// `world` must be NULL or a live world from `hearth_world_create`, not used afterwards.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_destroy(world: *mut HearthWorld) {
    guard_value((), || {
        if world.is_null() || (*world).locked.get() {
            return;
        }
        drop(Box::from_raw(world));
    })
}

/// Advances the world by `dt` seconds: 0 does nothing, otherwise 0.001 <= `dt` <= 0.1 (see
/// "Supported ranges" at the top of this header). User generators run
/// inside it, on this thread: force generators after the built-in ones at the start of the
/// step, contact generators after the narrow phase (see their callback types).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (dt outside the range),
/// `HEARTH_ERROR_WORLD_LOCKED` (called from a callback), `HEARTH_ERROR_PANIC` (an internal
/// error; the world then refuses further steps), `HEARTH_ERROR_IO` (the world's recording
/// failed to write after the last step: the recording has stopped, this step did not run, and
/// the next one will).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_step(world: *mut HearthWorld, dt: f32) -> HearthResult {
    guard(|| {
        let handle = world.as_ref().ok_or_else(|| Failure::null("world"))?;
        if handle.poisoned.get() {
            return Err(Failure::new(
                HEARTH_ERROR_PANIC,
                "the world panicked in an earlier step and cannot step again",
            ));
        }
        if handle.locked.get() {
            return Err(Failure::new(
                HEARTH_ERROR_WORLD_LOCKED,
                "the world is locked: it is stepping (called from a callback)",
            ));
        }
        crate::error::check_time_step("dt", dt)?;
        // A recording whose output failed after the last step says so now, and this step
        // does not run.
        super::record::take_failure(handle)?;
        handle.locked.set(true);
        handle.phase.set(PHASE_CORE);
        let r = catch_unwind(AssertUnwindSafe(|| {
            let started = std::time::Instant::now();
            drive_step(world, dt)?;
            super::record::after_step(world, dt, started.elapsed().as_secs_f32());
            Ok(())
        }));
        handle.phase.set(PHASE_IDLE);
        handle.locked.set(false);
        match r {
            Ok(r) => r,
            Err(p) => {
                handle.poisoned.set(true);
                std::panic::resume_unwind(p)
            }
        }
    })
}

/// Runs the core's stages with the user generators between them. Each `(*core).stage(dt)`
/// borrows the world for that call only; while callbacks run only the raw pointer is held.
///
/// # Safety
/// `world` must be a live, locked world.
unsafe fn drive_step(world: *mut HearthWorld, dt: f32) -> Result<(), Failure> {
    let handle = &*world;
    let core: *mut World = handle.world.get();
    if !(*core).begin_step(dt)? {
        return Ok(());
    }
    handle.phase.set(PHASE_FORCES);
    super::callback::run_force_callbacks(world, dt);
    handle.phase.set(PHASE_CORE);
    #[cfg(test)]
    if tests::PANIC_MID_STEP.with(Cell::get) {
        panic!("test hook: a panic injected between the force and collision stages");
    }
    (*core).find_pairs();
    super::events::run_pair_filter(world);
    (*core).collide_pairs(dt);
    handle.phase.set(PHASE_CONTACTS);
    super::callback::run_contact_callbacks(world, dt);
    handle.phase.set(PHASE_CORE);
    super::events::run_pre_solve(world);
    (*core).finish_step(dt);
    super::particle::publish_expired(&*core, &mut (*handle.scratch.get()).expired);
    super::events::publish(&*core, &mut *handle.events.get());
    Ok(())
}

/// Sets gravity (m/s², length up to 1e4) and wakes every dynamic body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (out of range),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_set_gravity(world: *mut HearthWorld, gravity: HearthVec3) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_gravity(gravity.into())?))
}

/// Reads gravity.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_gravity(world: *const HearthWorld, out: *mut HearthVec3) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out, "out")?;
        *out = w.settings.gravity.into();
        Ok(())
    })
}

/// Rebuilds the broad-phase tree top-down with a binned surface-area heuristic. Bodies
/// created one by one (a level load) leave the tree deeper and looser than that; after a
/// rebuild, ray casts, overlaps and the search for new contact pairs test fewer boxes (the
/// 1,000-body pile as created: 26.8 -> 17.7 boxes per closest ray). Ids, contacts and
/// every query's results are unchanged, and so are the bodies' motions (new contacts are
/// made in shape order); particles meet shapes in the tree's order, so a world with
/// particles steps on differently. Each step rebuilds the part of the tree its moved
/// proxies enlarged; this is for the rest, after loading. Allocates scratch memory.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_WORLD_LOCKED` (called from a callback).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_rebuild_broadphase(world: *mut HearthWorld) -> HearthResult {
    guard(|| {
        world_mut(world)?.rebuild_broadphase();
        Ok(())
    })
}

/// Counters of a world, for tools and tests.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthWorldCounters {
    /// Live bodies of every type.
    pub body_count: u32,
    /// Awake kinematic and dynamic bodies.
    pub awake_body_count: u32,
    /// Live contacts (shape pairs whose bounds overlap).
    pub contact_count: u32,
    /// Contacts with manifold points in the last step.
    pub touching_contact_count: u32,
    /// Height of the broad-phase tree.
    pub tree_height: u32,
}

/// Reads the world's counters.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_counters(
    world: *const HearthWorld,
    out: *mut HearthWorldCounters,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out, "out")?;
        *out = HearthWorldCounters {
            body_count: w.body_count() as u32,
            awake_body_count: w.awake_body_count() as u32,
            contact_count: w.contact_count() as u32,
            touching_contact_count: w.counters.touching_contacts as u32,
            tree_height: w.tree_height(),
        };
        Ok(())
    })
}

/// Reads the transforms of `count` bodies into the caller-owned `out_transforms` (one call
/// per frame instead of one per body). Every id is checked first; on any error nothing is
/// written. `count == 0` succeeds and may pass NULL arrays.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (the message names the
/// first bad index).
///
/// # Safety
/// `bodies` must hold `count` ids and `out_transforms` room for `count` transforms.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_transforms(
    world: *const HearthWorld,
    bodies: *const HearthBodyId,
    count: usize,
    out_transforms: *mut HearthTransform,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        if count == 0 {
            return Ok(());
        }
        if bodies.is_null() {
            return Err(Failure::null("bodies"));
        }
        validate::output(out_transforms, "out_transforms")?;
        let ids = std::slice::from_raw_parts(bodies, count);
        for (i, id) in ids.iter().enumerate() {
            if !w.bodies.contains((*id).into()) {
                return Err(Failure::new(
                    HEARTH_ERROR_INVALID_ID,
                    format!("bodies[{i}] is not a live body of this world"),
                ));
            }
        }
        let out = std::slice::from_raw_parts_mut(out_transforms, count);
        for (o, id) in out.iter_mut().zip(ids) {
            *o = w.bodies.get((*id).into()).expect("checked").xf.into();
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        /// Test-only hook (compiled into unit tests only, never into the library or the
        /// header): makes `drive_step` panic after the force stage, while the core holds the
        /// world half stepped.
        pub(super) static PANIC_MID_STEP: Cell<bool> = const { Cell::new(false) };
    }

    #[test]
    fn a_world_that_panicked_mid_step_refuses_further_steps() {
        let def = hearth_world_def_default();
        let mut world: *mut HearthWorld = std::ptr::null_mut();
        unsafe {
            assert_eq!(hearth_world_create(&def, &mut world), HEARTH_OK);
            assert_eq!(hearth_world_step(world, 1.0 / 60.0), HEARTH_OK);
            // A real panic inside the step, caught by the step's own guard.
            let hook = std::panic::take_hook();
            std::panic::set_hook(Box::new(|_| {})); // keep the expected panic off the output
            PANIC_MID_STEP.with(|p| p.set(true));
            let r = hearth_world_step(world, 1.0 / 60.0);
            PANIC_MID_STEP.with(|p| p.set(false));
            std::panic::set_hook(hook);
            assert_eq!(r, HEARTH_ERROR_PANIC);
            let msg = with_last_error(|m| m.to_string());
            assert!(msg.contains("injected"), "the panic's own message: {msg}");
            assert!((*world).poisoned.get(), "the guard poisons the world");
            assert!(!(*world).locked.get(), "the lock is released after the panic");
            // The hook is off now, yet the world refuses every later step.
            for _ in 0..2 {
                assert_eq!(hearth_world_step(world, 1.0 / 60.0), HEARTH_ERROR_PANIC);
                let msg = with_last_error(|m| m.to_string());
                assert!(msg.contains("panicked in an earlier step"), "{msg}");
            }
            // Reads still work, and the world can be destroyed.
            let mut g = HearthVec3::default();
            assert_eq!(hearth_world_get_gravity(world, &mut g), HEARTH_OK);
            hearth_world_destroy(world);
        }
    }
}
