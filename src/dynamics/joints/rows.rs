//! Joint rows in one form: a [`Row`] is one scalar constraint's Jacobian on the two bodies,
//! an [`Eq`] is a joint's equality rows (the point lock, the axis alignment, the angular lock,
//! the slider's cross-axis rows, the rigid distance) with their position errors and where
//! their accumulated impulses live, and [`Spd`] is a small dense Cholesky factor.
//!
//! Two uses:
//!
//! * A joint's equality rows are solved together as one block (`Eq::solve_block`) when the
//!   joint is not in the direct tree solve (`tree.rs`), e.g. it closes a loop.
//! * A limit, motor or spring row is **coupled** with its joint's equality rows
//!   (`Eq::couple`): the row is replaced by itself plus the equality impulses that keep the
//!   equality rows' velocities unchanged (`row − K_El·K_EE⁻¹·E`), whose effective mass is the
//!   Schur complement `1 / (K_ll − K_lE K_EE⁻¹ K_El)`. A hinge limit then sees the arm's inertia
//!   about the hinge, not about its centre of mass: solved alone, the limit row's impulse is
//!   undone by the point row that follows it and the arm overshoots by the inertia ratio.

// Small dense linear algebra reads best with index loops over rows and columns.
#![allow(clippy::needless_range_loop)]

use super::solver::{Bodies, Ctx, Frames};
use super::{Impulses, JointKind};
use crate::math::Vec3;

/// Most equality rows a joint has (fixed: 3 linear + 3 angular).
pub const MAX_ROWS: usize = 6;

/// One scalar row: `cdot = la·va + aa·wa + lb·vb + ab·wb`; an impulse `λ` changes the
/// velocities by `M⁻¹ Jᵀ λ`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Row {
    pub la: Vec3,
    pub aa: Vec3,
    pub lb: Vec3,
    pub ab: Vec3,
}

impl Row {
    /// The anchors' relative velocity along unit `n`: B's anchor at `rb` from its centre,
    /// A's at `arm_a`.
    #[inline]
    pub fn linear(n: Vec3, arm_a: Vec3, rb: Vec3) -> Row {
        Row {
            la: -n,
            aa: -arm_a.cross(n),
            lb: n,
            ab: rb.cross(n),
        }
    }

    /// Relative angular velocity `wb − wa` along unit `e`.
    #[inline]
    pub fn angular(e: Vec3) -> Row {
        Row {
            la: Vec3::ZERO,
            aa: -e,
            lb: Vec3::ZERO,
            ab: e,
        }
    }

    #[inline]
    pub fn dot(&self, o: &Row) -> f32 {
        self.la.dot(o.la) + self.aa.dot(o.aa) + self.lb.dot(o.lb) + self.ab.dot(o.ab)
    }

    #[inline]
    pub fn neg(&self) -> Row {
        Row {
            la: -self.la,
            aa: -self.aa,
            lb: -self.lb,
            ab: -self.ab,
        }
    }

    /// `self + s·o`.
    #[inline]
    pub fn add_scaled(&self, o: &Row, s: f32) -> Row {
        Row {
            la: self.la + s * o.la,
            aa: self.aa + s * o.aa,
            lb: self.lb + s * o.lb,
            ab: self.ab + s * o.ab,
        }
    }
}

impl Bodies {
    /// The row's velocity.
    #[inline]
    pub fn cdot(&self, r: &Row) -> f32 {
        r.la.dot(self.va) + r.aa.dot(self.wa) + r.lb.dot(self.vb) + r.ab.dot(self.wb)
    }

    /// Applies impulse `l` along the row.
    #[inline]
    pub fn apply_row(&mut self, r: &Row, l: f32) {
        self.va += (self.ma * l) * r.la;
        self.wa += self.ia * (l * r.aa);
        self.vb += (self.mb * l) * r.lb;
        self.wb += self.ib * (l * r.ab);
    }

    /// `M⁻¹ Jᵀ` of the row: the velocity change per unit impulse.
    #[inline]
    pub fn response(&self, r: &Row) -> Row {
        Row {
            la: self.ma * r.la,
            aa: self.ia * r.aa,
            lb: self.mb * r.lb,
            ab: self.ib * r.ab,
        }
    }
}

/// Where a row's accumulated impulse is kept in [`Impulses`]: one component of the linear or
/// angular vector, or the axial scalar. Each row owns one scalar, so an impulse stays on its
/// row when the row's direction turns: a row along a body axis (the slider's cross-axis
/// rows, the hinge's alignment rows) keeps its impulse as a coordinate in that body frame.
/// Booked as a world vector, the part of an old impulse that had turned out of the rows'
/// span was never solved again and the warm start applied it every sub-step for good — a
/// slider set up 45° off its rest pose was driven along its free axis to 1,300 m/s.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Slot {
    /// Component `k` of `Impulses::linear`.
    Linear(u8),
    /// Component `k` of `Impulses::angular`.
    Angular(u8),
    #[default]
    Axial,
}

impl Slot {
    /// The accumulated impulse of a row booked here.
    #[inline]
    pub fn get(self, imp: &Impulses) -> f32 {
        match self {
            Slot::Linear(k) => imp.linear[k as usize],
            Slot::Angular(k) => imp.angular[k as usize],
            Slot::Axial => imp.axial,
        }
    }

    /// Adds `x` to the accumulated impulse of a row booked here.
    #[inline]
    pub fn add(self, imp: &mut Impulses, x: f32) {
        match self {
            Slot::Linear(k) => imp.linear[k as usize] += x,
            Slot::Angular(k) => imp.angular[k as usize] += x,
            Slot::Axial => imp.axial += x,
        }
    }
}

/// A joint's equality rows now.
#[derive(Clone, Copy, Debug, Default)]
pub struct Eq {
    pub n: usize,
    pub rows: [Row; MAX_ROWS],
    /// Position error of each row (the row drives it to 0).
    pub err: [f32; MAX_ROWS],
    pub slots: [Slot; MAX_ROWS],
}

impl Eq {
    #[inline]
    fn push(&mut self, row: Row, err: f32, slot: Slot) {
        self.rows[self.n] = row;
        self.err[self.n] = err;
        self.slots[self.n] = slot;
        self.n += 1;
    }

    /// The point lock: three rows along the world axes (impulse: `Impulses::linear`, a
    /// world vector).
    fn point(&mut self, f: &Frames) {
        for (k, e) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            self.push(Row::linear(e, f.ra, f.rb), f.d[k], Slot::Linear(k as u8));
        }
    }

    /// The angular lock: three rows along the world axes (impulse: `Impulses::angular`, a
    /// world vector).
    fn angular_lock(&mut self, f: &Frames) {
        let err = f.rotation_error();
        for (k, e) in [Vec3::X, Vec3::Y, Vec3::Z].into_iter().enumerate() {
            self.push(Row::angular(e), err[k], Slot::Angular(k as u8));
        }
    }

    /// The equality rows of a joint of `kind` with frames `f`.
    pub fn of(kind: &JointKind, f: &Frames) -> Eq {
        let mut eq = Eq::default();
        match kind {
            JointKind::Ball(_) => eq.point(f),
            JointKind::Hinge(_) => {
                eq.point(f);
                // The Z axes stay aligned: rows along A's X and Y with the error `za × zb`.
                let (za, zb) = f.axes();
                let err = za.cross(zb);
                for (k, e) in f.cross_axes().into_iter().enumerate() {
                    eq.push(Row::angular(e), err.dot(e), Slot::Angular(k as u8));
                }
            }
            JointKind::Fixed => {
                eq.point(f);
                eq.angular_lock(f);
            }
            JointKind::Slider(_) => {
                // B's anchor stays on A's Z axis (`SliderRows`).
                let sr = f.slider();
                for k in 0..2 {
                    let e = sr.axes[k];
                    let row = Row::linear(e, sr.lever_a, sr.lever_b);
                    eq.push(row, e.dot(sr.offset), Slot::Linear(k as u8));
                }
                eq.angular_lock(f);
            }
            JointKind::Distance(p) if !p.enable_spring => {
                let (n, len) = super::distance::axis(f);
                eq.push(Row::linear(n, f.ra, f.rb), len - p.length, Slot::Axial);
            }
            JointKind::Distance(_) => {}
        }
        eq
    }

    /// The accumulated impulses of the rows.
    #[inline]
    pub fn acc(&self, imp: &Impulses) -> [f32; MAX_ROWS] {
        let mut a = [0.0; MAX_ROWS];
        for i in 0..self.n {
            a[i] = self.slots[i].get(imp);
        }
        a
    }

    /// Adds `s·d[i]` to each row's accumulated impulse.
    #[inline]
    pub fn add(&self, imp: &mut Impulses, d: &[f32; MAX_ROWS], s: f32) {
        for i in 0..self.n {
            self.slots[i].add(imp, s * d[i]);
        }
    }

    /// `K = J M⁻¹ Jᵀ` of the rows with the two bodies' masses, factored; `None` when singular
    /// (no rows, or bodies without mass on them).
    pub fn factor(&self, b: &Bodies) -> Option<Spd> {
        if self.n == 0 {
            return None;
        }
        let mut k = [[0.0f32; MAX_ROWS]; MAX_ROWS];
        for i in 0..self.n {
            let ri = b.response(&self.rows[i]);
            for j in 0..=i {
                let v = ri.dot(&self.rows[j]);
                k[i][j] = v;
                k[j][i] = v;
            }
        }
        if !b.locked {
            return Spd::factor(&k, self.n, false);
        }
        // How large each row would be on the bodies without locks: one that the locks leave
        // almost nothing of is left out (`Spd::factor_locked`).
        let mut free = [0.0f32; MAX_ROWS];
        for (i, f) in free.iter_mut().enumerate().take(self.n) {
            *f = self.free_diag(b, i);
        }
        Some(Spd::factor_locked(&k, self.n, &free))
    }

    /// Solves the rows together as one block (for a joint outside the tree solve): rigid with
    /// the full `K⁻¹` in the relax sweep, the stiff soft response in the biased sweep.
    pub fn solve_block(&self, k: &Spd, b: &mut Bodies, imp: &mut Impulses, ctx: &Ctx) {
        let bias = self.bias(b, ctx);
        let mut r = [0.0f32; MAX_ROWS];
        for i in 0..self.n {
            r[i] = -(b.cdot(&self.rows[i]) + bias[i]);
        }
        if k.any_dropped() {
            // A row left out (locked axes) gives up its accumulated impulse first: kept, the
            // warm start would push along it every sub-step with nothing to answer it; taken
            // out before the solve, the rows kept answer for it.
            let acc = self.acc(imp);
            let mut d = [0.0f32; MAX_ROWS];
            for i in 0..self.n {
                if k.dropped(i) {
                    d[i] = -acc[i];
                    b.apply_row(&self.rows[i], d[i]);
                }
            }
            self.add(imp, &d, 1.0);
            for i in 0..self.n {
                r[i] = -(b.cdot(&self.rows[i]) + bias[i]);
            }
        }
        let x = k.solve(&r);
        let acc = self.acc(imp);
        let mut d = [0.0f32; MAX_ROWS];
        for i in 0..self.n {
            if k.dropped(i) {
                continue;
            }
            d[i] = ctx.respond(x[i], acc[i]);
            b.apply_row(&self.rows[i], d[i]);
        }
        self.add(imp, &d, 1.0);
    }

    /// The diagonal row `i` would have on the bodies without locks (mean inverse inertia).
    fn free_diag(&self, b: &Bodies, i: usize) -> f32 {
        let r = &self.rows[i];
        b.free_a.0 * r.la.length_squared()
            + b.free_a.1 * r.aa.length_squared()
            + b.free_b.0 * r.lb.length_squared()
            + b.free_b.1 * r.ab.length_squared()
    }

    /// The rows' velocity bias. On bodies with locked axes a row the locks leave less than
    /// [`BIAS_FREE_ROW`] of its size corrects its error proportionally slower: its error is
    /// then mostly along locked axes (a hinge's alignment row nearly along a locked axis: the
    /// tilt about it that turns about two free axes left behind), which the bodies cannot
    /// correct, and through the little freedom left the full bias spun them fast.
    fn bias(&self, b: &Bodies, ctx: &Ctx) -> [f32; MAX_ROWS] {
        let mut bias = [0.0f32; MAX_ROWS];
        for i in 0..self.n {
            bias[i] = ctx.rigid_bias(self.err[i]);
            if b.locked && bias[i] != 0.0 {
                let free = self.free_diag(b, i);
                let kept = b.response(&self.rows[i]).dot(&self.rows[i]);
                if kept < BIAS_FREE_ROW * free {
                    bias[i] *= (kept / (BIAS_FREE_ROW * free)).max(0.0);
                }
            }
        }
        bias
    }

    /// `row` coupled with these rows (see the module notes); with no factor, `row` alone.
    pub fn couple(&self, k: Option<&Spd>, b: &Bodies, row: Row) -> Coupled {
        let resp = b.response(&row);
        let k_ll = resp.dot(&row);
        let mut c = Coupled {
            row,
            comp: [0.0; MAX_ROWS],
            mass: 0.0,
        };
        let mut k_schur = k_ll;
        if let Some(k) = k {
            let mut k_el = [0.0f32; MAX_ROWS];
            for i in 0..self.n {
                k_el[i] = resp.dot(&self.rows[i]);
            }
            let y = k.solve(&k_el);
            for i in 0..self.n {
                c.comp[i] = -y[i];
                c.row = c.row.add_scaled(&self.rows[i], -y[i]);
                k_schur -= k_el[i] * y[i];
            }
        }
        // Rounding can leave a hair above zero where the rows leave the coupled row no
        // freedom (a limit about an axis the equality rows already lock).
        c.mass = if k_schur > 1.0e-6 * k_ll && k_schur > 0.0 {
            1.0 / k_schur
        } else {
            0.0
        };
        c
    }
}

/// A limit, motor or spring row coupled with its joint's equality rows.
#[derive(Clone, Copy, Debug)]
pub struct Coupled {
    /// The row plus `comp` times the equality rows.
    pub row: Row,
    /// Equality impulses per unit impulse on the row.
    pub comp: [f32; MAX_ROWS],
    /// Effective mass of the coupled row (the Schur complement).
    pub mass: f32,
}

impl Coupled {
    /// The same row with the opposite sign (an upper limit after a lower one).
    #[inline]
    pub fn neg(&self) -> Coupled {
        let mut comp = self.comp;
        for c in comp.iter_mut() {
            *c = -*c;
        }
        Coupled {
            row: self.row.neg(),
            comp,
            mass: self.mass,
        }
    }

    /// Applies impulse `l` along the coupled row and books the equality part on `imp`.
    #[inline]
    pub fn apply(&self, eq: &Eq, b: &mut Bodies, imp: &mut Impulses, l: f32) {
        b.apply_row(&self.row, l);
        eq.add(imp, &self.comp, l);
    }
}

/// Below this fraction of what it would be without locks, a row's diagonal slows the
/// correction of its error in proportion (`Eq::bias`).
pub const BIAS_FREE_ROW: f32 = 0.1;

/// Below this fraction of its own diagonal, a row's pivot (what is left of it once the rows
/// taken before are eliminated) marks it as dependent on them: at most a tenth of the row's
/// direction (in the bodies' mass metric) is new, so its error is answered with at most ten
/// times its bias speed. Only bodies with locked axes (`body::LOCK_*`) have such rows; with
/// 1e-4 (a hundred times the speed) random locked chains of four to six joints gained
/// hundreds of joules in a step (`tests/locked_joints.rs`, seeds 40, 80, 97).
const DEPENDENT_PIVOT: f32 = 1.0e-2;
/// Below this fraction of what it would be without locks, a row's diagonal marks it as one
/// the locks leave (nearly) nothing of (`Spd::factor_locked`): two bodies that may only turn,
/// hinged where their arms are nearly in line, cannot move the anchors along the line, and
/// the rounding-level error there spun a 0.24 kg link to 257 rad/s in one step. Not more: a
/// slider between bodies that may only translate has rows whose lever on the other body
/// (where they act, `SliderRows`) is a hundredth of their size without locks.
pub const FREE_ROW: f32 = 1.0e-3;
/// Below this fraction of the block's largest diagonal, any row counts as one the bodies
/// cannot move along.
const NULL_ROW: f32 = 1.0e-9;

/// Cholesky factor `L Lᵀ` of a small symmetric positive definite matrix (size `n <= 6`), with
/// the reciprocals of the diagonal. With `drop_weak` the rows are taken largest pivot first
/// and the (nearly) dependent ones are left out.
#[derive(Clone, Copy, Debug)]
pub struct Spd {
    n: usize,
    l: [[f32; MAX_ROWS]; MAX_ROWS],
    inv_diag: [f32; MAX_ROWS],
    /// Row `i` of the factor is row `perm[i]` of the matrix.
    perm: [usize; MAX_ROWS],
    /// Rows of the factor kept (the others, left out, get zero).
    kept: usize,
}

impl Spd {
    /// `None` when `k` is not positive definite (to a relative tolerance).
    ///
    /// With `drop_weak` (bodies with locked axes) the rows that make it singular are left out
    /// instead (their impulses stay zero): diagonal pivoting takes the remaining row with the
    /// largest pivot relative to its diagonal, and stops once that row is dependent on those
    /// taken. Locks make rows dependent in exact arithmetic: a hinge's two alignment rows on
    /// bodies that may turn about one axis across the hinge both act about that one axis.
    /// Taken in their given order, whichever came first was kept with a pivot as small as
    /// the sine of the link's angle to a world axis, the other one's pivot was rounding, and
    /// the angular error the bodies cannot correct came back as a huge spin.
    pub fn factor(k: &[[f32; MAX_ROWS]; MAX_ROWS], n: usize, drop_weak: bool) -> Option<Spd> {
        let mut s = Spd {
            n,
            l: [[0.0; MAX_ROWS]; MAX_ROWS],
            inv_diag: [0.0; MAX_ROWS],
            perm: [0, 1, 2, 3, 4, 5],
            kept: n,
        };
        let scale = (0..n).map(|i| k[i][i]).fold(0.0f32, f32::max);
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        if drop_weak {
            // Rows judged by their dependence and against the largest.
            s.factor_pivoted(k, &[0.0; MAX_ROWS]);
            return (s.kept > 0).then_some(s);
        }
        for j in 0..n {
            let mut d = k[j][j];
            for p in 0..j {
                d -= s.l[j][p] * s.l[j][p];
            }
            if d <= 1.0e-7 * scale {
                return None;
            }
            let djj = d.sqrt();
            s.l[j][j] = djj;
            s.inv_diag[j] = 1.0 / djj;
            for i in j + 1..n {
                let mut v = k[i][j];
                for p in 0..j {
                    v -= s.l[i][p] * s.l[j][p];
                }
                s.l[i][j] = v * s.inv_diag[j];
            }
        }
        Some(s)
    }

    /// The factor of `K` for bodies with locked axes, `free[i]` the diagonal row `i` would have
    /// on the bodies without locks (mean inverse inertia): `factor` with `drop_weak`, where
    /// also a row the locks leave less than [`FREE_ROW`] of is left out. Such a row (a
    /// hinge's alignment row nearly along a locked axis, once the links have tilted a little
    /// about a free one) asks the bodies to correct an error nearly all along the locked axis
    /// through the little that is free of it, and the biased sweep turned a link by radians
    /// within a step.
    pub fn factor_locked(k: &[[f32; MAX_ROWS]; MAX_ROWS], n: usize, free: &[f32; MAX_ROWS]) -> Spd {
        let mut s = Spd {
            n,
            l: [[0.0; MAX_ROWS]; MAX_ROWS],
            inv_diag: [0.0; MAX_ROWS],
            perm: [0, 1, 2, 3, 4, 5],
            kept: n,
        };
        s.factor_pivoted(k, free);
        s
    }

    /// The pivoted factor: `perm`, `kept` and the first `kept` rows of `l` (in pivot order,
    /// over the permuted matrix).
    fn factor_pivoted(&mut self, k: &[[f32; MAX_ROWS]; MAX_ROWS], free: &[f32; MAX_ROWS]) {
        let n = self.n;
        let scale = (0..n).map(|i| k[i][i]).filter(|x| x.is_finite()).fold(0.0f32, f32::max);
        // Residual pivots of the rows not yet taken, updated as rows are taken.
        let mut d = [0.0f32; MAX_ROWS];
        for i in 0..n {
            d[i] = k[i][i];
        }
        for j in 0..n {
            // The row most independent of those taken, relative to its own size.
            let mut best = j;
            let mut best_ratio = -1.0f32;
            for c in j..n {
                let i = self.perm[c];
                let diag = k[i][i];
                let usable =
                    diag > NULL_ROW * scale && diag > FREE_ROW * free[i] && diag.is_finite() && free[i].is_finite();
                let ratio = if usable { d[c] / diag } else { 0.0 };
                if ratio > best_ratio {
                    best = c;
                    best_ratio = ratio;
                }
            }
            if best_ratio <= DEPENDENT_PIVOT {
                self.kept = j;
                return;
            }
            self.perm.swap(j, best);
            d.swap(j, best);
            self.l.swap(j, best);
            let djj = d[j].sqrt();
            self.l[j][j] = djj;
            self.inv_diag[j] = 1.0 / djj;
            let pj = self.perm[j];
            for c in j + 1..n {
                let i = self.perm[c];
                let mut v = k[i][pj];
                for p in 0..j {
                    v -= self.l[c][p] * self.l[j][p];
                }
                let lij = v * self.inv_diag[j];
                self.l[c][j] = lij;
                d[c] -= lij * lij;
            }
        }
        self.kept = n;
    }

    /// Row `i` of the matrix was left out (`drop_weak`).
    #[inline]
    pub fn dropped(&self, i: usize) -> bool {
        self.perm[self.kept..self.n].contains(&i)
    }

    /// Whether any row was left out.
    #[inline]
    pub fn any_dropped(&self) -> bool {
        self.kept < self.n
    }

    /// `K⁻¹ b` (rows left out get zero, and their entries of `b` are not read).
    pub fn solve(&self, b: &[f32; MAX_ROWS]) -> [f32; MAX_ROWS] {
        let m = self.kept;
        let mut y = [0.0f32; MAX_ROWS];
        for i in 0..m {
            let mut v = b[self.perm[i]];
            for p in 0..i {
                v -= self.l[i][p] * y[p];
            }
            y[i] = v * self.inv_diag[i];
        }
        for i in (0..m).rev() {
            let mut v = y[i];
            for p in i + 1..m {
                v -= self.l[p][i] * y[p];
            }
            y[i] = v * self.inv_diag[i];
        }
        let mut x = [0.0f32; MAX_ROWS];
        for i in 0..m {
            x[self.perm[i]] = y[i];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves_and_rejects_singular() {
        let mut k = [[0.0f32; 6]; 6];
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]];
        for i in 0..3 {
            for j in 0..3 {
                k[i][j] = a[i][j];
            }
        }
        let s = Spd::factor(&k, 3, false).unwrap();
        let x = s.solve(&[1.0, 2.0, 3.0, 0.0, 0.0, 0.0]);
        for i in 0..3 {
            let r: f32 = (0..3).map(|j| a[i][j] * x[j]).sum();
            assert!((r - [1.0, 2.0, 3.0][i]).abs() < 1e-5);
        }
        k[2] = k[1];
        k[0][2] = k[0][1];
        k[1][2] = k[1][1];
        k[2][2] = k[1][1];
        assert!(Spd::factor(&k, 3, false).is_none());
        // Dropping the dependent row solves the other two.
        let s = Spd::factor(&k, 3, true).unwrap();
        let x = s.solve(&[1.0, 2.0, 2.0, 0.0, 0.0, 0.0]);
        assert_eq!(x[2], 0.0);
        assert!((4.0 * x[0] + x[1] - 1.0).abs() < 1e-5 && (x[0] + 3.0 * x[1] - 2.0).abs() < 1e-5);
    }
}
