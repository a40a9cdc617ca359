//! GJK (Gilbert, Johnson & Keerthi 1988): distance and closest points between two convex
//! shapes given only by their support functions.
//!
//! The shapes are *cores*: a rounded shape (sphere, capsule, rounded hull) is its core
//! (point, segment, polyhedron) plus a radius the caller adds, so the distance between
//! the surfaces is `distance − radius_a − radius_b` and the surface points are the core
//! points moved along the normal by each radius.
//!
//! The iteration works on the Minkowski difference `B − A`: its point closest to the
//! origin, `v`, is the vector from A's closest point to B's. Each step adds the support
//! point of `B − A` along `−v` to a simplex of at most four points and replaces the
//! simplex by the smallest sub-simplex that contains its point closest to the origin
//! (Voronoi regions of segments and triangles, after Ericson, *Real-Time Collision
//! Detection* §5.1). It stops when the support point brings no progress (relative
//! `1e-6`), when the simplex encloses the origin (overlap), or after 64 iterations. The
//! closest points are the barycentric combinations of the simplex's points on A and B.
//!
//! Nothing allocates. `epa.rs` continues from an overlapping result.

use crate::math::Vec3;

/// A convex core given by its support function.
pub trait Support {
    /// A point of the core furthest along `d` (`d` need not be unit, may be zero).
    fn support(&self, d: Vec3) -> Vec3;
    /// A point inside the core (starts the search).
    fn center(&self) -> Vec3;
}

/// A point (the core of a sphere).
#[derive(Clone, Copy, Debug)]
pub struct Point(pub Vec3);

impl Support for Point {
    #[inline]
    fn support(&self, _d: Vec3) -> Vec3 {
        self.0
    }
    fn center(&self) -> Vec3 {
        self.0
    }
}

/// A segment (the core of a capsule).
#[derive(Clone, Copy, Debug)]
pub struct Segment(pub Vec3, pub Vec3);

impl Support for Segment {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        if d.dot(self.1 - self.0) > 0.0 {
            self.1
        } else {
            self.0
        }
    }
    fn center(&self) -> Vec3 {
        0.5 * (self.0 + self.1)
    }
}

/// A point set (its convex hull), e.g. a box's corners.
#[derive(Clone, Copy, Debug)]
pub struct Points<'a>(pub &'a [Vec3]);

impl Support for Points<'_> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        let mut best = self.0[0];
        let mut best_d = best.dot(d);
        for p in &self.0[1..] {
            let x = p.dot(d);
            if x > best_d {
                best_d = x;
                best = *p;
            }
        }
        best
    }
    fn center(&self) -> Vec3 {
        self.0.iter().copied().sum::<Vec3>() / self.0.len() as f32
    }
}

/// A vertex of the simplex: the support point of `B − A` and the points of A and B it
/// came from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SimplexVertex {
    pub w: Vec3,
    pub a: Vec3,
    pub b: Vec3,
}

/// The simplex GJK ended with (up to four vertices and their barycentric weights).
#[derive(Clone, Copy, Debug, Default)]
pub struct Simplex {
    pub v: [SimplexVertex; 4],
    pub weights: [f32; 4],
    pub count: usize,
}

/// Result of [`distance`].
#[derive(Clone, Copy, Debug)]
pub struct DistanceOutput {
    /// Distance between the cores (0 when they overlap).
    pub distance: f32,
    /// Closest points on A's and B's cores (on overlap: a common point, approximately).
    pub point_a: Vec3,
    pub point_b: Vec3,
    /// Unit vector from A to B (`(point_b − point_a) / distance`); zero on overlap.
    pub normal: Vec3,
    /// The cores overlap (or touch within rounding).
    pub overlap: bool,
    pub iterations: u32,
    pub simplex: Simplex,
}

/// Largest number of GJK iterations.
pub const MAX_ITERATIONS: u32 = 64;
/// Relative progress under which the iteration stops.
const REL_TOL: f32 = 1.0e-6;

#[inline]
fn support_vertex<A: Support + ?Sized, B: Support + ?Sized>(a: &A, b: &B, d: Vec3) -> SimplexVertex {
    // Support of B − A along d: B's along d minus A's along −d.
    let pa = a.support(-d);
    let pb = b.support(d);
    SimplexVertex {
        w: pb - pa,
        a: pa,
        b: pb,
    }
}

/// Distance and closest points between the cores of `a` and `b`.
pub fn distance<A: Support + ?Sized, B: Support + ?Sized>(a: &A, b: &B) -> DistanceOutput {
    let d0 = b.center() - a.center();
    let d0 = if d0.length_squared() > 1.0e-20 { d0 } else { Vec3::X };
    distance_from(a, b, d0)
}

/// [`distance`] starting from the direction `start` (from A towards B); a good guess (last
/// frame's normal) saves iterations.
pub fn distance_from<A: Support + ?Sized, B: Support + ?Sized>(a: &A, b: &B, start: Vec3) -> DistanceOutput {
    distance_until(a, b, start, -1.0)
}

/// [`distance_from`] that stops as soon as the distance is known to be at most `stop`:
/// when the simplex holds a point of the Minkowski difference within `stop` of the origin.
/// The output is then that point's (not overlapping, `distance <= stop`, an upper bound of
/// the true distance); otherwise the iteration runs on exactly as `distance_from`'s, with
/// the same output. Every distance `distance_from` would return is at most the stopped
/// one (the iteration only keeps closer points). A negative `stop` never stops early.
pub fn distance_until<A: Support + ?Sized, B: Support + ?Sized>(
    a: &A,
    b: &B,
    start: Vec3,
    stop: f32,
) -> DistanceOutput {
    let mut s = Simplex::default();
    let first = support_vertex(a, b, -start);
    s.v[0] = first;
    s.weights[0] = 1.0;
    s.count = 1;
    let mut v = first.w;
    let mut vv = v.length_squared();
    let mut iterations = 0;
    let mut overlap = false;
    while iterations < MAX_ITERATIONS {
        // The square root as the caller will see it, so that `distance <= stop` holds.
        if vv.sqrt() <= stop {
            break;
        }
        iterations += 1;
        if vv < 1.0e-14 {
            overlap = true;
            break;
        }
        let sv = support_vertex(a, b, -v);
        // No progress along v: v is (within tolerance) the closest point.
        if vv - v.dot(sv.w) <= REL_TOL * vv {
            break;
        }
        if s.v[..s.count].iter().any(|x| x.w == sv.w) {
            break;
        }
        // The simplex as it was, kept field by field (a whole-struct copy is a `memcpy` call
        // per iteration).
        let saved = (s.v[0], s.v[1], s.v[2], s.v[3], s.weights, s.count);
        s.v[s.count] = sv;
        s.count += 1;
        if !solve(&mut s) {
            overlap = true;
            break;
        }
        let nv = combine(&s, |x| x.w);
        let nvv = nv.length_squared();
        if nvv >= vv {
            // Rounding: keep the better simplex.
            let (v0, v1, v2, v3, weights, count) = saved;
            s.v = [v0, v1, v2, v3];
            s.weights = weights;
            s.count = count;
            break;
        }
        v = nv;
        vv = nvv;
    }
    let point_a = combine(&s, |x| x.a);
    let point_b = combine(&s, |x| x.b);
    if overlap {
        return DistanceOutput {
            distance: 0.0,
            point_a,
            point_b,
            normal: Vec3::ZERO,
            overlap: true,
            iterations,
            simplex: s,
        };
    }
    let dist = vv.sqrt();
    DistanceOutput {
        distance: dist,
        point_a,
        point_b,
        normal: if dist > 0.0 { v / dist } else { Vec3::ZERO },
        overlap: false,
        iterations,
        simplex: s,
    }
}

#[inline]
fn combine(s: &Simplex, f: impl Fn(&SimplexVertex) -> Vec3) -> Vec3 {
    let mut p = Vec3::ZERO;
    for i in 0..s.count {
        p += f(&s.v[i]) * s.weights[i];
    }
    p
}

/// Replaces the simplex by the sub-simplex whose hull holds its point closest to the
/// origin, with barycentric weights. Returns false when a tetrahedron contains the origin.
fn solve(s: &mut Simplex) -> bool {
    match s.count {
        2 => {
            solve2(s, 0, 1);
            true
        }
        3 => {
            let (v, w, n) = triangle(s.v[0].w, s.v[1].w, s.v[2].w);
            reduce(s, &v[..n], &w[..n]);
            true
        }
        4 => solve4(s),
        _ => true,
    }
}

fn reduce(s: &mut Simplex, keep: &[usize], weights: &[f32]) {
    // The kept vertices (at most three) gathered first, then written to the front: the
    // same simplex as from a copy of all four, without copying the fourth.
    let mut kept = [SimplexVertex::default(); 3];
    for (k, &i) in keep.iter().enumerate() {
        kept[k] = s.v[i];
    }
    for (k, (&v, &w)) in kept.iter().zip(weights).enumerate() {
        s.v[k] = v;
        s.weights[k] = w;
    }
    s.count = keep.len();
}

fn solve2(s: &mut Simplex, i: usize, j: usize) {
    let (p, q) = (s.v[i].w, s.v[j].w);
    let e = q - p;
    let ee = e.length_squared();
    let t = if ee > 0.0 { -p.dot(e) / ee } else { 0.0 };
    if t <= 0.0 {
        reduce(s, &[i], &[1.0]);
    } else if t >= 1.0 {
        reduce(s, &[j], &[1.0]);
    } else {
        reduce(s, &[i, j], &[1.0 - t, t]);
    }
}

/// Closest point of triangle `a b c` to the origin: the vertices (indices 0..2) of its
/// Voronoi region and their weights.
fn triangle(a: Vec3, b: Vec3, c: Vec3) -> ([usize; 3], [f32; 3], usize) {
    let ab = b - a;
    let ac = c - a;
    let ap = -a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return ([0, 0, 0], [1.0, 0.0, 0.0], 1);
    }
    let bp = -b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return ([1, 0, 0], [1.0, 0.0, 0.0], 1);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        return ([0, 1, 0], [1.0 - t, t, 0.0], 2);
    }
    let cp = -c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return ([2, 0, 0], [1.0, 0.0, 0.0], 1);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        return ([0, 2, 0], [1.0 - t, t, 0.0], 2);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return ([1, 2, 0], [1.0 - t, t, 0.0], 2);
    }
    let denom = va + vb + vc;
    if denom.abs() < 1.0e-30 {
        // Degenerate (collinear) triangle: the best edge.
        return ([0, 1, 0], [0.5, 0.5, 0.0], 2);
    }
    let inv = 1.0 / denom;
    let v = vb * inv;
    let w = vc * inv;
    ([0, 1, 2], [1.0 - v - w, v, w], 3)
}

fn solve4(s: &mut Simplex) -> bool {
    let p = [s.v[0].w, s.v[1].w, s.v[2].w, s.v[3].w];
    // Faces with the opposite vertex.
    const FACES: [([usize; 3], usize); 4] = [([0, 1, 2], 3), ([0, 3, 1], 2), ([0, 2, 3], 1), ([1, 3, 2], 0)];
    let mut best: Option<([usize; 3], [f32; 3], usize, f32)> = None;
    let mut outside_any = false;
    for (f, opp) in FACES {
        let (a, b, c) = (p[f[0]], p[f[1]], p[f[2]]);
        let n = (b - a).cross(c - a);
        let side_origin = -a.dot(n);
        let side_opp = (p[opp] - a).dot(n);
        // The origin is outside this face when it is on the other side from the opposite
        // vertex (a degenerate face counts as outside so the tetrahedron is never trusted).
        if side_origin * side_opp > 0.0 && side_opp.abs() > 1.0e-12 * n.length_squared().max(1.0e-30) {
            continue;
        }
        outside_any = true;
        let (idx, w, k) = triangle(a, b, c);
        let mut q = Vec3::ZERO;
        let mut map = [0usize; 3];
        for j in 0..k {
            map[j] = f[idx[j]];
            q += p[map[j]] * w[j];
        }
        let d = q.length_squared();
        if best.map_or(true, |b| d < b.3) {
            best = Some((map, w, k, d));
        }
    }
    if !outside_any {
        return false;
    }
    let (map, w, k, _) = best.expect("some face");
    reduce(s, &map[..k], &w[..k]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_to_box_corner_edge_and_face() {
        let corners: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 != 0 { 1.0 } else { -1.0 },
                    if i & 2 != 0 { 1.0 } else { -1.0 },
                    if i & 4 != 0 { 1.0 } else { -1.0 },
                )
            })
            .collect();
        let bx = Points(&corners);
        for (p, expect, closest) in [
            (Vec3::new(3.0, 0.0, 0.0), 2.0, Vec3::new(1.0, 0.0, 0.0)),
            (Vec3::new(2.0, 2.0, 0.5), 2.0f32.sqrt(), Vec3::new(1.0, 1.0, 0.5)),
            (Vec3::new(2.0, 3.0, 4.0), (1.0f32 + 4.0 + 9.0).sqrt(), Vec3::ONE),
        ] {
            let d = distance(&bx, &Point(p));
            assert!(!d.overlap);
            assert!((d.distance - expect).abs() < 1e-5, "{p}: {}", d.distance);
            assert!((d.point_a - closest).length() < 1e-4, "{p}: {}", d.point_a);
            assert!((d.normal - (p - closest).normalize()).length() < 1e-4);
        }
        assert!(distance(&bx, &Point(Vec3::new(0.5, 0.2, -0.3))).overlap);
    }

    /// `distance_until` either stops with a distance at most `stop` that bounds the full
    /// iteration's from above (or the full one overlaps), or returns the full iteration's
    /// output bit for bit: random point clouds from overlapping to 1 m apart, stops from
    /// none to 0.5 m.
    #[test]
    fn distance_until_bounds_or_matches() {
        let mut r = crate::math::test_rnd::Rnd(0x5eed_1234_abcd_0001);
        let mut rnd = move || r.f() - 0.5;
        let (mut stopped, mut ran) = (0, 0);
        for _ in 0..2000 {
            let a: Vec<Vec3> = (0..10).map(|_| Vec3::new(rnd(), rnd(), rnd())).collect();
            let off = Vec3::new(rnd(), rnd(), rnd()) * 4.0;
            let b: Vec<Vec3> = (0..10).map(|_| off + Vec3::new(rnd(), rnd(), rnd())).collect();
            let start = Vec3::new(rnd(), rnd(), rnd());
            let stop = if rnd() < -0.3 { -1.0 } else { rnd() + 0.5 };
            let full = distance_from(&Points(&a), &Points(&b), start);
            let early = distance_until(&Points(&a), &Points(&b), start, stop);
            if !early.overlap && early.distance <= stop && early.iterations < full.iterations {
                stopped += 1;
                assert!(
                    full.overlap || full.distance <= early.distance,
                    "{} > {}",
                    full.distance,
                    early.distance
                );
            } else {
                ran += 1;
                assert_eq!(early.overlap, full.overlap);
                assert_eq!(early.distance.to_bits(), full.distance.to_bits());
                assert_eq!(early.point_a, full.point_a);
                assert_eq!(early.point_b, full.point_b);
            }
        }
        assert!(stopped > 200 && ran > 200, "{stopped} stopped, {ran} ran");
    }

    #[test]
    fn segments_cross() {
        let a = Segment(Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
        let b = Segment(Vec3::new(0.3, 1.0, -1.0), Vec3::new(0.3, 1.0, 1.0));
        let d = distance(&a, &b);
        assert!((d.distance - 1.0).abs() < 1e-5);
        assert!((d.point_a - Vec3::new(0.3, 0.0, 0.0)).length() < 1e-5);
        assert!((d.normal - Vec3::Y).length() < 1e-5);
    }
}
