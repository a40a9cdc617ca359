//! A convex hull, scaled, seen as a `Polytope` by the triangle tests (`triangle.rs`).

use super::triangle::{Polytope, CLIP_CAP};
use crate::collision::hull::ConvexHull;
use crate::math::Vec3;
use crate::simd::{Lanes, F4};

/// A hull scaled uniformly about its origin, in its own frame.
pub struct HullView<'a> {
    hull: &'a ConvexHull,
    scale: f32,
}

impl<'a> HullView<'a> {
    pub fn new(hull: &'a ConvexHull, scale: f32) -> HullView<'a> {
        HullView { hull, scale }
    }

    /// The convex radius, scaled.
    pub fn radius(&self) -> f32 {
        self.hull.radius() * self.scale
    }
}

impl Polytope for HullView<'_> {
    #[inline]
    fn interval(&self, a: Vec3) -> (f32, f32) {
        // Four vertices at a time; the same values as one at a time (`v.dot(a)`, min, max).
        let (lo, hi) = self.hull.dot_interval(a);
        (lo * self.scale, hi * self.scale)
    }

    /// One vertex at a time for four axes: each lane's products (`v.dot(a)`'s order) and
    /// its minimum and maximum, as `interval` (lane by lane the same values).
    #[inline]
    fn interval4(&self, ax: F4, ay: F4, az: F4) -> (F4, F4) {
        let (mut lo, mut hi) = (F4::splat(f32::MAX), F4::splat(f32::MIN));
        for v in self.hull.vertices() {
            let x = F4::splat(v.x) * ax + F4::splat(v.y) * ay + F4::splat(v.z) * az;
            lo = F4::select(lo.gt(x), x, lo);
            hi = F4::select(x.gt(hi), x, hi);
        }
        let s = F4::splat(self.scale);
        (lo * s, hi * s)
    }

    fn face_count(&self) -> usize {
        self.hull.planes().len()
    }

    #[inline]
    fn face_plane(&self, f: usize) -> (Vec3, f32) {
        let p = self.hull.planes()[f];
        (p.normal, p.offset * self.scale)
    }

    fn face_polygon(&self, f: usize, out: &mut [(Vec3, u32); CLIP_CAP]) -> usize {
        // Room is left for the three cuts of a triangle; a larger face keeps its first
        // vertices (a smaller polygon inside the face).
        let mut k = 0;
        for v in self.hull.face_vertices(f).take(CLIP_CAP - 3) {
            out[k] = (self.hull.vertices()[v as usize] * self.scale, v as u32);
            k += 1;
        }
        k
    }

    fn incident_face(&self, d: Vec3) -> usize {
        let mut best = (0, f32::MAX);
        for (f, p) in self.hull.planes().iter().enumerate() {
            let c = p.normal.dot(d);
            if c < best.1 {
                best = (f, c);
            }
        }
        best.0
    }

    fn edge_direction_count(&self) -> usize {
        self.hull.edge_directions().len()
    }

    #[inline]
    fn edge_direction(&self, i: usize) -> Vec3 {
        self.hull.edge_directions()[i]
    }

    fn support_edge(&self, a: Vec3, i: usize) -> (Vec3, Vec3) {
        let d = self.hull.edge_directions()[i];
        let mut best = (Vec3::ZERO, Vec3::ZERO, f32::MIN);
        for &e in self.hull.edges() {
            let (p, q) = self.hull.edge_points(e as usize);
            let u = q - p;
            if d.cross(u).length_squared() > 1.0e-6 * u.length_squared() {
                continue;
            }
            let x = (p + q).dot(a);
            if x > best.2 {
                best = (p, q, x);
            }
        }
        (best.0 * self.scale, best.1 * self.scale)
    }

    fn center(&self) -> Vec3 {
        self.hull.mass_properties(1.0).center * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::hull::builder::{build, HullSettings};
    use crate::collision::narrow_phase::triangle::{polytope_triangle, LocalBox, TriContact, Triangle};

    /// The hull's extent four vertices at a time (`ConvexHull::dot_interval`) is the one
    /// vertex at a time of `v.dot(a)`, `min`, `max`, bit for bit: random hulls of 4 to 40
    /// points, random directions (some along the axes, where products tie or vanish).
    #[test]
    fn interval_matches_one_at_a_time() {
        let mut rnd = crate::math::test_rnd::Rnd(0x3c6e_f372_fe94_f82b);
        for n in 4..400 {
            let pts: Vec<Vec3> = (0..4 + n % 37).map(|_| rnd.point(Vec3::new(0.7, 0.5, 0.3))).collect();
            let hull = build(&pts, &HullSettings::default()).unwrap();
            for k in 0..40 {
                let a = match k % 8 {
                    0 => Vec3::X,
                    1 => Vec3::NEG_Y,
                    2 => Vec3::new(0.0, 1.0, 1.0),
                    _ => Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5) * 3.0,
                };
                let (mut lo, mut hi) = (f32::MAX, f32::MIN);
                for v in hull.vertices() {
                    let x = v.dot(a);
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
                let (l, h) = hull.dot_interval(a);
                // Equal values; a zero may differ only in its sign, which no caller reads.
                assert!(l == lo && (l == 0.0 || l.to_bits() == lo.to_bits()), "{l} {lo}");
                assert!(h == hi && (h == 0.0 || h.to_bits() == hi.to_bits()), "{h} {hi}");
            }
        }
    }

    /// A cube hull against random triangles gives the box's answer (normal, deepest point).
    #[test]
    fn cube_hull_matches_box() {
        let h = 0.5;
        let pts: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 != 0 { h } else { -h },
                    if i & 2 != 0 { h } else { -h },
                    if i & 4 != 0 { h } else { -h },
                )
            })
            .collect();
        let hull = build(&pts, &HullSettings::default()).unwrap();
        let view = HullView::new(&hull, 1.0);
        let bx = LocalBox(Vec3::splat(h));
        let mut seed = 5u32;
        let mut rnd = move || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1u32 << 24) as f32 - 0.5
        };
        let mut hits = 0;
        for _ in 0..2000 {
            let c = Vec3::new(rnd(), rnd() - 0.6, rnd()) * 1.5;
            let v = [0, 1, 2].map(|_| c + 2.0 * Vec3::new(rnd(), 0.3 * rnd(), rnd()));
            let n = (v[1] - v[0]).cross(v[2] - v[0]);
            if n.length() < 1e-3 {
                continue;
            }
            let n = n.normalize();
            let t = Triangle {
                v,
                n,
                flags: 0b111,
                index: 0,
            };
            let (mut a, mut b) = (TriContact::EMPTY, TriContact::EMPTY);
            let ha = polytope_triangle(&view, 0.0, &t, 0.05, &mut a);
            let hb = polytope_triangle(&bx, 0.0, &t, 0.05, &mut b);
            assert_eq!(ha, hb, "{v:?}");
            if ha {
                hits += 1;
                assert!((a.normal - b.normal).length() < 1e-4, "{} {}", a.normal, b.normal);
                let deep = |c: &TriContact| c.points[..c.count].iter().fold(f32::MAX, |m, p| m.min(p.separation));
                assert!((deep(&a) - deep(&b)).abs() < 1e-4);
            }
        }
        assert!(hits > 200, "{hits}");
    }
}
