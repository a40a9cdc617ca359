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

/// Writes the flags of `given` into the current column's `#given`.
fn put_flags(w: &mut Writer, given: &[bool]) {
    w.within("#given", |w| w.values(given.iter().map(|&g| [g as u8])));
}

/// Reads `n` flags from the current column's `#given`.
fn get_flags(r: &mut Reader, n: usize) -> ReadResult<Vec<bool>> {
    r.within("#given", |r| bool::get_all(n, r))
}

/// The bodies' rebuilt fields, in slot order, after the body pool: each field's flags,
/// then its stored values, in one pass each (the columns are made in the order value by
/// value writing would make them: `center`, its flags, `reported_xf`, its flags, then the
/// transform's `p` and `q` at the first one stored).
pub(super) fn put_bodies(w: &mut Writer, bodies: &Pool<Body>) {
    if bodies.is_empty() {
        return;
    }
    let given: Vec<bool> = bodies
        .iter()
        .map(|(_, b)| !b.center.same_bits(&b.xf.apply(b.local_center)))
        .collect();
    w.within("center", |w| {
        put_flags(w, &given);
        let stored: Vec<&Vec3> = (bodies.iter().zip(&given).filter(|(_, &g)| g))
            .map(|((_, b), _)| &b.center)
            .collect();
        Vec3::put_all(stored.iter().copied(), w);
    });
    let given: Vec<bool> = bodies.iter().map(|(_, b)| !b.reported_xf.same_bits(&b.xf)).collect();
    w.within("reported_xf", |w| {
        put_flags(w, &given);
        if given.contains(&true) {
            let stored: Vec<&Transform> = (bodies.iter().zip(&given).filter(|(_, &g)| g))
                .map(|((_, b), _)| &b.reported_xf)
                .collect();
            Transform::put_all(stored.iter().copied(), w);
        }
    });
}

pub(super) fn get_bodies(r: &mut Reader, bodies: &mut Pool<Body>) -> ReadResult<()> {
    let n = bodies.len();
    if n == 0 {
        return Ok(());
    }
    r.within("center", |r| {
        let given = get_flags(r, n)?;
        let mut stored = Vec3::get_all(given.iter().filter(|&&g| g).count(), r)?.into_iter();
        for (b, &g) in bodies.values_mut().zip(&given) {
            b.center = match g {
                true => stored.next().expect("one per flag"),
                false => b.xf.apply(b.local_center),
            };
        }
        Ok(())
    })?;
    r.within("reported_xf", |r| {
        let given = get_flags(r, n)?;
        let k = given.iter().filter(|&&g| g).count();
        let mut stored = match k {
            0 => Vec::new(),
            _ => Transform::get_all(k, r)?,
        }
        .into_iter();
        for (b, &g) in bodies.values_mut().zip(&given) {
            b.reported_xf = match g {
                true => stored.next().expect("one per flag"),
                false => b.xf,
            };
        }
        Ok(())
    })
}

/// The shapes' rebuilt boxes, in slot order, after the shape pool: each box's flags, then
/// its stored values, in one pass each. The columns are made in the order value by value
/// writing would make them: `aabb` and its flags, `fat_aabb` and its flags, and each box's
/// `min` and `max` at the first one stored (after the flags of the other box, unless that
/// is the first shape's; before the other box's `min` and `max` when it comes first in
/// slot order, or in the same shape: `aabb` before `fat_aabb`).
pub(super) fn put_shapes(w: &mut Writer, shapes: &Pool<Shape>, bodies: &Pool<Body>, store: &GeometryStore) {
    if shapes.is_empty() {
        return;
    }
    let tight: Vec<bool> = shapes
        .iter()
        .map(|(_, s)| !s.aabb.same_bits(&s.geometry.aabb(store, &bodies.at(s.body).xf)))
        .collect();
    let fat: Vec<bool> = shapes
        .iter()
        .map(|(_, s)| !s.fat_aabb.same_bits(&s.aabb.expanded(crate::world::AABB_MARGIN)))
        .collect();
    let put_tight = |w: &mut Writer| {
        w.within("aabb", |w| {
            let stored: Vec<&Aabb> = (shapes.iter().zip(&tight).filter(|(_, &g)| g))
                .map(|((_, s), _)| &s.aabb)
                .collect();
            Aabb::put_all(stored.iter().copied(), w)
        })
    };
    let put_fat = |w: &mut Writer| {
        w.within("fat_aabb", |w| {
            let stored: Vec<&Aabb> = (shapes.iter().zip(&fat).filter(|(_, &g)| g))
                .map(|((_, s), _)| &s.fat_aabb)
                .collect();
            Aabb::put_all(stored.iter().copied(), w)
        })
    };
    let (first_tight, first_fat) = (first(&tight), first(&fat));
    w.within("aabb", |w| put_flags(w, &tight));
    if first_tight == Some(0) {
        put_tight(w);
    }
    w.within("fat_aabb", |w| put_flags(w, &fat));
    if first_fat == Some(0) {
        put_fat(w);
    }
    match later(first_tight, first_fat) {
        (Some(t), Some(f)) if f < t => {
            put_fat(w);
            put_tight(w);
        }
        (t, f) => {
            if t.is_some() {
                put_tight(w);
            }
            if f.is_some() {
                put_fat(w);
            }
        }
    }
}

/// The index of the first set flag.
fn first(given: &[bool]) -> Option<usize> {
    given.iter().position(|&g| g)
}

/// The first stored indices of the two boxes, without those of the first shape (written
/// right after their flags).
fn later(t: Option<usize>, f: Option<usize>) -> (Option<usize>, Option<usize>) {
    (t.filter(|&i| i > 0), f.filter(|&i| i > 0))
}

pub(super) fn get_shapes(
    r: &mut Reader,
    shapes: &mut Pool<Shape>,
    bodies: &Pool<Body>,
    store: &GeometryStore,
) -> ReadResult<()> {
    let n = shapes.len();
    if n == 0 {
        return Ok(());
    }
    let boxes = |r: &mut Reader, name: &'static str, given: &[bool]| {
        let k = given.iter().filter(|&&g| g).count();
        r.within(name, |r| Aabb::get_all(k, r))
    };
    let tight = r.within("aabb", |r| get_flags(r, n))?;
    let mut tight_boxes = Vec::new();
    if first(&tight) == Some(0) {
        tight_boxes = boxes(r, "aabb", &tight)?;
    }
    let fat = r.within("fat_aabb", |r| get_flags(r, n))?;
    let mut fat_boxes = Vec::new();
    if first(&fat) == Some(0) {
        fat_boxes = boxes(r, "fat_aabb", &fat)?;
    }
    match later(first(&tight), first(&fat)) {
        (Some(t), Some(f)) if f < t => {
            fat_boxes = boxes(r, "fat_aabb", &fat)?;
            tight_boxes = boxes(r, "aabb", &tight)?;
        }
        (t, f) => {
            if t.is_some() {
                tight_boxes = boxes(r, "aabb", &tight)?;
            }
            if f.is_some() {
                fat_boxes = boxes(r, "fat_aabb", &fat)?;
            }
        }
    }
    let (mut tight_boxes, mut fat_boxes) = (tight_boxes.into_iter(), fat_boxes.into_iter());
    for ((s, &t), &f) in shapes.values_mut().zip(&tight).zip(&fat) {
        s.aabb = match t {
            true => tight_boxes.next().expect("one per flag"),
            false => match bodies.handle_at(s.body) {
                Some(_) if store.check(&s.geometry).is_ok() => s.geometry.aabb(store, &bodies.at(s.body).xf),
                _ => return bad("snapshot corrupted: a shape names a body or geometry that is not there"),
            },
        };
        s.fat_aabb = match f {
            true => fat_boxes.next().expect("one per flag"),
            false => s.aabb.expanded(crate::world::AABB_MARGIN),
        };
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::test_rnd::Rnd;
    use crate::snapshot::SnapBlank;

    /// The writer before the bulk one: value by value, each with its flag (the reference
    /// for the bytes and the order the columns are made in).
    fn put_one<T: Snap + SameBits>(w: &mut Writer, name: &'static str, v: &T, predicted: &T) {
        w.within(name, |w| {
            let given = !v.same_bits(predicted);
            w.within("#given", |w| given.put(w));
            if given {
                v.put(w);
            }
        });
    }

    fn payload(f: impl Fn(&mut Writer)) -> Vec<u8> {
        let mut w = Writer::new();
        f(&mut w);
        let mut out = Vec::new();
        w.finish(&mut out);
        out
    }

    /// Seeded randomized: bodies and shapes whose centres, reported transforms and boxes
    /// are rebuilt or stored, none, all or at random (so the first stored tight box comes
    /// before, with or after the first stored fat box, in the first shape or later): the
    /// bulk writer writes the bytes value-by-value writing does (the same columns, made in
    /// the same order), and the reader gives back every value bit for bit.
    #[test]
    fn bulk_rebuilt_values_match_value_by_value() {
        let store = GeometryStore::new(1);
        let mut seed = Rnd(0x2545_F491_4F6C_DD1D);
        for round in 0..400 {
            let state = seed.next_u64();
            let (bodies, shapes) = world(&mut Rnd(state), round, &store);
            let one = payload(|w| {
                for (_, b) in bodies.iter() {
                    put_one(w, "center", &b.center, &b.xf.apply(b.local_center));
                    put_one(w, "reported_xf", &b.reported_xf, &b.xf);
                }
                for (_, s) in shapes.iter() {
                    let tight = s.geometry.aabb(&store, &bodies.at(s.body).xf);
                    put_one(w, "aabb", &s.aabb, &tight);
                    put_one(w, "fat_aabb", &s.fat_aabb, &s.aabb.expanded(crate::world::AABB_MARGIN));
                }
            });
            let bulk = payload(|w| {
                put_bodies(w, &bodies);
                put_shapes(w, &shapes, &bodies, &store);
            });
            assert!(one == bulk, "round {round}: the bulk writer's bytes differ");
            let mut plain = Vec::new();
            let spans = crate::snapshot::columns::unpack(&bulk, &mut plain).unwrap();
            let mut r = Reader::new(&plain, &spans, 1);
            let (mut got_bodies, mut got_shapes) = world(&mut Rnd(state), round, &store);
            for b in got_bodies.values_mut() {
                b.center = Vec3::NAN;
                b.reported_xf.p = Vec3::NAN;
            }
            for s in got_shapes.values_mut() {
                s.aabb.min = Vec3::NAN;
                s.fat_aabb.max = Vec3::NAN;
            }
            get_bodies(&mut r, &mut got_bodies).unwrap();
            get_shapes(&mut r, &mut got_shapes, &got_bodies, &store).unwrap();
            r.finish().unwrap();
            for ((_, a), (_, b)) in bodies.iter().zip(got_bodies.iter()) {
                assert!(a.center.same_bits(&b.center) && a.reported_xf.same_bits(&b.reported_xf));
            }
            for ((_, a), (_, b)) in shapes.iter().zip(got_shapes.iter()) {
                assert!(
                    a.aabb.same_bits(&b.aabb) && a.fat_aabb.same_bits(&b.fat_aabb),
                    "round {round}"
                );
            }
        }
    }

    /// Bodies and shapes from `rng`, with values stored (not rebuilt) as round `round` asks.
    fn world(rng: &mut Rnd, round: usize, store: &GeometryStore) -> (Pool<Body>, Pool<Shape>) {
        {
            let rng = &mut *rng;
            let n_bodies = 1 + (rng.next_u64() % 5) as usize;
            let n_shapes = (rng.next_u64() % 9) as usize;
            // How often a value is stored: never, always, or now and then.
            let every = [0u64, 1, 2, 3, 5][round % 5];
            let stored = |rng: &mut Rnd| every != 0 && rng.next_u64() % every == 0;
            let mut bodies: Pool<Body> = Pool::new(1);
            for _ in 0..n_bodies {
                let mut b = Body::blank();
                b.xf = Transform {
                    p: rng.point(Vec3::splat(20.0)),
                    q: rng.quat(),
                };
                b.local_center = rng.point(Vec3::ONE);
                b.center = match stored(rng) {
                    true => rng.point(Vec3::splat(20.0)),
                    false => b.xf.apply(b.local_center),
                };
                b.reported_xf = match stored(rng) {
                    true => Transform {
                        p: rng.point(Vec3::splat(20.0)),
                        q: rng.quat(),
                    },
                    false => b.xf,
                };
                bodies.insert(b);
            }
            let mut shapes: Pool<Shape> = Pool::new(1);
            for _ in 0..n_shapes {
                let mut s = Shape::blank();
                s.body = (rng.next_u64() % n_bodies as u64) as u32;
                s.geometry = crate::collision::shape::Geometry::Sphere {
                    center: rng.point(Vec3::ONE),
                    radius: 0.1 + rng.f(),
                };
                let tight = s.geometry.aabb(store, &bodies.at(s.body).xf);
                s.aabb = match stored(rng) {
                    true => Aabb {
                        min: rng.point(Vec3::ONE),
                        max: rng.point(Vec3::ONE),
                    },
                    false => tight,
                };
                s.fat_aabb = match stored(rng) {
                    true => Aabb {
                        min: rng.point(Vec3::ONE),
                        max: rng.point(Vec3::ONE),
                    },
                    false => s.aabb.expanded(crate::world::AABB_MARGIN),
                };
                shapes.insert(s);
            }
            (bodies, shapes)
        }
    }
}
