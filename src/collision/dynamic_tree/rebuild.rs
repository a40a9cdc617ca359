//! Top-down binned SAH rebuild of a [`DynamicTree`].

use super::{DynamicTree, Stack, NULL_NODE};
use crate::collision::aabb::Aabb;
use crate::math::Vec3;

/// Number of bins per axis of the SAH rebuild.
const BIN_COUNT: usize = 16;

impl DynamicTree {
    /// Rebuilds the whole hierarchy top-down with a binned surface-area heuristic. Proxy
    /// ids, boxes and user data are unchanged. Allocates scratch memory.
    pub fn rebuild(&mut self) {
        if self.root == NULL_NODE {
            return;
        }
        // Collect leaves in a deterministic (depth-first) order, free internal nodes.
        let mut leaves: Vec<u32> = Vec::with_capacity(self.proxy_count as usize);
        let mut stack = Stack::new();
        stack.push(self.root);
        while let Some(i) = stack.pop() {
            let n = self.nodes[i as usize];
            if n.is_leaf() {
                leaves.push(i);
            } else {
                stack.push(n.child2);
                stack.push(n.child1);
                self.free_node(i);
            }
        }
        let centers: Vec<Vec3> = leaves.iter().map(|&l| self.nodes[l as usize].aabb.center()).collect();
        let mut order: Vec<u32> = (0..leaves.len() as u32).collect();

        // Work items: (start, end, parent, is first child). Internal nodes are created
        // parent-first; refitting them in reverse creation order is bottom-up.
        let mut created: Vec<u32> = Vec::with_capacity(leaves.len());
        let mut work: Vec<(usize, usize, u32, bool)> = vec![(0, leaves.len(), NULL_NODE, true)];
        while let Some((start, end, parent, first)) = work.pop() {
            let node = if end - start == 1 {
                leaves[order[start] as usize]
            } else {
                let mid = self.partition(&mut order[start..end], &leaves, &centers) + start;
                let i = self.allocate_node();
                self.nodes[i as usize].height = 1;
                created.push(i);
                work.push((mid, end, i, false));
                work.push((start, mid, i, true));
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
        for &i in created.iter().rev() {
            self.refit(i);
        }
    }

    /// Splits `order` (indices into `leaves`) by the best binned SAH plane over the three
    /// axes; returns the size of the first part (always in `1..len`).
    fn partition(&self, order: &mut [u32], leaves: &[u32], centers: &[Vec3]) -> usize {
        let n = order.len();
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
            for &k in order.iter() {
                let b = bin_of(centers[k as usize][axis], cmin[axis], scale);
                boxes[b] = boxes[b].union(&self.nodes[leaves[k as usize] as usize].aabb);
                counts[b] += 1;
            }
            // Sweep from the right to get suffix areas, then from the left.
            let mut right_area = [0.0f32; BIN_COUNT];
            let mut acc = Aabb::EMPTY;
            for b in (1..BIN_COUNT).rev() {
                acc = acc.union(&boxes[b]);
                right_area[b] = if acc.min.x <= acc.max.x { acc.perimeter() } else { 0.0 };
            }
            let mut left = Aabb::EMPTY;
            let mut left_count = 0;
            for split in 1..BIN_COUNT {
                left = left.union(&boxes[split - 1]);
                left_count += counts[split - 1];
                let right_count = n - left_count;
                if left_count == 0 || right_count == 0 {
                    continue;
                }
                let cost = left.perimeter() * left_count as f32 + right_area[split] * right_count as f32;
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
