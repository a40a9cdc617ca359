//! A static bounding volume hierarchy over a mesh's triangles, built once (binned SAH).
//!
//! Nodes are 32 bytes (`f32` bounds and two words) in depth-first order: an internal node's
//! left child is the next node and `data` holds the right child; a leaf (`count > 0`) holds
//! `count` triangles from `data`, triangles having been reordered into leaf order by the
//! builder. Ranges of more than `MAX_LEAF` triangles are split at the best of `BINS - 1`
//! planes per axis by the surface area heuristic (Wald 2007), or at the median when the
//! centroids do not separate; the build stops at `MAX_DEPTH` so a query's fixed stack never
//! overflows.

use crate::collision::aabb::Aabb;
use crate::math::Vec3;

/// Triangles per leaf when a split is no cheaper.
pub const MAX_LEAF: usize = 4;
/// SAH bins per axis.
const BINS: usize = 16;
/// Deepest node; a range still too big there becomes one leaf.
pub const MAX_DEPTH: usize = 48;

/// One node: bounds and either the right child (internal, `count == 0`) or the first
/// triangle of a leaf.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Node {
    pub min: [f32; 3],
    pub data: u32,
    pub max: [f32; 3],
    pub count: u32,
}

impl Node {
    #[inline]
    fn overlaps(&self, b: &Aabb) -> bool {
        self.min[0] <= b.max.x
            && self.max[0] >= b.min.x
            && self.min[1] <= b.max.y
            && self.max[1] >= b.min.y
            && self.min[2] <= b.max.z
            && self.max[2] >= b.min.z
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(Vec3::from(self.min), Vec3::from(self.max))
    }
}

/// Builds the nodes over items with the given bounds; returns the nodes and the item order
/// (leaf `data .. data + count` indexes this order).
pub fn build(bounds: &[Aabb]) -> (Vec<Node>, Vec<u32>) {
    let mut order: Vec<u32> = (0..bounds.len() as u32).collect();
    let centroids: Vec<Vec3> = bounds.iter().map(|b| b.center()).collect();
    let mut nodes = Vec::with_capacity((2 * bounds.len() / MAX_LEAF).max(1) + 1);
    if !bounds.is_empty() {
        let mut b = Builder {
            bounds,
            centroids: &centroids,
            order: &mut order,
            nodes: &mut nodes,
        };
        b.node(0, bounds.len(), 0);
    }
    nodes.shrink_to_fit();
    (nodes, order)
}

struct Builder<'a> {
    bounds: &'a [Aabb],
    centroids: &'a [Vec3],
    order: &'a mut [u32],
    nodes: &'a mut Vec<Node>,
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

impl Builder<'_> {
    fn range_bounds(&self, start: usize, end: usize) -> (Aabb, Aabb) {
        let (mut all, mut cent) = (Aabb::EMPTY, Aabb::EMPTY);
        for &i in &self.order[start..end] {
            all = all.union(&self.bounds[i as usize]);
            let c = self.centroids[i as usize];
            cent = cent.union(&Aabb::new(c, c));
        }
        (all, cent)
    }

    /// Emits the node over `order[start..end]` and its subtree; returns its index.
    fn node(&mut self, start: usize, end: usize, depth: usize) -> u32 {
        let (all, cent) = self.range_bounds(start, end);
        let index = self.nodes.len() as u32;
        self.nodes.push(Node {
            min: all.min.into(),
            data: start as u32,
            max: all.max.into(),
            count: (end - start) as u32,
        });
        let count = end - start;
        if count <= MAX_LEAF || depth >= MAX_DEPTH {
            return index;
        }
        let mid = match self.sah_split(start, end, &cent) {
            Some(m) => m,
            None => self.median_split(start, end, &cent),
        };
        self.node(start, mid, depth + 1);
        let right = self.node(mid, end, depth + 1);
        let n = &mut self.nodes[index as usize];
        n.data = right;
        n.count = 0;
        index
    }

    /// The cheapest binned split, partitioned in place; `None` when the centroids do not
    /// spread over two bins.
    fn sah_split(&mut self, start: usize, end: usize, cent: &Aabb) -> Option<usize> {
        let extent = cent.max - cent.min;
        let mut best: Option<(f32, usize, usize)> = None; // cost, axis, split bin
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / extent[axis];
            let mut bins = [Bin {
                bounds: Aabb::EMPTY,
                count: 0,
            }; BINS];
            for &i in &self.order[start..end] {
                let b = bin_of(self.centroids[i as usize][axis], cent.min[axis], scale);
                bins[b].count += 1;
                bins[b].bounds = bins[b].bounds.union(&self.bounds[i as usize]);
            }
            // Right-to-left sweep of areas and counts, then left to right for the cost.
            let mut right_area = [0.0f32; BINS];
            let mut right_count = [0usize; BINS];
            let (mut acc, mut n) = (Aabb::EMPTY, 0usize);
            for k in (1..BINS).rev() {
                acc = acc.union(&bins[k].bounds);
                n += bins[k].count;
                right_area[k] = if n > 0 { acc.perimeter() } else { 0.0 };
                right_count[k] = n;
            }
            let (mut acc, mut n) = (Aabb::EMPTY, 0usize);
            for k in 0..BINS - 1 {
                acc = acc.union(&bins[k].bounds);
                n += bins[k].count;
                let (nr, ar) = (right_count[k + 1], right_area[k + 1]);
                if n == 0 || nr == 0 {
                    continue;
                }
                let cost = acc.perimeter() * n as f32 + ar * nr as f32;
                if best.map_or(true, |b| cost < b.0) {
                    best = Some((cost, axis, k + 1));
                }
            }
        }
        let (_, axis, split) = best?;
        let scale = BINS as f32 / extent[axis];
        let (lo, centroids) = (cent.min[axis], self.centroids);
        let slice = &mut self.order[start..end];
        let mut left = 0;
        for k in 0..slice.len() {
            if bin_of(centroids[slice[k] as usize][axis], lo, scale) < split {
                slice.swap(left, k);
                left += 1;
            }
        }
        (left > 0 && left < slice.len()).then_some(start + left)
    }

    /// Halves the range at the median centroid of the longest centroid axis (also when the
    /// centroids coincide: the order then decides).
    fn median_split(&mut self, start: usize, end: usize, cent: &Aabb) -> usize {
        let e = cent.max - cent.min;
        let axis = if e.x >= e.y && e.x >= e.z {
            0
        } else if e.y >= e.z {
            1
        } else {
            2
        };
        let mid = (end - start) / 2;
        let centroids = self.centroids;
        self.order[start..end].select_nth_unstable_by(mid, |&a, &b| {
            centroids[a as usize][axis]
                .total_cmp(&centroids[b as usize][axis])
                .then(a.cmp(&b))
        });
        start + mid
    }
}

#[inline]
fn bin_of(c: f32, lo: f32, scale: f32) -> usize {
    (((c - lo) * scale) as usize).min(BINS - 1)
}

/// Calls `visit(first, count)` for every leaf whose bounds overlap `b` (leaf triangles are
/// `first .. first + count` in leaf order). `visit` returns false to stop.
#[inline]
pub fn query(nodes: &[Node], b: &Aabb, mut visit: impl FnMut(u32, u32) -> bool) {
    if nodes.is_empty() {
        return;
    }
    let mut stack = [0u32; MAX_DEPTH + 2];
    let mut top = 1usize;
    while top > 0 {
        top -= 1;
        let mut i = stack[top] as usize;
        loop {
            let n = &nodes[i];
            if !n.overlaps(b) {
                break;
            }
            if n.count > 0 {
                if !visit(n.data, n.count) {
                    return;
                }
                break;
            }
            // Descend left; the right child waits on the stack.
            stack[top] = n.data;
            top += 1;
            i += 1;
        }
    }
}

/// Depth of the tree (a single leaf has depth 1).
pub fn depth(nodes: &[Node]) -> usize {
    fn walk(nodes: &[Node], i: usize) -> usize {
        let n = &nodes[i];
        if n.count > 0 {
            1
        } else {
            1 + walk(nodes, i + 1).max(walk(nodes, n.data as usize))
        }
    }
    if nodes.is_empty() {
        0
    } else {
        walk(nodes, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_is_32_bytes() {
        assert_eq!(std::mem::size_of::<Node>(), 32);
    }

    #[test]
    fn coincident_items_still_build_and_query() {
        let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let bounds = vec![b; 1000];
        let (nodes, order) = build(&bounds);
        assert!(depth(&nodes) <= MAX_DEPTH + 1);
        let mut seen = vec![false; 1000];
        query(&nodes, &b, |first, count| {
            for k in first..first + count {
                seen[order[k as usize] as usize] = true;
            }
            true
        });
        assert!(seen.iter().all(|&s| s));
    }
}
