//! Top-down binned SAH rebuilds of a [`DynamicTree`]: of the whole hierarchy
//! (`rebuild`), or of the part above the proxies enlarged in place since the last one
//! (`rebuild_enlarged`, Box2D v3's partial `b2DynamicTree_Rebuild`).

use super::{DynamicTree, Stack, NULL_NODE};
use crate::collision::aabb::Aabb;
use crate::math::Vec3;

/// Number of bins per axis of the SAH rebuild.
const BIN_COUNT: usize = 16;

/// Storage of the rebuilds, reused from one to the next.
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// The subtrees the build arranges (leaves, or internal nodes kept whole).
    units: Vec<u32>,
    centers: Vec<Vec3>,
    order: Vec<u32>,
    created: Vec<u32>,
    /// Work items: (start, end, parent, is first child).
    work: Vec<(usize, usize, u32, bool)>,
}

impl DynamicTree {
    /// Rebuilds the whole hierarchy top-down with a binned surface-area heuristic. Proxy
    /// ids, boxes and user data are unchanged.
    pub fn rebuild(&mut self) {
        self.rebuild_from_units(true);
    }

    /// Rebuilds, top-down with the same binned SAH, every internal node marked enlarged
    /// (`enlarge_proxy`): the subtrees below them that hold no enlarged proxy are kept
    /// whole and arranged anew. Leaves only the unmarked tree. Allocates nothing once its
    /// scratch has grown. Deterministic: the same tree gives the same result.
    pub fn rebuild_enlarged(&mut self) {
        if self.has_enlarged() {
            self.rebuild_from_units(false);
        }
    }

    /// Frees the internal nodes to rebuild (all, or the enlarged ones) and builds a new
    /// hierarchy over what lies below them.
    fn rebuild_from_units(&mut self, full: bool) {
        if self.root == NULL_NODE {
            return;
        }
        let mut s = std::mem::take(&mut self.scratch);
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
        s.centers.clear();
        s.centers
            .extend(s.units.iter().map(|&l| self.nodes[l as usize].aabb.center()));
        s.order.clear();
        s.order.extend(0..s.units.len() as u32);

        // Internal nodes are created parent-first; refitting them in reverse creation order
        // is bottom-up.
        s.created.clear();
        s.work.clear();
        s.work.push((0, s.units.len(), NULL_NODE, true));
        while let Some((start, end, parent, first)) = s.work.pop() {
            let node = if end - start == 1 {
                s.units[s.order[start] as usize]
            } else {
                let mid = self.partition(&mut s.order[start..end], &s.units, &s.centers) + start;
                let i = self.allocate_node();
                self.nodes[i as usize].height = 1;
                s.created.push(i);
                s.work.push((mid, end, i, false));
                s.work.push((start, mid, i, true));
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
        for &i in s.created.iter().rev() {
            self.refit(i);
        }
        self.scratch = s;
    }

    /// Splits `order` (indices into `units`) by the best binned SAH plane over the three
    /// axes; returns the size of the first part (always in `1..len`). A unit counts with
    /// the leaves it holds, estimated as `2^height` (a kept subtree of a partial rebuild is
    /// about balanced; counted as one leaf, the few large subtrees of a mostly-resting
    /// world were split off one by one, and the rebuilt top grew deep).
    fn partition(&self, order: &mut [u32], units: &[u32], centers: &[Vec3]) -> usize {
        let n = order.len();
        let weight = |k: u32| (1u32 << self.nodes[units[k as usize] as usize].height.clamp(0, 24)) as f32;
        let total: f32 = order.iter().map(|&k| weight(k)).sum();
        let mut cmin = Vec3::splat(f32::MAX);
        let mut cmax = Vec3::splat(-f32::MAX);
        for &k in order.iter() {
            cmin = cmin.min(centers[k as usize]);
            cmax = cmax.max(centers[k as usize]);
        }
        let mut best: Option<(usize, usize)> = None; // (axis, split bin)
        let mut best_cost = f32::MAX;
        for axis in 0..3 {
            let extent = cmax[axis] - cmin[axis];
            if extent.is_nan() || extent <= 0.0 {
                continue;
            }
            let scale = BIN_COUNT as f32 / extent;
            let mut boxes = [Aabb::EMPTY; BIN_COUNT];
            let mut counts = [0usize; BIN_COUNT];
            let mut weights = [0.0f32; BIN_COUNT];
            for &k in order.iter() {
                let b = bin_of(centers[k as usize][axis], cmin[axis], scale);
                boxes[b] = boxes[b].union(&self.nodes[units[k as usize] as usize].aabb);
                counts[b] += 1;
                weights[b] += weight(k);
            }
            // Sweep from the right to get suffix areas, then from the left.
            let mut right_area = [0.0f32; BIN_COUNT];
            let mut acc = Aabb::EMPTY;
            for b in (1..BIN_COUNT).rev() {
                acc = acc.union(&boxes[b]);
                right_area[b] = if acc.min.x <= acc.max.x { acc.perimeter() } else { 0.0 };
            }
            let mut left = Aabb::EMPTY;
            let (mut left_count, mut left_weight) = (0, 0.0f32);
            for split in 1..BIN_COUNT {
                left = left.union(&boxes[split - 1]);
                left_count += counts[split - 1];
                left_weight += weights[split - 1];
                let right_count = n - left_count;
                if left_count == 0 || right_count == 0 {
                    continue;
                }
                let cost = left.perimeter() * left_weight + right_area[split] * (total - left_weight);
                if cost < best_cost {
                    best_cost = cost;
                    best = Some((axis, split));
                }
            }
        }
        let Some((axis, split)) = best else {
            // All centers coincide: split by count.
            return n / 2;
        };
        let scale = BIN_COUNT as f32 / (cmax[axis] - cmin[axis]);
        // In-place partition: not stable, but deterministic.
        let mut i = 0;
        for j in 0..n {
            if bin_of(centers[order[j] as usize][axis], cmin[axis], scale) < split {
                order.swap(i, j);
                i += 1;
            }
        }
        debug_assert!(i > 0 && i < n);
        i
    }
}

#[inline]
fn bin_of(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BIN_COUNT - 1)
}
