use super::*;

/// xorshift64* — tiny deterministic PRNG for the tests.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1).
    fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    fn vec3(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }
}

const WORLD: f32 = 100.0;

fn random_box(rng: &mut Rng) -> Aabb {
    let c = rng.vec3(-WORLD, WORLD);
    let e = rng.vec3(0.1, 4.0);
    Aabb::from_center_extents(c, e)
}

fn query_box(rng: &mut Rng) -> Aabb {
    let c = rng.vec3(-WORLD, WORLD);
    let e = rng.vec3(1.0, 30.0);
    Aabb::from_center_extents(c, e)
}

/// Brute-force mirror of the tree: proxy id -> (box, user data).
#[derive(Default)]
struct Mirror {
    live: Vec<Option<(Aabb, u32)>>,
    ids: Vec<u32>,
}

impl Mirror {
    fn insert(&mut self, id: u32, aabb: Aabb, ud: u32) {
        let i = id as usize;
        if self.live.len() <= i {
            self.live.resize(i + 1, None);
        }
        assert!(self.live[i].is_none(), "id {id} handed out twice");
        self.live[i] = Some((aabb, ud));
        self.ids.push(id);
    }

    fn remove_at(&mut self, k: usize) -> u32 {
        let id = self.ids.swap_remove(k);
        self.live[id as usize] = None;
        id
    }

    fn query(&self, q: &Aabb) -> Vec<u32> {
        let mut v: Vec<u32> = self
            .ids
            .iter()
            .copied()
            .filter(|&id| self.live[id as usize].unwrap().0.overlaps(q))
            .collect();
        v.sort_unstable();
        v
    }

    fn ray(&self, o: Vec3, d: Vec3, max_t: f32) -> Vec<(u32, f32)> {
        let inv = reciprocal(d);
        let mut v: Vec<(u32, f32)> = self
            .ids
            .iter()
            .filter_map(|&id| ray_aabb_entry(o, d, inv, max_t, &self.live[id as usize].unwrap().0).map(|t| (id, t)))
            .collect();
        v.sort_unstable_by_key(|p| p.0);
        v
    }
}

fn tree_query(tree: &DynamicTree, q: &Aabb, mirror: &Mirror) -> Vec<u32> {
    let mut v = Vec::new();
    tree.query(q, |p, ud| {
        assert_eq!(Some(ud), mirror.live[p as usize].map(|e| e.1), "user data of {p}");
        v.push(p);
        true
    });
    v.sort_unstable();
    v
}

fn random_ray(rng: &mut Rng) -> (Vec3, Vec3, f32) {
    let o = rng.vec3(-1.5 * WORLD, 1.5 * WORLD);
    let mut d = rng.vec3(-1.0, 1.0);
    // Some axis-aligned rays to exercise the zero-direction slabs.
    match rng.below(5) {
        0 => d.x = 0.0,
        1 => {
            d.y = 0.0;
            d.z = 0.0
        }
        _ => {}
    }
    if d == Vec3::ZERO {
        d = Vec3::X;
    }
    (o, d, rng.range(10.0, 400.0))
}

/// Checks queries and ray casts against brute force.
fn check_against_brute_force(tree: &DynamicTree, mirror: &Mirror, rng: &mut Rng) {
    for _ in 0..8 {
        let q = query_box(rng);
        assert_eq!(tree_query(tree, &q, mirror), mirror.query(&q));
    }
    for _ in 0..8 {
        let (o, d, max_t) = random_ray(rng);
        let expected = mirror.ray(o, d, max_t);

        // Unclipped: every hit along the whole segment.
        let mut hits = Vec::new();
        tree.ray_cast(o, d, max_t, |p, _, t| {
            assert_eq!(t, max_t);
            hits.push(p);
            t
        });
        hits.sort_unstable();
        assert_eq!(hits, expected.iter().map(|e| e.0).collect::<Vec<_>>());

        // Clipped to the entry of each hit: ends at the closest hit.
        let inv = reciprocal(d);
        let mut closest = f32::MAX;
        tree.ray_cast(o, d, max_t, |p, _, t| {
            let entry = ray_aabb_entry(o, d, inv, t, &tree.fat_aabb(p)).expect("reported box is hit");
            closest = closest.min(entry);
            if entry > 0.0 {
                entry
            } else {
                -1.0
            }
        });
        let brute = expected.iter().map(|e| e.1).fold(f32::MAX, f32::min);
        assert_eq!(closest, brute);
    }
}

#[test]
fn random_insert_remove_move_match_brute_force() {
    let mut rng = Rng::new(7);
    let mut tree = DynamicTree::new();
    let mut mirror = Mirror::default();
    let mut next_ud = 0u32;
    for _ in 0..2000 {
        let b = random_box(&mut rng);
        let id = tree.create_proxy(b, next_ud);
        mirror.insert(id, b, next_ud);
        next_ud += 1;
    }
    tree.validate();
    check_against_brute_force(&tree, &mirror, &mut rng);

    for batch in 0..30 {
        for _ in 0..300 {
            let r = rng.below(10);
            if r < 3 || mirror.ids.is_empty() {
                let b = random_box(&mut rng);
                let id = tree.create_proxy(b, next_ud);
                mirror.insert(id, b, next_ud);
                next_ud += 1;
            } else if r < 6 {
                let k = rng.below(mirror.ids.len());
                let id = mirror.remove_at(k);
                tree.destroy_proxy(id);
            } else {
                let k = rng.below(mirror.ids.len());
                let id = mirror.ids[k];
                let (old, ud) = mirror.live[id as usize].unwrap();
                // Small displacements mostly, teleports sometimes.
                let b = if rng.below(4) == 0 {
                    random_box(&mut rng)
                } else {
                    let d = rng.vec3(-3.0, 3.0);
                    Aabb::new(old.min + d, old.max + d)
                };
                tree.move_proxy(id, b);
                mirror.live[id as usize] = Some((b, ud));
            }
        }
        tree.validate();
        assert_eq!(tree.proxy_count() as usize, mirror.ids.len(), "batch {batch}");
        for &id in &mirror.ids {
            let (b, ud) = mirror.live[id as usize].unwrap();
            assert_eq!(tree.fat_aabb(id), b);
            assert_eq!(tree.user_data(id), ud);
        }
        check_against_brute_force(&tree, &mirror, &mut rng);
        let n = tree.proxy_count().max(2) as f32;
        assert!(
            (tree.height() as f32) <= 2.0 * n.log2() + 4.0,
            "height {} for {n} proxies",
            tree.height()
        );
    }

    // Drain completely.
    while !mirror.ids.is_empty() {
        let k = rng.below(mirror.ids.len());
        let id = mirror.remove_at(k);
        tree.destroy_proxy(id);
        if mirror.ids.len() % 97 == 0 {
            tree.validate();
            check_against_brute_force(&tree, &mirror, &mut rng);
        }
    }
    tree.validate();
    assert_eq!(tree.root(), NULL_NODE);
    assert_eq!(tree.node_count(), 0);
    assert_eq!(tree.height(), 0);
}

fn line_boxes(n: usize) -> Vec<Aabb> {
    (0..n)
        .map(|i| Aabb::from_center_extents(Vec3::new(i as f32 * 2.0, 0.0, 0.0), Vec3::splat(0.5)))
        .collect()
}

#[test]
fn sorted_line_insertion_stays_shallow() {
    let n = 10_000;
    let mut tree = DynamicTree::new();
    for (i, b) in line_boxes(n).into_iter().enumerate() {
        tree.create_proxy(b, i as u32);
    }
    tree.validate();
    let bound = 2.0 * (n as f32).log2() + 4.0;
    eprintln!(
        "sorted line n={n}: height {} (bound {bound:.1}), area ratio {:.2}",
        tree.height(),
        tree.area_ratio()
    );
    assert!((tree.height() as f32) <= bound);

    // Reverse order and a 3D sorted grid too.
    let mut rev = DynamicTree::new();
    for (i, b) in line_boxes(n).into_iter().enumerate().rev() {
        rev.create_proxy(b, i as u32);
    }
    rev.validate();
    eprintln!(
        "reverse line: height {}, area ratio {:.2}",
        rev.height(),
        rev.area_ratio()
    );
    assert!((rev.height() as f32) <= bound);

    let mut grid = DynamicTree::new();
    let mut k = 0;
    for x in 0..22 {
        for y in 0..22 {
            for z in 0..22 {
                let c = Vec3::new(x as f32, y as f32, z as f32) * 2.0;
                grid.create_proxy(Aabb::from_center_extents(c, Vec3::splat(0.5)), k);
                k += 1;
            }
        }
    }
    grid.validate();
    let gb = 2.0 * (k as f32).log2() + 4.0;
    eprintln!(
        "sorted grid n={k}: height {}, area ratio {:.2}",
        grid.height(),
        grid.area_ratio()
    );
    assert!((grid.height() as f32) <= gb);
}

#[test]
fn random_scene_quality_and_rebuild() {
    let mut rng = Rng::new(99);
    let mut tree = DynamicTree::new();
    let mut mirror = Mirror::default();
    for i in 0..10_000 {
        let b = random_box(&mut rng);
        let id = tree.create_proxy(b, i);
        mirror.insert(id, b, i);
    }
    tree.validate();
    let (h0, r0) = (tree.height(), tree.area_ratio());
    // Churn: move everything a few times.
    for _ in 0..3 {
        for &id in &mirror.ids.clone() {
            let d = rng.vec3(-2.0, 2.0);
            let (old, ud) = mirror.live[id as usize].unwrap();
            let b = Aabb::new(old.min + d, old.max + d);
            tree.move_proxy(id, b);
            mirror.live[id as usize] = Some((b, ud));
        }
    }
    tree.validate();
    let (h1, r1) = (tree.height(), tree.area_ratio());
    tree.rebuild();
    tree.validate();
    let (h2, r2) = (tree.height(), tree.area_ratio());
    eprintln!("random n=10000: incremental height {h0} ratio {r0:.2}; after 3x move height {h1} ratio {r1:.2}; rebuilt height {h2} ratio {r2:.2}");
    check_against_brute_force(&tree, &mirror, &mut rng);
    assert!((h1 as f32) <= 2.0 * 10_000f32.log2() + 4.0);
    assert!((h2 as f32) <= 2.0 * 10_000f32.log2() + 4.0);
    assert!(r2 <= r1 * 1.25, "rebuild made the tree much worse: {r1} -> {r2}");

    // The tree keeps working incrementally after a rebuild.
    for _ in 0..500 {
        let k = rng.below(mirror.ids.len());
        let id = mirror.remove_at(k);
        tree.destroy_proxy(id);
        let b = random_box(&mut rng);
        let id = tree.create_proxy(b, 7);
        mirror.insert(id, b, 7);
    }
    tree.validate();
    check_against_brute_force(&tree, &mirror, &mut rng);

    // Rebuild of a degenerate set (all boxes identical) and of a single proxy.
    let mut same = DynamicTree::new();
    for i in 0..100 {
        same.create_proxy(Aabb::from_center_extents(Vec3::ONE, Vec3::ONE), i);
    }
    same.rebuild();
    same.validate();
    assert!(same.height() <= 8);
    let mut one = DynamicTree::new();
    let id = one.create_proxy(Aabb::from_center_extents(Vec3::ONE, Vec3::ONE), 3);
    one.rebuild();
    one.validate();
    assert_eq!(one.root(), id);
}

#[test]
fn proxy_ids_are_reused_and_nodes_do_not_grow() {
    let mut tree = DynamicTree::new();
    let b = |x: f32| Aabb::from_center_extents(Vec3::new(x, 0.0, 0.0), Vec3::splat(0.5));
    let a = tree.create_proxy(b(0.0), 10);
    let p = tree.create_proxy(b(3.0), 11);
    let c = tree.create_proxy(b(6.0), 12);
    tree.destroy_proxy(p);
    let q = tree.create_proxy(b(9.0), 13);
    assert_eq!(q, p, "most recently destroyed id is reused");
    assert_eq!(tree.user_data(q), 13);
    assert_eq!(tree.fat_aabb(q), b(9.0));
    tree.validate();
    tree.destroy_proxy(a);
    tree.destroy_proxy(c);
    tree.destroy_proxy(q);
    tree.validate();

    // Stable proxy count: no node storage growth under churn after warm-up.
    let mut rng = Rng::new(3);
    let mut ids: Vec<u32> = (0..1000).map(|i| tree.create_proxy(random_box(&mut rng), i)).collect();
    let len = tree.nodes.len();
    let cap = tree.nodes.capacity();
    for _ in 0..20_000 {
        let k = rng.below(ids.len());
        match rng.below(3) {
            0 => tree.move_proxy(ids[k], random_box(&mut rng)),
            _ => {
                tree.destroy_proxy(ids[k]);
                ids[k] = tree.create_proxy(random_box(&mut rng), 0);
            }
        }
    }
    tree.validate();
    assert_eq!(tree.nodes.len(), len);
    assert_eq!(tree.nodes.capacity(), cap);
    assert!(ids.iter().all(|&id| (id as usize) < len));
}

#[test]
fn query_early_exit() {
    let mut rng = Rng::new(11);
    let mut tree = DynamicTree::new();
    for i in 0..499 {
        tree.create_proxy(random_box(&mut rng), i);
    }
    // One box on the test rays below.
    tree.create_proxy(Aabb::from_center_extents(Vec3::ZERO, Vec3::splat(5.0)), 499);
    let everything = Aabb::from_center_extents(Vec3::ZERO, Vec3::splat(1000.0));
    let mut all = 0;
    tree.query(&everything, |_, _| {
        all += 1;
        true
    });
    assert_eq!(all, 500);
    for stop_after in [1, 2, 37] {
        let mut calls = 0;
        tree.query(&everything, |_, _| {
            calls += 1;
            calls < stop_after
        });
        assert_eq!(calls, stop_after);
    }
    // Ray cast termination: returning 0 stops at the first reported proxy.
    let mut calls = 0;
    tree.ray_cast(Vec3::new(-200.0, 0.0, 0.0), Vec3::X, 400.0, |_, _, _| {
        calls += 1;
        0.0
    });
    assert_eq!(calls, 1);
    let mut calls = 0;
    tree.ray_cast(Vec3::new(-200.0, 0.0, 0.0), Vec3::X, 400.0, |_, _, t| {
        calls += 1;
        t
    });
    assert!(calls >= 1);
    // Ignoring (-1) visits the same set as continuing unclipped.
    let (mut ignored, mut kept) = (Vec::new(), Vec::new());
    tree.ray_cast(Vec3::new(-200.0, 1.0, 2.0), Vec3::X, 400.0, |p, _, _| {
        ignored.push(p);
        -1.0
    });
    tree.ray_cast(Vec3::new(-200.0, 1.0, 2.0), Vec3::X, 400.0, |p, _, t| {
        kept.push(p);
        t
    });
    assert!(!kept.is_empty());
    assert_eq!(ignored, kept);
}

#[test]
fn ray_edge_cases() {
    let mut tree = DynamicTree::new();
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let id = tree.create_proxy(unit, 5);
    let hits = |o: Vec3, d: Vec3, t: f32| {
        let mut v = Vec::new();
        tree.ray_cast(o, d, t, |p, ud, m| {
            v.push((p, ud));
            m
        });
        v
    };
    // Origin inside, zero-length segment, axis-aligned along a face, miss, too short.
    assert_eq!(hits(Vec3::splat(0.5), Vec3::X, 0.0), vec![(id, 5)]);
    assert_eq!(hits(Vec3::new(-1.0, 1.0, 0.5), Vec3::X, 10.0), vec![(id, 5)]);
    assert!(hits(Vec3::new(-1.0, 1.5, 0.5), Vec3::X, 10.0).is_empty());
    assert!(hits(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.5).is_empty());
    assert_eq!(hits(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 1.0), vec![(id, 5)]);
    assert!(hits(Vec3::new(2.0, 0.5, 0.5), Vec3::X, 10.0).is_empty());
    assert!(hits(Vec3::new(0.5, 0.5, 0.5), Vec3::X, -1.0).is_empty());
    assert_eq!(
        ray_aabb_entry(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, Vec3::X, 10.0, &unit),
        Some(1.0)
    );

    // Slab test against dense sampling of the segment.
    let mut rng = Rng::new(5);
    for _ in 0..2000 {
        let b = Aabb::from_center_extents(rng.vec3(-2.0, 2.0), rng.vec3(0.1, 1.5));
        let o = rng.vec3(-4.0, 4.0);
        let d = rng.vec3(-2.0, 2.0);
        let max_t = rng.range(0.0, 3.0);
        let hit = ray_aabb_entry(o, d, reciprocal(d), max_t, &b);
        let steps = 400;
        let first_inside = (0..=steps)
            .map(|s| s as f32 / steps as f32 * max_t)
            .find(|&t| b.contains(&Aabb::new(o + t * d, o + t * d)));
        match (hit, first_inside) {
            (Some(t), Some(s)) => assert!(t <= s + 1e-4 && s - t <= max_t / steps as f32 + 1e-4),
            (None, Some(s)) => panic!("slab test missed a sampled hit at t = {s}"),
            (Some(t), None) => {
                // Only grazing hits may escape the sampling.
                let p = o + t * d;
                assert!(b.expanded(1e-3).contains(&Aabb::new(p, p)));
            }
            (None, None) => {}
        }
    }
}

#[test]
fn deterministic_and_empty_tree() {
    let build = || {
        let mut rng = Rng::new(1234);
        let mut tree = DynamicTree::new();
        let mut ids = Vec::new();
        for i in 0..3000 {
            ids.push(tree.create_proxy(random_box(&mut rng), i));
            if i % 3 == 0 {
                let k = rng.below(ids.len());
                tree.move_proxy(ids[k], random_box(&mut rng));
            }
            if i % 5 == 0 {
                let k = rng.below(ids.len());
                tree.destroy_proxy(ids.swap_remove(k));
            }
        }
        tree
    };
    let (a, b) = (build(), build());
    assert_eq!(format!("{:?}", a), format!("{:?}", b));
    let q = Aabb::from_center_extents(Vec3::ZERO, Vec3::splat(40.0));
    let (mut va, mut vb) = (Vec::new(), Vec::new());
    a.query(&q, |p, _| {
        va.push(p);
        true
    });
    b.query(&q, |p, _| {
        vb.push(p);
        true
    });
    assert_eq!(va, vb, "same traversal order");

    let empty = DynamicTree::default();
    empty.validate();
    empty.query(&q, |_, _| panic!("empty tree reported a proxy"));
    empty.ray_cast(Vec3::ZERO, Vec3::X, 1.0, |_, _, _| {
        panic!("empty tree reported a proxy")
    });
    assert_eq!((empty.height(), empty.proxy_count(), empty.area_ratio()), (0, 0, 0.0));
}

#[test]
fn traversal_stack_spills_past_capacity() {
    let mut s = Stack::new();
    for i in 0..1000 {
        s.push(i);
    }
    for i in (0..1000).rev() {
        assert_eq!(s.pop(), Some(i));
    }
    assert_eq!(s.pop(), None);
}

#[test]
fn ray_stack_spills_past_capacity() {
    let mut s = RayStack::new();
    for i in 0..1000 {
        s.push((i, i as f32));
    }
    for i in (0..1000).rev() {
        assert_eq!(s.pop(), Some((i, i as f32)));
    }
    assert_eq!(s.pop(), None);
}

/// The lane-wise slab test gives exactly `ray_aabb_entry`'s answer (the same operations per
/// axis), for random rays including zero and subnormal direction components, origins on box
/// faces and segments of zero length.
#[test]
fn lane_slab_test_equals_the_scalar_one() {
    let mut rng = Rng::new(77);
    let mut hits = 0;
    for k in 0..200_000 {
        let b = Aabb::from_center_extents(rng.vec3(-2.0, 2.0), rng.vec3(0.0, 1.5));
        let mut o = rng.vec3(-4.0, 4.0);
        let mut d = rng.vec3(-2.0, 2.0);
        match k % 7 {
            0 => d.x = 0.0,
            1 => d.y = 1.0e-41,
            2 => o.z = b.min.z,
            3 => {
                o.y = b.max.y;
                d.y = 0.0
            }
            4 => d *= 1.0e-30,
            _ => {}
        }
        let max_t = if k % 11 == 0 { 0.0 } else { rng.range(0.0, 3.0) };
        let want = ray_aabb_entry(o, d, reciprocal(d), max_t, &b);
        let got = RaySlabs::new(o, d).entry(max_t, &b);
        assert_eq!(
            got.map(f32::to_bits),
            want.map(f32::to_bits),
            "ray {k}: {o} {d} {max_t} {b:?}"
        );
        hits += want.is_some() as u32;
    }
    assert!(hits > 3_000, "{hits}");
}

/// `query` reports leaves in the same order as a plain depth-first walk that tests each
/// node when popped (second child first): the broad phase's pair order, and so every
/// trajectory, does not depend on where the children are tested.
#[test]
fn query_order_is_the_plain_depth_first_order() {
    let mut rng = Rng::new(31);
    let mut tree = DynamicTree::new();
    let mut ids = Vec::new();
    for i in 0..2000 {
        ids.push(tree.create_proxy(random_box(&mut rng), i));
        if i % 4 == 0 {
            let k = rng.below(ids.len());
            tree.move_proxy(ids[k], random_box(&mut rng));
        }
    }
    for _ in 0..300 {
        let q = query_box(&mut rng);
        let mut got = Vec::new();
        tree.query(&q, |p, _| {
            got.push(p);
            true
        });
        let mut want = Vec::new();
        let mut stack = vec![tree.root];
        while let Some(i) = stack.pop() {
            let n = &tree.nodes[i as usize];
            if !n.aabb.overlaps(&q) {
                continue;
            }
            if n.is_leaf() {
                want.push(i);
            } else {
                stack.push(n.child1);
                stack.push(n.child2);
            }
        }
        assert_eq!(got, want);
    }
}

/// A ray clipped at each hit (a closest-hit query) walks front to back and stops early: it
/// ends at the nearest entry (as brute force finds it) after testing fewer boxes than the
/// unclipped walk.
#[test]
fn clipped_rays_walk_front_to_back() {
    let mut rng = Rng::new(8);
    let mut tree = DynamicTree::new();
    let mut mirror = Mirror::default();
    // A dense cloud (a pile's density), rays starting around and inside it.
    for i in 0..3000 {
        let b = Aabb::from_center_extents(rng.vec3(-20.0, 20.0), rng.vec3(0.1, 1.0));
        let id = tree.create_proxy(b, i);
        mirror.insert(id, b, i);
    }
    let (mut clipped_tests, mut full_tests) = (0u64, 0u64);
    for _ in 0..500 {
        let o = rng.vec3(-30.0, 30.0);
        let d = rng.vec3(-1.0, 1.0).normalize_or(Vec3::X) * 100.0;
        let max_t = 1.0;
        let inv = reciprocal(d);
        let mut best = f32::MAX;
        clipped_tests += tree.ray_cast(o, d, max_t, |p, _, cur| {
            let entry = ray_aabb_entry(o, d, inv, cur, &tree.fat_aabb(p)).expect("reported box is hit");
            best = best.min(entry);
            if entry > 0.0 {
                entry
            } else {
                -1.0
            }
        }) as u64;
        let brute = mirror.ray(o, d, max_t).iter().map(|e| e.1).fold(f32::MAX, f32::min);
        assert_eq!(best, brute);
        full_tests += tree.ray_cast(o, d, max_t, |_, _, cur| cur) as u64;
    }
    // Measured: 0.62 of the unclipped walk's tests.
    assert!(clipped_tests * 4 < full_tests * 3, "{clipped_tests} {full_tests}");
}

/// Proxies enlarged in place (`enlarge_proxy`) among inserts, removals and moves: the tree
/// stays valid for queries and rays before the partial rebuild (every box holds its
/// children, every enlarged node's ancestors are marked), `rebuild_enlarged` clears every
/// mark and leaves the same proxies, boxes and user data, its quality stays within 25 % of
/// a full rebuild's (Box2D's area ratio), and two trees given the same calls end bit for
/// bit the same.
#[test]
fn enlarging_in_place_and_rebuilding_the_enlarged_part_match_brute_force() {
    let run = |seed: u64| {
        let mut rng = Rng::new(seed);
        let mut tree = DynamicTree::new();
        let mut mirror = Mirror::default();
        let mut next_ud = 0u32;
        for _ in 0..1500 {
            let b = random_box(&mut rng);
            let id = tree.create_proxy(b, next_ud);
            mirror.insert(id, b, next_ud);
            next_ud += 1;
        }
        for batch in 0..25 {
            // A step's worth of moves: a random share of the proxies drifts (enlarged in
            // place), some are created, destroyed or teleported (moved) meanwhile.
            let share = rng.range(0.02, 0.9);
            for _ in 0..(share * mirror.ids.len() as f32) as usize {
                let r = rng.below(20);
                if r == 0 {
                    let b = random_box(&mut rng);
                    let id = tree.create_proxy(b, next_ud);
                    mirror.insert(id, b, next_ud);
                    next_ud += 1;
                } else if r == 1 && mirror.ids.len() > 1 {
                    let id = mirror.remove_at(rng.below(mirror.ids.len()));
                    tree.destroy_proxy(id);
                } else {
                    let id = mirror.ids[rng.below(mirror.ids.len())];
                    let (old, ud) = mirror.live[id as usize].unwrap();
                    let b = if r == 2 {
                        let b = random_box(&mut rng);
                        tree.move_proxy(id, b);
                        b
                    } else {
                        let d = rng.vec3(-2.0, 2.0);
                        let b = Aabb::new(old.min + d, old.max + d);
                        tree.enlarge_proxy(id, b);
                        b
                    };
                    mirror.live[id as usize] = Some((b, ud));
                }
            }
            tree.validate();
            assert!(tree.check().is_ok());
            check_against_brute_force(&tree, &mirror, &mut rng);
            if batch % 5 == 4 {
                // Sometimes the next step's narrow phase has nothing to rebuild beside.
                continue;
            }
            let had = tree.has_enlarged();
            let before = format!("{tree:?}");
            tree.rebuild_enlarged();
            assert!(!tree.has_enlarged());
            assert!(tree.nodes.iter().all(|n| !n.enlarged), "batch {batch}: a mark was left");
            if !had {
                assert_eq!(before, format!("{tree:?}"), "nothing to rebuild changed the tree");
            }
            tree.validate();
            check_against_brute_force(&tree, &mirror, &mut rng);
            for &id in &mirror.ids {
                let (b, ud) = mirror.live[id as usize].unwrap();
                assert_eq!((tree.fat_aabb(id), tree.user_data(id)), (b, ud));
            }
            let n = tree.proxy_count().max(2) as f32;
            assert!(
                (tree.height() as f32) <= 2.0 * n.log2() + 4.0,
                "height {}",
                tree.height()
            );
            let mut full = tree.clone();
            full.rebuild();
            assert!(
                tree.area_ratio() <= 1.25 * full.area_ratio(),
                "batch {batch}: partial {} against full {}",
                tree.area_ratio(),
                full.area_ratio()
            );
        }
        format!("{tree:?}")
    };
    for seed in 1..4 {
        assert_eq!(run(seed), run(seed), "seed {seed}: the same calls gave different trees");
    }
}

/// The tree as nested boxes, heights and proxies in depth-first order, without node indices.
fn shape_of(tree: &DynamicTree) -> Vec<(Aabb, i32, u32)> {
    let mut out = Vec::new();
    let mut stack = vec![tree.root];
    while let Some(i) = stack.pop() {
        let n = tree.nodes[i as usize];
        out.push((n.aabb, n.height, if n.is_leaf() { i } else { NULL_NODE }));
        if !n.is_leaf() {
            stack.push(n.child2);
            stack.push(n.child1);
        }
    }
    out
}

/// A rebuild split into jobs builds the same tree, node indices included, as one that splits
/// every range on the calling thread, whatever the job size (one job for everything too) and
/// whatever order and threads its jobs run in (two threads taking jobs from a shared counter,
/// and the jobs in reverse).
#[test]
fn rebuild_jobs_give_the_tree_of_a_serial_build_on_any_threads() {
    for seed in 1..6u64 {
        let mut rng = Rng::new(seed);
        let mut tree = DynamicTree::new();
        let mut ids = Vec::new();
        for k in 0..(500 + rng.below(3000)) {
            ids.push(tree.create_proxy(random_box(&mut rng), k as u32));
        }
        let share = rng.range(0.05, 1.0);
        for &id in &ids {
            if rng.f32() < share {
                let b = tree.fat_aabb(id);
                let d = rng.vec3(-3.0, 3.0);
                tree.enlarge_proxy(id, Aabb::new(b.min + d, b.max + d));
            }
        }
        let full = rng.below(2) == 0;
        let build = |job_units: usize, how: u32| {
            let mut t = tree.clone();
            let jobs = t.begin_rebuild(full, |_| job_units);
            let run = t.rebuild_jobs();
            match how {
                0 => (0..jobs).for_each(|k| unsafe { run.run(k) }),
                1 => (0..jobs).rev().for_each(|k| unsafe { run.run(k) }),
                _ => {
                    let next = std::sync::atomic::AtomicUsize::new(0);
                    std::thread::scope(|s| {
                        for _ in 0..2 {
                            s.spawn(|| loop {
                                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                                if k >= jobs {
                                    break;
                                }
                                // SAFETY: the counter hands out each job once.
                                unsafe { run.run(k) };
                            });
                        }
                    });
                }
            }
            t.end_rebuild();
            t.validate();
            assert!(t.nodes.iter().all(|n| !n.enlarged));
            (jobs, t)
        };
        let (none, serial) = build(1, 0);
        assert_eq!(none, 0);
        for job_units in [2, 7, 64, JOB_UNITS, usize::MAX] {
            let (jobs, first) = build(job_units, 0);
            assert!(jobs > 0 || !tree.has_enlarged() && !full);
            assert_eq!(shape_of(&first), shape_of(&serial), "seed {seed}, jobs of {job_units}");
            // Pre-order slots: the job size does not change the node indices either.
            assert_eq!(
                format!("{:?}", first.nodes),
                format!("{:?}", serial.nodes),
                "seed {seed}, jobs of {job_units}"
            );
            for how in 1..3 {
                let (_, t) = build(job_units, how);
                assert_eq!(
                    format!("{:?}", t.nodes),
                    format!("{:?}", first.nodes),
                    "seed {seed}, order {how}"
                );
            }
        }
    }
}

/// The ray walk as it was before the nearer child was walked straight away and finite rays
/// got their own slab test: both children pushed (nearer on top) and popped back, every
/// slab test through `RaySlabs::entry`. The reference `ray_cast` must match call for call.
fn ray_cast_reference<F: FnMut(u32, u32, f32) -> f32>(
    tree: &DynamicTree,
    origin: Vec3,
    dir: Vec3,
    max_t: f32,
    mut f: F,
) -> u32 {
    if tree.root == NULL_NODE || max_t.is_nan() || max_t < 0.0 {
        return 0;
    }
    let ray = RaySlabs::new(origin, dir);
    let mut max_t = max_t;
    let mut tested = 1u32;
    let Some(t_root) = ray.entry(max_t, &tree.nodes[tree.root as usize].aabb) else {
        return tested;
    };
    let mut stack = vec![(tree.root, t_root)];
    while let Some((i, entry)) = stack.pop() {
        if entry > max_t {
            continue;
        }
        let n = &tree.nodes[i as usize];
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
            let ea = ray.entry(max_t, &tree.nodes[a as usize].aabb);
            let eb = ray.entry(max_t, &tree.nodes[b as usize].aabb);
            match (ea, eb) {
                (Some(ta), Some(tb)) => {
                    if ta <= tb {
                        stack.push((b, tb));
                        stack.push((a, ta));
                    } else {
                        stack.push((a, ta));
                        stack.push((b, tb));
                    }
                }
                (Some(ta), None) => stack.push((a, ta)),
                (None, Some(tb)) => stack.push((b, tb)),
                (None, None) => {}
            }
        }
    }
    tested
}

/// A ray walk of the tree given its callback.
type Walk<'a> = dyn Fn(&mut dyn FnMut(u32, u32, f32) -> f32) -> u32 + 'a;

/// Seeded random trees (incremental and rebuilt) and 10,000 rays with random answers from
/// the callback (clip at the box entry, ignore, go on unclipped, stop): `ray_cast` makes
/// exactly the reference walk's calls (proxy, user data, clipped `max_t` bits, in order)
/// and returns the same count of boxes tested, for finite rays and rays with zero or
/// subnormal direction components, with the shallow (spill-free) stack, the deep one, a
/// spill-free one of 64 entries and a stack of
/// two entries that spills. `query` with a stack of two entries reports what `query` does.
#[test]
fn ray_cast_makes_the_reference_walks_calls() {
    let mut rng = Rng::new(0x5eed_ca57);
    let mut rays = 0;
    let mut spilled = false;
    for round in 0..20 {
        let mut tree = DynamicTree::new();
        let mut ids = Vec::new();
        let count = 1 + rng.below(1500);
        for i in 0..count {
            ids.push(tree.create_proxy(random_box(&mut rng), i as u32));
            if i % 5 == 0 {
                let k = rng.below(ids.len());
                tree.move_proxy(ids[k], random_box(&mut rng));
            }
        }
        if round % 3 == 2 {
            tree.rebuild();
        }
        tree.validate();
        spilled |= tree.height() >= 3;
        for _ in 0..500 {
            let (o, mut d, len) = random_ray(&mut rng);
            match rng.below(8) {
                0 => d.z = 1.0e-41,
                1 => d.y = 0.0,
                _ => {}
            }
            let d = d * (len / d.length().max(1.0e-30));
            let max_t = [1.0, 0.5, 0.0, rng.range(0.0, 2.0)][rng.below(4)];
            let mode = rng.below(4);
            let inv = reciprocal(d);
            // The callback's answer, from the proxy alone so that both walks get the same.
            let answer = |p: u32, cur: f32| -> f32 {
                let e = ray_aabb_entry(o, d, inv, cur, &tree.fat_aabb(p)).unwrap_or(-1.0);
                match (mode, p % 7) {
                    (_, 0) => -1.0,
                    (0, _) => cur,
                    (1, 1) if e > 0.5 * cur => 0.0,
                    _ if e > 0.0 => e,
                    _ => -1.0,
                }
            };
            let mut want = Vec::new();
            let want_n = ray_cast_reference(&tree, o, d, max_t, |p, u, cur| {
                want.push((p, u, cur.to_bits()));
                answer(p, cur)
            });
            let ray = RaySlabs::new(o, d);
            let walks: [&Walk; 4] = [
                &|g| tree.ray_cast(o, d, max_t, g),
                &|g| {
                    if ray.finite {
                        tree.ray_cast_with(max_t, |t, b| ray.entry_finite(t, b), g, FixedStack::<_, 2>::new())
                    } else {
                        tree.ray_cast_with(max_t, |t, b| ray.entry(t, b), g, FixedStack::<_, 2>::new())
                    }
                },
                &|g| tree.ray_cast_with(max_t, |t, b| ray.entry(t, b), g, RayStack::new()),
                &|g| {
                    let stack = BoundedStack::<_, 64>::new();
                    if ray.finite {
                        tree.ray_cast_with(max_t, |t, b| ray.entry_finite(t, b), g, stack)
                    } else {
                        tree.ray_cast_with(max_t, |t, b| ray.entry(t, b), g, stack)
                    }
                },
            ];
            for (k, walk) in walks.iter().enumerate() {
                let mut got = Vec::new();
                let got_n = walk(&mut |p, u, cur| {
                    got.push((p, u, cur.to_bits()));
                    answer(p, cur)
                });
                assert_eq!((got_n, &got), (want_n, &want), "round {round}, walk {k}");
            }
            rays += 1;
        }
        for _ in 0..50 {
            let q = query_box(&mut rng);
            let (mut a, mut b) = (Vec::new(), Vec::new());
            tree.query(&q, |p, _| {
                a.push(p);
                true
            });
            tree.query_with(
                &q,
                |p, _| {
                    b.push(p);
                    true
                },
                FixedStack::<_, 2>::new(),
            );
            assert_eq!(a, b, "round {round}");
        }
    }
    assert_eq!(rays, 10_000);
    assert!(spilled, "some tree deeper than the two-entry stack");
}
