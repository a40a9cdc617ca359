//! Plain C value types and their conversion to and from the core's glam types.

use crate::math::{Quat, Transform, Vec3};
use crate::pool::Handle;

/// A 3D vector of `float` (metres, m/s, N, ... by context).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HearthVec3 {
    /// X component.
    pub x: f32,
    /// Y component (up, with the default gravity).
    pub y: f32,
    /// Z component.
    pub z: f32,
}

/// A rotation quaternion `{x, y, z, w}`; need not be normalised, must not be zero.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HearthQuat {
    /// Vector part, X (`axis.x * sin(angle / 2)` for a unit quaternion).
    pub x: f32,
    /// Vector part, Y.
    pub y: f32,
    /// Vector part, Z.
    pub z: f32,
    /// Scalar part (`cos(angle / 2)`); the identity is `{0, 0, 0, 1}`.
    pub w: f32,
}

/// A rigid transform: rotation, then translation.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HearthTransform {
    /// Translation (m).
    pub position: HearthVec3,
    /// Rotation, applied before the translation.
    pub rotation: HearthQuat,
}

impl From<HearthVec3> for Vec3 {
    fn from(v: HearthVec3) -> Vec3 {
        Vec3::new(v.x, v.y, v.z)
    }
}
impl From<Vec3> for HearthVec3 {
    fn from(v: Vec3) -> HearthVec3 {
        HearthVec3 { x: v.x, y: v.y, z: v.z }
    }
}
impl From<HearthQuat> for Quat {
    fn from(q: HearthQuat) -> Quat {
        Quat::from_xyzw(q.x, q.y, q.z, q.w)
    }
}
impl From<Quat> for HearthQuat {
    fn from(q: Quat) -> HearthQuat {
        HearthQuat {
            x: q.x,
            y: q.y,
            z: q.z,
            w: q.w,
        }
    }
}
impl From<HearthTransform> for Transform {
    fn from(t: HearthTransform) -> Transform {
        Transform::new(t.position.into(), t.rotation.into())
    }
}
impl From<Transform> for HearthTransform {
    fn from(t: Transform) -> HearthTransform {
        HearthTransform {
            position: t.p.into(),
            rotation: t.q.into(),
        }
    }
}

/// Id of a body inside its world. All-zero is the null id. Ids of destroyed bodies and of
/// other worlds are rejected with `HEARTH_ERROR_INVALID_ID`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthBodyId {
    /// Slot of the body.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

/// Id of a shape inside its world. All-zero is the null id.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthShapeId {
    /// Slot of the shape.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

macro_rules! id_conversions {
    ($($name:ident),*) => {$(
        impl From<$name> for Handle {
            fn from(id: $name) -> Handle {
                Handle { index: id.index, generation: id.generation }
            }
        }
        impl From<Handle> for $name {
            fn from(h: Handle) -> $name {
                $name { index: h.index, generation: h.generation }
            }
        }
    )*};
}
/// Id of a convex hull (shared geometry) inside its world. All-zero is the null id. Ids of
/// destroyed hulls and of other worlds are rejected with `HEARTH_ERROR_INVALID_ID`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthHullId {
    /// Slot of the hull.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

/// Id of a triangle mesh (shared geometry) inside its world. All-zero is the null id.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthMeshId {
    /// Slot of the mesh.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

/// Id of a heightfield (shared geometry) inside its world. All-zero is the null id.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthHeightfieldId {
    /// Slot of the heightfield.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

id_conversions!(
    HearthBodyId,
    HearthShapeId,
    HearthHullId,
    HearthMeshId,
    HearthHeightfieldId
);

/// Sphere: centre in the body frame (m, each coordinate within ±1e5) and radius (m,
/// 0.001..=1e4).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSphere {
    /// Centre in the body frame (m).
    pub center: HearthVec3,
    /// Radius (m, > 0).
    pub radius: f32,
}

/// Box: centre (m, within ±1e5) and rotation in the body frame, half extents (m, each
/// 0.001..=1e4).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBox {
    /// Centre in the body frame (m).
    pub center: HearthVec3,
    /// Rotation in the body frame.
    pub rotation: HearthQuat,
    /// Half the edge lengths along the box's own axes (m, each > 0).
    pub half_extents: HearthVec3,
}

/// Capsule: segment end points `a`, `b` in the body frame (m, within ±1e5, at most 1e4 apart)
/// and radius (m, 0.001..=1e4).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthCapsule {
    /// One end of the segment, in the body frame (m).
    pub a: HearthVec3,
    /// The other end (m); may equal `a` (a sphere).
    pub b: HearthVec3,
    /// Radius around the segment (m, > 0).
    pub radius: f32,
}

/// Plane (static bodies only), in the body frame: points `p` with
/// `dot(normal, p) <= offset` are inside. The normal need not be unit length (it is
/// normalised together with the offset) but must not be zero; the normalised offset lies
/// within ±1e5 m.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthPlane {
    /// Outward normal in the body frame (not zero).
    pub normal: HearthVec3,
    /// Distance of the surface from the body origin along the normal (m).
    pub offset: f32,
}
