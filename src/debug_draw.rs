//! Debug draw (issue 14): the world described as primitives — segments, convex polygons,
//! spheres, capsules, axes and points, each with a colour — handed to a `DebugDraw` the host
//! implements (the C layer adapts it to C callbacks, `capi/draw.rs`). Drawing only reads the
//! world.

use crate::collision::aabb::Aabb;
use crate::collision::shape::Geometry;
use crate::dynamics::body::{Body, BodyType};
use crate::math::{Mat3, Transform, Vec3};
use crate::world::World;

/// A colour as `0xRRGGBBAA`.
pub type Color = u32;

/// Colours the world draws with.
pub mod colors {
    use super::Color;
    pub const STATIC: Color = 0x8C8C8CFF;
    pub const KINEMATIC: Color = 0x4C8CE6FF;
    pub const AWAKE: Color = 0xE68C33FF;
    pub const SLEEPING: Color = 0x8C7359FF;
    pub const AABB: Color = 0xCC33CCFF;
    pub const CONTACT_POINT: Color = 0xE63333FF;
    pub const CONTACT_NORMAL: Color = 0x33CC33FF;
    pub const CONTACT_IMPULSE: Color = 0xE6E633FF;
    pub const JOINT: Color = 0x33CCCCFF;
    pub const CENTER_OF_MASS: Color = 0xFFFFFFFF;
}

/// Half the side of the square patch a plane is drawn as (m), centred on the point of the
/// plane nearest the world origin.
pub const PLANE_PATCH_HALF_SIDE: f32 = 10.0;
/// Length of a drawn contact normal (m).
pub const CONTACT_NORMAL_LENGTH: f32 = 0.25;
/// Length of a drawn contact impulse per N·s of normal impulse (m).
pub const IMPULSE_SCALE: f32 = 0.1;
/// Size of a drawn contact point or joint anchor (m).
pub const POINT_SIZE: f32 = 0.05;

/// What `World::draw` draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawFlags {
    /// Every shape of every enabled body, coloured by the body's state (static, kinematic,
    /// awake dynamic, sleeping dynamic).
    pub shapes: bool,
    /// The tight bounding box of every bounded shape of every enabled body: 12 segments.
    pub aabbs: bool,
    /// Each point of each touching manifold: a point, its normal (a segment), and its normal
    /// impulse of the last step (a segment along the normal, when positive).
    pub contacts: bool,
    /// Each unbroken joint between enabled bodies: its two anchors (points), the segment
    /// between them and the segments from each body's centre of mass to its anchor.
    pub joints: bool,
    /// Each dynamic body's centre of mass and orientation (a transform).
    pub centers_of_mass: bool,
}

/// What draws: the primitives a renderer needs. World-space positions, metres.
pub trait DebugDraw {
    fn segment(&mut self, a: Vec3, b: Vec3, color: Color);
    /// A convex planar polygon (a face), its vertices in order; three for a triangle.
    fn polygon(&mut self, vertices: &[Vec3], color: Color);
    fn sphere(&mut self, center: Vec3, radius: f32, color: Color);
    /// The segment `a`–`b` swept by `radius`.
    fn capsule(&mut self, a: Vec3, b: Vec3, radius: f32, color: Color);
    /// A frame: its origin and axes (x red, y green, z blue by convention).
    fn transform(&mut self, xf: Transform);
    fn point(&mut self, p: Vec3, size: f32, color: Color);
}

/// The colour a body's shapes are drawn with.
pub fn body_color(b: &Body) -> Color {
    match b.body_type {
        BodyType::Static => colors::STATIC,
        BodyType::Kinematic => colors::KINEMATIC,
        BodyType::Dynamic if b.awake => colors::AWAKE,
        BodyType::Dynamic => colors::SLEEPING,
    }
}

/// The corners of an oriented box, bit `k` of the index choosing the sign of axis `k`.
fn box_corners(center: Vec3, m: Mat3, h: Vec3) -> [Vec3; 8] {
    let mut out = [Vec3::ZERO; 8];
    for (i, c) in out.iter_mut().enumerate() {
        let s = Vec3::new(
            if i & 1 != 0 { h.x } else { -h.x },
            if i & 2 != 0 { h.y } else { -h.y },
            if i & 4 != 0 { h.z } else { -h.z },
        );
        *c = center + m * s;
    }
    out
}

/// The six faces of a box as corner indices (counter-clockwise seen from outside).
const BOX_FACES: [[usize; 4]; 6] = [
    [0, 4, 6, 2],
    [1, 3, 7, 5],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 2, 3, 1],
    [4, 5, 7, 6],
];

fn draw_aabb(d: &mut dyn DebugDraw, b: &Aabb, color: Color) {
    let c = box_corners(b.center(), Mat3::IDENTITY, b.extents());
    for i in 0..8usize {
        for k in 0..3 {
            let j = i | (1 << k);
            if j != i {
                d.segment(c[i], c[j], color);
            }
        }
    }
}

impl World {
    /// Draws the world as `flags` asks (see `DrawFlags`). Disabled bodies are not drawn.
    /// Shapes: a sphere as a sphere, a capsule as a capsule, a box as its six faces, a plane
    /// as a square patch `2·PLANE_PATCH_HALF_SIDE` across, a hull as its faces, a mesh as its
    /// triangles, a heightfield as two triangles per solid cell.
    pub fn draw(&self, d: &mut dyn DebugDraw, flags: DrawFlags) {
        if flags.shapes || flags.aabbs {
            for (_, body) in self.bodies.iter() {
                if !body.enabled {
                    continue;
                }
                let color = body_color(body);
                for s in &body.shapes {
                    let shape = self.shapes.at(s.index);
                    if flags.shapes {
                        self.draw_geometry(d, &shape.geometry, &body.xf, color);
                    }
                    if flags.aabbs && !shape.geometry.is_unbounded() {
                        draw_aabb(d, &shape.aabb, colors::AABB);
                    }
                }
            }
        }
        if flags.contacts {
            for (_, c) in self.contacts.iter() {
                if !c.touching {
                    continue;
                }
                let mut one = |m: &crate::collision::narrow_phase::Manifold,
                               imp: &[crate::collision::contact::PointImpulse]| {
                    for (k, p) in m.points().iter().enumerate() {
                        d.point(p.point, POINT_SIZE, colors::CONTACT_POINT);
                        d.segment(
                            p.point,
                            p.point + m.normal * CONTACT_NORMAL_LENGTH,
                            colors::CONTACT_NORMAL,
                        );
                        let j = imp[k].normal;
                        if j > 0.0 {
                            d.segment(
                                p.point,
                                p.point + m.normal * (j * IMPULSE_SCALE),
                                colors::CONTACT_IMPULSE,
                            );
                        }
                    }
                };
                one(&c.manifold, &c.impulses);
                if c.multi {
                    for child in &c.more {
                        one(&child.manifold, &child.impulses);
                    }
                }
            }
        }
        if flags.joints {
            for (_, j) in self.joints.pool.iter() {
                if j.broken {
                    continue;
                }
                let a = self.bodies.at(j.a);
                let b = if j.b == crate::dynamics::body::NONE {
                    None
                } else {
                    Some(self.bodies.at(j.b))
                };
                if !a.enabled || b.is_some_and(|b| !b.enabled) {
                    continue;
                }
                let pa = a.xf.apply(j.def.frame_a.p);
                let pb = b.map_or(j.def.frame_b.p, |b| b.xf.apply(j.def.frame_b.p));
                d.segment(a.center, pa, colors::JOINT);
                if let Some(b) = b {
                    d.segment(b.center, pb, colors::JOINT);
                }
                d.segment(pa, pb, colors::JOINT);
                d.point(pa, POINT_SIZE, colors::JOINT);
                d.point(pb, POINT_SIZE, colors::JOINT);
            }
        }
        if flags.centers_of_mass {
            for (_, body) in self.bodies.iter() {
                if body.enabled && body.is_dynamic() {
                    d.transform(Transform::new(body.center, body.xf.q));
                }
            }
        }
    }

    fn draw_geometry(&self, d: &mut dyn DebugDraw, g: &Geometry, xf: &Transform, color: Color) {
        match *g {
            Geometry::Sphere { center, radius } => d.sphere(xf.apply(center), radius, color),
            Geometry::Capsule { a, b, radius } => d.capsule(xf.apply(a), xf.apply(b), radius, color),
            Geometry::Box {
                center,
                rotation,
                half_extents,
            } => {
                let c = box_corners(xf.apply(center), Mat3::from_quat(xf.q * rotation), half_extents);
                for f in BOX_FACES {
                    d.polygon(&[c[f[0]], c[f[1]], c[f[2]], c[f[3]]], color);
                }
            }
            Geometry::Plane { normal, offset } => {
                let n = xf.q * normal;
                let o = xf.apply(normal * offset);
                // Two unit tangents perpendicular to the normal.
                let t = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
                let u = n.cross(t).normalize();
                let v = n.cross(u);
                // The point of the plane nearest the world origin.
                let c = n * n.dot(o);
                let h = PLANE_PATCH_HALF_SIDE;
                d.polygon(
                    &[c + (u + v) * h, c + (v - u) * h, c - (u + v) * h, c + (u - v) * h],
                    color,
                );
            }
            Geometry::Hull { hull, local, scale } => {
                let h = self.geometry.hull_at(hull.index);
                let place = |p: Vec3| xf.apply(local.apply(p * scale));
                let mut face = Vec::with_capacity(16);
                for f in 0..h.faces().len() {
                    face.clear();
                    face.extend(h.face_vertices(f).map(|i| place(h.vertices()[i as usize])));
                    d.polygon(&face, color);
                }
            }
            Geometry::Mesh { mesh, local, scale } => {
                let m = self.geometry.mesh_at(mesh.index);
                for t in 0..m.triangle_count() as u32 {
                    let [a, b, c] = m.triangle(t).map(|p| xf.apply(local.apply(p * scale)));
                    d.polygon(&[a, b, c], color);
                }
            }
            Geometry::Heightfield {
                heightfield,
                local,
                scale,
            } => {
                let hf = self.geometry.heightfield_at(heightfield.index);
                for row in 0..hf.rows().saturating_sub(1) {
                    for column in 0..hf.columns().saturating_sub(1) {
                        if hf.is_hole(row, column) {
                            continue;
                        }
                        for k in 0..2 {
                            let (v, _, _) = hf.triangle(row, column, k, scale);
                            let [a, b, c] = v.map(|p| xf.apply(local.apply(p)));
                            d.polygon(&[a, b, c], color);
                        }
                    }
                }
            }
        }
    }
}
