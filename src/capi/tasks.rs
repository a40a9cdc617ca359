//! The host's job system: the task callbacks of `HearthWorldDef` adapted to the core's
//! `parallel::TaskRunner` (Box2D v3's model). Hearth hands the host a range task and an item
//! count; the host runs it over ranges of its choosing, on threads of its choosing, and
//! Hearth waits for it in `finish_task`.

use std::any::Any;
use std::os::raw::c_void;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;

use super::error::Failure;
use crate::parallel::{Task, TaskRunner};

/// A range of work Hearth hands the host: call it with `start < end <= item_count` (the
/// count passed to the enqueue callback), a `worker_index` below the world's
/// `worker_count` that no other range running at the same moment uses, and the
/// `task_context` the enqueue callback was given. Every index of `0..item_count` must be
/// covered by exactly one call. Any thread may call it, in any order; it returns normally
/// (Hearth catches its own failures and reports them from `hearth_world_step`).
pub type HearthTaskFn =
    Option<unsafe extern "C" fn(start: u32, end: u32, worker_index: u32, task_context: *mut c_void)>;

/// The host's enqueue callback: arrange for `task` to run over `0..item_count` (split into
/// ranges of at least `min_range` items, except perhaps the last, or run whole) with
/// `task_context`, and return a handle the finish callback will wait on. Returning NULL
/// tells Hearth the task has already run to completion inside this call (and the finish
/// callback is not called). Called on the thread that called `hearth_world_step`, several
/// times per step; `user_context` is the def's `user_task_context`.
pub type HearthEnqueueTaskFn = Option<
    unsafe extern "C" fn(
        task: HearthTaskFn,
        item_count: u32,
        min_range: u32,
        task_context: *mut c_void,
        user_context: *mut c_void,
    ) -> *mut c_void,
>;

/// The host's finish callback: wait until every range of the task behind `user_task` (a
/// non-NULL handle the enqueue callback returned) has returned, then release the handle.
/// Called on the thread that called `hearth_world_step`.
pub type HearthFinishTaskFn = Option<unsafe extern "C" fn(user_task: *mut c_void, user_context: *mut c_void)>;

/// The host's callbacks, as a `TaskRunner`.
pub(crate) struct HostTasks {
    enqueue: unsafe extern "C" fn(HearthTaskFn, u32, u32, *mut c_void, *mut c_void) -> *mut c_void,
    finish: unsafe extern "C" fn(*mut c_void, *mut c_void),
    user_context: *mut c_void,
    workers: u32,
}

// The host promises (HearthWorldDef docs) that its callbacks and context may be used from the
// stepping thread of whichever thread steps the world, and that tasks run on any thread.
unsafe impl Send for HostTasks {}
unsafe impl Sync for HostTasks {}

impl HostTasks {
    /// Checks the def's task fields: `enqueue` and `finish` both set or both NULL. Gives
    /// `None` when the host brings no job system.
    pub(crate) fn from_def(
        enqueue: HearthEnqueueTaskFn,
        finish: HearthFinishTaskFn,
        user_context: *mut c_void,
        workers: u32,
    ) -> Result<Option<HostTasks>, Failure> {
        match (enqueue, finish) {
            (Some(enqueue), Some(finish)) => Ok(Some(HostTasks {
                enqueue,
                finish,
                user_context,
                workers,
            })),
            (None, None) => Ok(None),
            (Some(_), None) => Err(Failure::invalid(
                "enqueue_task is set but finish_task is NULL: set both or neither",
            )),
            (None, Some(_)) => Err(Failure::invalid(
                "finish_task is set but enqueue_task is NULL: set both or neither",
            )),
        }
    }
}

/// What the trampoline needs: the stage's task and the bookkeeping that checks the host.
struct Running<'a> {
    task: &'a Task<'a>,
    count: u32,
    workers: u32,
    /// Items run so far, to check the host covered `0..count` once.
    items: AtomicU64,
    /// A call broke the contract (range or worker index out of bounds).
    misused: AtomicBool,
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

unsafe extern "C" fn trampoline(start: u32, end: u32, worker_index: u32, task_context: *mut c_void) {
    // SAFETY: `task_context` is the `Running` that `run` passed to the enqueue callback and
    // keeps alive until the finish callback has returned.
    let Some(r) = (task_context as *const Running).as_ref() else {
        return;
    };
    if start >= end || end > r.count || worker_index >= r.workers {
        r.misused.store(true, Ordering::Relaxed);
        return;
    }
    r.items.fetch_add((end - start) as u64, Ordering::Relaxed);
    // No panic leaves through the host's frames: it is kept and resumed on the stepping thread.
    if let Err(p) = catch_unwind(AssertUnwindSafe(|| (r.task)(start, end, worker_index))) {
        let mut slot = r.panic.lock().unwrap_or_else(|e| e.into_inner());
        slot.get_or_insert(p);
    }
}

impl TaskRunner for HostTasks {
    fn worker_count(&self) -> u32 {
        self.workers
    }

    fn run(&self, count: u32, min_range: u32, task: &Task) {
        let running = Running {
            task,
            count,
            workers: self.workers,
            items: AtomicU64::new(0),
            misused: AtomicBool::new(false),
            panic: Mutex::new(None),
        };
        let context = &running as *const Running as *mut c_void;
        // SAFETY: host callbacks from the def; `running` outlives the finish call.
        unsafe {
            let user_task = (self.enqueue)(Some(trampoline), count, min_range, context, self.user_context);
            if !user_task.is_null() {
                (self.finish)(user_task, self.user_context);
            }
        }
        if let Some(p) = running.panic.into_inner().unwrap_or_else(|e| e.into_inner()) {
            resume_unwind(p);
        }
        // Reported as HEARTH_ERROR_PANIC by the step (the world is then poisoned: a stage
        // ran partly).
        assert!(
            !running.misused.load(Ordering::Relaxed),
            "the host's job system called a task with a range outside 0..{count} or a worker index \
             not below worker_count {}",
            self.workers
        );
        let items = running.items.load(Ordering::Relaxed);
        assert!(
            items == count as u64,
            "the host's job system ran {items} items of a task of {count}: every item must run exactly once \
             before finish_task returns"
        );
    }
}
