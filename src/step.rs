//! The step, stage by stage. Read this file top to bottom to follow a frame.

use crate::collision::aabb::Aabb;
use crate::collision::broad_phase::{aabb_touches_plane, world_plane};
use crate::collision::filter::should_collide;
use crate::dynamics::body::NONE;
use crate::world::{World, AABB_MARGIN};
use std::sync::atomic::{AtomicU32, Ordering};

/// Extra distance (m) within which contact points are kept before touching.
pub const SPECULATIVE_DISTANCE: f32 = 0.02;

impl World {
    /// Advances the world by `dt` seconds: 0 does nothing, otherwise `dt` must lie within
    /// [`MIN_TIME_STEP`](crate::error::MIN_TIME_STEP) to
    /// [`MAX_TIME_STEP`](crate::error::MAX_TIME_STEP) (1 ms to 0.1 s; README "Supported
    /// ranges").
    ///
    /// The stages run in three calls, `begin_step`, `collide_step` and `finish_step`. A
    /// driver that runs host callbacks (the C layer, `capi/world.rs`) calls them itself and
    /// runs external force generators after `begin_step` and external contact generators
    /// after `collide_step`, with no borrow of the world alive while host code runs.
    pub fn step(&mut self, dt: f32) -> crate::error::Result<()> {
        if self.begin_step(dt)? {
            self.collide_step(dt);
            self.finish_step(dt);
        }
        Ok(())
    }

    /// Validates `dt` and runs stages 1–2. Returns false when there is nothing to do
    /// (`dt == 0`); the other stages must then not run.
    pub fn begin_step(&mut self, dt: f32) -> crate::error::Result<bool> {
        crate::error::check_time_step("dt", dt)?;
        if dt == 0.0 {
            return Ok(false);
        }
        self.counters = Default::default();
        self.begin_events();
        // 1. Start of frame: derived data is refreshed while the solver's body arrays are
        //    built (in `solve`).
        // 2. Forces: built-in force generators add to the accumulators of bodies and
        //    particles, on top of forces the host applied since the last step
        //    (generators/forces.rs). External (host) force generators run after this.
        self.apply_force_generators(dt);
        //    A body resting on particles gets its gravity in the particle stage (7).
        self.defer_coupled_gravity();
        //    So does a body resting on soft bodies, in the soft-body stage (7c).
        self.defer_soft_gravity();
        Ok(true)
    }

    /// Stages 3–5: broad phase, narrow phase, built-in contact generators.
    pub fn collide_step(&mut self, dt: f32) {
        // 3. Broad phase: new pairs from proxies whose fat boxes moved.
        self.find_pairs();
        //    (A host's pair filter runs here: `events.rs`, `World::step_with`.)
        self.collide_pairs(dt);
    }

    /// The rest of stage 3 after `find_pairs` (contacts for the kept candidates), stage 4 and
    /// the built-in contact generators.
    pub fn collide_pairs(&mut self, dt: f32) {
        self.create_pairs();
        // 4. Narrow phase: manifolds for every awake contact; wake sleepers that are touched;
        //    contact and sensor begin and end events (events.rs).
        self.collide(dt);
        // 5. Contact generators: rods and cables between bodies write generated contacts
        //    (generators/links.rs). External (host) contact generators run after this.
        self.generate_link_contacts(dt);
    }

    /// Stages 6–9: rigid solve, particles, bounds, sleep.
    pub fn finish_step(&mut self, dt: f32) {
        // 6. Integration and contact resolution, sub-stepped (solver.rs).
        crate::dynamics::solver::solve(self, dt);
        self.generated_contacts.clear();
        //    Hit events: contacts that approached fast and were pushed (events.rs).
        self.hit_events_after_solve();
        // 7. Particles: integration, contacts with shapes (two-way with dynamic bodies),
        //    rods and cables, sleep, lifetimes (particles/solver.rs).
        self.step_particles(dt);
        // 7c. Soft bodies: XPBD sub-steps, pressure, contacts with shapes (two-way with
        //     dynamic bodies), pins (soft/solver.rs).
        self.step_soft_bodies(dt);
        // 8. Bounds and sleep timers, body by body in parallel (`finish_bodies`): the speed
        //    limit (it holds at the end of every step: restitution and the coupled particle
        //    and soft-body stages change velocities after the sub-steps' caps), tight boxes,
        //    the motion average. Then on this thread the refit of moved proxies, sweeping
        //    them along the coming motion.
        let ready = self.finish_bodies(dt);
        self.cap_particle_speeds();
        self.refit_proxies(dt);
        // 9. Sleep.
        crate::dynamics::island::sleep_islands(self, ready);
        self.counters.awake_bodies = self.awake_bodies.len();
        self.counters.contacts = self.contacts.len();
        // 10. Events: body moves, ends of contacts destroyed since the last step.
        self.finish_events();
    }

    /// Stage 3: lists the candidate pairs of proxies whose fat boxes moved (no contacts yet;
    /// `collide_pairs` makes them, after a pair filter may have dropped some). The moved
    /// proxies are queried in parallel in fixed chunks, each into its own list, and the
    /// lists joined in chunk order: the candidates of one pass, in its order.
    pub fn find_pairs(&mut self) {
        let World {
            broad,
            shapes,
            bodies,
            counters,
            joints,
            tasks,
            ..
        } = self;
        broad.candidates.clear();
        counters.proxies_moved = broad.move_buffer.len();
        let chunks = broad.move_buffer.len().div_ceil(PAIR_CHUNK);
        if broad.chunk_candidates.len() < chunks {
            broad.chunk_candidates.resize_with(chunks, Vec::new);
        }
        let tested = std::sync::atomic::AtomicUsize::new(0);
        {
            let (tree, moved, planes) = (&broad.tree, &broad.move_buffer[..], &broad.planes[..]);
            let lists = crate::parallel::Disjoint::new(&mut broad.chunk_candidates[..chunks]);
            let (shapes, bodies, joints) = (&*shapes, &*bodies, &*joints);
            crate::parallel::run(&**tasks, chunks as u32, 1, &|start, end, _| {
                let mut count = 0;
                for chunk in start as usize..end as usize {
                    // SAFETY: each chunk is one task's.
                    let out = unsafe { lists.at(chunk) };
                    out.clear();
                    let span = chunk * PAIR_CHUNK..((chunk + 1) * PAIR_CHUNK).min(moved.len());
                    for &s in &moved[span] {
                        count += proxy_pairs(s, tree, planes, shapes, bodies, joints, out);
                    }
                }
                tested.fetch_add(count, Ordering::Relaxed);
            });
        }
        counters.pairs_tested += tested.into_inner();
        for list in &broad.chunk_candidates[..chunks] {
            broad.candidates.extend_from_slice(list);
        }
        for &s in &broad.move_buffer {
            shapes.at_mut(s).in_move_buffer = false;
        }
        broad.move_buffer.clear();
    }

    /// Contacts for the candidate pairs a pair filter kept.
    fn create_pairs(&mut self) {
        let mut candidates = std::mem::take(&mut self.broad.candidates);
        for &(a, b) in &candidates {
            if b != NONE {
                self.create_contact(a, b);
            }
        }
        candidates.clear();
        self.broad.candidates = candidates;
    }

    fn collide(&mut self, dt: f32) {
        // Every awake contact is updated in parallel: a task writes only to its own contacts
        // and to their result slots. What changes the world's lists (destroyed contacts,
        // woken sleepers) is merged after, on this thread, in the serial order.
        //    Beside it, in the same run, the broad-phase tree is rebuilt above the proxies
        //    the last step enlarged in place (`refit_proxies`): the top of the new hierarchy
        //    is split here, and each subtree below it is a job of the run, worth `JOB_ITEMS`
        //    items and run by whichever range holds its first item. The tree is not used
        //    again until the next step's pair search, and the rebuild's result does not
        //    depend on when or where its jobs run.
        let n = self.awake_contacts.len();
        let slop = self.settings.linear_slop;
        self.narrow_results.clear();
        self.narrow_results.resize(n, 0);
        // One job for the whole rebuild when the contacts beside it keep the other workers
        // busy at least as long; otherwise the top is split here into jobs of `JOB_UNITS`.
        let workers = self.tasks.worker_count() as usize;
        let jobs = self.broad.tree.begin_rebuild_enlarged(|units| {
            let levels = (usize::BITS - units.leading_zeros()) as usize;
            if workers <= 1 || n * CONTACT_PER_UNIT_LEVEL >= (workers - 1) * units * levels {
                usize::MAX
            } else {
                crate::collision::dynamic_tree::JOB_UNITS
            }
        });
        {
            let World {
                contacts,
                shapes,
                bodies,
                geometry,
                awake_contacts,
                narrow_results,
                tasks,
                broad,
                ..
            } = self;
            let rebuild = broad.tree.rebuild_jobs();
            let rebuild_items = jobs * JOB_ITEMS;
            let (contacts, results) = (contacts.disjoint(), crate::parallel::Disjoint::new(narrow_results));
            let awake_contacts = &*awake_contacts;
            let (shapes, bodies, geometry) = (&*shapes, &*bodies, &*geometry);
            let count = (rebuild_items + n) as u32;
            crate::parallel::run(&**tasks, count, NARROW_MIN_RANGE, &|start, end, _| {
                let (start, end) = (start as usize, end as usize);
                for k in start.div_ceil(JOB_ITEMS)..end.min(rebuild_items).div_ceil(JOB_ITEMS) {
                    // SAFETY: job `k`'s first item, `k * JOB_ITEMS`, is in exactly one range.
                    unsafe { rebuild.run(k) };
                }
                let (start, end) = (
                    start.max(rebuild_items) - rebuild_items,
                    end.max(rebuild_items) - rebuild_items,
                );
                for (k, &ci) in awake_contacts[start..end].iter().enumerate() {
                    // SAFETY: `awake_contacts` lists each contact once and `start + k` is this
                    // task's own index.
                    let (c, r) = unsafe { (contacts.at_mut(ci), results.at(start + k)) };
                    *r = update_contact(c, shapes, bodies, geometry, dt, slop);
                }
            });
        }
        self.broad.tree.end_rebuild();
        self.scratch_wake.clear();
        let mut touching = 0;
        let mut i = n;
        while i > 0 {
            i -= 1;
            // Destroying swaps the last awake contact into place `i`, which was already
            // merged, so `awake_contacts[j]` for `j <= i` is still the contact updated at `j`.
            let (ci, r) = (self.awake_contacts[i], self.narrow_results[i]);
            if r & DESTROY != 0 {
                self.destroy_contact(ci);
                continue;
            }
            touching += (r & TOUCHING != 0) as usize;
            if r & (EVENTS | WAKE_A | WAKE_B) == 0 {
                // Nothing to merge: the contact itself is not read again (at 10,000 contacts
                // this loop would otherwise cost a cache miss each on the stepping thread).
                continue;
            }
            let c = self.contacts.at(ci);
            if c.event_flags != 0 {
                let (sa, sb) = (self.shapes.at(c.shape_a), self.shapes.at(c.shape_b));
                let (ba, bb) = (self.bodies.at(c.body_a), self.bodies.at(c.body_b));
                let (motion, spin) = (contact_motion(sa, ba, sb, bb), ba.w.length() + bb.w.length());
                self.contact_events_after_update(ci, motion, spin);
            }
            let c = self.contacts.at(ci);
            if r & WAKE_A != 0 {
                self.scratch_wake.push(c.body_a);
            } else if r & WAKE_B != 0 {
                self.scratch_wake.push(c.body_b);
            }
        }
        let mut wake = std::mem::take(&mut self.scratch_wake);
        for &b in &wake {
            self.wake_body(b);
        }
        self.counters.touching_contacts = touching;
        wake.clear();
        self.scratch_wake = wake;
    }

    /// Caps the speed of every particle at `max_linear_speed` (bodies: `finish_bodies`).
    fn cap_particle_speeds(&mut self) {
        let max = self.settings.max_linear_speed;
        for v in &mut self.particles.vel {
            *v = crate::world::cap_speed(*v, max);
        }
    }

    /// Each awake body once, in parallel (a task writes only its own bodies, their shapes
    /// and their marks): caps a dynamic body's speed, computes its shapes' tight boxes,
    /// marks it in `body_marks` when a shape's swept box left its fat box (`REFIT`) or its
    /// move should be reported (`MOVED`), and updates its motion average and sleep timer
    /// (`island::update_motion`). Returns whether some body has been still for
    /// `time_to_sleep`. The longest timer is a maximum, so the answer does not depend on how
    /// the bodies were split.
    fn finish_bodies(&mut self, dt: f32) -> bool {
        let max = self.settings.max_linear_speed;
        let rule = crate::dynamics::island::MotionRule::new(&self.settings, dt);
        let slots = self.bodies.slot_count();
        if self.body_marks.len() < slots {
            self.body_marks.resize(slots, 0);
        }
        let longest = AtomicU32::new(0);
        let World {
            awake_bodies,
            bodies,
            shapes,
            geometry,
            tasks,
            body_marks,
            ..
        } = self;
        let geometry = &*geometry;
        let (bodies, shapes, marks) = (
            bodies.disjoint(),
            shapes.disjoint(),
            crate::parallel::Disjoint::new(&mut body_marks[..]),
        );
        let awake_bodies = &*awake_bodies;
        crate::parallel::run(
            &**tasks,
            awake_bodies.len() as u32,
            BOUNDS_MIN_RANGE,
            &|start, end, _| {
                let mut still = 0.0f32;
                for &bi in &awake_bodies[start as usize..end as usize] {
                    // SAFETY: each awake body is listed once, and a shape belongs to one body.
                    let body = unsafe { bodies.at_mut(bi) };
                    if body.is_dynamic() {
                        body.v = crate::world::cap_speed(body.v, max);
                    }
                    let d = body.v * dt;
                    let mut mark = 0;
                    for link in &body.shapes {
                        // SAFETY: as above.
                        let shape = unsafe { shapes.at_mut(link.index) };
                        if shape.proxy != NONE {
                            shape.aabb = shape.geometry.aabb(geometry, &body.xf);
                            if !shape.fat_aabb.contains(&shape.aabb.swept(d)) {
                                mark |= REFIT;
                            }
                        }
                    }
                    if body.enable_move_events && !body.is_static() && body.xf != body.reported_xf {
                        mark |= MOVED;
                    }
                    still = still.max(rule.update(body));
                    // SAFETY: the body's own mark.
                    unsafe { *marks.at(bi as usize) = mark };
                }
                // Sleep timers are never negative, so their bits order as the numbers do.
                longest.fetch_max(still.to_bits(), Ordering::Relaxed);
            },
        );
        f32::from_bits(longest.into_inner()) >= self.settings.time_to_sleep
    }

    /// On the stepping thread, in awake order, the refit of every proxy whose swept box left
    /// its fat box (the bodies `finish_bodies` marked): the same fat box `refresh_proxy`
    /// computes, but enlarged in place in the tree (rebuilt beside the next narrow phase)
    /// instead of reinserted. `refresh_proxy` (teleports, wakes, type changes) still
    /// reinserts: a proxy moved far would otherwise stretch its old ancestors' boxes across
    /// the level until the next step.
    fn refit_proxies(&mut self, dt: f32) {
        for k in 0..self.awake_bodies.len() {
            let bi = self.awake_bodies[k];
            if self.body_marks[bi as usize] & REFIT == 0 {
                continue;
            }
            let body = self.bodies.at(bi);
            let d = body.v * dt;
            for j in 0..body.shapes.len() {
                let s = self.bodies.at(bi).shapes[j].index;
                let shape = self.shapes.at(s);
                if shape.proxy == NONE {
                    continue;
                }
                let bb = shape.aabb.swept(d);
                if !shape.fat_aabb.contains(&bb) {
                    // Sweep one more step of motion ahead, so a fast body refits every other
                    // step (as `refresh_proxy`).
                    let fat = bb.swept(d).expanded(AABB_MARGIN);
                    let proxy = shape.proxy;
                    self.shapes.at_mut(s).fat_aabb = fat;
                    // In place: the tree above it is rebuilt beside the next narrow phase
                    // (`collide`).
                    self.broad.tree.enlarge_proxy(proxy, fat);
                    self.push_moved(s);
                }
            }
        }
    }
}

/// `World::body_marks`: a shape of the body left its fat box; the body's move is to be
/// reported; the body woke after `finish_bodies` (its move is checked in full).
pub(crate) const REFIT: u8 = 1;
pub(crate) const MOVED: u8 = 2;
pub(crate) const WOKEN: u8 = 4;

/// Moved proxies per pair-finding chunk: a fixed number, so the candidates do not depend on
/// the workers.
const PAIR_CHUNK: usize = 64;

/// The candidate pairs of moved shape `s`: the tree's proxies its fat box overlaps and the
/// planes it touches, pushed to `out`. Returns the number of tree proxies tested.
fn proxy_pairs(
    s: u32,
    tree: &crate::collision::dynamic_tree::DynamicTree,
    planes: &[u32],
    shapes: &crate::pool::Pool<crate::collision::shape::Shape>,
    bodies: &crate::pool::Pool<crate::dynamics::body::Body>,
    joints: &crate::dynamics::joints::Joints,
    out: &mut Vec<(u32, u32)>,
) -> usize {
    let shape = shapes.at(s);
    let body = bodies.at(shape.body);
    let fat = shape.fat_aabb;
    let mut tested = 0;
    let first = out.len();
    tree.query(&fat, |_, t| {
        tested += 1;
        if t == s {
            return true;
        }
        let other = shapes.at(t);
        if other.body == shape.body || (other.in_move_buffer && t < s) {
            return true;
        }
        let other_body = bodies.at(other.body);
        // A sensor sees bodies of every type (not two static ones); two sensors never pair
        // (events.rs).
        let bodies_pair = match (shape.def.is_sensor, other.def.is_sensor) {
            (false, false) => body.is_dynamic() || other_body.is_dynamic(),
            (true, true) => false,
            _ => !body.is_static() || !other_body.is_static(),
        };
        if bodies_pair
            // Joints with collide_connected off (issue 5) filter their body pair.
            && joints.should_collide(shape.body, other.body)
            && should_collide(&shape.def.filter, &other.def.filter)
        {
            out.push((s, t));
        }
        true
    });
    // In shape order, not the tree's: the contacts are made in this order, so the results
    // do not depend on the tree's shape (the in-place enlargement and its rebuilds, a
    // broad-phase rebuild the host asks for).
    out[first..].sort_unstable_by_key(|&(_, t)| t);
    // Planes (static, outside the tree, never sensors) pair with dynamic bodies' shapes and
    // with kinematic bodies' sensors: a sensor sees bodies of every type, as in the tree query
    // above (a kinematic sensor used to miss every plane).
    let kinematic_sensor = shape.def.is_sensor && !body.is_dynamic() && !body.is_static();
    if body.is_dynamic() || kinematic_sensor {
        for &p in planes {
            let plane = shapes.at(p);
            let (n, d) = world_plane(&plane.geometry, &bodies.at(plane.body).xf);
            if aabb_touches_plane(&fat, n, d)
                && joints.should_collide(shape.body, plane.body)
                && should_collide(&shape.def.filter, &plane.def.filter)
            {
                out.push((s, p));
            }
        }
    }
    tested
}

/// Awake bodies per bounds task, at least.
const BOUNDS_MIN_RANGE: u32 = 64;

/// Contacts per narrow-phase task, at least.
const NARROW_MIN_RANGE: u32 = 16;
/// Items of the narrow-phase run that one job of the tree rebuild counts for (a job of up to
/// 256 units costs about as much as 50 to 100 contact updates), so that the pool's ranges
/// spread the jobs over the workers.
const JOB_ITEMS: usize = 32;
/// About how many times the work of sorting one unit into a bin at one level of the tree
/// rebuild a contact update costs (box contacts of the pile: about 700 against 200
/// instructions).
const CONTACT_PER_UNIT_LEVEL: usize = 4;
/// Narrow-phase results: the pair's fat boxes parted, it touches, the sleeper to wake, it
/// has events to report.
const DESTROY: u8 = 1;
const TOUCHING: u8 = 2;
const WAKE_A: u8 = 4;
const WAKE_B: u8 = 8;
const EVENTS: u8 = 16;

/// Updates one awake contact's manifold; returns its `DESTROY`, `TOUCHING`, `WAKE_*` and
/// `EVENTS` bits.
fn update_contact(
    c: &mut crate::collision::contact::Contact,
    shapes: &crate::pool::Pool<crate::collision::shape::Shape>,
    bodies: &crate::pool::Pool<crate::dynamics::body::Body>,
    geometry: &crate::collision::geometry_store::GeometryStore,
    dt: f32,
    slop: f32,
) -> u8 {
    c.disabled = false;
    let (sa, sb) = (shapes.at(c.shape_a), shapes.at(c.shape_b));
    let (ba, bb) = (bodies.at(c.body_a), bodies.at(c.body_b));
    if !fat_overlap(
        &sa.fat_aabb,
        sa.proxy,
        &sb.fat_aabb,
        sb.proxy,
        &sb.geometry,
        &bb.xf,
        &sa.geometry,
        &ba.xf,
    ) {
        return DESTROY;
    }
    let motion = contact_motion(sa, ba, sb, bb);
    // A sensor measures overlap only: no speculative points.
    let speculative = if c.event_flags & crate::events::SENSOR != 0 {
        0.0
    } else {
        SPECULATIVE_DISTANCE + motion * dt
    };
    if apart(sa, &ba.xf, sb, &bb.xf, speculative) {
        // Tight boxes further apart than the speculative distance: no points, and the
        // narrow phase is skipped.
        c.clear();
    } else {
        c.update(geometry, sa, &ba.xf, sb, &bb.xf, speculative);
    }
    let events = if c.event_flags != 0 && crate::events::events_pending(c, slop) {
        EVENTS
    } else {
        0
    };
    if c.event_flags & crate::events::SENSOR != 0 {
        // A sensor never touches for the solver and wakes nothing; its overlap is read from
        // the points in the merge (`contact_events_after_update`).
        return events;
    }
    let mut r = events | if c.touching { TOUCHING } else { 0 };
    if c.touching && (!ba.awake || !bb.awake) {
        let (sleeper, bit) = if ba.awake { (bb, WAKE_B) } else { (ba, WAKE_A) };
        if !sleeper.is_static() {
            r |= bit;
        }
    }
    r
}

/// Relative speed bound of two shapes' surfaces: their bodies' relative linear speed plus
/// each one's spin times its shape's extent.
fn contact_motion(
    sa: &crate::collision::shape::Shape,
    ba: &crate::dynamics::body::Body,
    sb: &crate::collision::shape::Shape,
    bb: &crate::dynamics::body::Body,
) -> f32 {
    (bb.v - ba.v).length() + ba.w.length() * sa.extent + bb.w.length() * sb.extent
}

/// Are two shapes' tight bounds further apart than `margin` (so no contact point can exist)?
fn apart(
    a: &crate::collision::shape::Shape,
    xf_a: &crate::math::Transform,
    b: &crate::collision::shape::Shape,
    xf_b: &crate::math::Transform,
    margin: f32,
) -> bool {
    match (a.proxy == NONE, b.proxy == NONE) {
        (false, false) => {
            let (ba, bb) = (a.aabb, b.aabb);
            let gap = (ba.min - bb.max).max(bb.min - ba.max);
            gap.max_element() > margin
        }
        (true, false) => {
            let (n, d) = world_plane(&a.geometry, xf_a);
            let bb = b.aabb;
            n.dot(bb.center()) - n.abs().dot(bb.extents()) > d + margin
        }
        (false, true) => {
            let (n, d) = world_plane(&b.geometry, xf_b);
            let ba = a.aabb;
            n.dot(ba.center()) - n.abs().dot(ba.extents()) > d + margin
        }
        (true, true) => true,
    }
}

/// Do two shapes' fat boxes still overlap (a plane counts as a half-space)?
#[allow(clippy::too_many_arguments)]
fn fat_overlap(
    a: &Aabb,
    proxy_a: u32,
    b: &Aabb,
    proxy_b: u32,
    geom_b: &crate::collision::shape::Geometry,
    xf_b: &crate::math::Transform,
    geom_a: &crate::collision::shape::Geometry,
    xf_a: &crate::math::Transform,
) -> bool {
    if proxy_b == NONE {
        let (n, d) = world_plane(geom_b, xf_b);
        return aabb_touches_plane(a, n, d);
    }
    if proxy_a == NONE {
        let (n, d) = world_plane(geom_a, xf_a);
        return aabb_touches_plane(b, n, d);
    }
    a.overlaps(b)
}
