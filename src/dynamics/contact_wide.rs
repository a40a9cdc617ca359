//! The contact solver's passes, four (SSE2) or eight (AVX2) constraints at a time.
//!
//! Each step the contacts listed by `contact_solver::prepare` are graph-coloured so that no
//! two of a colour share a dynamic body, then packed a lane each into batches in colour order;
//! `pack` stages each lane's input straight from its contact and builds the constraints in
//! lanes. Lanes of a batch touch different bodies, so one batch gathers the velocities of its
//! bodies, solves all its constraints with lane arithmetic and scatters the velocities back: a
//! Gauss–Seidel sweep with independent constraints side by side. Constraints that fit no colour
//! go into batches of their own. Static bodies (and kinematic ones: zero inverse mass) are
//! never written, so they do not take part in the colouring.
//!
//! Per sub-step (Box2D v3's soft step): `refresh` (current lever arms at the midpoint of the
//! two material points, Jacobians, the block matrix K and its inverse, separations),
//! `warm_start`, a soft `solve` sweep that pushes overlap out and damps, the position update,
//! then a rigid relax `solve` sweep that removes the push velocity. Each sweep block-solves a
//! manifold's normal impulses (exactly through K⁻¹, by projected Gauss–Seidel on K where a point
//! would pull), then, in batches of rounded pairs, its rolling resistance, then its patch
//! friction (static/dynamic coefficients, twist with torsional friction). After the
//! sub-steps: `restitution`, then `store` writes the impulses back for warm starting.

use crate::collision::contact::{Contact, GeneratedContact};
use crate::collision::narrow_phase::MAX_MANIFOLD_POINTS;
use crate::dynamics::contact_solver::{self, ContactRef, LaneImpulses, Sources};
use crate::dynamics::solver::{BodyState, Velocity};
use crate::math::Vec3;
use crate::parallel::{SharedMut, TaskRunner};
use crate::pool::{DisjointPool, Pool};
#[cfg(target_arch = "x86_64")]
use crate::simd::F8;
use crate::simd::{Lanes, F4, M, V};
use std::ops::Range;

const MAXP: usize = MAX_MANIFOLD_POINTS;

/// Colours tried before a constraint goes to a batch of its own.
const COLORS: usize = 24;
const ALL_COLORS: u32 = (1 << COLORS) - 1;

/// Inner iterations of the projected Gauss–Seidel fallback of the block solve. The fallback
/// runs in most four-point batches of a pile or pyramid (some lane has a lifting point); the
/// 30-box tower and the 385-box pyramid rest to the same 0.1 mm with 1, 2 or 4 iterations.
const BLOCK_ITERATIONS: usize = 2;

/// Relative regularisation of K (four coplanar points constrain only three motions).
const BLOCK_REGULARIZATION: f32 = 1.0e-3;

/// Fraction of the remaining error a rigid (generated) constraint removes per sub-step.
const RIGID_PUSH: f32 = 0.3;

/// Lane index marking an empty lane.
const EMPTY: u32 = u32::MAX;

#[derive(Clone, Copy, Default)]
pub struct WidePoint<L> {
    /// Arms to the shapes' core points at the start of the step (they turn with the bodies);
    /// the contact point is the core point plus `oa` (resp. `ob`) along the normal.
    ca0: V<L>,
    cb0: V<L>,
    separation0: L,
    /// All-ones in lanes where this point exists.
    active: L,
    rna: V<L>,
    rnb: V<L>,
    ia: V<L>,
    ib: V<L>,
    separation: L,
    normal_mass: L,
    impulse: L,
    max_impulse: L,
    relative_velocity: L,
}

#[derive(Clone, Copy, Default)]
pub struct WideFriction<L> {
    ca0: V<L>,
    cb0: V<L>,
    rta: [V<L>; 2],
    rtb: [V<L>; 2],
    ita: [V<L>; 2],
    itb: [V<L>; 2],
    ina: V<L>,
    inb: V<L>,
    tangent_mass: [L; 2],
    twist_mass: L,
    twist_radius: L,
    tangent_impulse: [L; 2],
    twist_impulse: L,
    sliding: L,
    /// Rolling resistance and torsional friction as levers (m): the largest rolling and
    /// extra twist impulse per unit of normal impulse (spin batches only).
    rolling: L,
    torsion: L,
    /// Inverse inertia times each tangent, and the rolling rows' 2×2 effective mass (the
    /// inverse of `tᵢ·(I_A⁻¹ + I_B⁻¹)·tⱼ`; entries 00, 01, 11).
    ira: [V<L>; 2],
    irb: [V<L>; 2],
    rolling_mass: [L; 3],
    /// Rolling impulse about each tangent (an angular impulse on B).
    rolling_impulse: [L; 2],
}

#[derive(Clone, Copy, Default)]
pub struct WideContact<L: Lanes> {
    /// Solver state indices of the bodies; 0 is the static dummy.
    a: L::Indices,
    b: L::Indices,
    /// Index of each lane's scalar constraint, or `EMPTY`.
    src: L::Indices,
    /// Largest point count of the lanes: 1, or 4 (missing points inactive).
    count: usize,
    /// Every lane's body B is the static dummy: B's half of the work is skipped.
    b_static: bool,
    /// The lanes resist rolling and spin (`ContactRef::spins`; a batch holds one kind): rows
    /// about the two tangents, and the twist row even for one-point manifolds.
    spin: bool,
    ma: L,
    mb: L,
    /// Some lane's body has a locked linear axis (`body::LOCK_*`): impulses are applied
    /// through `free_a`/`free_b`. Without locks the passes take the plain path.
    locked: bool,
    /// 1.0 along the world axes each lane's body may move along, 0.0 along its locked ones
    /// (all ones without locks): the body's inverse mass per axis is `ma * free_a`.
    free_a: V<L>,
    free_b: V<L>,
    /// The linear part of the effective mass along the normal and each tangent:
    /// `d·(M_A⁻¹ + M_B⁻¹)·d` with the per-axis inverse masses, `ma + mb` bit for bit when no
    /// axis is locked (`linear_term`).
    m_normal: L,
    m_tangent: [L; 2],
    normal: V<L>,
    /// Offsets from each core point to the contact point: `r_a·n` and `−r_b·n`.
    oa: V<L>,
    ob: V<L>,
    /// Where the contact point sits between the two bodies' contact points: 0 on A's, 1 on
    /// B's. A rounded surface defines where it touches now (a rolling sphere touches below its
    /// centre, whatever the ground's material point did); otherwise the midpoint.
    at_b: L,
    tangents: [V<L>; 2],
    static_friction: L,
    dynamic_friction: L,
    restitution: L,
    /// All-ones in lanes solved rigidly: generated contacts (rods, cables) must hold their
    /// length under load, and they do not form the deep stacks the soft contacts damp.
    rigid: L,
    /// The biased sweep's coefficients per lane, fixed for a step (`set_softness`): push-out
    /// rate, mass scale, impulse leak, and the part of its impulse a point keeps.
    soft_rate: L,
    soft_ms: L,
    soft_is: L,
    soft_keep: L,
    /// The smaller shape's size (`Contact::size`; `f32::MAX` for generated contacts), and the
    /// overlap allowed without push-out: `linear_slop`, or a fiftieth of the size for small
    /// shapes (`set_softness`).
    size: L,
    slop: L,
    /// Squared relative motion under which a refresh is light (`LIGHT_REFRESH_MOTION`).
    light_tol2: L,
    has_restitution: bool,
    /// Some lane's contact has several manifolds (`ContactRef::shared`, `store`).
    shared: bool,
    points: [WidePoint<L>; MAXP],
    k: [[L; MAXP]; MAXP],
    k_inv: [[L; MAXP]; MAXP],
    friction: WideFriction<L>,
}

/// How many constraints a batch solves at once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LaneWidth {
    /// Eight (AVX2) where the CPU has AVX2, else four.
    #[default]
    Auto,
    /// Four (SSE2 on x86_64).
    Four,
}

/// The batches of one step, four or eight lanes wide.
enum Lanesets {
    Four(Vec<WideContact<F4>>),
    #[cfg(target_arch = "x86_64")]
    Eight(Vec<WideContact<F8>>),
}

/// Calls the pass `$f::<L>(batches, args…)` on the four-lane batches, or through its AVX2
/// entry point in `eight` on the eight-lane ones. Results are bit for bit the same either way:
/// a colour's constraints share no dynamic body, batches are homogeneous (see `build`), and
/// every pass decides lane by lane.
macro_rules! dispatch {
    ($sets:expr, $f:ident($($arg:expr),*)) => {
        match $sets {
            Lanesets::Four(b) => $f::<F4>(b, $($arg),*),
            // SAFETY: `Eight` batches exist only where AVX2 was detected (`Batches::new`).
            #[cfg(target_arch = "x86_64")]
            Lanesets::Eight(b) => unsafe { eight::$f(b, $($arg),*) },
        }
    };
}

/// The passes compiled for AVX2 on eight lanes: each entry point enables the feature and the
/// generic pass (`#[inline(always)]`, like everything it calls) is compiled inside it.
#[cfg(target_arch = "x86_64")]
mod eight {
    use super::*;

    macro_rules! entry {
        ($($name:ident($($p:ident: $t:ty),*);)*) => {$(
            #[target_feature(enable = "avx2")]
            pub unsafe fn $name(b: &mut Vec<WideContact<F8>>, $($p: $t),*) {
                super::$name::<F8>(b, $($p),*)
            }
        )*};
    }

    entry! {
        grow_all(used: usize);
        pack_range_all(spans: &[Span], members: &[Vec<u32>], singles: &[u32], refs: &[ContactRef], sources: &Sources, range: Range<usize>);
        set_softness_all(soft: &SoftSweep, inv_h: f32);
        refresh_all(states: &[BodyState], first: bool);
        refresh_warm_start_all(states: &[BodyState], vel: &mut [Velocity], first: bool, range: Range<usize>);
        solve_all(vel: &mut [Velocity], inv_h: f32, forward: bool, bias: Option<&SoftSweep>, range: Range<usize>);
        restitution_all(vel: &mut [Velocity], threshold: f32);
        store_all(refs: &[ContactRef], contacts: &DisjointPool<Contact>, shared: bool, range: Range<usize>);
    }
}

/// Reused storage of the batched solver.
pub struct Batches {
    sets: Lanesets,
    /// Per solver body, the colours it is used in (bit per colour).
    body_colors: Vec<u32>,
    color_members: Vec<Vec<u32>>,
    singles: Vec<u32>,
    /// A colour's members ordered by `order_key` (reused).
    ordered: Vec<u32>,
    /// Each batch's constraints: a run of a colour's members or one single (`layout`).
    spans: Vec<Span>,
    /// The end of each non-empty colour's batches (batches are packed colour by colour), then
    /// the end of the constraints that fit no colour (one batch each, solved in order).
    ends: Vec<u32>,
}

impl Default for Batches {
    fn default() -> Self {
        Batches::new(LaneWidth::Auto)
    }
}

impl Batches {
    pub fn new(width: LaneWidth) -> Batches {
        #[cfg(target_arch = "x86_64")]
        let sets = if width == LaneWidth::Auto && std::arch::is_x86_feature_detected!("avx2") {
            Lanesets::Eight(Vec::new())
        } else {
            Lanesets::Four(Vec::new())
        };
        #[cfg(not(target_arch = "x86_64"))]
        let sets = {
            let _ = width;
            Lanesets::Four(Vec::new())
        };
        Batches {
            sets,
            body_colors: Vec::new(),
            color_members: Vec::new(),
            singles: Vec::new(),
            ordered: Vec::new(),
            spans: Vec::new(),
            ends: Vec::new(),
        }
    }

    /// Lanes per batch in use: 4 or 8.
    pub fn lanes(&self) -> usize {
        match &self.sets {
            Lanesets::Four(_) => F4::N,
            #[cfg(target_arch = "x86_64")]
            Lanesets::Eight(_) => F8::N,
        }
    }

    /// Colours the contacts of `refs` and packs their constraints into batches, building
    /// each lane's constraint from `sources`. Colouring and the layout of the batches run on
    /// the calling thread; the batches are then packed by `runner`'s workers, each batch from
    /// its own constraints only, so every worker count packs the same bits.
    pub fn build(&mut self, refs: &[ContactRef], sources: &Sources, runner: &dyn TaskRunner) {
        self.body_colors.clear();
        self.body_colors.resize(sources.states.len(), 0);
        self.color_members.resize_with(COLORS, Vec::new);
        for members in self.color_members.iter_mut() {
            members.clear();
        }
        self.singles.clear();
        let colors = &mut self.body_colors;
        // Contacts between two awake bodies are coloured first, those with a static or
        // sleeping body (the static dummy) after them: a body's contacts with the ground then
        // take later colours, so a sweep ends each body on its support. Solved the other way
        // round, a light box pressed by a heavy one left every sweep moving into the ground
        // (the heavy box's push came last) and rocked: a 30× heavier box on a box floor never
        // came to rest, though it did on a plane, whose contacts happened to come last.
        let moving = refs.iter().enumerate().filter(|(_, r)| r.b != 0);
        let grounded = refs.iter().enumerate().filter(|(_, r)| r.b == 0);
        for (ri, r) in moving.chain(grounded) {
            // The first colour neither written body uses yet.
            let (a, b) = (r.a as usize, r.b as usize);
            let used_a = if r.writes_a() { colors[a] } else { 0 };
            let used_b = if r.writes_b() { colors[b] } else { 0 };
            let free = !(used_a | used_b) & ALL_COLORS;
            if free == 0 {
                self.singles.push(ri as u32);
                continue;
            }
            let color = free.trailing_zeros();
            if r.writes_a() {
                colors[a] |= 1 << color;
            }
            if r.writes_b() {
                colors[b] |= 1 << color;
            }
            self.color_members[color as usize].push(ri as u32);
        }
        // Each worker's share of a colour's batches (the solver stages hand a worker the
        // same share of every colour) holds the constraints of its share of the bodies.
        let homes = Homes::new(runner, sources.states.len());
        for members in self.color_members.iter_mut() {
            order(members, &mut self.ordered, refs, homes);
        }
        let used = self.layout(refs);
        dispatch!(&mut self.sets, grow_all(used));
        let shared = SharedMut::new(self);
        crate::parallel::run(runner, used as u32, PACK_MIN_RANGE, &|start, end, _| {
            // SAFETY: (as the solver stages' `SharedMut<Batches>`) each range writes only its
            // own batches of `sets` and reads `spans` and the members, which nobody writes
            // until `run` returns.
            let b = unsafe { shared.get() };
            let range = start as usize..end as usize;
            dispatch!(
                &mut b.sets,
                pack_range_all(&b.spans, &b.color_members, &b.singles, refs, sources, range)
            )
        });
    }

    /// Lays out the batches: each colour's members (ordered, see `order`) kind by kind in
    /// runs of up to a batch's lanes, then the constraints that fit no colour one per batch.
    /// Fills `spans` and `ends`; returns the number of batches.
    fn layout(&mut self, refs: &[ContactRef]) -> usize {
        let lanes = self.lanes();
        self.spans.clear();
        self.ends.clear();
        for (list, members) in self.color_members.iter().enumerate() {
            let mut start = 0;
            for group in members.chunk_by(|&x, &y| refs[x as usize].kind() == refs[y as usize].kind()) {
                for chunk in group.chunks(lanes) {
                    self.spans.push(Span {
                        list: list as u32,
                        start: start as u32,
                        len: chunk.len() as u32,
                    });
                    start += chunk.len();
                }
            }
            if !members.is_empty() {
                self.ends.push(self.spans.len() as u32);
            }
        }
        for k in 0..self.singles.len() {
            self.spans.push(Span {
                list: SINGLES,
                start: k as u32,
                len: 1,
            });
        }
        self.ends.push(self.spans.len() as u32);
        self.spans.len()
    }

    /// Batches in all.
    pub fn len(&self) -> usize {
        self.ends.last().map_or(0, |&e| e as usize)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The batches by colour, in solve order: each range but the last holds one colour's
    /// batches, which share no dynamic body and may be solved at the same time; the last holds
    /// the constraints that fit no colour, which must be solved one after another.
    pub fn colours(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        let starts = std::iter::once(0).chain(self.ends.iter().copied());
        starts
            .zip(self.ends.iter().copied())
            .map(|(s, e)| s as usize..e as usize)
    }
}

/// Which worker's share of the solver bodies a constraint belongs to (by its body A, never
/// the static dummy): the solver stages run each worker on its own share of every colour and
/// of the bodies (`solver_stages::worker`), so a colour ordered by these homes has a worker
/// solve, colour after colour, the constraints of the bodies it integrates, and a body's
/// velocity stays in one core's cache through the sub-steps instead of moving between the
/// cores at every colour. Results do not depend on it: constraints of one colour share no
/// dynamic body, and every lane is solved alone.
#[derive(Clone, Copy)]
struct Homes {
    /// The workers (1: one home).
    count: usize,
    /// Solver slots.
    slots: usize,
}

/// Most homes (`order`'s buckets are on the stack).
const MAX_HOMES: usize = 16;

impl Homes {
    fn new(runner: &dyn TaskRunner, slots: usize) -> Homes {
        let workers = match runner.concurrent() {
            0 | 1 => runner.worker_count(),
            c => c,
        };
        Homes {
            count: (workers as usize).clamp(1, MAX_HOMES),
            slots: slots.max(1),
        }
    }

    #[inline(always)]
    fn of(&self, r: &ContactRef) -> usize {
        r.a as usize * self.count / self.slots
    }
}

/// Orders a colour's members by home (`Homes`), then by `ContactRef::order_key`, keeping
/// their order within both (a counting sort: linear, stable, no allocation once `scratch`
/// has grown).
fn order(members: &mut [u32], scratch: &mut Vec<u32>, refs: &[ContactRef], homes: Homes) {
    if members.len() < 2 {
        // Most of the 24 colours are empty: no counts to clear.
        return;
    }
    const KEYS: usize = ContactRef::ORDER_KEYS;
    let key = |i: u32| {
        let r = &refs[i as usize];
        homes.of(r) * KEYS + r.order_key()
    };
    let mut start = [0usize; MAX_HOMES * KEYS + 1];
    for &i in members.iter() {
        start[key(i) + 1] += 1;
    }
    for k in 1..=homes.count * KEYS {
        start[k] += start[k - 1];
    }
    scratch.clear();
    scratch.resize(members.len(), 0);
    for &i in members.iter() {
        let k = key(i);
        scratch[start[k]] = i;
        start[k] += 1;
    }
    members.copy_from_slice(scratch);
}

/// Batches packed per task, at least.
const PACK_MIN_RANGE: u32 = 32;

/// `Span::list` of the constraints that fit no colour.
const SINGLES: u32 = COLORS as u32;

/// One batch's constraints: `len` members of `color_members[list]` (or of `singles` when
/// `list` is `SINGLES`) from `start`.
#[derive(Clone, Copy, Debug)]
struct Span {
    list: u32,
    start: u32,
    len: u32,
}

/// Exactly `used` batches, last step's storage reused (no zeroing: `pack` writes every field).
#[inline(always)]
fn grow_all<L: Lanes + Default>(batches: &mut Vec<WideContact<L>>, used: usize) {
    batches.truncate(used);
    while batches.len() < used {
        batches.push(WideContact::default());
    }
}

/// Packs the batches of `range`, each from its span of constraints, in place over last
/// step's storage: no zeroing, no copies.
#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `grow_all` sizes (see `dispatch!`)
fn pack_range_all<L: Lanes + Default>(
    batches: &mut Vec<WideContact<L>>,
    spans: &[Span],
    members: &[Vec<u32>],
    singles: &[u32],
    refs: &[ContactRef],
    sources: &Sources,
    range: Range<usize>,
) {
    for k in range {
        let s = spans[k];
        let list = if s.list == SINGLES {
            singles
        } else {
            &members[s.list as usize][..]
        };
        let lanes = &list[s.start as usize..(s.start + s.len) as usize];
        pack(&mut batches[k], lanes, refs, sources);
    }
}

/// Per-lane staging of a 3-vector field.
#[derive(Clone, Copy, Default)]
struct Stage3<A> {
    x: A,
    y: A,
    z: A,
}

impl<A: AsMut<[f32]>> Stage3<A> {
    #[inline(always)]
    fn set(&mut self, lane: usize, v: Vec3) {
        self.x.as_mut()[lane] = v.x;
        self.y.as_mut()[lane] = v.y;
        self.z.as_mut()[lane] = v.z;
    }
}

impl<A> Stage3<A> {
    #[inline(always)]
    fn load<L: Lanes<Floats = A>>(&self) -> V<L> {
        V {
            x: L::load(&self.x),
            y: L::load(&self.y),
            z: L::load(&self.z),
        }
    }
}

/// Raw input of a batch, staged lane by lane in the solver's orientation (static B) before it
/// is loaded into lanes; empty lanes stay zero.
struct Staging<L: Lanes> {
    /// ma, mb, radius_a, radius_b, static and dynamic friction, restitution, twist impulse,
    /// 1/point count, rigid (all-ones), rolling and torsion levers, size, own tangents
    /// (all-ones in lanes with locked linear axes).
    f: [L::Floats; 14],
    /// Normal, centres of mass of A and B, friction and rolling impulses on B (world), and
    /// the locked linear axes of A and B (1.0 locked, 0.0 free), and the two tangents of a
    /// lane with locks (`lock_tangents`).
    v: [Stage3<L::Floats>; 9],
    /// Per point: separation, normal impulse, active (all-ones).
    pf: [[L::Floats; 3]; MAXP],
    /// Per point: the point midway between the surfaces.
    pv: [Stage3<L::Floats>; MAXP],
}

impl<L: Lanes> Staging<L> {
    #[inline(always)]
    fn new() -> Self {
        Staging {
            f: [L::Floats::default(); 14],
            v: [Stage3::default(); 9],
            pf: [[L::Floats::default(); 3]; MAXP],
            pv: [Stage3::default(); MAXP],
        }
    }

    /// Lane `i` from the persistent contact of `r` (its manifold `r.child`).
    #[inline(always)]
    fn contact(&mut self, i: usize, r: &ContactRef, c: &Contact, s: &Sources) -> bool {
        let (manifold, impulses, patch) = c.child(r.child as usize);
        let (mut ca, mut cb) = (s.bodies.at(c.body_a).center, s.bodies.at(c.body_b).center);
        let (mut n, mut radius_a, mut radius_b, mut friction, mut rolling) =
            (manifold.normal, c.radius_a, c.radius_b, patch.tangent, patch.rolling);
        if r.swapped {
            std::mem::swap(&mut ca, &mut cb);
            std::mem::swap(&mut radius_a, &mut radius_b);
            n = -n;
            // The stored friction and rolling impulses act on the contact's B, here side A.
            friction = -friction;
            rolling = -rolling;
        }
        let count = manifold.count;
        let locked = self.lane(
            i,
            r,
            s,
            [radius_a, radius_b, c.static_friction, c.dynamic_friction],
            c.restitution,
        );
        if locked {
            self.lock_tangents(i, r, s, n);
        }
        self.f[7].as_mut()[i] = patch.twist;
        self.f[8].as_mut()[i] = 1.0 / count as f32;
        self.f[10].as_mut()[i] = c.rolling_resistance;
        self.f[11].as_mut()[i] = c.torsional_friction;
        self.f[12].as_mut()[i] = c.size;
        for (slot, x) in self.v.iter_mut().zip([n, ca, cb, friction, rolling]) {
            slot.set(i, x);
        }
        for (p, (mp, imp)) in manifold.points().iter().zip(impulses).enumerate() {
            for (slot, x) in self.pf[p].iter_mut().zip([mp.separation, imp.normal, on()]) {
                slot.as_mut()[i] = x;
            }
            self.pv[p].set(i, mp.point);
        }
        locked
    }

    /// Lane `i` from a contact generated this step (rods, cables, user callbacks): a single
    /// point, not persistent, solved rigidly.
    #[inline(always)]
    fn generated(&mut self, i: usize, r: &ContactRef, g: &GeneratedContact, s: &Sources) -> bool {
        let center = |b: u32| {
            if b == crate::dynamics::body::NONE {
                g.point
            } else {
                s.bodies.at(b).center
            }
        };
        let (mut ca, mut cb, mut n) = (center(g.body_a), center(g.body_b), g.normal);
        if r.swapped {
            std::mem::swap(&mut ca, &mut cb);
            n = -n;
        }
        let locked = self.lane(i, r, s, [0.0, 0.0, g.friction, g.friction], g.restitution);
        if locked {
            self.lock_tangents(i, r, s, n);
        }
        self.f[8].as_mut()[i] = 1.0;
        self.f[9].as_mut()[i] = on();
        self.f[12].as_mut()[i] = f32::MAX;
        for (slot, x) in self.v.iter_mut().zip([n, ca, cb]) {
            slot.set(i, x);
        }
        for (slot, x) in self.pf[0].iter_mut().zip([-g.penetration, 0.0, on()]) {
            slot.as_mut()[i] = x;
        }
        self.pv[0].set(i, g.point);
        locked
    }

    /// The inverse masses, locked linear axes, radii, friction coefficients and restitution
    /// of lane `i`. Returns whether either body has a locked linear axis.
    #[inline(always)]
    fn lane(&mut self, i: usize, r: &ContactRef, s: &Sources, [ra, rb, fs, fd]: [f32; 4], e: f32) -> bool {
        let (sa, sb) = (&s.states[r.a as usize], &s.states[r.b as usize]);
        for (slot, x) in self.f.iter_mut().zip([sa.inv_mass, sb.inv_mass, ra, rb, fs, fd, e]) {
            slot.as_mut()[i] = x;
        }
        (sa.locks | sb.locks) & 7 != 0
    }

    /// The locked linear axes of lane `i`'s bodies, and friction tangents that diagonalise the
    /// linear part of the friction rows' effective mass, `F = m_A·diag(free_A) +
    /// m_B·diag(free_B)` in the contact plane (the default basis for a normal nearly
    /// perpendicular to a locked axis has one tangent a little off that axis: its row's effective
    /// mass was near zero while it still coupled to the free tangent, and the friction cone
    /// clamped the free tangent's impulse by the other's huge one).
    #[inline(always)]
    fn lock_tangents(&mut self, i: usize, r: &ContactRef, s: &Sources, n: Vec3) {
        let (sa, sb) = (&s.states[r.a as usize], &s.states[r.b as usize]);
        let axes = |l: u8| Vec3::new((l & 1) as f32, ((l >> 1) & 1) as f32, ((l >> 2) & 1) as f32);
        let (la, lb) = (axes(sa.locks), axes(sb.locks));
        self.v[5].set(i, la);
        self.v[6].set(i, lb);
        let f = sa.inv_mass * (Vec3::ONE - la) + sb.inv_mass * (Vec3::ONE - lb);
        let (t1, t2) = crate::math::orthonormal_basis(n);
        let (a, b, c) = (t1.dot(f * t1), t1.dot(f * t2), t2.dot(f * t2));
        let phi = 0.5 * (2.0 * b).atan2(a - c);
        let (sin, cos) = phi.sin_cos();
        self.v[7].set(i, t1 * cos + t2 * sin);
        self.v[8].set(i, t2 * cos - t1 * sin);
        self.f[13].as_mut()[i] = on();
    }
}

/// All-ones: a lane mask that is set.
#[inline(always)]
fn on() -> f32 {
    f32::from_bits(u32::MAX)
}

/// Tangential speed (m/s) below which a contact patch starts a step sticking.
const STICK_SPEED: f32 = 0.01;

/// Two unit tangents completing the unit normal `n` to a right-handed basis (Duff et al. 2017,
/// branch-free): `math::orthonormal_basis` lane by lane.
#[inline(always)]
fn basis<L: Lanes>(n: V<L>) -> (V<L>, V<L>) {
    let one = L::one();
    let sign = L::select(n.z.ge(L::zero()), one, -one);
    let a = -(one / (sign + n.z));
    let b = n.x * n.y * a;
    (
        V {
            x: one + sign * n.x * n.x * a,
            y: sign * b,
            z: -(sign * n.x),
        },
        V {
            x: b,
            y: sign + n.y * n.y * a,
            z: -n.y,
        },
    )
}

/// Packs up to `L::N` contacts into `w`, setting every field the passes read before they
/// write it (the storage is reused from earlier steps). Each lane's input is staged from its
/// contact; the constraint is then built in lanes: the tangent basis, the arms of the points
/// and of the patch centroid at the start of the step (kept as offsets from the shapes' core
/// points), the approach speeds for restitution, the twist lever (mean distance of the points
/// from the centroid) and whether the patch starts the step sliding.
#[inline(always)]
fn pack<L: Lanes>(w: &mut WideContact<L>, lanes: &[u32], refs: &[ContactRef], sources: &Sources) {
    let mut st = Staging::<L>::new();
    let mut src = L::Indices::default();
    src.as_mut().fill(EMPTY);
    (w.a, w.b, w.src, w.count, w.has_restitution, w.locked, w.shared) = (
        L::Indices::default(),
        L::Indices::default(),
        src,
        1,
        false,
        false,
        false,
    );
    // Batches hold one kind (see `pack_all`), so the first lane speaks for all.
    w.spin = refs[lanes[0] as usize].spins();
    for (i, &k) in lanes.iter().enumerate() {
        let r = &refs[k as usize];
        w.a.as_mut()[i] = r.a;
        w.b.as_mut()[i] = r.b;
        w.src.as_mut()[i] = k;
        w.shared |= r.shared();
        match r.contact() {
            Some(ci) => {
                let c = sources.contacts.at(ci);
                w.count = w.count.max(c.child(r.child as usize).0.count);
                w.has_restitution |= c.restitution > 0.0;
                w.locked |= st.contact(i, r, c, sources);
            }
            None => {
                let g = &sources.generated[r.generated_index()];
                w.has_restitution |= g.restitution > 0.0;
                w.locked |= st.generated(i, r, g, sources);
            }
        }
    }
    // Batches run as one-point or four-point manifolds (missing points inactive).
    w.count = if w.count <= 1 { 1 } else { MAXP };
    w.b_static = w.b.as_ref().iter().all(|&b| b == 0);
    if w.count == 1 {
        build::<L, 1>(w, &st, sources.vel);
    } else {
        build::<L, MAXP>(w, &st, sources.vel);
    }
}

/// The linear part of a row's effective mass along the unit direction `d`: `d·M⁻¹·d` for each
/// body with the per-axis inverse mass `m·(1 − lock)` (`lock` 1.0 on locked axes), written
/// `m·(1 − lock·d²)` so that a body without locks gives `m` bit for bit (`lock·d²` is +0).
#[inline(always)]
fn linear_term<L: Lanes>(ma: L, mb: L, lock_a: V<L>, lock_b: V<L>, d: V<L>) -> L {
    let one = L::one();
    let d2 = V {
        x: d.x * d.x,
        y: d.y * d.y,
        z: d.z * d.z,
    };
    ma * (one - lock_a.dot(d2)) + mb * (one - lock_b.dot(d2))
}

/// `v` along the axes a body may move along: `v ⊙ free` in a batch with locked linear axes,
/// `v` itself otherwise (bit for bit the same for a body without locks: `free` is all ones).
#[inline(always)]
fn on_free<L: Lanes>(locked: bool, v: V<L>, free: V<L>) -> V<L> {
    if locked {
        V {
            x: v.x * free.x,
            y: v.y * free.y,
            z: v.z * free.z,
        }
    } else {
        v
    }
}

/// Velocity of a body's material point at arm `r`.
#[inline(always)]
fn point_velocity<L: Lanes>(v: V<L>, w: V<L>, r: V<L>) -> V<L> {
    v + w.cross(r)
}

/// Builds the constraint of a packed batch of `N`-point manifolds from its staged input.
#[inline(always)]
fn build<L: Lanes, const N: usize>(w: &mut WideContact<L>, st: &Staging<L>, vel: &[Velocity]) {
    let zero = L::zero();
    let [ma, mb, radius_a, radius_b, fs, fd, e, twist, inv_count, rigid, rolling, torsion, size, own] =
        load_all::<L, 14>(&st.f);
    w.size = size;
    let light_tol = L::splat(LIGHT_REFRESH_MOTION).min(size * L::splat(LIGHT_REFRESH_FRACTION));
    w.light_tol2 = light_tol * light_tol;
    let [n, ca, cb, friction] = [0, 1, 2, 3].map(|i| st.v[i].load::<L>());
    (
        w.ma,
        w.mb,
        w.static_friction,
        w.dynamic_friction,
        w.restitution,
        w.rigid,
    ) = (ma, mb, fs, fd, e, rigid);
    let (mut t1, mut t2) = basis(n);
    if w.locked {
        t1 = V::select(own, st.v[7].load::<L>(), t1);
        t2 = V::select(own, st.v[8].load::<L>(), t2);
    }
    (w.normal, w.tangents) = (n, [t1, t2]);
    if w.locked {
        let [lock_a, lock_b] = [5, 6].map(|i| st.v[i].load::<L>());
        let one = V {
            x: L::one(),
            y: L::one(),
            z: L::one(),
        };
        (w.free_a, w.free_b) = (one - lock_a, one - lock_b);
        w.m_normal = linear_term(ma, mb, lock_a, lock_b, n);
        w.m_tangent = [t1, t2].map(|t| linear_term(ma, mb, lock_a, lock_b, t));
    } else {
        let m = ma + mb;
        (w.m_normal, w.m_tangent) = (m, [m, m]);
    }
    // Contact points sit on the shapes' rounded surfaces, `radius` out from the core points.
    let (oa, ob) = (n.scale(radius_a), n.scale(-radius_b));
    let (round_a, round_b) = (radius_a.gt(zero), radius_b.gt(zero));
    let half = L::splat(0.5);
    w.at_b = L::select(
        round_a,
        L::select(round_b, half, zero),
        L::select(round_b, L::one(), half),
    );
    (w.oa, w.ob) = (oa, ob);
    let (va, wa) = gather(vel, &w.a);
    let (vb, wb) = gather(vel, &w.b);
    let mut points = [V::zero(); MAXP];
    let mut centroid = V::zero();
    for (p, wp) in w.points[..N].iter_mut().enumerate() {
        let [separation, impulse, active] = load_all::<L, 3>(&st.pf[p]);
        let point = st.pv[p].load::<L>();
        points[p] = point;
        centroid = centroid + point;
        let (ra, rb) = (point - ca, point - cb);
        (wp.separation0, wp.active, wp.impulse, wp.max_impulse) = (separation, active, impulse, zero);
        wp.relative_velocity = L::select(
            active,
            (point_velocity(vb, wb, rb) - point_velocity(va, wa, ra)).dot(n),
            zero,
        );
        wp.ca0 = V::select(active, ra - oa, V::zero());
        wp.cb0 = V::select(active, rb - ob, V::zero());
    }
    let centroid = centroid.scale(inv_count);
    let mut twist_radius = zero;
    if N > 1 {
        for (p, point) in points.iter().enumerate() {
            let d = (*point - centroid).length_squared().sqrt();
            twist_radius = twist_radius + L::select(w.points[p].active, d, zero);
        }
        twist_radius = twist_radius * inv_count;
    }
    let (ra, rb) = (centroid - ca, centroid - cb);
    let dv = point_velocity(vb, wb, rb) - point_velocity(va, wa, ra);
    let vt = dv - n.scale(dv.dot(n));
    let f = &mut w.friction;
    (f.ca0, f.cb0, f.twist_radius, f.twist_impulse) = (ra - oa, rb - ob, twist_radius, twist);
    f.tangent_impulse = [friction.dot(t1), friction.dot(t2)];
    if w.spin {
        let roll = st.v[4].load::<L>();
        (f.rolling, f.torsion) = (rolling, torsion);
        f.rolling_impulse = [roll.dot(t1), roll.dot(t2)];
    }
    f.sliding = vt.length_squared().gt(L::splat(STICK_SPEED * STICK_SPEED));
}

/// The lanes' bodies' motion so far: translation, rotation and world inverse inertia.
#[inline(always)]
fn gather_states<L: Lanes>(states: &[BodyState], idx: &L::Indices) -> (V<L>, M<L>, M<L>) {
    let dp = V::from_columns(state_rows(states, idx, 0));
    let [x, y, z, w] = state_rows(states, idx, 1);
    (
        dp,
        rotation(x, y, z, w),
        M {
            c0: V::from_columns(state_rows(states, idx, 2)),
            c1: V::from_columns(state_rows(states, idx, 3)),
            c2: V::from_columns(state_rows(states, idx, 4)),
        },
    )
}

/// Row `r` of the lanes' body states, as four columns. (Helpers on the passes' paths are
/// functions marked `#[inline(always)]`, never closures: a closure is compiled apart, without
/// the AVX2 of the eight-lane entry points, and would call every intrinsic out of line.)
#[inline(always)]
fn state_rows<L: Lanes>(states: &[BodyState], idx: &L::Indices, r: usize) -> [L; 4] {
    let idx = idx.as_ref();
    L::gather(|i| &states[idx[i] as usize].rows[r])
}

/// Loads `K` staged fields.
#[inline(always)]
fn load_all<L: Lanes, const K: usize>(a: &[L::Floats; K]) -> [L; K] {
    let mut out = [L::zero(); K];
    for (o, x) in out.iter_mut().zip(a) {
        *o = L::load(x);
    }
    out
}

/// The rotation matrices of unit quaternions.
#[inline(always)]
fn rotation<L: Lanes>(x: L, y: L, z: L, w: L) -> M<L> {
    let (x2, y2, z2) = (x + x, y + y, z + z);
    let (xx, xy, xz) = (x * x2, x * y2, x * z2);
    let (yy, yz, zz) = (y * y2, y * z2, z * z2);
    let (wx, wy, wz) = (w * x2, w * y2, w * z2);
    let one = L::one();
    M {
        c0: V {
            x: one - (yy + zz),
            y: xy + wz,
            z: xz - wy,
        },
        c1: V {
            x: xy - wz,
            y: one - (xx + zz),
            z: yz + wx,
        },
        c2: V {
            x: xz + wy,
            y: yz - wx,
            z: one - (xx + yy),
        },
    }
}

#[inline(always)]
pub(crate) fn gather<L: Lanes>(vel: &[Velocity], idx: &L::Indices) -> (V<L>, V<L>) {
    let idx = idx.as_ref();
    (
        V::from_columns(L::gather(|i| &vel[idx[i] as usize].rows()[0])),
        V::from_columns(L::gather(|i| &vel[idx[i] as usize].rows()[1])),
    )
}

/// Writes the lanes back. Lanes of static (index 0) and kinematic bodies carry exactly the
/// velocity they gathered (their inverse mass and inertia are zero), and the colouring keeps
/// the dynamic bodies of a batch distinct, so writing every lane is safe.
#[inline(always)]
pub(crate) fn scatter<L: Lanes>(vel: &mut [Velocity], idx: &L::Indices, v: V<L>, w: V<L>) {
    let zero = L::zero();
    let vr = L::scatter([v.x, v.y, v.z, zero]);
    let wr = L::scatter([w.x, w.y, w.z, zero]);
    for ((&i, v), w) in idx.as_ref().iter().zip(vr.as_ref()).zip(wr.as_ref()) {
        let rows = vel[i as usize].rows_mut();
        rows[0] = *v;
        rows[1] = *w;
    }
}

#[inline(always)]
fn safe_inverse<L: Lanes>(k: L) -> L {
    let ok = k.gt(L::zero());
    L::select(ok, L::one() / L::select(ok, k, L::one()), L::zero())
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
/// Inverts each lane's K (symmetric positive definite after regularisation, identity rows
/// for missing points) by Cholesky: K = L Lᵀ, K⁻¹ = L⁻ᵀ L⁻¹.
#[inline(always)]
fn invert_spd<L: Lanes>(k: &[[L; MAXP]; MAXP], n: usize, out: &mut [[L; MAXP]; MAXP]) {
    let mut l = [[L::zero(); MAXP]; MAXP];
    let mut inv_diag = [L::zero(); MAXP];
    for j in 0..n {
        let mut d = k[j][j];
        for p in 0..j {
            d = d - l[j][p] * l[j][p];
        }
        let d = d.max(L::splat(1e-20)).sqrt();
        l[j][j] = d;
        inv_diag[j] = L::splat(1.0) / d;
        for i in j + 1..n {
            let mut s = k[i][j];
            for p in 0..j {
                s = s - l[i][p] * l[j][p];
            }
            l[i][j] = s * inv_diag[j];
        }
    }
    // L⁻¹ by forward substitution.
    let mut li = [[L::zero(); MAXP]; MAXP];
    for i in 0..n {
        li[i][i] = inv_diag[i];
        for j in 0..i {
            let mut s = L::zero();
            for p in j..i {
                s = s + l[i][p] * li[p][j];
            }
            li[i][j] = -(s * inv_diag[i]);
        }
    }
    for i in 0..n {
        for j in 0..=i {
            let mut s = L::zero();
            for p in i..n {
                s = s + li[p][i] * li[p][j];
            }
            out[i][j] = s;
            out[j][i] = s;
        }
    }
}

/// Offsets of the contact points from the core points, and where between them forces act.
struct Geometry<L> {
    oa: V<L>,
    ob: V<L>,
    at_b: L,
}

/// Current lever arms and the gap between the two bodies' contact points. Core points (box
/// vertices, sphere centres, capsule segment points) turn with their bodies; each contact
/// point keeps its offset along the normal. Both arms reach one point (`at_b` of the way from
/// A's contact point to B's), so equal and opposite impulses conserve angular momentum.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn arms<L: Lanes>(
    ca0: V<L>,
    cb0: V<L>,
    g: &Geometry<L>,
    dpa: V<L>,
    dpb: V<L>,
    rot_a: &M<L>,
    rot_b: &M<L>,
) -> (V<L>, V<L>, V<L>) {
    let pra = rot_a.mul_vec(ca0) + g.oa;
    let prb = rot_b.mul_vec(cb0) + g.ob;
    let gap = ((ca0 + g.oa) - (cb0 + g.ob)) + (dpb - dpa) + (prb - pra);
    (
        pra.add_scaled(gap, g.at_b),
        prb.add_scaled(gap, g.at_b - L::splat(1.0)),
        gap,
    )
}

/// Relative motion (m; rad counts as m of arm) since the start of the step below which a
/// constraint keeps the arms of its last full refresh and updates separations to first order
/// (a tenth of the smaller shape's size for shapes under a centimetre).
const LIGHT_REFRESH_MOTION: f32 = 1.0e-3;
/// For small shapes the threshold is at most this fraction of the smaller shape's size.
const LIGHT_REFRESH_FRACTION: f32 = 0.1;

pub fn refresh(states: &[BodyState], batches: &mut Batches, first: bool) {
    dispatch!(&mut batches.sets, refresh_all(states, first))
}

/// Brings the constraints up to date with the motion so far. On the first sub-step (`first`):
/// arms, Jacobians, effective masses, K and K⁻¹, separations. Later, a constraint whose bodies
/// moved less than `LIGHT_REFRESH_MOTION` relative to each other only updates separations
/// (`s₀ + n·Δp + θ_B·(r_B×n) − θ_A·(r_A×n)`, exact to first order); others recompute their
/// arms, so fast contacts keep impulses at one point and angular momentum exact. The choice is
/// made lane by lane.
#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `pack_all` grows (see `dispatch!`)
fn refresh_all<L: Lanes>(batches: &mut Vec<WideContact<L>>, states: &[BodyState], first: bool) {
    for w in batches.iter_mut() {
        match (w.count == 1, w.b_static) {
            (true, true) => refresh_batch::<L, 1, true>(states, w, first),
            (true, false) => refresh_batch::<L, 1, false>(states, w, first),
            (false, true) => refresh_batch::<L, MAXP, true>(states, w, first),
            (false, false) => refresh_batch::<L, MAXP, false>(states, w, first),
        }
    }
}

/// The lanes whose bodies barely moved relative to each other, with their first-order
/// separations written; the other lanes' separations are left alone.
#[inline(always)]
fn light_refresh<L: Lanes, const N: usize, const SB: bool>(states: &[BodyState], w: &mut WideContact<L>) -> L {
    let (dpa, tha) = (
        V::from_columns(state_rows::<L>(states, &w.a, 0)),
        V::from_columns(state_rows::<L>(states, &w.a, 5)),
    );
    let (dpb, thb) = if SB {
        (V::zero(), V::zero())
    } else {
        (
            V::from_columns(state_rows::<L>(states, &w.b, 0)),
            V::from_columns(state_rows::<L>(states, &w.b, 5)),
        )
    };
    let d = dpb - dpa;
    let tol2 = w.light_tol2;
    let light = d
        .length_squared()
        .le(tol2)
        .and((tha.length_squared() + thb.length_squared()).le(tol2));
    if light.bits() == 0 {
        return light;
    }
    let nd = w.normal.dot(d);
    for p in w.points[..N].iter_mut() {
        let mut s = p.separation0 + nd - tha.dot(p.rna);
        if !SB {
            s = s + thb.dot(p.rnb);
        }
        p.separation = L::select(light, s, p.separation);
    }
    light
}

/// `refresh` for one batch of `N`-point manifolds (1, or 4 with missing points inactive).
/// `block`: the first sub-step, which also builds K and K⁻¹.
#[inline(always)]
fn refresh_batch<L: Lanes, const N: usize, const SB: bool>(states: &[BodyState], w: &mut WideContact<L>, block: bool) {
    // Lanes that keep their arms (`light_refresh` updated their separations).
    let keep = if block {
        L::zero()
    } else {
        light_refresh::<L, N, SB>(states, w)
    };
    if keep.bits() == L::ALL {
        return;
    }
    let (dpa, rot_a, ia) = gather_states(states, &w.a);
    let (dpb, rot_b, ib) = if SB {
        (V::zero(), M::identity(), M::zero())
    } else {
        gather_states(states, &w.b)
    };
    let n = w.normal;
    let m = w.m_normal;
    let g = Geometry {
        oa: w.oa,
        ob: w.ob,
        at_b: w.at_b,
    };
    for p in w.points[..N].iter_mut() {
        let (ra, rb, gap) = arms(p.ca0, p.cb0, &g, dpa, dpb, &rot_a, &rot_b);
        p.separation = L::select(keep, p.separation, p.separation0 + gap.dot(n));
        p.rna = V::select(keep, p.rna, ra.cross(n));
        p.ia = V::select(keep, p.ia, ia.mul_vec(p.rna));
        let mut k = m + p.rna.dot(p.ia);
        if !SB {
            p.rnb = V::select(keep, p.rnb, rb.cross(n));
            p.ib = V::select(keep, p.ib, ib.mul_vec(p.rnb));
            k = k + p.rnb.dot(p.ib);
        }
        p.normal_mass = L::select(keep, p.normal_mass, L::select(p.active, safe_inverse(k), L::zero()));
    }
    if block && N > 1 {
        let one = L::one();
        for i in 0..N {
            for j in i..N {
                let (pi, pj) = (&w.points[i], &w.points[j]);
                let both = pi.active.and(pj.active);
                let mut kij = m + pi.rna.dot(pj.ia);
                if !SB {
                    kij = kij + pi.rnb.dot(pj.ib);
                }
                if i == j {
                    w.k[i][i] = L::select(both, kij, one);
                } else {
                    let v = L::select(both, kij, L::zero());
                    w.k[i][j] = v;
                    w.k[j][i] = v;
                }
            }
        }
        let mut reg = w.k;
        for (i, row) in reg.iter_mut().enumerate().take(N) {
            row[i] = row[i] * L::splat(1.0 + BLOCK_REGULARIZATION);
        }
        invert_spd(&reg, N, &mut w.k_inv);
    }
    let f = &mut w.friction;
    let (ra, rb, _) = arms(f.ca0, f.cb0, &g, dpa, dpb, &rot_a, &rot_b);
    for k in 0..2 {
        let t = w.tangents[k];
        f.rta[k] = V::select(keep, f.rta[k], ra.cross(t));
        f.ita[k] = V::select(keep, f.ita[k], ia.mul_vec(f.rta[k]));
        let mut km = w.m_tangent[k] + f.rta[k].dot(f.ita[k]);
        if !SB {
            f.rtb[k] = V::select(keep, f.rtb[k], rb.cross(t));
            f.itb[k] = V::select(keep, f.itb[k], ib.mul_vec(f.rtb[k]));
            km = km + f.rtb[k].dot(f.itb[k]);
        }
        f.tangent_mass[k] = L::select(keep, f.tangent_mass[k], safe_inverse(km));
    }
    // One-point manifolds have no twist lever (the radius is zero) unless they have
    // torsional friction.
    if N > 1 || w.spin {
        f.ina = V::select(keep, f.ina, ia.mul_vec(n));
        let mut kt = n.dot(f.ina);
        if !SB {
            f.inb = V::select(keep, f.inb, ib.mul_vec(n));
            kt = kt + n.dot(f.inb);
        }
        f.twist_mass = L::select(keep, f.twist_mass, safe_inverse(kt));
    }
    if w.spin {
        // Rolling rows: relative angular velocity about the two tangents.
        let mut k = [L::zero(); 3];
        for t in 0..2 {
            let tangent = w.tangents[t];
            f.ira[t] = V::select(keep, f.ira[t], ia.mul_vec(tangent));
            if !SB {
                f.irb[t] = V::select(keep, f.irb[t], ib.mul_vec(tangent));
            }
        }
        for (slot, (i, j)) in k.iter_mut().zip([(0, 0), (0, 1), (1, 1)]) {
            *slot = w.tangents[i].dot(f.ira[j]);
            if !SB {
                *slot = *slot + w.tangents[i].dot(f.irb[j]);
            }
        }
        // Inverted at unit scale: a body of 1e14 kg has angular entries near 1e-21, whose
        // determinant (1e-42) is below f32's normal range, and its inverse overflowed to
        // infinity (then NaN in the sweep; found by the API fuzzer).
        let s = safe_inverse(k[0] + k[2]);
        let (k0, k1, k2) = (k[0] * s, k[1] * s, k[2] * s);
        let inv_det = safe_inverse(k0 * k2 - k1 * k1) * s;
        let mass = [k2 * inv_det, -(k1 * inv_det), k0 * inv_det];
        for (m, x) in f.rolling_mass.iter_mut().zip(mass) {
            *m = L::select(keep, *m, x);
        }
    }
}

/// Sets each batch's biased-sweep coefficients for this step: the soft contact's (the static
/// variant when a body has infinite mass), or for rigid lanes the full response, no leak and a
/// fast push-out (a fraction of the sub-step rate; the relax sweep removes the push velocity)
/// so a rod keeps its length while it swings.
pub fn set_softness(batches: &mut Batches, soft: &SoftSweep, inv_h: f32) {
    dispatch!(&mut batches.sets, set_softness_all(soft, inv_h))
}

#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `pack_all` grows (see `dispatch!`)
fn set_softness_all<L: Lanes>(batches: &mut Vec<WideContact<L>>, soft: &SoftSweep, inv_h: f32) {
    let (zero, one) = (L::zero(), L::one());
    for w in batches.iter_mut() {
        let dynamic = w.ma.gt(zero).and(w.mb.gt(zero));
        let (d, s) = (&soft.soft, &soft.soft_static);
        let rate = L::select(dynamic, L::splat(d.bias_rate), L::splat(s.bias_rate));
        let ms = L::select(dynamic, L::splat(d.mass_scale), L::splat(s.mass_scale));
        let is = L::select(dynamic, L::splat(d.impulse_scale), L::splat(s.impulse_scale));
        w.soft_rate = L::select(w.rigid, L::splat(RIGID_PUSH * inv_h), rate);
        w.soft_ms = L::select(w.rigid, one, ms);
        w.soft_is = L::select(w.rigid, zero, is);
        w.soft_keep = (one - w.soft_is) / w.soft_ms;
        w.slop = L::splat(soft.slop).min(w.size * L::splat(SLOP_FRACTION));
    }
}

/// Largest allowed overlap as a fraction of the smaller shape's size (`Contact::size`): a
/// 1 cm box keeps a tenth of a millimetre, under the 0.2 mm `linear_slop` of larger ones.
const SLOP_FRACTION: f32 = 0.02;

/// Relative velocity along `d` with angular Jacobians `ja`, `jb`.
#[inline(always)]
fn rel<L: Lanes, const SB: bool>(va: V<L>, wa: V<L>, vb: V<L>, wb: V<L>, d: V<L>, ja: V<L>, jb: V<L>) -> L {
    if SB {
        -(d.dot(va) + wa.dot(ja))
    } else {
        d.dot(vb - va) + wb.dot(jb) - wa.dot(ja)
    }
}

/// `refresh`, then the warm start (the last step's impulses applied to the velocities), batch
/// by batch in one pass over the constraints. Refreshing reads positions only, so this is
/// the same as refreshing every batch and then warm starting every batch.
pub fn refresh_warm_start(states: &[BodyState], vel: &mut [Velocity], batches: &mut Batches, first: bool) {
    let all = 0..batches.len();
    dispatch!(&mut batches.sets, refresh_warm_start_all(states, vel, first, all))
}

/// `refresh_warm_start` over the batches of `range` only.
pub fn refresh_warm_start_range(
    states: &[BodyState],
    vel: &mut [Velocity],
    batches: &mut Batches,
    first: bool,
    range: Range<usize>,
) {
    dispatch!(&mut batches.sets, refresh_warm_start_all(states, vel, first, range))
}

#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `pack_all` grows (see `dispatch!`)
fn refresh_warm_start_all<L: Lanes>(
    batches: &mut Vec<WideContact<L>>,
    states: &[BodyState],
    vel: &mut [Velocity],
    first: bool,
    range: Range<usize>,
) {
    for w in batches[range].iter_mut() {
        match (w.count == 1, w.b_static) {
            (true, true) => refresh_warm_start_batch::<L, 1, true>(states, vel, w, first),
            (true, false) => refresh_warm_start_batch::<L, 1, false>(states, vel, w, first),
            (false, true) => refresh_warm_start_batch::<L, MAXP, true>(states, vel, w, first),
            (false, false) => refresh_warm_start_batch::<L, MAXP, false>(states, vel, w, first),
        }
    }
}

#[inline(always)]
fn refresh_warm_start_batch<L: Lanes, const N: usize, const SB: bool>(
    states: &[BodyState],
    vel: &mut [Velocity],
    w: &mut WideContact<L>,
    first: bool,
) {
    refresh_batch::<L, N, SB>(states, w, first);
    warm_start_batch::<L, N, SB>(vel, w);
}

#[inline(always)]
fn warm_start_batch<L: Lanes, const N: usize, const SB: bool>(vel: &mut [Velocity], w: &WideContact<L>) {
    let (mut va, mut wa) = gather(vel, &w.a);
    let mut lin = w.normal.scale(sum_impulses::<L, N>(w));
    let f = &w.friction;
    let (mut ang_a, mut ang_b) = if N > 1 || w.spin {
        (f.ina.scale(f.twist_impulse), f.inb.scale(f.twist_impulse))
    } else {
        (V::zero(), V::zero())
    };
    if w.spin {
        for k in 0..2 {
            ang_a = ang_a.add_scaled(f.ira[k], f.rolling_impulse[k]);
            if !SB {
                ang_b = ang_b.add_scaled(f.irb[k], f.rolling_impulse[k]);
            }
        }
    }
    for p in &w.points[..N] {
        ang_a = ang_a.add_scaled(p.ia, p.impulse);
        if !SB {
            ang_b = ang_b.add_scaled(p.ib, p.impulse);
        }
    }
    for k in 0..2 {
        lin = lin.add_scaled(w.tangents[k], f.tangent_impulse[k]);
        ang_a = ang_a.add_scaled(f.ita[k], f.tangent_impulse[k]);
        if !SB {
            ang_b = ang_b.add_scaled(f.itb[k], f.tangent_impulse[k]);
        }
    }
    va = va.add_scaled(on_free(w.locked, lin, w.free_a), -w.ma);
    wa = wa - ang_a;
    scatter(vel, &w.a, va, wa);
    if !SB {
        let (mut vb, mut wb) = gather(vel, &w.b);
        vb = vb.add_scaled(on_free(w.locked, lin, w.free_b), w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.b, vb, wb);
    }
}

#[inline(always)]
fn sum_impulses<L: Lanes, const N: usize>(w: &WideContact<L>) -> L {
    w.points[..N].iter().fold(L::zero(), |s, p| s + p.impulse)
}

/// One sweep over real velocities: block-solved normal impulses (speculative points may close
/// their gap within the sub-step and no more), then patch friction.
/// Soft-constraint coefficients of a biased sweep (Box2D v3's soft step): the push-out rate,
/// and how much of the rigid response and of the accumulated impulse each update keeps. The
/// leak of accumulated impulse is what damps a deep stack's oscillations.
#[derive(Clone, Copy, Debug)]
pub struct SoftSweep {
    pub soft: crate::dynamics::solver::Softness,
    /// Softness of contacts with a static or kinematic body (stiffer).
    pub soft_static: crate::dynamics::solver::Softness,
    pub max_push: f32,
    pub slop: f32,
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
/// One sweep: soft and biased (`Some`), or rigid without bias (`None`, the relax sweep).
/// Speculative points (positive separation) may close their gap within the sub-step, no more.
pub fn solve(vel: &mut [Velocity], batches: &mut Batches, inv_h: f32, forward: bool, bias: Option<&SoftSweep>) {
    let all = 0..batches.len();
    dispatch!(&mut batches.sets, solve_all(vel, inv_h, forward, bias, all))
}

/// `solve` over the batches of `range` only.
pub fn solve_range(
    vel: &mut [Velocity],
    batches: &mut Batches,
    inv_h: f32,
    forward: bool,
    bias: Option<&SoftSweep>,
    range: Range<usize>,
) {
    dispatch!(&mut batches.sets, solve_all(vel, inv_h, forward, bias, range))
}

#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `pack_all` grows (see `dispatch!`)
fn solve_all<L: Lanes>(
    batches: &mut Vec<WideContact<L>>,
    vel: &mut [Velocity],
    inv_h: f32,
    forward: bool,
    bias: Option<&SoftSweep>,
    range: Range<usize>,
) {
    for w in batches[range].iter_mut() {
        match (w.count == 1, w.b_static) {
            (true, true) => solve_batch::<L, 1, true>(vel, w, inv_h, forward, bias),
            (true, false) => solve_batch::<L, 1, false>(vel, w, inv_h, forward, bias),
            (false, true) => solve_batch::<L, MAXP, true>(vel, w, inv_h, forward, bias),
            (false, false) => solve_batch::<L, MAXP, false>(vel, w, inv_h, forward, bias),
        }
    }
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
#[inline(always)]
fn solve_batch<L: Lanes, const N: usize, const SB: bool>(
    vel: &mut [Velocity],
    w: &mut WideContact<L>,
    inv_h: f32,
    forward: bool,
    bias: Option<&SoftSweep>,
) {
    let zero = L::zero();
    let one = L::splat(1.0);
    let inv_h = L::splat(inv_h);
    let (mut va, mut wa) = gather(vel, &w.a);
    // A static B has no velocity and never moves.
    let (mut vb, mut wb) = if SB { (V::zero(), V::zero()) } else { gather(vel, &w.b) };
    let n = w.normal;
    // Per lane: the biased sweep's coefficients (see `set_softness`), or rigid without bias
    // for the relax sweep.
    let (rate, ms, is, keep, max_push, slop) = match bias {
        Some(b) => (
            w.soft_rate,
            w.soft_ms,
            w.soft_is,
            w.soft_keep,
            L::splat(-b.max_push),
            w.slop,
        ),
        None => (zero, one, zero, one, zero, zero),
    };
    let mut rhs = [zero; MAXP];
    let mut msp = [one; MAXP];
    let mut isp = [zero; MAXP];
    let mut kp = [one; MAXP];
    for i in 0..N {
        let p = &w.points[i];
        let spec = p.separation.gt(zero);
        let push = (rate * (p.separation + slop).min(zero)).max(max_push);
        let b = L::select(spec, p.separation * inv_h, push);
        msp[i] = L::select(spec, one, ms);
        isp[i] = L::select(spec, zero, is);
        kp[i] = L::select(spec, one, keep);
        let v = rel::<L, SB>(va, wa, vb, wb, n, p.rna, p.rnb) + b;
        rhs[i] = L::select(p.active, v, zero);
    }
    // Solve K e = −rhs for e ≥ −(1 − is)λ/ms, then Δλ = ms·e − is·λ (soft update).
    // A batch touching without load, not approaching and without friction (side faces of
    // neighbours) would change nothing: every impulse is zero and stays zero.
    let mut idle = L::splat(f32::from_bits(u32::MAX));
    for (p, r) in w.points[..N].iter().zip(&rhs) {
        idle = idle.and(p.impulse.le(zero)).and(r.ge(zero));
    }
    if idle.bits() == L::ALL {
        let f = &w.friction;
        let still = f.tangent_impulse[0].ge(zero).and(f.tangent_impulse[0].le(zero));
        let still = still
            .and(f.tangent_impulse[1].ge(zero))
            .and(f.tangent_impulse[1].le(zero));
        let mut still = still.and(f.twist_impulse.ge(zero)).and(f.twist_impulse.le(zero));
        if w.spin {
            for r in f.rolling_impulse {
                still = still.and(r.ge(zero)).and(r.le(zero));
            }
        }
        if still.bits() == L::ALL {
            return;
        }
    }
    let mut delta = [zero; MAXP];
    if N == 1 {
        let p = &w.points[0];
        let new = (p.impulse - msp[0] * p.normal_mass * rhs[0] - isp[0] * p.impulse).max(zero);
        delta[0] = new - p.impulse;
    } else {
        // Idle lanes (see above) need nothing. Exact solution with every point pushing: K e = −rhs, Δλ = ms·e − is·λ. (A clamped
        // exact solution is no good start: K of four coplanar points is nearly singular and
        // its exact solution may hold large self-cancelling parts.)
        let mut ok = L::splat(f32::from_bits(u32::MAX));
        let mut lower = [zero; MAXP];
        for i in 0..N {
            let mut d = zero;
            for j in 0..N {
                d = d - w.k_inv[i][j] * rhs[j];
            }
            let p = &w.points[i];
            // e may not go below this, or the point would pull.
            lower[i] = -(kp[i] * p.impulse);
            let e = L::select(idle, zero, d);
            ok = ok.and(e.ge(lower[i]));
            delta[i] = msp[i] * e - isp[i] * p.impulse;
        }
        if ok.bits() != L::ALL {
            // Some lane has a point that would pull: projected Gauss–Seidel on K there.
            let mut e = [zero; MAXP];
            for it in 0..BLOCK_ITERATIONS {
                for s in 0..N {
                    let i = if forward ^ (it % 2 == 1) { s } else { N - 1 - s };
                    let mut r = rhs[i];
                    for j in 0..N {
                        r = r + w.k[i][j] * e[j];
                    }
                    let p = &w.points[i];
                    e[i] = L::select(p.active, (e[i] - p.normal_mass * r).max(lower[i]), zero);
                }
            }
            for i in 0..N {
                let soft = msp[i] * e[i] - isp[i] * w.points[i].impulse;
                delta[i] = L::select(ok, delta[i], soft);
            }
        }
    }
    let (mut lin, mut ang_a, mut ang_b, mut total) = (zero, V::zero(), V::zero(), zero);
    for (p, d) in w.points[..N].iter_mut().zip(delta) {
        p.impulse = p.impulse + d;
        p.max_impulse = p.max_impulse.max(d);
        total = total + p.impulse;
        lin = lin + d;
        ang_a = ang_a.add_scaled(p.ia, d);
        if !SB {
            ang_b = ang_b.add_scaled(p.ib, d);
        }
    }
    va = va.add_scaled(on_free(w.locked, n, w.free_a), -(w.ma * lin));
    wa = wa - ang_a;
    if !SB {
        vb = vb.add_scaled(on_free(w.locked, n, w.free_b), w.mb * lin);
        wb = wb + ang_b;
    }
    if w.spin {
        rolling_resistance::<L, SB>(&mut w.friction, &w.tangents, total, &mut wa, &mut wb);
    }

    // Patch friction: the static coefficient while the patch sticks, dynamic once it slides.
    let f = &mut w.friction;
    let old = f.tangent_impulse;
    let mut new = [zero; 2];
    for k in 0..2 {
        let vt = rel::<L, SB>(va, wa, vb, wb, w.tangents[k], f.rta[k], f.rtb[k]);
        new[k] = old[k] - f.tangent_mass[k] * vt;
    }
    let old_twist = f.twist_impulse;
    let twist = if N > 1 || w.spin {
        old_twist - f.twist_mass * (wb - wa).dot(n)
    } else {
        zero
    };
    let len2 = new[0] * new[0] + new[1] * new[1];
    // Stick or slide is decided per step from the tangential speed at its start (see
    // `prepare`): deciding mid-step would latch on the transient before the normal impulse
    // has built up.
    let limit = L::select(f.sliding, w.dynamic_friction, w.static_friction) * total;
    let over = len2.gt(limit * limit);
    let scale = L::select(over, limit / L::select(over, len2, L::splat(1.0)).sqrt(), L::splat(1.0));
    new[0] = new[0] * scale;
    new[1] = new[1] * scale;
    // The patch's own extent, plus torsional friction where the lanes have it.
    let twist_limit = if w.spin {
        limit * f.twist_radius + f.torsion * total
    } else {
        limit * f.twist_radius
    };
    let twist = twist.min(twist_limit).max(-twist_limit);
    let d_twist = twist - old_twist;
    let mut lin = V::zero();
    let (mut ang_a, mut ang_b) = if N > 1 || w.spin {
        (f.ina.scale(d_twist), f.inb.scale(d_twist))
    } else {
        (V::zero(), V::zero())
    };
    for k in 0..2 {
        let d = new[k] - old[k];
        lin = lin.add_scaled(w.tangents[k], d);
        ang_a = ang_a.add_scaled(f.ita[k], d);
        if !SB {
            ang_b = ang_b.add_scaled(f.itb[k], d);
        }
    }
    f.tangent_impulse = new;
    f.twist_impulse = twist;
    va = va.add_scaled(on_free(w.locked, lin, w.free_a), -w.ma);
    wa = wa - ang_a;
    scatter(vel, &w.a, va, wa);
    if !SB {
        vb = vb.add_scaled(on_free(w.locked, lin, w.free_b), w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.b, vb, wb);
    }
}

/// Rolling resistance (Box2D v3's, about both tangents): the relative angular velocity in the
/// contact plane is driven to zero by an angular impulse no larger than the lever
/// `f.rolling` times the manifold's normal impulse `total` (the 2D impulse clamped to a disc).
#[inline(always)]
fn rolling_resistance<L: Lanes, const SB: bool>(
    f: &mut WideFriction<L>,
    tangents: &[V<L>; 2],
    total: L,
    wa: &mut V<L>,
    wb: &mut V<L>,
) {
    let (c0, c1) = if SB {
        (-wa.dot(tangents[0]), -wa.dot(tangents[1]))
    } else {
        let dw = *wb - *wa;
        (dw.dot(tangents[0]), dw.dot(tangents[1]))
    };
    let old = f.rolling_impulse;
    let m = &f.rolling_mass;
    let mut new = [old[0] - (m[0] * c0 + m[1] * c1), old[1] - (m[1] * c0 + m[2] * c1)];
    let limit = f.rolling * total;
    let len2 = new[0] * new[0] + new[1] * new[1];
    let over = len2.gt(limit * limit);
    let one = L::one();
    let scale = L::select(over, limit / L::select(over, len2, one).sqrt(), one);
    new[0] = new[0] * scale;
    new[1] = new[1] * scale;
    let (d0, d1) = (new[0] - old[0], new[1] - old[1]);
    f.rolling_impulse = new;
    *wa = *wa - f.ira[0].scale(d0) - f.ira[1].scale(d1);
    if !SB {
        *wb = *wb + f.irb[0].scale(d0) + f.irb[1].scale(d1);
    }
}

/// Bounces: points that approached faster than `threshold` and pushed leave at −e times their
/// approach speed.
pub fn restitution(vel: &mut [Velocity], batches: &mut Batches, threshold: f32) {
    dispatch!(&mut batches.sets, restitution_all(vel, threshold))
}

#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `pack_all` grows (see `dispatch!`)
fn restitution_all<L: Lanes>(batches: &mut Vec<WideContact<L>>, vel: &mut [Velocity], threshold: f32) {
    for w in batches.iter_mut().filter(|w| w.has_restitution) {
        if w.b_static {
            restitution_batch::<L, true>(vel, w, threshold);
        } else {
            restitution_batch::<L, false>(vel, w, threshold);
        }
    }
}

#[inline(always)]
fn restitution_batch<L: Lanes, const SB: bool>(vel: &mut [Velocity], w: &mut WideContact<L>, threshold: f32) {
    let zero = L::zero();
    let (mut va, mut wa) = gather(vel, &w.a);
    let (mut vb, mut wb) = if SB { (V::zero(), V::zero()) } else { gather(vel, &w.b) };
    let n = w.normal;
    for p in w.points[..w.count].iter_mut() {
        let bounce = p
            .active
            .and(w.restitution.gt(zero))
            .and((-p.relative_velocity).gt(L::splat(threshold)))
            .and(p.max_impulse.gt(zero));
        if bounce.bits() == 0 {
            continue;
        }
        let vn = rel::<L, SB>(va, wa, vb, wb, n, p.rna, p.rnb);
        let new = (p.impulse - p.normal_mass * (vn + w.restitution * p.relative_velocity)).max(zero);
        let d = L::select(bounce, new - p.impulse, zero);
        p.impulse = p.impulse + d;
        p.max_impulse = p.max_impulse.max(d);
        va = va.add_scaled(on_free(w.locked, n, w.free_a), -(w.ma * d));
        wa = wa.add_scaled(p.ia, -d);
        if !SB {
            vb = vb.add_scaled(on_free(w.locked, n, w.free_b), w.mb * d);
            wb = wb.add_scaled(p.ib, d);
        }
    }
    scatter(vel, &w.a, va, wa);
    if !SB {
        scatter(vel, &w.b, vb, wb);
    }
}

#[inline(always)]
fn floats3<L: Lanes>(v: &V<L>) -> [L::Floats; 3] {
    [v.x.to_floats(), v.y.to_floats(), v.z.to_floats()]
}

/// Writes each lane's impulses back to its contact: batch by batch on `runner`'s workers,
/// then, on the calling thread, the lanes of contacts with several manifolds (two tasks
/// would otherwise reach one contact at once). Each lane writes only its own manifold's
/// impulses, so the order changes nothing.
pub fn store(batches: &mut Batches, refs: &[ContactRef], contacts: &mut Pool<Contact>, runner: &dyn TaskRunner) {
    let n = batches.len() as u32;
    let out = contacts.disjoint();
    let sets = SharedMut::new(batches);
    crate::parallel::run(runner, n, STORE_MIN_RANGE, &|start, end, _| {
        // SAFETY: each range reads only its own batches, and writes the contacts of their
        // lanes, which no other lane names (`shared` contacts are left to the pass below).
        let b = unsafe { sets.get() };
        dispatch!(&mut b.sets, store_all(refs, &out, false, start as usize..end as usize))
    });
    // SAFETY: one thread; a contact is reached by one lane at a time.
    let b = unsafe { sets.get() };
    let all = 0..n as usize;
    dispatch!(&mut b.sets, store_all(refs, &out, true, all))
}

/// Batches stored per task, at least.
const STORE_MIN_RANGE: u32 = 64;

/// `store` over the batches of `range`: the lanes whose contact has several manifolds when
/// `shared`, the others otherwise.
#[inline(always)]
#[allow(clippy::ptr_arg)] // all passes take the storage `grow_all` sizes (see `dispatch!`)
fn store_all<L: Lanes>(
    batches: &mut Vec<WideContact<L>>,
    refs: &[ContactRef],
    contacts: &DisjointPool<Contact>,
    shared: bool,
    range: Range<usize>,
) {
    for w in batches[range].iter() {
        if shared && !w.shared {
            continue;
        }
        let f = &w.friction;
        let (t0, t1, tw, sl) = (
            f.tangent_impulse[0].to_floats(),
            f.tangent_impulse[1].to_floats(),
            f.twist_impulse.to_floats(),
            f.sliding.bits(),
        );
        let tangents = [floats3(&w.tangents[0]), floats3(&w.tangents[1])];
        let mut impulses = [L::Floats::default(); MAXP];
        for (i, p) in impulses.iter_mut().zip(&w.points) {
            *i = p.impulse.to_floats();
        }
        for (lane, &src) in w.src.as_ref().iter().enumerate() {
            if src == EMPTY {
                continue;
            }
            let r = &refs[src as usize];
            let Some(ci) = r.contact().filter(|_| r.shared() == shared) else {
                continue;
            };
            let at = |x: &L::Floats| x.as_ref()[lane];
            let tangent = |k: usize| Vec3::new(at(&tangents[k][0]), at(&tangents[k][1]), at(&tangents[k][2]));
            let out = LaneImpulses {
                normal: impulses.each_ref().map(at),
                tangent: tangent(0) * at(&t0) + tangent(1) * at(&t1),
                twist: at(&tw),
                sliding: sl & (1 << lane) != 0,
            };
            // SAFETY: (see `store`) no other task reaches this contact now.
            contact_solver::store(r, &out, unsafe { contacts.at_mut(ci) });
        }
        if w.spin {
            store_rolling(w, &tangents, refs, contacts, shared);
        }
    }
}

/// Writes each lane's rolling impulse back to its contact (batches with rolling resistance).
#[inline(always)]
fn store_rolling<L: Lanes>(
    w: &WideContact<L>,
    tangents: &[[L::Floats; 3]; 2],
    refs: &[ContactRef],
    contacts: &DisjointPool<Contact>,
    shared: bool,
) {
    let r = [
        w.friction.rolling_impulse[0].to_floats(),
        w.friction.rolling_impulse[1].to_floats(),
    ];
    for (lane, &src) in w.src.as_ref().iter().enumerate() {
        if src == EMPTY {
            continue;
        }
        let rf = &refs[src as usize];
        let Some(ci) = rf.contact().filter(|_| rf.shared() == shared) else {
            continue;
        };
        let mut rolling = Vec3::ZERO;
        for (t, imp) in tangents.iter().zip(&r) {
            let at = |x: &L::Floats| x.as_ref()[lane];
            rolling += Vec3::new(at(&t[0]), at(&t[1]), at(&t[2])) * at(imp);
        }
        // SAFETY: (see `store`) no other task reaches this contact now.
        contact_solver::store_rolling(rf, rolling, unsafe { contacts.at_mut(ci) });
    }
}
