//! What a step tells the host: contact begin, end and hit events, sensor begin and end
//! events, body move events; and the two hooks a host may put into the step, the pair
//! filter (new broad-phase pairs) and the pre-solve callback (touching contacts, each step).
//!
//! Events are written during the step into arrays the world owns (`Events`), cleared at the
//! start of the next step and kept warm, so a step allocates nothing once they have grown.
//! Every kind is enabled per shape (`ShapeDef::enable_contact_events`, `enable_hit_events`,
//! `enable_sensor_events`) or per body (`BodyDef::enable_move_events`); a world that enables
//! none does one flag test per awake contact and per awake body.
//!
//! * **Contact begin** when a contact's manifold first has a point at most `linear_slop`
//!   apart (the shapes touch), **end** when it has no point left (the shapes are more than
//!   the speculative distance apart), when their bounds part, or when either shape or body is
//!   destroyed. The hysteresis keeps a resting or sliding contact from flickering. Both
//!   shapes must enable contact events.
//! * **Hit**: in a step where the solver pushed a contact with an approach speed above
//!   `WorldSettings::hit_event_threshold`: the point and normal (from A to B) of the fastest
//!   approaching point and its speed at impact (the relative normal speed at the start of the
//!   step, carried over the remaining gap by the bodies' gravity: exact for a free fall).
//!   Either shape may enable hit events.
//! * **Sensor begin/end**: a sensor shape and a non-sensor shape start or stop overlapping
//!   (exact shapes, not bounds), or either is destroyed. Both must enable sensor events.
//!   Sensors see shapes on bodies of every type (not two static ones). A sleeping body does
//!   not move, so overlaps with it are kept while it sleeps (no end event because it fell
//!   asleep) and its contacts with a sleeping or static sensor are not re-tested until it
//!   wakes; a sensor never wakes a body.
//! * **Body move**: every body with move events that moved in the step (its transform
//!   changed since it was last reported) and every such body that fell asleep in the step
//!   (`fell_asleep`), in the order of the awake list, then of falling asleep.
//!
//! End events caused by destroying a shape or body between steps are reported with the next
//! step's events (their ids are then no longer live).

use crate::collision::narrow_phase::{Manifold, MAX_MANIFOLD_POINTS};
use crate::dynamics::body::{BodyHandle, ShapeHandle};
use crate::math::{Transform, Vec3};
use crate::world::World;

/// Contact flag: the pair reports begin and end events.
pub(crate) const CONTACT_EVENTS: u8 = 1;
/// Contact flag: the pair reports hit events.
pub(crate) const HIT_EVENTS: u8 = 2;
/// Contact flag: one shape is a sensor (the pair never reaches the solver).
pub(crate) const SENSOR: u8 = 4;
/// Contact flag: the sensor pair reports begin and end events.
pub(crate) const SENSOR_EVENTS: u8 = 8;

/// Two shapes (and their bodies) that started or stopped touching.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ContactEvent {
    pub shape_a: ShapeHandle,
    pub shape_b: ShapeHandle,
    pub body_a: BodyHandle,
    pub body_b: BodyHandle,
}

/// Two shapes that met faster than the hit threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitEvent {
    pub shape_a: ShapeHandle,
    pub shape_b: ShapeHandle,
    pub body_a: BodyHandle,
    pub body_b: BodyHandle,
    /// Where they met (world, m).
    pub point: Vec3,
    /// From A to B.
    pub normal: Vec3,
    /// Approach speed along the normal at impact (m/s).
    pub speed: f32,
}

/// A sensor and a shape that started or stopped overlapping it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SensorEvent {
    pub sensor_shape: ShapeHandle,
    pub visitor_shape: ShapeHandle,
    pub sensor_body: BodyHandle,
    pub visitor_body: BodyHandle,
}

/// A body that moved in the step, or fell asleep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveEvent {
    pub body: BodyHandle,
    pub transform: Transform,
    pub user_data: u64,
    pub fell_asleep: bool,
}

/// What a pre-solve callback sees: a touching contact and its (first) manifold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreSolveContact {
    pub shape_a: ShapeHandle,
    pub shape_b: ShapeHandle,
    pub body_a: BodyHandle,
    pub body_b: BodyHandle,
    /// The manifold: unit normal from A to B, points with their separations (negative:
    /// overlap). A shape against a mesh or heightfield may have several; this is the first
    /// with points.
    pub manifold: Manifold,
}

/// Hooks a host puts into a step (`World::step_with`). Both default to keeping everything.
pub trait StepCallbacks {
    /// Called for every pair of shapes the broad phase would make a contact for. False: no
    /// contact, until the pair is proposed again — which happens when either shape's
    /// broad-phase box is refit (its body moved past the box's margin, was teleported, or a
    /// shape was added), so a filter that depends on changing state should expect to be asked
    /// again, and a rejected pair is not re-tested while both shapes stay inside their boxes.
    fn pair_filter(&mut self, _world: &World, _a: ShapeHandle, _b: ShapeHandle) -> bool {
        true
    }
    /// Called once per step for every touching, awake contact (not sensors), after the
    /// narrow phase and before the solver. False: the contact does not push in this step.
    fn pre_solve(&mut self, _world: &World, _contact: &PreSolveContact) -> bool {
        true
    }
}

/// A `StepCallbacks` that keeps everything.
pub struct NoCallbacks;
impl StepCallbacks for NoCallbacks {}

/// A contact that may report a hit once the solver has run: (contact, speed, point, normal).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HitCandidate {
    pub contact: u32,
    pub speed: f32,
    pub point: Vec3,
    pub normal: Vec3,
}

/// The events of the last step, and the storage that builds them.
#[derive(Default)]
pub struct Events {
    pub contact_begin: Vec<ContactEvent>,
    pub contact_end: Vec<ContactEvent>,
    pub contact_hit: Vec<HitEvent>,
    pub sensor_begin: Vec<SensorEvent>,
    pub sensor_end: Vec<SensorEvent>,
    pub body_moves: Vec<MoveEvent>,
    /// End events from destroyed contacts, appended to the step's own at its end.
    pub(crate) pending_contact_end: Vec<ContactEvent>,
    pub(crate) pending_sensor_end: Vec<SensorEvent>,
    pub(crate) hits: Vec<HitCandidate>,
    /// Bodies put to sleep in this step.
    pub(crate) fell_asleep: Vec<u32>,
    /// Touching awake contacts offered to the pre-solve callback this step.
    pub(crate) pre_solve: Vec<u32>,
    /// Per chunk of awake bodies, its move events (joined into `body_moves`).
    pub(crate) move_chunks: Vec<Vec<MoveEvent>>,
}

impl Events {
    fn clear(&mut self) {
        self.contact_begin.clear();
        self.contact_end.clear();
        self.contact_hit.clear();
        self.sensor_begin.clear();
        self.sensor_end.clear();
        self.body_moves.clear();
        self.hits.clear();
        self.fell_asleep.clear();
    }
}

/// A contact's first manifold with points (a shape against a mesh may have an empty first).
fn first_manifold(c: &crate::collision::contact::Contact) -> Manifold {
    (0..c.manifold_count())
        .map(|k| *c.child(k).0)
        .find(|m| m.count > 0)
        .unwrap_or(c.manifold)
}

/// Smallest separation over every manifold of a contact.
fn min_separation(c: &crate::collision::contact::Contact) -> f32 {
    let mut s = f32::MAX;
    for k in 0..c.manifold_count() {
        for p in c.child(k).0.points() {
            s = s.min(p.separation);
        }
    }
    s
}

/// After contact `c`'s narrow phase, on the task that updated it: takes a sensor contact out
/// of the solver (`touching` false) and says whether `World::contact_events_after_update`
/// has anything to do for it — an overlap, begin or end to report, or a hit candidate. The
/// same tests that function makes, so the merge after the narrow phase reads only the
/// contacts that need it.
pub(crate) fn events_pending(c: &mut crate::collision::contact::Contact, slop: f32) -> bool {
    let flags = c.event_flags;
    if flags & SENSOR != 0 {
        c.touching = false;
        return (min_separation(c) <= 0.0) != c.reported;
    }
    if flags & (CONTACT_EVENTS | HIT_EVENTS) == 0 {
        return false;
    }
    let now = if c.reported {
        c.touching
    } else {
        c.touching && min_separation(c) <= slop
    };
    now != c.reported || (flags & HIT_EVENTS != 0 && c.touching)
}

/// Awake bodies per move-event chunk: a fixed number, so the events do not depend on workers.
const MOVE_CHUNK: usize = 256;

impl World {
    /// The last step's events (`Events`); valid until the next step.
    pub fn events(&self) -> &Events {
        &self.events
    }

    /// Starts a step's events: the last step's are dropped.
    pub(crate) fn begin_events(&mut self) {
        self.events.clear();
    }

    /// The flags (`CONTACT_EVENTS`, …) of a new contact between shapes `a` and `b`.
    pub(crate) fn contact_flags(&self, a: u32, b: u32) -> u8 {
        let (a, b) = (&self.shapes.at(a).def, &self.shapes.at(b).def);
        let mut f = 0;
        if a.is_sensor || b.is_sensor {
            f |= SENSOR;
            if a.enable_sensor_events && b.enable_sensor_events {
                f |= SENSOR_EVENTS;
            }
        } else {
            if a.enable_contact_events && b.enable_contact_events {
                f |= CONTACT_EVENTS;
            }
            if a.enable_hit_events || b.enable_hit_events {
                f |= HIT_EVENTS;
            }
        }
        f
    }

    fn contact_event(&self, ci: u32) -> ContactEvent {
        let c = self.contacts.at(ci);
        let handle = |s: u32| self.shapes.handle_at(s).expect("live shape");
        let body = |b: u32| self.bodies.handle_at(b).expect("live body");
        ContactEvent {
            shape_a: handle(c.shape_a),
            shape_b: handle(c.shape_b),
            body_a: body(c.body_a),
            body_b: body(c.body_b),
        }
    }

    fn sensor_event(&self, ci: u32) -> SensorEvent {
        let e = self.contact_event(ci);
        if self.shapes.at(self.contacts.at(ci).shape_a).def.is_sensor {
            SensorEvent {
                sensor_shape: e.shape_a,
                visitor_shape: e.shape_b,
                sensor_body: e.body_a,
                visitor_body: e.body_b,
            }
        } else {
            SensorEvent {
                sensor_shape: e.shape_b,
                visitor_shape: e.shape_a,
                sensor_body: e.body_b,
                visitor_body: e.body_a,
            }
        }
    }

    /// After contact `ci`'s narrow phase (stage 4): begin and end events, the sensor overlap
    /// (a sensor contact is then taken out of the solver and islands), and hit candidates.
    /// `motion` bounds the relative speed of the two shapes' points (`collide`: |vB − vA| +
    /// |ωA|·extentA + |ωB|·extentB) and `spin` is |ωA| + |ωB|.
    pub(crate) fn contact_events_after_update(&mut self, ci: u32, motion: f32, spin: f32) {
        let flags = self.contacts.at(ci).event_flags;
        if flags & SENSOR != 0 {
            let c = self.contacts.at_mut(ci);
            // From the points (`touching` is kept false for the solver, and the body-pair
            // cache moves the points without setting it).
            let overlap = min_separation(c) <= 0.0;
            c.touching = false;
            if overlap != c.reported {
                c.reported = overlap;
                if flags & SENSOR_EVENTS != 0 {
                    let e = self.sensor_event(ci);
                    if overlap {
                        self.events.sensor_begin.push(e);
                    } else {
                        self.events.sensor_end.push(e);
                    }
                }
            }
            return;
        }
        if flags & (CONTACT_EVENTS | HIT_EVENTS) == 0 {
            return;
        }
        let c = self.contacts.at(ci);
        let slop = self.settings.linear_slop;
        let now = if c.reported {
            c.touching
        } else {
            c.touching && min_separation(c) <= slop
        };
        if now != c.reported {
            self.contacts.at_mut(ci).reported = now;
            if flags & CONTACT_EVENTS != 0 {
                let e = self.contact_event(ci);
                if now {
                    self.events.contact_begin.push(e);
                } else {
                    self.events.contact_end.push(e);
                }
            }
        }
        if flags & HIT_EVENTS != 0 && self.contacts.at(ci).touching {
            self.hit_candidate(ci, motion, spin);
        }
    }

    /// The fastest approaching point of contact `ci` before the solve, if above the threshold.
    fn hit_candidate(&mut self, ci: u32, motion: f32, spin: f32) {
        let c = self.contacts.at(ci);
        let (a, b) = (self.bodies.at(c.body_a), self.bodies.at(c.body_b));
        let g = self.settings.gravity;
        let accel = |body: &crate::dynamics::body::Body| {
            if body.is_dynamic() && body.awake {
                g * body.gravity_scale
            } else {
                Vec3::ZERO
            }
        };
        let relative_accel = accel(b) - accel(a);
        // A bound on every point's approach speed first (a resting pile has slow contacts):
        // |relative velocity| at a point is at most |vB − vA| + |ωA|·rA + |ωB|·rB, r within a
        // shape's extent plus the gap (points lie midway between the surfaces).
        let mut gap = 0.0_f32;
        for k in 0..c.manifold_count() {
            for p in c.child(k).0.points() {
                gap = gap.max(p.separation);
            }
        }
        let bound = motion + spin * gap;
        let threshold = self.settings.hit_event_threshold;
        if bound * bound + 2.0 * relative_accel.length() * gap <= threshold * threshold {
            return;
        }
        let mut best: Option<HitCandidate> = None;
        for k in 0..c.manifold_count() {
            let m = c.child(k).0;
            let n = m.normal;
            for p in m.points() {
                let va = a.v + a.w.cross(p.point - a.center);
                let vb = b.v + b.w.cross(p.point - b.center);
                let approach = -(vb - va).dot(n);
                if approach <= 0.0 {
                    continue;
                }
                // Carried over the gap still open by the bodies' gravity (a free fall).
                let closing = -relative_accel.dot(n);
                let speed = if p.separation > 0.0 && closing > 0.0 {
                    (approach * approach + 2.0 * closing * p.separation).sqrt()
                } else {
                    approach
                };
                if best.map_or(true, |h| speed > h.speed) {
                    best = Some(HitCandidate {
                        contact: ci,
                        speed,
                        point: p.point,
                        normal: n,
                    });
                }
            }
        }
        if let Some(h) = best {
            if h.speed > self.settings.hit_event_threshold {
                self.events.hits.push(h);
            }
        }
    }

    /// A contact is being destroyed: its end event, if it reported a begin.
    pub(crate) fn contact_events_on_destroy(&mut self, ci: u32) {
        let c = self.contacts.at(ci);
        if !c.reported {
            return;
        }
        if c.event_flags & SENSOR_EVENTS != 0 {
            let e = self.sensor_event(ci);
            self.events.pending_sensor_end.push(e);
        } else if c.event_flags & CONTACT_EVENTS != 0 {
            let e = self.contact_event(ci);
            self.events.pending_contact_end.push(e);
        }
    }

    /// After the solve: hits whose contact pushed.
    pub(crate) fn hit_events_after_solve(&mut self) {
        for k in 0..self.events.hits.len() {
            let h = self.events.hits[k];
            let Some(handle) = self.contacts.handle_at(h.contact) else {
                continue;
            };
            let c = self.contacts.get(handle).expect("live contact");
            if c.disabled {
                continue;
            }
            let pushed = (0..c.manifold_count()).any(|m| {
                let (manifold, impulses, _) = c.child(m);
                impulses[..manifold.count].iter().any(|i| i.normal > 0.0)
            });
            if pushed {
                let e = self.contact_event(h.contact);
                self.events.contact_hit.push(HitEvent {
                    shape_a: e.shape_a,
                    shape_b: e.shape_b,
                    body_a: e.body_a,
                    body_b: e.body_b,
                    point: h.point,
                    normal: h.normal,
                    speed: h.speed,
                });
            }
        }
    }

    /// The end of a step: move events, and end events of contacts destroyed since the last.
    pub(crate) fn finish_events(&mut self) {
        let World {
            events,
            bodies,
            awake_bodies,
            body_marks,
            tasks,
            ..
        } = self;
        use crate::step::{MOVED, WOKEN};
        events.contact_end.append(&mut events.pending_contact_end);
        events.sensor_end.append(&mut events.pending_sensor_end);
        // Move events of the awake bodies in fixed chunks in parallel (a task writes only its
        // own bodies' reported transforms and its chunk's list), joined in awake order.
        let chunks = awake_bodies.len().div_ceil(MOVE_CHUNK);
        if events.move_chunks.len() < chunks {
            events.move_chunks.resize_with(chunks, Vec::new);
        }
        {
            let lists = crate::parallel::Disjoint::new(&mut events.move_chunks[..chunks]);
            let (slots, awake_bodies, marks) = (bodies.disjoint(), &awake_bodies[..], &body_marks[..]);
            crate::parallel::run(&**tasks, chunks as u32, 1, &|start, end, _| {
                for chunk in start as usize..end as usize {
                    // SAFETY: each chunk is one task's, and each awake body is in one chunk.
                    let out = unsafe { lists.at(chunk) };
                    out.clear();
                    let span = chunk * MOVE_CHUNK..((chunk + 1) * MOVE_CHUNK).min(awake_bodies.len());
                    for &b in &awake_bodies[span] {
                        // `finish_bodies` marked the bodies to report; one woken since is
                        // checked here.
                        if marks.get(b as usize).is_some_and(|m| m & (MOVED | WOKEN) == 0) {
                            continue;
                        }
                        // SAFETY: as above.
                        let (handle, body) = unsafe { slots.handle_and_mut(b) };
                        if !body.enable_move_events || body.is_static() || body.xf == body.reported_xf {
                            continue;
                        }
                        body.reported_xf = body.xf;
                        out.push(MoveEvent {
                            body: handle,
                            transform: body.xf,
                            user_data: body.user_data,
                            fell_asleep: false,
                        });
                    }
                }
            });
        }
        for list in &events.move_chunks[..chunks] {
            events.body_moves.extend_from_slice(list);
        }
        for &b in events.fell_asleep.iter() {
            let handle = bodies.handle_at(b).expect("live body");
            let body = bodies.at_mut(b);
            if !body.enable_move_events {
                continue;
            }
            body.reported_xf = body.xf;
            events.body_moves.push(MoveEvent {
                body: handle,
                transform: body.xf,
                user_data: body.user_data,
                fell_asleep: true,
            });
        }
    }

    // ------------------------------------------------------------------ step hooks

    /// Advances the world like `step`, running the host's pair filter and pre-solve
    /// callbacks in their places (`StepCallbacks`).
    pub fn step_with(&mut self, dt: f32, callbacks: &mut dyn StepCallbacks) -> crate::error::Result<()> {
        if self.begin_step(dt)? {
            self.find_pairs();
            for i in 0..self.pair_candidate_count() {
                let (a, b) = self.pair_candidate(i);
                let keep = callbacks.pair_filter(self, a, b);
                self.keep_pair_candidate(i, keep);
            }
            self.collide_pairs(dt);
            for i in 0..self.pre_solve_count() {
                let c = self.pre_solve_contact(i);
                if !callbacks.pre_solve(self, &c) {
                    self.disable_pre_solve_contact(i);
                }
            }
            self.finish_step(dt);
        }
        Ok(())
    }

    /// Candidate pairs found by `find_pairs`, for a pair filter.
    pub fn pair_candidate_count(&self) -> usize {
        self.broad.candidates.len()
    }

    /// Candidate `i`'s shapes.
    pub fn pair_candidate(&self, i: usize) -> (ShapeHandle, ShapeHandle) {
        let (a, b) = self.broad.candidates[i];
        let h = |s: u32| self.shapes.handle_at(s).expect("live shape");
        (h(a), h(b))
    }

    /// Keeps or drops candidate `i` (a dropped one gets no contact in `collide_pairs`).
    pub fn keep_pair_candidate(&mut self, i: usize, keep: bool) {
        if !keep {
            self.broad.candidates[i].1 = crate::dynamics::body::NONE;
        }
    }

    /// Lists the touching awake contacts for a pre-solve callback (after `collide_pairs`);
    /// returns how many.
    pub fn pre_solve_count(&mut self) -> usize {
        let World {
            events,
            awake_contacts,
            contacts,
            ..
        } = self;
        events.pre_solve.clear();
        events
            .pre_solve
            .extend(awake_contacts.iter().copied().filter(|&c| contacts.at(c).touching));
        events.pre_solve.len()
    }

    /// Pre-solve contact `i`.
    pub fn pre_solve_contact(&self, i: usize) -> PreSolveContact {
        let ci = self.events.pre_solve[i];
        let e = self.contact_event(ci);
        PreSolveContact {
            shape_a: e.shape_a,
            shape_b: e.shape_b,
            body_a: e.body_a,
            body_b: e.body_b,
            manifold: first_manifold(self.contacts.at(ci)),
        }
    }

    /// Pre-solve contact `i` does not push in this step.
    pub fn disable_pre_solve_contact(&mut self, i: usize) {
        let ci = self.events.pre_solve[i];
        self.contacts.at_mut(ci).disabled = true;
    }
}

const _: () = assert!(MAX_MANIFOLD_POINTS == 4);
