//! Soft bodies: triangle meshes whose vertices are point masses held by springs, with an
//! optional volume constraint and an ideal-gas pressure (P·V = nRT) inside.
//!
//! Each soft body is one object in the world's pool (`SoftBodyHandle`), holding its
//! vertices as dense arrays (positions, velocities, inverse masses), its triangles, its
//! stretch springs (the unique mesh edges, plus the inner springs of a lattice) and its
//! bending springs (between the two vertices opposite each edge shared by two triangles).
//!
//! * `mesh.rs` — helpers: icosphere, box lattice, cloth grid (and their checked forms
//!   with the parameter ranges); edges, bending pairs, closedness and neighbours.
//! * `solver.rs` — the soft-body stage of the step (after the particle stage): XPBD with
//!   sub-steps, the skin's area, two-way impulses with dynamic bodies, pins.
//! * `contact.rs` — vertex contacts with rigid shapes and planes: found once per step,
//!   solved each sub-step, fixed geometry last so it wins over a dynamic body.
//! * `face.rs` — a skin's faces against rigid shapes' corners, edges and thin parts, which
//!   reach through between vertices.
//!
//! **Skins.** A closed mesh with no inner springs (an icosphere, a closed host mesh) is a
//! *skin*, a membrane: its stretch springs resist stretching only (it buckles under
//! compression), an inextensible skin's total area is held at most at its rest area (the
//! uniform tension that holds it against its gas), and shapes are kept out of its faces
//! as well as its vertices.
//!
//! **Pins.** A vertex pinned to the world stays where it was pinned. A vertex pinned to a
//! static or kinematic body follows the body. A vertex pinned to a dynamic body is held at
//! its point by a rigid attachment solved in the soft sub-steps as a two-body constraint:
//! the body feels the soft body's pull (a flag drags its pole), momentum is exchanged both
//! ways. Every free vertex is also tethered (a long-range attachment) to the two pinned
//! vertices nearest to it at rest, no further than its rest distance from each, so a
//! large hanging cloth does not stretch under its own weight. Destroying a body unpins
//! every vertex pinned to it; those vertices then move freely again.

mod contact;
mod face;
pub mod mesh;
pub mod solver;

use crate::error::{check_finite, check_non_negative, check_positive, check_quat, check_vec, invalid, Error, Result};
use crate::math::{Quat, Transform, Vec3};
use crate::pool::{Handle, Pool};
use crate::world::World;
pub use face::FaceContact;
pub use mesh::SoftMesh;

pub type SoftBodyHandle = Handle;

/// Everything about a soft body except its mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoftBodyDef {
    /// Placement of the mesh: vertices are rotated, then moved by `position`.
    pub transform: Transform,
    /// Initial velocity of every vertex (m/s).
    pub velocity: Vec3,
    /// Total mass (kg, > 0), shared equally by the vertices unless per-vertex masses are
    /// given.
    pub mass: f32,
    /// Compliance of the stretch springs (m/N, >= 0; 0 is inextensible). XPBD: the
    /// stiffness does not depend on the time step and any value is stable. A skin's
    /// springs resist stretching only.
    pub edge_compliance: f32,
    /// Compliance of the bending springs (m/N, >= 0); infinity disables bending.
    pub bend_compliance: f32,
    /// Keep the enclosed volume at its rest value (closed meshes).
    pub preserve_volume: bool,
    /// Compliance of the volume constraint (1/(N·m²)... m³/J, >= 0).
    pub volume_compliance: f32,
    /// Gas pressure as n·R·T (J = Pa·m³, >= 0): each face is pushed along its normal by
    /// `nRT / V · area`, V the current enclosed volume.
    pub pressure: f32,
    /// Linear damping of the vertices (1/s, >= 0): slows every motion, like air drag.
    pub damping: f32,
    /// Damping of deformation (1/s, >= 0): each vertex's velocity relaxes at this rate
    /// towards the rigid motion of the whole soft body (its centre's velocity plus its
    /// angular velocity), so wobbling and bouncing on the gas die out while flight and
    /// spin are untouched.
    pub deformation_damping: f32,
    /// Coulomb friction against shapes (>= 0; geometric mean with the shape's).
    pub friction: f32,
    /// Bounce against shapes (>= 0; the larger of the two).
    pub restitution: f32,
    /// Radius of the vertices for collision (m, >= 0).
    pub vertex_radius: f32,
    /// Multiplier of world gravity.
    pub gravity_scale: f32,
    /// XPBD sub-steps per step (1..=64).
    pub substeps: u32,
    /// Gauss–Seidel passes over the stretch springs per sub-step (1..=16). One pass rings
    /// and stretches a large cloth; two hang a 64×64 cloth within 0.5 %.
    pub iterations: u32,
    /// Collide with rigid shapes and planes.
    pub collide: bool,
    pub user_data: u64,
}

impl Default for SoftBodyDef {
    fn default() -> Self {
        SoftBodyDef {
            transform: Transform::new(Vec3::ZERO, Quat::IDENTITY),
            velocity: Vec3::ZERO,
            mass: 1.0,
            edge_compliance: 0.0,
            bend_compliance: 1.0e-2,
            preserve_volume: false,
            volume_compliance: 0.0,
            pressure: 0.0,
            damping: 0.5,
            deformation_damping: 2.0,
            friction: 0.5,
            restitution: 0.0,
            vertex_radius: 0.01,
            gravity_scale: 1.0,
            substeps: 20,
            iterations: 2,
            collide: true,
            user_data: 0,
        }
    }
}

impl SoftBodyDef {
    pub fn validate(&self) -> Result<()> {
        check_vec("position", self.transform.p)?;
        check_quat("rotation", self.transform.q)?;
        check_vec("velocity", self.velocity)?;
        check_positive("mass", self.mass)?;
        check_non_negative("edge_compliance", self.edge_compliance)?;
        if self.bend_compliance.is_nan() || self.bend_compliance < 0.0 {
            return Err(invalid(format!(
                "bend_compliance must be >= 0 (infinity: no bending), got {}",
                self.bend_compliance
            )));
        }
        check_non_negative("volume_compliance", self.volume_compliance)?;
        check_non_negative("pressure", self.pressure)?;
        check_non_negative("damping", self.damping)?;
        check_non_negative("deformation_damping", self.deformation_damping)?;
        check_non_negative("friction", self.friction)?;
        check_non_negative("restitution", self.restitution)?;
        check_non_negative("vertex_radius", self.vertex_radius)?;
        check_finite("gravity_scale", self.gravity_scale)?;
        if !(1..=64).contains(&self.substeps) {
            return Err(invalid(format!("substeps must be in 1..=64, got {}", self.substeps)));
        }
        if !(1..=16).contains(&self.iterations) {
            return Err(invalid(format!(
                "iterations must be in 1..=16, got {}",
                self.iterations
            )));
        }
        Ok(())
    }
}

/// The part of a soft body's definition that may change after creation: stiffness,
/// damping, gas, contact materials, sub-steps (`World::set_soft_body_settings`). Field
/// meanings and ranges as in `SoftBodyDef`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoftBodySettings {
    pub edge_compliance: f32,
    pub bend_compliance: f32,
    pub preserve_volume: bool,
    pub volume_compliance: f32,
    pub pressure: f32,
    pub damping: f32,
    pub deformation_damping: f32,
    pub friction: f32,
    pub restitution: f32,
    pub vertex_radius: f32,
    pub gravity_scale: f32,
    pub substeps: u32,
    pub iterations: u32,
    pub collide: bool,
}

impl SoftBodyDef {
    /// The settings part of the def.
    pub fn settings(&self) -> SoftBodySettings {
        SoftBodySettings {
            edge_compliance: self.edge_compliance,
            bend_compliance: self.bend_compliance,
            preserve_volume: self.preserve_volume,
            volume_compliance: self.volume_compliance,
            pressure: self.pressure,
            damping: self.damping,
            deformation_damping: self.deformation_damping,
            friction: self.friction,
            restitution: self.restitution,
            vertex_radius: self.vertex_radius,
            gravity_scale: self.gravity_scale,
            substeps: self.substeps,
            iterations: self.iterations,
            collide: self.collide,
        }
    }

    /// The def with `settings` in place of its own.
    pub fn with_settings(&self, s: &SoftBodySettings) -> SoftBodyDef {
        SoftBodyDef {
            edge_compliance: s.edge_compliance,
            bend_compliance: s.bend_compliance,
            preserve_volume: s.preserve_volume,
            volume_compliance: s.volume_compliance,
            pressure: s.pressure,
            damping: s.damping,
            deformation_damping: s.deformation_damping,
            friction: s.friction,
            restitution: s.restitution,
            vertex_radius: s.vertex_radius,
            gravity_scale: s.gravity_scale,
            substeps: s.substeps,
            iterations: s.iterations,
            collide: s.collide,
            ..*self
        }
    }
}

/// A vertex pinned to the world (`body` null) or to a body, at `local` in its frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pin {
    pub vertex: u32,
    pub body: Handle,
    /// The pin point: world space for world pins, the body's frame otherwise.
    pub local: Vec3,
}

/// A spring between two vertices with its rest length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Spring {
    pub a: u32,
    pub b: u32,
    pub rest: f32,
    /// Resists stretching only (an edge of a skin: a membrane buckles instead of carrying
    /// compression).
    pub tension_only: bool,
}

/// A tether (long-range attachment): a vertex stays within `max` (its rest distance) of
/// the point of a pin (`pin`: index in `SoftBody::pins`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tether {
    pub vertex: u32,
    pub pin: u32,
    pub max: f32,
}

/// Pinned vertices each free vertex is tethered to (the nearest at rest).
pub(crate) const TETHERS_PER_VERTEX: usize = 2;

/// What a vertex collides with this step: a plane (normal out of the shape) and the pair's
/// materials. Against something that does not respond (a world plane, a static, kinematic
/// or sleeping body) the plane is `n · x = offset` in world space. Against a dynamic body
/// coupled to the stage (`coupled != NONE`) it is kept in the body's frame as it was when
/// found: `n` and the surface point `point` (relative to the centre of mass), so it moves
/// and turns with the body through the sub-steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexContact {
    pub n: Vec3,
    pub offset: f32,
    pub point: Vec3,
    /// Kinematic body slot whose velocity the vertex is measured against, else `NONE`.
    pub body: u32,
    /// Index of the coupled dynamic body in the stage (two-way), else `NONE`.
    pub coupled: u32,
    /// Slot of a sleeping dynamic body it touches (woken when pushed hard), else `NONE`.
    pub sleeper: u32,
    pub friction: f32,
    pub restitution: f32,
    pub active: bool,
}

impl Default for VertexContact {
    fn default() -> Self {
        VertexContact {
            n: Vec3::Y,
            offset: 0.0,
            point: Vec3::ZERO,
            body: crate::dynamics::body::NONE,
            coupled: crate::dynamics::body::NONE,
            sleeper: crate::dynamics::body::NONE,
            friction: 0.0,
            restitution: 0.0,
            active: false,
        }
    }
}

/// One soft body.
pub struct SoftBody {
    pub def: SoftBodyDef,
    pub pos: Vec<Vec3>,
    pub vel: Vec<Vec3>,
    /// Positions at the start of the sub-step.
    pub(crate) prev: Vec<Vec3>,
    /// Inverse masses as created (1/kg).
    pub inv_mass: Vec<f32>,
    /// Inverse masses for the solve: 0 for vertices pinned to the world or to a body that
    /// does not respond (refreshed every step).
    pub(crate) w: Vec<f32>,
    /// Rest positions (the mesh as created, in world space).
    pub(crate) rest: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
    pub(crate) edges: Vec<Spring>,
    pub(crate) bends: Vec<Spring>,
    pub(crate) pins: Vec<Pin>,
    pub(crate) tethers: Vec<Tether>,
    /// How each pin holds its vertex this step (aligned with `pins`).
    pub(crate) pin_at: Vec<solver::PinAt>,
    /// Each vertex's contact with fixed geometry this step (planes, static, kinematic and
    /// sleeping bodies).
    pub contacts: Vec<VertexContact>,
    /// Each vertex's contact with an awake dynamic body this step.
    pub body_contacts: Vec<VertexContact>,
    /// Shapes held out of the faces of a skin this step (`face.rs`).
    pub face_contacts: Vec<face::FaceContact>,
    /// Normal of the fixed geometry each vertex touches in the current sub-step, zero if
    /// none (scratch).
    pub(crate) held: Vec<Vec3>,

    /// Coupled bodies (indices in the stage's list) this soft body acts on this step.
    pub(crate) touching: Vec<u32>,
    /// Velocities before the sub-step's update (scratch, one per vertex).
    pub(crate) old: Vec<Vec3>,
    /// Volume-constraint gradients (scratch, one per vertex).
    pub(crate) grad: Vec<Vec3>,
    /// Enclosed volume at creation (m³).
    pub rest_volume: f32,
    /// Surface area at creation (m²).
    pub rest_area: f32,
    /// A skin: a closed surface (every edge shared by two triangles wound the same way)
    /// with no inner springs, a membrane with an inside and an outside. Its edges resist
    /// stretching only (it buckles instead of carrying compression), its area may not
    /// exceed its rest area when inextensible, and rigid shapes are held out of its faces
    /// as well as its vertices (`face.rs`).
    pub skin: bool,
    /// For a skin, each triangle's neighbours across its edges (`mesh::neighbours`); empty
    /// otherwise.
    pub(crate) neighbours: Vec<[u32; 3]>,
    /// Longest rest length of a stretch spring (m).
    pub(crate) longest_edge: f32,
    /// Impulses applied since the last step, added to velocities at its start (N·s).
    pub(crate) impulses: Vec<Vec3>,
    pub(crate) has_impulses: bool,
}

impl SoftBody {
    pub fn vertex_count(&self) -> usize {
        self.pos.len()
    }

    /// Enclosed volume (m³) of the current positions: the signed sum over triangles, so
    /// it is meaningful for closed, outward-wound meshes.
    pub fn volume(&self) -> f32 {
        volume_of(&self.pos, &self.triangles)
    }

    pub fn total_mass(&self) -> f32 {
        self.inv_mass.iter().map(|&w| if w > 0.0 { 1.0 / w } else { 0.0 }).sum()
    }

    /// Mass-weighted centre (m).
    pub fn center(&self) -> Vec3 {
        let mut m = 0.0;
        let mut c = Vec3::ZERO;
        for (p, &w) in self.pos.iter().zip(&self.inv_mass) {
            if w > 0.0 {
                c += *p / w;
                m += 1.0 / w;
            }
        }
        if m > 0.0 {
            c / m
        } else {
            Vec3::ZERO
        }
    }

    /// Area-weighted vertex normals into `out` (one per vertex; unit, or zero for a vertex
    /// in no triangle).
    pub fn normals_into(&self, out: &mut [Vec3]) {
        for o in out.iter_mut() {
            *o = Vec3::ZERO;
        }
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.pos[i as usize]);
            let n = (b - a).cross(c - a);
            for &i in t {
                out[i as usize] += n;
            }
        }
        for o in out.iter_mut() {
            *o = o.normalize_or_zero();
        }
    }

    /// Rebuilds solve masses and tethers after pins changed: each free vertex is tethered
    /// to its `TETHERS_PER_VERTEX` nearest pinned vertices at rest (ties to the lower pin
    /// index), with its rest distance as the limit. With two or more pins the tethers hold
    /// a vertex on the circle its rest distances allow: a cloth hung by two corners keeps
    /// its top edge straight and every vertex below at its rest depth.
    fn refresh_pins(&mut self) {
        self.w.copy_from_slice(&self.inv_mass);
        for p in &self.pins {
            self.w[p.vertex as usize] = 0.0;
        }
        self.tethers.clear();
        if self.pins.is_empty() {
            return;
        }
        for v in 0..self.pos.len() {
            if self.pins.iter().any(|p| p.vertex as usize == v) {
                continue;
            }
            let mut best = [Tether {
                vertex: v as u32,
                pin: u32::MAX,
                max: f32::MAX,
            }; TETHERS_PER_VERTEX];
            for (k, p) in self.pins.iter().enumerate() {
                let d = self.rest[v].distance(self.rest[p.vertex as usize]);
                if let Some(at) = best.iter().position(|b| d < b.max) {
                    best.copy_within(at..TETHERS_PER_VERTEX - 1, at + 1);
                    best[at] = Tether {
                        vertex: v as u32,
                        pin: k as u32,
                        max: d,
                    };
                }
            }
            self.tethers.extend(best.iter().filter(|t| t.pin != u32::MAX));
        }
    }
}

pub(crate) fn volume_of(pos: &[Vec3], triangles: &[[u32; 3]]) -> f32 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| pos[i as usize]);
            a.dot(b.cross(c))
        })
        .sum::<f32>()
        / 6.0
}

pub(crate) fn area_of(pos: &[Vec3], triangles: &[[u32; 3]]) -> f32 {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| pos[i as usize]);
            (b - a).cross(c - a).length()
        })
        .sum::<f32>()
        * 0.5
}

/// The soft bodies of a world.
pub struct SoftBodies {
    pub(crate) pool: Pool<SoftBody>,
    /// Slots of the live soft bodies, ascending (the stage's deterministic order).
    pub(crate) live: Vec<u32>,
    pub(crate) scratch: solver::SoftScratch,
}

impl SoftBodies {
    pub fn new(tag: u32) -> SoftBodies {
        SoftBodies {
            pool: Pool::new(tag),
            live: Vec::new(),
            scratch: Default::default(),
        }
    }
}

/// Largest mesh accepted (vertices, triangles).
pub const MAX_SOFT_VERTICES: usize = 1 << 20;

impl World {
    /// Creates a soft body from a mesh (in its own frame; `def.transform` places it).
    /// `masses` (kg, one per vertex, each > 0) replaces the equal split of `def.mass`.
    pub fn create_soft_body(
        &mut self,
        def: &SoftBodyDef,
        mesh: &SoftMesh,
        masses: Option<&[f32]>,
    ) -> Result<SoftBodyHandle> {
        def.validate()?;
        let n = mesh.vertices.len();
        if n == 0 || n > MAX_SOFT_VERTICES || mesh.triangles.len() > 2 * MAX_SOFT_VERTICES {
            return Err(invalid(format!(
                "a soft body needs 1..={MAX_SOFT_VERTICES} vertices, got {n}"
            )));
        }
        for (i, v) in mesh.vertices.iter().enumerate() {
            check_vec(&format!("vertices[{i}]"), *v)?;
        }
        for (i, t) in mesh.triangles.iter().enumerate() {
            if t.iter().any(|&k| k as usize >= n) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return Err(invalid(format!(
                    "triangle {i} has an index out of range or repeats a vertex"
                )));
            }
        }
        if mesh.extra_edges.iter().flatten().any(|&k| k as usize >= n) {
            return Err(invalid("an extra edge has an index out of range"));
        }
        let inv_mass: Vec<f32> = match masses {
            Some(m) => {
                if m.len() != n {
                    return Err(invalid(format!("{} masses for {n} vertices", m.len())));
                }
                for (i, &x) in m.iter().enumerate() {
                    check_positive(&format!("masses[{i}]"), x)?;
                }
                m.iter().map(|&x| 1.0 / x).collect()
            }
            None => vec![n as f32 / def.mass; n],
        };
        let q = check_quat("rotation", def.transform.q)?;
        let xf = Transform::new(def.transform.p, q);
        let pos: Vec<Vec3> = mesh.vertices.iter().map(|&v| xf.apply(v)).collect();
        if let Some(i) = pos.iter().position(|p| !p.is_finite()) {
            return Err(invalid(format!(
                "transform.position {} places vertex {i} outside the float range",
                def.transform.p
            )));
        }
        let (edges, bends) = mesh::topology(&mesh.triangles, &mesh.extra_edges);
        let skin = mesh.extra_edges.is_empty() && mesh::is_closed(&mesh.triangles);
        let spring = |e: &[u32; 2]| Spring {
            a: e[0],
            b: e[1],
            rest: pos[e[0] as usize].distance(pos[e[1] as usize]),
            tension_only: false,
        };
        let edges: Vec<Spring> = edges
            .iter()
            .map(|e| Spring {
                tension_only: skin,
                ..spring(e)
            })
            .collect();
        // Built even when bending is off (infinite compliance) so it can be turned on later.
        let bends: Vec<Spring> = bends.iter().map(spring).collect();
        let longest_edge = edges.iter().map(|e| e.rest).fold(0.0, f32::max);
        let rest_volume = volume_of(&pos, &mesh.triangles);
        let rest_area = area_of(&pos, &mesh.triangles);
        let body = SoftBody {
            def: SoftBodyDef { transform: xf, ..*def },
            vel: vec![def.velocity; n],
            prev: pos.clone(),
            w: inv_mass.clone(),
            inv_mass,
            rest: pos.clone(),
            pos,
            triangles: mesh.triangles.clone(),
            edges,
            bends,
            pins: Vec::new(),
            tethers: Vec::new(),
            pin_at: Vec::new(),
            contacts: vec![VertexContact::default(); n],
            body_contacts: vec![VertexContact::default(); n],
            face_contacts: Vec::new(),
            held: vec![Vec3::ZERO; n],
            touching: Vec::new(),
            grad: vec![Vec3::ZERO; n],
            old: vec![Vec3::ZERO; n],
            rest_volume,
            rest_area,
            skin,
            longest_edge,
            neighbours: if skin {
                mesh::neighbours(&mesh.triangles)
            } else {
                Vec::new()
            },
            impulses: vec![Vec3::ZERO; n],
            has_impulses: false,
        };
        let h = self.soft_bodies.pool.insert(body);
        let live = &mut self.soft_bodies.live;
        let at = live.partition_point(|&i| i < h.index);
        live.insert(at, h.index);
        Ok(h)
    }

    pub fn soft_body(&self, h: SoftBodyHandle) -> Result<&SoftBody> {
        self.soft_bodies.pool.get(h).ok_or(Error::InvalidId("soft body"))
    }

    fn soft_body_mut(&mut self, h: SoftBodyHandle) -> Result<&mut SoftBody> {
        self.soft_bodies.pool.get_mut(h).ok_or(Error::InvalidId("soft body"))
    }

    pub fn destroy_soft_body(&mut self, h: SoftBodyHandle) -> Result<()> {
        self.soft_bodies.pool.remove(h).ok_or(Error::InvalidId("soft body"))?;
        self.soft_bodies.live.retain(|&i| i != h.index);
        Ok(())
    }

    pub fn soft_body_count(&self) -> usize {
        self.soft_bodies.pool.len()
    }

    /// Pins `vertex` where it is now: to the world (`body` null) or to a body at the point
    /// it has in the body's frame now. A static or kinematic body carries it along; a
    /// dynamic body is held to it two-way (the body feels the pull). Pinning a pinned vertex
    /// moves its pin.
    pub fn pin_soft_vertex(&mut self, h: SoftBodyHandle, vertex: u32, body: Option<crate::BodyHandle>) -> Result<()> {
        let xf = match body {
            Some(b) => Some(self.body(b)?.xf),
            None => None,
        };
        let s = self.soft_body_mut(h)?;
        let p = *s
            .pos
            .get(vertex as usize)
            .ok_or_else(|| invalid(format!("vertex {vertex} out of range ({})", s.pos.len())))?;
        let pin = Pin {
            vertex,
            body: body.unwrap_or(Handle::NULL),
            local: xf.map_or(p, |xf| xf.apply_inv(p)),
        };
        s.pins.retain(|q| q.vertex != vertex);
        s.pins.push(pin);
        s.vel[vertex as usize] = Vec3::ZERO;
        s.refresh_pins();
        Ok(())
    }

    /// Frees a pinned vertex (a vertex that is not pinned is left as it is).
    pub fn unpin_soft_vertex(&mut self, h: SoftBodyHandle, vertex: u32) -> Result<()> {
        let s = self.soft_body_mut(h)?;
        if vertex as usize >= s.pos.len() {
            return Err(invalid(format!("vertex {vertex} out of range ({})", s.pos.len())));
        }
        s.pins.retain(|q| q.vertex != vertex);
        s.refresh_pins();
        Ok(())
    }

    /// Is `vertex` pinned?
    pub fn soft_vertex_is_pinned(&self, h: SoftBodyHandle, vertex: u32) -> Result<bool> {
        let s = self.soft_body(h)?;
        if vertex as usize >= s.pos.len() {
            return Err(invalid(format!("vertex {vertex} out of range ({})", s.pos.len())));
        }
        Ok(s.pins.iter().any(|p| p.vertex == vertex))
    }

    /// Applies an impulse (N·s) to one vertex (`Some`) or spread over the whole body in
    /// proportion to mass (`None`: every vertex changes velocity by `impulse / mass`).
    /// Acts at the start of the next step; pinned vertices ignore it.
    pub fn apply_soft_impulse(&mut self, h: SoftBodyHandle, vertex: Option<u32>, impulse: Vec3) -> Result<()> {
        crate::error::check_impulse("impulse", impulse)?;
        let s = self.soft_body_mut(h)?;
        match vertex {
            Some(v) => {
                let i = v as usize;
                if i >= s.pos.len() {
                    return Err(invalid(format!("vertex {v} out of range ({})", s.pos.len())));
                }
                s.impulses[i] += impulse;
            }
            None => {
                let m = s.total_mass();
                for (k, &w) in s.inv_mass.iter().enumerate() {
                    if w > 0.0 {
                        s.impulses[k] += impulse / (m * w);
                    }
                }
            }
        }
        s.has_impulses = true;
        Ok(())
    }

    /// Sets the gas pressure n·R·T (J, >= 0).
    pub fn set_soft_pressure(&mut self, h: SoftBodyHandle, pressure: f32) -> Result<()> {
        check_non_negative("pressure", pressure)?;
        self.soft_body_mut(h)?.def.pressure = pressure;
        Ok(())
    }

    /// The settings a soft body runs with now.
    pub fn soft_body_settings(&self, h: SoftBodyHandle) -> Result<SoftBodySettings> {
        Ok(self.soft_body(h)?.def.settings())
    }

    /// Replaces a soft body's settings (stiffness, damping, gas, materials, sub-steps);
    /// they take effect at the next step. Every field is range-checked as at creation and
    /// nothing changes on error.
    pub fn set_soft_body_settings(&mut self, h: SoftBodyHandle, settings: &SoftBodySettings) -> Result<()> {
        let s = self.soft_body_mut(h)?;
        let def = s.def.with_settings(settings);
        def.validate()?;
        s.def = def;
        Ok(())
    }

    /// Called when a body is destroyed: vertices pinned to it are freed.
    pub(crate) fn unpin_soft_vertices_of(&mut self, body: Handle) {
        for &i in &self.soft_bodies.live {
            let s = self.soft_bodies.pool.at_mut(i);
            if s.pins.iter().any(|p| p.body == body) {
                s.pins.retain(|p| p.body != body);
                s.refresh_pins();
            }
        }
    }
}
