//! A convex hull, scaled, seen as a `Polytope` by the triangle tests (`triangle.rs`).

use super::triangle::{Polytope, CLIP_CAP};
use crate::collision::hull::ConvexHull;
use crate::math::Vec3;

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
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for v in self.hull.vertices() {
            let x = v.dot(a);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        (lo * self.scale, hi * self.scale)
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
