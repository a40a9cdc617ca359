//! Shape geometry in the local frame of its body, its bounds and its mass.

use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::{ConvexHullHandle, GeometryStore, HeightfieldHandle, MeshHandle};
use crate::math::{Mat3, Quat, Transform, Vec3};

/// Collision geometry, placed in the local frame of the body that owns it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Geometry {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// An oriented box: `rotation` is relative to the body.
    Box {
        center: Vec3,
        rotation: Quat,
        half_extents: Vec3,
    },
    /// Segment `a`–`b` swept by `radius`.
    Capsule {
        a: Vec3,
        b: Vec3,
        radius: f32,
    },
    /// The half-space `dot(normal, p) <= offset` (static bodies only).
    Plane {
        normal: Vec3,
        offset: f32,
    },
    /// A convex hull from the world's `GeometryStore`, placed by `local` (relative to the
    /// body) and scaled uniformly by `scale` about the hull's origin.
    Hull {
        hull: ConvexHullHandle,
        local: Transform,
        scale: f32,
    },
    /// A triangle mesh from the world's `GeometryStore` (static and kinematic bodies only),
    /// scaled per axis by `scale` (each > 0) in its own frame, then placed by `local`.
    Mesh {
        mesh: MeshHandle,
        local: Transform,
        scale: Vec3,
    },
    /// A heightfield from the world's `GeometryStore` (static and kinematic bodies only):
    /// `scale.x` and `scale.z` are the sample spacing, `scale.y` multiplies the heights.
    Heightfield {
        heightfield: HeightfieldHandle,
        local: Transform,
        scale: Vec3,
    },
}

/// Shape kinds in dispatch order; narrowphase pairs are ordered so `kind(a) <= kind(b)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ShapeKind {
    Sphere = 0,
    Capsule = 1,
    Box = 2,
    Hull = 3,
    Mesh = 4,
    Heightfield = 5,
    Plane = 6,
}

impl Geometry {
    pub fn kind(&self) -> ShapeKind {
        match self {
            Geometry::Sphere { .. } => ShapeKind::Sphere,
            Geometry::Capsule { .. } => ShapeKind::Capsule,
            Geometry::Box { .. } => ShapeKind::Box,
            Geometry::Hull { .. } => ShapeKind::Hull,
            Geometry::Mesh { .. } => ShapeKind::Mesh,
            Geometry::Heightfield { .. } => ShapeKind::Heightfield,
            Geometry::Plane { .. } => ShapeKind::Plane,
        }
    }

    /// Triangle meshes and heightfields: static level geometry made of triangles, touching
    /// a convex shape along several manifolds.
    pub fn is_triangles(&self) -> bool {
        matches!(self, Geometry::Mesh { .. } | Geometry::Heightfield { .. })
    }

    /// Bounds of a mesh or heightfield in its own unscaled frame, with its placement.
    fn triangles_frame(&self, store: &GeometryStore) -> Option<(Aabb, Transform, Vec3)> {
        match *self {
            Geometry::Mesh { mesh, local, scale } => Some((store.mesh_at(mesh.index).bounds(), local, scale)),
            Geometry::Heightfield {
                heightfield,
                local,
                scale,
            } => Some((store.heightfield_at(heightfield.index).bounds(), local, scale)),
            _ => None,
        }
    }

    /// A box around shared geometry (hull, mesh, heightfield) in the body's frame: centre,
    /// rotation, half extents. `None` for the primitive shapes, which describe themselves.
    pub fn local_box(&self, store: &GeometryStore) -> Option<(Vec3, Quat, Vec3)> {
        if let Geometry::Hull { hull, local, scale } = *self {
            let h = store.hull_at(hull.index);
            let (lo, hi) = h.local_bounds();
            let half = 0.5 * (hi - lo) * scale + Vec3::splat(h.radius() * scale);
            return Some((local.apply(0.5 * (lo + hi) * scale), local.q, half));
        }
        let (b, local, scale) = self.triangles_frame(store)?;
        Some((local.apply(b.center() * scale), local.q, b.extents() * scale))
    }

    /// True for geometry without finite extent (planes).
    pub fn is_unbounded(&self) -> bool {
        matches!(self, Geometry::Plane { .. })
    }

    /// World-space bounds under the body transform `xf`. Planes get an enormous box.
    pub fn aabb(&self, store: &GeometryStore, xf: &Transform) -> Aabb {
        match *self {
            Geometry::Sphere { center, radius } => Aabb::from_center_extents(xf.apply(center), Vec3::splat(radius)),
            Geometry::Box {
                center,
                rotation,
                half_extents,
            } => {
                let m = Mat3::from_quat(xf.q * rotation);
                let e = Vec3::new(
                    m.row(0).abs().dot(half_extents),
                    m.row(1).abs().dot(half_extents),
                    m.row(2).abs().dot(half_extents),
                );
                Aabb::from_center_extents(xf.apply(center), e)
            }
            Geometry::Capsule { a, b, radius } => {
                let wa = xf.apply(a);
                let wb = xf.apply(b);
                Aabb::new(wa.min(wb), wa.max(wb)).expanded(radius)
            }
            Geometry::Plane { .. } => Aabb::new(Vec3::splat(-1.0e18), Vec3::splat(1.0e18)),
            Geometry::Hull { hull, local, scale } => {
                let h = store.hull_at(hull.index);
                let m = Mat3::from_quat(xf.q * local.q) * scale;
                // The bounds of `m * v` over the vertices, four at a time (the same values).
                let (lo, hi) = h.transformed_bounds(&m);
                let p = xf.apply(local.p);
                Aabb::new(lo + p, hi + p).expanded(h.radius() * scale)
            }
            Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
                let (b, local, scale) = self.triangles_frame(store).expect("a mesh or heightfield");
                let m = Mat3::from_quat(xf.q * local.q);
                let (c, e) = (b.center() * scale, b.extents() * scale);
                let e = Vec3::new(m.row(0).abs().dot(e), m.row(1).abs().dot(e), m.row(2).abs().dot(e));
                Aabb::from_center_extents(xf.apply(local.apply(c)), e)
            }
        }
    }

    /// Volume in m³ (0 for a plane).
    pub fn volume(&self, store: &GeometryStore) -> f32 {
        match *self {
            Geometry::Sphere { radius, .. } => 4.0 / 3.0 * std::f32::consts::PI * radius.powi(3),
            Geometry::Box { half_extents: h, .. } => 8.0 * h.x * h.y * h.z,
            Geometry::Capsule { a, b, radius } => {
                let l = (b - a).length();
                std::f32::consts::PI * radius * radius * (l + 4.0 / 3.0 * radius)
            }
            Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => 0.0,
            Geometry::Hull { hull, scale, .. } => store.hull_at(hull.index).volume() * scale * scale * scale,
        }
    }

    /// Mass properties at `density` (kg/m³), expressed in the body frame.
    pub fn mass_properties(&self, store: &GeometryStore, density: f32) -> MassProperties {
        use std::f32::consts::PI;
        match *self {
            Geometry::Sphere { center, radius } => {
                let m = density * self.volume(store);
                let i = 0.4 * m * radius * radius;
                MassProperties {
                    mass: m,
                    center,
                    inertia: Mat3::from_diagonal(Vec3::splat(i)),
                }
            }
            Geometry::Box {
                center,
                rotation,
                half_extents: h,
            } => {
                let m = density * self.volume(store);
                let s = h * h;
                let d = Vec3::new(s.y + s.z, s.x + s.z, s.x + s.y) * (m / 3.0);
                let r = Mat3::from_quat(rotation);
                let inertia = r * Mat3::from_diagonal(d) * r.transpose();
                MassProperties {
                    mass: m,
                    center,
                    inertia,
                }
            }
            Geometry::Capsule { a, b, radius: r } => {
                // Cylinder plus two hemispheres, about the capsule's own axis frame, then rotated.
                let axis = b - a;
                let l = axis.length();
                let center = 0.5 * (a + b);
                let mc = density * PI * r * r * l;
                let ms = density * 4.0 / 3.0 * PI * r * r * r;
                let r2 = r * r;
                let i_axial = mc * r2 * 0.5 + ms * 0.4 * r2;
                // Hemisphere centroid is 3r/8 from its flat face; parallel-axis about the capsule centre.
                let d = 0.5 * l + 3.0 / 8.0 * r;
                let i_hemi_own = (0.4 - (3.0f32 / 8.0).powi(2)) * r2 * 0.5 * ms; // per hemisphere about its centroid
                let i_perp = mc * (r2 / 4.0 + l * l / 12.0) + 2.0 * (i_hemi_own + 0.5 * ms * d * d);
                let local = Mat3::from_diagonal(Vec3::new(i_perp, i_axial, i_perp));
                let rot = if l > 1e-6 {
                    Mat3::from_quat(Quat::from_rotation_arc(Vec3::Y, axis / l))
                } else {
                    Mat3::IDENTITY
                };
                MassProperties {
                    mass: mc + ms,
                    center,
                    inertia: rot * local * rot.transpose(),
                }
            }
            Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => MassProperties::ZERO,
            Geometry::Hull { hull, local, scale } => {
                let mp = store.hull_at(hull.index).mass_properties(density);
                let s3 = scale * scale * scale;
                let r = Mat3::from_quat(local.q);
                MassProperties {
                    mass: mp.mass * s3,
                    center: local.apply(mp.center * scale),
                    inertia: r * (mp.inertia * (s3 * scale * scale)) * r.transpose(),
                }
            }
        }
    }
}

/// Mass, centre of mass and inertia about the centre of mass, in the body frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    pub mass: f32,
    pub center: Vec3,
    pub inertia: Mat3,
}

impl MassProperties {
    pub const ZERO: MassProperties = MassProperties {
        mass: 0.0,
        center: Vec3::ZERO,
        inertia: Mat3::ZERO,
    };

    /// Combines parts by the parallel-axis theorem (compound bodies).
    pub fn combine(parts: impl Iterator<Item = MassProperties> + Clone) -> MassProperties {
        let mut mass = 0.0;
        let mut moment = Vec3::ZERO;
        for p in parts.clone() {
            mass += p.mass;
            moment += p.mass * p.center;
        }
        if mass <= 0.0 {
            return MassProperties::ZERO;
        }
        let center = moment / mass;
        let mut inertia = Mat3::ZERO;
        for p in parts {
            let d = p.center - center;
            let shift = Mat3::from_diagonal(Vec3::splat(d.dot(d))) - outer(d, d);
            inertia += p.inertia + shift * p.mass;
        }
        MassProperties { mass, center, inertia }
    }
}

#[inline]
fn outer(a: Vec3, b: Vec3) -> Mat3 {
    Mat3::from_cols(a * b.x, a * b.y, a * b.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn store() -> GeometryStore {
        GeometryStore::new(1)
    }

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn box_inertia_matches_formula() {
        let g = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 2.0, 3.0),
        };
        let mp = g.mass_properties(&store(), 2.0);
        assert!(close(mp.mass, 96.0, 1e-6));
        // I_x = m/12 (h² + d²) with full sizes 4 and 6
        assert!(close(mp.inertia.x_axis.x, 96.0 / 12.0 * (16.0 + 36.0), 1e-5));
        assert!(close(mp.inertia.y_axis.y, 96.0 / 12.0 * (4.0 + 36.0), 1e-5));
        assert!(close(mp.inertia.z_axis.z, 96.0 / 12.0 * (4.0 + 16.0), 1e-5));
    }

    #[test]
    fn compound_of_two_boxes_equals_one_long_box() {
        let h = Vec3::new(0.5, 0.5, 0.5);
        let a = Geometry::Box {
            center: Vec3::new(-0.5, 0.0, 0.0),
            rotation: Quat::IDENTITY,
            half_extents: h,
        };
        let b = Geometry::Box {
            center: Vec3::new(0.5, 0.0, 0.0),
            rotation: Quat::IDENTITY,
            half_extents: h,
        };
        let whole = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 0.5, 0.5),
        };
        let c =
            MassProperties::combine([a.mass_properties(&store(), 3.0), b.mass_properties(&store(), 3.0)].into_iter());
        let w = whole.mass_properties(&store(), 3.0);
        assert!(close(c.mass, w.mass, 1e-6));
        assert!(c.center.length() < 1e-6);
        for i in 0..3 {
            assert!(close(c.inertia.col(i)[i], w.inertia.col(i)[i], 1e-5));
        }
    }

    #[test]
    fn rotated_box_inertia_is_rotated() {
        let h = Vec3::new(1.0, 0.25, 0.5);
        let q = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let g = Geometry::Box {
            center: Vec3::ZERO,
            rotation: q,
            half_extents: h,
        };
        let s = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(0.25, 1.0, 0.5),
        };
        let a = g.mass_properties(&store(), 1.0).inertia;
        let b = s.mass_properties(&store(), 1.0).inertia;
        for i in 0..3 {
            assert!((a.col(i) - b.col(i)).length() < 1e-4);
        }
    }

    #[test]
    fn capsule_limits() {
        // A zero-length capsule is a sphere.
        let c = Geometry::Capsule {
            a: Vec3::ZERO,
            b: Vec3::ZERO,
            radius: 0.5,
        };
        let s = Geometry::Sphere {
            center: Vec3::ZERO,
            radius: 0.5,
        };
        let (mc, ms) = (c.mass_properties(&store(), 1.0), s.mass_properties(&store(), 1.0));
        assert!(close(mc.mass, ms.mass, 1e-5));
        assert!(close(mc.inertia.x_axis.x, ms.inertia.x_axis.x, 1e-4));
        assert!(close(mc.inertia.y_axis.y, ms.inertia.y_axis.y, 1e-4));
    }

    #[test]
    fn rotated_box_aabb() {
        let g = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 1.0, 1.0),
        };
        let xf = Transform::new(
            Vec3::new(0.0, 5.0, 0.0),
            Quat::from_rotation_y(std::f32::consts::FRAC_PI_4),
        );
        let bb = g.aabb(&store(), &xf);
        let r = 2.0f32.sqrt();
        assert!((bb.max.x - r).abs() < 1e-5 && (bb.max.y - 6.0).abs() < 1e-5);
    }
}

/// Material and density of a shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeDef {
    /// kg/m³.
    pub density: f32,
    /// Coulomb coefficient while the surfaces stick.
    pub static_friction: f32,
    /// Coulomb coefficient while they slide.
    pub dynamic_friction: f32,
    pub restitution: f32,
    pub user_data: u64,
    /// Rolling resistance (Box2D v3's `rollingResistance`), in `0..=ROLLING_MAX`: a torque
    /// against the relative rolling of two touching shapes (their relative angular velocity
    /// about axes in the contact plane) of up to `rolling_resistance × radius × normal force`,
    /// where `radius` is the larger rounding radius of the pair (sphere or capsule radius; 0
    /// for boxes and planes, which do not roll). The pair uses the larger value. A solid ball
    /// rolling on a level floor decelerates at `5/7 · rolling_resistance · g` while friction
    /// can keep it rolling (`rolling_resistance` up to 1.4 × friction; above, it slides and
    /// slows at `friction · g`), and rests on slopes up to `atan(rolling_resistance)` where
    /// friction holds it too.
    pub rolling_resistance: f32,
    /// Torsional (spin) friction, in `0..=TORSIONAL_MAX`: a torque against the relative spin
    /// of two touching shapes about the contact normal of up to
    /// `torsional_friction × radius × normal force` (`radius` as above), on top of the
    /// friction of a contact patch's own extent. The pair uses the larger value. A solid ball
    /// spinning in place on a level floor slows at `5/2 · torsional_friction · g / radius`
    /// rad/s².
    pub torsional_friction: f32,
    /// Which shapes this one collides with and which queries see it
    /// ([`crate::collision::filter`]). Default: category 1, every mask bit, no group.
    pub filter: crate::collision::filter::Filter,
    /// A sensor (`events.rs`): reports overlaps with non-sensor shapes as sensor events and
    /// never makes a solver contact, never pushes, adds no mass and is ignored by particles and
    /// soft bodies. Planes cannot be sensors.
    pub is_sensor: bool,
    /// Contact begin and end events for this shape's contacts (both shapes must enable them).
    /// Default on.
    pub enable_contact_events: bool,
    /// Contact hit events for this shape's contacts (either shape enables them). Default off.
    pub enable_hit_events: bool,
    /// Sensor events: on a sensor, it reports; on another shape, sensors see it (both must
    /// enable them). Default on.
    pub enable_sensor_events: bool,
}

/// Largest accepted `ShapeDef::rolling_resistance`: a lever as long as the radius.
pub const ROLLING_MAX: f32 = 1.0;
/// Largest accepted `ShapeDef::torsional_friction`: a contact patch as wide as the radius.
pub const TORSIONAL_MAX: f32 = 1.0;

impl Default for ShapeDef {
    fn default() -> Self {
        ShapeDef {
            density: 1000.0,
            static_friction: 0.6,
            dynamic_friction: 0.6,
            restitution: 0.0,
            user_data: 0,
            rolling_resistance: ShapeDef::DEFAULT_ROLLING_RESISTANCE,
            torsional_friction: ShapeDef::DEFAULT_TORSIONAL_FRICTION,
            filter: crate::collision::filter::Filter::DEFAULT,
            is_sensor: false,
            enable_contact_events: true,
            enable_hit_events: false,
            enable_sensor_events: true,
        }
    }
}

impl ShapeDef {
    /// Default rolling resistance: a ball stops like one rolling on short grass or carpet.
    pub const DEFAULT_ROLLING_RESISTANCE: f32 = 0.05;
    /// Default torsional friction.
    pub const DEFAULT_TORSIONAL_FRICTION: f32 = 0.05;

    /// Range-checks the material (README "Supported ranges").
    pub fn validate(&self) -> crate::error::Result<()> {
        use crate::error::{check_density, check_non_negative, check_restitution, invalid};
        check_density("density", self.density)?;
        check_non_negative("static_friction", self.static_friction)?;
        check_non_negative("dynamic_friction", self.dynamic_friction)?;
        check_restitution("restitution", self.restitution)?;
        for (name, x, max) in [
            ("rolling_resistance", self.rolling_resistance, ROLLING_MAX),
            ("torsional_friction", self.torsional_friction, TORSIONAL_MAX),
        ] {
            check_non_negative(name, x)?;
            if x > max {
                return Err(invalid(format!("{name} must be in 0..={max}, got {x}")));
            }
        }
        Ok(())
    }
}

impl Geometry {
    /// Range-checks the geometry (README "Supported ranges": sizes within [1 mm, 10 km],
    /// placements within ±100 km) and returns it normalised (unit plane normal and box
    /// rotation).
    pub fn validated(&self) -> crate::error::Result<Geometry> {
        use crate::error::{check_distance, check_length, check_lengths, check_position, check_quat, invalid};
        Ok(match *self {
            Geometry::Sphere { center, radius } => {
                check_position("sphere center", center)?;
                check_length("sphere radius", radius)?;
                *self
            }
            Geometry::Box {
                center,
                rotation,
                half_extents,
            } => {
                check_position("box center", center)?;
                let rotation = check_quat("box rotation", rotation)?;
                check_lengths("box half_extents", half_extents)?;
                Geometry::Box {
                    center,
                    rotation,
                    half_extents,
                }
            }
            Geometry::Capsule { a, b, radius } => {
                check_position("capsule a", a)?;
                check_position("capsule b", b)?;
                check_length("capsule radius", radius)?;
                check_distance("capsule segment length |b - a|", (b - a).length())?;
                *self
            }
            Geometry::Plane { normal, offset } => {
                let l = normal.length();
                if !normal.is_finite() || !(1.0e-6..=f32::MAX).contains(&l) {
                    return Err(invalid(format!(
                        "plane normal must be finite and non-zero (length at least 1e-6), got {normal}"
                    )));
                }
                if !offset.is_finite() || (offset / l).abs() > crate::error::MAX_COORDINATE {
                    return Err(invalid(format!(
                        "plane offset must be finite and, divided by the normal's length, within ±{} m, got {offset}",
                        crate::error::MAX_COORDINATE
                    )));
                }
                Geometry::Plane {
                    normal: normal / l,
                    offset: offset / l,
                }
            }
            Geometry::Hull { hull, local, scale } => {
                check_position("hull position", local.p)?;
                let q = check_quat("hull rotation", local.q)?;
                crate::error::check_positive("hull scale", scale)?;
                Geometry::Hull {
                    hull,
                    local: Transform::new(local.p, q),
                    scale,
                }
            }
            Geometry::Mesh { mesh, local, scale } => {
                let (local, scale) = triangles_placement("mesh", local, scale)?;
                Geometry::Mesh { mesh, local, scale }
            }
            Geometry::Heightfield {
                heightfield,
                local,
                scale,
            } => {
                let (local, scale) = triangles_placement("heightfield", local, scale)?;
                Geometry::Heightfield {
                    heightfield,
                    local,
                    scale,
                }
            }
        })
    }

    /// Radius by which the shape rounds its core (a point for a sphere, a segment for a
    /// capsule); 0 for boxes and planes. A contact point on a rounded surface does not turn
    /// with the body: rolling moves the contact over the surface.
    pub fn rounding_radius(&self, store: &GeometryStore) -> f32 {
        match *self {
            Geometry::Sphere { radius, .. } | Geometry::Capsule { radius, .. } => radius,
            Geometry::Box { .. } | Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => 0.0,
            Geometry::Hull { hull, scale, .. } => store.hull_at(hull.index).radius() * scale,
        }
    }

    /// The shape's smallest dimension (m): a sphere's or capsule's radius, a box's smallest
    /// half extent, a hull's inner radius (from its vertex centroid to the nearest face, plus
    /// its convex radius); planes, meshes and heightfields have none (`f32::MAX`). Contacts
    /// scale their length tolerances (allowed overlap, manifold reuse) down to it, so
    /// millimetre bodies rest like metre ones.
    pub fn feature_size(&self, store: &GeometryStore) -> f32 {
        match *self {
            Geometry::Sphere { radius, .. } | Geometry::Capsule { radius, .. } => radius,
            Geometry::Box { half_extents, .. } => half_extents.min_element(),
            Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => f32::MAX,
            Geometry::Hull { hull, scale, .. } => {
                let h = store.hull_at(hull.index);
                let c = h.vertices().iter().copied().sum::<Vec3>() / h.vertices().len().max(1) as f32;
                let inner = h.planes().iter().map(|p| -p.distance(c)).fold(f32::MAX, f32::min);
                (inner.max(0.0) + h.radius()) * scale
            }
        }
    }

    /// Radius of a sphere about the body's centre of mass that bounds the shape (planes: 0).
    pub fn extent_from(&self, store: &GeometryStore, local_center: Vec3) -> f32 {
        match *self {
            Geometry::Sphere { center, radius } => (center - local_center).length() + radius,
            Geometry::Box {
                center, half_extents, ..
            } => (center - local_center).length() + half_extents.length(),
            Geometry::Capsule { a, b, radius } => (a - local_center).length().max((b - local_center).length()) + radius,
            Geometry::Plane { .. } => 0.0,
            Geometry::Hull { hull, local, scale } => {
                let h = store.hull_at(hull.index);
                let c = local.apply(h.mass_properties(1.0).center * scale);
                (c - local_center).length() + scale * (h.bound_radius() + h.radius())
            }
            Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
                let (b, local, scale) = self.triangles_frame(store).expect("a mesh or heightfield");
                let c = local.apply(b.center() * scale);
                (c - local_center).length() + (b.extents() * scale).length()
            }
        }
    }
}

/// Smallest per-axis scale of a mesh or heightfield shape.
pub const MIN_TRIANGLES_SCALE: f32 = 1.0e-4;

/// Checks the placement of a mesh or heightfield shape; returns it with a unit rotation.
fn triangles_placement(what: &str, local: Transform, scale: Vec3) -> crate::error::Result<(Transform, Vec3)> {
    use crate::error::{check_position, check_quat, check_vec, invalid};
    check_position(&format!("{what} position"), local.p)?;
    let q = check_quat(&format!("{what} rotation"), local.q)?;
    check_vec(&format!("{what} scale"), scale)?;
    if scale.min_element() < MIN_TRIANGLES_SCALE || scale.max_element() > crate::error::MAX_LENGTH {
        return Err(invalid(format!(
            "{what} scale must be within [{MIN_TRIANGLES_SCALE}, {}] on every axis, got {scale}",
            crate::error::MAX_LENGTH
        )));
    }
    Ok((Transform::new(local.p, q), scale))
}

/// A shape attached to a body.
pub struct Shape {
    pub body: u32,
    pub geometry: Geometry,
    pub def: ShapeDef,
    /// Tree proxy, or `crate::dynamics::body::NONE` for planes.
    pub proxy: u32,
    /// Tight world bounds at the end of the last step (or at creation / teleport).
    pub aabb: Aabb,
    pub fat_aabb: Aabb,
    /// Set while the shape sits in the broad phase's move buffer.
    pub in_move_buffer: bool,
    /// Radius about the body's centre of mass that bounds the shape (`Geometry::extent_from`),
    /// kept current when the body's mass changes.
    pub extent: f32,
}
