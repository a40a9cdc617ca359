//! Cross-references of a decoded snapshot, checked before it replaces a world's state.
//!
//! The checksum catches accidents; a buffer made on purpose (or by a buggy writer) can carry
//! a valid checksum over inconsistent content. Every index the engine later follows without
//! a check (slot indices of bodies, shapes, contacts, joints and particles, awake-list
//! positions, tree nodes, soft-body vertices) is checked here against what it names, so
//! such a buffer is refused instead of loading and failing in a later step. Handles (ids
//! with a reuse counter) are looked up with a check wherever the engine uses them and need
//! none here.

use super::{bad, ReadResult};
use crate::collision::broad_phase::BroadPhase;
use crate::collision::contact::Contact;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::narrow_phase::MAX_MANIFOLD_POINTS;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::{Body, NONE};
use crate::dynamics::joints::Joints;
use crate::generators::Generator;
use crate::particles::Particles;
use crate::pool::Pool;
use crate::soft::SoftBodies;

/// The decoded state a restore is about to swap in.
pub(super) struct Decoded<'a> {
    pub geometry: &'a GeometryStore,
    pub bodies: &'a Pool<Body>,
    pub shapes: &'a Pool<Shape>,
    pub contacts: &'a Pool<Contact>,
    pub awake_contacts: &'a [u32],
    pub broad: &'a BroadPhase,
    pub awake_bodies: &'a [u32],
    pub islands: &'a Pool<Vec<u32>>,
    pub generators: &'a Pool<Generator>,
    pub particles: &'a Particles,
    pub joints: &'a Joints,
    pub soft_bodies: &'a SoftBodies,
}

fn live<T>(pool: &Pool<T>, slot: u32) -> bool {
    pool.handle_at(slot).is_some()
}

fn corrupt<T>(what: impl std::fmt::Display) -> ReadResult<T> {
    bad(format!("snapshot corrupted: {what}"))
}

/// Refuses a decoded snapshot whose indices name nothing or disagree with what they name.
pub(super) fn check(d: &Decoded) -> ReadResult<()> {
    check_bodies(d)?;
    check_shapes(d)?;
    check_contacts(d)?;
    check_joints(d)?;
    for (h, g) in d.generators.iter() {
        if !g.bodies.consistent() || !g.particles.consistent() {
            return corrupt(format!("generator {} has inconsistent attachment lists", h.index));
        }
    }
    check_particles(d.particles)?;
    check_soft_bodies(d)
}

fn check_bodies(d: &Decoded) -> ReadResult<()> {
    for (h, b) in d.bodies.iter() {
        let i = h.index;
        for &s in &b.shapes {
            match d.shapes.get(s) {
                Some(shape) if shape.body == i => {}
                _ => return corrupt(format!("body {i} lists shape {} that is not its own", s.index)),
            }
        }
        for &c in &b.contacts {
            if !live(d.contacts, c) || {
                let k = d.contacts.at(c);
                k.body_a != i && k.body_b != i
            } {
                return corrupt(format!("body {i} lists contact {c} that is not its own"));
            }
        }
        if b.awake_index != NONE && d.awake_bodies.get(b.awake_index as usize) != Some(&i) {
            return corrupt(format!("body {i}'s awake-list position {} is wrong", b.awake_index));
        }
    }
    for (k, &i) in d.awake_bodies.iter().enumerate() {
        if !live(d.bodies, i) || d.bodies.at(i).awake_index as usize != k {
            return corrupt(format!("awake body {k} names body {i} that is not there"));
        }
    }
    for (h, island) in d.islands.iter() {
        if let Some(&i) = island.iter().find(|&&i| !live(d.bodies, i)) {
            return corrupt(format!("island {} names body {i} that is not there", h.index));
        }
        // The world links an island through its bodies: each is in it once, and says so.
        let mut sorted = island.clone();
        sorted.sort_unstable();
        sorted.dedup();
        if island.is_empty()
            || sorted.len() != island.len()
            || island.iter().any(|&i| d.bodies.at(i).sleep_island.index != h.index)
        {
            return corrupt(format!("island {} does not list its bodies once each", h.index));
        }
    }
    Ok(())
}

fn check_shapes(d: &Decoded) -> ReadResult<()> {
    let tree = &d.broad.tree;
    tree.check().or_else(corrupt)?;
    for (h, s) in d.shapes.iter() {
        let i = h.index;
        if !live(d.bodies, s.body) || !d.bodies.at(s.body).shapes.contains(&h) {
            return corrupt(format!("shape {i} names body {} that does not list it", s.body));
        }
        if d.geometry.check(&s.geometry).is_err() {
            return corrupt(format!(
                "shape {i} names a convex hull, mesh or heightfield that is not there"
            ));
        }
        let plane = matches!(s.geometry, Geometry::Plane { .. });
        if s.proxy != NONE && (plane || tree.leaf_user_data(s.proxy) != Some(i)) {
            return corrupt(format!("shape {i}'s tree proxy {} is not its leaf", s.proxy));
        }
    }
    for (what, list) in [("move buffer", &d.broad.move_buffer), ("plane list", &d.broad.planes)] {
        if let Some(&i) = list.iter().find(|&&i| i != NONE && !live(d.shapes, i)) {
            return corrupt(format!("the broad phase's {what} names shape {i} that is not there"));
        }
    }
    Ok(())
}

fn check_contacts(d: &Decoded) -> ReadResult<()> {
    for (h, c) in d.contacts.iter() {
        let i = h.index;
        let shape_of = |s: u32, b: u32| live(d.shapes, s) && d.shapes.at(s).body == b;
        if !shape_of(c.shape_a, c.body_a) || !shape_of(c.shape_b, c.body_b) {
            return corrupt(format!(
                "contact {i} names shapes or bodies that are not there or not theirs"
            ));
        }
        if c.manifold.count > MAX_MANIFOLD_POINTS || c.more.iter().any(|m| m.manifold.count > MAX_MANIFOLD_POINTS) {
            return corrupt(format!("contact {i} has more than {MAX_MANIFOLD_POINTS} points"));
        }
        if c.awake_index != NONE && d.awake_contacts.get(c.awake_index as usize) != Some(&i) {
            return corrupt(format!("contact {i}'s awake-list position {} is wrong", c.awake_index));
        }
    }
    for (k, &i) in d.awake_contacts.iter().enumerate() {
        if !live(d.contacts, i) || d.contacts.at(i).awake_index as usize != k {
            return corrupt(format!("awake contact {k} names contact {i} that is not there"));
        }
    }
    if d.broad.pairs.values().any(|&c| !live(d.contacts, c)) {
        return corrupt("the broad phase's pair map names a contact that is not there");
    }
    Ok(())
}

fn check_joints(d: &Decoded) -> ReadResult<()> {
    for (h, j) in d.joints.pool.iter() {
        for end in [j.a, j.b] {
            if end != NONE && !live(d.bodies, end) {
                return corrupt(format!("joint {} names body {end} that is not there", h.index));
            }
        }
    }
    for (b, list) in d.joints.per_body.iter().enumerate() {
        if let Some(&j) = list.iter().find(|&&j| !live(&d.joints.pool, j)) {
            return corrupt(format!("body {b}'s joint list names joint {j} that is not there"));
        }
    }
    Ok(())
}

fn check_particles(p: &Particles) -> ReadResult<()> {
    let n = p.handle.len();
    let lens = [
        p.pos.len(),
        p.vel.len(),
        p.force.len(),
        p.accel.len(),
        p.inv_mass.len(),
        p.radius.len(),
        p.damping.len(),
        p.gravity_scale.len(),
        p.restitution.len(),
        p.friction.len(),
        p.lifetime.len(),
        p.motion.len(),
        p.sleep_time.len(),
        p.flags.len(),
        p.user_data.len(),
    ];
    if lens.iter().any(|&l| l != n) || p.ids.len() != n {
        return corrupt("the particle arrays differ in length");
    }
    for (h, &k) in p.ids.iter() {
        if p.handle.get(k as usize) != Some(&h) {
            return corrupt(format!(
                "particle {} names array entry {k} that is not its own",
                h.index
            ));
        }
    }
    Ok(())
}

fn check_soft_bodies(d: &Decoded) -> ReadResult<()> {
    let s = d.soft_bodies;
    if let Some(&i) = s.live.iter().find(|&&i| !live(&s.pool, i)) {
        return corrupt(format!("the live soft-body list names soft body {i} that is not there"));
    }
    for (h, b) in s.pool.iter() {
        let n = b.pos.len() as u32;
        let ok = b.vel.len() == b.pos.len()
            && b.prev.len() == b.pos.len()
            && b.inv_mass.len() == b.pos.len()
            && b.triangles.iter().flatten().all(|&v| v < n)
            && b.edges.iter().chain(&b.bends).all(|e| e.a < n && e.b < n)
            && b.pins.iter().all(|p| p.vertex < n)
            && b.tethers
                .iter()
                .all(|t| t.vertex < n && (t.pin as usize) < b.pins.len());
        if !ok {
            return corrupt(format!("soft body {} names vertices or pins it does not have", h.index));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::math::{Quat, Transform, Vec3};
    use crate::world::World;
    use crate::{BodyDef, BodyType, Geometry, JointDef, JointKind, ShapeDef, WorldSettings};

    const DT: f32 = 1.0 / 60.0;

    fn body(w: &mut World, t: BodyType, p: Vec3, h: Vec3) -> crate::BodyHandle {
        let b = w
            .create_body(&BodyDef {
                body_type: t,
                transform: Transform::new(p, Quat::IDENTITY),
                ..Default::default()
            })
            .unwrap();
        let g = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: h,
        };
        w.create_shape(b, &ShapeDef::default(), &g).unwrap();
        b
    }

    /// Boxes resting on a ground box (contacts), a joint, a particle and a soft body; a
    /// body destroyed so that its slot is free.
    fn world() -> (World, u32) {
        let mut w = World::new(WorldSettings::default()).unwrap();
        body(&mut w, BodyType::Static, Vec3::ZERO, Vec3::new(10.0, 0.5, 10.0));
        let a = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 1.0, 0.0), Vec3::splat(0.5));
        let b = body(&mut w, BodyType::Dynamic, Vec3::new(1.5, 1.0, 0.0), Vec3::splat(0.5));
        let gone = body(&mut w, BodyType::Dynamic, Vec3::new(5.0, 1.0, 0.0), Vec3::splat(0.5));
        w.create_joint(&JointDef {
            body_a: a,
            body_b: b,
            frame_a: Transform::new(Vec3::new(0.75, 0.0, 0.0), Quat::IDENTITY),
            frame_b: Transform::new(Vec3::new(-0.75, 0.0, 0.0), Quat::IDENTITY),
            ..JointDef::new(JointKind::Ball(Default::default()))
        })
        .unwrap();
        w.create_particle(&Default::default()).unwrap();
        w.create_soft_body(
            &crate::soft::SoftBodyDef {
                transform: Transform::new(Vec3::new(-3.0, 2.0, 0.0), Quat::IDENTITY),
                ..Default::default()
            },
            &crate::soft::mesh::icosphere(0.5, 1),
            None,
        )
        .unwrap();
        w.destroy_body(gone).unwrap();
        for _ in 0..10 {
            w.step(DT).unwrap();
        }
        (w, gone.index)
    }

    fn bytes(w: &World) -> Vec<u8> {
        let mut out = Vec::new();
        w.save_snapshot(&mut out);
        out
    }

    /// A snapshot written from a world whose indices were broken on purpose (so its
    /// checksum is valid) is refused with a message naming what is wrong, and the world
    /// restoring it is unchanged; the unbroken snapshot loads.
    #[test]
    fn valid_checksum_with_inconsistent_indices_is_refused() {
        type Break = fn(&mut World, u32);
        let breaks: [(&str, Break); 12] = [
            ("contact", |w, _| {
                w.contacts.at_mut(w.awake_contacts[0]).shape_a = 10_000
            }),
            ("contact", |w, _| w.contacts.at_mut(w.awake_contacts[0]).body_b = 3),
            ("contact", |w, _| {
                w.contacts.at_mut(w.awake_contacts[0]).manifold.count = 5
            }),
            ("joint", |w, gone| {
                let j = w.joints.pool.iter().next().unwrap().0;
                w.joints.pool.get_mut(j).unwrap().a = gone;
            }),
            ("joint list", |w, _| w.joints.per_body[1].push(7)),
            ("lists contact", |w, _| w.bodies.at_mut(1).contacts.push(999)),
            ("awake", |w, _| w.awake_bodies.push(0)),
            ("awake", |w, _| w.awake_contacts.swap(0, 1)),
            ("proxy", |w, _| w.shapes.at_mut(1).proxy = 10_000),
            ("move buffer", |w, gone| w.broad.move_buffer.push(gone)),
            ("particle", |w, _| w.particles.pos.push(Vec3::ZERO)),
            ("soft body", |w, _| {
                let s = w.soft_bodies.live[0];
                w.soft_bodies.pool.at_mut(s).triangles[0][1] = 5_000;
            }),
        ];
        let (src, gone) = world();
        assert!(src.awake_contacts.len() >= 2, "the boxes touch the ground");
        let good = bytes(&src);
        let mut target = World::new(WorldSettings::default()).unwrap();
        let before = bytes(&target);
        for (k, (what, f)) in breaks.iter().enumerate() {
            let mut w = World::new(WorldSettings::default()).unwrap();
            w.restore_snapshot(&good).unwrap();
            f(&mut w, gone);
            let bad = bytes(&w);
            let e = target
                .restore_snapshot(&bad)
                .expect_err(&format!("break {k} ({what}) loaded"));
            assert!(e.0.contains("corrupted") && e.0.contains(what), "break {k}: {}", e.0);
            assert!(bytes(&target) == before, "break {k} changed the world");
        }
        target.restore_snapshot(&good).unwrap();
        assert!(bytes(&target) == good);
    }
}
