//! Broadphase dynamic AABB tree: a bounding volume hierarchy over fat boxes.
//!
//! The design follows Box2D v3's `b2DynamicTree` in 3D: nodes live in a `Vec` and refer to
//! each other by index, freed nodes go on an intrusive free list (no allocation once the
//! node count is stable), a proxy id is the index of its leaf node. Insertion picks the
//! sibling by the surface-area heuristic with branch and bound, then walks back to the
//! root refitting boxes and applying local tree rotations that reduce the summed area,
//! which keeps the tree shallow under incremental insert / remove / move. `rebuild`
//! rebuilds the whole hierarchy top-down with a binned SAH.
//!
//! Every operation is deterministic: the same sequence of calls gives the same tree.

use crate::collision::aabb::Aabb;
use crate::math::Vec3;
use glam::Vec3A;

/// The null node / proxy index.
pub const NULL_NODE: u32 = u32::MAX;

/// Capacity of the on-stack traversal stack; deeper trees spill into a heap `Vec`.
const STACK_CAPACITY: usize = 256;

#[derive(Clone, Copy, Debug)]
struct Node {
    aabb: Aabb,
    /// Parent index; the next free node while on the free list.
    parent: u32,
    child1: u32,
    child2: u32,
    user_data: u32,
    /// 0 for a leaf, -1 for a free node.
    height: i32,
    /// An internal node whose box was enlarged in place (`enlarge_proxy`) or that lies
    /// above such a node: `rebuild_enlarged` rebuilds it. Every ancestor of an enlarged
    /// node is enlarged too (`refit` keeps this). Never set on leaves.
    enlarged: bool,
}

impl Node {
    const FREE: Node = Node {
        aabb: Aabb::EMPTY,
        parent: NULL_NODE,
        child1: NULL_NODE,
        child2: NULL_NODE,
        user_data: 0,
        height: -1,
        enlarged: false,
    };

    #[inline]
    fn is_leaf(&self) -> bool {
        self.height == 0
    }
}

/// A dynamic bounding volume hierarchy. Proxies are leaves; their boxes are stored as given
/// (the caller fattens them).
#[derive(Clone, Debug)]
pub struct DynamicTree {
    nodes: Vec<Node>,
    root: u32,
    free_list: u32,
    /// Allocated nodes (leaves and internal).
    node_count: u32,
    proxy_count: u32,
    /// Scratch of the rebuilds, kept so that a partial rebuild per step allocates nothing.
    scratch: rebuild::Scratch,
}

impl Default for DynamicTree {
    fn default() -> Self {
        Self::new()
    }
}

/// Traversal stack: a fixed array that spills into a `Vec` only if it overflows (a tree
/// deeper than the capacity).
struct FixedStack<T, const N: usize> {
    items: [T; N],
    len: usize,
    spill: Vec<T>,
}

/// Node stack of the box queries and walks.
type Stack = FixedStack<u32, STACK_CAPACITY>;
/// Ray traversal stack of (node, entry parameter).
type RayStack = FixedStack<(u32, f32), RAY_STACK_CAPACITY>;

impl<T: Copy + Default, const N: usize> FixedStack<T, N> {
    #[inline]
    fn new() -> Self {
        FixedStack {
            items: [T::default(); N],
            len: 0,
            spill: Vec::new(),
        }
    }

    #[inline]
    fn push(&mut self, v: T) {
        if self.len < N {
            self.items[self.len] = v;
            self.len += 1;
        } else {
            self.spill.push(v);
        }
    }

    /// The spill holds entries only while the array is full (pushes spill only then, and
    /// pops drain the spill first), so the spill is looked at only then.
    #[inline]
    fn pop(&mut self) -> Option<T> {
        if self.len == N {
            if let Some(v) = self.spill.pop() {
                return Some(v);
            }
        }
        if self.len > 0 {
            self.len -= 1;
            Some(self.items[self.len])
        } else {
            None
        }
    }
}

/// The stack of a tree walk.
trait WalkStack<T> {
    fn push(&mut self, v: T);
    fn pop(&mut self) -> Option<T>;
}

impl<T: Copy + Default, const N: usize> WalkStack<T> for FixedStack<T, N> {
    #[inline]
    fn push(&mut self, v: T) {
        FixedStack::push(self, v)
    }
    #[inline]
    fn pop(&mut self) -> Option<T> {
        FixedStack::pop(self)
    }
}

/// A fixed array without a spill, for the walks of a tree lower than `N` (whose stack never
/// holds `N` entries: at most one per level below the root); one past that would panic.
struct BoundedStack<T, const N: usize> {
    items: [T; N],
    len: usize,
}

impl<T: Copy + Default, const N: usize> BoundedStack<T, N> {
    #[inline]
    fn new() -> Self {
        BoundedStack {
            items: [T::default(); N],
            len: 0,
        }
    }
}

impl<T: Copy, const N: usize> WalkStack<T> for BoundedStack<T, N> {
    #[inline]
    fn push(&mut self, v: T) {
        self.items[self.len] = v;
        self.len += 1;
    }
    #[inline]
    fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

/// Slab test of the segment `origin + t * dir`, `t` in `[0, max_t]`, against `b`. `inv_dir`
/// is the component-wise reciprocal of `dir` (ignored where `dir` is zero). Returns the
/// entry parameter (0 when the origin is inside). Monotone: a box containing `b` is always
/// hit too, so the tree never culls a leaf this test would accept.
#[inline]
pub fn ray_aabb_entry(origin: Vec3, dir: Vec3, inv_dir: Vec3, max_t: f32, b: &Aabb) -> Option<f32> {
    let mut t0 = 0.0f32;
    let mut t1 = max_t;
    for a in 0..3 {
        let o = origin[a];
        if dir[a] == 0.0 {
            if o < b.min[a] || o > b.max[a] {
                return None;
            }
        } else {
            let inv = inv_dir[a];
            let mut ta = (b.min[a] - o) * inv;
            let mut tb = (b.max[a] - o) * inv;
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                return None;
            }
        }
    }
    Some(t0)
}

/// A segment prepared for many slab tests: origin and reciprocal direction in SIMD lanes.
/// Rays with a zero (or subnormal) direction component, whose reciprocal is infinite, take
/// the scalar [`ray_aabb_entry`] instead, so the answer is always that function's.
#[derive(Clone, Copy)]
pub struct RaySlabs {
    origin: Vec3A,
    inv: Vec3A,
    dir: Vec3,
    /// Every reciprocal is finite: the lane-wise test applies.
    finite: bool,
}

impl RaySlabs {
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        let inv = reciprocal(dir);
        RaySlabs {
            origin: origin.into(),
            inv: inv.into(),
            dir,
            finite: inv.is_finite() && dir.cmpne(Vec3::ZERO).all(),
        }
    }

    /// [`RaySlabs::entry`] for a ray whose reciprocals are all finite (`finite`), without
    /// the branch: the same value, found with comparisons that need no NaN handling
    /// (nothing here is NaN: finite reciprocals, finite boxes, `max_t` never NaN).
    #[inline(always)]
    fn entry_finite(&self, max_t: f32, b: &Aabb) -> Option<f32> {
        debug_assert!(self.finite);
        let ta = (Vec3A::from(b.min) - self.origin) * self.inv;
        let tb = (Vec3A::from(b.max) - self.origin) * self.inv;
        let t0 = ta.min(tb).max(Vec3A::ZERO).max_element();
        let t1 = ta.max(tb).min_element();
        if t0 <= t1 && t0 <= max_t {
            Some(t0)
        } else {
            None
        }
    }

    /// The same answer as [`ray_aabb_entry`]: the entry parameter of the segment `[0,
    /// max_t]` into `b` (0 when the origin is inside), or `None`.
    #[inline]
    pub fn entry(&self, max_t: f32, b: &Aabb) -> Option<f32> {
        if !self.finite {
            return ray_aabb_entry(self.origin.into(), self.dir, self.inv.into(), max_t, b);
        }
        let ta = (Vec3A::from(b.min) - self.origin) * self.inv;
        let tb = (Vec3A::from(b.max) - self.origin) * self.inv;
        let t0 = ta.min(tb).max_element().max(0.0);
        let t1 = ta.max(tb).min_element().min(max_t);
        if t0 <= t1 {
            Some(t0)
        } else {
            None
        }
    }
}

/// Capacity of the on-stack ray traversal stack (entries of node and entry parameter).
const RAY_STACK_CAPACITY: usize = 128;

/// Capacity of the traversal stacks of `query` and `ray_cast` in a tree lower than it (the
/// settled 4,000-body pile's tree is 15 to 17 levels high): they never spill there, and a
/// small stack is cheaper to set up per call.
const SHALLOW_STACK: usize = 32;

#[inline]
fn reciprocal(dir: Vec3) -> Vec3 {
    let r = |x: f32| if x == 0.0 { 0.0 } else { 1.0 / x };
    Vec3::new(r(dir.x), r(dir.y), r(dir.z))
}

impl DynamicTree {
    pub fn new() -> Self {
        DynamicTree {
            nodes: Vec::new(),
            root: NULL_NODE,
            free_list: NULL_NODE,
            node_count: 0,
            proxy_count: 0,
            scratch: Default::default(),
        }
    }

    /// Pre-allocates room for `proxies` leaves (and their internal nodes).
    pub fn with_capacity(proxies: usize) -> Self {
        let mut t = Self::new();
        t.nodes.reserve(2 * proxies);
        t
    }

    fn allocate_node(&mut self) -> u32 {
        self.node_count += 1;
        if self.free_list != NULL_NODE {
            let i = self.free_list;
            self.free_list = self.nodes[i as usize].parent;
            self.nodes[i as usize] = Node {
                height: 0,
                ..Node::FREE
            };
            i
        } else {
            let i = self.nodes.len() as u32;
            assert!(i != NULL_NODE, "dynamic tree node overflow");
            self.nodes.push(Node {
                height: 0,
                ..Node::FREE
            });
            i
        }
    }

    fn free_node(&mut self, i: u32) {
        debug_assert!(self.nodes[i as usize].height >= 0);
        self.nodes[i as usize] = Node {
            parent: self.free_list,
            ..Node::FREE
        };
        self.free_list = i;
        self.node_count -= 1;
    }

    #[inline]
    fn check_proxy(&self, proxy: u32) -> &Node {
        let n = &self.nodes[proxy as usize];
        assert!(n.is_leaf(), "invalid proxy id {proxy}");
        n
    }

    /// Creates a leaf for `aabb` and returns its proxy id. Ids of destroyed proxies are
    /// reused (most recently destroyed first).
    pub fn create_proxy(&mut self, aabb: Aabb, user_data: u32) -> u32 {
        let leaf = self.allocate_node();
        let n = &mut self.nodes[leaf as usize];
        n.aabb = aabb;
        n.user_data = user_data;
        n.height = 0;
        self.insert_leaf(leaf);
        self.proxy_count += 1;
        leaf
    }

    pub fn destroy_proxy(&mut self, proxy: u32) {
        self.check_proxy(proxy);
        self.remove_leaf(proxy);
        self.free_node(proxy);
        self.proxy_count -= 1;
    }

    /// Replaces the box of a proxy in place, without moving the leaf: its ancestors' boxes
    /// grow to hold the new box (and stay as large) and are marked enlarged, up to the
    /// root, for `rebuild_enlarged` to rebuild that part of the tree. Far cheaper than
    /// `move_proxy`, and the tree stays valid for queries in between (Box2D v3's
    /// `b2DynamicTree_EnlargeProxy`).
    pub fn enlarge_proxy(&mut self, proxy: u32, aabb: Aabb) {
        self.check_proxy(proxy);
        self.nodes[proxy as usize].aabb = aabb;
        let mut i = self.nodes[proxy as usize].parent;
        // Grow the boxes while they change...
        while i != NULL_NODE {
            let n = &mut self.nodes[i as usize];
            let grown = n.aabb.union(&aabb);
            let changed = !same_box(&grown, &n.aabb);
            n.aabb = grown;
            n.enlarged = true;
            i = n.parent;
            if !changed {
                break;
            }
        }
        // ...then mark the rest of the way up, up to the first node already marked (whose
        // ancestors are all marked).
        while i != NULL_NODE && !self.nodes[i as usize].enlarged {
            self.nodes[i as usize].enlarged = true;
            i = self.nodes[i as usize].parent;
        }
    }

    /// Whether `rebuild_enlarged` has anything to do.
    #[inline]
    pub fn has_enlarged(&self) -> bool {
        self.root != NULL_NODE && self.nodes[self.root as usize].enlarged
    }

    /// Replaces the box of a proxy: removes the leaf and reinserts it.
    pub fn move_proxy(&mut self, proxy: u32, aabb: Aabb) {
        self.check_proxy(proxy);
        self.remove_leaf(proxy);
        self.nodes[proxy as usize].aabb = aabb;
        self.insert_leaf(proxy);
    }

    #[inline]
    pub fn fat_aabb(&self, proxy: u32) -> Aabb {
        self.check_proxy(proxy).aabb
    }

    #[inline]
    pub fn user_data(&self, proxy: u32) -> u32 {
        self.check_proxy(proxy).user_data
    }

    /// Height of the tree: 0 for a single leaf, 0 when empty.
    pub fn height(&self) -> u32 {
        if self.root == NULL_NODE {
            0
        } else {
            self.nodes[self.root as usize].height as u32
        }
    }

    pub fn proxy_count(&self) -> u32 {
        self.proxy_count
    }

    /// Allocated nodes, leaves and internal.
    pub fn node_count(&self) -> u32 {
        self.node_count
    }

    pub fn root(&self) -> u32 {
        self.root
    }

    /// The box of the whole tree, `Aabb::EMPTY` when empty.
    pub fn root_aabb(&self) -> Aabb {
        if self.root == NULL_NODE {
            Aabb::EMPTY
        } else {
            self.nodes[self.root as usize].aabb
        }
    }

    /// Calls `f(proxy, user_data)` for every proxy whose box overlaps `aabb`, until `f`
    /// returns false. Depth first, the second child's subtree before the first's; children
    /// are tested before they are pushed, so only overlapping nodes reach the stack.
    pub fn query<F: FnMut(u32, u32) -> bool>(&self, aabb: &Aabb, f: F) {
        if self.root == NULL_NODE || !self.nodes[self.root as usize].aabb.overlaps(aabb) {
            return;
        }
        // The walk holds at most one node per level below the root on its stack (the first
        // children not yet walked), so a tree that low never spills: a smaller stack, less
        // to clear per call.
        if self.height() < SHALLOW_STACK as u32 {
            self.query_with(aabb, f, BoundedStack::<u32, SHALLOW_STACK>::new())
        } else {
            self.query_with(aabb, f, Stack::new())
        }
    }

    /// `query` with a stack of `N` entries. The node walked next is kept out of the stack:
    /// of two overlapping children the second is walked at once and the first pushed, which
    /// is the order pushing both and popping the second would give.
    #[inline]
    fn query_with<F: FnMut(u32, u32) -> bool, S: WalkStack<u32>>(&self, aabb: &Aabb, mut f: F, mut stack: S) {
        let nodes = &self.nodes[..];
        let mut i = self.root;
        loop {
            let n = &nodes[i as usize];
            if n.is_leaf() {
                if !f(i, n.user_data) {
                    return;
                }
            } else {
                let first = nodes[n.child1 as usize].aabb.overlaps(aabb);
                if nodes[n.child2 as usize].aabb.overlaps(aabb) {
                    if first {
                        stack.push(n.child1);
                    }
                    i = n.child2;
                    continue;
                }
                if first {
                    i = n.child1;
                    continue;
                }
            }
            match stack.pop() {
                Some(next) => i = next,
                None => return,
            }
        }
    }

    /// Casts the segment `origin + t * dir`, `t` in `[0, max_t]`, Box2D style: `f(proxy,
    /// user_data, max_t_so_far)` is called for every proxy whose box the (clipped) segment
    /// hits, and returns 0 to terminate, a negative value to ignore the proxy, or a value
    /// `t` in `(0, max_t_so_far]` to clip the segment to `[0, t]` (returning
    /// `max_t_so_far` continues unclipped). Returns the number of node boxes tested.
    ///
    /// Front to back: both children of a node are slab-tested when the node is reached and
    /// pushed with their entry parameters, the nearer one on top; a node popped with an
    /// entry past the (clipped) `max_t` is dropped unvisited. A caller clipping the ray at
    /// each hit (a closest-hit query) so meets near proxies first and prunes the rest.
    pub fn ray_cast<F: FnMut(u32, u32, f32) -> f32>(&self, origin: Vec3, dir: Vec3, max_t: f32, f: F) -> u32 {
        if self.root == NULL_NODE || max_t.is_nan() || max_t < 0.0 {
            return 0;
        }
        let ray = RaySlabs::new(origin, dir);
        // As in `query`, at most one stacked node per level below the root.
        let shallow = self.height() < SHALLOW_STACK as u32;
        match (ray.finite, shallow) {
            (true, true) => self.ray_cast_with(
                max_t,
                |t, b| ray.entry_finite(t, b),
                f,
                BoundedStack::<_, SHALLOW_STACK>::new(),
            ),
            (true, false) => self.ray_cast_with(max_t, |t, b| ray.entry_finite(t, b), f, RayStack::new()),
            (false, _) => self.ray_cast_with(max_t, |t, b| ray.entry(t, b), f, RayStack::new()),
        }
    }

    /// `ray_cast` with the slab test `entry` and a stack of `N` entries. The nearer child
    /// hit is walked at once instead of being pushed and popped straight back (the same
    /// order), so only farther children wait on the stack.
    #[inline]
    fn ray_cast_with<E, F, S>(&self, max_t: f32, entry: E, mut f: F, mut stack: S) -> u32
    where
        E: Fn(f32, &Aabb) -> Option<f32>,
        F: FnMut(u32, u32, f32) -> f32,
        S: WalkStack<(u32, f32)>,
    {
        let nodes = &self.nodes[..];
        let mut max_t = max_t;
        let mut tested = 1u32;
        let Some(t_root) = entry(max_t, &nodes[self.root as usize].aabb) else {
            return tested;
        };
        let mut next = (self.root, t_root);
        loop {
            let (i, at) = next;
            // A node reached straight from its parent entered before the current `max_t`
            // (nothing clipped it in between); a stacked one may have been passed since.
            if at <= max_t {
                let n = &nodes[i as usize];
                if n.is_leaf() {
                    let value = f(i, n.user_data, max_t);
                    if value == 0.0 {
                        return tested;
                    }
                    if value > 0.0 && value <= max_t {
                        max_t = value;
                    }
                } else {
                    let (a, b) = (n.child1, n.child2);
                    tested += 2;
                    let ea = entry(max_t, &nodes[a as usize].aabb);
                    let eb = entry(max_t, &nodes[b as usize].aabb);
                    match (ea, eb) {
                        (Some(ta), Some(tb)) => {
                            // The nearer entry is walked first (ties: the first child).
                            if ta <= tb {
                                stack.push((b, tb));
                                next = (a, ta);
                            } else {
                                stack.push((a, ta));
                                next = (b, tb);
                            }
                            continue;
                        }
                        (Some(ta), None) => {
                            next = (a, ta);
                            continue;
                        }
                        (None, Some(tb)) => {
                            next = (b, tb);
                            continue;
                        }
                        (None, None) => {}
                    }
                }
            }
            match stack.pop() {
                Some(s) => next = s,
                None => return tested,
            }
        }
    }

    /// Sum of the perimeters (half surface areas) of the internal nodes other than the
    /// root, divided by the root's: Box2D's tree quality metric (lower is better).
    pub fn area_ratio(&self) -> f32 {
        if self.root == NULL_NODE {
            return 0.0;
        }
        let root_area = self.nodes[self.root as usize].aabb.perimeter();
        let total: f32 = self
            .nodes
            .iter()
            .enumerate()
            .filter(|(i, n)| n.height > 0 && *i as u32 != self.root)
            .map(|(_, n)| n.aabb.perimeter())
            .sum();
        if root_area > 0.0 {
            total / root_area
        } else {
            0.0
        }
    }

    // ---------------------------------------------------------------------------------
    // Insertion and removal

    /// Cheapest sibling for a new leaf with box `d` (SAH with branch and bound, following a
    /// single greedy path like Box2D v3's `b2FindBestSibling`).
    fn find_best_sibling(&self, d: &Aabb) -> u32 {
        let center_d = d.center();
        let area_d = d.perimeter();
        let nodes = &self.nodes;

        let root_box = nodes[self.root as usize].aabb;
        let mut area_base = root_box.perimeter();
        let mut direct_cost = root_box.union(d).perimeter();
        let mut inherited_cost = 0.0f32;

        let mut best = self.root;
        let mut best_cost = direct_cost;
        let mut index = self.root;
        while !nodes[index as usize].is_leaf() {
            let n = &nodes[index as usize];
            let (c1, c2) = (n.child1, n.child2);

            // Cost of making `index` the sibling.
            let cost = direct_cost + inherited_cost;
            if cost < best_cost {
                best = index;
                best_cost = cost;
            }
            // Area growth of this node, inherited by everything below.
            inherited_cost += direct_cost - area_base;

            let n1 = &nodes[c1 as usize];
            let n2 = &nodes[c2 as usize];
            let (leaf1, leaf2) = (n1.is_leaf(), n2.is_leaf());

            let direct1 = n1.aabb.union(d).perimeter();
            let mut area1 = 0.0;
            let mut lower1 = f32::MAX;
            if leaf1 {
                let cost1 = direct1 + inherited_cost;
                if cost1 < best_cost {
                    best = c1;
                    best_cost = cost1;
                }
            } else {
                area1 = n1.aabb.perimeter();
                // Either child 1 itself is the sibling, or a descendant is, which costs at
                // least a new node of area(d) plus child 1's growth.
                lower1 = inherited_cost + direct1 + (area_d - area1).min(0.0);
            }

            let direct2 = n2.aabb.union(d).perimeter();
            let mut area2 = 0.0;
            let mut lower2 = f32::MAX;
            if leaf2 {
                let cost2 = direct2 + inherited_cost;
                if cost2 < best_cost {
                    best = c2;
                    best_cost = cost2;
                }
            } else {
                area2 = n2.aabb.perimeter();
                lower2 = inherited_cost + direct2 + (area_d - area2).min(0.0);
            }

            if leaf1 && leaf2 {
                break;
            }
            if best_cost <= lower1 && best_cost <= lower2 {
                break;
            }
            if lower1 == lower2 && !leaf1 {
                // No clear choice (e.g. both children contain d): use centroid distance.
                lower1 = (n1.aabb.center() - center_d).length_squared();
                lower2 = (n2.aabb.center() - center_d).length_squared();
            }
            if lower1 < lower2 && !leaf1 {
                index = c1;
                area_base = area1;
                direct_cost = direct1;
            } else {
                index = c2;
                area_base = area2;
                direct_cost = direct2;
            }
        }
        best
    }

    fn insert_leaf(&mut self, leaf: u32) {
        if self.root == NULL_NODE {
            self.root = leaf;
            self.nodes[leaf as usize].parent = NULL_NODE;
            return;
        }
        let leaf_box = self.nodes[leaf as usize].aabb;
        let sibling = self.find_best_sibling(&leaf_box);

        let old_parent = self.nodes[sibling as usize].parent;
        let new_parent = self.allocate_node();
        {
            let s = self.nodes[sibling as usize];
            let p = &mut self.nodes[new_parent as usize];
            p.parent = old_parent;
            p.aabb = leaf_box.union(&s.aabb);
            p.height = s.height + 1;
            p.child1 = sibling;
            p.child2 = leaf;
        }
        if old_parent != NULL_NODE {
            let op = &mut self.nodes[old_parent as usize];
            if op.child1 == sibling {
                op.child1 = new_parent;
            } else {
                op.child2 = new_parent;
            }
        } else {
            self.root = new_parent;
        }
        self.nodes[sibling as usize].parent = new_parent;
        self.nodes[leaf as usize].parent = new_parent;

        // Refit and rotate on the way up.
        let mut index = new_parent;
        while index != NULL_NODE {
            self.refit(index);
            self.rotate(index);
            index = self.nodes[index as usize].parent;
        }
    }

    fn remove_leaf(&mut self, leaf: u32) {
        if leaf == self.root {
            self.root = NULL_NODE;
            return;
        }
        let parent = self.nodes[leaf as usize].parent;
        let (grand_parent, sibling) = {
            let p = &self.nodes[parent as usize];
            (p.parent, if p.child1 == leaf { p.child2 } else { p.child1 })
        };
        self.nodes[sibling as usize].parent = grand_parent;
        self.free_node(parent);
        if grand_parent == NULL_NODE {
            self.root = sibling;
            return;
        }
        let gp = &mut self.nodes[grand_parent as usize];
        if gp.child1 == parent {
            gp.child1 = sibling;
        } else {
            gp.child2 = sibling;
        }
        let mut index = grand_parent;
        while index != NULL_NODE {
            self.refit(index);
            index = self.nodes[index as usize].parent;
        }
    }

    /// Recomputes the box and height of internal node `i` from its children.
    #[inline]
    fn refit(&mut self, i: u32) {
        let n = self.nodes[i as usize];
        let (a, b) = (self.nodes[n.child1 as usize], self.nodes[n.child2 as usize]);
        self.nodes[i as usize].refit_from(&a, &b);
    }

    /// Tree rotation at internal node `a` with children `b`, `c`: swaps a child with a
    /// grandchild on the other side when that lowers the summed area of the internal nodes
    /// (Box2D v3's `b2RotateNodes`). The box of `a` is unchanged; its height is refit.
    fn rotate(&mut self, a: u32) {
        let nodes = &self.nodes;
        let na = &nodes[a as usize];
        if na.height < 2 {
            return;
        }
        let (b, c) = (na.child1, na.child2);

        // Candidates, in this order: (child of `a` to move down, internal sibling receiving
        // it, which grandchild slot it swaps with). Delta = area change of the receiving
        // sibling; the first strictly better one (lower area, or equal area and lower
        // height) wins.
        let mut best: Option<(u32, u32, bool)> = None;
        let mut best_delta = 0.0f32;
        let mut best_height = na.height;
        for (down_i, side_i) in [(b, c), (c, b)] {
            let side = &nodes[side_i as usize];
            if side.is_leaf() {
                continue;
            }
            let down = &nodes[down_i as usize];
            let f = &nodes[side.child1 as usize];
            let g = &nodes[side.child2 as usize];
            let base = side.aabb.perimeter();
            // Swap `down` with f: side becomes (down, g), `a` gets (f, side'); then with g.
            for (first, keep, up) in [(true, g, f), (false, f, g)] {
                let delta = down.aabb.union(&keep.aabb).perimeter() - base;
                let side_h = 1 + down.height.max(keep.height);
                let height = 1 + side_h.max(up.height);
                if delta < best_delta || (delta == best_delta && height < best_height) {
                    best_delta = delta;
                    best_height = height;
                    best = Some((down_i, side_i, first));
                }
            }
        }

        let Some((down, side, first)) = best else {
            return;
        };
        let ns = self.nodes[side as usize];
        let up = if first { ns.child1 } else { ns.child2 };
        // Child slot of `a` that held `down` now holds `up`.
        {
            let na = &mut self.nodes[a as usize];
            if na.child1 == down {
                na.child1 = up;
            } else {
                na.child2 = up;
            }
        }
        {
            let ns = &mut self.nodes[side as usize];
            if first {
                ns.child1 = down;
            } else {
                ns.child2 = down;
            }
        }
        self.nodes[down as usize].parent = side;
        self.nodes[up as usize].parent = a;
        self.refit(side);
        self.refit(a);
    }

    // ---------------------------------------------------------------------------------
    // Validation

    /// The leaf `proxy`'s user data when `proxy` is a leaf of this tree.
    pub(crate) fn leaf_user_data(&self, proxy: u32) -> Option<u32> {
        let n = self.nodes.get(proxy as usize)?;
        n.is_leaf().then_some(n.user_data)
    }

    /// Checks the structure a restored snapshot brings (no panic, O(n)): every index in
    /// range, parent and child links agreeing, heights, counts and the free list, so that
    /// no later traversal can index out of range or loop. Boxes are not compared (their
    /// values do not make an index go wrong).
    pub(crate) fn check(&self) -> Result<(), String> {
        let n = self.nodes.len();
        let node = |i: u32, what: &str| {
            self.nodes
                .get(i as usize)
                .ok_or_else(|| format!("tree {what} {i} out of range ({n} nodes)"))
        };
        let mut seen = vec![false; n];
        let (mut reached, mut leaves) = (0u32, 0u32);
        if self.root != NULL_NODE {
            if node(self.root, "root")?.parent != NULL_NODE {
                return Err("tree root has a parent".into());
            }
            let mut stack = vec![self.root];
            while let Some(i) = stack.pop() {
                let nd = node(i, "node")?;
                if std::mem::replace(&mut seen[i as usize], true) {
                    return Err(format!("tree node {i} reached twice"));
                }
                reached += 1;
                if nd.height < 0 {
                    return Err(format!("tree node {i} is free but linked"));
                }
                if nd.is_leaf() {
                    leaves += 1;
                    if nd.child1 != NULL_NODE || nd.child2 != NULL_NODE || nd.enlarged {
                        return Err(format!("tree leaf {i} has children or an enlarged mark"));
                    }
                    continue;
                }
                let (a, b) = (node(nd.child1, "child")?, node(nd.child2, "child")?);
                if a.parent != i || b.parent != i || nd.height != 1 + a.height.max(b.height) {
                    return Err(format!("tree node {i}: children's links or height disagree"));
                }
                if (a.enlarged || b.enlarged) && !nd.enlarged {
                    return Err(format!("tree node {i} is not marked enlarged but a child is"));
                }
                stack.push(nd.child1);
                stack.push(nd.child2);
            }
        }
        if leaves != self.proxy_count || reached != self.node_count {
            return Err("tree counts disagree with its nodes".into());
        }
        let mut free = 0usize;
        let mut i = self.free_list;
        while i != NULL_NODE {
            let nd = node(i, "free node")?;
            if nd.height != -1 || std::mem::replace(&mut seen[i as usize], true) {
                return Err(format!("tree free list: node {i} in use or listed twice"));
            }
            free += 1;
            i = nd.parent;
        }
        if free + self.node_count as usize != n {
            return Err("tree nodes neither linked nor free".into());
        }
        Ok(())
    }

    /// Checks the structure (panics on failure): parent links, heights, boxes containing
    /// their children, leaf count, free list. O(n); meant for tests and debugging.
    pub fn validate(&self) {
        let mut reached = 0u32;
        let mut leaves = 0u32;
        if self.root != NULL_NODE {
            assert_eq!(self.nodes[self.root as usize].parent, NULL_NODE, "root has a parent");
            let mut stack = Stack::new();
            stack.push(self.root);
            while let Some(i) = stack.pop() {
                let n = &self.nodes[i as usize];
                reached += 1;
                assert!(n.height >= 0, "node {i} is free but linked");
                if n.is_leaf() {
                    leaves += 1;
                    assert!(n.child1 == NULL_NODE && n.child2 == NULL_NODE, "leaf {i} has children");
                    assert!(!n.enlarged, "leaf {i} marked enlarged");
                    continue;
                }
                let (c1, c2) = (n.child1, n.child2);
                assert!(c1 != NULL_NODE && c2 != NULL_NODE && c1 != c2, "node {i} children");
                let a = &self.nodes[c1 as usize];
                let b = &self.nodes[c2 as usize];
                assert_eq!(a.parent, i, "child {c1} parent link");
                assert_eq!(b.parent, i, "child {c2} parent link");
                assert_eq!(n.height, 1 + a.height.max(b.height), "node {i} height");
                assert!(n.aabb.contains(&a.aabb) && n.aabb.contains(&b.aabb), "node {i} box");
                assert!(n.enlarged || !(a.enlarged || b.enlarged), "node {i} enlarged mark");
                stack.push(c1);
                stack.push(c2);
            }
        }
        assert_eq!(leaves, self.proxy_count, "proxy count");
        assert_eq!(reached, self.node_count, "node count");
        let mut free = 0usize;
        let mut i = self.free_list;
        while i != NULL_NODE {
            assert_eq!(self.nodes[i as usize].height, -1, "free node {i} in use");
            free += 1;
            assert!(free <= self.nodes.len(), "free list cycle");
            i = self.nodes[i as usize].parent;
        }
        assert_eq!(free + self.node_count as usize, self.nodes.len(), "leaked nodes");
    }
}

mod rebuild;
pub use rebuild::{RebuildJobs, JOB_UNITS};

#[cfg(test)]
mod tests;

// ------------------------------------------------------------------------------------
// Snapshots

/// The same box bit for bit.
fn same_box(a: &Aabb, b: &Aabb) -> bool {
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    bits(a.min) == bits(b.min) && bits(a.max) == bits(b.max)
}

/// A node's box is stored (not the predicted one).
const SNAP_BOX: u8 = 1;
/// A node's parent is stored (not the predicted one).
const SNAP_PARENT: u8 = 2;
/// An internal node is marked enlarged (its part of the tree is rebuilt at the next
/// step's narrow phase, so the mark decides the tree's future shape).
const SNAP_ENLARGED: u8 = 4;

/// The columns of the tree's nodes after `flags` and `height` that some nodes have and others
/// do not, by kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SnapColumns {
    /// `child1` and `child2`, of the internal nodes.
    Children,
    /// `user_data`, of the leaves.
    UserData,
    /// `parent`, of the nodes whose parent is stored.
    Parent,
    /// `aabb` (`min`, `max`), of the nodes whose box is stored.
    Box,
}

impl DynamicTree {
    /// The parent each node would have from the child links alone: the internal node that
    /// lists it, `NULL_NODE` for the root, free nodes and nodes no one lists.
    fn predicted_parents(nodes: &[Node]) -> Vec<u32> {
        let mut p = vec![NULL_NODE; nodes.len()];
        for (i, n) in nodes.iter().enumerate() {
            if n.height > 0 {
                for c in [n.child1, n.child2] {
                    if let Some(slot) = p.get_mut(c as usize) {
                        *slot = i as u32;
                    }
                }
            }
        }
        p
    }

    /// The optional columns some node has, in the order node-by-node writing makes them (the
    /// order of the first node having each, and within a node children or user data, then
    /// parent, then box), so that writing and reading them column by column keeps the
    /// payload's column list as it was. From the nodes' heights and `flags` alone, which
    /// the reader has when it needs this.
    fn snapshot_columns(nodes: &[Node], flags: &[u8]) -> impl Iterator<Item = SnapColumns> {
        let first = |at: Option<usize>, within: u8, c: SnapColumns| at.map(|i| (i, within, c));
        let mut order = [
            first(nodes.iter().position(|n| n.height > 0), 0, SnapColumns::Children),
            first(nodes.iter().position(|n| n.height == 0), 0, SnapColumns::UserData),
            first(flags.iter().position(|&f| f & SNAP_PARENT != 0), 1, SnapColumns::Parent),
            first(flags.iter().position(|&f| f & SNAP_BOX != 0), 2, SnapColumns::Box),
        ];
        order.sort_unstable_by_key(|c| c.map(|(i, within, _)| (i, within)).unwrap_or((usize::MAX, 0)));
        order.into_iter().flatten().map(|(_, _, c)| c)
    }

    /// Writes the tree node for node (its shape decides the order pairs are found in), each
    /// field of every node in one pass over the nodes (the bytes node-by-node writing
    /// would make: every column holds the same values in node order, and the columns are
    /// made in the same order, `snapshot_columns`). A box or parent equal bit for bit to its
    /// prediction is not stored, only a flag: a leaf's box is predicted by
    /// `leaf_box(user_data)` (the shape's fat box), an internal node's as the union of its
    /// children's, a free node's as empty; a parent from the child links
    /// (`predicted_parents`).
    pub(crate) fn put_snapshot(&self, w: &mut crate::snapshot::Writer, leaf_box: impl Fn(u32) -> Option<Aabb>) {
        use crate::snapshot::Snap;
        let DynamicTree {
            nodes,
            root,
            free_list,
            node_count,
            proxy_count,
            scratch: _,
        } = self;
        w.put_len(nodes.len());
        if !nodes.is_empty() {
            let parents = Self::predicted_parents(nodes);
            let flags: Vec<u8> = nodes
                .iter()
                .zip(&parents)
                .map(|(n, &p)| {
                    let predicted = match n.height {
                        h if h < 0 => Some(Aabb::EMPTY),
                        0 => leaf_box(n.user_data),
                        _ => nodes
                            .get(n.child1 as usize)
                            .zip(nodes.get(n.child2 as usize))
                            .map(|(a, b)| a.aabb.union(&b.aabb)),
                    };
                    let store_box = !predicted.is_some_and(|b| same_box(&b, &n.aabb));
                    (store_box as u8 * SNAP_BOX)
                        | ((p != n.parent) as u8 * SNAP_PARENT)
                        | (n.enlarged as u8 * SNAP_ENLARGED)
                })
                .collect();
            w.within("flags", |w| w.values(flags.iter().map(|&f| [f])));
            w.within("height", |w| w.values(nodes.iter().map(|n| n.height.to_le_bytes())));
            let with = |bit: u8| {
                nodes
                    .iter()
                    .zip(&flags)
                    .filter(move |(_, &f)| f & bit != 0)
                    .map(|(n, _)| n)
            };
            for c in Self::snapshot_columns(nodes, &flags) {
                match c {
                    SnapColumns::Children => {
                        let internal = || nodes.iter().filter(|n| n.height > 0);
                        w.within("child1", |w| w.values(internal().map(|n| n.child1.to_le_bytes())));
                        w.within("child2", |w| w.values(internal().map(|n| n.child2.to_le_bytes())));
                    }
                    SnapColumns::UserData => w.within("user_data", |w| {
                        w.values(
                            nodes
                                .iter()
                                .filter(|n| n.height == 0)
                                .map(|n| n.user_data.to_le_bytes()),
                        )
                    }),
                    SnapColumns::Parent => w.within("parent", |w| {
                        w.values(with(SNAP_PARENT).map(|n| n.parent.to_le_bytes()))
                    }),
                    SnapColumns::Box => w.within("aabb", |w| Aabb::put_all(with(SNAP_BOX).map(|n| &n.aabb), w)),
                }
            }
        }
        w.within("root", |w| root.put(w));
        w.within("free_list", |w| free_list.put(w));
        w.within("node_count", |w| node_count.put(w));
        w.within("proxy_count", |w| proxy_count.put(w));
    }

    /// Reads what `put_snapshot` wrote, column by column, rebuilding the boxes and parents
    /// it predicted (in order of height, so children's boxes come first). A flags byte with
    /// unknown bits or an enlarged mark on a leaf or free node, a height below -1 or not
    /// below the node count (which no valid tree has), a column shorter than its nodes need,
    /// or a box that cannot be predicted (a child out of range or not below its parent, a
    /// leaf `leaf_box` knows nothing of) is an error; the structure is checked afterwards
    /// (`check`).
    pub(crate) fn get_snapshot<'a>(
        r: &mut crate::snapshot::Reader<'a>,
        leaf_box: impl Fn(u32) -> Option<Aabb>,
    ) -> crate::snapshot::ReadResult<DynamicTree> {
        use crate::snapshot::{bad, Snap};
        let n = r.count()?;
        let mut nodes = Vec::new();
        if n > 0 {
            let flags = r.within("flags", |r| r.take_values(n, 1))?;
            if let Some(f) = flags
                .iter()
                .find(|&&f| f & !(SNAP_BOX | SNAP_PARENT | SNAP_ENLARGED) != 0)
            {
                return bad(format!("snapshot corrupted: tree node flags {f}"));
            }
            let heights = r.within("height", |r| r.take_values(n, 4))?;
            nodes.reserve_exact(n);
            for (&f, h) in flags.iter().zip(heights.chunks_exact(4)) {
                let height = i32::from_le_bytes(h.try_into().expect("4 bytes"));
                let enlarged = f & SNAP_ENLARGED != 0;
                if enlarged && height <= 0 {
                    return bad(format!(
                        "snapshot corrupted: tree node flags {f} on a leaf or free node"
                    ));
                }
                if height < -1 || height as i64 >= n as i64 {
                    return bad(format!("snapshot corrupted: tree node height {height} of {n} nodes"));
                }
                nodes.push(Node {
                    height,
                    enlarged,
                    ..Node::FREE
                });
            }
            let u32s = |b: &'a [u8]| {
                b.chunks_exact(4)
                    .map(|c| u32::from_le_bytes(c.try_into().expect("4 bytes")))
            };
            let with = |bit: u8| flags.iter().filter(|&&f| f & bit != 0).count();
            for c in Self::snapshot_columns(&nodes, flags) {
                match c {
                    SnapColumns::Children => {
                        let k = nodes.iter().filter(|n| n.height > 0).count();
                        let c1 = r.within("child1", |r| r.take_values(k, 4))?;
                        let c2 = r.within("child2", |r| r.take_values(k, 4))?;
                        let internal = nodes.iter_mut().filter(|n| n.height > 0);
                        for ((node, a), b) in internal.zip(u32s(c1)).zip(u32s(c2)) {
                            (node.child1, node.child2) = (a, b);
                        }
                    }
                    SnapColumns::UserData => {
                        let k = nodes.iter().filter(|n| n.height == 0).count();
                        let u = r.within("user_data", |r| r.take_values(k, 4))?;
                        for (node, u) in nodes.iter_mut().filter(|n| n.height == 0).zip(u32s(u)) {
                            node.user_data = u;
                        }
                    }
                    SnapColumns::Parent => {
                        let p = r.within("parent", |r| r.take_values(with(SNAP_PARENT), 4))?;
                        let given = nodes.iter_mut().zip(flags).filter(|(_, &f)| f & SNAP_PARENT != 0);
                        for ((node, _), p) in given.zip(u32s(p)) {
                            node.parent = p;
                        }
                    }
                    SnapColumns::Box => {
                        let boxes = r.within("aabb", |r| Aabb::get_all(with(SNAP_BOX), r))?;
                        let given = nodes.iter_mut().zip(flags).filter(|(_, &f)| f & SNAP_BOX != 0);
                        for ((node, _), b) in given.zip(boxes) {
                            node.aabb = b;
                        }
                    }
                }
            }
            let parents = Self::predicted_parents(&nodes);
            for ((node, &f), p) in nodes.iter_mut().zip(flags).zip(parents) {
                if f & SNAP_PARENT == 0 {
                    node.parent = p;
                }
            }
            // The boxes to rebuild, leaves' now and internal nodes' in order of height
            // (counting sort; heights are below `n`), so that children's come first. Free
            // nodes' predicted box is the empty one they have.
            let mut at = vec![0u32; n + 1];
            for (i, (node, &f)) in nodes.iter_mut().zip(flags).enumerate() {
                if f & SNAP_BOX != 0 {
                    continue;
                }
                if node.height == 0 {
                    match leaf_box(node.user_data) {
                        Some(b) => node.aabb = b,
                        None => return bad(format!("snapshot corrupted: tree node {i}'s box cannot be rebuilt")),
                    }
                } else if node.height > 0 {
                    at[node.height as usize] += 1;
                }
            }
            let mut sum = 0;
            for a in &mut at {
                (*a, sum) = (sum, sum + *a);
            }
            let mut order = vec![0u32; sum as usize];
            for (i, (node, &f)) in nodes.iter().zip(flags).enumerate() {
                if f & SNAP_BOX == 0 && node.height > 0 {
                    let slot = &mut at[node.height as usize];
                    order[*slot as usize] = i as u32;
                    *slot += 1;
                }
            }
            for i in order {
                let node = nodes[i as usize];
                let child = |c: u32| {
                    nodes
                        .get(c as usize)
                        .filter(|k| k.height >= 0 && k.height < node.height)
                };
                match child(node.child1).zip(child(node.child2)) {
                    Some((a, b)) => nodes[i as usize].aabb = a.aabb.union(&b.aabb),
                    None => return bad(format!("snapshot corrupted: tree node {i}'s box cannot be rebuilt")),
                }
            }
        }
        Ok(DynamicTree {
            nodes,
            root: r.within("root", u32::get)?,
            free_list: r.within("free_list", u32::get)?,
            node_count: r.within("node_count", u32::get)?,
            proxy_count: r.within("proxy_count", u32::get)?,
            scratch: Default::default(),
        })
    }
}

#[cfg(test)]
mod snapshot_tests {
    use super::*;
    use crate::math::test_rnd::Rnd;
    use crate::snapshot::{unpack, ReadResult, Reader, Snap, Writer};

    /// The tree written node by node, every field of a node before the next node's (how
    /// `put_snapshot` wrote it before it wrote column by column): the reference its bytes
    /// are compared with.
    fn put_by_node(t: &DynamicTree, w: &mut Writer, leaf_box: impl Fn(u32) -> Option<Aabb>) {
        let parents = DynamicTree::predicted_parents(&t.nodes);
        w.put_len(t.nodes.len());
        for (i, n) in t.nodes.iter().enumerate() {
            let predicted = match n.height {
                h if h < 0 => Some(Aabb::EMPTY),
                0 => leaf_box(n.user_data),
                _ => t
                    .nodes
                    .get(n.child1 as usize)
                    .zip(t.nodes.get(n.child2 as usize))
                    .map(|(a, b)| a.aabb.union(&b.aabb)),
            };
            let store_box = !predicted.is_some_and(|p| same_box(&p, &n.aabb));
            let store_parent = parents[i] != n.parent;
            let flags =
                (store_box as u8 * SNAP_BOX) | (store_parent as u8 * SNAP_PARENT) | (n.enlarged as u8 * SNAP_ENLARGED);
            w.within("flags", |w| flags.put(w));
            w.within("height", |w| n.height.put(w));
            if n.height > 0 {
                w.within("child1", |w| n.child1.put(w));
                w.within("child2", |w| n.child2.put(w));
            } else if n.height == 0 {
                w.within("user_data", |w| n.user_data.put(w));
            }
            if store_parent {
                w.within("parent", |w| n.parent.put(w));
            }
            if store_box {
                w.within("aabb", |w| n.aabb.put(w));
            }
        }
        w.within("root", |w| t.root.put(w));
        w.within("free_list", |w| t.free_list.put(w));
        w.within("node_count", |w| t.node_count.put(w));
        w.within("proxy_count", |w| t.proxy_count.put(w));
    }

    fn payload(f: impl FnOnce(&mut Writer)) -> Vec<u8> {
        let mut w = Writer::new();
        w.within("tree", f);
        let mut out = Vec::new();
        w.finish(&mut out);
        out
    }

    /// The tree read from the columns `plain[spans]`, every byte of them read.
    fn read(plain: &[u8], spans: &[(usize, usize)], leaf_box: impl Fn(u32) -> Option<Aabb>) -> ReadResult<DynamicTree> {
        let mut r = Reader::new(plain, spans, 0);
        let t = r.within("tree", |r| DynamicTree::get_snapshot(r, leaf_box))?;
        r.finish()?;
        Ok(t)
    }

    /// Moves the nodes to randomly shuffled indices (links renamed to match): the same
    /// tree with its leaves, internal and free nodes in any order, so that the first node
    /// of each kind (which decides the column order) falls anywhere.
    fn relabel(t: &mut DynamicTree, rng: &mut Rnd) {
        let n = t.nodes.len();
        let mut to: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            to.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
        }
        let map = |i: u32| if i == NULL_NODE { i } else { to[i as usize] };
        let mut nodes = vec![Node::FREE; n];
        for (i, node) in t.nodes.iter().enumerate() {
            let mut m = *node;
            m.parent = map(m.parent);
            if m.height > 0 {
                (m.child1, m.child2) = (map(m.child1), map(m.child2));
            }
            nodes[to[i] as usize] = m;
        }
        t.nodes = nodes;
        t.root = map(t.root);
        t.free_list = map(t.free_list);
    }

    fn assert_same(a: &DynamicTree, b: &DynamicTree, what: &str) {
        assert_eq!(a.nodes.len(), b.nodes.len(), "{what}");
        for (i, (x, y)) in a.nodes.iter().zip(&b.nodes).enumerate() {
            assert!(same_box(&x.aabb, &y.aabb), "{what}: node {i} box");
            let fields = |n: &Node| (n.parent, n.child1, n.child2, n.user_data, n.height, n.enlarged);
            assert_eq!(fields(x), fields(y), "{what}: node {i}");
        }
        let top = |t: &DynamicTree| (t.root, t.free_list, t.node_count, t.proxy_count);
        assert_eq!(top(a), top(b), "{what}");
    }

    /// Seeded random trees (inserts, removals, moves and in-place enlargements, so with
    /// free nodes, enlarged marks, boxes that are not their children's union and leaves
    /// whose shape box differs or is unknown): column-by-column writing gives the bytes
    /// node-by-node writing gave, the reader gives back the same tree, and a column cut
    /// short or a changed byte is refused or read without a panic.
    #[test]
    fn snapshot_columns_match_node_by_node_and_round_trip() {
        let mut rng = Rnd(0x7e1e_5eed_0bad_cafe);
        let mut seen = [false; 3];
        let mut first_kinds = [false; 2];
        for round in 0..300 {
            let mut t = DynamicTree::new();
            // What `leaf_box` answers per user data: the box given, another one, or nothing.
            let mut known: Vec<Option<Aabb>> = Vec::new();
            let mut live: Vec<u32> = Vec::new();
            let random_box = |rng: &mut Rnd| {
                let c = rng.point(Vec3::splat(20.0));
                let h = rng.point(Vec3::splat(2.0)).abs() + Vec3::splat(0.05);
                Aabb::new(c - h, c + h)
            };
            let ops = rng.next_u64() % 80;
            for _ in 0..ops {
                let roll = rng.next_u64() % 20;
                if live.is_empty() || roll < 10 {
                    let b = random_box(&mut rng);
                    let u = known.len() as u32;
                    known.push(match rng.next_u64() % 8 {
                        0 => None,
                        1 => Some(b.expanded(0.25)),
                        _ => Some(b),
                    });
                    live.push(t.create_proxy(b, u));
                } else {
                    let k = (rng.next_u64() % live.len() as u64) as usize;
                    let p = live[k];
                    match roll {
                        10..=12 => {
                            t.destroy_proxy(p);
                            live.swap_remove(k);
                        }
                        13..=16 => t.move_proxy(p, random_box(&mut rng)),
                        17 | 18 => {
                            let grown = t.fat_aabb(p).union(&random_box(&mut rng));
                            t.enlarge_proxy(p, grown);
                        }
                        _ => {
                            // Shrunk in place: the ancestors keep their larger boxes, which
                            // are then not their children's union (stored, not rebuilt).
                            let b = t.fat_aabb(p);
                            let q = (b.max - b.min) * 0.25;
                            t.enlarge_proxy(p, Aabb::new(b.min + q, b.max - q));
                        }
                    }
                }
            }
            if round % 2 == 1 {
                relabel(&mut t, &mut rng);
            }
            if round % 4 == 3 {
                // Free nodes with boxes (which no tree operation leaves, but the writer
                // stores as they are): a node whose parent and box are both stored.
                for node in t.nodes.iter_mut().filter(|n| n.height < 0) {
                    node.aabb = random_box(&mut rng);
                }
            }
            t.validate();
            let leaf_box = |u: u32| known.get(u as usize).copied().flatten();
            let bytes = payload(|w| t.put_snapshot(w, leaf_box));
            assert_eq!(bytes, payload(|w| put_by_node(&t, w, leaf_box)), "round {round}: bytes");
            let mut plain = Vec::new();
            let spans = unpack(&bytes, &mut plain).expect("unpacks");
            let back = read(&plain, &spans, leaf_box).expect("reads back");
            assert_same(&t, &back, &format!("round {round}"));
            assert!(back.check().is_ok(), "round {round}");
            // What the rounds covered: stored boxes, stored parents, enlarged marks, and
            // trees whose first node is a leaf or an internal node (other column orders).
            let parents = DynamicTree::predicted_parents(&t.nodes);
            for (n, &p) in t.nodes.iter().zip(&parents) {
                seen[0] |= n.height > 0
                    && !same_box(
                        &n.aabb,
                        &t.nodes[n.child1 as usize].aabb.union(&t.nodes[n.child2 as usize].aabb),
                    );
                seen[1] |= n.parent != p;
                seen[2] |= n.enlarged;
            }
            if let Some(n) = t.nodes.first() {
                first_kinds[(n.height > 0) as usize] = true;
            }
            // A column one byte short is refused; a byte changed anywhere is refused or
            // read (and then checked) without a panic.
            for (k, &(at, end)) in spans.iter().enumerate() {
                if end > at {
                    let mut cut = plain.clone();
                    cut.remove(end - 1);
                    let mut short = spans.clone();
                    short[k].1 -= 1;
                    for s in &mut short[k + 1..] {
                        (s.0, s.1) = (s.0 - 1, s.1 - 1);
                    }
                    assert!(
                        read(&cut, &short, leaf_box).is_err(),
                        "round {round}: column {k} cut short"
                    );
                }
            }
            for _ in 0..8 {
                if plain.is_empty() {
                    break;
                }
                let mut bent = plain.clone();
                let at = (rng.next_u64() % bent.len() as u64) as usize;
                bent[at] ^= 1 << (rng.next_u64() % 8);
                if let Ok(t) = read(&bent, &spans, leaf_box) {
                    let _ = t.check();
                }
            }
        }
        assert_eq!(seen, [true; 3], "stored boxes, stored parents, enlarged marks");
        assert_eq!(first_kinds, [true; 2], "first node a leaf, first node internal");
    }
}
