//! Queries: what a ray or a moving shape hits, and what overlaps a shape, a box or a point.
//!
//! * `ray` — a ray against one shape of each kind.
//! * `cast` — query shapes as rounded cores; shape casts by conservative advancement;
//!   exact overlap and point tests against one shape.
//!
//! The world's queries (below) walk the broad phase's dynamic tree, which holds every
//! shape but planes (static, kinematic, dynamic, sleeping alike), and test the planes one
//! by one. They take `&World`: nothing changes, and nothing is allocated (the tree, mesh
//! and heightfield walks use fixed stacks). Every query takes a [`QueryFilter`], tested
//! against each shape's [`Filter`](crate::collision::filter::Filter).

pub mod cast;
pub mod ray;

use crate::collision::aabb::Aabb;
use crate::collision::broad_phase::{aabb_touches_plane, world_plane};
use crate::collision::filter::QueryFilter;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::{BodyHandle, ShapeHandle};
use crate::error::{check_position, invalid, Result};
use crate::math::{Transform, Vec3};
use crate::world::World;

/// Longest accepted ray or cast translation (m).
pub const MAX_TRANSLATION: f32 = 1.0e6;

/// A ray's or a shape cast's hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QueryHit {
    pub shape: ShapeHandle,
    pub body: BodyHandle,
    /// World point on the hit surface.
    pub point: Vec3,
    /// Unit surface normal there, facing the ray (or the moving shape).
    pub normal: Vec3,
    /// Fraction of the translation, in `[0, 1]`.
    pub fraction: f32,
}

/// Checks a ray or cast: a position origin and a finite, non-zero translation.
pub fn check_ray(origin: Vec3, translation: Vec3) -> Result<()> {
    check_position("origin", origin)?;
    let l = translation.length();
    if !translation.is_finite() || l == 0.0 || l > MAX_TRANSLATION {
        return Err(invalid(format!(
            "translation must be finite, non-zero and at most {MAX_TRANSLATION} m long, got {translation}"
        )));
    }
    Ok(())
}

/// Checks a query shape: a sphere, capsule, box or hull, valid as a shape would be.
fn check_query_shape(world: &World, geometry: &Geometry, xf: &Transform) -> Result<Geometry> {
    if matches!(
        geometry,
        Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. }
    ) {
        return Err(invalid(
            "a query shape must be a sphere, capsule, box or hull (not a plane, mesh or heightfield)",
        ));
    }
    let g = geometry.validated()?;
    world.geometry.check(&g)?;
    check_position("transform position", xf.p)?;
    crate::error::check_quat("transform rotation", xf.q)?;
    Ok(g)
}

impl World {
    #[inline]
    fn hit_of(&self, s: u32, point: Vec3, normal: Vec3, fraction: f32) -> QueryHit {
        let shape = self.shapes.at(s);
        QueryHit {
            shape: self.shapes.handle_at(s).expect("live shape"),
            body: self.bodies.handle_at(shape.body).expect("live body"),
            point,
            normal,
            fraction,
        }
    }

    /// Casts the ray `origin + t · translation`, `t` in `[0, 1]`, and calls `f` with each
    /// hit of a shape the filter accepts (one hit per shape, its nearest, in no particular
    /// order). `f` returns how to go on (Box2D v3's protocol): a negative value ignores the
    /// hit, 0 stops, a fraction in `(0, 1]` clips the ray there (later hits are nearer;
    /// return the hit's own fraction to find the closest), anything larger continues.
    /// A ray starting inside a solid shape does not hit that shape (see `ray`).
    pub fn cast_ray(
        &self,
        origin: Vec3,
        translation: Vec3,
        filter: &QueryFilter,
        mut f: impl FnMut(&QueryHit) -> f32,
    ) -> Result<()> {
        check_ray(origin, translation)?;
        self.ray_walk(origin, translation, filter, |s, h| {
            f(&self.hit_of(s, origin + h.fraction * translation, h.normal, h.fraction))
        });
        Ok(())
    }

    /// The ray traversal behind every ray query (`cast_ray`, `cast_ray_closest`, and through
    /// them the C batch call): the planes one by one, then the tree front to back (see
    /// [`DynamicTree::ray_cast`](crate::collision::dynamic_tree::DynamicTree::ray_cast)),
    /// each leaf's shape tested against the ray clipped so far. `f(shape slot, hit)` answers
    /// as in `cast_ray`. Returns the number of tree boxes tested (the work a ray did).
    pub(crate) fn ray_walk(
        &self,
        origin: Vec3,
        translation: Vec3,
        filter: &QueryFilter,
        mut f: impl FnMut(u32, &ray::ShapeRayHit) -> f32,
    ) -> u32 {
        let mut max_t = 1.0f32;
        for &p in &self.broad.planes {
            let shape = self.shapes.at(p);
            if !filter.accepts(&shape.def.filter) {
                continue;
            }
            let xf = &self.bodies.at(shape.body).xf;
            if let Some(h) = ray::ray_cast_geometry(&self.geometry, &shape.geometry, xf, origin, translation, max_t) {
                let v = f(p, &h);
                if v == 0.0 {
                    return 0;
                }
                if v > 0.0 && v <= max_t {
                    max_t = v;
                }
            }
        }
        self.broad.tree.ray_cast(origin, translation, max_t, |_, s, cur| {
            let shape = self.shapes.at(s);
            if !filter.accepts(&shape.def.filter) {
                return -1.0;
            }
            let xf = &self.bodies.at(shape.body).xf;
            match ray::ray_cast_geometry(&self.geometry, &shape.geometry, xf, origin, translation, cur) {
                Some(h) => {
                    let v = f(s, &h);
                    if v.is_nan() {
                        -1.0
                    } else {
                        v
                    }
                }
                None => -1.0,
            }
        })
    }

    /// The nearest hit of the ray (see [`World::cast_ray`]), if any. Of hits at the same
    /// fraction, the first one met is kept.
    pub fn cast_ray_closest(&self, origin: Vec3, translation: Vec3, filter: &QueryFilter) -> Result<Option<QueryHit>> {
        Ok(self.cast_ray_closest_counted(origin, translation, filter)?.0)
    }

    /// Like [`World::cast_ray_closest`], also returning the number of broad-phase tree boxes
    /// the ray tested: the traversal's work, for tests and benches.
    pub fn cast_ray_closest_counted(
        &self,
        origin: Vec3,
        translation: Vec3,
        filter: &QueryFilter,
    ) -> Result<(Option<QueryHit>, u32)> {
        check_ray(origin, translation)?;
        let mut best: Option<(u32, ray::ShapeRayHit)> = None;
        let tested = self.ray_walk(origin, translation, filter, |s, h| {
            if best.map_or(true, |b| h.fraction < b.1.fraction) {
                best = Some((s, *h));
            }
            h.fraction
        });
        let hit = best.map(|(s, h)| self.hit_of(s, origin + h.fraction * translation, h.normal, h.fraction));
        Ok((hit, tested))
    }

    /// Casts a sphere, capsule, box or hull (`geometry`, placed by `xf` as on a body) along
    /// `translation` and returns the first shape it touches: fraction of the translation
    /// (0 when it overlaps something at the start), the point on the hit surface and its
    /// normal facing the moving shape. The fraction is never past the true time of impact
    /// and at most `CAST_TOLERANCE` metres (along the normal) before it.
    pub fn cast_shape(
        &self,
        geometry: &Geometry,
        xf: &Transform,
        translation: Vec3,
        filter: &QueryFilter,
    ) -> Result<Option<QueryHit>> {
        let g = check_query_shape(self, geometry, xf)?;
        check_ray(xf.p, translation)?;
        let a = cast::rounded(&self.geometry, &g, xf).expect("checked convex");
        let a_box = g.aabb(&self.geometry, xf);
        let swept = a_box.swept(translation);
        let mut best: Option<QueryHit> = None;
        let consider = |s: u32, shape: &Shape, best: &mut Option<QueryHit>| {
            if !filter.accepts(&shape.def.filter) {
                return;
            }
            let lim = best.map_or(1.0, |b| b.fraction);
            let sxf = &self.bodies.at(shape.body).xf;
            if let Some(r) = cast::cast_against(&self.geometry, &a, &a_box, translation, &shape.geometry, sxf, lim) {
                if best.map_or(true, |b| r.fraction < b.fraction) {
                    *best = Some(self.hit_of(s, r.point, r.normal, r.fraction));
                }
            }
        };
        for &p in &self.broad.planes {
            consider(p, self.shapes.at(p), &mut best);
        }
        self.broad.tree.query(&swept, |_, s| {
            consider(s, self.shapes.at(s), &mut best);
            true
        });
        Ok(best)
    }

    /// Calls `f` with every shape the filter accepts that overlaps or touches a sphere,
    /// capsule, box or hull (`geometry` placed by `xf`), exactly (GJK against the shape's
    /// own geometry), until `f` returns false.
    pub fn overlap_shape(
        &self,
        geometry: &Geometry,
        xf: &Transform,
        filter: &QueryFilter,
        mut f: impl FnMut(ShapeHandle) -> bool,
    ) -> Result<()> {
        let g = check_query_shape(self, geometry, xf)?;
        let a = cast::rounded(&self.geometry, &g, xf).expect("checked convex");
        let a_box = g.aabb(&self.geometry, xf);
        let test = |s: u32| {
            let shape = self.shapes.at(s);
            filter.accepts(&shape.def.filter)
                && cast::overlaps(
                    &self.geometry,
                    &a,
                    &a_box,
                    &shape.geometry,
                    &self.bodies.at(shape.body).xf,
                )
        };
        for &p in &self.broad.planes {
            if test(p) && !f(self.shapes.handle_at(p).expect("live shape")) {
                return Ok(());
            }
        }
        self.broad.tree.query(&a_box, |_, s| {
            !test(s) || f(self.shapes.handle_at(s).expect("live shape"))
        });
        Ok(())
    }

    /// Calls `f` with every shape the filter accepts whose tight bounds (as of the last
    /// step, creation or teleport) overlap `aabb` (planes: whose half-space the box reaches),
    /// until `f` returns false.
    pub fn overlap_aabb(
        &self,
        aabb: &Aabb,
        filter: &QueryFilter,
        mut f: impl FnMut(ShapeHandle) -> bool,
    ) -> Result<()> {
        check_position("aabb min", aabb.min)?;
        check_position("aabb max", aabb.max)?;
        if !aabb.min.cmple(aabb.max).all() {
            return Err(invalid(format!(
                "aabb min must not exceed max on any axis, got min {} max {}",
                aabb.min, aabb.max
            )));
        }
        for &p in &self.broad.planes {
            let shape = self.shapes.at(p);
            let (n, d) = world_plane(&shape.geometry, &self.bodies.at(shape.body).xf);
            if filter.accepts(&shape.def.filter)
                && aabb_touches_plane(aabb, n, d)
                && !f(self.shapes.handle_at(p).expect("live shape"))
            {
                return Ok(());
            }
        }
        self.broad.tree.query(aabb, |_, s| {
            let shape = self.shapes.at(s);
            !(filter.accepts(&shape.def.filter) && shape.aabb.overlaps(aabb))
                || f(self.shapes.handle_at(s).expect("live shape"))
        });
        Ok(())
    }

    /// Calls `f` with every solid shape the filter accepts that contains `point` (on the
    /// surface counts; meshes and heightfields, being surfaces, contain none), until `f`
    /// returns false.
    pub fn overlap_point(
        &self,
        point: Vec3,
        filter: &QueryFilter,
        mut f: impl FnMut(ShapeHandle) -> bool,
    ) -> Result<()> {
        check_position("point", point)?;
        let test = |s: u32| {
            let shape = self.shapes.at(s);
            filter.accepts(&shape.def.filter)
                && cast::contains_point(&self.geometry, &shape.geometry, &self.bodies.at(shape.body).xf, point)
        };
        for &p in &self.broad.planes {
            if test(p) && !f(self.shapes.handle_at(p).expect("live shape")) {
                return Ok(());
            }
        }
        let bb = Aabb::new(point, point);
        self.broad
            .tree
            .query(&bb, |_, s| !test(s) || f(self.shapes.handle_at(s).expect("live shape")));
        Ok(())
    }
}
