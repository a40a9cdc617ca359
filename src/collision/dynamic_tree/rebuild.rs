//! Top-down binned SAH rebuilds of a [`DynamicTree`]: of the whole hierarchy
//! (`rebuild`), or of the part above the proxies enlarged in place since the last one
//! (Box2D v3's partial `b2DynamicTree_Rebuild`), in three parts so that the middle one can
//! run on several threads:
//!
//! 1. `begin_rebuild` (calling thread) frees the internal nodes to rebuild, gathers what lies
//!    below them (the *units*: leaves, or subtrees kept whole), takes the nodes the new
//!    hierarchy needs from the free list and splits the units top-down until every range
//!    holds at most a job's worth of units. Each such range becomes a job.
//! 2. [`RebuildJobs::run`] builds one job's subtree into its own nodes; jobs touch disjoint
//!    nodes and may run at the same time, on any threads, in any order.
//! 3. `end_rebuild` (calling thread) refits the nodes above the jobs.
//!
//! The new internal nodes are numbered in pre-order (a range's node is followed by its first
//! part's nodes, then its second part's), so the tree, node indices included, is the same
//! whatever the size of the jobs, how many threads ran them or in which order; its shape is
//! that of a plain recursive build.

use super::{DynamicTree, FixedStack, Node, Stack, NULL_NODE};
use crate::collision::aabb::Aabb;
use crate::parallel::Disjoint;
use glam::Vec3A;

/// Number of bins per axis of the SAH rebuild.
const BIN_COUNT: usize = 16;

/// Most units one job builds when the rebuild is shared among workers. Larger ranges are
/// split on the calling thread first: the top four levels of a 4,000-unit build (about a
/// fifth of its instructions) then run there, in exchange for some sixteen jobs to spread
/// over the workers.
pub const JOB_UNITS: usize = 256;

/// A job's work stack: (range start, range end, parent, is first child, pre-order slot). It
/// holds at most one entry per level of the subtree, plus one.
type WorkStack = FixedStack<(u32, u32, u32, bool, u32), 128>;

/// Storage of the rebuilds, reused from one to the next.
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// The subtrees the build arranges (leaves, or internal nodes kept whole), and per unit
    /// its box, centre and weight (`partition`), gathered so that the partitioning reads
    /// them in sequence.
    units: Vec<u32>,
    boxes: Vec<BinBox>,
    centers: Vec<Vec3A>,
    weights: Vec<f32>,
    /// Unit indices, partitioned in place range by range.
    order: Vec<u32>,
    /// Nodes created above the jobs, parents first.
    created: Vec<u32>,
    /// Ranges still to split: (start, end, parent, is first child, pre-order slot).
    work: Vec<(usize, usize, u32, bool, usize)>,
    jobs: Vec<Job>,
    /// The new internal nodes, by pre-order slot.
    reserved: Vec<u32>,
}

/// A range of `order` whose subtree one task builds, into the `len - 1` reserved nodes from
/// pre-order slot `slot` on.
#[derive(Clone, Copy, Debug)]
struct Job {
    start: u32,
    end: u32,
    slot: u32,
}

/// The jobs of a rebuild begun with `begin_rebuild`, ready to run on any threads.
pub struct RebuildJobs<'a> {
    nodes: Disjoint<'a, Node>,
    order: Disjoint<'a, u32>,
    boxes: &'a [BinBox],
    centers: &'a [Vec3A],
    weights: &'a [f32],
    units: &'a [u32],
    jobs: &'a [Job],
    reserved: &'a [u32],
}

impl DynamicTree {
    /// Rebuilds the whole hierarchy top-down with a binned surface-area heuristic. Proxy
    /// ids, boxes and user data are unchanged.
    pub fn rebuild(&mut self) {
        self.rebuild_serial(true);
    }

    /// Rebuilds, top-down with the same binned SAH, every internal node marked enlarged
    /// (`enlarge_proxy`): the subtrees below them that hold no enlarged proxy are kept
    /// whole and arranged anew. Leaves only the unmarked tree. Allocates nothing once its
    /// scratch has grown. Deterministic: the same tree gives the same result. The same as
    /// `begin_rebuild_enlarged`, every job, then `end_rebuild`.
    pub fn rebuild_enlarged(&mut self) {
        self.rebuild_serial(false);
    }

    fn rebuild_serial(&mut self, full: bool) {
        let jobs = self.begin_rebuild(full, |_| usize::MAX);
        if jobs > 0 {
            let run = self.rebuild_jobs();
            for k in 0..jobs {
                // SAFETY: each job once, one at a time.
                unsafe { run.run(k) };
            }
        }
        self.end_rebuild();
    }

    /// Begins the partial rebuild of `rebuild_enlarged` and returns its number of jobs
    /// (0 when nothing is enlarged). Until `end_rebuild`, only `rebuild_jobs` may be used.
    /// `job_units` gives the most units a job may build, from the number of units: the
    /// rest is split on this thread first.
    pub fn begin_rebuild_enlarged(&mut self, job_units: impl Fn(usize) -> usize) -> usize {
        if self.has_enlarged() {
            self.begin_rebuild(false, job_units)
        } else {
            self.scratch.created.clear();
            self.scratch.jobs.clear();
            0
        }
    }

    /// The jobs of the rebuild begun last, to run each exactly once before `end_rebuild`.
    pub fn rebuild_jobs(&mut self) -> RebuildJobs<'_> {
        let Scratch {
            units,
            boxes,
            centers,
            weights,
            order,
            jobs,
            reserved,
            ..
        } = &mut self.scratch;
        RebuildJobs {
            nodes: Disjoint::new(&mut self.nodes),
            order: Disjoint::new(order),
            boxes,
            centers,
            weights,
            units,
            jobs,
            reserved,
        }
    }

    /// Finishes the rebuild begun last, once all its jobs have run: refits the nodes above
    /// them.
    pub fn end_rebuild(&mut self) {
        let created = std::mem::take(&mut self.scratch.created);
        for &i in created.iter().rev() {
            self.refit(i);
        }
        self.scratch.created = created;
        self.scratch.jobs.clear();
    }

    /// Frees the internal nodes to rebuild (all, or the enlarged ones), splits what lies
    /// below them down to jobs of at most `job_units(units)` units (1: no jobs, all split
    /// here) and reserves the new nodes. Returns the number of jobs.
    pub(super) fn begin_rebuild(&mut self, full: bool, job_units: impl Fn(usize) -> usize) -> usize {
        let mut s = std::mem::take(&mut self.scratch);
        s.created.clear();
        s.jobs.clear();
        s.reserved.clear();
        if self.root == NULL_NODE {
            self.scratch = s;
            return 0;
        }
        // Collect the units in a deterministic (depth-first) order, free the nodes above.
        s.units.clear();
        let mut stack = Stack::new();
        stack.push(self.root);
        while let Some(i) = stack.pop() {
            let n = self.nodes[i as usize];
            if n.is_leaf() || !(full || n.enlarged) {
                s.units.push(i);
            } else {
                stack.push(n.child2);
                stack.push(n.child1);
                self.free_node(i);
            }
        }
        let nodes = &self.nodes;
        let unit = |i: &u32| &nodes[*i as usize];
        s.boxes.clear();
        s.boxes.extend(s.units.iter().map(|i| BinBox::from(&unit(i).aabb)));
        s.centers.clear();
        s.centers
            .extend(s.units.iter().map(|i| Vec3A::from(unit(i).aabb.center())));
        s.weights.clear();
        s.weights.extend(s.units.iter().map(|i| unit_weight(unit(i))));
        s.order.clear();
        s.order.extend(0..s.units.len() as u32);
        for _ in 1..s.units.len() {
            let i = self.allocate_node();
            self.nodes[i as usize].height = 1;
            s.reserved.push(i);
        }
        let job_units = job_units(s.units.len()).max(1);

        // Nodes are created parent-first: refitting in reverse creation order is bottom-up.
        s.work.clear();
        s.work.push((0, s.units.len(), NULL_NODE, true, 0));
        while let Some((start, end, parent, first, slot)) = s.work.pop() {
            let node = if end - start == 1 {
                s.units[s.order[start] as usize]
            } else if end - start <= job_units {
                s.jobs.push(Job {
                    start: start as u32,
                    end: end as u32,
                    slot: slot as u32,
                });
                s.reserved[slot]
            } else {
                let mid = partition(&mut s.order[start..end], &s.boxes, &s.centers, &s.weights) + start;
                let i = s.reserved[slot];
                s.created.push(i);
                s.work.push((mid, end, i, false, slot + (mid - start)));
                s.work.push((start, mid, i, true, slot + 1));
                i
            };
            self.nodes[node as usize].parent = parent;
            if parent == NULL_NODE {
                self.root = node;
            } else if first {
                self.nodes[parent as usize].child1 = node;
            } else {
                self.nodes[parent as usize].child2 = node;
            }
        }
        let jobs = s.jobs.len();
        self.scratch = s;
        jobs
    }
}

impl RebuildJobs<'_> {
    /// Builds job `k`'s subtree into its reserved nodes and refits them. Its root is
    /// already linked to the node above.
    ///
    /// # Safety
    /// No other call for the same `k` runs at the same time (each job runs once).
    pub unsafe fn run(&self, k: usize) {
        let job = self.jobs[k];
        let (start, end) = (job.start as usize, job.end as usize);
        // SAFETY: jobs cover disjoint ranges of `order`, and only job `k` uses this one.
        let order = unsafe { self.order.range(start, end) };
        // This job's nodes, by pre-order slot from its root's.
        let reserved = &self.reserved[job.slot as usize..job.slot as usize + (end - start - 1)];
        // SAFETY (every `nodes.at` below): the nodes reached are this job's reserved nodes
        // and its units, which no other job reaches, and each reference is dropped before
        // the next one to the same node is made.
        let node = |i: u32| unsafe { self.nodes.at(i as usize) };
        let mut work = WorkStack::new();
        work.push((0, order.len() as u32, NULL_NODE, true, 0));
        while let Some((lo, hi, parent, first, slot)) = work.pop() {
            let (lo, hi) = (lo as usize, hi as usize);
            let i = if hi - lo == 1 {
                self.units[order[lo] as usize]
            } else {
                reserved[slot as usize]
            };
            if hi - lo > 1 {
                let mid = partition(&mut order[lo..hi], self.boxes, self.centers, self.weights) + lo;
                work.push((mid as u32, hi as u32, i, false, slot + (mid - lo) as u32));
                work.push((lo as u32, mid as u32, i, true, slot + 1));
            }
            if parent != NULL_NODE {
                node(i).parent = parent;
                let p = node(parent);
                if first {
                    p.child1 = i;
                } else {
                    p.child2 = i;
                }
            }
        }
        // Pre-order puts every parent before its descendants.
        for &i in reserved.iter().rev() {
            let n = *node(i);
            let (a, b) = (*node(n.child1), *node(n.child2));
            node(i).refit_from(&a, &b);
        }
    }
}

impl Node {
    /// Box, height and enlarged mark of an internal node from its two children.
    #[inline]
    pub(super) fn refit_from(&mut self, a: &Node, b: &Node) {
        self.aabb = a.aabb.union(&b.aabb);
        self.height = 1 + a.height.max(b.height);
        // Keep "an enlarged node's ancestors are enlarged" through inserts, removals and
        // rotations, which refit every node up to the root.
        self.enlarged |= a.enlarged || b.enlarged;
    }
}

/// How many leaves a unit counts for in the SAH cost, estimated as `2^height` (a kept
/// subtree of a partial rebuild is about balanced; counted as one leaf, the few large
/// subtrees of a mostly-resting world were split off one by one, and the rebuilt top grew
/// deep).
#[inline]
fn unit_weight(n: &Node) -> f32 {
    (1u32 << n.height.clamp(0, 24)) as f32
}

/// A unit's box as the partitioning reads it: the same bounds as its `Aabb`, in SIMD lanes
/// (a union is two instructions).
#[derive(Clone, Copy, Debug)]
struct BinBox {
    min: Vec3A,
    max: Vec3A,
}

impl BinBox {
    const EMPTY: BinBox = BinBox {
        min: Vec3A::splat(f32::MAX),
        max: Vec3A::splat(-f32::MAX),
    };

    #[inline]
    fn union(&self, o: &BinBox) -> BinBox {
        BinBox {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// `Aabb::perimeter`, the same operations in the same order: half the surface area, or
    /// 0 for the empty box.
    #[inline]
    fn perimeter(&self) -> f32 {
        if self.min.x <= self.max.x {
            let d = self.max - self.min;
            d.x * d.y + d.y * d.z + d.z * d.x
        } else {
            0.0
        }
    }
}

impl From<&Aabb> for BinBox {
    fn from(b: &Aabb) -> Self {
        BinBox {
            min: b.min.into(),
            max: b.max.into(),
        }
    }
}

/// Splits `order` (indices of units) by the best binned SAH plane over the three axes;
/// returns the size of the first part (always in `1..len`). One pass over the units bins
/// them along all three axes.
fn partition(order: &mut [u32], boxes: &[BinBox], centers: &[Vec3A], weights: &[f32]) -> usize {
    let n = order.len();
    let frame = bin_frame(order, centers, weights);
    let units = Units {
        boxes,
        centers,
        weights,
    };
    let best = if n <= SMALL_RANGE {
        best_split_small(units, order, &frame)
    } else {
        best_split_binned(units, order, &frame)
    };
    let BinFrame { cmin, scale, .. } = frame;
    let Some((axis, split)) = best else {
        // All centres coincide: split by count.
        return n / 2;
    };
    // In-place partition: not stable, but deterministic.
    let mut i = 0;
    for j in 0..n {
        if bins_of(centers[order[j] as usize], cmin, scale)[axis] < split {
            order.swap(i, j);
            i += 1;
        }
    }
    debug_assert!(i > 0 && i < n);
    i
}

/// The binning of `order`'s units: their total weight, the least corner of their centres,
/// the scale from a centre's offset to its bin along each axis, and which axes the centres
/// spread along.
fn bin_frame(order: &[u32], centers: &[Vec3A], weights: &[f32]) -> BinFrame {
    let mut total = 0.0f32;
    let mut cmin = Vec3A::splat(f32::MAX);
    let mut cmax = Vec3A::splat(-f32::MAX);
    for &k in order.iter() {
        total += weights[k as usize];
        cmin = cmin.min(centers[k as usize]);
        cmax = cmax.max(centers[k as usize]);
    }
    let extent = cmax - cmin;
    // An axis along which all centres coincide (or that is not finite) is not split; its
    // scale of 0 puts every unit in bin 0.
    let valid = [0, 1, 2].map(|a| extent[a] > 0.0);
    let scale = Vec3A::from_array([0, 1, 2].map(|a| if valid[a] { BIN_COUNT as f32 / extent[a] } else { 0.0 }));
    BinFrame {
        total,
        cmin,
        scale,
        valid,
    }
}

/// What `bin_frame` finds.
#[derive(Clone, Copy, Debug)]
struct BinFrame {
    total: f32,
    cmin: Vec3A,
    scale: Vec3A,
    valid: [bool; 3],
}

/// The gathered per-unit data `partition` reads.
#[derive(Clone, Copy)]
struct Units<'a> {
    boxes: &'a [BinBox],
    centers: &'a [Vec3A],
    weights: &'a [f32],
}

/// Ranges of at most this many units are split by `best_split_small`.
const SMALL_RANGE: usize = 12;

/// The (axis, split bin) of least SAH cost over the bins of `order`'s centres, or `None`
/// when no axis separates them. Bins every unit along all three axes in one pass.
fn best_split_binned(units: Units, order: &[u32], frame: &BinFrame) -> Option<(usize, usize)> {
    let Units {
        boxes,
        centers,
        weights,
    } = units;
    let BinFrame {
        total,
        cmin,
        scale,
        valid,
    } = *frame;
    let n = order.len();
    let mut boxes_b = [[BinBox::EMPTY; BIN_COUNT]; 3];
    let mut counts = [[0u32; BIN_COUNT]; 3];
    let mut weights_b = [[0.0f32; BIN_COUNT]; 3];
    for &k in order.iter() {
        let (b, w) = (&boxes[k as usize], weights[k as usize]);
        let bins = bins_of(centers[k as usize], cmin, scale);
        for axis in 0..3 {
            let bin = bins[axis];
            boxes_b[axis][bin] = boxes_b[axis][bin].union(b);
            counts[axis][bin] += 1;
            weights_b[axis][bin] += w;
        }
    }
    let mut best: Option<(usize, usize)> = None; // (axis, split bin)
    let mut best_cost = f32::MAX;
    for axis in (0..3).filter(|&a| valid[a]) {
        let (boxes, counts, weights) = (&boxes_b[axis], &counts[axis], &weights_b[axis]);
        // Sweep from the right to get suffix areas, then from the left.
        let mut right_area = [0.0f32; BIN_COUNT];
        let mut acc = BinBox::EMPTY;
        for b in (1..BIN_COUNT).rev() {
            acc = acc.union(&boxes[b]);
            right_area[b] = acc.perimeter();
        }
        let mut left = BinBox::EMPTY;
        let (mut left_count, mut left_weight) = (0, 0.0f32);
        for split in 1..BIN_COUNT {
            left = left.union(&boxes[split - 1]);
            left_count += counts[split - 1] as usize;
            left_weight += weights[split - 1];
            if left_count == 0 || left_count == n {
                continue;
            }
            let cost = left.perimeter() * left_weight + right_area[split] * (total - left_weight);
            if cost < best_cost {
                best_cost = cost;
                best = Some((axis, split));
            }
        }
    }
    best
}

/// `best_split_binned` for a few units: the same choice, bit for bit, without 16 bins per
/// axis. Only the planes just past an occupied bin can differ in cost (every plane up to
/// the next occupied bin leaves the same units on each side, and the binned sweep keeps
/// the first of equal costs), so each axis tries those, with the left and right boxes and
/// weights built in the binned sweep's order of operations: a bin's box and weight from its
/// units in `order`'s order, the left side from the lowest bin up, the right side from the
/// highest down.
fn best_split_small(units: Units, order: &[u32], frame: &BinFrame) -> Option<(usize, usize)> {
    let Units {
        boxes,
        centers,
        weights,
    } = units;
    let BinFrame {
        total,
        cmin,
        scale,
        valid,
    } = *frame;
    let n = order.len();
    debug_assert!(n <= SMALL_RANGE);
    let mut bins = [[0usize; 3]; SMALL_RANGE];
    for (b, &k) in bins.iter_mut().zip(order) {
        *b = bins_of(centers[k as usize], cmin, scale);
    }
    let mut best: Option<(usize, usize)> = None;
    let mut best_cost = f32::MAX;
    for axis in (0..3).filter(|&a| valid[a]) {
        // Positions in `order`, stably sorted by bin (insertion sort: a few units).
        let mut by_bin = [0u8; SMALL_RANGE];
        for j in 0..n {
            let mut p = j;
            while p > 0 && bins[by_bin[p - 1] as usize][axis] > bins[j][axis] {
                by_bin[p] = by_bin[p - 1];
                p -= 1;
            }
            by_bin[p] = j as u8;
        }
        let by_bin = &by_bin[..n];
        // The occupied bins, lowest first: (bin, box, weight).
        let mut groups = [(0usize, BinBox::EMPTY, 0.0f32); SMALL_RANGE];
        let mut m = 0;
        for &j in by_bin {
            let bin = bins[j as usize][axis];
            if m == 0 || groups[m - 1].0 != bin {
                groups[m] = (bin, BinBox::EMPTY, 0.0);
                m += 1;
            }
            let k = order[j as usize] as usize;
            let g = &mut groups[m - 1];
            g.1 = g.1.union(&boxes[k]);
            g.2 += weights[k];
        }
        let groups = &groups[..m];
        // Right side's area past each group: the union from the highest group down.
        let mut right_area = [0.0f32; SMALL_RANGE];
        let mut acc = BinBox::EMPTY;
        for g in (1..m).rev() {
            acc = acc.union(&groups[g].1);
            right_area[g] = acc.perimeter();
        }
        let mut left = BinBox::EMPTY;
        let mut left_weight = 0.0f32;
        for g in 1..m {
            left = left.union(&groups[g - 1].1);
            left_weight += groups[g - 1].2;
            let cost = left.perimeter() * left_weight + right_area[g] * (total - left_weight);
            if cost < best_cost {
                best_cost = cost;
                best = Some((axis, groups[g - 1].0 + 1));
            }
        }
    }
    best
}

/// The bin of centre `c` along each axis: `(c - min) * scale` rounded down, at most the last
/// bin (`c >= min`, so never negative).
#[inline]
fn bins_of(c: Vec3A, min: Vec3A, scale: Vec3A) -> [usize; 3] {
    let t = ((c - min) * scale).min(Vec3A::splat((BIN_COUNT - 1) as f32));
    // `t` lies in [0, 15] (a NaN lane of the product takes the 15 of `min`), where
    // truncating to i32 is `as usize`'s rounding: one SIMD conversion for the three lanes
    // instead of three saturating scalar ones.
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_shuffle_epi32};
        // SAFETY: SSE2 is part of every x86_64 target; these touch registers only.
        unsafe {
            let i = _mm_cvttps_epi32(t.into());
            [
                _mm_cvtsi128_si32(i) as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b01_01_01_01>(i)) as usize,
                _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b10_10_10_10>(i)) as usize,
            ]
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    [t.x as usize, t.y as usize, t.z as usize]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::test_rnd::Rnd;

    /// The SIMD truncation of `bins_of` gives the scalar `as usize` bins, including at bin
    /// edges, for coincident centres and for the infinite scale of a subnormal extent.
    #[test]
    fn bins_of_truncates_as_the_scalar_conversion() {
        let scalar = |c: Vec3A, min: Vec3A, scale: Vec3A| {
            let t = ((c - min) * scale).min(Vec3A::splat((BIN_COUNT - 1) as f32));
            [t.x as usize, t.y as usize, t.z as usize]
        };
        let mut rnd = Rnd(0x0b1e_5eed_0000_0002);
        let min = Vec3A::new(-1.0, 0.0, 3.0);
        for k in 0..100_000 {
            let extent = Vec3A::new(rnd.f() * 10.0, 1e-40, [0.0, 2.0, 1e-3][k % 3]);
            let scale = Vec3A::from_array([0, 1, 2].map(|a| {
                if extent[a] > 0.0 {
                    BIN_COUNT as f32 / extent[a]
                } else {
                    0.0
                }
            }));
            let edge = (rnd.next_u64() % 17) as f32 / BIN_COUNT as f32;
            let f = if k % 2 == 0 { edge } else { rnd.f() };
            let c = min + extent * f;
            assert_eq!(bins_of(c, min, scale), scalar(c, min, scale), "{c} {scale}");
        }
    }

    /// The few-unit split chooses what the binned sweep chooses, over random ranges of 2 to
    /// `SMALL_RANGE` units: spread or clustered centres, shared coordinates (centres that
    /// coincide along an axis), equal boxes, signed zeros and subtree weights of 1 to 2^24.
    #[test]
    fn small_ranges_split_as_the_binned_sweep_does() {
        let mut rnd = Rnd(0x5eed_1234_abcd_0001);
        let mut chosen = 0;
        for case in 0..20_000 {
            let n = 2 + (rnd.next_u64() % (SMALL_RANGE as u64 - 1)) as usize;
            let spread = [1e-6, 1e-2, 1.0, 100.0][case % 4];
            let mut boxes: Vec<BinBox> = Vec::new();
            let mut centers: Vec<Vec3A> = Vec::new();
            let mut weights: Vec<f32> = Vec::new();
            for k in 0..n {
                let mut c = Vec3A::new(rnd.f(), rnd.f(), rnd.f()) * spread;
                // Snap some coordinates to a few values: coincident centres, ties.
                for a in 0..3 {
                    match rnd.next_u64() % 4 {
                        0 => c[a] = 0.0,
                        1 => c[a] = -0.0,
                        2 if k > 0 => c[a] = centers[k - 1][a],
                        _ => {}
                    }
                }
                let half = if rnd.next_u64() % 3 == 0 && k > 0 {
                    boxes[k - 1].max - centers[k - 1]
                } else {
                    Vec3A::new(rnd.f(), rnd.f(), rnd.f()) * spread
                };
                boxes.push(BinBox {
                    min: c - half,
                    max: c + half,
                });
                centers.push(c);
                weights.push((1u32 << (rnd.next_u64() % 25)) as f32);
            }
            let order: Vec<u32> = (0..n as u32).rev().collect();
            let frame = bin_frame(&order, &centers, &weights);
            let units = Units {
                boxes: &boxes,
                centers: &centers,
                weights: &weights,
            };
            let small = best_split_small(units, &order, &frame);
            let binned = best_split_binned(units, &order, &frame);
            assert_eq!(small, binned, "case {case}: {n} units");
            chosen += small.is_some() as usize;
        }
        // Most ranges are split along some axis; the rest fall back to halving.
        assert!(chosen > 15_000, "{chosen}");
    }
}
