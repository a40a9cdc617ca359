//! Axis-aligned bounding boxes.

use crate::math::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    /// An inverted box: the identity for `union`.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::MAX),
        max: Vec3::splat(-f32::MAX),
    };

    #[inline]
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    #[inline]
    pub fn from_center_extents(c: Vec3, e: Vec3) -> Self {
        Aabb { min: c - e, max: c + e }
    }

    #[inline]
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    #[inline]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && self.max.x >= o.min.x
            && self.min.y <= o.max.y
            && self.max.y >= o.min.y
            && self.min.z <= o.max.z
            && self.max.z >= o.min.z
    }

    /// True when `o` lies entirely inside `self`.
    #[inline]
    pub fn contains(&self, o: &Aabb) -> bool {
        self.min.x <= o.min.x
            && self.min.y <= o.min.y
            && self.min.z <= o.min.z
            && o.max.x <= self.max.x
            && o.max.y <= self.max.y
            && o.max.z <= self.max.z
    }

    #[inline]
    pub fn expanded(&self, margin: f32) -> Aabb {
        Aabb {
            min: self.min - Vec3::splat(margin),
            max: self.max + Vec3::splat(margin),
        }
    }

    /// Grows the box along a displacement (a swept box).
    #[inline]
    pub fn swept(&self, d: Vec3) -> Aabb {
        Aabb {
            min: self.min + d.min(Vec3::ZERO),
            max: self.max + d.max(Vec3::ZERO),
        }
    }

    /// Half the surface area: the cost metric of the tree.
    #[inline]
    pub fn perimeter(&self) -> f32 {
        let d = self.max - self.min;
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    #[inline]
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    #[inline]
    pub fn extents(&self) -> Vec3 {
        0.5 * (self.max - self.min)
    }
}

/// The empty box (a snapshot's placeholder for boxes rebuilt after decoding).
impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}
