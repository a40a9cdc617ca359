//! The world: owns bodies, shapes and contacts, and the operations a host performs on them.
//! The step itself is in `step.rs`.

use crate::collision::broad_phase::BroadPhase;
use crate::collision::contact::Contact;
use crate::collision::geometry_store::{ConvexHullHandle, GeometryStore, HeightfieldHandle, MeshHandle};
use crate::collision::heightfield::Heightfield;
use crate::collision::hull::builder::HullSettings;
use crate::collision::hull::ConvexHull;
use crate::collision::mesh::TriangleMesh;
use crate::collision::shape::{Geometry, MassProperties, Shape, ShapeDef};
use crate::dynamics::body::{Body, BodyDef, BodyHandle, BodyType, ShapeHandle, NONE};
use crate::dynamics::contact_wide::Batches;
pub use crate::dynamics::contact_wide::LaneWidth;
use crate::dynamics::solver::SolverScratch;
use crate::error::{
    check_acceleration, check_angular_velocity, check_damping, check_force, check_impulse, check_non_negative,
    check_position, check_velocity, invalid, Error, Result, MAX_ANGULAR_SPEED,
};
use crate::math::{Transform, Vec3};
use crate::pool::{Handle, Pool, WorldTag};

/// How unconstrained bodies are integrated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Semi-implicit (symplectic) Euler, the default.
    SemiImplicitEuler,
    /// Classical fourth-order Runge–Kutta for bodies with no contacts in the step.
    Rk4,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldSettings {
    pub gravity: Vec3,
    /// Solver sub-steps per step.
    pub substeps: u32,
    /// Soft (biased) sweeps over the contacts per sub-step, each followed by the position
    /// update and one rigid relax sweep.
    pub velocity_iterations: u32,
    pub integrator: Integrator,
    pub enable_sleep: bool,
    /// Speed (m/s, and rad/s) below which a body counts as still: an average of its v² + ω²
    /// over the last 0.1 s (half-life, `dynamics/island.rs`) under its square, and its
    /// current speed under twice it.
    pub sleep_threshold: f32,
    /// Seconds an island must stay still before it sleeps.
    pub time_to_sleep: f32,
    /// Stiffness of contacts (Hz; capped at a quarter of the sub-step rate) and their damping
    /// ratio. Overlap under load is `weight / (effective mass · (2π·hertz)²)`.
    pub contact_hertz: f32,
    pub contact_damping_ratio: f32,
    /// Fastest speed at which overlap is pushed apart (m/s).
    pub contact_push_max_velocity: f32,
    /// Approach speed below which contacts do not bounce (m/s).
    pub restitution_threshold: f32,
    /// Overlap allowed without correction (m); keeps resting contacts steady.
    pub linear_slop: f32,
    /// Fastest speed a body's centre of mass may reach (m/s). Every velocity a body gets —
    /// set by the host, from forces, impulses, contacts, joints, particles, soft bodies or a
    /// kinematic target — is capped at it, keeping its direction.
    pub max_linear_speed: f32,
    /// Fastest a body may spin (rad/s), capped the same way. The default, 100π rad/s (50
    /// turns a second), turns a body by at most 0.87 rad per sub-step at 60 Hz with six
    /// sub-steps.
    pub max_angular_speed: f32,
    /// Contact constraints solved at once: eight where the CPU has AVX2 (`Auto`), or four.
    /// Results are bit for bit the same either way.
    pub lane_width: LaneWidth,
    /// Approach speed above which a contact with hit events reports a hit (m/s).
    pub hit_event_threshold: f32,
    /// Threads a step may use, 1..=64 (default 1). Above 1 the world starts `worker_count −
    /// 1` threads of its own, parked between steps, unless the host supplies its job system
    /// with `World::set_task_runner`. Results are bit for bit the same at every count.
    pub worker_count: u32,
}

/// Default `WorldSettings::max_angular_speed`: 100π rad/s.
pub const DEFAULT_MAX_ANGULAR_SPEED: f32 = 100.0 * std::f32::consts::PI;

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            substeps: 6,
            velocity_iterations: 1,
            integrator: Integrator::SemiImplicitEuler,
            enable_sleep: true,
            sleep_threshold: 0.05,
            time_to_sleep: 0.5,
            contact_hertz: 120.0,
            contact_damping_ratio: 10.0,
            contact_push_max_velocity: 3.0,
            restitution_threshold: 1.0,
            linear_slop: 0.0002,
            max_linear_speed: 400.0,
            max_angular_speed: DEFAULT_MAX_ANGULAR_SPEED,
            lane_width: LaneWidth::Auto,
            hit_event_threshold: 1.0,
            worker_count: 1,
        }
    }
}

impl WorldSettings {
    /// Range-checks every setting (README "Supported ranges").
    pub fn validate(&self) -> Result<()> {
        use crate::error::{check_acceleration, check_range, MAX_LENGTH, MAX_SPEED};
        check_acceleration("gravity", self.gravity)?;
        if self.substeps == 0 || self.substeps > 64 {
            return Err(invalid(format!("substeps must be in 1..=64, got {}", self.substeps)));
        }
        if self.velocity_iterations == 0 || self.velocity_iterations > 64 {
            return Err(invalid(format!(
                "velocity_iterations must be in 1..=64, got {}",
                self.velocity_iterations
            )));
        }
        check_range("sleep_threshold", self.sleep_threshold, 0.0, MAX_SPEED, " m/s")?;
        check_non_negative("time_to_sleep", self.time_to_sleep)?;
        // Softness (dynamics/solver.rs) divides by 2·ratio + h·ω: a positive stiffness keeps
        // it away from 0, a bounded ratio keeps it finite.
        check_range("contact_hertz", self.contact_hertz, 1.0e-3, 1.0e6, " Hz")?;
        check_range("contact_damping_ratio", self.contact_damping_ratio, 0.0, 1.0e3, "")?;
        check_range(
            "contact_push_max_velocity",
            self.contact_push_max_velocity,
            1.0e-6,
            MAX_SPEED,
            " m/s",
        )?;
        check_range(
            "restitution_threshold",
            self.restitution_threshold,
            0.0,
            MAX_SPEED,
            " m/s",
        )?;
        check_range("hit_event_threshold", self.hit_event_threshold, 0.0, MAX_SPEED, " m/s")?;
        check_range("linear_slop", self.linear_slop, 0.0, MAX_LENGTH, " m")?;
        if self.worker_count == 0 || self.worker_count > crate::parallel::MAX_WORKERS {
            return Err(invalid(format!(
                "worker_count must be in 1..={}, got {}",
                crate::parallel::MAX_WORKERS,
                self.worker_count
            )));
        }
        check_range("max_linear_speed", self.max_linear_speed, 1.0e-3, MAX_SPEED, " m/s")?;
        check_range(
            "max_angular_speed",
            self.max_angular_speed,
            1.0e-3,
            MAX_ANGULAR_SPEED,
            " rad/s",
        )?;
        Ok(())
    }
}

/// `v` scaled down to length `max` if longer (the solver's speed cap). Its inputs are finite
/// and bounded (an impulse times an inverse mass stays below 1e34), so the length is too.
pub(crate) fn cap_speed(v: Vec3, max: f32) -> Vec3 {
    let l = v.length();
    if l > max {
        v * (max / l)
    } else {
        v
    }
}

/// Margin added around shape boxes in the tree so small motions do not touch it (m).
pub const AABB_MARGIN: f32 = 0.1;

/// Counters of the last step: work done, for tests and profiling.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepCounters {
    pub awake_bodies: usize,
    pub contacts: usize,
    pub touching_contacts: usize,
    pub pairs_tested: usize,
    pub proxies_moved: usize,
}

pub struct World {
    pub settings: WorldSettings,
    pub bodies: Pool<Body>,
    pub shapes: Pool<Shape>,
    pub contacts: Pool<Contact>,
    pub(crate) broad: BroadPhase,
    /// Slot indices of awake bodies (kinematic and dynamic).
    pub(crate) awake_bodies: Vec<u32>,
    /// Slot indices of contacts with at least one awake body.
    pub(crate) awake_contacts: Vec<u32>,
    /// The first body of each sleeping island; the others follow `Body::island_next`.
    pub(crate) islands: Pool<u32>,
    pub(crate) solver: SolverScratch,
    /// Contacts written by contact generators for the current step (cleared each step).
    pub generated_contacts: Vec<crate::collision::contact::GeneratedContact>,
    pub(crate) scratch_wake: Vec<u32>,
    pub(crate) island_scratch: crate::dynamics::island::IslandScratch,
    pub counters: StepCounters,
    /// Force and contact generators (issue 4, `generators/`).
    pub generators: Pool<crate::generators::Generator>,
    pub(crate) generator_scratch: crate::generators::forces::GeneratorScratch,
    /// Springs between bodies and world points for this step's sub-steps.
    pub(crate) body_springs: crate::generators::springs::BodySprings,
    /// The particle world (issue 4, `particles/`).
    pub particles: crate::particles::Particles,
    /// Joints (issue 5, `joints/`).
    pub joints: crate::dynamics::joints::Joints,
    /// Soft bodies (issue 6, `soft/`).
    pub soft_bodies: crate::soft::SoftBodies,
    /// The tag in every id of this world, leased from the process-wide registry (`pool.rs`)
    /// and returned when the world is dropped.
    pub(crate) tag: WorldTag,
    /// Shared geometry used by shapes: convex hulls (issue 13, `collision/geometry_store.rs`).
    pub geometry: GeometryStore,
    /// The last step's events (`events.rs`).
    pub(crate) events: crate::events::Events,
    /// Runs the parallel stages (`parallel/`): `Serial`, the world's own `ThreadPool`, or the
    /// host's job system.
    pub(crate) tasks: Box<dyn crate::parallel::TaskRunner>,
    /// The narrow phase's result per awake contact (`step.rs`, `collide`).
    pub(crate) narrow_results: Vec<u8>,
    /// Per body slot, what `finish_bodies` found this step (`step::REFIT`, `MOVED`,
    /// `WOKEN`); read by the proxy refit and the move events.
    pub(crate) body_marks: Vec<u8>,
}

impl World {
    pub fn new(settings: WorldSettings) -> Result<World> {
        settings.validate()?;
        let lease = WorldTag::acquire().ok_or_else(|| {
            Error::LimitReached(format!(
                "{} worlds are alive at once, the most whose ids can be told apart; destroy one first",
                crate::pool::MAX_LIVE_WORLDS
            ))
        })?;
        let tag = lease.stamp();
        let tasks: Box<dyn crate::parallel::TaskRunner> = if settings.worker_count > 1 {
            Box::new(crate::parallel::ThreadPool::new(settings.worker_count).map_err(|e| {
                Error::LimitReached(format!("could not start {} worker threads: {e}", settings.worker_count))
            })?)
        } else {
            Box::new(crate::parallel::Serial)
        };
        Ok(World {
            settings,
            bodies: Pool::new(tag),
            shapes: Pool::new(tag),
            contacts: Pool::new(tag),
            broad: BroadPhase::default(),
            awake_bodies: Vec::new(),
            awake_contacts: Vec::new(),
            islands: Pool::new(tag),
            solver: SolverScratch {
                batches: Batches::new(settings.lane_width),
                ..SolverScratch::default()
            },
            generated_contacts: Vec::new(),
            scratch_wake: Vec::new(),
            island_scratch: Default::default(),
            counters: StepCounters::default(),
            generators: Pool::new(tag),
            generator_scratch: Default::default(),
            body_springs: Default::default(),
            particles: crate::particles::Particles::new(tag),
            joints: crate::dynamics::joints::Joints::new(tag),
            soft_bodies: crate::soft::SoftBodies::new(tag),
            tag: lease,
            geometry: GeometryStore::new(tag),
            events: Default::default(),
            tasks,
            narrow_results: Vec::new(),
            body_marks: Vec::new(),
        })
    }

    /// Runs the world's parallel stages on `runner` (a host's job system) from the next step
    /// on, replacing the world's own threads. `settings.worker_count` becomes
    /// `runner.worker_count()`. Results do not depend on the runner.
    pub fn set_task_runner(&mut self, runner: Box<dyn crate::parallel::TaskRunner>) -> Result<()> {
        let n = runner.worker_count();
        if n == 0 || n > crate::parallel::MAX_WORKERS {
            return Err(invalid(format!(
                "the task runner's worker_count must be in 1..={}, got {n}",
                crate::parallel::MAX_WORKERS
            )));
        }
        self.settings.worker_count = n;
        self.tasks = runner;
        Ok(())
    }

    // ---------------------------------------------------------------- bodies

    pub fn create_body(&mut self, def: &BodyDef) -> Result<BodyHandle> {
        let def = def.validated(self.settings.max_linear_speed, self.settings.max_angular_speed)?;
        let h = self.bodies.insert(Body::new(&def));
        // Every body could sleep alone: falling asleep and waking never allocate.
        self.islands.reserve_total(self.bodies.len());
        if def.body_type != BodyType::Static {
            if def.awake {
                self.add_awake_body(h.index);
            } else {
                self.put_to_sleep(&[h.index]);
            }
        }
        Ok(h)
    }

    pub fn body(&self, h: BodyHandle) -> Result<&Body> {
        self.bodies.get(h).ok_or(Error::InvalidId("body"))
    }

    pub(crate) fn body_index(&self, h: BodyHandle) -> Result<u32> {
        self.body(h).map(|_| h.index)
    }

    pub fn destroy_body(&mut self, h: BodyHandle) -> Result<()> {
        let index = self.body_index(h)?;
        self.wake_body(index);
        // Joints (issue 5): destroyed with the body; their other bodies are woken.
        self.destroy_body_joints(index);
        // Contacts: wake whoever was touching, then drop.
        while let Some(&c) = self.bodies.at(index).contacts.last() {
            let other = {
                let ct = self.contacts.at(c);
                if ct.body_a == index {
                    ct.body_b
                } else {
                    ct.body_a
                }
            };
            self.wake_body(other);
            self.destroy_contact(c);
        }
        let shapes = std::mem::take(&mut self.bodies.at_mut(index).shapes);
        for s in shapes {
            self.remove_shape_proxy(s.index);
            if let Some(shape) = self.shapes.remove(s) {
                self.geometry.release(&shape.geometry);
            }
        }
        self.remove_awake_body(index);
        self.bodies.remove(h);
        // Generators (issue 4): the body leaves every attachment list and link.
        self.detach_body_everywhere(h);
        // Soft bodies (issue 6): vertices pinned to the body are freed.
        self.unpin_soft_vertices_of(h);
        Ok(())
    }

    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    pub fn transform(&self, h: BodyHandle) -> Result<Transform> {
        Ok(self.body(h)?.xf)
    }

    pub fn set_transform(&mut self, h: BodyHandle, xf: Transform) -> Result<()> {
        let index = self.body_index(h)?;
        check_position("transform.position", xf.p)?;
        let q = crate::error::check_quat("transform.rotation", xf.q)?;
        let xf = Transform::new(xf.p, q);
        let body = self.bodies.at_mut(index);
        body.set_transform(xf);
        body.kinematic_target = None;
        let shapes: Vec<u32> = body.shapes.iter().map(|s| s.index).collect();
        for s in shapes {
            self.refresh_proxy(s, Vec3::ZERO, true);
        }
        self.wake_body(index);
        Ok(())
    }

    /// Kinematic bodies: move to `target` by velocity. The step after this call sets the
    /// velocities that reach the target by the end of that step; the body then sits exactly
    /// on it, its velocities read as those it moved with during that step, and it stops at
    /// the start of the next step (velocities zero) unless given a new target or velocity. A target farther than the
    /// speed limits allow in one step is approached at the limits and kept until reached.
    /// `set_transform` drops a pending target; a pending target overrides velocities set
    /// with `set_linear_velocity` / `set_angular_velocity`.
    pub fn set_kinematic_target(&mut self, h: BodyHandle, target: Transform) -> Result<()> {
        let index = self.body_index(h)?;
        if self.bodies.at(index).body_type != BodyType::Kinematic {
            return Err(invalid("a target transform needs a kinematic body"));
        }
        check_position("target.position", target.p)?;
        let q = crate::error::check_quat("target.rotation", target.q)?;
        self.bodies.at_mut(index).kinematic_target = Some(Transform::new(target.p, q));
        self.wake_body(index);
        Ok(())
    }

    pub fn linear_velocity(&self, h: BodyHandle) -> Result<Vec3> {
        Ok(self.body(h)?.v)
    }

    pub fn angular_velocity(&self, h: BodyHandle) -> Result<Vec3> {
        Ok(self.body(h)?.w)
    }

    /// Sets the linear velocity (m/s, at most `max_linear_speed`; faster is refused). Static
    /// bodies ignore it.
    pub fn set_linear_velocity(&mut self, h: BodyHandle, v: Vec3) -> Result<()> {
        let index = self.body_index(h)?;
        check_velocity("linear velocity", v, self.settings.max_linear_speed)?;
        let max = self.settings.max_linear_speed;
        let body = self.bodies.at_mut(index);
        if body.is_static() {
            return Ok(());
        }
        body.v = crate::dynamics::body::lock_linear(crate::math::clamp_length(v, max), body.locks());
        body.kinematic_stop = false;
        if v != Vec3::ZERO {
            self.wake_body(index);
        }
        Ok(())
    }

    /// Sets the angular velocity (rad/s, at most `max_angular_speed`; faster is refused). Static bodies
    /// ignore it.
    pub fn set_angular_velocity(&mut self, h: BodyHandle, w: Vec3) -> Result<()> {
        let index = self.body_index(h)?;
        check_angular_velocity("angular velocity", w, self.settings.max_angular_speed)?;
        let max = self.settings.max_angular_speed;
        let body = self.bodies.at_mut(index);
        if body.is_static() {
            return Ok(());
        }
        body.w = crate::dynamics::body::lock_angular(crate::math::clamp_length(w, max), body.locks());
        body.kinematic_stop = false;
        if w != Vec3::ZERO {
            self.wake_body(index);
        }
        Ok(())
    }

    /// Runs `act` on a dynamic body that is awake (woken first when `wake`); static and
    /// kinematic bodies, and sleeping ones not woken, are left alone.
    fn act_on_dynamic(&mut self, h: BodyHandle, wake: bool, act: impl FnOnce(&mut Body)) -> Result<()> {
        let i = self.body_index(h)?;
        if !self.bodies.at(i).is_dynamic() {
            return Ok(());
        }
        if wake {
            self.wake_body(i);
        }
        let b = self.bodies.at_mut(i);
        if b.awake {
            act(b);
        }
        Ok(())
    }

    /// Adds a force (N) at the centre of mass until the end of the next step. Wakes the body.
    pub fn apply_force(&mut self, h: BodyHandle, f: Vec3, wake: bool) -> Result<()> {
        check_force("force", f)?;
        self.act_on_dynamic(h, wake, |b| b.add_force_torque(f.as_dvec3(), glam::DVec3::ZERO))
    }

    /// Adds a force (N) at a world point: a force plus the torque of its lever arm.
    pub fn apply_force_at_point(&mut self, h: BodyHandle, f: Vec3, point: Vec3, wake: bool) -> Result<()> {
        check_force("force", f)?;
        check_position("point", point)?;
        self.act_on_dynamic(h, wake, |b| b.add_force_at(f.as_dvec3(), point))
    }

    pub fn apply_torque(&mut self, h: BodyHandle, t: Vec3, wake: bool) -> Result<()> {
        check_force("torque", t)?;
        self.act_on_dynamic(h, wake, |b| b.add_force_torque(glam::DVec3::ZERO, t.as_dvec3()))
    }

    /// Applies an impulse (N·s) at a world point: changes velocity at once, capped at the
    /// speed limits.
    pub fn apply_impulse_at_point(&mut self, h: BodyHandle, j: Vec3, point: Vec3, wake: bool) -> Result<()> {
        check_impulse("impulse", j)?;
        check_position("point", point)?;
        let limits = self.speed_limits();
        self.act_on_dynamic(h, wake, |b| {
            let arm = point.as_dvec3() - b.center.as_dvec3();
            b.apply_impulses(j.as_dvec3(), arm.cross(j.as_dvec3()), limits)
        })
    }

    /// Applies an impulse (N·s) at the centre of mass: changes the linear velocity at once,
    /// capped at `max_linear_speed`.
    pub fn apply_linear_impulse(&mut self, h: BodyHandle, j: Vec3, wake: bool) -> Result<()> {
        check_impulse("impulse", j)?;
        let limits = self.speed_limits();
        self.act_on_dynamic(h, wake, |b| b.apply_impulses(j.as_dvec3(), glam::DVec3::ZERO, limits))
    }

    /// Applies an angular impulse (N·m·s). The new angular velocity is capped at
    /// `max_angular_speed`.
    pub fn apply_angular_impulse(&mut self, h: BodyHandle, j: Vec3, wake: bool) -> Result<()> {
        check_impulse("angular impulse", j)?;
        let limits = self.speed_limits();
        self.act_on_dynamic(h, wake, |b| b.apply_impulses(glam::DVec3::ZERO, j.as_dvec3(), limits))
    }

    /// The world's speed limits: (`max_linear_speed` m/s, `max_angular_speed` rad/s).
    pub fn speed_limits(&self) -> (f32, f32) {
        (self.settings.max_linear_speed, self.settings.max_angular_speed)
    }

    pub fn set_damping(&mut self, h: BodyHandle, linear: f32, angular: f32) -> Result<()> {
        let i = self.body_index(h)?;
        check_damping("linear damping", linear)?;
        check_damping("angular damping", angular)?;
        let b = self.bodies.at_mut(i);
        b.linear_damping = linear;
        b.angular_damping = angular;
        Ok(())
    }

    pub fn set_gravity(&mut self, g: Vec3) -> Result<()> {
        check_acceleration("gravity", g)?;
        self.settings.gravity = g;
        let all: Vec<u32> = self
            .bodies
            .iter()
            .filter(|(_, b)| b.is_dynamic())
            .map(|(h, _)| h.index)
            .collect();
        for i in all {
            self.wake_body(i);
        }
        Ok(())
    }

    pub fn is_awake(&self, h: BodyHandle) -> Result<bool> {
        Ok(self.body(h)?.awake)
    }

    /// Wakes (true) or puts to sleep (false) the body's whole island.
    pub fn set_awake(&mut self, h: BodyHandle, awake: bool) -> Result<()> {
        let i = self.body_index(h)?;
        if awake {
            self.wake_body(i);
        } else if self.bodies.at(i).awake {
            let island = self.island_of(i);
            self.put_to_sleep(&island);
        }
        Ok(())
    }

    // ---------------------------------------------------------------- shapes

    pub fn create_shape(&mut self, body: BodyHandle, def: &ShapeDef, geometry: &Geometry) -> Result<ShapeHandle> {
        let bi = self.body_index(body)?;
        def.validate()?;
        let geometry = geometry.validated()?;
        if geometry.is_unbounded() && def.is_sensor {
            return Err(invalid("a plane cannot be a sensor (use a box)"));
        }
        if geometry.is_unbounded() && !self.bodies.at(bi).is_static() {
            return Err(invalid("a plane can only be attached to a static body"));
        }
        if geometry.is_triangles() && self.bodies.at(bi).is_dynamic() {
            let what = if matches!(geometry, Geometry::Mesh { .. }) {
                "a triangle mesh"
            } else {
                "a heightfield"
            };
            return Err(invalid(format!(
                "{what} can only be attached to a static or kinematic body: it is a surface \
                 without volume, so it gives a dynamic body no mass or inertia (use convex \
                 hulls or primitives for moving bodies)"
            )));
        }
        self.geometry.check(&geometry)?;
        if let Geometry::Hull { hull, scale, .. } = geometry {
            let (lo, hi) = self.geometry.hull(hull)?.local_bounds();
            let extent = (hi - lo).length() * scale;
            if extent < crate::collision::hull::builder::MIN_HULL_EXTENT {
                return Err(invalid(format!(
                    "hull scale {scale} makes the hull {extent} m across; at least {} m is needed",
                    crate::collision::hull::builder::MIN_HULL_EXTENT
                )));
            }
        }
        self.geometry.retain(&geometry);
        let shape = Shape {
            body: bi,
            geometry,
            def: *def,
            proxy: NONE,
            aabb: crate::collision::aabb::Aabb::EMPTY,
            fat_aabb: crate::collision::aabb::Aabb::EMPTY,
            in_move_buffer: false,
            extent: 0.0,
        };
        let h = self.shapes.insert(shape);
        self.bodies.at_mut(bi).shapes.push(h);
        if self.bodies.at(bi).enabled {
            self.add_shape_proxy(h.index);
        }
        self.update_mass(bi);
        self.wake_body(bi);
        Ok(h)
    }

    /// Puts a shape into the broad phase: its box into the tree (queued for new pairs), or a
    /// plane into the plane list.
    pub(crate) fn add_shape_proxy(&mut self, s: u32) {
        let shape = self.shapes.at(s);
        let geometry = shape.geometry;
        let bi = shape.body;
        if geometry.is_unbounded() {
            self.broad.planes.push(s);
        } else {
            let xf = self.bodies.at(bi).xf;
            let tight = geometry.aabb(&self.geometry, &xf);
            let fat = tight.expanded(AABB_MARGIN);
            let proxy = self.broad.tree.create_proxy(fat, s);
            let shape = self.shapes.at_mut(s);
            shape.proxy = proxy;
            shape.aabb = tight;
            shape.fat_aabb = fat;
            self.push_moved(s);
        }
    }

    pub fn destroy_shape(&mut self, h: ShapeHandle) -> Result<()> {
        let s = self.shapes.get(h).ok_or(Error::InvalidId("shape"))?;
        let bi = s.body;
        let doomed: Vec<u32> = self
            .bodies
            .at(bi)
            .contacts
            .iter()
            .copied()
            .filter(|&c| {
                let ct = self.contacts.at(c);
                ct.shape_a == h.index || ct.shape_b == h.index
            })
            .collect();
        for c in doomed {
            let ct = self.contacts.at(c);
            let (a, b) = (ct.body_a, ct.body_b);
            self.wake_body(a);
            self.wake_body(b);
            self.destroy_contact(c);
        }
        self.remove_shape_proxy(h.index);
        if let Some(shape) = self.shapes.remove(h) {
            self.geometry.release(&shape.geometry);
        }
        self.bodies.at_mut(bi).shapes.retain(|&x| x != h);
        self.update_mass(bi);
        self.wake_body(bi);
        Ok(())
    }

    pub fn shape(&self, h: ShapeHandle) -> Result<&Shape> {
        self.shapes.get(h).ok_or(Error::InvalidId("shape"))
    }

    pub(crate) fn remove_shape_proxy(&mut self, s: u32) {
        let shape = self.shapes.at_mut(s);
        if shape.proxy != NONE {
            self.broad.tree.destroy_proxy(shape.proxy);
            shape.proxy = NONE;
        } else {
            self.broad.planes.retain(|&p| p != s);
        }
        if shape.in_move_buffer {
            shape.in_move_buffer = false;
            self.broad.move_buffer.retain(|&m| m != s);
        }
    }

    pub(crate) fn update_mass(&mut self, bi: u32) {
        let body = self.bodies.at(bi);
        let mp = body.mass_override.unwrap_or_else(|| self.shape_mass(bi));
        self.bodies.at_mut(bi).set_mass_properties(mp);
        // Shape extents are measured from the centre of mass, which may have moved.
        let center = self.bodies.at(bi).local_center;
        for k in 0..self.bodies.at(bi).shapes.len() {
            let h = self.bodies.at(bi).shapes[k];
            let shape = self.shapes.get_mut(h).unwrap();
            shape.extent = shape.geometry.extent_from(&self.geometry, center);
        }
    }

    /// The mass properties of a body's shapes at their densities.
    pub(crate) fn shape_mass(&self, bi: u32) -> MassProperties {
        let body = self.bodies.at(bi);
        MassProperties::combine(
            body.shapes
                .iter()
                .map(|s| self.shapes.get(*s).unwrap())
                .filter(|s| !s.def.is_sensor)
                .map(|s| s.geometry.mass_properties(&self.geometry, s.def.density)),
        )
    }

    /// Recomputes a shape's box; if it left its fat box, refit the proxy and queue it for new
    /// pairs. `displacement` sweeps the box along the body's predicted motion.
    pub(crate) fn refresh_proxy(&mut self, s: u32, displacement: Vec3, force: bool) {
        let shape = self.shapes.at(s);
        if shape.proxy == NONE {
            return;
        }
        let xf = self.bodies.at(shape.body).xf;
        let tight = shape.geometry.aabb(&self.geometry, &xf);
        let bb = tight.swept(displacement);
        let proxy = shape.proxy;
        let refit = force || !shape.fat_aabb.contains(&bb);
        let shape = self.shapes.at_mut(s);
        shape.aabb = tight;
        if refit {
            // Sweep one more step of motion ahead, so a fast body refits every other step.
            let fat = bb.swept(displacement).expanded(AABB_MARGIN);
            shape.fat_aabb = fat;
            self.broad.tree.move_proxy(proxy, fat);
            self.push_moved(s);
        }
    }

    pub(crate) fn push_moved(&mut self, s: u32) {
        let shape = self.shapes.at_mut(s);
        if !shape.in_move_buffer {
            shape.in_move_buffer = true;
            self.broad.move_buffer.push(s);
        }
    }

    // ---------------------------------------------------------------- shared geometry

    /// Builds a convex hull from a point cloud (`collision/hull/builder.rs`) and stores it
    /// for shapes to use. Nothing is stored on error.
    pub fn create_convex_hull(&mut self, points: &[Vec3], settings: &HullSettings) -> Result<ConvexHullHandle> {
        let hull = crate::collision::hull::builder::build(points, settings)?;
        Ok(self.geometry.add_hull(hull))
    }

    /// Frees a convex hull; refused (`InvalidArgument`, naming the number of users) while
    /// shapes use it.
    pub fn destroy_convex_hull(&mut self, h: ConvexHullHandle) -> Result<()> {
        self.geometry.remove_hull(h)
    }

    pub fn convex_hull(&self, h: ConvexHullHandle) -> Result<&ConvexHull> {
        self.geometry.hull(h)
    }

    /// Builds a triangle mesh (`collision/mesh/`) from vertices and triangles (copied) and
    /// stores it for shapes to use. Nothing is stored on error.
    pub fn create_mesh(&mut self, vertices: &[Vec3], triangles: &[[u32; 3]]) -> Result<MeshHandle> {
        let mesh = TriangleMesh::new(vertices, triangles)?;
        Ok(self.geometry.add_mesh(mesh))
    }

    /// Frees a triangle mesh; refused (`InvalidArgument`, naming the number of users) while
    /// shapes use it.
    pub fn destroy_mesh(&mut self, h: MeshHandle) -> Result<()> {
        self.geometry.remove_mesh(h)
    }

    pub fn mesh(&self, h: MeshHandle) -> Result<&TriangleMesh> {
        self.geometry.mesh(h)
    }

    /// Builds a heightfield (`collision/heightfield.rs`) of `rows × columns` row-major
    /// heights with optional per-cell holes (copied) and stores it for shapes to use.
    pub fn create_heightfield(
        &mut self,
        rows: u32,
        columns: u32,
        heights: &[f32],
        holes: Option<&[bool]>,
    ) -> Result<HeightfieldHandle> {
        let hf = Heightfield::new(rows, columns, heights, holes)?;
        Ok(self.geometry.add_heightfield(hf))
    }

    /// Frees a heightfield; refused while shapes use it.
    pub fn destroy_heightfield(&mut self, h: HeightfieldHandle) -> Result<()> {
        self.geometry.remove_heightfield(h)
    }

    pub fn heightfield(&self, h: HeightfieldHandle) -> Result<&Heightfield> {
        self.geometry.heightfield(h)
    }

    // ---------------------------------------------------------------- contacts

    pub(crate) fn create_contact(&mut self, sa: u32, sb: u32) {
        // Order so the narrowphase sees the lower shape kind first (it handles either order).
        let key = crate::collision::broad_phase::pair_key(sa, sb);
        if self.broad.pairs.contains_key(&key) {
            return;
        }
        let (a, b) = (self.shapes.at(sa), self.shapes.at(sb));
        let mut contact = Contact::new(&self.geometry, sa, sb, a, b, key);
        contact.event_flags = self.contact_flags(sa, sb);
        let (ba, bb) = (contact.body_a, contact.body_b);
        let h = self.contacts.insert(contact);
        self.broad.pairs.insert(key, h.index);
        self.bodies.at_mut(ba).contacts.push(h.index);
        self.bodies.at_mut(bb).contacts.push(h.index);
        if self.bodies.at(ba).awake || self.bodies.at(bb).awake {
            self.add_awake_contact(h.index);
        }
    }

    pub(crate) fn destroy_contact(&mut self, c: u32) {
        self.contact_events_on_destroy(c);
        let ct = self.contacts.at(c);
        let (ba, bb, key) = (ct.body_a, ct.body_b, ct.key);
        self.remove_awake_contact(c);
        self.broad.pairs.remove(&key);
        for b in [ba, bb] {
            let list = &mut self.bodies.at_mut(b).contacts;
            if let Some(pos) = list.iter().position(|&x| x == c) {
                list.swap_remove(pos);
            }
        }
        let h = self.contacts.handle_at(c).expect("live contact");
        self.contacts.remove(h);
    }

    pub(crate) fn add_awake_contact(&mut self, c: u32) {
        let ct = self.contacts.at_mut(c);
        if ct.awake_index == NONE {
            ct.awake_index = self.awake_contacts.len() as u32;
            self.awake_contacts.push(c);
        }
    }

    pub(crate) fn remove_awake_contact(&mut self, c: u32) {
        let i = self.contacts.at(c).awake_index;
        if i == NONE {
            return;
        }
        self.awake_contacts.swap_remove(i as usize);
        if let Some(&moved) = self.awake_contacts.get(i as usize) {
            self.contacts.at_mut(moved).awake_index = i;
        }
        self.contacts.at_mut(c).awake_index = NONE;
    }

    // ---------------------------------------------------------------- sleep

    pub(crate) fn add_awake_body(&mut self, b: u32) {
        let body = self.bodies.at_mut(b);
        if body.awake_index == NONE {
            body.awake = true;
            body.awake_index = self.awake_bodies.len() as u32;
            self.awake_bodies.push(b);
            // Woken after this step's `finish_bodies`, perhaps: its move is checked in full.
            if let Some(mark) = self.body_marks.get_mut(b as usize) {
                *mark = crate::step::WOKEN;
            }
        }
    }

    pub(crate) fn remove_awake_body(&mut self, b: u32) {
        let body = self.bodies.at_mut(b);
        let i = body.awake_index;
        body.awake = false;
        if i == NONE {
            return;
        }
        body.awake_index = NONE;
        self.awake_bodies.swap_remove(i as usize);
        if let Some(&moved) = self.awake_bodies.get(i as usize) {
            self.bodies.at_mut(moved).awake_index = i;
        }
    }

    /// Wakes a body and everything in its sleeping island; resets the sleep timer if awake.
    pub(crate) fn wake_body(&mut self, b: u32) {
        let body = self.bodies.at_mut(b);
        if body.is_static() || !body.enabled {
            return;
        }
        let threshold = self.settings.sleep_threshold;
        if body.awake {
            body.sleep_time = 0.0;
            body.motion = body.motion.max(2.0 * threshold * threshold);
            return;
        }
        let island = body.sleep_island;
        let (mut m, alone) = match self.islands.remove(island) {
            Some(first) => (first, false),
            None => (b, true),
        };
        while m != NONE {
            let body = self.bodies.at_mut(m);
            let next = if alone { NONE } else { body.island_next };
            body.island_next = NONE;
            body.sleep_island = Handle::NULL;
            body.sleep_time = 0.0;
            body.motion = 2.0 * threshold * threshold;
            self.add_awake_body(m);
            let n = self.bodies.at(m).contacts.len();
            for k in 0..n {
                let c = self.bodies.at(m).contacts[k];
                self.add_awake_contact(c);
            }
            m = next;
        }
    }

    /// Puts a set of (kinematic or dynamic) bodies to sleep as one island.
    pub(crate) fn put_to_sleep(&mut self, members: &[u32]) {
        let Some(&first) = members.first() else {
            return;
        };
        let island = self.islands.insert(first);
        for (k, &m) in members.iter().enumerate() {
            self.remove_awake_body(m);
            let body = self.bodies.at_mut(m);
            body.sleep_island = island;
            body.island_next = members.get(k + 1).copied().unwrap_or(NONE);
            body.v = Vec3::ZERO;
            body.w = Vec3::ZERO;
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
            body.sleep_time = 0.0;
        }
        for &m in members {
            let n = self.bodies.at(m).contacts.len();
            for k in 0..n {
                let c = self.bodies.at(m).contacts[k];
                let ct = self.contacts.at(c);
                if !self.bodies.at(ct.body_a).awake && !self.bodies.at(ct.body_b).awake {
                    self.remove_awake_contact(c);
                }
            }
        }
    }

    /// The bodies connected to `b` through touching contacts and joints (dynamic bodies only).
    fn island_of(&self, b: u32) -> Vec<u32> {
        let mut out = vec![b];
        let mut k = 0;
        while k < out.len() {
            let x = out[k];
            k += 1;
            for &c in &self.bodies.at(x).contacts {
                let ct = self.contacts.at(c);
                if !ct.touching {
                    continue;
                }
                let o = if ct.body_a == x { ct.body_b } else { ct.body_a };
                if self.bodies.at(o).is_dynamic() && !out.contains(&o) {
                    out.push(o);
                }
            }
            // Joints (issue 5) join bodies into one island too.
            for o in self.joint_partners(x) {
                let other = self.bodies.at(o);
                if other.is_dynamic() && other.enabled && !out.contains(&o) {
                    out.push(o);
                }
            }
        }
        out
    }

    /// Number of awake bodies (kinematic and dynamic).
    pub fn awake_body_count(&self) -> usize {
        self.awake_bodies.len()
    }

    /// Contact constraints the solver handles at once (4, or 8 with AVX2).
    pub fn contact_lanes(&self) -> usize {
        self.solver.batches.lanes()
    }

    pub fn contact_count(&self) -> usize {
        self.contacts.len()
    }

    /// The tag carried by every id of this world (1..=4095; no two live worlds share one).
    pub fn tag(&self) -> u32 {
        self.tag.tag()
    }

    pub fn tree_height(&self) -> u32 {
        self.broad.tree.height()
    }

    /// Rebuilds the broad-phase tree top-down with a binned surface-area heuristic (the
    /// incremental inserts of a level load leave it deeper and looser than that). Proxy
    /// ids, fat boxes and contacts are unchanged; later queries and pair searches visit
    /// fewer boxes. New contacts are made in shape order (`step.rs`, `proxy_pairs`), so
    /// bodies move as they would have without it; particles meet shapes in tree order, so
    /// they may not. Allocates scratch; meant for loading time (each step rebuilds the
    /// part above the proxies it moved, `DynamicTree::rebuild_enlarged`).
    pub fn rebuild_broadphase(&mut self) {
        self.broad.tree.rebuild();
    }
}
