//! Values stored only when they differ from what the reader can rebuild from what it has
//! read already: a flag per value (column `#given` under the value's), and the value (its
//! column) only when the flag is set. The writer compares bit for bit, so a value is
//! either rebuilt exactly (the same function of the same stored bits, in the same order)
//! or stored: no rebuild has to be proven identical, only computed the same way on both
//! sides.
//!
//! Rebuilt this way: a body's world centre of mass (`xf.apply(local_center)`) and the
//! transform last reported in a move event (its transform); a shape's tight box (its
//! geometry's box at its body's transform) and fat box (the tight box grown by the margin);
//! the dynamic tree's boxes and parent links (`DynamicTree::put_snapshot`).

use super::{bad, ReadResult, Reader, Snap, Writer};
use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::shape::Shape;
use crate::dynamics::body::Body;
use crate::math::{Quat, Transform, Vec3};
use crate::pool::Pool;

/// Equality of every bit.
pub(crate) trait SameBits {
    fn same_bits(&self, o: &Self) -> bool;
}

impl SameBits for Vec3 {
    fn same_bits(&self, o: &Self) -> bool {
        self.to_array().map(f32::to_bits) == o.to_array().map(f32::to_bits)
    }
}

impl SameBits for Quat {
    fn same_bits(&self, o: &Self) -> bool {
        self.to_array().map(f32::to_bits) == o.to_array().map(f32::to_bits)
    }
}

impl SameBits for Transform {
    fn same_bits(&self, o: &Self) -> bool {
        self.p.same_bits(&o.p) && self.q.same_bits(&o.q)
    }
}

impl SameBits for Aabb {
    fn same_bits(&self, o: &Self) -> bool {
        self.min.same_bits(&o.min) && self.max.same_bits(&o.max)
    }
}

/// Writes `v` under `name`: only a flag when it equals `predicted` bit for bit.
fn put<T: Snap + SameBits>(w: &mut Writer, name: &'static str, v: &T, predicted: &T) {
    w.within(name, |w| {
        let given = !v.same_bits(predicted);
        w.within("#given", |w| given.put(w));
        if given {
            v.put(w);
        }
    });
}

/// Reads what `put` wrote: the stored value, or `predicted`.
fn get<T: Snap>(r: &mut Reader, name: &'static str, predicted: impl FnOnce() -> ReadResult<T>) -> ReadResult<T> {
    r.within(name, |r| {
        if r.within("#given", bool::get)? {
            T::get(r)
        } else {
            predicted()
        }
    })
}

/// The bodies' rebuilt fields, in slot order, after the body pool.
pub(super) fn put_bodies(w: &mut Writer, bodies: &Pool<Body>) {
    for (_, b) in bodies.iter() {
        put(w, "center", &b.center, &b.xf.apply(b.local_center));
        put(w, "reported_xf", &b.reported_xf, &b.xf);
    }
}

pub(super) fn get_bodies(r: &mut Reader, bodies: &mut Pool<Body>) -> ReadResult<()> {
    for b in bodies.values_mut() {
        b.center = get(r, "center", || Ok(b.xf.apply(b.local_center)))?;
        b.reported_xf = get(r, "reported_xf", || Ok(b.xf))?;
    }
    Ok(())
}

/// The shapes' rebuilt boxes, in slot order, after the shape pool.
pub(super) fn put_shapes(w: &mut Writer, shapes: &Pool<Shape>, bodies: &Pool<Body>, store: &GeometryStore) {
    for (_, s) in shapes.iter() {
        let tight = s.geometry.aabb(store, &bodies.at(s.body).xf);
        put(w, "aabb", &s.aabb, &tight);
        put(w, "fat_aabb", &s.fat_aabb, &s.aabb.expanded(crate::world::AABB_MARGIN));
    }
}

pub(super) fn get_shapes(
    r: &mut Reader,
    shapes: &mut Pool<Shape>,
    bodies: &Pool<Body>,
    store: &GeometryStore,
) -> ReadResult<()> {
    for s in shapes.values_mut() {
        s.aabb = get(r, "aabb", || match bodies.handle_at(s.body) {
            Some(_) if store.check(&s.geometry).is_ok() => Ok(s.geometry.aabb(store, &bodies.at(s.body).xf)),
            _ => bad("snapshot corrupted: a shape names a body or geometry that is not there"),
        })?;
        let fat = s.aabb.expanded(crate::world::AABB_MARGIN);
        s.fat_aabb = get(r, "fat_aabb", || Ok(fat))?;
    }
    Ok(())
}
