//! The direct solve of the joints' equality rows over a spanning forest of the joint graph
//! (Baraff 1996, *Linear-time dynamics using Lagrange multipliers*; our own derivation in the
//! body-tree form below).
//!
//! Gauss–Seidel over joint rows converges slowly when masses differ a lot along a chain: each
//! row sees only its two bodies, so a light link between a heavy end mass and the anchor
//! passes the load on a little per sweep and a 20-link chain with a 100× end mass stretched
//! 2.3 % at six sub-steps. Here the equality rows of every joint in a forest are solved
//! exactly, in time linear in the bodies, every time the joints are solved (biased and relax
//! sweeps); the load reaches the anchor in one solve whatever the mass ratio.
//!
//! **The forest.** Built once per step (`build`). Static, sleeping and kinematic bodies are one
//! *ground* node. Joints with equality rows are taken in order and kept when they join two
//! different components (union–find), so each component is a tree hanging from at most one
//! ground joint. A joint that would close a loop (a second anchor of a bridge, the second
//! string of a cradle ball, the grid's cross links), every joint of a component that has a
//! distance spring, that has a slider or a hinge or ball with limits, a motor or a spring and
//! also a loop, or that has both a slider and such a hinge or ball
//! (`Forest::find_components`), a joint touching a body without full inertia, and the rows
//! of those joints stay in the iterative path (`solver.rs`), solved before the tree in each
//! sweep; contacts follow. A tree joint's limits, motor and spring are solved here, after
//! the equality rows, with the whole tree's response
//! (`Forest::solve_axial`). Each tree body is a node whose
//! parent joint joins it to its parent body or to the ground; nodes are kept in depth-first
//! pre-order, so walking the list backwards visits children before parents.
//!
//! **The algebra.** Unknowns are the velocity changes `x_b` (6 per body) and impulses `λ_j`
//! (one per row): `M_b x_b = Σ_j J_jbᵀ λ_j`, `Σ_b J_jb x_b = r_j`. Eliminating leaves first:
//! `D_b = M_b + Σ_children J_jbᵀ S_j⁻¹ J_jb` with `S_j = J_jc D_c⁻¹ J_jcᵀ` for the child `c` of
//! joint `j` (the articulated mass of the subtree seen through the joint). Solve: backwards
//! `u_b = D_b⁻¹ g_b`, `z_j = S_j⁻¹ (r_j − J_jb u_b)`, `g_parent += J_jpᵀ z_j`; forwards
//! `λ_j = z_j − S_j⁻¹ J_jp x_parent`, `x_b = u_b + D_b⁻¹ J_jbᵀ λ_j`. Every pivot is positive
//! definite, so no pivoting. Factored once per position: lazily before the first biased
//! sweep, and after each position update (before the relax sweep, reused by the next
//! sub-step's biased sweep). `D_b` and its Cholesky factor are kept in f64 (a link's inertia
//! next to a heavy subtree's articulated mass spans many decades); the per-row data in f32.
//!
//! No allocation once the buffers have grown; the order is that of the joint constraints, so
//! the result is deterministic.

// Small dense linear algebra reads best with index loops over rows and columns.
#![allow(clippy::needless_range_loop)]

use super::rows::{Eq, Row, Slot};
use super::solver::{load, write, Ctx, Frames, JointConstraint};
use super::Impulses;
use crate::dynamics::solver::{BodyState, Velocity};
use crate::math::Vec3;

type V6 = [f64; 6];

const NONE: u32 = u32::MAX;
const ZERO6: V6 = [0.0; 6];

#[derive(Clone, Copy, Debug)]
struct Node {
    /// Solver index of the body.
    body: u32,
    /// Parent node (`NONE`: the ground or a root).
    parent: u32,
    /// Constraint index of the joint to the parent (`NONE`: a root body).
    joint: u32,
    /// Solver index of the joint's other body (0 for a root).
    other: u32,
    /// The body is side A of its parent joint.
    child_is_a: bool,
    /// Number of rows of the parent joint and their first index in the per-row arrays.
    k: u32,
    off: u32,
    /// The node's tree has a slider or a joint with limits, a motor or a spring: its rows
    /// respond rigidly (with the position bias) in the biased sweep too (`Forest::solve`).
    rigid: bool,
}

/// Which of a tree joint's scalar rows an [`Axial`] is: a slider's along its axis (motor,
/// limits), a hinge's about its axis (spring, motor, limits), a ball's twist limits or its
/// swing cone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Along {
    SliderAxis,
    HingeAxis,
    BallTwist,
    BallCone,
}

/// A tree joint's scalar row (limits, motor, spring), solved with the tree's response
/// (`Forest::solve_axial`).
#[derive(Clone, Copy, Debug)]
struct Axial {
    /// The joint's node, and the node range of its tree.
    node: u32,
    start: u32,
    end: u32,
    along: Along,
    /// The row's Jacobian on the node's body and on the other body, and the row's position
    /// (translation, angle) (refreshed by `factor`); `live` is false where the row is not
    /// defined (twist past `MAX_TWIST_SWING`, no swing).
    jc: V6,
    jp: V6,
    pos: f32,
    live: bool,
}

/// The spanning forest and its factorisation (buffers reused across steps). Per-row data is
/// stored by row (a node's rows from `Node::off`), so a ball joint's node takes a few hundred
/// bytes: the solve walks the forest three times per sweep and is bound by memory traffic.
#[derive(Default)]
pub struct Forest {
    uf: Vec<u32>,
    degree: Vec<u32>,
    head: Vec<u32>,
    adj: Vec<(u32, u32)>,
    stack: Vec<(u32, u32, u32)>,
    node_of: Vec<u32>,
    nodes: Vec<Node>,
    /// Per node: `D` while factoring, then its Cholesky factor (packed lower triangles, f64:
    /// the articulated mass of a heavy subtree next to a light link's inertia spans decades).
    dinv: Vec<[f64; 21]>,
    /// Per row: the joint's Jacobian on the node's body and on the other body, `D⁻¹ J_cᵀ`,
    /// the row of `S⁻¹`, the position error.
    jc: Vec<V6>,
    jp: Vec<V6>,
    y: Vec<V6>,
    sinv: Vec<V6>,
    err: Vec<f32>,
    /// Per row: where its accumulated impulse is kept.
    slot: Vec<Slot>,
    /// Per row, per solve: right-hand side, then `z`, then `λ`.
    rhs: Vec<f64>,
    z: Vec<f64>,
    /// Per node, per solve.
    g: Vec<V6>,
    u: Vec<V6>,
    x: Vec<V6>,
    /// The tree sliders with limits or a motor.
    axial: Vec<Axial>,
    /// The factorisation is out of date (new step).
    stale: bool,
    /// Per body: the union–find of the joint graph without the ground (`find_components`),
    /// and per component root its `COMPONENT_*` flags.
    component_uf: Vec<u32>,
    component_flags: Vec<u8>,
}

/// `Forest::component_flags`: the component has a joint to the ground; it closes a loop (a
/// cycle of its own, or a second joint to the ground); it has a slider; it has a hinge or
/// ball with limits, a motor or a spring (rows the forest solves with its tree's response);
/// it has a distance spring (rows solved one joint at a time: it is no tree joint).
const COMPONENT_GROUNDED: u8 = 1;
const COMPONENT_LOOP: u8 = 2;
const COMPONENT_SLIDER: u8 = 4;
const COMPONENT_SCALAR: u8 = 8;
const COMPONENT_LIMITED: u8 = 16;

fn find(uf: &mut [u32], mut x: u32) -> u32 {
    while uf[x as usize] != x {
        let p = uf[x as usize];
        uf[x as usize] = uf[p as usize];
        x = p;
    }
    x
}

/// Whether a body is ground (no mass: static, sleeping, kinematic, the world) and whether it
/// may be a tree node (full mass and inertia).
fn classify(s: &BodyState, index: u32) -> (bool, bool) {
    if index == 0 || s.inv_mass == 0.0 {
        return (true, false);
    }
    if s.locks != 0 {
        // Locked axes: the iterative rows, whose velocities the solver projects.
        return (false, false);
    }
    let det = s.inv_i().determinant();
    (false, det > 0.0 && det.is_finite())
}

#[inline]
fn packed(r: usize, c: usize) -> usize {
    let (r, c) = if r >= c { (r, c) } else { (c, r) };
    r * (r + 1) / 2 + c
}

impl Forest {
    /// Finds the components of the joint graph and what each holds (`COMPONENT_*`): the
    /// graph of every non-ground body (whatever its mass, inertia or locks: a loop through a
    /// body the forest cannot take is still a loop) and every joint, springs included.
    fn find_components(&mut self, constraints: &[JointConstraint], states: &[BodyState]) {
        let n = states.len();
        self.component_uf.clear();
        self.component_uf.extend(0..n as u32);
        self.component_flags.clear();
        self.component_flags.resize(n, 0);
        let ground = |i: u32| classify(&states[i as usize], i).0;
        for c in constraints {
            let kind = match c.kind {
                super::JointKind::Slider(_) => COMPONENT_SLIDER,
                super::JointKind::Distance(p) if p.enable_spring => COMPONENT_SCALAR,
                k if super::solver::has_scalar_rows(&k) => COMPONENT_LIMITED,
                _ => 0,
            };
            match (ground(c.ia), ground(c.ib)) {
                (true, true) => {}
                (false, false) => {
                    let uf = &mut self.component_uf;
                    let (ra, rb) = (find(uf, c.ia), find(uf, c.ib));
                    let flags = &mut self.component_flags;
                    if ra == rb {
                        flags[ra as usize] |= COMPONENT_LOOP | kind;
                        continue;
                    }
                    let (fa, fb) = (flags[ra as usize], flags[rb as usize]);
                    let (lo, hi) = (ra.min(rb), ra.max(rb));
                    uf[hi as usize] = lo;
                    let bridge = if fa & fb & COMPONENT_GROUNDED != 0 {
                        COMPONENT_LOOP
                    } else {
                        0
                    };
                    flags[lo as usize] = fa | fb | kind | bridge;
                }
                (ga, _) => {
                    let body = if ga { c.ib } else { c.ia };
                    let r = find(&mut self.component_uf, body) as usize;
                    let f = &mut self.component_flags[r];
                    let bridge = if *f & COMPONENT_GROUNDED != 0 {
                        COMPONENT_LOOP
                    } else {
                        0
                    };
                    *f |= kind | bridge | COMPONENT_GROUNDED;
                }
            }
        }
    }

    /// Whether the joint's component is solved by Gauss–Seidel alone (see `build`): it has
    /// a distance spring, or it closes a loop and has a slider or a hinge or ball with limits,
    /// a motor or a spring, or it has both a slider and such a hinge or ball.
    fn iterated(&mut self, c: &JointConstraint, states: &[BodyState]) -> bool {
        let body = if classify(&states[c.ia as usize], c.ia).0 {
            c.ib
        } else {
            c.ia
        };
        let f = self.component_flags[find(&mut self.component_uf, body) as usize];
        let has = |flag: u8| f & flag != 0;
        has(COMPONENT_SCALAR)
            || (has(COMPONENT_LOOP) && has(COMPONENT_SLIDER | COMPONENT_LIMITED))
            || (has(COMPONENT_SLIDER) && has(COMPONENT_LIMITED))
    }

    /// Number of joints in the forest this step.
    pub fn len(&self) -> usize {
        self.nodes.iter().filter(|n| n.joint != NONE).count()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Chooses the tree joints (sets `JointConstraint::tree`) and orders the tree bodies.
    pub fn build(&mut self, constraints: &mut [JointConstraint], states: &[BodyState]) {
        let n = states.len();
        self.find_components(constraints, states);
        self.nodes.clear();
        self.stale = true;
        self.uf.clear();
        self.uf.extend(0..n as u32);
        self.degree.clear();
        self.degree.resize(n, 0);
        let key = |index: u32| -> Option<u32> {
            match classify(&states[index as usize], index) {
                (true, _) => Some(0),
                (false, true) => Some(index),
                (false, false) => None,
            }
        };
        for c in constraints.iter_mut() {
            c.tree = false;
            // Components with a distance spring, loops with a slider or with limits, motors or
            // springs, and components with both a slider and a limited hinge or ball are
            // solved by Gauss–Seidel alone (`tests/joint_loops.rs`). Before tree joints'
            // limits were solved with the tree's response (`solve_axial`), such rows were
            // solved one joint at a time before the forest, and the forest's exact solve fed
            // energy in: seeded random open chains with limits and springs gained more than
            // their energy scale in 12 of 300 (497 times it in the worst), rings with a
            // slider in 13 of 300 (a rigid slider tree and the soft loop-closing joint fought,
            // their forces growing to ten times the weights). Open chains of hinges and balls
            // with limits keep the forest: by Gauss–Seidel their joints sagged (291 of 300
            // random chains past 5 mm, the worst 0.85 m; a 0.03 kg two-body effective mass
            // at a far anchor makes a weak soft row), in the forest 26 (the worst 1.1 cm).
            // With a slider as well, one of 300 chains gained a third of its energy scale in
            // the forest (a free slider's child gathering speed along its rail), so those
            // stay with Gauss–Seidel. Loops without a slider or limits keep the forest (its
            // soft trees settle with the loop's rows: a 20×20 ball-joint grid hangs with
            // 3.5 mm of gap, 8.5 mm without it), and so do chains with plain joints, whose
            // load the forest carries exactly (a 20-link chain with a 100× end mass).
            c.iterated = self.iterated(c, states);
            if !has_equality_rows(c) || c.iterated {
                continue;
            }
            let (Some(ka), Some(kb)) = (key(c.ia), key(c.ib)) else {
                continue;
            };
            let (ra, rb) = (find(&mut self.uf, ka), find(&mut self.uf, kb));
            if ra == rb {
                continue;
            }
            self.uf[ra.max(rb) as usize] = ra.min(rb);
            c.tree = true;
            self.degree[ka as usize] += 1;
            self.degree[kb as usize] += 1;
        }
        // Adjacency in compressed rows.
        self.head.clear();
        self.head.push(0);
        let mut sum = 0;
        for &d in &self.degree {
            sum += d;
            self.head.push(sum);
        }
        self.adj.clear();
        self.adj.resize(sum as usize, (0, 0));
        for d in self.degree.iter_mut() {
            *d = 0;
        }
        for (ci, c) in constraints.iter().enumerate() {
            if !c.tree {
                continue;
            }
            let (ka, kb) = (key(c.ia).unwrap_or(0), key(c.ib).unwrap_or(0));
            for (from, to) in [(ka, kb), (kb, ka)] {
                let slot = self.head[from as usize] + self.degree[from as usize];
                self.adj[slot as usize] = (to, ci as u32);
                self.degree[from as usize] += 1;
            }
        }
        // Depth-first from the ground, then from every body not reached.
        self.node_of.clear();
        self.node_of.resize(n, NONE);
        self.stack.clear();
        for k in (self.head[0]..self.head[1]).rev() {
            let (to, ci) = self.adj[k as usize];
            self.stack.push((to, NONE, ci));
        }
        self.drain(constraints);
        for r in 1..n {
            if self.degree[r] > 0 && self.node_of[r] == NONE {
                self.stack.push((r as u32, NONE, NONE));
                self.drain(constraints);
            }
        }
        // A tree slider's linear rows act at the child's centre: its Jacobian on the child
        // then has no lever arm, so `S` stays well conditioned however far the child slid
        // (the lever goes to the parent side, into `D_parent` in f64). With the lever on
        // the child, a body 120 m along its rail made `S` singular in f32 and the chain
        // blew up. See `SliderRows`.
        for node in &self.nodes {
            if node.joint != NONE {
                let c = &mut constraints[node.joint as usize];
                c.slider_point = if node.child_is_a { 0.0 } else { 1.0 };
            }
        }
        // Trees with a slider or with scalar rows (limits, motors, springs) respond rigidly,
        // and those rows are solved with their tree's response: see `Forest::solve`. A tree is
        // a run of nodes from a root.
        self.axial.clear();
        let mut start = 0;
        for end in 1..=self.nodes.len() {
            if end < self.nodes.len() && self.nodes[end].parent != NONE {
                continue;
            }
            let mut rigid = false;
            for i in start..end {
                let n = &self.nodes[i];
                if n.joint == NONE {
                    continue;
                }
                let mut push = |along| {
                    self.axial.push(Axial {
                        node: i as u32,
                        start: start as u32,
                        end: end as u32,
                        along,
                        jc: ZERO6,
                        jp: ZERO6,
                        pos: 0.0,
                        live: false,
                    })
                };
                match constraints[n.joint as usize].kind {
                    super::JointKind::Slider(p) => {
                        rigid = true;
                        if super::slider::has_axial_rows(&p) {
                            push(Along::SliderAxis);
                        }
                    }
                    super::JointKind::Hinge(p) if super::hinge::has_axial_rows(&p) => {
                        rigid = true;
                        push(Along::HingeAxis);
                    }
                    super::JointKind::Ball(p) if super::ball::has_limits(&p) => {
                        rigid = true;
                        if super::ball::cone_angle(&p).is_some() {
                            push(Along::BallCone);
                        }
                        if p.enable_twist_limit {
                            push(Along::BallTwist);
                        }
                    }
                    _ => {}
                }
            }
            for n in &mut self.nodes[start..end] {
                n.rigid = rigid;
            }
            start = end;
        }
        let rows = self.nodes.last().map_or(0, |n| (n.off + n.k) as usize);
        self.dinv.resize(self.nodes.len(), [0.0; 21]);
        for v in [&mut self.jc, &mut self.jp, &mut self.y, &mut self.sinv] {
            v.resize(rows, ZERO6);
        }
        self.err.resize(rows, 0.0);
        for v in [&mut self.rhs, &mut self.z] {
            v.resize(rows, 0.0);
        }
        self.slot.resize(rows, Slot::Axial);
        for v in [&mut self.g, &mut self.u, &mut self.x] {
            v.resize(self.nodes.len(), ZERO6);
        }
    }

    /// Pops the depth-first stack empty, appending nodes in pre-order.
    fn drain(&mut self, constraints: &[JointConstraint]) {
        while let Some((body, parent, joint)) = self.stack.pop() {
            let index = self.nodes.len() as u32;
            self.node_of[body as usize] = index;
            let off = self.nodes.last().map_or(0, |n| n.off + n.k);
            let (child_is_a, other, k) = if joint == NONE {
                (false, 0, 0)
            } else {
                let c = &constraints[joint as usize];
                let is_a = c.ia == body;
                (is_a, if is_a { c.ib } else { c.ia }, equality_row_count(c) as u32)
            };
            self.nodes.push(Node {
                body,
                parent,
                joint,
                other,
                child_is_a,
                k,
                off,
                rigid: false,
            });
            for k in (self.head[body as usize]..self.head[body as usize + 1]).rev() {
                let (to, ci) = self.adj[k as usize];
                if ci != joint {
                    self.stack.push((to, index, ci));
                }
            }
        }
    }

    /// Factors the forest at the bodies' current positions.
    fn factor(&mut self, constraints: &[JointConstraint], states: &[BodyState]) {
        self.stale = false;
        for (i, node) in self.nodes.iter().enumerate() {
            let s = &states[node.body as usize];
            let d = &mut self.dinv[i];
            *d = [0.0; 21];
            let mass = 1.0 / s.inv_mass as f64;
            for k in 0..3 {
                d[packed(k, k)] = mass;
            }
            let inertia = s.inv_i().as_dmat3().inverse();
            for c in 0..3 {
                for r in c..3 {
                    d[packed(3 + r, 3 + c)] = inertia.col(c)[r];
                }
            }
        }
        for i in (0..self.nodes.len()).rev() {
            let node = self.nodes[i];
            let l = cholesky6(&self.dinv[i]);
            self.dinv[i] = l;
            if node.joint == NONE {
                continue;
            }
            let c = &constraints[node.joint as usize];
            let (sa, sb) = (&states[c.ia as usize], &states[c.ib as usize]);
            let eq = Eq::of(&c.kind, &Frames::new(c, sa, sb));
            let (k, off) = (node.k as usize, node.off as usize);
            debug_assert_eq!(eq.n, k);
            for r in 0..k {
                let row = &eq.rows[r];
                let (a, b) = ([row.la, row.aa], [row.lb, row.ab]);
                let (mine, other) = if node.child_is_a { (a, b) } else { (b, a) };
                self.jc[off + r] = [mine[0].x, mine[0].y, mine[0].z, mine[1].x, mine[1].y, mine[1].z].map(f64::from);
                self.jp[off + r] =
                    [other[0].x, other[0].y, other[0].z, other[1].x, other[1].y, other[1].z].map(f64::from);
                self.err[off + r] = eq.err[r];
                self.slot[off + r] = eq.slots[r];
            }
            let rows = off..off + k;
            let dp = (node.parent != NONE).then_some(node.parent as usize);
            match k {
                1 => self.factor_joint::<1>(&l, rows, dp),
                3 => self.factor_joint::<3>(&l, rows, dp),
                5 => self.factor_joint::<5>(&l, rows, dp),
                _ => self.factor_joint::<6>(&l, rows, dp),
            }
        }
        self.factor_axial(constraints, states);
    }

    /// The tree joints' scalar rows at the bodies' current positions.
    fn factor_axial(&mut self, constraints: &[JointConstraint], states: &[BodyState]) {
        for a in self.axial.iter_mut() {
            let node = &self.nodes[a.node as usize];
            let c = &constraints[node.joint as usize];
            let (sa, sb) = (&states[c.ia as usize], &states[c.ib as usize]);
            let f = Frames::new(c, sa, sb);
            let found = match a.along {
                Along::SliderAxis => {
                    let sr = f.slider();
                    let row = Row::linear(sr.axes[2], sr.lever_a, sr.lever_b);
                    Some((row, sr.axes[2].dot(sr.offset)))
                }
                Along::HingeAxis | Along::BallTwist => f.twist().map(|(angle, axis)| (Row::angular(axis), angle)),
                Along::BallCone => super::ball::cone_row(&f).map(|(j, angle)| (Row::angular(j), angle)),
            };
            a.live = found.is_some();
            let Some((row, pos)) = found else {
                continue;
            };
            let (mine, other) = if node.child_is_a {
                ([row.la, row.aa], [row.lb, row.ab])
            } else {
                ([row.lb, row.ab], [row.la, row.aa])
            };
            a.jc = [mine[0].x, mine[0].y, mine[0].z, mine[1].x, mine[1].y, mine[1].z].map(f64::from);
            a.jp = [other[0].x, other[0].y, other[0].z, other[1].x, other[1].y, other[1].z].map(f64::from);
            a.pos = pos;
        }
    }

    /// One joint of the factorisation, `K` rows: `Y = D⁻¹ J_cᵀ`, `S⁻¹ = (J_c Y)⁻¹`, and
    /// `D_parent += J_pᵀ S⁻¹ J_p` (f64 while factoring).
    fn factor_joint<const K: usize>(&mut self, l: &[f64; 21], rows: std::ops::Range<usize>, parent: Option<usize>) {
        let jc: [[f64; 6]; K] = std::array::from_fn(|r| self.jc[rows.start + r]);
        let y: [[f64; 6]; K] = std::array::from_fn(|r| chol_solve6(l, &jc[r]));
        let mut s = [[0.0f64; K]; K];
        for a in 0..K {
            for b in 0..=a {
                let v = dot6(&jc[a], &y[b]);
                s[a][b] = v;
                s[b][a] = v;
            }
        }
        let s = spd_inverse::<K>(&s).unwrap_or([[0.0; K]; K]);
        for r in 0..K {
            self.y[rows.start + r] = y[r];
            let mut row = ZERO6;
            row[..K].copy_from_slice(&s[r]);
            self.sinv[rows.start + r] = row;
        }
        if let Some(p) = parent {
            let jp: [[f64; 6]; K] = std::array::from_fn(|r| self.jp[rows.start + r]);
            // W = S⁻¹ J_p; D_parent += J_pᵀ W.
            let mut w = [[0.0f64; 6]; K];
            for a in 0..K {
                for b in 0..K {
                    for e in 0..6 {
                        w[a][e] += s[a][b] * jp[b][e];
                    }
                }
            }
            let dp = &mut self.dinv[p];
            let mut idx = 0;
            for r in 0..6 {
                for c in 0..=r {
                    let mut v = 0.0;
                    for a in 0..K {
                        v += jp[a][r] * w[a][c];
                    }
                    dp[idx] += v;
                    idx += 1;
                }
            }
        }
    }

    /// Solves the tree joints' equality rows exactly against the current velocities, rigid
    /// (relax sweep) or as Box2D's stiff soft constraint (biased sweep, `ctx`), and applies the
    /// impulses. Refactors first when the positions moved (`positions_moved`) or the step is new.
    ///
    /// A tree with a slider responds rigidly in the biased sweep too,
    /// with the same position bias (a Baumgarte feedback; the exact solve leaves no
    /// Gauss–Seidel mode for it to pump). A slider's rows act at a point that moves along one of its bodies as it slides,
    /// so the impulses kept from the last sub-step no longer balance on that body: a link of
    /// 0.6 m hinged to the world holding a child slid 60 m along it balances the hinge's torque
    /// against the child's weight at a 60 m lever, and re-applied at the moved lever (or leaked
    /// in proportion, as the soft response does) they left the light link a velocity error of
    /// rad/s. The soft response takes only its mass scale (95 %) of it; the rest turned the
    /// link, which moved the rail at the child by the whole lever, which the next correction
    /// answered with a larger impulse. The loop's gain grows with the lever and the sliding
    /// speed: past some 50 m at 20 m/s it gained, and 32 of 60 random hinge → slider chains
    /// blew up (`tests/slider_chains.rs`). Rigid, the error is answered in full each sweep.
    /// With limits or a motor on the slider the same chains blew up as long as those trees
    /// kept the soft response (limits at ±500 m that were never reached: 34 of 60), so they
    /// respond rigidly too, and the slider's limits and motor are solved after the equality
    /// rows with the tree's response (`solve_axial`). So do trees with a hinge's or ball's
    /// limits, motor or spring, whose rows are solved the same way: the rows' impulses are
    /// booked on the tree's equality rows (`z`), which a soft response would leak away each
    /// sweep while the limit's own impulse stays.
    pub fn solve(
        &mut self,
        constraints: &mut [JointConstraint],
        vel: &mut [Velocity],
        states: &[BodyState],
        ctx: &Ctx,
        positions_moved: bool,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        if self.stale || positions_moved {
            self.factor(constraints, states);
        }
        let m = self.nodes.len();
        // Right-hand sides: drive each row's velocity to minus its position bias.
        for node in &self.nodes {
            let (vc, vp) = (six(&vel[node.body as usize]), six(&vel[node.other as usize]));
            for r in node.off as usize..(node.off + node.k) as usize {
                let cdot = dot6(&self.jc[r], &vc) + dot6(&self.jp[r], &vp);
                self.rhs[r] = -(cdot + ctx.rigid_bias(self.err[r]) as f64);
            }
        }
        for g in self.g.iter_mut() {
            *g = ZERO6;
        }
        self.sweep(0..m);
        let rigid = ctx.soft.impulse_scale == 0.0 && ctx.soft.mass_scale == 1.0;
        for i in 0..m {
            let node = self.nodes[i];
            let (k, off) = (node.k as usize, node.off as usize);
            if rigid {
                // The velocity changes are the solution itself.
                let x = &self.x[i];
                let u = &mut vel[node.body as usize];
                u.v += Vec3::new(x[0] as f32, x[1] as f32, x[2] as f32);
                u.w += Vec3::new(x[3] as f32, x[4] as f32, x[5] as f32);
            }
            if k == 0 {
                continue;
            }
            let c = &mut constraints[node.joint as usize];
            if rigid {
                for r in off..off + k {
                    self.slot[r].add(&mut c.imp, self.z[r] as f32);
                }
            } else {
                // Soft: scale the rigid solution and leak part of the accumulated impulse,
                // applied joint by joint through the rows.
                let (mut b, _) = load(c, vel, states);
                for r in off..off + k {
                    let d = if node.rigid {
                        self.z[r] as f32
                    } else {
                        ctx.respond(self.z[r] as f32, self.slot[r].get(&c.imp))
                    };
                    self.slot[r].add(&mut c.imp, d);
                    b.apply_row(&self.row(&node, r), d);
                }
                write(c, &b, vel);
            }
        }
        for k in 0..self.axial.len() {
            self.solve_axial(k, constraints, vel, ctx);
        }
    }

    /// The elimination over nodes `range` (whole trees) with the right-hand sides `rhs` and
    /// the outside impulses `g` (both per solve): `x` the velocity changes, `z` the impulses.
    fn sweep(&mut self, range: std::ops::Range<usize>) {
        // Backwards: children before parents.
        for i in range.clone().rev() {
            let u = chol_solve6(&self.dinv[i], &self.g[i]);
            self.u[i] = u;
            match self.nodes[i].k {
                0 => {}
                1 => self.backward::<1>(i),
                3 => self.backward::<3>(i),
                5 => self.backward::<5>(i),
                _ => self.backward::<6>(i),
            }
        }
        // Forwards: parents before children; `z` becomes `λ`.
        for i in range {
            self.x[i] = match self.nodes[i].k {
                0 => self.u[i],
                1 => self.forward::<1>(i),
                3 => self.forward::<3>(i),
                5 => self.forward::<5>(i),
                _ => self.forward::<6>(i),
            };
        }
    }

    /// A tree joint's scalar rows along one direction (`Axial` `k`: a slider's motor and
    /// limits, a hinge's spring, motor and limits, a ball's twist limits or swing cone),
    /// solved with the response of its whole tree: a unit impulse along the row, with the
    /// impulses of the tree's equality rows that keep their velocities, moves every body of
    /// the tree (`x`) and the row by `1 / mass`. The row's impulse then stops or drives the
    /// joint against everything hanging on it, and the equality rows stay solved. Solved
    /// against the two bodies alone (coupled with the joint's own equality rows only), a
    /// slider limit holding a 100× end mass below two light links saw their mass, and the
    /// rigid tree bounced the chain between the limits at 30 m/s; hinge and ball limits so
    /// solved before the forest's exact solve fed energy into random limited chains (12 of
    /// 300 gained more than their energy scale, `tests/joint_loops.rs`).
    fn solve_axial(&mut self, k: usize, constraints: &mut [JointConstraint], vel: &mut [Velocity], ctx: &Ctx) {
        let a = self.axial[k];
        let range = a.start as usize..a.end as usize;
        let node = self.nodes[a.node as usize];
        if !a.live {
            // Not defined at this pose (the hinge's or twist's axes nearly opposite, far from
            // the joint's pose: the alignment rows turn them back first; no swing).
            let imp = &mut constraints[node.joint as usize].imp;
            match a.along {
                Along::HingeAxis => (imp.axial, imp.motor, imp.lower, imp.upper) = (0.0, 0.0, 0.0, 0.0),
                Along::BallTwist => (imp.lower, imp.upper) = (0.0, 0.0),
                Along::BallCone => imp.cone = 0.0,
                Along::SliderAxis => {}
            }
            return;
        }
        // In solve order: spring toward 0 (a hinge's), motor (target speed, largest force or
        // torque), lower and upper limits; a ball's cone is one limit of its own.
        let (spring, drive, bounds, cone) = match constraints[node.joint as usize].kind {
            super::JointKind::Slider(p) => (
                false,
                p.enable_motor.then_some((p.motor_speed, p.max_motor_force)),
                p.enable_limit.then_some((p.lower, p.upper)),
                None,
            ),
            super::JointKind::Hinge(p) => (
                p.enable_spring && p.spring_hertz > 0.0,
                p.enable_motor.then_some((p.motor_speed, p.max_motor_torque)),
                p.enable_limit.then_some((p.lower, p.upper)),
                None,
            ),
            super::JointKind::Ball(p) if a.along == Along::BallTwist => {
                (false, None, Some((p.lower_twist, p.upper_twist)), None)
            }
            super::JointKind::Ball(p) => (false, None, None, Some(super::ball::cone_angle(&p).unwrap_or(a.pos))),
            _ => (false, None, None, None),
        };
        let mut cdot =
            (dot6(&a.jc, &six(&vel[node.body as usize])) + dot6(&a.jp, &six(&vel[node.other as usize]))) as f32;
        // Limits that hold no impulse and stay apart within the sub-step give none whatever
        // the response (`Ctx::limit`): most of a ragdoll's, most of the time. Their tree's
        // sweep is skipped.
        let imp = &constraints[node.joint as usize].imp;
        let resting = |v: f32, c: f32, acc: f32| acc == 0.0 && c > 0.0 && v + c * ctx.inv_h >= 0.0;
        if !spring
            && drive.is_none()
            && bounds.map_or(true, |(lo, up)| {
                resting(cdot, a.pos - lo, imp.lower) && resting(-cdot, up - a.pos, imp.upper)
            })
            && cone.map_or(true, |limit| resting(cdot, limit - a.pos, imp.cone))
        {
            return;
        }
        // The response to a unit impulse along the row.
        for i in range.clone() {
            self.g[i] = ZERO6;
            let n = &self.nodes[i];
            for r in n.off as usize..(n.off + n.k) as usize {
                self.rhs[r] = 0.0;
            }
        }
        self.g[a.node as usize] = a.jc;
        if node.parent != NONE {
            self.g[node.parent as usize] = a.jp;
        }
        self.sweep(range.clone());
        let parent_x = if node.parent != NONE {
            dot6(&a.jp, &self.x[node.parent as usize])
        } else {
            0.0
        };
        let inv_mass = dot6(&a.jc, &self.x[a.node as usize]) + parent_x;
        let mass = if inv_mass > 0.0 && inv_mass.is_finite() {
            (1.0 / inv_mass) as f32
        } else {
            0.0
        };
        let c = &mut constraints[node.joint as usize];
        let inv_mass = inv_mass as f32;
        let mut total = 0.0f32;
        let imp = &mut c.imp;
        // Each row in turn: its impulse `d` moves the row's velocity by `d / mass`.
        let motor = |cdot: &mut f32, total: &mut f32, acc: &mut f32, speed: f32, max: f32| {
            let old = *acc;
            *acc = (old - mass * (*cdot - speed)).clamp(-max, max);
            let d = *acc - old;
            *cdot += inv_mass * d;
            *total += d;
        };
        let limits = |cdot: &mut f32, total: &mut f32, imp: &mut Impulses, lower: f32, upper: f32| {
            let d = ctx.limit(mass, *cdot, a.pos - lower, &mut imp.lower);
            *cdot += inv_mass * d;
            *total += d;
            let d = ctx.limit(mass, -*cdot, upper - a.pos, &mut imp.upper);
            *total -= d;
        };
        if let Some(limit) = cone {
            total += ctx.limit(mass, cdot, limit - a.pos, &mut imp.cone);
        }
        if spring {
            let d = super::solver::soft_impulse(&c.spring, mass, cdot, a.pos, &mut imp.axial);
            cdot += inv_mass * d;
            total += d;
        }
        if let Some((speed, max)) = drive {
            motor(&mut cdot, &mut total, &mut imp.motor, speed, max * ctx.h);
        }
        if let Some((lower, upper)) = bounds {
            limits(&mut cdot, &mut total, imp, lower, upper);
        }
        if total == 0.0 {
            return;
        }
        let t = total as f64;
        for i in range {
            let n = self.nodes[i];
            let x = &self.x[i];
            let u = &mut vel[n.body as usize];
            u.v += Vec3::new((x[0] * t) as f32, (x[1] * t) as f32, (x[2] * t) as f32);
            u.w += Vec3::new((x[3] * t) as f32, (x[4] * t) as f32, (x[5] * t) as f32);
            if n.k > 0 {
                let imp = &mut constraints[n.joint as usize].imp;
                for r in n.off as usize..(n.off + n.k) as usize {
                    self.slot[r].add(imp, (self.z[r] * t) as f32);
                }
            }
        }
    }

    /// Backward pass of one joint with `K` rows: `z = S⁻¹ (r − J_c u)`, `g_parent += J_pᵀ z`.
    #[inline]
    fn backward<const K: usize>(&mut self, i: usize) {
        let node = self.nodes[i];
        let off = node.off as usize;
        let u = self.u[i];
        let t: [f64; K] = std::array::from_fn(|r| self.rhs[off + r] - dot6(&self.jc[off + r], &u));
        let mut z = [0.0f64; K];
        for r in 0..K {
            let row = &self.sinv[off + r];
            for e in 0..K {
                z[r] += row[e] * t[e];
            }
            self.z[off + r] = z[r];
        }
        if node.parent != NONE {
            let mut g = self.g[node.parent as usize];
            for r in 0..K {
                axpy6(&mut g, z[r], &self.jp[off + r]);
            }
            self.g[node.parent as usize] = g;
        }
    }

    /// Forward pass of one joint with `K` rows: `λ = z − S⁻¹ J_p x_parent`, returns
    /// `x = u + Y λ`.
    #[inline]
    fn forward<const K: usize>(&mut self, i: usize) -> V6 {
        let node = self.nodes[i];
        let off = node.off as usize;
        let mut x = self.u[i];
        if node.parent != NONE {
            let xp = self.x[node.parent as usize];
            let t: [f64; K] = std::array::from_fn(|r| dot6(&self.jp[off + r], &xp));
            for r in 0..K {
                let row = &self.sinv[off + r];
                let mut d = 0.0;
                for e in 0..K {
                    d += row[e] * t[e];
                }
                self.z[off + r] -= d;
            }
        }
        for r in 0..K {
            axpy6(&mut x, self.z[off + r], &self.y[off + r]);
        }
        x
    }

    /// Row `r` of a node's parent joint.
    fn row(&self, node: &Node, r: usize) -> Row {
        let (a, b) = if node.child_is_a {
            (&self.jc[r], &self.jp[r])
        } else {
            (&self.jp[r], &self.jc[r])
        };
        let v = |x: &V6, k: usize| Vec3::new(x[k] as f32, x[k + 1] as f32, x[k + 2] as f32);
        Row {
            la: v(a, 0),
            aa: v(a, 3),
            lb: v(b, 0),
            ab: v(b, 3),
        }
    }
}

#[inline]
fn six(u: &Velocity) -> V6 {
    [u.v.x, u.v.y, u.v.z, u.w.x, u.w.y, u.w.z].map(f64::from)
}

/// Whether the joint has equality rows (all but a distance joint with its spring on).
pub fn has_equality_rows(c: &JointConstraint) -> bool {
    equality_row_count(c) > 0
}

/// Number of equality rows of the joint (`Eq::of`).
pub fn equality_row_count(c: &JointConstraint) -> usize {
    use super::JointKind;
    match c.kind {
        JointKind::Ball(_) => 3,
        JointKind::Hinge(_) | JointKind::Slider(_) => 5,
        JointKind::Fixed => 6,
        JointKind::Distance(p) => usize::from(!p.enable_spring),
    }
}

#[inline]
fn dot6(a: &V6, b: &V6) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

#[inline]
fn axpy6(y: &mut V6, a: f64, x: &V6) {
    for k in 0..6 {
        y[k] += a * x[k];
    }
}

/// Cholesky factor `L` (`D = L Lᵀ`) of a symmetric positive definite 6×6 matrix, both as
/// packed lower triangles, with the diagonal of `L` stored inverted. Zero when `D` is not
/// positive definite (cannot happen for bodies with mass and inertia; decouples the subtree).
fn cholesky6(a: &[f64; 21]) -> [f64; 21] {
    let mut l = [0.0f64; 21];
    let scale = (0..6).map(|i| a[packed(i, i)]).fold(0.0, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return [0.0; 21];
    }
    for j in 0..6 {
        let mut d = a[packed(j, j)];
        for p in 0..j {
            d -= l[packed(j, p)] * l[packed(j, p)];
        }
        if d <= 1.0e-13 * scale {
            return [0.0; 21];
        }
        let inv = 1.0 / d.sqrt();
        l[packed(j, j)] = inv;
        for i in j + 1..6 {
            let mut v = a[packed(i, j)];
            for p in 0..j {
                v -= l[packed(i, p)] * l[packed(j, p)];
            }
            l[packed(i, j)] = v * inv;
        }
    }
    l
}

/// `D⁻¹ b` from the factor of `cholesky6`.
#[inline]
fn chol_solve6(l: &[f64; 21], b: &[f64; 6]) -> [f64; 6] {
    let mut y = *b;
    for i in 0..6 {
        let row = i * (i + 1) / 2;
        let mut v = y[i];
        for p in 0..i {
            v -= l[row + p] * y[p];
        }
        y[i] = v * l[row + i];
    }
    for i in (0..6).rev() {
        let mut v = y[i];
        for p in i + 1..6 {
            v -= l[p * (p + 1) / 2 + i] * y[p];
        }
        y[i] = v * l[i * (i + 1) / 2 + i];
    }
    y
}

/// Inverse of a small symmetric positive definite matrix (Cholesky); `None` when it is not
/// positive definite.
fn spd_inverse<const N: usize>(a: &[[f64; N]; N]) -> Option<[[f64; N]; N]> {
    let mut l = [[0.0f64; N]; N];
    let scale = (0..N).map(|i| a[i][i]).fold(0.0, f64::max);
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    for j in 0..N {
        let mut d = a[j][j];
        for p in 0..j {
            d -= l[j][p] * l[j][p];
        }
        if d <= 1.0e-13 * scale {
            return None;
        }
        let djj = d.sqrt();
        l[j][j] = djj;
        for i in j + 1..N {
            let mut v = a[i][j];
            for p in 0..j {
                v -= l[i][p] * l[j][p];
            }
            l[i][j] = v / djj;
        }
    }
    // L⁻¹ (lower triangular), then A⁻¹ = L⁻ᵀ L⁻¹.
    let mut li = [[0.0f64; N]; N];
    for j in 0..N {
        li[j][j] = 1.0 / l[j][j];
        for i in j + 1..N {
            let mut s = 0.0;
            for p in j..i {
                s += l[i][p] * li[p][j];
            }
            li[i][j] = -s / l[i][i];
        }
    }
    let mut out = [[0.0f64; N]; N];
    for i in 0..N {
        for j in 0..=i {
            let mut s = 0.0;
            for p in i..N {
                s += li[p][i] * li[p][j];
            }
            out[i][j] = s;
            out[j][i] = s;
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_solves() {
        let mut a = [[0.0f64; 6]; 6];
        let mut p = [0.0f64; 21];
        for i in 0..6 {
            for j in 0..6 {
                a[i][j] = if i == j {
                    4.0 + i as f64
                } else {
                    1.0 / (1.0 + (i + j) as f64)
                };
                p[packed(i, j)] = a[i][j];
            }
        }
        let l = cholesky6(&p);
        let b = [1.0, -2.0, 0.5, 3.0, 0.0, 1.0];
        let x = chol_solve6(&l, &b);
        for i in 0..6 {
            let s: f64 = (0..6).map(|k| a[i][k] * x[k]).sum();
            assert!((s - b[i]).abs() < 1e-12);
        }
        let s: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| a[i][j]));
        let inv = spd_inverse::<3>(&s).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                let v: f64 = (0..3).map(|k| a[i][k] * inv[k][j]).sum();
                assert!((v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
            }
        }
    }
}
