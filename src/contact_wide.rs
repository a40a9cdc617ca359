//! The contact solver's passes, four constraints at a time.
//!
//! Each step the prepared constraints are graph-coloured so that no two constraints of a
//! colour share a dynamic body, then packed four to a batch (lanes) in colour order. Lanes of a
//! batch touch different bodies, so one batch gathers the velocities of its bodies, solves all
//! four constraints with `F4` arithmetic and scatters the velocities back: a Gauss–Seidel
//! sweep with four independent constraints per instruction. Constraints that fit no colour
//! go into batches of their own. Static bodies (and kinematic ones: zero inverse mass) are
//! never written, so they do not take part in the colouring.
//!
//! Per sub-step (Box2D v3's soft step): `refresh` (current lever arms at the midpoint of the
//! two material points, Jacobians, the block matrix K and its inverse, separations),
//! `warm_start`, a soft `solve` sweep that pushes overlap out and damps, the position update,
//! then a rigid relax `solve` sweep that removes the push velocity. Each sweep block-solves a
//! manifold's normal impulses (exactly through K⁻¹, by projected Gauss–Seidel on K where a point
//! would pull) and then its patch friction (static/dynamic coefficients, twist). After the
//! sub-steps: `restitution`, then `store` writes the impulses back for warm starting.

use crate::collision::MAX_MANIFOLD_POINTS;
use crate::contact_solver::ContactConstraint;
use crate::math::Vec3;
use crate::simd::{self, load, transpose, F4, M4, V4};
use crate::solver::{BodyState, Velocity};

const MAXP: usize = MAX_MANIFOLD_POINTS;

/// Colours tried before a constraint goes to a batch of its own.
const COLORS: usize = 24;

/// Inner iterations of the projected Gauss–Seidel fallback of the block solve.
const BLOCK_ITERATIONS: usize = 4;

/// Relative regularisation of K (four coplanar points constrain only three motions).
const BLOCK_REGULARIZATION: f32 = 1.0e-3;

/// Fraction of the remaining error a rigid (generated) constraint removes per sub-step.
const RIGID_PUSH: f32 = 0.3;

/// Lane index marking an empty lane.
const EMPTY: u32 = u32::MAX;

#[derive(Clone, Copy, Default)]
pub struct WidePoint {
    /// Arms to the shapes' core points at the start of the step (they turn with the bodies);
    /// the contact point is the core point plus `oa` (resp. `ob`) along the normal.
    ca0: V4,
    cb0: V4,
    separation0: F4,
    /// All-ones in lanes where this point exists.
    active: F4,
    rna: V4,
    rnb: V4,
    ia: V4,
    ib: V4,
    separation: F4,
    normal_mass: F4,
    impulse: F4,
    max_impulse: F4,
    relative_velocity: F4,
}

#[derive(Clone, Copy, Default)]
pub struct WideFriction {
    ca0: V4,
    cb0: V4,
    rta: [V4; 2],
    rtb: [V4; 2],
    ita: [V4; 2],
    itb: [V4; 2],
    ina: V4,
    inb: V4,
    tangent_mass: [F4; 2],
    twist_mass: F4,
    twist_radius: F4,
    tangent_impulse: [F4; 2],
    twist_impulse: F4,
    sliding: F4,
}

#[derive(Clone, Copy, Default)]
pub struct WideContact {
    /// Solver state indices of the bodies; 0 is the static dummy.
    a: [u32; 4],
    b: [u32; 4],
    /// Index of each lane's scalar constraint, or `EMPTY`.
    src: [u32; 4],
    /// Largest point count of the lanes: 1, or 4 (missing points inactive).
    count: usize,
    /// Every lane's body B is the static dummy: B's half of the work is skipped.
    b_static: bool,
    ma: F4,
    mb: F4,
    normal: V4,
    /// Offsets from each core point to the contact point: `r_a·n` and `−r_b·n`.
    oa: V4,
    ob: V4,
    /// Where the contact point sits between the two bodies' contact points: 0 on A's, 1 on
    /// B's. A rounded surface defines where it touches now (a rolling sphere touches below its
    /// centre, whatever the ground's material point did); otherwise the midpoint.
    at_b: F4,
    tangents: [V4; 2],
    static_friction: F4,
    dynamic_friction: F4,
    restitution: F4,
    /// All-ones in lanes solved rigidly (see `ContactConstraint::rigid`).
    rigid: F4,
    /// The biased sweep's coefficients per lane, fixed for a step (`set_softness`): push-out
    /// rate, mass scale, impulse leak, and the part of its impulse a point keeps.
    soft_rate: F4,
    soft_ms: F4,
    soft_is: F4,
    soft_keep: F4,
    has_restitution: bool,
    points: [WidePoint; MAXP],
    k: [[F4; MAXP]; MAXP],
    k_inv: [[F4; MAXP]; MAXP],
    friction: WideFriction,
}

/// Reused storage of the batched solver.
#[derive(Default)]
pub struct Batches {
    pub batches: Vec<WideContact>,
    color_bits: Vec<Vec<u64>>,
    color_members: Vec<Vec<u32>>,
    singles: Vec<u32>,
}

impl Batches {
    /// Colours and packs `constraints` into batches. `states` gives inverse masses.
    pub fn build(&mut self, constraints: &[ContactConstraint], states: &[BodyState]) {
        let words = states.len().div_ceil(64);
        self.color_bits.resize_with(COLORS, Vec::new);
        self.color_members.resize_with(COLORS, Vec::new);
        for c in 0..COLORS {
            self.color_bits[c].clear();
            self.color_bits[c].resize(words, 0);
            self.color_members[c].clear();
        }
        self.singles.clear();
        let writes = |i: u32| i != 0 && states[i as usize].inv_mass > 0.0;
        'next: for (ci, c) in constraints.iter().enumerate() {
            let (wa, wb) = (writes(c.a), writes(c.b));
            for color in 0..COLORS {
                let bits = &mut self.color_bits[color];
                let used = |i: u32| bits[i as usize / 64] & (1u64 << (i % 64)) != 0;
                if (wa && used(c.a)) || (wb && used(c.b)) {
                    continue;
                }
                for (w, i) in [(wa, c.a), (wb, c.b)] {
                    if w {
                        bits[i as usize / 64] |= 1u64 << (i % 64);
                    }
                }
                self.color_members[color].push(ci as u32);
                continue 'next;
            }
            self.singles.push(ci as u32);
        }
        // Batches are packed in place over last step's storage: no zeroing, no copies.
        let mut used = 0;
        for color in 0..COLORS {
            let members = &mut self.color_members[color];
            // Like with like: lanes of a batch then share their point count, whether B is
            // static, and whether they carried load (idle batches end their sweep early).
            members.sort_by_key(|&i| {
                let c = &constraints[i as usize];
                let loaded = c.points[..c.count].iter().any(|p| p.normal_impulse > 0.0);
                (c.count > 1, c.b != 0, loaded)
            });
            for chunk in members.chunks(4) {
                next_slot(&mut self.batches, used);
                pack(&mut self.batches[used], chunk, constraints);
                used += 1;
            }
        }
        for &i in &self.singles {
            next_slot(&mut self.batches, used);
            pack(&mut self.batches[used], &[i], constraints);
            used += 1;
        }
        self.batches.truncate(used);
    }
}

fn next_slot(batches: &mut Vec<WideContact>, used: usize) {
    if batches.len() == used {
        batches.push(WideContact::default());
    }
}

/// Packs up to four constraints into `w`, setting every field the passes read before they
/// write it (the storage is reused from earlier steps).
fn pack(w: &mut WideContact, lanes: &[u32], constraints: &[ContactConstraint]) {
    // Stage each field per lane (empty lanes stay zero), then load the lanes at once.
    #[derive(Default)]
    struct Stage {
        f: [[f32; 4]; 11],
        v: [[Vec3; 4]; 7],
        pf: [[[f32; 4]; 4]; MAXP],
        pv: [[[Vec3; 4]; 2]; MAXP],
    }
    let mut st = Stage::default();
    (w.a, w.b, w.src, w.count, w.has_restitution) = ([0; 4], [0; 4], [EMPTY; 4], 0, false);
    let mut sliding = [0.0f32; 4];
    let on = f32::from_bits(u32::MAX);
    for (i, &k) in lanes.iter().enumerate() {
        let c = &constraints[k as usize];
        w.a[i] = c.a;
        w.b[i] = c.b;
        w.src[i] = k;
        w.count = w.count.max(c.count);
        w.has_restitution |= c.restitution > 0.0;
        let (oa, ob) = (c.normal * c.radius_a, c.normal * -c.radius_b);
        let at_b = match (c.radius_a > 0.0, c.radius_b > 0.0) {
            (true, false) => 0.0,
            (false, true) => 1.0,
            _ => 0.5,
        };
        let f = &c.friction;
        for (slot, x) in st.f.iter_mut().zip([
            c.ma,
            c.mb,
            at_b,
            c.static_friction,
            c.dynamic_friction,
            c.restitution,
            f.twist_radius,
            f.tangent_impulse[0],
            f.tangent_impulse[1],
            f.twist_impulse,
            if c.rigid { on } else { 0.0 },
        ]) {
            slot[i] = x;
        }
        for (slot, x) in
            st.v.iter_mut()
                .zip([c.normal, oa, ob, c.tangents[0], c.tangents[1], f.ra0 - oa, f.rb0 - ob])
        {
            slot[i] = x;
        }
        for (p, cp) in c.points[..c.count].iter().enumerate() {
            for (slot, x) in st.pf[p]
                .iter_mut()
                .zip([cp.separation0, on, cp.normal_impulse, cp.relative_velocity])
            {
                slot[i] = x;
            }
            st.pv[p][0][i] = cp.ra0 - oa;
            st.pv[p][1][i] = cp.rb0 - ob;
        }
        if f.sliding {
            sliding[i] = on;
        }
    }
    // Batches run as one-point or four-point manifolds (missing points are inactive).
    w.count = if w.count <= 1 { 1 } else { MAXP };
    w.b_static = w.b.iter().all(|&b| b == 0);
    let [ma, mb, at_b, fs, fd, e, twist_radius, t0, t1, twist, rigid] = st.f.map(F4::from_array);
    w.rigid = rigid;
    let [normal, oa, ob, tan0, tan1, fca0, fcb0] = st.v.map(V4::from_lanes);
    (w.ma, w.mb, w.at_b, w.static_friction, w.dynamic_friction, w.restitution) = (ma, mb, at_b, fs, fd, e);
    (w.normal, w.oa, w.ob, w.tangents) = (normal, oa, ob, [tan0, tan1]);
    let f = &mut w.friction;
    (f.ca0, f.cb0, f.twist_radius, f.tangent_impulse, f.twist_impulse) = (fca0, fcb0, twist_radius, [t0, t1], twist);
    f.sliding = F4::from_array(sliding);
    for p in 0..w.count {
        let wp = &mut w.points[p];
        let [sep0, active, impulse, rel] = st.pf[p].map(F4::from_array);
        (wp.separation0, wp.active, wp.impulse, wp.relative_velocity) = (sep0, active, impulse, rel);
        wp.max_impulse = F4::zero();
        wp.ca0 = V4::from_lanes(st.pv[p][0]);
        wp.cb0 = V4::from_lanes(st.pv[p][1]);
    }
}

/// Four bodies' motion so far into lanes: translation, rotation and world inverse inertia.
#[inline(always)]
fn gather_states(states: &[BodyState], idx: &[u32; 4]) -> (V4, M4, M4) {
    let rows = idx.map(|i| &states[i as usize].rows);
    let lanes = |r: usize| {
        transpose([
            load(&rows[0][r]),
            load(&rows[1][r]),
            load(&rows[2][r]),
            load(&rows[3][r]),
        ])
    };
    let v = |t: [F4; 4]| V4 {
        x: t[0],
        y: t[1],
        z: t[2],
    };
    let dp = v(lanes(0));
    let [x, y, z, w] = lanes(1);
    (
        dp,
        rotation(x, y, z, w),
        M4 {
            c0: v(lanes(2)),
            c1: v(lanes(3)),
            c2: v(lanes(4)),
        },
    )
}

/// The rotation matrices of four unit quaternions.
#[inline(always)]
fn rotation(x: F4, y: F4, z: F4, w: F4) -> M4 {
    let (x2, y2, z2) = (x + x, y + y, z + z);
    let (xx, xy, xz) = (x * x2, x * y2, x * z2);
    let (yy, yz, zz) = (y * y2, y * z2, z * z2);
    let (wx, wy, wz) = (w * x2, w * y2, w * z2);
    let one = F4::splat(1.0);
    M4 {
        c0: V4 {
            x: one - (yy + zz),
            y: xy + wz,
            z: xz - wy,
        },
        c1: V4 {
            x: xy - wz,
            y: one - (xx + zz),
            z: yz + wx,
        },
        c2: V4 {
            x: xz + wy,
            y: yz - wx,
            z: one - (xx + yy),
        },
    }
}

#[inline(always)]
fn gather(vel: &[Velocity], idx: &[u32; 4]) -> (V4, V4) {
    let rows = idx.map(|i| vel[i as usize].rows());
    let v = transpose([
        load(&rows[0][0]),
        load(&rows[1][0]),
        load(&rows[2][0]),
        load(&rows[3][0]),
    ]);
    let w = transpose([
        load(&rows[0][1]),
        load(&rows[1][1]),
        load(&rows[2][1]),
        load(&rows[3][1]),
    ]);
    (
        V4 {
            x: v[0],
            y: v[1],
            z: v[2],
        },
        V4 {
            x: w[0],
            y: w[1],
            z: w[2],
        },
    )
}

/// Writes the lanes back. Lanes of static (index 0) and kinematic bodies carry exactly the
/// velocity they gathered (their inverse mass and inertia are zero), and the colouring keeps
/// the dynamic bodies of a batch distinct, so writing every lane is safe.
#[inline(always)]
fn scatter(vel: &mut [Velocity], idx: &[u32; 4], v: V4, w: V4) {
    let zero = F4::zero();
    let vr = transpose([v.x, v.y, v.z, zero]);
    let wr = transpose([w.x, w.y, w.z, zero]);
    for i in 0..4 {
        let rows = vel[idx[i] as usize].rows_mut();
        simd::store(vr[i], &mut rows[0]);
        simd::store(wr[i], &mut rows[1]);
    }
}

#[inline(always)]
fn safe_inverse(k: F4) -> F4 {
    let ok = k.gt(F4::zero());
    F4::select(ok, F4::splat(1.0).div(F4::select(ok, k, F4::splat(1.0))), F4::zero())
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
/// Inverts each lane's K (symmetric positive definite after regularisation, identity rows
/// for missing points) by Cholesky: K = L Lᵀ, K⁻¹ = L⁻ᵀ L⁻¹.
fn invert_spd(k: &[[F4; MAXP]; MAXP], n: usize, out: &mut [[F4; MAXP]; MAXP]) {
    let mut l = [[F4::zero(); MAXP]; MAXP];
    let mut inv_diag = [F4::zero(); MAXP];
    for j in 0..n {
        let mut d = k[j][j];
        for p in 0..j {
            d = d - l[j][p] * l[j][p];
        }
        let d = d.max(F4::splat(1e-20)).sqrt();
        l[j][j] = d;
        inv_diag[j] = F4::splat(1.0) / d;
        for i in j + 1..n {
            let mut s = k[i][j];
            for p in 0..j {
                s = s - l[i][p] * l[j][p];
            }
            l[i][j] = s * inv_diag[j];
        }
    }
    // L⁻¹ by forward substitution.
    let mut li = [[F4::zero(); MAXP]; MAXP];
    for i in 0..n {
        li[i][i] = inv_diag[i];
        for j in 0..i {
            let mut s = F4::zero();
            for p in j..i {
                s = s + l[i][p] * li[p][j];
            }
            li[i][j] = -(s * inv_diag[i]);
        }
    }
    for i in 0..n {
        for j in 0..=i {
            let mut s = F4::zero();
            for p in i..n {
                s = s + li[p][i] * li[p][j];
            }
            out[i][j] = s;
            out[j][i] = s;
        }
    }
}

/// Offsets of the contact points from the core points, and where between them forces act.
struct Geometry4 {
    oa: V4,
    ob: V4,
    at_b: F4,
}

/// Current lever arms and the gap between the two bodies' contact points. Core points (box
/// vertices, sphere centres, capsule segment points) turn with their bodies; each contact
/// point keeps its offset along the normal. Both arms reach one point (`at_b` of the way from
/// A's contact point to B's), so equal and opposite impulses conserve angular momentum.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn arms(ca0: V4, cb0: V4, g: &Geometry4, dpa: V4, dpb: V4, rot_a: &M4, rot_b: &M4) -> (V4, V4, V4) {
    let pra = rot_a.mul_vec(ca0) + g.oa;
    let prb = rot_b.mul_vec(cb0) + g.ob;
    let gap = ((ca0 + g.oa) - (cb0 + g.ob)) + (dpb - dpa) + (prb - pra);
    (
        pra.add_scaled(gap, g.at_b),
        prb.add_scaled(gap, g.at_b - F4::splat(1.0)),
        gap,
    )
}

/// Relative motion (m; rad counts as m of arm) since the start of the step below which a
/// batch keeps the arms of its last full refresh and updates separations to first order.
const LIGHT_REFRESH_MOTION: f32 = 1.0e-3;

/// Brings the constraints up to date with the motion so far. On the first sub-step (`first`):
/// arms, Jacobians, effective masses, K and K⁻¹, separations. Later, a batch whose bodies
/// moved less than `LIGHT_REFRESH_MOTION` relative to each other only updates separations
/// (`s₀ + n·Δp + θ_B·(r_B×n) − θ_A·(r_A×n)`, exact to first order); others recompute their
/// arms, so fast contacts keep impulses at one point and angular momentum exact.
pub fn refresh(states: &[BodyState], batches: &mut [WideContact], first: bool) {
    for w in batches.iter_mut() {
        match (w.count == 1, w.b_static) {
            (true, true) => refresh_batch::<1, true>(states, w, first),
            (true, false) => refresh_batch::<1, false>(states, w, first),
            (false, true) => refresh_batch::<MAXP, true>(states, w, first),
            (false, false) => refresh_batch::<MAXP, false>(states, w, first),
        }
    }
}

/// First-order separation update for a batch whose bodies barely moved relative to each
/// other; false (and nothing changed) when some lane moved too much.
#[inline(always)]
fn light_refresh<const N: usize, const SB: bool>(states: &[BodyState], w: &mut WideContact) -> bool {
    let motion = |idx: &[u32; 4]| {
        let rows = idx.map(|i| &states[i as usize].rows);
        let lanes = |r: usize| {
            let t = transpose([
                load(&rows[0][r]),
                load(&rows[1][r]),
                load(&rows[2][r]),
                load(&rows[3][r]),
            ]);
            V4 {
                x: t[0],
                y: t[1],
                z: t[2],
            }
        };
        (lanes(0), lanes(5))
    };
    let (dpa, tha) = motion(&w.a);
    let (dpb, thb) = if SB { (V4::zero(), V4::zero()) } else { motion(&w.b) };
    let d = dpb - dpa;
    let tol2 = F4::splat(LIGHT_REFRESH_MOTION * LIGHT_REFRESH_MOTION);
    if d.length_squared()
        .gt(tol2)
        .or((tha.length_squared() + thb.length_squared()).gt(tol2))
        .bits()
        != 0
    {
        return false;
    }
    let nd = w.normal.dot(d);
    for p in w.points[..N].iter_mut() {
        let mut s = p.separation0 + nd - tha.dot(p.rna);
        if !SB {
            s = s + thb.dot(p.rnb);
        }
        p.separation = s;
    }
    true
}

/// `refresh` for one batch of `N`-point manifolds (1, or 4 with missing points inactive).
#[inline(always)]
fn refresh_batch<const N: usize, const SB: bool>(states: &[BodyState], w: &mut WideContact, block: bool) {
    if !block && light_refresh::<N, SB>(states, w) {
        return;
    }
    let (dpa, rot_a, ia) = gather_states(states, &w.a);
    let (dpb, rot_b, ib) = if SB {
        (V4::zero(), M4::IDENTITY, M4::default())
    } else {
        gather_states(states, &w.b)
    };
    let n = w.normal;
    let m = w.ma + w.mb;
    let g = Geometry4 {
        oa: w.oa,
        ob: w.ob,
        at_b: w.at_b,
    };
    for p in w.points[..N].iter_mut() {
        let (ra, rb, gap) = arms(p.ca0, p.cb0, &g, dpa, dpb, &rot_a, &rot_b);
        p.separation = p.separation0 + gap.dot(n);
        p.rna = ra.cross(n);
        p.ia = ia.mul_vec(p.rna);
        let mut k = m + p.rna.dot(p.ia);
        if !SB {
            p.rnb = rb.cross(n);
            p.ib = ib.mul_vec(p.rnb);
            k = k + p.rnb.dot(p.ib);
        }
        p.normal_mass = F4::select(p.active, safe_inverse(k), F4::zero());
    }
    if block && N > 1 {
        let one = F4::splat(1.0);
        for i in 0..N {
            for j in i..N {
                let (pi, pj) = (&w.points[i], &w.points[j]);
                let both = pi.active.and(pj.active);
                let mut kij = m + pi.rna.dot(pj.ia);
                if !SB {
                    kij = kij + pi.rnb.dot(pj.ib);
                }
                if i == j {
                    w.k[i][i] = F4::select(both, kij, one);
                } else {
                    let v = F4::select(both, kij, F4::zero());
                    w.k[i][j] = v;
                    w.k[j][i] = v;
                }
            }
        }
        let mut reg = w.k;
        for (i, row) in reg.iter_mut().enumerate().take(N) {
            row[i] = row[i] * F4::splat(1.0 + BLOCK_REGULARIZATION);
        }
        invert_spd(&reg, N, &mut w.k_inv);
    }
    let f = &mut w.friction;
    let (ra, rb, _) = arms(f.ca0, f.cb0, &g, dpa, dpb, &rot_a, &rot_b);
    for k in 0..2 {
        let t = w.tangents[k];
        f.rta[k] = ra.cross(t);
        f.ita[k] = ia.mul_vec(f.rta[k]);
        let mut km = m + f.rta[k].dot(f.ita[k]);
        if !SB {
            f.rtb[k] = rb.cross(t);
            f.itb[k] = ib.mul_vec(f.rtb[k]);
            km = km + f.rtb[k].dot(f.itb[k]);
        }
        f.tangent_mass[k] = safe_inverse(km);
    }
    // One-point manifolds have no twist lever (the radius is zero).
    if N > 1 {
        f.ina = ia.mul_vec(n);
        let mut kt = n.dot(f.ina);
        if !SB {
            f.inb = ib.mul_vec(n);
            kt = kt + n.dot(f.inb);
        }
        f.twist_mass = safe_inverse(kt);
    }
}

/// Sets each batch's biased-sweep coefficients for this step: the soft contact's (the static
/// variant when a body has infinite mass), or for rigid lanes the full response, no leak and a
/// fast push-out (a fraction of the sub-step rate; the relax sweep removes the push velocity)
/// so a rod keeps its length while it swings.
pub fn set_softness(batches: &mut [WideContact], soft: &SoftSweep, inv_h: f32) {
    let (zero, one) = (F4::zero(), F4::splat(1.0));
    for w in batches.iter_mut() {
        let dynamic = w.ma.gt(zero).and(w.mb.gt(zero));
        let pick = |d: f32, s: f32| F4::select(dynamic, F4::splat(d), F4::splat(s));
        let rate = pick(soft.soft.bias_rate, soft.soft_static.bias_rate);
        let ms = pick(soft.soft.mass_scale, soft.soft_static.mass_scale);
        let is = pick(soft.soft.impulse_scale, soft.soft_static.impulse_scale);
        w.soft_rate = F4::select(w.rigid, F4::splat(RIGID_PUSH * inv_h), rate);
        w.soft_ms = F4::select(w.rigid, one, ms);
        w.soft_is = F4::select(w.rigid, zero, is);
        w.soft_keep = (one - w.soft_is) / w.soft_ms;
    }
}

/// Relative velocity along `d` with angular Jacobians `ja`, `jb`.
#[inline(always)]
fn rel<const SB: bool>(va: V4, wa: V4, vb: V4, wb: V4, d: V4, ja: V4, jb: V4) -> F4 {
    if SB {
        -(d.dot(va) + wa.dot(ja))
    } else {
        d.dot(vb - va) + wb.dot(jb) - wa.dot(ja)
    }
}

pub fn warm_start(vel: &mut [Velocity], batches: &[WideContact]) {
    for w in batches {
        match (w.count == 1, w.b_static) {
            (true, true) => warm_start_batch::<1, true>(vel, w),
            (true, false) => warm_start_batch::<1, false>(vel, w),
            (false, true) => warm_start_batch::<MAXP, true>(vel, w),
            (false, false) => warm_start_batch::<MAXP, false>(vel, w),
        }
    }
}

#[inline(always)]
fn warm_start_batch<const N: usize, const SB: bool>(vel: &mut [Velocity], w: &WideContact) {
    let (mut va, mut wa) = gather(vel, &w.a);
    let mut lin = w.normal.scale(sum_impulses::<N>(w));
    let f = &w.friction;
    let (mut ang_a, mut ang_b) = if N > 1 {
        (f.ina.scale(f.twist_impulse), f.inb.scale(f.twist_impulse))
    } else {
        (V4::zero(), V4::zero())
    };
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
    va = va.add_scaled(lin, -w.ma);
    wa = wa - ang_a;
    scatter(vel, &w.a, va, wa);
    if !SB {
        let (mut vb, mut wb) = gather(vel, &w.b);
        vb = vb.add_scaled(lin, w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.b, vb, wb);
    }
}

#[inline(always)]
fn sum_impulses<const N: usize>(w: &WideContact) -> F4 {
    w.points[..N].iter().fold(F4::zero(), |s, p| s + p.impulse)
}

/// One sweep over real velocities: block-solved normal impulses (speculative points may close
/// their gap within the sub-step and no more), then patch friction.
/// Soft-constraint coefficients of a biased sweep (Box2D v3's soft step): the push-out rate,
/// and how much of the rigid response and of the accumulated impulse each update keeps. The
/// leak of accumulated impulse is what damps a deep stack's oscillations.
#[derive(Clone, Copy, Debug)]
pub struct SoftSweep {
    pub soft: crate::solver::Softness,
    /// Softness of contacts with a static or kinematic body (stiffer).
    pub soft_static: crate::solver::Softness,
    pub max_push: f32,
    pub slop: f32,
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
/// One sweep: soft and biased (`Some`), or rigid without bias (`None`, the relax sweep).
/// Speculative points (positive separation) may close their gap within the sub-step, no more.
pub fn solve(vel: &mut [Velocity], batches: &mut [WideContact], inv_h: f32, forward: bool, bias: Option<&SoftSweep>) {
    for w in batches.iter_mut() {
        match (w.count == 1, w.b_static) {
            (true, true) => solve_batch::<1, true>(vel, w, inv_h, forward, bias),
            (true, false) => solve_batch::<1, false>(vel, w, inv_h, forward, bias),
            (false, true) => solve_batch::<MAXP, true>(vel, w, inv_h, forward, bias),
            (false, false) => solve_batch::<MAXP, false>(vel, w, inv_h, forward, bias),
        }
    }
}

#[allow(clippy::needless_range_loop)] // index notation mirrors the matrix algebra
#[inline(always)]
fn solve_batch<const N: usize, const SB: bool>(
    vel: &mut [Velocity],
    w: &mut WideContact,
    inv_h: f32,
    forward: bool,
    bias: Option<&SoftSweep>,
) {
    let zero = F4::zero();
    let one = F4::splat(1.0);
    let inv_h = F4::splat(inv_h);
    let (mut va, mut wa) = gather(vel, &w.a);
    // A static B has no velocity and never moves.
    let (mut vb, mut wb) = if SB {
        (V4::zero(), V4::zero())
    } else {
        gather(vel, &w.b)
    };
    let n = w.normal;
    // Per lane: the biased sweep's coefficients (see `set_softness`), or rigid without bias
    // for the relax sweep.
    let (rate, ms, is, keep, max_push, slop) = match bias {
        Some(b) => (
            w.soft_rate,
            w.soft_ms,
            w.soft_is,
            w.soft_keep,
            F4::splat(-b.max_push),
            F4::splat(b.slop),
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
        let b = F4::select(spec, p.separation * inv_h, push);
        msp[i] = F4::select(spec, one, ms);
        isp[i] = F4::select(spec, zero, is);
        kp[i] = F4::select(spec, one, keep);
        let v = rel::<SB>(va, wa, vb, wb, n, p.rna, p.rnb) + b;
        rhs[i] = F4::select(p.active, v, zero);
    }
    // Solve K e = −rhs for e ≥ −(1 − is)λ/ms, then Δλ = ms·e − is·λ (soft update).
    // A batch touching without load, not approaching and without friction (side faces of
    // neighbours) would change nothing: every impulse is zero and stays zero.
    let mut idle = F4::splat(f32::from_bits(u32::MAX));
    for (p, r) in w.points[..N].iter().zip(&rhs) {
        idle = idle.and(p.impulse.le(zero)).and(r.ge(zero));
    }
    if idle.bits() == 0b1111 {
        let f = &w.friction;
        let still = f.tangent_impulse[0].ge(zero).and(f.tangent_impulse[0].le(zero));
        let still = still
            .and(f.tangent_impulse[1].ge(zero))
            .and(f.tangent_impulse[1].le(zero));
        let still = still.and(f.twist_impulse.ge(zero)).and(f.twist_impulse.le(zero));
        if still.bits() == 0b1111 {
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
        let mut ok = F4::splat(f32::from_bits(u32::MAX));
        let mut lower = [zero; MAXP];
        for i in 0..N {
            let mut d = zero;
            for j in 0..N {
                d = d - w.k_inv[i][j] * rhs[j];
            }
            let p = &w.points[i];
            // e may not go below this, or the point would pull.
            lower[i] = -(kp[i] * p.impulse);
            let e = F4::select(idle, zero, d);
            ok = ok.and(e.ge(lower[i]));
            delta[i] = msp[i] * e - isp[i] * p.impulse;
        }
        if ok.bits() != 0b1111 {
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
                    e[i] = F4::select(p.active, (e[i] - p.normal_mass * r).max(lower[i]), zero);
                }
            }
            for i in 0..N {
                let soft = msp[i] * e[i] - isp[i] * w.points[i].impulse;
                delta[i] = F4::select(ok, delta[i], soft);
            }
        }
    }
    let (mut lin, mut ang_a, mut ang_b, mut total) = (zero, V4::zero(), V4::zero(), zero);
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
    va = va.add_scaled(n, -(w.ma * lin));
    wa = wa - ang_a;
    if !SB {
        vb = vb.add_scaled(n, w.mb * lin);
        wb = wb + ang_b;
    }

    // Patch friction: the static coefficient while the patch sticks, dynamic once it slides.
    let f = &mut w.friction;
    let old = f.tangent_impulse;
    let mut new = [zero; 2];
    for k in 0..2 {
        let vt = rel::<SB>(va, wa, vb, wb, w.tangents[k], f.rta[k], f.rtb[k]);
        new[k] = old[k] - f.tangent_mass[k] * vt;
    }
    let old_twist = f.twist_impulse;
    let twist = if N > 1 {
        old_twist - f.twist_mass * (wb - wa).dot(n)
    } else {
        zero
    };
    let len2 = new[0] * new[0] + new[1] * new[1];
    // Stick or slide is decided per step from the tangential speed at its start (see
    // `prepare`): deciding mid-step would latch on the transient before the normal impulse
    // has built up.
    let limit = F4::select(f.sliding, w.dynamic_friction, w.static_friction) * total;
    let over = len2.gt(limit * limit);
    let scale = F4::select(
        over,
        limit / F4::select(over, len2, F4::splat(1.0)).sqrt(),
        F4::splat(1.0),
    );
    new[0] = new[0] * scale;
    new[1] = new[1] * scale;
    let twist_limit = limit * f.twist_radius;
    let twist = twist.min(twist_limit).max(-twist_limit);
    let d_twist = twist - old_twist;
    let mut lin = V4::zero();
    let (mut ang_a, mut ang_b) = if N > 1 {
        (f.ina.scale(d_twist), f.inb.scale(d_twist))
    } else {
        (V4::zero(), V4::zero())
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
    va = va.add_scaled(lin, -w.ma);
    wa = wa - ang_a;
    scatter(vel, &w.a, va, wa);
    if !SB {
        vb = vb.add_scaled(lin, w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.b, vb, wb);
    }
}

/// Bounces: points that approached faster than `threshold` and pushed leave at −e times their
/// approach speed.
pub fn restitution(vel: &mut [Velocity], batches: &mut [WideContact], threshold: f32) {
    for w in batches.iter_mut().filter(|w| w.has_restitution) {
        if w.b_static {
            restitution_batch::<true>(vel, w, threshold);
        } else {
            restitution_batch::<false>(vel, w, threshold);
        }
    }
}

fn restitution_batch<const SB: bool>(vel: &mut [Velocity], w: &mut WideContact, threshold: f32) {
    let zero = F4::zero();
    let (mut va, mut wa) = gather(vel, &w.a);
    let (mut vb, mut wb) = if SB {
        (V4::zero(), V4::zero())
    } else {
        gather(vel, &w.b)
    };
    let n = w.normal;
    for p in w.points[..w.count].iter_mut() {
        let bounce = p
            .active
            .and((-p.relative_velocity).gt(F4::splat(threshold)))
            .and(p.max_impulse.gt(zero));
        if bounce.bits() == 0 {
            continue;
        }
        let vn = rel::<SB>(va, wa, vb, wb, n, p.rna, p.rnb);
        let new = (p.impulse - p.normal_mass * (vn + w.restitution * p.relative_velocity)).max(zero);
        let d = F4::select(bounce, new - p.impulse, zero);
        p.impulse = p.impulse + d;
        p.max_impulse = p.max_impulse.max(d);
        va = va.add_scaled(n, -(w.ma * d));
        wa = wa.add_scaled(p.ia, -d);
        if !SB {
            vb = vb.add_scaled(n, w.mb * d);
            wb = wb.add_scaled(p.ib, d);
        }
    }
    scatter(vel, &w.a, va, wa);
    if !SB {
        scatter(vel, &w.b, vb, wb);
    }
}

/// Writes each lane's impulses back to its scalar constraint.
pub fn store(batches: &[WideContact], constraints: &mut [ContactConstraint]) {
    for w in batches {
        let f = &w.friction;
        let (t0, t1, tw, sl) = (
            f.tangent_impulse[0].to_array(),
            f.tangent_impulse[1].to_array(),
            f.twist_impulse.to_array(),
            f.sliding.bits(),
        );
        let impulses: [[f32; 4]; MAXP] = std::array::from_fn(|p| w.points[p].impulse.to_array());
        for lane in 0..4 {
            if w.src[lane] == EMPTY {
                continue;
            }
            let c = &mut constraints[w.src[lane] as usize];
            for (point, lanes) in c.points[..c.count].iter_mut().zip(&impulses) {
                point.normal_impulse = lanes[lane];
            }
            c.friction.tangent_impulse = [t0[lane], t1[lane]];
            c.friction.twist_impulse = tw[lane];
            c.friction.sliding = sl & (1 << lane) != 0;
        }
    }
}
