//! Shared geometry: objects built once and instanced by many shapes.
//!
//! A convex hull (and, later, a triangle mesh or a heightfield) is expensive to build and
//! may be large, so it is not part of a shape. It lives in the world's `GeometryStore`,
//! in a generational [`Pool`] (ids like every other world object), and a shape refers to it
//! by handle with its own placement: `Geometry::Hull { hull, local, scale }`. Any number of
//! shapes, on any bodies, may use one hull.
//!
//! * **Lifetime.** Each stored object counts its users. `World::create_shape` checks that
//!   the handle is live and counts the new user; destroying the shape (or its body)
//!   releases it. Destroying a hull that still has users is refused with
//!   `InvalidArgument` naming the number of users, so a shape never refers to a freed slot.
//! * **Hot path.** Because a used slot cannot be freed, the narrow phase, bounds, mass and
//!   rounding code index the pool by slot (`hull_at(handle.index)`) with no generation check
//!   and no reference counting: `collide`, `Geometry::aabb`, `Geometry::mass_properties`,
//!   `Geometry::rounding_radius` and `Geometry::extent_from` take `&GeometryStore`.
//! * **Determinism.** Slots are handed out in call order, like every pool.
//!
//! Triangle meshes (`collision/mesh/`) and heightfields (`collision/heightfield.rs`) are
//! stored the same way, with `Geometry::Mesh` / `Geometry::Heightfield` placing them with a
//! per-axis scale.
//!
//! ## Adding a kind
//!
//! 1. Put the data type in its own module under `collision/` (as `collision/hull/`), built
//!    and validated by a constructor that returns `Result`.
//! 2. Add a `Pool<Stored<YourType>>` field here with `add_*`, `remove_*` (refusing while
//!    used, through [`Stored::release_check`]), `*_at(slot)` and a checked getter; extend
//!    [`GeometryStore::retain`], [`GeometryStore::release`] and [`GeometryStore::check`]
//!    for the new `Geometry` variant.
//! 3. Add `Geometry::YourKind { handle, local: Transform, scale: Vec3 }` (per-axis scale
//!    for meshes and heightfields) and a `ShapeKind`; fill in the `Geometry` methods
//!    (`aabb`, `volume`, `mass_properties` — zero for static-only kinds, `rounding_radius`,
//!    `extent_from`, `validated`) and the pairs in `narrow_phase::collide_ordered`.
//! 4. World operations (`create_*`/`destroy_*` in `world.rs`), C exports in a new
//!    `capi/` file, and the recording (`src/record`) when it learns the kind.

use crate::collision::heightfield::Heightfield;
use crate::collision::hull::ConvexHull;
use crate::collision::mesh::TriangleMesh;
use crate::collision::shape::Geometry;
use crate::error::{invalid, Error, Result};
use crate::pool::{Handle, Pool};

/// Handle of a convex hull in a world.
pub type ConvexHullHandle = Handle;
/// Handle of a triangle mesh in a world.
pub type MeshHandle = Handle;
/// Handle of a heightfield in a world.
pub type HeightfieldHandle = Handle;

/// A stored object and the number of shapes using it.
pub struct Stored<T> {
    pub value: T,
    pub users: u32,
}

impl<T> Stored<T> {
    /// `Ok` when nothing uses the object, else the refusal naming the users.
    pub fn release_check(&self, what: &str) -> Result<()> {
        if self.users > 0 {
            return Err(invalid(format!(
                "{what} is used by {} shape{}; destroy them first",
                self.users,
                if self.users == 1 { "" } else { "s" }
            )));
        }
        Ok(())
    }
}

/// The world's shared geometry (see the module doc).
pub struct GeometryStore {
    hulls: Pool<Stored<ConvexHull>>,
    meshes: Pool<Stored<TriangleMesh>>,
    heightfields: Pool<Stored<Heightfield>>,
}

/// The checked getters, users count and refusing removal of one kind.
macro_rules! stored_kind {
    ($add:ident, $remove:ident, $get:ident, $users:ident, $count:ident, $at:ident, $field:ident, $ty:ty, $what:literal) => {
        pub fn $add(&mut self, value: $ty) -> Handle {
            self.$field.insert(Stored { value, users: 0 })
        }

        /// Frees the object; refused while shapes use it.
        pub fn $remove(&mut self, h: Handle) -> Result<()> {
            self.$field
                .get(h)
                .ok_or(Error::InvalidId($what))?
                .release_check($what)?;
            self.$field.remove(h);
            Ok(())
        }

        pub fn $get(&self, h: Handle) -> Result<&$ty> {
            self.$field
                .get(h)
                .map(|s| &s.value)
                .ok_or(Error::InvalidId($what))
        }

        /// Number of shapes using the object.
        pub fn $users(&self, h: Handle) -> Result<u32> {
            self.$field.get(h).map(|s| s.users).ok_or(Error::InvalidId($what))
        }

        pub fn $count(&self) -> usize {
            self.$field.len()
        }

        /// The object by slot, for the hot path: the slot is live while a shape refers to it.
        #[inline]
        pub fn $at(&self, slot: u32) -> &$ty {
            &self.$field.at(slot).value
        }
    };
}

impl GeometryStore {
    pub fn new(tag: u32) -> GeometryStore {
        GeometryStore {
            hulls: Pool::new(tag),
            meshes: Pool::new(tag),
            heightfields: Pool::new(tag),
        }
    }

    stored_kind!(
        add_mesh,
        remove_mesh,
        mesh,
        mesh_users,
        mesh_count,
        mesh_at,
        meshes,
        TriangleMesh,
        "triangle mesh"
    );
    stored_kind!(
        add_heightfield,
        remove_heightfield,
        heightfield,
        heightfield_users,
        heightfield_count,
        heightfield_at,
        heightfields,
        Heightfield,
        "heightfield"
    );

    pub fn add_hull(&mut self, hull: ConvexHull) -> ConvexHullHandle {
        self.hulls.insert(Stored { value: hull, users: 0 })
    }

    /// Frees a hull; refused while shapes use it.
    pub fn remove_hull(&mut self, h: ConvexHullHandle) -> Result<()> {
        self.hulls
            .get(h)
            .ok_or(Error::InvalidId("convex hull"))?
            .release_check("convex hull")?;
        self.hulls.remove(h);
        Ok(())
    }

    pub fn hull(&self, h: ConvexHullHandle) -> Result<&ConvexHull> {
        self.hulls
            .get(h)
            .map(|s| &s.value)
            .ok_or(Error::InvalidId("convex hull"))
    }

    /// Number of shapes using a hull.
    pub fn hull_users(&self, h: ConvexHullHandle) -> Result<u32> {
        self.hulls
            .get(h)
            .map(|s| s.users)
            .ok_or(Error::InvalidId("convex hull"))
    }

    pub fn hull_count(&self) -> usize {
        self.hulls.len()
    }

    /// A hull by slot, for the hot path: the slot is live while a shape refers to it.
    #[inline]
    pub fn hull_at(&self, slot: u32) -> &ConvexHull {
        &self.hulls.at(slot).value
    }

    /// Checks that the shared object a geometry refers to is live.
    pub fn check(&self, g: &Geometry) -> Result<()> {
        match g {
            Geometry::Hull { hull, .. } => self.hull(*hull).map(|_| ()),
            Geometry::Mesh { mesh, .. } => self.mesh(*mesh).map(|_| ()),
            Geometry::Heightfield { heightfield, .. } => self.heightfield(*heightfield).map(|_| ()),
            _ => Ok(()),
        }
    }

    /// The user count of the geometry's shared object, if it has one.
    fn users_mut(&mut self, g: &Geometry) -> Option<&mut u32> {
        match g {
            Geometry::Hull { hull, .. } => Some(&mut self.hulls.at_mut(hull.index).users),
            Geometry::Mesh { mesh, .. } => Some(&mut self.meshes.at_mut(mesh.index).users),
            Geometry::Heightfield { heightfield, .. } => Some(&mut self.heightfields.at_mut(heightfield.index).users),
            _ => None,
        }
    }

    /// Counts a new user of the geometry's shared object (after `check`).
    pub fn retain(&mut self, g: &Geometry) {
        if let Some(u) = self.users_mut(g) {
            *u += 1;
        }
    }

    /// Forgets a user of the geometry's shared object.
    pub fn release(&mut self, g: &Geometry) {
        if let Some(u) = self.users_mut(g) {
            *u = u.saturating_sub(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::collision::hull::builder::HullSettings;
    use crate::dynamics::body::BodyDef;
    use crate::math::{Quat, Transform, Vec3};
    use crate::{Error, Geometry, ShapeDef, World, WorldSettings};

    fn cube_points(h: f32) -> Vec<Vec3> {
        (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 != 0 { h } else { -h },
                    if i & 2 != 0 { h } else { -h },
                    if i & 4 != 0 { h } else { -h },
                )
            })
            .collect()
    }

    #[test]
    fn hull_is_shared_and_refused_while_used() {
        let mut w = World::new(WorldSettings::default()).unwrap();
        let h = w
            .create_convex_hull(&cube_points(0.5), &HullSettings::default())
            .unwrap();
        let dynamic = BodyDef {
            body_type: crate::BodyType::Dynamic,
            ..Default::default()
        };
        let body = w.create_body(&dynamic).unwrap();
        let other = w.create_body(&dynamic).unwrap();
        let g = |p: Vec3, s: f32| Geometry::Hull {
            hull: h,
            local: Transform::new(p, Quat::IDENTITY),
            scale: s,
        };
        let s1 = w.create_shape(body, &ShapeDef::default(), &g(Vec3::ZERO, 1.0)).unwrap();
        let _s2 = w.create_shape(body, &ShapeDef::default(), &g(Vec3::X, 2.0)).unwrap();
        let _s3 = w
            .create_shape(other, &ShapeDef::default(), &g(Vec3::ZERO, 1.0))
            .unwrap();
        assert_eq!(w.geometry.hull_users(h).unwrap(), 3);
        let err = w.destroy_convex_hull(h).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidArgument(m) if m.contains("used by 3 shapes")),
            "{err}"
        );
        // Mass: a unit cube and a cube of side 2 at density 1000.
        let mass = w.body(body).unwrap().mass;
        assert!((mass - 9000.0).abs() < 1e-2, "{mass}");
        w.destroy_shape(s1).unwrap();
        w.destroy_body(other).unwrap();
        assert_eq!(w.geometry.hull_users(h).unwrap(), 1);
        w.destroy_body(body).unwrap();
        w.destroy_convex_hull(h).unwrap();
        assert!(matches!(w.destroy_convex_hull(h), Err(Error::InvalidId(_))));
        // A stale hull cannot be used by a new shape, and nothing is created.
        let b = w.create_body(&BodyDef::default()).unwrap();
        assert!(w.create_shape(b, &ShapeDef::default(), &g(Vec3::ZERO, 1.0)).is_err());
        assert!(w.body(b).unwrap().shapes.is_empty());
    }

    #[test]
    fn bad_scale_and_placement_are_refused() {
        let mut w = World::new(WorldSettings::default()).unwrap();
        let h = w
            .create_convex_hull(&cube_points(0.5), &HullSettings::default())
            .unwrap();
        let body = w.create_body(&BodyDef::default()).unwrap();
        for (p, q, s) in [
            (Vec3::ZERO, Quat::IDENTITY, 0.0),
            (Vec3::ZERO, Quat::IDENTITY, -1.0),
            (Vec3::ZERO, Quat::IDENTITY, f32::NAN),
            (Vec3::ZERO, Quat::IDENTITY, 1.0e-4),
            (Vec3::NAN, Quat::IDENTITY, 1.0),
            (Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0), 1.0),
        ] {
            let g = Geometry::Hull {
                hull: h,
                local: Transform::new(p, q),
                scale: s,
            };
            assert!(w.create_shape(body, &ShapeDef::default(), &g).is_err(), "{p} {q} {s}");
        }
        assert_eq!(w.geometry.hull_users(h).unwrap(), 0);
    }
}

impl<T: crate::snapshot::Snap> crate::snapshot::Snap for Stored<T> {
    fn put(&self, w: &mut crate::snapshot::Writer) {
        let Stored { value, users } = self;
        value.put(w);
        users.put(w);
    }
    fn get(r: &mut crate::snapshot::Reader) -> crate::snapshot::ReadResult<Self> {
        Ok(Stored {
            value: crate::snapshot::Snap::get(r)?,
            users: crate::snapshot::Snap::get(r)?,
        })
    }
}
crate::snap_struct!(GeometryStore {
    hulls,
    meshes,
    heightfields,
});
