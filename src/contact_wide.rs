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
    /// Largest point count of the lanes.
    count: usize,
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
        self.batches.clear();
        for color in 0..COLORS {
            let members = &mut self.color_members[color];
            // Like with like: lanes of a batch then share their point count.
            members.sort_by_key(|&i| constraints[i as usize].count);
            for chunk in members.chunks(4) {
                self.batches.push(pack(chunk, constraints));
            }
        }
        for &i in &self.singles {
            self.batches.push(pack(&[i], constraints));
        }
    }
}

fn pack(lanes: &[u32], constraints: &[ContactConstraint]) -> WideContact {
    // Stage each field per lane (empty lanes stay zero), then load the lanes at once.
    #[derive(Default)]
    struct Stage {
        f: [[f32; 4]; 10],
        v: [[Vec3; 4]; 7],
        pf: [[[f32; 4]; 4]; MAXP],
        pv: [[[Vec3; 4]; 2]; MAXP],
    }
    let mut st = Stage::default();
    let mut w = WideContact {
        a: [0; 4],
        b: [0; 4],
        src: [EMPTY; 4],
        ..Default::default()
    };
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
            w.friction.sliding = F4::from_array({
                let mut m = w.friction.sliding.to_array();
                m[i] = on;
                m
            });
        }
    }
    let [ma, mb, at_b, fs, fd, e, twist_radius, t0, t1, twist] = st.f.map(F4::from_array);
    let [normal, oa, ob, tan0, tan1, fca0, fcb0] = st.v.map(V4::from_lanes);
    (w.ma, w.mb, w.at_b, w.static_friction, w.dynamic_friction, w.restitution) = (ma, mb, at_b, fs, fd, e);
    (w.normal, w.oa, w.ob, w.tangents) = (normal, oa, ob, [tan0, tan1]);
    let f = &mut w.friction;
    (f.ca0, f.cb0, f.twist_radius, f.tangent_impulse, f.twist_impulse) = (fca0, fcb0, twist_radius, [t0, t1], twist);
    for p in 0..w.count {
        let wp = &mut w.points[p];
        let [sep0, active, impulse, rel] = st.pf[p].map(F4::from_array);
        (wp.separation0, wp.active, wp.impulse, wp.relative_velocity) = (sep0, active, impulse, rel);
        wp.ca0 = V4::from_lanes(st.pv[p][0]);
        wp.cb0 = V4::from_lanes(st.pv[p][1]);
    }
    w
}

/// Four bodies' motion so far into lanes: translation, rotation and world inverse inertia.
#[inline(always)]
fn gather_states(states: &[BodyState], idx: &[u32; 4]) -> (V4, M4, M4) {
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
    (
        lanes(0),
        M4 {
            c0: lanes(1),
            c1: lanes(2),
            c2: lanes(3),
        },
        M4 {
            c0: lanes(4),
            c1: lanes(5),
            c2: lanes(6),
        },
    )
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

/// Recomputes arms, Jacobians, effective masses and separations from the motion so far;
/// with `block`, also K and K⁻¹ (once per step: they change little within it).
pub fn refresh(states: &[BodyState], batches: &mut [WideContact], block: bool) {
    for w in batches.iter_mut() {
        let (dpa, rot_a, ia) = gather_states(states, &w.a);
        let (dpb, rot_b, ib) = gather_states(states, &w.b);
        let n = w.normal;
        let m = w.ma + w.mb;
        let g = Geometry4 {
            oa: w.oa,
            ob: w.ob,
            at_b: w.at_b,
        };
        for p in w.points[..w.count].iter_mut() {
            let (ra, rb, gap) = arms(p.ca0, p.cb0, &g, dpa, dpb, &rot_a, &rot_b);
            p.separation = p.separation0 + gap.dot(n);
            p.rna = ra.cross(n);
            p.rnb = rb.cross(n);
            p.ia = ia.mul_vec(p.rna);
            p.ib = ib.mul_vec(p.rnb);
            let k = m + p.rna.dot(p.ia) + p.rnb.dot(p.ib);
            p.normal_mass = F4::select(p.active, safe_inverse(k), F4::zero());
        }
        if block && w.count > 1 {
            let one = F4::splat(1.0);
            for i in 0..w.count {
                for j in i..w.count {
                    let (pi, pj) = (&w.points[i], &w.points[j]);
                    let both = pi.active.and(pj.active);
                    let kij = m + pi.rna.dot(pj.ia) + pi.rnb.dot(pj.ib);
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
            for (i, row) in reg.iter_mut().enumerate().take(w.count) {
                row[i] = row[i] * F4::splat(1.0 + BLOCK_REGULARIZATION);
            }
            invert_spd(&reg, w.count, &mut w.k_inv);
        }
        let f = &mut w.friction;
        let (ra, rb, _) = arms(f.ca0, f.cb0, &g, dpa, dpb, &rot_a, &rot_b);
        for k in 0..2 {
            let t = w.tangents[k];
            f.rta[k] = ra.cross(t);
            f.rtb[k] = rb.cross(t);
            f.ita[k] = ia.mul_vec(f.rta[k]);
            f.itb[k] = ib.mul_vec(f.rtb[k]);
            f.tangent_mass[k] = safe_inverse(m + f.rta[k].dot(f.ita[k]) + f.rtb[k].dot(f.itb[k]));
        }
        f.ina = ia.mul_vec(n);
        f.inb = ib.mul_vec(n);
        f.twist_mass = safe_inverse(n.dot(f.ina) + n.dot(f.inb));
    }
}

/// Relative velocity along `d` with angular Jacobians `ja`, `jb`.
#[inline(always)]
fn rel(va: V4, wa: V4, vb: V4, wb: V4, d: V4, ja: V4, jb: V4) -> F4 {
    d.dot(vb - va) + wb.dot(jb) - wa.dot(ja)
}

pub fn warm_start(vel: &mut [Velocity], batches: &[WideContact]) {
    for w in batches {
        let (mut va, mut wa) = gather(vel, &w.a);
        let (mut vb, mut wb) = gather(vel, &w.b);
        let mut lin = w.normal.scale(sum_impulses(w));
        let f = &w.friction;
        let mut ang_a = f.ina.scale(f.twist_impulse);
        let mut ang_b = f.inb.scale(f.twist_impulse);
        for p in &w.points[..w.count] {
            ang_a = ang_a.add_scaled(p.ia, p.impulse);
            ang_b = ang_b.add_scaled(p.ib, p.impulse);
        }
        for k in 0..2 {
            lin = lin.add_scaled(w.tangents[k], f.tangent_impulse[k]);
            ang_a = ang_a.add_scaled(f.ita[k], f.tangent_impulse[k]);
            ang_b = ang_b.add_scaled(f.itb[k], f.tangent_impulse[k]);
        }
        va = va.add_scaled(lin, -w.ma);
        wa = wa - ang_a;
        vb = vb.add_scaled(lin, w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.a, va, wa);
        scatter(vel, &w.b, vb, wb);
    }
}

#[inline(always)]
fn sum_impulses(w: &WideContact) -> F4 {
    w.points[..w.count].iter().fold(F4::zero(), |s, p| s + p.impulse)
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
    let zero = F4::zero();
    let one = F4::splat(1.0);
    let inv_h = F4::splat(inv_h);
    for w in batches.iter_mut() {
        let (mut va, mut wa) = gather(vel, &w.a);
        let (mut vb, mut wb) = gather(vel, &w.b);
        let n = w.normal;
        let count = w.count;
        // Per lane: rigid (relax), or soft with the dynamic or the static coefficients.
        let (rate, ms, is) = match bias {
            None => (zero, one, zero),
            Some(b) => {
                let stat = w.ma.gt(zero).and(w.mb.gt(zero));
                let pick = |d: f32, s: f32| F4::select(stat, F4::splat(d), F4::splat(s));
                (
                    pick(b.soft.bias_rate, b.soft_static.bias_rate),
                    pick(b.soft.mass_scale, b.soft_static.mass_scale),
                    pick(b.soft.impulse_scale, b.soft_static.impulse_scale),
                )
            }
        };
        let (max_push, slop) = bias.map_or((zero, zero), |b| (F4::splat(-b.max_push), F4::splat(b.slop)));
        let mut rhs = [zero; MAXP];
        let mut msp = [one; MAXP];
        let mut isp = [zero; MAXP];
        for i in 0..count {
            let p = &w.points[i];
            let spec = p.separation.gt(zero);
            let push = (rate * (p.separation + slop).min(zero)).max(max_push);
            let b = F4::select(spec, p.separation * inv_h, push);
            msp[i] = F4::select(spec, one, ms);
            isp[i] = F4::select(spec, zero, is);
            let v = rel(va, wa, vb, wb, n, p.rna, p.rnb) + b;
            rhs[i] = F4::select(p.active, v, zero);
        }
        // Solve K e = −rhs for e ≥ −(1 − is)λ/ms, then Δλ = ms·e − is·λ (soft update).
        let mut delta = [zero; MAXP];
        if count == 1 {
            let p = &w.points[0];
            let new = (p.impulse - msp[0] * p.normal_mass * rhs[0] - isp[0] * p.impulse).max(zero);
            delta[0] = new - p.impulse;
        } else {
            // Lanes touching without load and not approaching (side faces of neighbours) need
            // nothing: every impulse is zero and stays zero.
            let mut idle = F4::splat(f32::from_bits(u32::MAX));
            for (p, r) in w.points[..count].iter().zip(&rhs) {
                idle = idle.and(p.impulse.le(zero)).and(r.ge(zero));
            }
            // Exact solution with every point pushing: K e = −rhs, Δλ = ms·e − is·λ. (A clamped
            // exact solution is no good start: K of four coplanar points is nearly singular and
            // its exact solution may hold large self-cancelling parts.)
            let mut ok = F4::splat(f32::from_bits(u32::MAX));
            let mut lower = [zero; MAXP];
            for i in 0..count {
                let mut d = zero;
                for j in 0..count {
                    d = d - w.k_inv[i][j] * rhs[j];
                }
                let p = &w.points[i];
                // e may not go below this, or the point would pull.
                lower[i] = -((one - isp[i]) * p.impulse / msp[i]);
                let e = F4::select(idle, zero, d);
                ok = ok.and(e.ge(lower[i]));
                delta[i] = msp[i] * e - isp[i] * p.impulse;
            }
            if ok.bits() != 0b1111 {
                // Some lane has a point that would pull: projected Gauss–Seidel on K there.
                let mut e = [zero; MAXP];
                for it in 0..BLOCK_ITERATIONS {
                    for s in 0..count {
                        let i = if forward ^ (it % 2 == 1) { s } else { count - 1 - s };
                        let mut r = rhs[i];
                        for j in 0..count {
                            r = r + w.k[i][j] * e[j];
                        }
                        let p = &w.points[i];
                        e[i] = F4::select(p.active, (e[i] - p.normal_mass * r).max(lower[i]), zero);
                    }
                }
                for i in 0..count {
                    let soft = msp[i] * e[i] - isp[i] * w.points[i].impulse;
                    delta[i] = F4::select(ok, delta[i], soft);
                }
            }
        }
        let (mut lin, mut ang_a, mut ang_b, mut total) = (zero, V4::zero(), V4::zero(), zero);
        for (p, d) in w.points[..count].iter_mut().zip(delta) {
            p.impulse = p.impulse + d;
            p.max_impulse = p.max_impulse.max(d);
            total = total + p.impulse;
            lin = lin + d;
            ang_a = ang_a.add_scaled(p.ia, d);
            ang_b = ang_b.add_scaled(p.ib, d);
        }
        va = va.add_scaled(n, -(w.ma * lin));
        wa = wa - ang_a;
        vb = vb.add_scaled(n, w.mb * lin);
        wb = wb + ang_b;

        // Patch friction: the static coefficient while the patch sticks, dynamic once it slides.
        let f = &mut w.friction;
        let old = f.tangent_impulse;
        let mut new = [zero; 2];
        for k in 0..2 {
            let vt = rel(va, wa, vb, wb, w.tangents[k], f.rta[k], f.rtb[k]);
            new[k] = old[k] - f.tangent_mass[k] * vt;
        }
        let old_twist = f.twist_impulse;
        let twist = old_twist - f.twist_mass * (wb - wa).dot(n);
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
        let mut ang_a = f.ina.scale(d_twist);
        let mut ang_b = f.inb.scale(d_twist);
        for k in 0..2 {
            let d = new[k] - old[k];
            lin = lin.add_scaled(w.tangents[k], d);
            ang_a = ang_a.add_scaled(f.ita[k], d);
            ang_b = ang_b.add_scaled(f.itb[k], d);
        }
        f.tangent_impulse = new;
        f.twist_impulse = twist;
        va = va.add_scaled(lin, -w.ma);
        wa = wa - ang_a;
        vb = vb.add_scaled(lin, w.mb);
        wb = wb + ang_b;
        scatter(vel, &w.a, va, wa);
        scatter(vel, &w.b, vb, wb);
    }
}

/// Bounces: points that approached faster than `threshold` and pushed leave at −e times their
/// approach speed.
pub fn restitution(vel: &mut [Velocity], batches: &mut [WideContact], threshold: f32) {
    let zero = F4::zero();
    for w in batches.iter_mut().filter(|w| w.has_restitution) {
        let (mut va, mut wa) = gather(vel, &w.a);
        let (mut vb, mut wb) = gather(vel, &w.b);
        let n = w.normal;
        for p in w.points[..w.count].iter_mut() {
            let bounce = p
                .active
                .and((-p.relative_velocity).gt(F4::splat(threshold)))
                .and(p.max_impulse.gt(zero));
            if bounce.bits() == 0 {
                continue;
            }
            let vn = rel(va, wa, vb, wb, n, p.rna, p.rnb);
            let new = (p.impulse - p.normal_mass * (vn + w.restitution * p.relative_velocity)).max(zero);
            let d = F4::select(bounce, new - p.impulse, zero);
            p.impulse = p.impulse + d;
            p.max_impulse = p.max_impulse.max(d);
            va = va.add_scaled(n, -(w.ma * d));
            wa = wa.add_scaled(p.ia, -d);
            vb = vb.add_scaled(n, w.mb * d);
            wb = wb.add_scaled(p.ib, d);
        }
        scatter(vel, &w.a, va, wa);
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
        let maxes: [[f32; 4]; MAXP] = std::array::from_fn(|p| w.points[p].max_impulse.to_array());
        for lane in 0..4 {
            if w.src[lane] == EMPTY {
                continue;
            }
            let c = &mut constraints[w.src[lane] as usize];
            for p in 0..c.count {
                c.points[p].normal_impulse = impulses[p][lane];
                c.points[p].max_normal_impulse = maxes[p][lane];
            }
            c.friction.tangent_impulse = [t0[lane], t1[lane]];
            c.friction.twist_impulse = tw[lane];
            c.friction.sliding = sl & (1 << lane) != 0;
        }
    }
}
