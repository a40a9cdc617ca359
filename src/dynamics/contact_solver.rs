//! Contacts to solve, per step. `prepare` lists every touching manifold (and every contact a
//! generator wrote) as a small `ContactRef`: its solver bodies, which way round, and its kind.
//! A contact against a mesh or heightfield may have several manifolds (`Contact::child`);
//! each is its own ref, naming the manifold by `child`, and so its own constraint.
//! The batched solver (`contact_wide.rs`) colours the refs and builds the constraints in lanes
//! straight from the contacts as it packs them, so no array of scalar constraints is written
//! and read back; after the solve, `store` keeps each lane's impulses on its contact for warm
//! starting.

use crate::collision::contact::{Contact, GeneratedContact};
use crate::collision::narrow_phase::MAX_MANIFOLD_POINTS;
use crate::dynamics::body::{Body, NONE};
use crate::dynamics::solver::{BodyState, Velocity};
use crate::math::Vec3;
use crate::pool::Pool;
use crate::world::World;

/// `ContactRef::source` bit of a generated contact (the rest indexes `World::generated_contacts`).
const GENERATED: u32 = 1 << 31;

/// One contact in the solver's orientation: a static body (solver index 0) is always B, so
/// batches whose B sides are all static skip B's half of the work.
#[derive(Clone, Copy, Debug)]
pub struct ContactRef {
    /// The persistent contact, or `GENERATED` | the generated contact's index.
    pub source: u32,
    /// Solver state indices of the bodies (0: the static dummy).
    pub a: u32,
    pub b: u32,
    /// A and B are the contact's B and A.
    pub swapped: bool,
    /// Batch kind and load (bits 0..3, see `ContactRef::order_key`), and whether side A
    /// (bit 4) and B (bit 5) have finite mass (`writes_a`, `writes_b`).
    key: u8,
    /// Which of the contact's manifolds (`Contact::child`).
    pub child: u16,
}

const SPINS: u8 = 1 << 3;
const WRITES_A: u8 = 1 << 4;
const WRITES_B: u8 = 1 << 5;
const SHARED: u8 = 1 << 6;

impl ContactRef {
    #[allow(clippy::too_many_arguments)]
    fn new(
        source: u32,
        child: u16,
        a: u32,
        b: u32,
        ma: f32,
        mb: f32,
        count: usize,
        spins: bool,
        loaded: bool,
        shared: bool,
    ) -> ContactRef {
        // A static (or sleeping) A goes to B.
        let swapped = a == 0 && b != 0;
        let (a, b, ma, mb) = if swapped { (b, a, mb, ma) } else { (a, b, ma, mb) };
        ContactRef {
            source,
            a,
            b,
            swapped,
            key: if spins { SPINS } else { 0 }
                | u8::from(count > 1) << 2
                | u8::from(b != 0) << 1
                | u8::from(loaded)
                | if ma > 0.0 { WRITES_A } else { 0 }
                | if mb > 0.0 { WRITES_B } else { 0 }
                | if shared { SHARED } else { 0 },
            child,
        }
    }

    /// Side A has finite mass: the colouring reserves its body.
    #[inline(always)]
    pub fn writes_a(&self) -> bool {
        self.key & WRITES_A != 0
    }

    /// Side B has finite mass.
    #[inline(always)]
    pub fn writes_b(&self) -> bool {
        self.key & WRITES_B != 0
    }

    /// Its contact has several manifolds (one constraint each): their results are stored
    /// one after another, never from two tasks at once (`contact_wide::store`).
    #[inline(always)]
    pub fn shared(&self) -> bool {
        self.key & SHARED != 0
    }

    /// Whether it resists rolling and spin, point-count class and whether side B is dynamic:
    /// a batch holds one kind only, so a constraint is solved the same way whatever its
    /// batch-mates (and the lane width).
    #[inline(always)]
    pub fn kind(&self) -> u8 {
        (self.key & 0b1111) >> 1
    }

    /// Like with like: the kinds, then whether the constraint carried load last step (batches
    /// of idle constraints end their sweep early). Four bits.
    #[inline(always)]
    pub fn order_key(&self) -> usize {
        (self.key & 0b1111) as usize
    }

    /// Number of distinct `order_key` values.
    pub const ORDER_KEYS: usize = 16;

    /// The constraint has rolling resistance or torsional friction (rows about the tangents,
    /// and a twist row even with one point).
    #[inline(always)]
    pub fn spins(&self) -> bool {
        self.key & SPINS != 0
    }

    /// Index in `World::generated_contacts` of a generated contact.
    #[inline(always)]
    pub fn generated_index(&self) -> usize {
        (self.source & !GENERATED) as usize
    }

    /// The persistent contact it was built from, if any.
    #[inline(always)]
    pub fn contact(&self) -> Option<u32> {
        (self.source & GENERATED == 0).then_some(self.source)
    }
}

/// What a lane's constraint is built from.
pub struct Sources<'a> {
    pub contacts: &'a Pool<Contact>,
    pub bodies: &'a Pool<Body>,
    pub generated: &'a [GeneratedContact],
    pub states: &'a [BodyState],
    /// Velocities at the start of the step.
    pub vel: &'a [Velocity],
}

/// The solver index of a body for this step: its own while awake, else the static dummy.
#[inline]
fn solver_index(bodies: &Pool<Body>, b: u32) -> u32 {
    if b == NONE {
        return 0;
    }
    let body = bodies.at(b);
    if body.awake {
        body.solver_index
    } else {
        0
    }
}

/// Awake contacts per listing task; a fixed number, so the lists do not depend on workers.
const PREPARE_CHUNK: usize = 512;

/// The refs of one awake contact (none unless it touches, is enabled and moves a body),
/// pushed to `out`; returns whether it bounces.
#[inline]
fn contact_refs(ci: u32, c: &Contact, bodies: &Pool<Body>, states: &[BodyState], out: &mut Vec<ContactRef>) -> bool {
    if !c.touching || c.disabled {
        return false;
    }
    let (a, b) = (solver_index(bodies, c.body_a), solver_index(bodies, c.body_b));
    let (ma, mb) = (states[a as usize].inv_mass, states[b as usize].inv_mass);
    if ma == 0.0 && mb == 0.0 {
        return false;
    }
    let spins = c.rolling_resistance > 0.0 || c.torsional_friction > 0.0;
    let shared = c.manifold_count() > 1;
    for k in 0..c.manifold_count() {
        let (m, impulses, _) = c.child(k);
        let count = m.count;
        if count == 0 {
            continue;
        }
        let loaded = impulses[..count].iter().any(|p| p.normal > 0.0);
        out.push(ContactRef::new(
            ci, k as u16, a, b, ma, mb, count, spins, loaded, shared,
        ));
    }
    c.restitution > 0.0
}

/// Lists every awake contact with manifold points and every generated contact that moves a
/// body (`SolverScratch::refs`), and notes whether any of them bounces. The awake contacts
/// are listed in fixed chunks in parallel, each into its own list, and the lists joined in
/// chunk order: the same refs in the same order as one pass would give.
pub fn prepare(world: &mut World) {
    let World {
        solver: scratch,
        awake_contacts,
        contacts,
        bodies,
        tasks,
        generated_contacts,
        ..
    } = world;
    let chunks = awake_contacts.len().div_ceil(PREPARE_CHUNK);
    if scratch.ref_chunks.len() < chunks {
        scratch.ref_chunks.resize_with(chunks, Vec::new);
    }
    let bounced = std::sync::atomic::AtomicBool::new(false);
    {
        let (states, lists) = (
            &scratch.states[..],
            crate::parallel::Disjoint::new(&mut scratch.ref_chunks[..chunks]),
        );
        let (awake_contacts, contacts, bodies) = (&*awake_contacts, &*contacts, &*bodies);
        crate::parallel::run(&**tasks, chunks as u32, 1, &|start, end, _| {
            let mut bounces = false;
            for chunk in start as usize..end as usize {
                // SAFETY: each chunk is one task's.
                let out = unsafe { lists.at(chunk) };
                out.clear();
                let span = chunk * PREPARE_CHUNK..((chunk + 1) * PREPARE_CHUNK).min(awake_contacts.len());
                for &ci in &awake_contacts[span] {
                    bounces |= contact_refs(ci, contacts.at(ci), bodies, states, out);
                }
            }
            if bounces {
                bounced.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        });
    }
    let (refs, states) = (&mut scratch.refs, &scratch.states);
    refs.clear();
    for list in &scratch.ref_chunks[..chunks] {
        refs.extend_from_slice(list);
    }
    let mut bounces = bounced.into_inner();
    for (gi, g) in generated_contacts.iter().enumerate() {
        let (a, b) = (solver_index(bodies, g.body_a), solver_index(bodies, g.body_b));
        let (ma, mb) = (states[a as usize].inv_mass, states[b as usize].inv_mass);
        if ma == 0.0 && mb == 0.0 {
            continue;
        }
        bounces |= g.restitution > 0.0;
        refs.push(ContactRef::new(
            GENERATED | gi as u32,
            0,
            a,
            b,
            ma,
            mb,
            1,
            false,
            false,
            false,
        ));
    }
    scratch.bounces = bounces;
}

/// What one lane solved, written back to its contact for warm starting the next step.
pub struct LaneImpulses {
    pub normal: [f32; MAX_MANIFOLD_POINTS],
    /// Friction impulse on side B as a world vector, and about the normal.
    pub tangent: Vec3,
    pub twist: f32,
    pub sliding: bool,
}

/// Keeps a lane's rolling-resistance impulse (on side B, world) on its contact.
#[inline]
pub fn store_rolling(r: &ContactRef, rolling: Vec3, contact: &mut Contact) {
    let (_, _, friction) = contact.child_impulses_mut(r.child as usize);
    let rolling = if rolling.is_finite() { rolling } else { Vec3::ZERO };
    friction.rolling = if r.swapped { -rolling } else { rolling };
}

/// Keeps a lane's impulses on its contact (generated contacts keep none).
#[inline]
pub fn store(r: &ContactRef, out: &LaneImpulses, contact: &mut Contact) {
    let (count, impulses, friction) = contact.child_impulses_mut(r.child as usize);
    // A diverged lane (see `solver::guard_velocities`) must not warm-start the next step.
    let finite = out.normal[..count].iter().all(|n| n.is_finite()) && out.tangent.is_finite() && out.twist.is_finite();
    for (imp, &n) in impulses[..count].iter_mut().zip(&out.normal) {
        imp.normal = if finite { n } else { 0.0 };
    }
    friction.tangent = if !finite {
        Vec3::ZERO
    } else if r.swapped {
        -out.tangent
    } else {
        out.tangent
    };
    friction.twist = if finite { out.twist } else { 0.0 };
    friction.sliding = out.sliding;
}

// The solver walks refs in colour order; they stay 16 bytes.
const _: () = assert!(std::mem::size_of::<ContactRef>() == 16);
