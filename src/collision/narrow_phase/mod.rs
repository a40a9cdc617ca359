//! Narrowphase: contact manifolds between pairs of shapes.
//!
//! Every function here is pure geometry: shapes in their body's local frame plus the body
//! transforms in, a [`Manifold`] out. The world's contact stage calls [`collide`].
//!
//! Conventions for every pair: the normal is a world-space unit vector from A to B; a
//! point lies midway between the two surfaces along the normal; separation is signed
//! (negative = penetration) and points are kept while it is at most `speculative`. When
//! the geometry gives no direction (coincident centres, zero-length capsules) the normal
//! is +Y. Nothing here allocates.
//!
//! One file per family: `sphere` (sphere against everything), `capsule` (capsule against
//! capsule, box, plane), `box_box`, `plane` (box against plane), `hull` (hulls against
//! spheres, capsules and planes), `hull_hull` (hulls and boxes against hulls, SAT with a
//! cached axis); `geom` holds the shared helpers. Triangle meshes and heightfields:
//! `triangle` (a convex shape against one triangle, with active edges), `mesh` (the
//! triangles under a shape, folded into several manifolds by normal: [`collide_triangles`]),
//! `hull_view` (a hull as a polytope for the triangle test).

mod box_box;
mod capsule;
mod geom;
pub(crate) mod hull;
mod hull_hull;
mod hull_view;
pub mod mesh;
mod plane;
mod sphere;
pub mod triangle;

pub use mesh::{collide_triangles, MeshManifolds, MAX_MESH_MANIFOLDS};

pub use hull_hull::{FaceHold, SatCache, SatFeature};

use crate::collision::geometry_store::GeometryStore;
use crate::collision::shape::Geometry;
use crate::math::{Transform, Vec3};
use geom::{WorldBox, WorldPlane};

/// Most points a manifold carries (a face–face box contact is reduced to four).
pub const MAX_MANIFOLD_POINTS: usize = 4;

/// One contact point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ManifoldPoint {
    /// World-space point midway between the two surfaces.
    pub point: Vec3,
    /// Signed distance along the normal: negative when penetrating, positive when
    /// separated (speculative point).
    pub separation: f32,
    /// Feature key: stable across frames while the same features touch, used to match
    /// points between frames for warm starting.
    pub id: u32,
}

/// Contact manifold between shape A and shape B.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Manifold {
    /// World-space unit normal pointing from A to B.
    pub normal: Vec3,
    pub points: [ManifoldPoint; MAX_MANIFOLD_POINTS],
    pub count: usize,
}

impl Manifold {
    pub const EMPTY: Manifold = Manifold {
        normal: Vec3::ZERO,
        points: [ManifoldPoint {
            point: Vec3::ZERO,
            separation: 0.0,
            id: 0,
        }; MAX_MANIFOLD_POINTS],
        count: 0,
    };

    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.count]
    }
}

/// Computes the contact manifold of `a` (on a body at `xf_a`) against `b` (at `xf_b`).
/// Points are reported while their separation is at most `speculative` metres, so the
/// solver can stop fast bodies before they pass through. Plane–plane gives no contact.
///
/// Pairs are handled with `kind(a) <= kind(b)`; the other order swaps the arguments and
/// flips the normal (points, separations and ids are unchanged).
/// Shared geometry (hulls) is read from `store`.
pub fn collide(
    store: &GeometryStore,
    a: &Geometry,
    xf_a: &Transform,
    b: &Geometry,
    xf_b: &Transform,
    speculative: f32,
) -> Manifold {
    collide_cached(store, a, xf_a, b, xf_b, speculative, &mut SatCache::default())
}

/// [`collide`] with the pair's separating-axis cache (`SatCache`), kept by the caller
/// between calls for the same ordered pair (the world keeps one per contact).
pub fn collide_cached(
    store: &GeometryStore,
    a: &Geometry,
    xf_a: &Transform,
    b: &Geometry,
    xf_b: &Transform,
    speculative: f32,
    cache: &mut SatCache,
) -> Manifold {
    if a.kind() > b.kind() {
        let mut m = collide_ordered(store, b, xf_b, a, xf_a, speculative, cache);
        m.normal = -m.normal;
        return m;
    }
    collide_ordered(store, a, xf_a, b, xf_b, speculative, cache)
}

/// `collide` for shapes that use no shared geometry (unit tests of the primitive pairs).
#[cfg(test)]
pub(crate) fn collide_primitives(
    a: &Geometry,
    xf_a: &Transform,
    b: &Geometry,
    xf_b: &Transform,
    speculative: f32,
) -> Manifold {
    collide(&GeometryStore::new(1), a, xf_a, b, xf_b, speculative)
}

/// `collide` for `kind(a) <= kind(b)`.
fn collide_ordered(
    store: &GeometryStore,
    a: &Geometry,
    xf_a: &Transform,
    b: &Geometry,
    xf_b: &Transform,
    speculative: f32,
    cache: &mut SatCache,
) -> Manifold {
    use hull::Poly;
    use Geometry as G;
    if b.is_triangles() {
        // A convex shape against a mesh or heightfield: the deepest of its manifolds (the
        // contact stage takes them all, through `collide_triangles`).
        let mut out = MeshManifolds::EMPTY;
        collide_triangles(store, a, xf_a, b, xf_b, speculative, &mut out);
        return mesh::deepest(&out);
    }
    let hull_poly = |g: &Geometry, xf: &Transform| match *g {
        G::Hull { hull, local, scale } => Poly::hull(store.hull_at(hull.index), &local, scale, xf),
        _ => unreachable!("only called for hulls"),
    };
    match (*a, *b) {
        (G::Sphere { center, radius }, G::Hull { .. }) => {
            hull::sphere_hull(xf_a.apply(center), radius, &hull_poly(b, xf_b), speculative)
        }
        (G::Capsule { a: pa, b: qa, radius }, G::Hull { .. }) => {
            hull::capsule_hull(xf_a.apply(pa), xf_a.apply(qa), radius, &hull_poly(b, xf_b), speculative)
        }
        (
            G::Box {
                center,
                rotation,
                half_extents,
            },
            G::Hull { .. },
        ) => hull_hull::hull_hull(
            &Poly::boxed(center, rotation, half_extents, xf_a),
            &hull_poly(b, xf_b),
            speculative,
            cache,
        ),
        (G::Hull { .. }, G::Hull { .. }) => {
            hull_hull::hull_hull(&hull_poly(a, xf_a), &hull_poly(b, xf_b), speculative, cache)
        }
        (G::Hull { .. }, G::Plane { normal, offset }) => {
            let plane = WorldPlane::new(normal, offset, xf_b);
            hull::hull_plane(&hull_poly(a, xf_a), plane.n, plane.d, speculative)
        }
        (G::Sphere { center: ca, radius: ra }, G::Sphere { center: cb, radius: rb }) => {
            sphere::sphere_sphere(xf_a.apply(ca), ra, xf_b.apply(cb), rb, speculative)
        }
        (
            G::Sphere { center, radius },
            G::Capsule {
                a: pb,
                b: qb,
                radius: rb,
            },
        ) => sphere::sphere_capsule(
            xf_a.apply(center),
            radius,
            xf_b.apply(pb),
            xf_b.apply(qb),
            rb,
            speculative,
        ),
        (
            G::Sphere { center, radius },
            G::Box {
                center: cb,
                rotation,
                half_extents,
            },
        ) => {
            let bx = WorldBox::new(cb, rotation, half_extents, xf_b);
            sphere::sphere_box(xf_a.apply(center), radius, &bx, speculative)
        }
        (G::Sphere { center, radius }, G::Plane { normal, offset }) => {
            let plane = WorldPlane::new(normal, offset, xf_b);
            sphere::sphere_plane(xf_a.apply(center), radius, &plane, speculative)
        }
        (
            G::Capsule {
                a: pa,
                b: qa,
                radius: ra,
            },
            G::Capsule {
                a: pb,
                b: qb,
                radius: rb,
            },
        ) => capsule::capsule_capsule(
            xf_a.apply(pa),
            xf_a.apply(qa),
            ra,
            xf_b.apply(pb),
            xf_b.apply(qb),
            rb,
            speculative,
        ),
        (
            G::Capsule { a: pa, b: qa, radius },
            G::Box {
                center,
                rotation,
                half_extents,
            },
        ) => {
            let bx = WorldBox::new(center, rotation, half_extents, xf_b);
            capsule::capsule_box(xf_a.apply(pa), xf_a.apply(qa), radius, &bx, speculative)
        }
        (G::Capsule { a: pa, b: qa, radius }, G::Plane { normal, offset }) => {
            let plane = WorldPlane::new(normal, offset, xf_b);
            capsule::capsule_plane(xf_a.apply(pa), xf_a.apply(qa), radius, &plane, speculative)
        }
        (
            G::Box {
                center: ca,
                rotation: qa,
                half_extents: ha,
            },
            G::Box {
                center: cb,
                rotation: qb,
                half_extents: hb,
            },
        ) => {
            let ba = WorldBox::new(ca, qa, ha, xf_a);
            let bb = WorldBox::new(cb, qb, hb, xf_b);
            box_box::box_box(&ba, &bb, speculative)
        }
        (
            G::Box {
                center,
                rotation,
                half_extents,
            },
            G::Plane { normal, offset },
        ) => {
            let bx = WorldBox::new(center, rotation, half_extents, xf_a);
            let plane = WorldPlane::new(normal, offset, xf_b);
            plane::box_plane(&bx, &plane, speculative)
        }
        // Plane–plane, and (unreachable) out-of-order pairs.
        _ => Manifold::EMPTY,
    }
}

#[cfg(test)]
mod fuzz_tests;
#[cfg(test)]
mod hull_tests;
