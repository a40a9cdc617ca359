//! Recording exports: record a world into a file or through a host write callback, for the
//! browser viewer (`viewer/`). The format is `docs/recording-format.md`; the core's
//! `record::Recorder` encodes each step into a buffer, and this layer writes the buffer out
//! after the step's core stages, with no borrow of the world held while host code runs.
//!
//! The write callback is called on the thread that called `hearth_world_step` (or a start
//! function) in its own phase of the step: the world is locked, so reads work and every change
//! (including starting or stopping the recording) returns `HEARTH_ERROR_WORLD_LOCKED`.

use std::ffi::CStr;
use std::io::Write;
use std::os::raw::{c_char, c_void};

use super::error::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{HearthWorld, PHASE_IDLE, PHASE_RECORD};
use crate::record::{RecordOptions, Recorder};

/// Receives the next `len` bytes of a recording (`bytes` is valid only during the call).
/// Return 0 when they were written; any other value stops the recording, and the next
/// `hearth_world_step` or `hearth_world_record_stop` reports `HEARTH_ERROR_IO`.
pub type HearthRecordWriteFn =
    Option<unsafe extern "C" fn(user_data: *mut c_void, bytes: *const u8, len: usize) -> i32>;

/// How to record. Get one from `hearth_record_def_default()`, then edit it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthRecordDef {
    /// 1 to record every touching contact manifold each step (points, normal, normal
    /// impulses; about 25 bytes per point), 0 not to (default).
    pub record_contacts: u8,
    /// `hearth_world_record_start_callback` only (NULL for a file): called with the
    /// recording's bytes, in order, once when recording starts and once after every step.
    pub write: HearthRecordWriteFn,
    /// Passed to `write` unchanged. The host owns it; it must stay valid until the recording
    /// stops (or the world is destroyed).
    pub user_data: *mut c_void,
    /// Set by `hearth_record_def_default()`; do not change.
    pub internal_value: u32,
}

enum Sink {
    File {
        file: std::fs::File,
        path: String,
    },
    Callback {
        write: unsafe extern "C" fn(*mut c_void, *const u8, usize) -> i32,
        user_data: *mut c_void,
    },
}

/// A world's running recording (C-layer state, outside the core's `World`).
pub(crate) struct Recording {
    recorder: Recorder,
    sink: Sink,
    /// Why the output failed; reported by the next step or by stop.
    failure: Option<String>,
}

impl Recording {
    fn describe(&self) -> String {
        match &self.sink {
            Sink::File { path, .. } => format!("the recording to '{path}'"),
            Sink::Callback { .. } => "the recording's write callback".to_string(),
        }
    }
}

/// Writes out what the recorder holds. The world is locked in `PHASE_RECORD` while a host
/// callback runs, and the driver holds no reference to the core's `World`.
///
/// # Safety
/// `handle` is a live world and no other reference to its recording is alive.
unsafe fn flush(handle: &HearthWorld) {
    let rec = match &mut *handle.recording.get() {
        Some(r) if r.failure.is_none() => r,
        _ => return,
    };
    let failure = {
        let bytes = rec.recorder.bytes();
        if bytes.is_empty() {
            None
        } else {
            match &mut rec.sink {
                Sink::File { file, path } => file
                    .write_all(bytes)
                    .err()
                    .map(|e| format!("writing the recording to '{path}' failed: {e}")),
                Sink::Callback { write, user_data } => {
                    let (locked, phase) = (handle.locked.get(), handle.phase.get());
                    handle.locked.set(true);
                    handle.phase.set(PHASE_RECORD);
                    let code = write(*user_data, bytes.as_ptr(), bytes.len());
                    handle.phase.set(phase);
                    handle.locked.set(locked);
                    (code != 0).then(|| format!("the recording's write callback returned {code}"))
                }
            }
        }
    };
    rec.recorder.clear();
    if let Some(f) = failure {
        rec.failure = Some(format!(
            "{f}; the recording stopped (what was written before replays up to its last whole step)"
        ));
    }
}

/// Called by `hearth_world_step` before stepping: a recording whose output failed is ended
/// here and the failure returned, so the step changes nothing and says why.
///
/// # Safety
/// `handle` is a live, unlocked world.
pub(crate) unsafe fn take_failure(handle: &HearthWorld) -> Result<(), Failure> {
    let slot = &mut *handle.recording.get();
    if let Some(msg) = slot.as_ref().and_then(|r| r.failure.clone()) {
        *slot = None;
        return Err(Failure::new(HEARTH_ERROR_IO, msg));
    }
    Ok(())
}

/// Called by `hearth_world_step` after the core's stages: records the step and writes it out.
///
/// # Safety
/// `world` is a live world, locked by the running step; no reference to its core is alive.
pub(crate) unsafe fn after_step(world: *mut HearthWorld, dt: f32, step_seconds: f32) {
    let handle = &*world;
    match &mut *handle.recording.get() {
        Some(r) if r.failure.is_none() && dt > 0.0 => {
            r.recorder.record_step(&*handle.world.get(), dt, step_seconds);
        }
        _ => return,
    }
    flush(handle);
}

/// The default recording settings: no contacts, no callback.
#[no_mangle]
pub extern "C" fn hearth_record_def_default() -> HearthRecordDef {
    HearthRecordDef {
        record_contacts: 0,
        write: None,
        user_data: std::ptr::null_mut(),
        internal_value: DEF_COOKIE,
    }
}

/// The world, checked to be idle.
unsafe fn idle_world<'a>(world: *mut HearthWorld) -> Result<&'a HearthWorld, Failure> {
    let handle = world.as_ref().ok_or_else(|| Failure::null("world"))?;
    if handle.locked.get() {
        return Err(Failure::new(
            HEARTH_ERROR_WORLD_LOCKED,
            "the world is locked: it is stepping (called from a callback)",
        ));
    }
    Ok(handle)
}

/// Refuses a second recording (checked after the arguments, which are reported first).
unsafe fn not_recording(handle: &HearthWorld) -> Result<(), Failure> {
    if let Some(r) = &*handle.recording.get() {
        return Err(Failure::invalid(format!(
            "the world is already recording ({}); call hearth_world_record_stop first",
            r.describe()
        )));
    }
    Ok(())
}

/// Starts a recording; the first bytes (header, every body, frame 0) are written at once.
unsafe fn start(handle: &HearthWorld, options: RecordOptions, sink: Sink) -> Result<(), Failure> {
    let recorder = Recorder::new(&*handle.world.get(), options);
    *handle.recording.get() = Some(Recording {
        recorder,
        sink,
        failure: None,
    });
    flush(handle);
    let slot = &mut *handle.recording.get();
    if let Some(msg) = slot.as_ref().and_then(|r| r.failure.clone()) {
        *slot = None;
        return Err(Failure::new(HEARTH_ERROR_IO, msg));
    }
    Ok(())
}

fn options(def: &HearthRecordDef) -> Result<RecordOptions, Failure> {
    validate::cookie(def.internal_value, "hearth_record_def")?;
    Ok(RecordOptions {
        contacts: validate::flag(def.record_contacts, "def.record_contacts")?,
    })
}

/// Starts recording `world` into the file at `path` (UTF-8; created, or truncated if it
/// exists). The header, every body with its shapes and the current state are written at once;
/// then every `hearth_world_step` appends the step (open the file with `viewer/index.html`).
/// The recording ends with `hearth_world_record_stop` or `hearth_world_destroy`. A write that
/// fails later stops the recording; the next step (which then does not run) or stop returns
/// `HEARTH_ERROR_IO` with the system's message.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, path or def NULL),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_record_def_default()`, a flag not
/// 0/1, `def.write` not NULL, path empty or not UTF-8, the world already recording),
/// `HEARTH_ERROR_IO` (the file cannot be created or written; the message names the path),
/// `HEARTH_ERROR_WORLD_LOCKED` (called from a callback).
///
/// # Safety
/// `world` must be NULL or a live world; `path` NULL or a NUL-terminated string; `def` NULL
/// or a `HearthRecordDef`.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_record_start_file(
    world: *mut HearthWorld,
    path: *const c_char,
    def: *const HearthRecordDef,
) -> HearthResult {
    guard(|| {
        let handle = idle_world(world)?;
        if path.is_null() {
            return Err(Failure::null("path"));
        }
        let def = validate::input(def, "def")?;
        let options = options(def)?;
        if def.write.is_some() {
            return Err(Failure::invalid(
                "def.write must be NULL for a file recording (use hearth_world_record_start_callback)",
            ));
        }
        let path = CStr::from_ptr(path)
            .to_str()
            .map_err(|_| Failure::invalid("path must be UTF-8"))?;
        if path.is_empty() {
            return Err(Failure::invalid("path must not be empty"));
        }
        not_recording(handle)?;
        let file = std::fs::File::create(path).map_err(|e| {
            Failure::new(
                HEARTH_ERROR_IO,
                format!("cannot create the recording file '{path}': {e}"),
            )
        })?;
        start(
            handle,
            options,
            Sink::File {
                file,
                path: path.to_string(),
            },
        )
    })
}

/// Starts recording `world` through the host's `def->write` callback (for hosts with their own
/// file systems or streams). `write` is called at once with the header, every body and the
/// current state, then after every `hearth_world_step` with that step, on the stepping
/// thread; the world is locked during the call (reads work, changes return
/// `HEARTH_ERROR_WORLD_LOCKED`). A non-zero return stops the recording; the start (if it was
/// the first call), the next step (which then does not run) or the stop returns
/// `HEARTH_ERROR_IO`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, def or `def.write` NULL),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from `hearth_record_def_default()`, a flag not
/// 0/1, the world already recording; the arguments are checked first), `HEARTH_ERROR_IO`
/// (the first write failed),
/// `HEARTH_ERROR_WORLD_LOCKED` (called from a callback).
///
/// # Safety
/// `world` must be NULL or a live world; `def` NULL or a `HearthRecordDef` whose `write` and
/// `user_data` stay valid until the recording stops.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_record_start_callback(
    world: *mut HearthWorld,
    def: *const HearthRecordDef,
) -> HearthResult {
    guard(|| {
        let handle = idle_world(world)?;
        let def = validate::input(def, "def")?;
        let options = options(def)?;
        let write = def.write.ok_or_else(|| Failure::null("def.write"))?;
        not_recording(handle)?;
        start(
            handle,
            options,
            Sink::Callback {
                write,
                user_data: def.user_data,
            },
        )
    })
}

/// Stops the world's recording and closes its file (the callback is not called again). Every
/// step recorded so far is in the output.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (the world is not
/// recording), `HEARTH_ERROR_IO` (a write had failed since the last step: the recording is
/// stopped all the same and the message says what failed), `HEARTH_ERROR_WORLD_LOCKED`
/// (called from a callback).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_record_stop(world: *mut HearthWorld) -> HearthResult {
    guard(|| {
        let handle = world.as_ref().ok_or_else(|| Failure::null("world"))?;
        if handle.locked.get() {
            return Err(Failure::new(
                HEARTH_ERROR_WORLD_LOCKED,
                "the world is locked: it is stepping (called from a callback)",
            ));
        }
        let rec = (*handle.recording.get())
            .take()
            .ok_or_else(|| Failure::invalid("the world is not recording"))?;
        debug_assert_eq!(handle.phase.get(), PHASE_IDLE);
        if let Some(msg) = rec.failure {
            return Err(Failure::new(HEARTH_ERROR_IO, msg));
        }
        if let Sink::File { file, path } = rec.sink {
            file.sync_all()
                .map_err(|e| Failure::new(HEARTH_ERROR_IO, format!("closing the recording '{path}' failed: {e}")))?;
        }
        Ok(())
    })
}
