//! [`Snap`] for every stored type with public fields, and for the stored enums. Types with
//! private fields list theirs next to their definition (`snap_struct!` at the end of their
//! module): `DynamicTree`, `GeometryStore`, `TriangleMesh`, `Heightfield`, the contact
//! caches, generator `Attachments`, soft-body face contacts and the particle and soft-body
//! carry-over state.

use super::{bad, ReadResult, Reader, Snap, Writer};
use crate::collision::aabb::Aabb;
use crate::collision::contact::{Contact, FrictionImpulse, PointImpulse};
use crate::collision::filter::Filter;
use crate::collision::hull::{ConvexHull, EdgeGauss, EdgeLanes, Face, HalfEdge, Plane, VertexLanes};
use crate::collision::mesh::bvh::Node as BvhNode;
use crate::collision::narrow_phase::{FaceHold, Manifold, ManifoldPoint, SatCache, SatFeature};
use crate::collision::shape::{Geometry, MassProperties, Shape, ShapeDef};
use crate::dynamics::body::{Body, BodyType};
use crate::dynamics::joints::{
    BallParams, DistanceParams, HingeParams, Impulses, Joint, JointDef, JointKind, Joints, SliderParams,
};
use crate::events::{ContactEvent, SensorEvent};
use crate::generators::{End, Generator, GeneratorDef, Spring};
use crate::math::Transform;
use crate::particles::{ContactOther, ExpiredParticle, ParticleSettings, Particles, UserParticleContact};
use crate::pool::Handle;
use crate::snap_struct;
use crate::soft::solver::PinAt;
use crate::soft::{FaceContact, Pin, SoftBodies, SoftBody, SoftBodyDef, Spring as SoftSpring, Tether, VertexContact};
use crate::world::{Integrator, LaneWidth, StepCounters, WorldSettings};

/// Ids keep index and reuse counter; the world tag is the reading world's.
impl Snap for Handle {
    fn put(&self, w: &mut Writer) {
        self.index.put(w);
        crate::pool::counter_of(*self).put(w);
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let index = u32::get(r)?;
        let counter = u32::get(r)?;
        crate::pool::handle_with_tag(index, counter, r.tag).map_or_else(
            || bad(format!("snapshot corrupted: id counter {counter} out of range")),
            Ok,
        )
    }
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.value_groups::<4, 8>(items.map(|h| {
            let mut b = [0u8; 8];
            b[..4].copy_from_slice(&h.index.to_le_bytes());
            b[4..].copy_from_slice(&crate::pool::counter_of(*h).to_le_bytes());
            b
        }));
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        let mut v = vec![Handle::NULL; n.min(r.remaining())];
        Self::get_into(&mut v, n, |d, i| &mut d[i], r)?;
        Ok(v)
    }
    fn get_into<O>(
        dst: &mut [O],
        n: usize,
        at: impl Fn(&mut [O], usize) -> &mut Self + Copy,
        r: &mut Reader,
    ) -> ReadResult<()> {
        let b = r.take_values(n, 8)?;
        let tag = r.tag;
        for (i, c) in b.chunks_exact(8).enumerate() {
            *at(dst, i) = handle_from(c, tag)?;
        }
        Ok(())
    }
    /// Filled into vectors the last restore on this thread freed (`Reader::spare`).
    fn get_vecs(lens: &[usize], r: &mut Reader) -> ReadResult<Vec<Vec<Self>>> {
        let b = r.take_values(lens.iter().sum(), 8)?;
        let mut values = b.chunks_exact(8);
        let mut out = Vec::with_capacity(lens.len());
        for &k in lens {
            let mut v = match k {
                0 => Vec::new(),
                _ => r.spare.0.pop().unwrap_or_default(),
            };
            v.clear();
            for c in values.by_ref().take(k) {
                v.push(handle_from(c, r.tag)?);
            }
            out.push(v);
        }
        Ok(out)
    }
}

/// The id stored in `c` (index, counter), with the world tag `tag`.
#[inline(always)]
fn handle_from(c: &[u8], tag: u32) -> ReadResult<Handle> {
    let index = u32::from_le_bytes(c[..4].try_into().expect("4 bytes"));
    let counter = u32::from_le_bytes(c[4..].try_into().expect("4 bytes"));
    match crate::pool::handle_with_tag(index, counter, tag) {
        Some(h) => Ok(h),
        None => bad(format!("snapshot corrupted: id counter {counter} out of range")),
    }
}

/// Blanks to read into (`SnapBlank`): every field is overwritten by `get_into`.
impl super::SnapBlank for Body {
    fn blank() -> Self {
        Body {
            body_type: BodyType::Static,
            xf: Default::default(),
            center: Default::default(),
            local_center: Default::default(),
            v: Default::default(),
            w: Default::default(),
            force: Default::default(),
            torque: Default::default(),
            mass: 0.0,
            inv_mass: 0.0,
            inertia_local: Default::default(),
            inv_inertia_local: Default::default(),
            isotropic: false,
            inv_inertia_world: Default::default(),
            linear_damping: 0.0,
            angular_damping: 0.0,
            gravity_scale: 0.0,
            allow_sleep: false,
            awake: false,
            motion: 0.0,
            sleep_time: 0.0,
            user_data: 0,
            shapes: Vec::new(),
            contacts: Vec::new(),
            awake_index: 0,
            sleep_island: Handle::NULL,
            island_next: 0,
            solver_index: 0,
            kinematic_target: None,
            kinematic_stop: false,
            enable_move_events: false,
            reported_xf: Default::default(),
            mass_override: None,
            enabled: false,
            locked_axes: 0,
        }
    }
}

impl super::SnapBlank for Shape {
    fn blank() -> Self {
        Shape {
            body: 0,
            geometry: Geometry::Sphere {
                center: Default::default(),
                radius: 0.0,
            },
            def: Default::default(),
            proxy: 0,
            aabb: Default::default(),
            fat_aabb: Default::default(),
            in_move_buffer: false,
            extent: 0.0,
        }
    }
}

impl super::SnapBlank for Contact {
    fn blank() -> Self {
        Contact {
            shape_a: 0,
            shape_b: 0,
            body_a: 0,
            body_b: 0,
            manifold: Default::default(),
            impulses: Default::default(),
            friction: Default::default(),
            static_friction: 0.0,
            dynamic_friction: 0.0,
            restitution: 0.0,
            rolling_resistance: 0.0,
            torsional_friction: 0.0,
            touching: false,
            awake_index: 0,
            key: 0,
            radius_a: 0.0,
            radius_b: 0.0,
            size: 0.0,
            cache: Default::default(),
            multi: false,
            more: Vec::new(),
            sat: Default::default(),
            event_flags: 0,
            reported: false,
            disabled: false,
        }
    }
}

snap_struct!(Transform { p, q });
snap_struct!(WorldSettings {
    gravity,
    substeps,
    velocity_iterations,
    integrator,
    enable_sleep,
    sleep_threshold,
    time_to_sleep,
    contact_hertz,
    contact_damping_ratio,
    contact_push_max_velocity,
    restitution_threshold,
    linear_slop,
    max_linear_speed,
    max_angular_speed,
    lane_width,
    hit_event_threshold;
    // Threads are the target world's own (results do not depend on them): `read.rs`.
    skip worker_count
});
snap_struct!(StepCounters {
    awake_bodies,
    contacts,
    touching_contacts,
    pairs_tested,
    proxies_moved,
});
snap_struct!(Body {
    body_type,
    xf,
    local_center,
    v,
    w,
    force,
    torque,
    mass,
    inv_mass,
    inertia_local,
    inv_inertia_local,
    isotropic,
    inv_inertia_world,
    linear_damping,
    angular_damping,
    gravity_scale,
    allow_sleep,
    awake,
    motion,
    sleep_time,
    user_data,
    shapes,
    contacts,
    awake_index,
    sleep_island,
    solver_index,
    kinematic_target,
    kinematic_stop,
    enable_move_events,
    mass_override,
    enabled,
    locked_axes;
    // Stored after the pool, only where they differ from what they are rebuilt as
    // (`predicted.rs`).
    skip center,
    reported_xf,
    // Rebuilt from the stored islands (`read.rs`).
    island_next,
});
snap_struct!(Aabb { min, max });
snap_struct!(ShapeDef {
    density,
    static_friction,
    dynamic_friction,
    restitution,
    user_data,
    rolling_resistance,
    torsional_friction,
    filter,
    is_sensor,
    enable_contact_events,
    enable_hit_events,
    enable_sensor_events,
});
snap_struct!(Filter {
    category_bits,
    mask_bits,
    group_index,
});
snap_struct!(ContactEvent {
    shape_a,
    shape_b,
    body_a,
    body_b,
});
snap_struct!(SensorEvent {
    sensor_shape,
    visitor_shape,
    sensor_body,
    visitor_body,
});
snap_struct!(Shape {
    body,
    geometry,
    def,
    proxy,
    in_move_buffer,
    extent;
    // Stored after the pool, only where they differ from what they are rebuilt as
    // (`predicted.rs`).
    skip aabb,
    fat_aabb,
});
snap_struct!(MassProperties { mass, center, inertia });
snap_struct!(PointImpulse { normal });
snap_struct!(FrictionImpulse {
    tangent,
    twist,
    rolling,
    sliding,
});
snap_struct!(ManifoldPoint { point, separation, id });
snap_struct!(Manifold { normal, points, count });
snap_struct!(Contact {
    shape_a,
    shape_b,
    body_a,
    body_b,
    manifold,
    impulses,
    friction,
    static_friction,
    dynamic_friction,
    restitution,
    rolling_resistance,
    torsional_friction,
    touching,
    awake_index,
    key,
    radius_a,
    radius_b,
    size,
    cache,
    multi,
    more,
    sat,
    event_flags,
    reported,
    disabled,
});
snap_struct!(Plane { normal, offset });
snap_struct!(Face { first, count });
snap_struct!(HalfEdge { origin, twin, face });
snap_struct!(EdgeGauss {
    n1,
    n2,
    n2_x_n1,
    v0,
    v1,
});
snap_struct!(ConvexHull {
    vertices,
    planes,
    faces,
    half_edges,
    edges,
    edge_directions,
    edge_gauss,
    radius,
    unit_mass,
    area,
    min,
    max,
    bound_radius,
    lanes,
    edge_lanes,
});
snap_struct!(VertexLanes { x, y, z });
snap_struct!(EdgeLanes { n1, n2, n2_x_n1 });
snap_struct!(BvhNode { min, data, max, count });

// ------------------------------------------------------------------ generators
snap_struct!(Spring {
    other,
    local_point,
    rest_length,
    stiffness,
    damping,
});
snap_struct!(Generator {
    def,
    bodies,
    particles,
    broken,
    elapsed,
    warm,
});

// ------------------------------------------------------------------ particles
snap_struct!(ParticleSettings {
    velocity_iterations,
    position_iterations,
});
snap_struct!(ExpiredParticle {
    id,
    position,
    velocity,
    user_data,
});
snap_struct!(UserParticleContact {
    particle,
    other,
    point,
    normal,
    penetration,
    restitution,
    friction,
});
snap_struct!(Particles {
    ids,
    handle,
    pos,
    vel,
    force,
    accel,
    inv_mass,
    radius,
    damping,
    gravity_scale,
    restitution,
    friction,
    lifetime,
    motion,
    sleep_time,
    flags,
    user_data,
    expired,
    user_contacts,
    settings,
    removed_since_prune,
    scratch,
});

// ------------------------------------------------------------------ joints
snap_struct!(BallParams {
    enable_swing_limit,
    swing_limit,
    enable_twist_limit,
    lower_twist,
    upper_twist,
});
snap_struct!(HingeParams {
    enable_limit,
    lower,
    upper,
    enable_motor,
    motor_speed,
    max_motor_torque,
    enable_spring,
    spring_hertz,
    spring_damping_ratio,
});
snap_struct!(DistanceParams {
    length,
    enable_limit,
    min_length,
    max_length,
    enable_spring,
    spring_hertz,
    spring_damping_ratio,
});
snap_struct!(SliderParams {
    enable_limit,
    lower,
    upper,
    enable_motor,
    motor_speed,
    max_motor_force,
});
snap_struct!(JointDef {
    kind,
    body_a,
    body_b,
    frame_a,
    frame_b,
    collide_connected,
    break_force,
    break_torque,
});
snap_struct!(Impulses {
    linear,
    angular,
    axial,
    motor,
    lower,
    upper,
    cone,
});
snap_struct!(Joint {
    def,
    a,
    b,
    broken,
    impulses,
    force,
    torque,
});
snap_struct!(Joints {
    pool,
    per_body,
    broken;
    skip constraints
});

// ------------------------------------------------------------------ soft bodies
snap_struct!(SoftBodyDef {
    transform,
    velocity,
    mass,
    edge_compliance,
    bend_compliance,
    preserve_volume,
    volume_compliance,
    pressure,
    damping,
    deformation_damping,
    friction,
    restitution,
    vertex_radius,
    gravity_scale,
    substeps,
    iterations,
    collide,
    user_data,
});
snap_struct!(Pin { vertex, body, local });
snap_struct!(SoftSpring {
    a,
    b,
    rest,
    tension_only,
});
snap_struct!(Tether { vertex, pin, max });
snap_struct!(VertexContact {
    n,
    offset,
    point,
    body,
    coupled,
    sleeper,
    friction,
    restitution,
    active,
});
snap_struct!(FaceContact {
    triangle,
    bary,
    point,
    coupled,
    body,
    friction,
});
snap_struct!(SoftBody {
    def,
    pos,
    vel,
    prev,
    inv_mass,
    w,
    rest,
    triangles,
    edges,
    bends,
    pins,
    tethers,
    pin_at,
    contacts,
    body_contacts,
    face_contacts,
    held,
    touching,
    old,
    grad,
    rest_volume,
    rest_area,
    skin,
    neighbours,
    longest_edge,
    impulses,
    has_impulses,
});
snap_struct!(SoftBodies { pool, live, scratch });

// ------------------------------------------------------------------ enums

macro_rules! snap_unit_enum {
    ($t:ty, $what:literal: $($v:path),*) => {
        impl Snap for $t {
            fn put(&self, w: &mut Writer) {
                let all = [$($v),*];
                w.put_tag(all.iter().position(|x| x == self).expect("listed variant") as u8)
            }
            fn get(r: &mut Reader) -> ReadResult<Self> {
                let all = [$($v),*];
                Ok(all[r.tag($what, all.len() as u8)? as usize])
            }
            fn put_all<'s, I>(items: I, w: &mut Writer)
            where
                I: Iterator<Item = &'s Self> + Clone,
                Self: 's,
            {
                // Entered only for a value, as `put` per value would.
                if items.clone().next().is_some() {
                    let all = [$($v),*];
                    w.within("#tag", |w| {
                        w.values(items.map(|x| [all.iter().position(|a| a == x).expect("listed variant") as u8]))
                    });
                }
            }
            fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
                if n == 0 {
                    return Ok(Vec::new());
                }
                let all = [$($v),*];
                let b = r.within("#tag", |r| r.take_values(n, 1))?;
                if let Some(t) = b.iter().find(|&&t| t as usize >= all.len()) {
                    return bad(format!("snapshot corrupted: {} variant {t} unknown", $what));
                }
                Ok(b.iter().map(|&t| all[t as usize]).collect())
            }
        }
    };
}
snap_unit_enum!(BodyType, "body type": BodyType::Static, BodyType::Kinematic, BodyType::Dynamic);
snap_unit_enum!(Integrator, "integrator": Integrator::SemiImplicitEuler, Integrator::Rk4);
snap_unit_enum!(LaneWidth, "lane width": LaneWidth::Auto, LaneWidth::Four);

impl Geometry {
    /// The variant's tag.
    fn tag(&self) -> u8 {
        match self {
            Geometry::Sphere { .. } => 0,
            Geometry::Box { .. } => 1,
            Geometry::Capsule { .. } => 2,
            Geometry::Plane { .. } => 3,
            Geometry::Hull { .. } => 4,
            Geometry::Mesh { .. } => 5,
            Geometry::Heightfield { .. } => 6,
        }
    }

    /// The variant's fields (its tag is written apart).
    fn put_fields(&self, w: &mut Writer) {
        match self {
            Geometry::Sphere { center, radius } => {
                center.put(w);
                radius.put(w);
            }
            Geometry::Box {
                center,
                rotation,
                half_extents,
            } => {
                center.put(w);
                rotation.put(w);
                half_extents.put(w);
            }
            Geometry::Capsule { a, b, radius } => {
                a.put(w);
                b.put(w);
                radius.put(w);
            }
            Geometry::Plane { normal, offset } => {
                normal.put(w);
                offset.put(w);
            }
            Geometry::Hull { hull, local, scale } => {
                hull.put(w);
                local.put(w);
                scale.put(w);
            }
            Geometry::Mesh { mesh, local, scale } => {
                mesh.put(w);
                local.put(w);
                scale.put(w);
            }
            Geometry::Heightfield {
                heightfield,
                local,
                scale,
            } => {
                heightfield.put(w);
                local.put(w);
                scale.put(w);
            }
        }
    }

    /// The fields of the variant of tag `t` (below 7).
    fn get_fields(t: u8, r: &mut Reader) -> ReadResult<Self> {
        Ok(match t {
            0 => Geometry::Sphere {
                center: Snap::get(r)?,
                radius: Snap::get(r)?,
            },
            1 => Geometry::Box {
                center: Snap::get(r)?,
                rotation: Snap::get(r)?,
                half_extents: Snap::get(r)?,
            },
            2 => Geometry::Capsule {
                a: Snap::get(r)?,
                b: Snap::get(r)?,
                radius: Snap::get(r)?,
            },
            3 => Geometry::Plane {
                normal: Snap::get(r)?,
                offset: Snap::get(r)?,
            },
            4 => Geometry::Hull {
                hull: Snap::get(r)?,
                local: Snap::get(r)?,
                scale: Snap::get(r)?,
            },
            5 => Geometry::Mesh {
                mesh: Snap::get(r)?,
                local: Snap::get(r)?,
                scale: Snap::get(r)?,
            },
            _ => Geometry::Heightfield {
                heightfield: Snap::get(r)?,
                local: Snap::get(r)?,
                scale: Snap::get(r)?,
            },
        })
    }
}

/// Each shape's geometry: its tag (in `#tag`), then its variant's fields; `put_all` and
/// `get_all` write and read all the tags in one pass, then the fields value by value (the
/// same bytes, in columns made in the same order: `#tag` at the first value).
impl Snap for Geometry {
    fn put(&self, w: &mut Writer) {
        w.put_tag(self.tag());
        self.put_fields(w);
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let t = r.tag("geometry", 7)?;
        Self::get_fields(t, r)
    }
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.put_tagged_all(items, Self::tag, Self::put_fields);
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        r.get_tagged_all(n, "geometry", 7, Self::get_fields)
    }
}

/// The SAT cache's deciding feature: its tag (in `#tag`), then its face or edges, in the
/// feature's own column; `put_all` and `get_all` move all the tags in one pass, then the
/// fields (the same bytes, in columns made in the same order: `#tag` at the first value).
impl Snap for SatFeature {
    fn put(&self, w: &mut Writer) {
        w.put_tag(sat_tag(self));
        put_sat_fields(self, w);
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        let t = r.tag("SAT feature", 4)?;
        get_sat_fields(t, r)
    }
    fn put_all<'s, I>(items: I, w: &mut Writer)
    where
        I: Iterator<Item = &'s Self> + Clone,
        Self: 's,
    {
        w.put_tagged_all(items, sat_tag, put_sat_fields);
    }
    fn get_all(n: usize, r: &mut Reader) -> ReadResult<Vec<Self>> {
        r.get_tagged_all(n, "SAT feature", 4, get_sat_fields)
    }
}

fn sat_tag(f: &SatFeature) -> u8 {
    match f {
        SatFeature::None => 0,
        SatFeature::FaceA(_) => 1,
        SatFeature::FaceB(_) => 2,
        SatFeature::Edges(..) => 3,
    }
}

fn put_sat_fields(f: &SatFeature, w: &mut Writer) {
    match *f {
        SatFeature::None => {}
        SatFeature::FaceA(f) | SatFeature::FaceB(f) => f.put(w),
        SatFeature::Edges(a, b) => {
            a.put(w);
            b.put(w)
        }
    }
}

/// The fields of the feature of tag `t` (below 4).
fn get_sat_fields(t: u8, r: &mut Reader) -> ReadResult<SatFeature> {
    Ok(match t {
        0 => SatFeature::None,
        1 => SatFeature::FaceA(Snap::get(r)?),
        2 => SatFeature::FaceB(Snap::get(r)?),
        _ => SatFeature::Edges(Snap::get(r)?, Snap::get(r)?),
    })
}

snap_struct!(FaceHold {
    valid,
    r,
    t,
    same,
    other
});
snap_struct!(SatCache { feature, hold });

impl Snap for JointKind {
    fn put(&self, w: &mut Writer) {
        match self {
            JointKind::Ball(p) => {
                w.put_tag(0);
                p.put(w)
            }
            JointKind::Hinge(p) => {
                w.put_tag(1);
                p.put(w)
            }
            JointKind::Fixed => w.put_tag(2),
            JointKind::Distance(p) => {
                w.put_tag(3);
                p.put(w)
            }
            JointKind::Slider(p) => {
                w.put_tag(4);
                p.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(match r.tag("joint kind", 5)? {
            0 => JointKind::Ball(Snap::get(r)?),
            1 => JointKind::Hinge(Snap::get(r)?),
            2 => JointKind::Fixed,
            3 => JointKind::Distance(Snap::get(r)?),
            _ => JointKind::Slider(Snap::get(r)?),
        })
    }
}

impl Snap for End {
    fn put(&self, w: &mut Writer) {
        match self {
            End::World(p) => {
                w.put_tag(0);
                p.put(w)
            }
            End::Body { body, local } => {
                w.put_tag(1);
                body.put(w);
                local.put(w)
            }
            End::Particle(h) => {
                w.put_tag(2);
                h.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(match r.tag("spring end", 3)? {
            0 => End::World(Snap::get(r)?),
            1 => End::Body {
                body: Snap::get(r)?,
                local: Snap::get(r)?,
            },
            _ => End::Particle(Snap::get(r)?),
        })
    }
}

impl Snap for ContactOther {
    fn put(&self, w: &mut Writer) {
        match self {
            ContactOther::World => w.put_tag(0),
            ContactOther::Body(b) => {
                w.put_tag(1);
                b.put(w)
            }
            ContactOther::Particle(h) => {
                w.put_tag(2);
                h.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(match r.tag("particle contact", 3)? {
            0 => ContactOther::World,
            1 => ContactOther::Body(Snap::get(r)?),
            _ => ContactOther::Particle(Snap::get(r)?),
        })
    }
}

impl Snap for PinAt {
    fn put(&self, w: &mut Writer) {
        match self {
            PinAt::Fixed(p) => {
                w.put_tag(0);
                p.put(w)
            }
            PinAt::Body { k, arm } => {
                w.put_tag(1);
                k.put(w);
                arm.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(match r.tag("pin", 2)? {
            0 => PinAt::Fixed(Snap::get(r)?),
            _ => PinAt::Body {
                k: Snap::get(r)?,
                arm: Snap::get(r)?,
            },
        })
    }
}

/// User generators store no callback: their function pointer and user data mean nothing in
/// another process. They are read back as 0 (no callback) and `World::restore` puts back the
/// callbacks the target world holds (same world) or leaves them for the host to re-register.
impl Snap for GeneratorDef {
    fn put(&self, w: &mut Writer) {
        match self {
            GeneratorDef::Gravity { acceleration } => {
                w.put_tag(0);
                acceleration.put(w)
            }
            GeneratorDef::Drag { k1, k2 } => {
                w.put_tag(1);
                k1.put(w);
                k2.put(w)
            }
            GeneratorDef::Spring(s) => {
                w.put_tag(2);
                s.put(w)
            }
            GeneratorDef::Bungee(s) => {
                w.put_tag(3);
                s.put(w)
            }
            GeneratorDef::StiffSpring {
                anchor,
                local_point,
                stiffness,
                damping,
            } => {
                w.put_tag(4);
                anchor.put(w);
                local_point.put(w);
                stiffness.put(w);
                damping.put(w)
            }
            GeneratorDef::Buoyancy {
                normal,
                surface,
                max_depth,
                volume,
                liquid_density,
                local_point,
            } => {
                w.put_tag(5);
                normal.put(w);
                surface.put(w);
                max_depth.put(w);
                volume.put(w);
                liquid_density.put(w);
                local_point.put(w)
            }
            GeneratorDef::Explosion {
                center,
                blast_radius,
                blast_impulse,
                shock_speed,
                shock_thickness,
                shock_force,
                max_radius,
                affect_all,
            } => {
                w.put_tag(6);
                center.put(w);
                blast_radius.put(w);
                blast_impulse.put(w);
                shock_speed.put(w);
                shock_thickness.put(w);
                shock_force.put(w);
                max_radius.put(w);
                affect_all.put(w)
            }
            GeneratorDef::Rod { a, b, length } => {
                w.put_tag(7);
                a.put(w);
                b.put(w);
                length.put(w)
            }
            GeneratorDef::Cable {
                a,
                b,
                max_length,
                restitution,
            } => {
                w.put_tag(8);
                a.put(w);
                b.put(w);
                max_length.put(w);
                restitution.put(w)
            }
            GeneratorDef::ExternalForce {
                callback: _,
                user_data: _,
            } => w.put_tag(9),
            GeneratorDef::ExternalContact {
                callback: _,
                user_data: _,
                capacity,
            } => {
                w.put_tag(10);
                capacity.put(w)
            }
        }
    }
    fn get(r: &mut Reader) -> ReadResult<Self> {
        Ok(match r.tag("generator", 11)? {
            0 => GeneratorDef::Gravity {
                acceleration: Snap::get(r)?,
            },
            1 => GeneratorDef::Drag {
                k1: Snap::get(r)?,
                k2: Snap::get(r)?,
            },
            2 => GeneratorDef::Spring(Snap::get(r)?),
            3 => GeneratorDef::Bungee(Snap::get(r)?),
            4 => GeneratorDef::StiffSpring {
                anchor: Snap::get(r)?,
                local_point: Snap::get(r)?,
                stiffness: Snap::get(r)?,
                damping: Snap::get(r)?,
            },
            5 => GeneratorDef::Buoyancy {
                normal: Snap::get(r)?,
                surface: Snap::get(r)?,
                max_depth: Snap::get(r)?,
                volume: Snap::get(r)?,
                liquid_density: Snap::get(r)?,
                local_point: Snap::get(r)?,
            },
            6 => GeneratorDef::Explosion {
                center: Snap::get(r)?,
                blast_radius: Snap::get(r)?,
                blast_impulse: Snap::get(r)?,
                shock_speed: Snap::get(r)?,
                shock_thickness: Snap::get(r)?,
                shock_force: Snap::get(r)?,
                max_radius: Snap::get(r)?,
                affect_all: Snap::get(r)?,
            },
            7 => GeneratorDef::Rod {
                a: Snap::get(r)?,
                b: Snap::get(r)?,
                length: Snap::get(r)?,
            },
            8 => GeneratorDef::Cable {
                a: Snap::get(r)?,
                b: Snap::get(r)?,
                max_length: Snap::get(r)?,
                restitution: Snap::get(r)?,
            },
            9 => GeneratorDef::ExternalForce {
                callback: 0,
                user_data: 0,
            },
            _ => GeneratorDef::ExternalContact {
                callback: 0,
                user_data: 0,
                capacity: Snap::get(r)?,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::narrow_phase::{Manifold, ManifoldPoint};
    use crate::math::Vec3;

    /// The payload `f` writes.
    fn payload(f: impl Fn(&mut Writer)) -> Vec<u8> {
        let mut w = Writer::new();
        f(&mut w);
        let mut out = Vec::new();
        w.finish(&mut out);
        out
    }

    /// `put_all` of `values` writes the bytes `put` of each in turn writes (columns made in
    /// the same order, also for no values when `empty_too`: a struct's `put_all` makes its
    /// fields' columns even for none), and both `get_all` (in place
    /// for types with a default) and `get` of each read the values back.
    fn bulk_matches_one_by_one<T: Snap + PartialEq + std::fmt::Debug>(values: &[T], empty_too: bool) {
        let one = payload(|w| w.within("x", |w| values.iter().for_each(|v| v.put(w))));
        let all = payload(|w| w.within("x", |w| T::put_all(values.iter(), w)));
        if !values.is_empty() || empty_too {
            assert_eq!(one, all, "{} values", values.len());
        }
        let mut plain = Vec::new();
        let spans = super::super::columns::unpack(&all, &mut plain).unwrap();
        let mut r = Reader::new(&plain, &spans, 7);
        assert_eq!(r.within("x", |r| T::get_all(values.len(), r)).as_deref(), Ok(values));
        r.finish().unwrap();
        let mut r = Reader::new(&plain, &spans, 7);
        let got: ReadResult<Vec<T>> = r.within("x", |r| (0..values.len()).map(|_| T::get(r)).collect());
        assert_eq!(got.as_deref(), Ok(values));
        if !values.is_empty() || empty_too {
            r.finish().unwrap();
        }
        // More values than were written: refused, by either of `get_all`'s paths (in place
        // for counts the bytes left could hold, field by field past that).
        for more in [values.len() + 1, 2 * values.len() + 1, plain.len() + 1] {
            let mut r = Reader::new(&plain, &spans, 7);
            let got = r.within("x", |r| T::get_all(more, r));
            assert!(got.unwrap_err().0.contains("corrupted"), "{more} of {}", values.len());
        }
    }

    /// Seeded randomized: ids (null among them), enum tags, maps (empty among them),
    /// arrays of vectors, matrices and manifolds (read in place, field by field, down to
    /// their arrays of points) of many counts, across the 64-value blocks.
    #[test]
    fn bulk_paths_match_value_by_value() {
        // Values on a grid of 0.37 in [-370, 370].
        let grid = |r: &mut crate::math::test_rnd::Rnd| (r.next_u64() % 2001) as f32 * 0.37 - 370.0;
        let mut rng = crate::math::test_rnd::Rnd(0x9E37_79B9_7F4A_7C15);
        for n in [0usize, 1, 2, 7, 64, 65, 300] {
            let vectors: Vec<[Vec3; 4]> = (0..n)
                .map(|_| std::array::from_fn(|_| Vec3::new(grid(&mut rng), grid(&mut rng), grid(&mut rng))))
                .collect();
            let matrices: Vec<glam::Mat3> = (0..n)
                .map(|_| glam::Mat3::from_cols_array(&std::array::from_fn(|_| grid(&mut rng))))
                .collect();
            bulk_matches_one_by_one(&vectors, true);
            bulk_matches_one_by_one(&matrices, true);
            let manifolds: Vec<Manifold> = (0..n)
                .map(|_| Manifold {
                    normal: Vec3::new(grid(&mut rng), grid(&mut rng), grid(&mut rng)),
                    points: std::array::from_fn(|_| ManifoldPoint {
                        point: Vec3::new(grid(&mut rng), grid(&mut rng), grid(&mut rng)),
                        separation: grid(&mut rng),
                        id: rng.next_u64() as u32,
                    }),
                    count: rng.next_u64() as usize % 5,
                })
                .collect();
            bulk_matches_one_by_one(&manifolds, false);
            let handles: Vec<Handle> = (0..n)
                .map(|i| {
                    let (index, counter) = (rng.next_u64() as u32 % 5000, 1 + rng.next_u64() as u32 % 1000);
                    if i % 5 == 0 {
                        Handle::NULL
                    } else {
                        crate::pool::handle_with_tag(index, counter, 7).unwrap()
                    }
                })
                .collect();
            bulk_matches_one_by_one(&handles, true);
            let types: Vec<BodyType> = (0..n)
                .map(|_| [BodyType::Static, BodyType::Kinematic, BodyType::Dynamic][rng.next_u64() as usize % 3])
                .collect();
            bulk_matches_one_by_one(&types, true);
            // Enums with fields: every variant, the tags in one pass, the fields after.
            let v3 = |r: &mut crate::math::test_rnd::Rnd| Vec3::new(grid(r), grid(r), grid(r));
            let geometries: Vec<Geometry> = (0..n)
                .map(|_| match rng.next_u64() % 4 {
                    0 => Geometry::Sphere {
                        center: v3(&mut rng),
                        radius: grid(&mut rng),
                    },
                    1 => Geometry::Box {
                        center: v3(&mut rng),
                        rotation: glam::Quat::from_xyzw(grid(&mut rng), grid(&mut rng), grid(&mut rng), grid(&mut rng)),
                        half_extents: v3(&mut rng),
                    },
                    2 => Geometry::Capsule {
                        a: v3(&mut rng),
                        b: v3(&mut rng),
                        radius: grid(&mut rng),
                    },
                    _ => Geometry::Plane {
                        normal: v3(&mut rng),
                        offset: grid(&mut rng),
                    },
                })
                .collect();
            bulk_matches_one_by_one(&geometries, true);
            let features: Vec<SatFeature> = (0..n)
                .map(|_| {
                    let (a, b) = (rng.next_u64() as u16, rng.next_u64() as u16);
                    [
                        SatFeature::None,
                        SatFeature::FaceA(a),
                        SatFeature::FaceB(b),
                        SatFeature::Edges(a, b),
                    ][rng.next_u64() as usize % 4]
                })
                .collect();
            bulk_matches_one_by_one(&features, true);
            // Lists of indices and ids (filled into kept vectors on restore), all empty
            // in every other round.
            let long = if n % 2 == 0 { 4 } else { 1 };
            let lists: Vec<Vec<u32>> = (0..n)
                .map(|_| (0..rng.next_u64() % long).map(|_| rng.next_u64() as u32).collect())
                .collect();
            bulk_matches_one_by_one(&lists, false);
            let id_lists: Vec<Vec<Handle>> = (0..n)
                .map(|_| {
                    (0..rng.next_u64() % long)
                        .map(|_| {
                            handles
                                .get(rng.next_u64() as usize % n.max(1))
                                .copied()
                                .unwrap_or(Handle::NULL)
                        })
                        .collect()
                })
                .collect();
            bulk_matches_one_by_one(&id_lists, false);
            let maps: Vec<crate::hash::IntMap<u64, u32>> = (0..n.min(20))
                .map(|k| {
                    (0..k * 7)
                        .map(|_| (rng.next_u64() % 50, rng.next_u64() as u32))
                        .collect()
                })
                .collect();
            bulk_matches_one_by_one(&maps, true);
            // A map's keys, then its values, in their own columns: the bytes of writing
            // entry by entry in key order.
            for m in &maps {
                let mut keys: Vec<u64> = m.keys().copied().collect();
                keys.sort_unstable();
                let by_entry = payload(|w| {
                    w.put_len(keys.len());
                    for k in &keys {
                        w.within("#key", |w| k.put(w));
                        w.within("#value", |w| m[k].put(w));
                    }
                });
                assert_eq!(payload(|w| m.put(w)), by_entry);
            }
        }
    }
}
