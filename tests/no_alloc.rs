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
    let mut w = scenes::world(false);
    scenes::pyramid(&mut w, 10);
    assert_eq!(allocations_per_step(&mut w, 120, 120), 0, "pyramid (sleep off)");

    let mut w = scenes::world(false);
    scenes::spheres_grid(&mut w, 30);
    assert_eq!(allocations_per_step(&mut w, 60, 120), 0, "spheres grid (sleep off)");

    let mut w = scenes::world(true);
    scenes::tower(&mut w, 10);
    assert_eq!(allocations_per_step(&mut w, 600, 60), 0, "sleeping tower");

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
