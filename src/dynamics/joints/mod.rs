//! Joints between rigid bodies: ball-and-socket (swing cone and twist limits), hinge (limits,
//! motor, spring), fixed (weld), distance (limits, spring) and slider (limits, motor).
//!
//! A joint is an object in the world's joint pool, created from a [`JointDef`]: two bodies
//! (body B may be the null handle: the world), a local frame on each (position and rotation
//! relative to the body origin; for the world, a world-space frame), whether the two bodies
//! collide, and break thresholds. The joint's axis is the **local Z axis of its frames**:
//! the hinge turns about it, the slider moves along it, the ball joint's cone is around it and
//! its twist is about it. Angles and translations are measured from the pose where the two
//! frames coincide.
//!
//! Joints are solved by the same sub-stepped solver as contacts (`solver.rs`): prepared next
//! to the contacts, warm started, solved before the contacts in the biased sweep and in the
//! relax sweep, their impulses stored after the sub-steps. The equality rows of a spanning
//! forest of the joints are solved exactly (`tree.rs`), so heavy loads on light chains do not
//! stretch them; limits, motors and springs are coupled with their joint's equality rows
//! (`rows.rs`); springs are soft by definition.
//!
//! Destroying a body destroys every joint attached to it (their ids become stale; the other
//! body is woken).
//!
//! * `solver.rs` — prepare, warm start, solve, store; the sweep's helpers.
//! * `tree.rs` — the spanning forest and its exact solve of the equality rows.
//! * `rows.rs` — rows in one form: equality rows per joint, coupled scalar rows, small
//!   Cholesky.
//! * `ball.rs`, `hinge.rs`, `fixed.rs`, `distance.rs`, `slider.rs` — one joint type each.

pub mod ball;
pub mod distance;
pub mod fixed;
pub mod hinge;
pub mod rows;
pub mod slider;
pub mod solver;
pub mod tree;

use crate::dynamics::body::NONE;
use crate::error::{check_finite, check_non_negative, check_positive, check_quat, check_vec, invalid, Error, Result};
use crate::math::{Transform, Vec3};
use crate::pool::{Handle, Pool};
use crate::world::World;

pub type JointHandle = Handle;

/// Ball-and-socket: the anchors coincide; optional swing cone and twist limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallParams {
    pub enable_swing_limit: bool,
    /// Half-angle of the cone (rad, 0..=π) the B frame's Z axis may swing in around A's.
    pub swing_limit: f32,
    /// Also keeps the swing within 0.9π (162°): twist is not defined at a half-turn swing.
    pub enable_twist_limit: bool,
    /// Twist about the Z axis (rad, -π..=π, lower <= upper).
    pub lower_twist: f32,
    pub upper_twist: f32,
}

/// Hinge: the anchors coincide and the Z axes stay aligned; B turns about Z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HingeParams {
    pub enable_limit: bool,
    /// Angle limits (rad, -π..=π, lower <= upper).
    pub lower: f32,
    pub upper: f32,
    pub enable_motor: bool,
    /// Target relative angular speed about Z (rad/s).
    pub motor_speed: f32,
    /// Largest torque the motor applies (N·m, >= 0).
    pub max_motor_torque: f32,
    pub enable_spring: bool,
    /// Spring toward angle 0: frequency (Hz, >= 0; 0 = no spring force) and damping ratio.
    pub spring_hertz: f32,
    pub spring_damping_ratio: f32,
}

/// Distance: the anchors stay `length` apart (rigid), or a spring toward `length` within
/// `min_length..=max_length`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceParams {
    /// Rest length (m, >= 0).
    pub length: f32,
    pub enable_limit: bool,
    pub min_length: f32,
    pub max_length: f32,
    pub enable_spring: bool,
    pub spring_hertz: f32,
    pub spring_damping_ratio: f32,
}

/// Slider (prismatic): B keeps A's orientation and moves only along A's Z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderParams {
    pub enable_limit: bool,
    /// Translation limits along Z (m, lower <= upper).
    pub lower: f32,
    pub upper: f32,
    pub enable_motor: bool,
    /// Target relative speed along Z (m/s).
    pub motor_speed: f32,
    /// Largest force the motor applies (N, >= 0).
    pub max_motor_force: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    Ball(BallParams),
    Hinge(HingeParams),
    Fixed,
    Distance(DistanceParams),
    Slider(SliderParams),
}

/// Everything needed to create a joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointDef {
    pub kind: JointKind,
    pub body_a: Handle,
    /// The null handle joins body A to the world; `frame_b` is then in world space.
    pub body_b: Handle,
    /// Joint frame on A, relative to A's origin.
    pub frame_a: Transform,
    /// Joint frame on B, relative to B's origin (or in world space).
    pub frame_b: Transform,
    /// Whether the two bodies' shapes collide with each other (default false).
    pub collide_connected: bool,
    /// Force (N) and torque (N·m) above which the joint breaks (`f32::MAX`: never).
    pub break_force: f32,
    pub break_torque: f32,
}

impl Default for BallParams {
    fn default() -> Self {
        BallParams {
            enable_swing_limit: false,
            swing_limit: 0.25 * std::f32::consts::PI,
            enable_twist_limit: false,
            lower_twist: -0.25 * std::f32::consts::PI,
            upper_twist: 0.25 * std::f32::consts::PI,
        }
    }
}

impl Default for HingeParams {
    fn default() -> Self {
        HingeParams {
            enable_limit: false,
            lower: -0.5 * std::f32::consts::PI,
            upper: 0.5 * std::f32::consts::PI,
            enable_motor: false,
            motor_speed: 0.0,
            max_motor_torque: 0.0,
            enable_spring: false,
            spring_hertz: 0.0,
            spring_damping_ratio: 0.0,
        }
    }
}

impl Default for DistanceParams {
    fn default() -> Self {
        DistanceParams {
            length: 1.0,
            enable_limit: false,
            min_length: 0.0,
            max_length: 1.0e6,
            enable_spring: false,
            spring_hertz: 0.0,
            spring_damping_ratio: 0.0,
        }
    }
}

impl Default for SliderParams {
    fn default() -> Self {
        SliderParams {
            enable_limit: false,
            lower: -1.0,
            upper: 1.0,
            enable_motor: false,
            motor_speed: 0.0,
            max_motor_force: 0.0,
        }
    }
}

impl JointDef {
    /// A def of the given kind with defaults: identity frames, no collision between the
    /// bodies, unbreakable. Set the bodies before creating it.
    pub fn new(kind: JointKind) -> JointDef {
        JointDef {
            kind,
            body_a: Handle::NULL,
            body_b: Handle::NULL,
            frame_a: Transform::IDENTITY,
            frame_b: Transform::IDENTITY,
            collide_connected: false,
            break_force: f32::MAX,
            break_torque: f32::MAX,
        }
    }

    /// Range-checks every number; returns the def with its frame rotations normalised.
    pub fn validated(&self) -> Result<JointDef> {
        let mut d = *self;
        check_vec("frame_a.position", d.frame_a.p)?;
        check_vec("frame_b.position", d.frame_b.p)?;
        d.frame_a.q = check_quat("frame_a.rotation", d.frame_a.q)?;
        d.frame_b.q = check_quat("frame_b.rotation", d.frame_b.q)?;
        check_positive("break_force", d.break_force)?;
        check_positive("break_torque", d.break_torque)?;
        d.kind.validate()?;
        Ok(d)
    }
}

fn check_angle(name: &str, x: f32) -> Result<()> {
    check_finite(name, x)?;
    if x.abs() > std::f32::consts::PI + 1e-6 {
        return Err(invalid(format!("{name} must be within -pi..=pi rad, got {x}")));
    }
    Ok(())
}

fn check_range(lower_name: &str, lower: f32, upper_name: &str, upper: f32) -> Result<()> {
    if lower > upper {
        return Err(invalid(format!(
            "{lower_name} ({lower}) must not be greater than {upper_name} ({upper})"
        )));
    }
    Ok(())
}

/// Angle limits (rad).
pub fn check_angle_limits(lower: f32, upper: f32) -> Result<()> {
    check_angle("lower", lower)?;
    check_angle("upper", upper)?;
    check_range("lower", lower, "upper", upper)
}

/// Translation limits (m).
pub fn check_translation_limits(lower: f32, upper: f32) -> Result<()> {
    check_finite("lower", lower)?;
    check_finite("upper", upper)?;
    check_range("lower", lower, "upper", upper)
}

/// Length limits (m, >= 0).
pub fn check_length_limits(min: f32, max: f32) -> Result<()> {
    check_non_negative("min_length", min)?;
    check_non_negative("max_length", max)?;
    check_range("min_length", min, "max_length", max)
}

/// Motor speed and its largest force or torque (>= 0).
pub fn check_motor(speed: f32, max: f32) -> Result<()> {
    check_finite("motor_speed", speed)?;
    check_non_negative("max motor force/torque", max)
}

/// Spring frequency (Hz) and damping ratio (both >= 0).
pub fn check_spring(hertz: f32, damping_ratio: f32) -> Result<()> {
    check_non_negative("spring_hertz", hertz)?;
    check_non_negative("spring_damping_ratio", damping_ratio)
}

impl JointKind {
    fn validate(&self) -> Result<()> {
        match *self {
            JointKind::Ball(p) => {
                check_finite("swing_limit", p.swing_limit)?;
                if !(0.0..=std::f32::consts::PI + 1e-6).contains(&p.swing_limit) {
                    return Err(invalid(format!(
                        "swing_limit must be within 0..=pi rad, got {}",
                        p.swing_limit
                    )));
                }
                check_angle_limits(p.lower_twist, p.upper_twist)
            }
            JointKind::Hinge(p) => {
                check_angle_limits(p.lower, p.upper)?;
                check_motor(p.motor_speed, p.max_motor_torque)?;
                check_spring(p.spring_hertz, p.spring_damping_ratio)
            }
            JointKind::Fixed => Ok(()),
            JointKind::Distance(p) => {
                check_non_negative("length", p.length)?;
                check_length_limits(p.min_length, p.max_length)?;
                check_spring(p.spring_hertz, p.spring_damping_ratio)
            }
            JointKind::Slider(p) => {
                check_translation_limits(p.lower, p.upper)?;
                check_motor(p.motor_speed, p.max_motor_force)
            }
        }
    }
}

/// Accumulated impulses of a joint's rows (warm started across sub-steps and steps).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Impulses {
    /// Point lock (ball, hinge, fixed): a world vector. Slider: x and y are the two rows
    /// across the axis, along A's frame X and Y (so they turn with A).
    pub linear: Vec3,
    /// Angular lock (fixed, slider): a world vector. Hinge: x and y are the two alignment
    /// rows, along A's frame X and Y.
    pub angular: Vec3,
    /// The distance row (rigid or spring) or the hinge spring.
    pub axial: f32,
    pub motor: f32,
    pub lower: f32,
    pub upper: f32,
    /// The ball joint's swing cone.
    pub cone: f32,
}

pub struct Joint {
    pub def: JointDef,
    /// Slot index of body A and of body B (`NONE`: the world).
    pub(crate) a: u32,
    pub(crate) b: u32,
    pub broken: bool,
    pub(crate) impulses: Impulses,
    /// Force (N) and torque (N·m) the joint applied to body B during the last step, world
    /// frame (the torque excludes the moment of the force about B's anchor).
    pub force: Vec3,
    pub torque: Vec3,
}

impl Joint {
    /// True when the joint filters contacts between its two bodies.
    fn filters(&self) -> bool {
        !self.def.collide_connected && self.b != NONE
    }
}

/// The joint pool, the per-body joint lists, the solver's joint constraints and the broken
/// report of the last step.
pub struct Joints {
    pub pool: Pool<Joint>,
    /// Joints of each body, by body slot index (grown on demand; short lists).
    pub(crate) per_body: Vec<Vec<u32>>,
    pub(crate) constraints: solver::JointSet,
    /// Joints that broke in the last step (valid until the next step).
    pub broken: Vec<JointHandle>,
}

impl Joints {
    pub fn new(tag: u32) -> Joints {
        Joints {
            pool: Pool::new(tag),
            per_body: Vec::new(),
            constraints: solver::JointSet::default(),
            broken: Vec::new(),
        }
    }

    fn list(&self, body: u32) -> &[u32] {
        self.per_body.get(body as usize).map(|v| v.as_slice()).unwrap_or(&[])
    }

    fn list_mut(&mut self, body: u32) -> &mut Vec<u32> {
        if self.per_body.len() <= body as usize {
            self.per_body.resize_with(body as usize + 1, Vec::new);
        }
        &mut self.per_body[body as usize]
    }

    /// False when a joint with `collide_connected == false` joins the two bodies (by slot
    /// index): their shapes must not collide.
    #[inline]
    pub fn should_collide(&self, a: u32, b: u32) -> bool {
        let (la, lb) = (self.list(a), self.list(b));
        let (short, other) = if la.len() <= lb.len() { (la, b) } else { (lb, a) };
        !short.iter().any(|&j| {
            let joint = self.pool.at(j);
            joint.filters() && (joint.a == other || joint.b == other)
        })
    }

    /// Number of live joints.
    pub fn len(&self) -> usize {
        self.pool.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pool.is_empty()
    }
}

impl World {
    /// Creates a joint. Wakes both bodies; when the bodies may not collide, destroys the
    /// contacts between them.
    pub fn create_joint(&mut self, def: &JointDef) -> Result<JointHandle> {
        let def = def.validated()?;
        let a = self.bodies.get(def.body_a).ok_or(Error::InvalidId("body_a"))?;
        let a_index = def.body_a.index;
        let b_index = if def.body_b.is_null() {
            NONE
        } else {
            self.bodies.get(def.body_b).ok_or(Error::InvalidId("body_b"))?;
            def.body_b.index
        };
        if b_index == a_index {
            return Err(invalid("a joint needs two different bodies"));
        }
        let b_static = b_index == NONE || self.bodies.at(b_index).is_static();
        if a.is_static() && b_static {
            return Err(invalid("a joint needs at least one non-static body"));
        }
        let joint = Joint {
            def,
            a: a_index,
            b: b_index,
            broken: false,
            impulses: Impulses::default(),
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
        };
        let filters = joint.filters();
        let h = self.joints.pool.insert(joint);
        self.joints.list_mut(a_index).push(h.index);
        if b_index != NONE {
            self.joints.list_mut(b_index).push(h.index);
        }
        if filters {
            let doomed: Vec<u32> = self
                .bodies
                .at(a_index)
                .contacts
                .iter()
                .copied()
                .filter(|&c| {
                    let ct = self.contacts.at(c);
                    ct.body_a == b_index || ct.body_b == b_index
                })
                .collect();
            for c in doomed {
                self.destroy_contact(c);
            }
        }
        self.wake_body(a_index);
        if b_index != NONE {
            self.wake_body(b_index);
        }
        Ok(h)
    }

    pub fn joint(&self, h: JointHandle) -> Result<&Joint> {
        self.joints.pool.get(h).ok_or(Error::InvalidId("joint"))
    }

    fn joint_mut(&mut self, h: JointHandle) -> Result<&mut Joint> {
        self.joints.pool.get_mut(h).ok_or(Error::InvalidId("joint"))
    }

    /// Destroys a joint and wakes its bodies. Contacts between them come back through the
    /// broad phase once their boxes move.
    pub fn destroy_joint(&mut self, h: JointHandle) -> Result<()> {
        let j = self.joint(h)?;
        let (a, b) = (j.a, j.b);
        for body in [a, b] {
            if body == NONE {
                continue;
            }
            let list = self.joints.list_mut(body);
            if let Some(pos) = list.iter().position(|&x| x == h.index) {
                list.swap_remove(pos);
            }
            self.wake_body(body);
            // Let the broad phase find pairs the joint filtered out.
            let n = self.bodies.at(body).shapes.len();
            for k in 0..n {
                let s = self.bodies.at(body).shapes[k].index;
                if self.shapes.at(s).proxy != NONE {
                    self.push_moved(s);
                }
            }
        }
        self.joints.pool.remove(h);
        Ok(())
    }

    /// Destroys every joint of a body (called by `destroy_body`).
    pub(crate) fn destroy_body_joints(&mut self, body: u32) {
        while let Some(&j) = self.joints.list(body).last() {
            let h = self.joints.pool.handle_at(j).expect("live joint");
            self.destroy_joint(h).expect("live joint");
        }
    }

    /// Wakes a joint's bodies (after a change of its motor, limits or spring).
    fn wake_joint(&mut self, h: JointHandle) -> Result<()> {
        let j = self.joint(h)?;
        let (a, b) = (j.a, j.b);
        self.wake_body(a);
        if b != NONE {
            self.wake_body(b);
        }
        Ok(())
    }

    /// Sets the motor of a hinge (speed in rad/s, torque in N·m) or slider (m/s, N).
    pub fn set_joint_motor(&mut self, h: JointHandle, enable: bool, speed: f32, max: f32) -> Result<()> {
        check_motor(speed, max)?;
        match &mut self.joint_mut(h)?.def.kind {
            JointKind::Hinge(p) => {
                (p.enable_motor, p.motor_speed, p.max_motor_torque) = (enable, speed, max);
            }
            JointKind::Slider(p) => {
                (p.enable_motor, p.motor_speed, p.max_motor_force) = (enable, speed, max);
            }
            _ => return Err(invalid("only hinge and slider joints have a motor")),
        }
        self.wake_joint(h)
    }

    /// The motor of a hinge or slider: (enabled, speed, max torque or force).
    pub fn joint_motor(&self, h: JointHandle) -> Result<(bool, f32, f32)> {
        match self.joint(h)?.def.kind {
            JointKind::Hinge(p) => Ok((p.enable_motor, p.motor_speed, p.max_motor_torque)),
            JointKind::Slider(p) => Ok((p.enable_motor, p.motor_speed, p.max_motor_force)),
            _ => Err(invalid("only hinge and slider joints have a motor")),
        }
    }

    /// Sets the limits: hinge angles (rad), slider translations (m), distance lengths (m),
    /// ball twist angles (rad).
    pub fn set_joint_limits(&mut self, h: JointHandle, enable: bool, lower: f32, upper: f32) -> Result<()> {
        let kind = self.joint(h)?.def.kind;
        match kind {
            JointKind::Hinge(_) | JointKind::Ball(_) => check_angle_limits(lower, upper)?,
            JointKind::Slider(_) => check_translation_limits(lower, upper)?,
            JointKind::Distance(_) => check_length_limits(lower, upper)?,
            JointKind::Fixed => return Err(invalid("a fixed joint has no limits")),
        }
        match &mut self.joint_mut(h)?.def.kind {
            JointKind::Hinge(p) => (p.enable_limit, p.lower, p.upper) = (enable, lower, upper),
            JointKind::Slider(p) => (p.enable_limit, p.lower, p.upper) = (enable, lower, upper),
            JointKind::Distance(p) => (p.enable_limit, p.min_length, p.max_length) = (enable, lower, upper),
            JointKind::Ball(p) => (p.enable_twist_limit, p.lower_twist, p.upper_twist) = (enable, lower, upper),
            JointKind::Fixed => unreachable!(),
        }
        self.wake_joint(h)
    }

    /// The limits as set by `set_joint_limits`: (enabled, lower, upper).
    pub fn joint_limits(&self, h: JointHandle) -> Result<(bool, f32, f32)> {
        match self.joint(h)?.def.kind {
            JointKind::Hinge(p) => Ok((p.enable_limit, p.lower, p.upper)),
            JointKind::Slider(p) => Ok((p.enable_limit, p.lower, p.upper)),
            JointKind::Distance(p) => Ok((p.enable_limit, p.min_length, p.max_length)),
            JointKind::Ball(p) => Ok((p.enable_twist_limit, p.lower_twist, p.upper_twist)),
            JointKind::Fixed => Err(invalid("a fixed joint has no limits")),
        }
    }

    /// Sets the swing cone of a ball joint (half-angle, rad, 0..=π).
    pub fn set_joint_cone_limit(&mut self, h: JointHandle, enable: bool, angle: f32) -> Result<()> {
        check_finite("angle", angle)?;
        if !(0.0..=std::f32::consts::PI + 1e-6).contains(&angle) {
            return Err(invalid(format!("cone angle must be within 0..=pi rad, got {angle}")));
        }
        match &mut self.joint_mut(h)?.def.kind {
            JointKind::Ball(p) => (p.enable_swing_limit, p.swing_limit) = (enable, angle),
            _ => return Err(invalid("only ball joints have a cone limit")),
        }
        self.wake_joint(h)
    }

    /// The swing cone of a ball joint: (enabled, half-angle).
    pub fn joint_cone_limit(&self, h: JointHandle) -> Result<(bool, f32)> {
        match self.joint(h)?.def.kind {
            JointKind::Ball(p) => Ok((p.enable_swing_limit, p.swing_limit)),
            _ => Err(invalid("only ball joints have a cone limit")),
        }
    }

    /// Sets the spring of a hinge (toward angle 0) or distance joint (toward its length).
    pub fn set_joint_spring(&mut self, h: JointHandle, enable: bool, hertz: f32, damping_ratio: f32) -> Result<()> {
        check_spring(hertz, damping_ratio)?;
        match &mut self.joint_mut(h)?.def.kind {
            JointKind::Hinge(p) => {
                (p.enable_spring, p.spring_hertz, p.spring_damping_ratio) = (enable, hertz, damping_ratio)
            }
            JointKind::Distance(p) => {
                (p.enable_spring, p.spring_hertz, p.spring_damping_ratio) = (enable, hertz, damping_ratio)
            }
            _ => return Err(invalid("only hinge and distance joints have a spring")),
        }
        self.wake_joint(h)
    }

    /// The spring of a hinge or distance joint: (enabled, hertz, damping ratio).
    pub fn joint_spring(&self, h: JointHandle) -> Result<(bool, f32, f32)> {
        match self.joint(h)?.def.kind {
            JointKind::Hinge(p) => Ok((p.enable_spring, p.spring_hertz, p.spring_damping_ratio)),
            JointKind::Distance(p) => Ok((p.enable_spring, p.spring_hertz, p.spring_damping_ratio)),
            _ => Err(invalid("only hinge and distance joints have a spring")),
        }
    }

    /// Force (N) and torque (N·m) the joint applied to body B in the last step.
    pub fn joint_force(&self, h: JointHandle) -> Result<(Vec3, Vec3)> {
        let j = self.joint(h)?;
        Ok((j.force, j.torque))
    }

    /// Joints that broke during the last step (valid until the next step).
    pub fn broken_joints(&self) -> &[JointHandle] {
        &self.joints.broken
    }

    /// Slot indices of the bodies joined to `body` by unbroken joints (for islands).
    pub(crate) fn joint_partners(&self, body: u32) -> impl Iterator<Item = u32> + '_ {
        self.joints.list(body).iter().filter_map(move |&j| {
            let joint = self.joints.pool.at(j);
            if joint.broken || joint.b == NONE {
                return None;
            }
            Some(if joint.a == body { joint.b } else { joint.a })
        })
    }
}
