//! The rods of the particle stage, solved exactly together.
//!
//! Gauss–Seidel moves a correction along a chain one rod per sweep, so a long rope under a
//! heavy load stretches unless it runs hundreds of sweeps. Rods are equalities, so instead
//! all of them are solved at once: with `J` their Jacobian (row i acts along the rod's
//! direction `n_i` on its two ends) and `W` the inverse masses of the particles and coupled
//! bodies (with their inertia at the arms), the impulses solve `(J W Jᵀ) λ = r`.
//!
//! `A = J W Jᵀ` couples two rods when they share a particle or body. The rows are ordered
//! by reverse Cuthill–McKee (a breadth-first order from a peripheral rod), which gives a
//! chain bandwidth 1 and a net bandwidth about its width, and `A` is factored as a band
//! `L D Lᵀ` in `O(n b²)`. Used at the velocity level (impulses that make every rod's
//! length rate exactly zero) and at the position level (Newton steps of the projection to
//! the exact lengths). A structure wider than `MAX_BAND` falls back to Gauss–Seidel.

use super::constraint::{Constraint, Kind, Side, Sys};

/// Widest band solved directly.
pub const MAX_BAND: usize = 48;

#[derive(Default)]
pub(crate) struct RodBlock {
    /// Constraint index of each row, in band order.
    rows: Vec<u32>,
    /// (side key, row in band order, +1/-1 for side a/b), sorted by key: rows sharing a
    /// key are coupled.
    touch: Vec<(u32, u32, i8)>,
    band: usize,
    /// Strictly lower band of L, `band` entries per row, and D.
    lower: Vec<f64>,
    diag: Vec<f64>,
    x: Vec<f64>,
    // Ordering scratch.
    adj_start: Vec<u32>,
    adj: Vec<u32>,
    order: Vec<u32>,
    pos: Vec<u32>,
    seen: Vec<bool>,
    tmp: Vec<u32>,
}

#[inline]
fn side_key(s: &Side, particles: usize) -> Option<u32> {
    match *s {
        Side::Particle(i) => Some(i),
        Side::Body { c, .. } => Some(particles as u32 + c),
        Side::Fixed { .. } => None,
    }
}

impl RodBlock {
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Picks the rods of `constraints` (marking them `blocked`) and orders them. Returns
    /// false (nothing blocked) when there are none or the band would be too wide.
    pub fn build(&mut self, constraints: &mut [Constraint], particles: usize) -> bool {
        self.rows.clear();
        self.touch.clear();
        let candidates = constraints
            .iter()
            .enumerate()
            .filter(|(_, c)| c.kind == Kind::Rod && c.mass > 0.0)
            .map(|(i, _)| i as u32);
        self.rows.extend(candidates);
        let n = self.rows.len();
        if n == 0 {
            return false;
        }
        // Row adjacency (in candidate numbering) through shared sides.
        for (r, &ci) in self.rows.iter().enumerate() {
            let c = &constraints[ci as usize];
            for (s, sign) in [(&c.a, 1i8), (&c.b, -1i8)] {
                if let Some(k) = side_key(s, particles) {
                    self.touch.push((k, r as u32, sign));
                }
            }
        }
        self.touch.sort_unstable();
        self.adj_start.clear();
        self.adj_start.resize(n + 1, 0);
        for_each_pair(&self.touch, |i, j| {
            self.adj_start[i as usize + 1] += 1;
            self.adj_start[j as usize + 1] += 1;
        });
        for k in 0..n {
            self.adj_start[k + 1] += self.adj_start[k];
        }
        self.adj.clear();
        self.adj.resize(self.adj_start[n] as usize, 0);
        self.pos.clear();
        self.pos.extend_from_slice(&self.adj_start[..n]);
        {
            let (adj, fill) = (&mut self.adj, &mut self.pos);
            for_each_pair(&self.touch, |i, j| {
                adj[fill[i as usize] as usize] = j;
                fill[i as usize] += 1;
                adj[fill[j as usize] as usize] = i;
                fill[j as usize] += 1;
            });
        }
        self.reverse_cuthill_mckee(n);
        // pos[candidate] = band position; bandwidth.
        self.pos.clear();
        self.pos.resize(n, 0);
        for (k, &r) in self.order.iter().enumerate() {
            self.pos[r as usize] = k as u32;
        }
        let mut band = 0usize;
        for r in 0..n {
            for e in self.adj_start[r]..self.adj_start[r + 1] {
                let o = self.adj[e as usize] as usize;
                band = band.max((self.pos[r] as i64 - self.pos[o] as i64).unsigned_abs() as usize);
            }
        }
        if band > MAX_BAND {
            self.rows.clear();
            return false;
        }
        self.band = band;
        // Renumber rows and touches into band order.
        for t in self.touch.iter_mut() {
            t.1 = self.pos[t.1 as usize];
        }
        self.tmp.clear();
        self.tmp.extend(self.order.iter().map(|&r| self.rows[r as usize]));
        std::mem::swap(&mut self.rows, &mut self.tmp);
        for &ci in &self.rows {
            constraints[ci as usize].blocked = true;
        }
        self.lower.clear();
        self.lower.resize(n * band.max(1), 0.0);
        self.diag.clear();
        self.diag.resize(n, 0.0);
        self.x.clear();
        self.x.resize(n, 0.0);
        true
    }

    fn reverse_cuthill_mckee(&mut self, n: usize) {
        self.order.clear();
        self.seen.clear();
        self.seen.resize(n, false);
        let degree = |r: usize, s: &[u32]| s[r + 1] - s[r];
        while self.order.len() < n {
            // Start each component at an unvisited row of least degree (a chain's end).
            let start = (0..n)
                .filter(|&r| !self.seen[r])
                .min_by_key(|&r| (degree(r, &self.adj_start), r))
                .expect("an unvisited row");
            self.seen[start] = true;
            let mut head = self.order.len();
            self.order.push(start as u32);
            while head < self.order.len() {
                let r = self.order[head] as usize;
                head += 1;
                let first = self.order.len();
                for e in self.adj_start[r]..self.adj_start[r + 1] {
                    let o = self.adj[e as usize] as usize;
                    if !self.seen[o] {
                        self.seen[o] = true;
                        self.order.push(o as u32);
                    }
                }
                let adj_start = &self.adj_start;
                self.order[first..].sort_unstable_by_key(|&o| (degree(o as usize, adj_start), o));
            }
        }
        self.order.reverse();
    }

    /// Fills `A = J W Jᵀ` for the rods' current directions and arms and factors it.
    fn factor(&mut self, constraints: &[Constraint], sys: &Sys) {
        let (n, b) = (self.rows.len(), self.band);
        self.lower.iter_mut().for_each(|v| *v = 0.0);
        for (p, &ci) in self.rows.iter().enumerate() {
            let c = &constraints[ci as usize];
            let k = sys.inv_mass(&c.a, c.ra, c.n) + sys.inv_mass(&c.b, c.rb, c.n);
            self.diag[p] = k as f64 * (1.0 + 1.0e-6);
        }
        // Off-diagonal entries: every pair of rods sharing a side.
        let (rows, lower) = (&self.rows, &mut self.lower);
        let mut k = 0;
        while k < self.touch.len() {
            let key = self.touch[k].0;
            let mut end = k + 1;
            while end < self.touch.len() && self.touch[end].0 == key {
                end += 1;
            }
            for x in k..end {
                for y in x + 1..end {
                    let (_, px, sx) = self.touch[x];
                    let (_, py, sy) = self.touch[y];
                    if px == py {
                        continue; // a rod from a particle to itself
                    }
                    let (ci, cj) = (
                        &constraints[rows[px as usize] as usize],
                        &constraints[rows[py as usize] as usize],
                    );
                    let (si, ri) = if sx > 0 { (&ci.a, ci.ra) } else { (&ci.b, ci.rb) };
                    let rj = if sy > 0 { cj.ra } else { cj.rb };
                    let v = (sx as f32) * (sy as f32) * sys.coupling(si, ri, ci.n, rj, cj.n);
                    let (hi, lo) = if px > py { (px, py) } else { (py, px) };
                    lower[hi as usize * b + b + lo as usize - hi as usize] += v as f64;
                }
            }
            k = end;
        }
        // Band LDLᵀ.
        for p in 0..n {
            let p0 = p.saturating_sub(b);
            for q in p0..p {
                let mut s = self.lower[p * b + b + q - p];
                for kk in p0.max(q.saturating_sub(b))..q {
                    s -= self.lower[p * b + b + kk - p] * self.lower[q * b + b + kk - q] * self.diag[kk];
                }
                self.lower[p * b + b + q - p] = s / self.diag[q];
            }
            let a = self.diag[p];
            let mut d = a;
            for kk in p0..p {
                let l = self.lower[p * b + b + kk - p];
                d -= l * l * self.diag[kk];
            }
            self.diag[p] = d.max(1.0e-6 * a).max(f64::MIN_POSITIVE);
        }
    }

    /// Solves `L D Lᵀ x = x` in place.
    fn substitute(&mut self) {
        let (n, b) = (self.rows.len(), self.band);
        for p in 0..n {
            let mut s = self.x[p];
            for q in p.saturating_sub(b)..p {
                s -= self.lower[p * b + b + q - p] * self.x[q];
            }
            self.x[p] = s;
        }
        for p in 0..n {
            self.x[p] /= self.diag[p];
        }
        for p in (0..n).rev() {
            let mut s = self.x[p];
            for q in p + 1..(p + b + 1).min(n) {
                s -= self.lower[q * b + b + p - q] * self.x[q];
            }
            self.x[p] = s;
        }
    }

    /// Impulses that bring every rod's length rate to zero (given everything else).
    pub fn solve_velocity(&mut self, constraints: &mut [Constraint], sys: &mut Sys, refactor: bool) {
        if self.rows.is_empty() {
            return;
        }
        if refactor {
            self.factor(constraints, sys);
        }
        for (p, &ci) in self.rows.iter().enumerate() {
            let c = &constraints[ci as usize];
            let vn = c.n.dot(sys.velocity(&c.a, c.ra) - sys.velocity(&c.b, c.rb));
            self.x[p] = -(vn as f64);
        }
        self.substitute();
        for (p, &ci) in self.rows.iter().enumerate() {
            let c = &mut constraints[ci as usize];
            let d = self.x[p] as f32;
            c.impulse += d;
            c.apply(sys, c.n * d);
        }
    }

    /// A Newton step of the projection of every rod to its length.
    pub fn solve_position(&mut self, constraints: &mut [Constraint], sys: &mut Sys) {
        if self.rows.is_empty() {
            return;
        }
        for &ci in &self.rows {
            let c = &mut constraints[ci as usize];
            let (n, gap) = c.measure(sys, c.ra, c.rb);
            c.n = n;
            c.gap = gap;
        }
        self.factor(constraints, sys);
        for (p, &ci) in self.rows.iter().enumerate() {
            self.x[p] = -(constraints[ci as usize].gap as f64);
        }
        self.substitute();
        for (p, &ci) in self.rows.iter().enumerate() {
            let c = &constraints[ci as usize];
            let d = c.n * self.x[p] as f32;
            sys.shift(&c.a, c.ra, d);
            sys.shift(&c.b, c.rb, -d);
        }
    }
}

/// Calls `f(i, j)` for every pair of distinct rows sharing a key in the sorted `touch`.
fn for_each_pair(touch: &[(u32, u32, i8)], mut f: impl FnMut(u32, u32)) {
    let mut k = 0;
    while k < touch.len() {
        let mut end = k + 1;
        while end < touch.len() && touch[end].0 == touch[k].0 {
            end += 1;
        }
        for x in k..end {
            for y in x + 1..end {
                if touch[x].1 != touch[y].1 {
                    f(touch[x].1, touch[y].1);
                }
            }
        }
        k = end;
    }
}
