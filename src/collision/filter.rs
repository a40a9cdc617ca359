//! Collision filtering by category bits, mask bits and group index (Box2D v3's rules).
//!
//! Two shapes with the same non-zero `group_index` always collide when it is positive and
//! never when it is negative. Otherwise they collide when each one's category is in the
//! other's mask. Queries test a [`QueryFilter`] against a shape's filter the same way
//! (without groups).

/// Per-shape collision filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Filter {
    /// The categories this shape belongs to (usually one bit).
    pub category_bits: u64,
    /// The categories this shape collides with.
    pub mask_bits: u64,
    /// Shapes sharing a positive group always collide, a negative group never; 0 is no
    /// group (the bits decide).
    pub group_index: i32,
}

impl Filter {
    /// Category 1, every mask bit, no group: collides with everything by default.
    pub const DEFAULT: Filter = Filter {
        category_bits: 1,
        mask_bits: u64::MAX,
        group_index: 0,
    };
}

impl Default for Filter {
    fn default() -> Self {
        Filter::DEFAULT
    }
}

/// Whether shapes filtered by `a` and `b` may collide.
#[inline]
pub fn should_collide(a: &Filter, b: &Filter) -> bool {
    if a.group_index == b.group_index && a.group_index != 0 {
        return a.group_index > 0;
    }
    (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0
}

/// The filter of a query: which shape categories it reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct QueryFilter {
    /// The categories of the query (tested against each shape's mask).
    pub category_bits: u64,
    /// The shape categories the query reports.
    pub mask_bits: u64,
}

impl QueryFilter {
    /// Category 1, every mask bit: sees every shape whose mask includes category 1 (every
    /// shape with the default filter).
    pub const DEFAULT: QueryFilter = QueryFilter {
        category_bits: 1,
        mask_bits: u64::MAX,
    };

    /// Every shape, whatever its filter.
    pub const ALL: QueryFilter = QueryFilter {
        category_bits: u64::MAX,
        mask_bits: u64::MAX,
    };

    /// Whether a shape filtered by `shape` is seen by this query.
    #[inline]
    pub fn accepts(&self, shape: &Filter) -> bool {
        (self.category_bits & shape.mask_bits) != 0 && (shape.category_bits & self.mask_bits) != 0
    }
}

impl Default for QueryFilter {
    fn default() -> Self {
        QueryFilter::DEFAULT
    }
}

impl crate::world::World {
    /// The filter of a shape.
    pub fn shape_filter(&self, h: crate::dynamics::body::ShapeHandle) -> crate::error::Result<Filter> {
        Ok(self.shape(h)?.def.filter)
    }

    /// Changes a shape's filter. Pairs are re-evaluated at once for contacts that exist
    /// (those the new filter forbids are removed, and both of their bodies woken, so a body
    /// resting on a shape it no longer collides with falls) and at the next step for new
    /// ones: the shape's proxy goes into the move buffer (for a plane, the proxies of the
    /// dynamic shapes whose fat boxes reach it), and its body is woken.
    pub fn set_shape_filter(
        &mut self,
        h: crate::dynamics::body::ShapeHandle,
        filter: Filter,
    ) -> crate::error::Result<()> {
        use crate::collision::broad_phase::{aabb_touches_plane, world_plane};
        let s = self.shape(h)?;
        let bi = s.body;
        if s.def.filter == filter {
            return Ok(());
        }
        self.shapes.at_mut(h.index).def.filter = filter;
        let mut k = 0;
        while k < self.bodies.at(bi).contacts.len() {
            let c = self.bodies.at(bi).contacts[k];
            let ct = self.contacts.at(c);
            let other = if ct.shape_a == h.index {
                ct.shape_b
            } else if ct.shape_b == h.index {
                ct.shape_a
            } else {
                k += 1;
                continue;
            };
            if should_collide(&filter, &self.shapes.at(other).def.filter) {
                k += 1;
                continue;
            }
            let (a, b) = (ct.body_a, ct.body_b);
            self.wake_body(a);
            self.wake_body(b);
            // destroy_contact swap-removes `c` from this list: look at index k again.
            self.destroy_contact(c);
        }
        let shape = self.shapes.at(h.index);
        if shape.proxy != crate::dynamics::body::NONE {
            self.push_moved(h.index);
        } else {
            let (n, d) = world_plane(&shape.geometry, &self.bodies.at(bi).xf);
            let reach: Vec<u32> = self
                .shapes
                .iter()
                .filter(|(_, t)| {
                    t.proxy != crate::dynamics::body::NONE
                        && self.bodies.at(t.body).is_dynamic()
                        && aabb_touches_plane(&t.fat_aabb, n, d)
                })
                .map(|(t, _)| t.index)
                .collect();
            for t in reach {
                self.push_moved(t);
                let tb = self.shapes.at(t).body;
                self.wake_body(tb);
            }
        }
        self.wake_body(bi);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(category_bits: u64, mask_bits: u64, group_index: i32) -> Filter {
        Filter {
            category_bits,
            mask_bits,
            group_index,
        }
    }

    #[test]
    fn truth_table() {
        // (a, b, expected)
        let all = u64::MAX;
        let rows = [
            (f(1, all, 0), f(1, all, 0), true),
            (f(1, 2, 0), f(2, 1, 0), true),
            (f(1, 2, 0), f(2, 2, 0), false),       // b does not accept a's category
            (f(1, 4, 0), f(2, 1, 0), false),       // a does not accept b's category
            (f(1, 0, 0), f(1, all, 0), false),     // an empty mask collides with nothing
            (f(0, all, 0), f(1, all, 0), false),   // no category: nothing accepts it
            (f(1, 0, 3), f(2, 0, 3), true),        // same positive group beats the bits
            (f(1, all, -3), f(1, all, -3), false), // same negative group never
            (f(1, all, -3), f(1, all, -4), true),  // different groups: the bits decide
            (f(1, 2, 3), f(1, 2, 4), false),       // different groups: the bits decide
            (f(1, all, 0), f(1, all, -1), true),   // group 0 is no group
            (f(1 << 63, 1 << 63, 0), f(1 << 63, 1 << 63, 0), true), // the 64th bit counts
        ];
        for (i, (a, b, expect)) in rows.iter().enumerate() {
            assert_eq!(should_collide(a, b), *expect, "row {i}");
            assert_eq!(should_collide(b, a), *expect, "row {i} swapped");
        }
    }

    #[test]
    fn symmetric_over_random_filters() {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for _ in 0..10_000 {
            let a = f(next() & 0xff, next() & 0xff, (next() % 5) as i32 - 2);
            let b = f(next() & 0xff, next() & 0xff, (next() % 5) as i32 - 2);
            let expect = if a.group_index == b.group_index && a.group_index != 0 {
                a.group_index > 0
            } else {
                a.category_bits & b.mask_bits != 0 && b.category_bits & a.mask_bits != 0
            };
            assert_eq!(should_collide(&a, &b), expect);
            assert_eq!(should_collide(&a, &b), should_collide(&b, &a));
        }
    }

    #[test]
    fn query_filter() {
        let shape = f(4, 1, 0);
        assert!(QueryFilter::DEFAULT.accepts(&shape));
        assert!(QueryFilter::ALL.accepts(&shape));
        assert!(!QueryFilter {
            category_bits: 2,
            mask_bits: u64::MAX
        }
        .accepts(&shape));
        assert!(!QueryFilter {
            category_bits: 1,
            mask_bits: 3
        }
        .accepts(&shape));
        assert!(QueryFilter {
            category_bits: 1,
            mask_bits: 4
        }
        .accepts(&shape));
    }
}
