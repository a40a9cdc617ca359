//! Hot paths do not allocate: after warm-up a step makes no heap allocation.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// A host job system that runs each task in ranges of the minimum length on the calling
/// thread, without allocating.
struct InlineHost {
    workers: u32,
}

impl hearth::parallel::TaskRunner for InlineHost {
    fn worker_count(&self) -> u32 {
        self.workers
    }

    fn run(&self, count: u32, min_range: u32, task: &hearth::parallel::Task) {
        let mut start = 0;
        while start < count {
            let end = (start + min_range.max(1)).min(count);
            task(start, end, start / min_range.max(1) % self.workers);
            start = end;
        }
    }
}

fn allocations_per_step(world: &mut hearth::World, warmup: usize, measured: usize) -> usize {
    for _ in 0..warmup {
        world.step(1.0 / 60.0).unwrap();
    }
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..measured {
        world.step(1.0 / 60.0).unwrap();
    }
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

// One test function: the counter is global, so the scenes run one after another.
#[test]
fn steady_steps_do_not_allocate() {
    // Through the C API: hearth_world_step with user callbacks, a spring, joints, a soft
    // body and particles expiring every 15 steps.
    let mut scene = capi_scene::Scene::new();
    for k in 0..240 {
        scene.step(k);
    }
    let (expired, before) = (scene.expired, ALLOCATIONS.load(Ordering::Relaxed));
    for k in 240..480 {
        scene.step(k);
    }
    let allocations = ALLOCATIONS.load(Ordering::Relaxed) - before;
    assert!(
        scene.expired - expired >= 16 * 15,
        "particles expired while measured: {}",
        scene.expired - expired
    );
    assert_eq!(allocations, 0, "C API scene: allocations in 240 steps");

    let mut w = scenes::world(false);
    scenes::pyramid(&mut w, 10);
    assert_eq!(allocations_per_step(&mut w, 120, 120), 0, "pyramid (sleep off)");

    // Every event kind (issue 14): boxes with hit events bouncing on the ground, sensors a
    // kinematic sweeper carries back and forth through them, move events, the step hooks.
    let (mut w, sweeper) = events_scene();
    let mut hooks = KeepAll(0);
    let run = |w: &mut hearth::World, from: usize, to: usize, hooks: &mut KeepAll| -> usize {
        let mut events = 0;
        for k in from..to {
            if k % 120 == 0 {
                let dir = if (k / 120) % 2 == 0 { 4.0 } else { -4.0 };
                w.set_linear_velocity(sweeper, hearth::Vec3::new(dir, 0.0, 0.0))
                    .unwrap();
            }
            w.step_with(1.0 / 60.0, hooks).unwrap();
            let ev = w.events();
            events += ev.sensor_begin.len() + ev.sensor_end.len() + ev.body_moves.len() + ev.contact_hit.len();
        }
        events
    };
    run(&mut w, 0, 960, &mut hooks);
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let events = run(&mut w, 960, 1200, &mut hooks);
    let allocations = ALLOCATIONS.load(Ordering::Relaxed) - before;
    assert!(events > 240 && hooks.0 > 0, "events while measured: {events}");
    assert_eq!(allocations, 0, "every event kind: allocations in 240 steps");

    let mut w = scenes::world(false);
    scenes::spheres_grid(&mut w, 30);
    assert_eq!(allocations_per_step(&mut w, 60, 120), 0, "spheres grid (sleep off)");

    // At every worker count: the world's own parked threads, and a host job system (C
    // callbacks) that runs each task in two ranges. The counter counts every thread.
    for workers in [2, 4] {
        let settings = hearth::WorldSettings {
            enable_sleep: false,
            worker_count: workers,
            ..Default::default()
        };
        let mut w = hearth::World::new(settings).unwrap();
        scenes::pyramid(&mut w, 10);
        assert_eq!(
            allocations_per_step(&mut w, 120, 120),
            0,
            "pyramid at {workers} workers"
        );
        let mut w = hearth::World::new(settings).unwrap();
        scenes::pile(&mut w, 400);
        assert_eq!(allocations_per_step(&mut w, 240, 60), 0, "pile at {workers} workers");
    }
    // A host that runs every task on the calling thread (the solver then runs one task per
    // stage instead of workers meeting at a barrier).
    for workers in [2, 4] {
        let mut w = hearth::World::new(hearth::WorldSettings {
            enable_sleep: false,
            ..Default::default()
        })
        .unwrap();
        w.set_task_runner(Box::new(InlineHost { workers })).unwrap();
        scenes::pyramid(&mut w, 10);
        assert_eq!(
            allocations_per_step(&mut w, 120, 60),
            0,
            "pyramid on an inline host of {workers} workers"
        );
    }
    assert_eq!(
        capi_scene::hosted_pyramid_allocations(),
        0,
        "pyramid on a host job system"
    );

    let mut w = scenes::world(true);
    scenes::tower(&mut w, 10);
    assert_eq!(allocations_per_step(&mut w, 600, 60), 0, "sleeping tower");

    // Falling asleep and waking up: a sleeping island is a list linked through its bodies
    // and the island scratch is reserved while the bodies are awake, so the step where the
    // tower first falls asleep, a wake and the next sleep do not allocate.
    let mut w = scenes::world(true);
    let top = *scenes::tower(&mut w, 10).last().unwrap();
    for _ in 0..10 {
        w.step(1.0 / 60.0).unwrap();
    }
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    let mut naps = 0;
    for _ in 0..2 {
        for _ in 0..600 {
            w.step(1.0 / 60.0).unwrap();
            if !w.is_awake(top).unwrap() {
                break;
            }
        }
        naps += !w.is_awake(top).unwrap() as usize;
        w.set_awake(top, true).unwrap();
    }
    assert_eq!(naps, 2, "the tower falls asleep twice");
    assert_eq!(
        ALLOCATIONS.load(Ordering::Relaxed) - before,
        0,
        "tower falling asleep and waking"
    );

    // Mixed bodies on terrain: several manifolds per pair, reused storage. The balls and
    // capsules get strong angular damping so they stop rolling into new neighbours (a new
    // pair may grow the pair storage, as in any scene).
    for heightfield in [false, true] {
        let mut w = scenes::world(false);
        if heightfield {
            scenes::terrain_heightfield(&mut w, 32, false, 2);
        } else {
            scenes::terrain_mesh(&mut w, 32, false, 2);
        }
        for b in scenes::terrain_drop(&mut w, 64, 4.0, 2) {
            w.set_damping(b, 0.5, 5.0).unwrap();
        }
        let n = allocations_per_step(&mut w, 480, 60);
        assert_eq!(
            n,
            0,
            "bodies on a {} (sleep off)",
            if heightfield { "heightfield" } else { "mesh" }
        );
    }
}

/// A pre-solve callback that keeps everything (and counts its calls).
struct KeepAll(usize);
impl hearth::events::StepCallbacks for KeepAll {
    fn pre_solve(&mut self, _: &hearth::World, _: &hearth::events::PreSolveContact) -> bool {
        self.0 += 1;
        true
    }
}

/// Boxes on a ground plane with hit events, and a kinematic body carrying two sensors.
fn events_scene() -> (hearth::World, hearth::BodyHandle) {
    use hearth::{BodyDef, BodyType, Geometry, Quat, ShapeDef, Transform, Vec3};
    let mut w = scenes::world(false);
    let ground = w.create_body(&BodyDef::default()).unwrap();
    let plane = Geometry::Plane {
        normal: Vec3::Y,
        offset: 0.0,
    };
    w.create_shape(ground, &ShapeDef::default(), &plane).unwrap();
    let cube = |h: f32| Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::splat(h),
    };
    let hits = ShapeDef {
        enable_hit_events: true,
        restitution: 0.5,
        ..Default::default()
    };
    for i in 0..24 {
        let p = Vec3::new((i % 6) as f32 * 1.5 - 4.0, 0.5 + (i / 6) as f32 * 1.2, 0.0);
        let b = w
            .create_body(&BodyDef {
                body_type: BodyType::Dynamic,
                transform: Transform::new(p, Quat::IDENTITY),
                ..Default::default()
            })
            .unwrap();
        w.create_shape(b, &hits, &cube(0.4)).unwrap();
    }
    let sweeper = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            transform: Transform::new(Vec3::new(-8.0, 1.0, 0.0), Quat::IDENTITY),
            ..Default::default()
        })
        .unwrap();
    let sensor = ShapeDef {
        is_sensor: true,
        ..Default::default()
    };
    w.create_shape(sweeper, &sensor, &cube(1.0)).unwrap();
    (w, sweeper)
}

mod capi_scene {
    //! A scene built and stepped through the C API (`hearth_world_step`): user force and
    //! contact callbacks, a built-in spring, a ball-joint chain, a soft ball, and bursts of
    //! particles that keep expiring.
    use hearth::capi::body::*;
    use hearth::capi::callback::*;
    use hearth::capi::error::{HearthResult, HEARTH_OK};
    use hearth::capi::events::*;
    use hearth::capi::generator::*;
    use hearth::capi::joint::*;
    use hearth::capi::particle::*;
    use hearth::capi::shape::*;
    use hearth::capi::soft::*;
    use hearth::capi::types::*;
    use hearth::capi::world::*;

    fn ok(r: HearthResult) {
        assert_eq!(r, HEARTH_OK, "a C API call failed");
    }

    unsafe extern "C" fn enqueue(
        task: hearth::capi::tasks::HearthTaskFn,
        count: u32,
        _min_range: u32,
        task_context: *mut std::ffi::c_void,
        _user: *mut std::ffi::c_void,
    ) -> *mut std::ffi::c_void {
        let task = task.unwrap();
        task(count / 2, count, 1, task_context);
        if count / 2 > 0 {
            task(0, count / 2, 0, task_context);
        }
        std::ptr::null_mut()
    }

    unsafe extern "C" fn finish(_: *mut std::ffi::c_void, _: *mut std::ffi::c_void) {}

    /// Allocations in 120 steps of a 5-layer pyramid of boxes on a plane, after 120 of
    /// warm-up, in a world whose tasks run through a host's enqueue callback.
    pub fn hosted_pyramid_allocations() -> usize {
        unsafe {
            let mut wd = hearth_world_def_default();
            wd.worker_count = 2;
            wd.enable_sleep = 0;
            wd.enqueue_task = Some(enqueue);
            wd.finish_task = Some(finish);
            let mut world = std::ptr::null_mut();
            ok(hearth_world_create(&wd, &mut world));
            let mut ground = HearthBodyId::default();
            ok(hearth_body_create(world, &hearth_body_def_default(), &mut ground));
            let plane = HearthPlane {
                normal: v(0.0, 1.0, 0.0),
                offset: 0.0,
            };
            let mut shape = HearthShapeId::default();
            ok(hearth_shape_create_plane(
                world,
                ground,
                &hearth_shape_def_default(),
                &plane,
                &mut shape,
            ));
            for layer in 0..5 {
                for i in 0..5 - layer {
                    for k in 0..5 - layer {
                        let mut bd = hearth_body_def_default();
                        bd.r#type = HEARTH_BODY_DYNAMIC;
                        let off = layer as f32 * 0.5;
                        bd.transform.position = v(i as f32 + off, 0.5 + layer as f32, k as f32 + off);
                        let mut b = HearthBodyId::default();
                        ok(hearth_body_create(world, &bd, &mut b));
                        let cube = HearthBox {
                            center: v(0.0, 0.0, 0.0),
                            rotation: HearthQuat {
                                x: 0.0,
                                y: 0.0,
                                z: 0.0,
                                w: 1.0,
                            },
                            half_extents: v(0.5, 0.5, 0.5),
                        };
                        ok(hearth_shape_create_box(
                            world,
                            b,
                            &hearth_shape_def_default(),
                            &cube,
                            &mut shape,
                        ));
                    }
                }
            }
            for _ in 0..120 {
                ok(hearth_world_step(world, 1.0 / 60.0));
            }
            let before = super::ALLOCATIONS.load(super::Ordering::Relaxed);
            for _ in 0..120 {
                ok(hearth_world_step(world, 1.0 / 60.0));
            }
            let n = super::ALLOCATIONS.load(super::Ordering::Relaxed) - before;
            hearth_world_destroy(world);
            n
        }
    }

    fn v(x: f32, y: f32, z: f32) -> HearthVec3 {
        HearthVec3 { x, y, z }
    }

    unsafe extern "C" fn keep_pair(
        _: *mut std::ffi::c_void,
        _: *mut HearthWorld,
        _: HearthShapeId,
        _: HearthShapeId,
    ) -> u8 {
        1
    }

    unsafe extern "C" fn keep_contact(
        _: *mut std::ffi::c_void,
        _: *mut HearthWorld,
        c: *const HearthPreSolveContact,
    ) -> u8 {
        ((*c).point_count > 0) as u8
    }

    unsafe extern "C" fn push(_: *mut std::ffi::c_void, world: *mut HearthWorld, ctx: *const HearthGeneratorContext) {
        let c = &*ctx;
        for i in 0..c.body_count {
            ok(hearth_body_apply_force(world, *c.bodies.add(i), v(0.0, 5.0, 1.0)));
        }
    }

    unsafe extern "C" fn hold(
        _: *mut std::ffi::c_void,
        _: *mut HearthWorld,
        ctx: *const HearthGeneratorContext,
        sink: *mut HearthContactSink,
    ) {
        let c = &*ctx;
        for i in 0..c.body_count {
            // A contact holding the body above y = 0.25 (it rests on the ground there).
            let contact = HearthGeneratedContact {
                body_a: *c.bodies.add(i),
                particle_a: Default::default(),
                body_b: Default::default(),
                particle_b: Default::default(),
                point: v(3.0, 0.0, 0.0),
                normal: v(0.0, 1.0, 0.0),
                penetration: 0.0,
                restitution: 0.0,
                friction: 0.5,
            };
            ok(hearth_contact_sink_add(sink, &contact));
        }
    }

    pub struct Scene {
        pub world: *mut HearthWorld,
        burst: HearthBurstDef,
        pub expired: usize,
        pub events: usize,
    }

    impl Scene {
        pub fn new() -> Scene {
            unsafe {
                let mut wd = hearth_world_def_default();
                wd.enable_sleep = 0;
                let mut world = std::ptr::null_mut();
                ok(hearth_world_create(&wd, &mut world));
                let mut sd = hearth_shape_def_default();
                // Every event kind on (issue 14), and both step callbacks set.
                sd.enable_hit_events = 1;
                ok(hearth_world_set_pair_filter_callback(
                    world,
                    Some(keep_pair),
                    std::ptr::null_mut(),
                ));
                ok(hearth_world_set_pre_solve_callback(
                    world,
                    Some(keep_contact),
                    std::ptr::null_mut(),
                ));
                let mut ground = Default::default();
                ok(hearth_body_create(world, &hearth_body_def_default(), &mut ground));
                let mut s = Default::default();
                let plane = HearthPlane {
                    normal: v(0.0, 1.0, 0.0),
                    offset: 0.0,
                };
                ok(hearth_shape_create_plane(world, ground, &sd, &plane, &mut s));
                let dynamic_box = |p: HearthVec3| {
                    let mut bd = hearth_body_def_default();
                    bd.r#type = HEARTH_BODY_DYNAMIC;
                    bd.transform.position = p;
                    let mut b = Default::default();
                    ok(hearth_body_create(world, &bd, &mut b));
                    let shape = HearthBox {
                        center: v(0.0, 0.0, 0.0),
                        rotation: HearthQuat {
                            x: 0.0,
                            y: 0.0,
                            z: 0.0,
                            w: 1.0,
                        },
                        half_extents: v(0.25, 0.25, 0.25),
                    };
                    let mut s = Default::default();
                    ok(hearth_shape_create_box(world, b, &sd, &shape, &mut s));
                    b
                };
                // A chain of three boxes on ball joints from a world anchor: it swings.
                let mut prev = HearthBodyId::default();
                for k in 0..3 {
                    let b = dynamic_box(v(0.6 * (k + 1) as f32, 5.0, 0.0));
                    let mut jd = hearth_ball_joint_def_default();
                    jd.base.body_a = b;
                    jd.base.body_b = prev;
                    jd.base.frame_a.position = v(-0.3, 0.0, 0.0);
                    jd.base.frame_b.position = if k == 0 { v(0.0, 5.0, 0.0) } else { v(0.3, 0.0, 0.0) };
                    let mut j = Default::default();
                    ok(hearth_joint_create_ball(world, &jd, &mut j));
                    prev = b;
                }
                // A box pushed by a user force callback, held by a user contact callback.
                let pushed = dynamic_box(v(3.0, 0.25, 0.0));
                let mut fd = hearth_user_force_generator_def_default();
                fd.callback = Some(push);
                let mut g = Default::default();
                ok(hearth_generator_create_user_force(world, &fd, &mut g));
                ok(hearth_generator_attach_body(world, g, pushed));
                let mut cd = hearth_user_contact_generator_def_default();
                cd.callback = Some(hold);
                ok(hearth_generator_create_user_contact(world, &cd, &mut g));
                ok(hearth_generator_attach_body(world, g, pushed));
                // A box on a built-in spring from a world point.
                let bobbing = dynamic_box(v(-3.0, 2.0, 0.0));
                let mut spd = hearth_spring_generator_def_default();
                spd.other.point = v(-3.0, 4.0, 0.0);
                spd.stiffness = 200.0;
                ok(hearth_generator_create_spring(world, &spd, &mut g));
                ok(hearth_generator_attach_body(world, g, bobbing));
                // A soft ball dropped on the ground.
                let mut soft = hearth_soft_body_def_default();
                soft.transform.position = v(0.0, 1.0, 3.0);
                soft.pressure = 300.0;
                let mut h = Default::default();
                ok(hearth_soft_body_create_icosphere(world, &soft, 0.4, 2, &mut h));
                let mut burst = hearth_burst_def_default();
                burst.position = v(0.0, 0.5, -3.0);
                burst.lifetime_min = 0.1;
                burst.lifetime_max = 0.2;
                Scene {
                    world,
                    burst,
                    expired: 0,
                    events: 0,
                }
            }
        }

        /// One step: every 15th emits a burst of 16 particles living 0.1..0.2 s, so each
        /// burst has expired (and been reported) before the next.
        pub fn step(&mut self, k: usize) {
            unsafe {
                let mut ce = std::mem::zeroed::<HearthContactEvents>();
                ok(hearth_world_get_contact_events(self.world, &mut ce));
                let mut be = std::mem::zeroed::<HearthBodyEvents>();
                ok(hearth_world_get_body_events(self.world, &mut be));
                self.events += ce.begin_count + ce.hit_count + be.move_count;
                if k % 15 == 0 {
                    self.burst.seed = k as u64 + 1;
                    ok(hearth_particle_emit_burst(
                        self.world,
                        &self.burst,
                        std::ptr::null_mut(),
                        0,
                        std::ptr::null_mut(),
                    ));
                }
                ok(hearth_world_step(self.world, 1.0 / 60.0));
                let mut expired = std::ptr::null();
                let mut count = 0;
                ok(hearth_world_get_expired_particles(self.world, &mut expired, &mut count));
                self.expired += count;
            }
        }
    }

    impl Drop for Scene {
        fn drop(&mut self) {
            unsafe { hearth_world_destroy(self.world) };
        }
    }
}
