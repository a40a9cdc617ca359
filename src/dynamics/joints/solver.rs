//! The joints' part of the sub-stepped solve (Box2D v3 order): `prepare` next to the
//! contacts, then per sub-step `warm_start`, `solve` with bias (before the contacts' soft
//! sweep) and `solve` without bias (the relax sweep, after the positions moved), and `store`
//! after the sub-steps (impulses kept for the next step, applied force and torque, breaking).
//!
//! Anchors and axes are recomputed from each body's motion since the step start (`dp`, `dq`
//! of its `BodyState`) every time a joint is solved, so joints stay stiff while bodies turn.
//! Each sweep solves, joint by joint, the limits, motors and springs (coupled with the joint's
//! equality rows, `rows.rs`) and the equality rows of joints outside the forest as one block
//! each (joints on bodies with locked axes [`LOCKED_ITERATIONS`] times, those of components
//! the forest leaves to Gauss–Seidel [`ITERATED_SWEEPS`] times); then the equality
//! rows of the spanning forest exactly, and the limits and motor of the forest's sliders with
//! their tree's response (`tree.rs`).
//!
//! Rows are fully rigid in the relax sweep. In the biased sweep they are Box2D v3's stiff
//! soft constraint ([`JOINT_STIFFNESS`] of the sub-step rate, damping ratio
//! [`JOINT_DAMPING_RATIO`], correction at most [`MAX_BIAS_SPEED`]): a rigid row with a
//! Baumgarte bias was tried first and a 20-link chain hanging at rest went unstable with any
//! bias (the warm-started impulses pump the chain's axial mode); the soft row's leak damps it.
//! The price is a sag of `load / (effective mass · ω²)`, tiny where the forest's exact
//! effective mass applies. A forest tree with a slider responds rigidly with the same bias in
//! the biased sweep too (`Forest::solve`). Limits are one-sided
//! rows that act speculatively (a gap may close within the sub-step, no more). Motors are
//! velocity rows clamped by their largest force or torque times the sub-step. Springs are
//! soft rows ([`Softness`]) with the spring's own frequency and damping.

use super::rows::Eq;
use super::tree::Forest;
use super::{Impulses, JointKind};
use crate::dynamics::body::{lock_linear, NONE};
use crate::dynamics::solver::{BodySim, BodyState, Softness, Velocity};
use crate::math::{clamp_length, Mat3, Quat, Transform, Vec3};
use crate::world::World;

/// Stiffness of joint rows in the biased sweep as a fraction of the sub-step rate (Hz·s):
/// a quarter, the stiffest Gauss–Seidel stays stable at (measured on a 20-link chain; half
/// the rate already blows a hanging chain up). The sag under load is
/// `load / (effective mass · ω²)`, so more sub-steps make joints stiffer quadratically.
pub const JOINT_STIFFNESS: f32 = 0.25;
/// Damping ratio of joint rows in the biased sweep.
pub const JOINT_DAMPING_RATIO: f32 = 5.0;
/// Largest swing (rad) between the frames' Z axes at which twist is measured: 162°. Past
/// it, twist limits, the hinge's spring and limits rest (see `Frames::twist`).
pub const MAX_TWIST_SWING: f32 = 0.9 * std::f32::consts::PI;
/// `1 + cos(MAX_TWIST_SWING)`.
const TWIST_MIN_COS_SUM: f32 = 0.048_943_35;

/// Fastest speed (m/s, rad/s) at which position error is corrected.
pub const MAX_BIAS_SPEED: f32 = 5.0;
/// Sweeps over the joints in each of the biased and relax passes of a sub-step.
pub const JOINT_ITERATIONS: u32 = 1;

/// One joint prepared for the step.
#[derive(Clone, Copy, Debug)]
pub struct JointConstraint {
    /// Slot of the joint in the pool.
    pub joint: u32,
    /// Solver indices of the two bodies (0: static, sleeping or the world).
    pub ia: u32,
    pub ib: u32,
    /// Joint frames at the step start: positions relative to each body's centre of mass and
    /// rotations, both in world orientation.
    pub frame_a: Transform,
    pub frame_b: Transform,
    /// `center_b - center_a` at the step start.
    pub delta_center: Vec3,
    pub kind: JointKind,
    pub imp: Impulses,
    /// The spring's soft coefficients for this step's sub-step (hinge, distance).
    pub spring: Softness,
    /// The equality rows are solved by the direct tree solve (`tree.rs`), not here.
    pub tree: bool,
    /// The joint's component of the joint graph is solved here alone, not by the forest
    /// (`Forest::build`), with [`ITERATED_SWEEPS`] sweeps per pass.
    pub iterated: bool,
    /// Where the slider's linear rows act, from A's centre of mass (0) to B's (1) (see
    /// [`SliderRows`]).
    pub slider_point: f32,
}

/// This step's joint constraints and the spanning forest of their direct solve.
#[derive(Default)]
pub struct JointSet {
    pub list: Vec<JointConstraint>,
    pub forest: Forest,
}

/// The joint frames now: arms from the centres of mass, the anchor separation
/// `d = anchor_b - anchor_a`, and the frame rotations.
#[derive(Clone, Copy, Debug)]
pub struct Frames {
    pub ra: Vec3,
    pub rb: Vec3,
    pub d: Vec3,
    pub qa: Quat,
    pub qb: Quat,
    /// See `JointConstraint::slider_point`.
    pub slider_point: f32,
}

impl Frames {
    pub(crate) fn new(c: &JointConstraint, sa: &BodyState, sb: &BodyState) -> Frames {
        let ra = sa.dq() * c.frame_a.p;
        let rb = sb.dq() * c.frame_b.p;
        Frames {
            ra,
            rb,
            d: c.delta_center + sb.dp() - sa.dp() + rb - ra,
            qa: sa.dq() * c.frame_a.q,
            qb: sb.dq() * c.frame_b.q,
            slider_point: c.slider_point,
        }
    }

    /// The slider's linear rows (across and along its axis): directions, position errors
    /// and where they act. See [`SliderRows`].
    pub fn slider(&self) -> SliderRows {
        let centers = self.d + self.ra - self.rb;
        let w = self.slider_point;
        if w == 0.0 {
            // At A's centre; A's frame turned onto B's about A's centre.
            let turn = self.qb * self.qa.conjugate();
            SliderRows {
                axes: [self.qb * Vec3::X, self.qb * Vec3::Y, self.qb * Vec3::Z],
                offset: centers + self.rb - turn * self.ra,
                lever_a: Vec3::ZERO,
                lever_b: -centers,
            }
        } else if w == 1.0 {
            // At B's centre; B's frame turned onto A's about B's centre.
            let turn = self.qa * self.qb.conjugate();
            SliderRows {
                axes: [self.qa * Vec3::X, self.qa * Vec3::Y, self.qa * Vec3::Z],
                offset: centers + turn * self.rb - self.ra,
                lever_a: centers,
                lever_b: Vec3::ZERO,
            }
        } else {
            // Between the centres; the turn of the lever arms to first order: the offset at
            // B's anchor, less what the rotation rows will take off it about that point.
            let lever_a = w * centers;
            let rot = self.rotation_error();
            let shift = self.ra + self.d - lever_a;
            SliderRows {
                axes: [self.qa * Vec3::X, self.qa * Vec3::Y, self.qa * Vec3::Z],
                offset: self.d + shift.cross(rot),
                lever_a,
                lever_b: lever_a - centers,
            }
        }
    }

    /// The Z axes of the two frames (the joint axis).
    #[inline]
    pub fn axes(&self) -> (Vec3, Vec3) {
        (self.qa * Vec3::Z, self.qb * Vec3::Z)
    }

    /// A's frame X and Y axes: the directions of the hinge's alignment rows and the
    /// slider's cross-axis rows (their impulses are kept as coordinates along these).
    #[inline]
    pub fn cross_axes(&self) -> [Vec3; 2] {
        [self.qa * Vec3::X, self.qa * Vec3::Y]
    }

    /// A vector with coordinates `c.x`, `c.y` along A's frame X and Y axes.
    #[inline]
    pub fn from_cross(&self, c: Vec3) -> Vec3 {
        let [x, y] = self.cross_axes();
        c.x * x + c.y * y
    }

    /// The twist of B's frame about Z relative to A's (the twist of the swing–twist
    /// decomposition of the relative rotation): the angle (rad, -π..=π) and the angular
    /// row of its rate, `(za + zb) / (1 + za·zb)`, so that `d(angle)/dt = row · (wb − wa)`
    /// exactly at any swing. `None` where the twist is not defined well: B's Z axis turned
    /// more than [`MAX_TWIST_SWING`] from A's (at half a turn the decomposition is singular
    /// and the angle jumps; a limit there kicked the body into a spin).
    pub fn twist(&self) -> Option<(f32, Vec3)> {
        let (za, zb) = self.axes();
        let c = 1.0 + za.dot(zb);
        if c < TWIST_MIN_COS_SUM {
            return None;
        }
        let q = self.qa.conjugate() * self.qb;
        Some((wrap_angle(2.0 * q.z.atan2(q.w)), (za + zb) / c))
    }

    /// The rotation from A's frame to B's as a rotation vector (small-angle form).
    pub fn rotation_error(&self) -> Vec3 {
        let mut q = self.qb * self.qa.conjugate();
        if q.w < 0.0 {
            q = -q;
        }
        2.0 * Vec3::new(q.x, q.y, q.z)
    }
}

fn wrap_angle(a: f32) -> f32 {
    use std::f32::consts::PI;
    if a > PI {
        a - 2.0 * PI
    } else if a < -PI {
        a + 2.0 * PI
    } else {
        a
    }
}

/// The slider's linear rows. The constraint is "B's anchor stays on A's axis, B keeps A's
/// rotation"; with the rotation locked by the three angular rows, the linear rows may act
/// at any point without changing what they allow (adding multiples of the angular rows and
/// their errors to them cancels out). They act at a point between the centres of mass
/// (`JointConstraint::slider_point`) chosen to keep the solve well conditioned however far
/// apart the anchors are: the child's centre in the forest, else a point that decouples
/// them from the angular rows (in proportion to the bodies' inverse inertias; the centre of
/// a body joined to the ground). At B's anchor, a body 500 m along a rail had the rail's
/// force at a 500 m lever cancelled by the angular rows' torque in f32, and the solve blew
/// up.
///
/// Against the ground (one body's centre), the position errors are measured as if that
/// body were already turned onto the other's frame about its centre — the error the
/// rotation rows leave to them — so they do not depend on its rotation at all, exactly at
/// any misalignment, and the rows (along the other body's axes) are their exact Jacobians.
/// Measured in the turning frame instead, a slider set up half a turn off its rest pose was
/// pushed across an axis that then turned under it, and ended up sliding at 19 m/s.
/// Between two dynamic bodies the same holds to first order in the rotation error.
#[derive(Clone, Copy, Debug)]
pub struct SliderRows {
    /// The frame's X and Y axes (the rows across the axis) and its Z axis (the slider axis).
    pub axes: [Vec3; 3],
    /// B's anchor relative to A's, after the pivot's turn: errors `axes[k] · offset` across
    /// the axis, translation `axes[2] · offset` along it.
    pub offset: Vec3,
    /// Lever arms of the rows on A and on B (one of them zero).
    pub lever_a: Vec3,
    pub lever_b: Vec3,
}

/// The two bodies' velocities and inverse masses while one joint is solved.
pub struct Bodies {
    pub va: Vec3,
    pub wa: Vec3,
    pub vb: Vec3,
    pub wb: Vec3,
    /// Inverse masses per world axis: zero along locked axes (`body::LOCK_*`).
    pub ma: Vec3,
    pub mb: Vec3,
    pub ia: Mat3,
    pub ib: Mat3,
    /// Either body has locked axes: singular blocks drop their dependent rows.
    pub locked: bool,
    /// With `locked`: each body's inverse mass and mean inverse inertia as if nothing were
    /// locked (`BodyState::free_inv_i`; the real ones for a body without locks).
    pub free_a: (f32, f32),
    pub free_b: (f32, f32),
}

/// The sweep being run, and how its rigid rows respond: in the biased sweep a stiff soft
/// constraint (Box2D v3's joint softness: the position error is fed back at the spring's rate,
/// the response is scaled and part of the accumulated impulse leaks, which damps the chain
/// modes a rigid Baumgarte feedback excites), in the relax sweep fully rigid without bias.
#[derive(Clone, Copy, Debug)]
pub struct Ctx {
    pub inv_h: f32,
    pub h: f32,
    pub use_bias: bool,
    pub soft: Softness,
}

impl Ctx {
    pub fn new(h: f32, use_bias: bool) -> Ctx {
        let soft = if use_bias {
            Softness::new(JOINT_STIFFNESS / h, JOINT_DAMPING_RATIO, h)
        } else {
            Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            }
        };
        Ctx {
            inv_h: 1.0 / h,
            h,
            use_bias,
            soft,
        }
    }

    /// Velocity bias of a rigid row with position error `c` (the row drives `c` to 0).
    #[inline]
    pub fn rigid_bias(&self, c: f32) -> f32 {
        (self.soft.bias_rate * c).clamp(-MAX_BIAS_SPEED, MAX_BIAS_SPEED)
    }

    /// The same for a vector error.
    #[inline]
    pub fn rigid_bias_vec(&self, c: Vec3) -> Vec3 {
        (self.soft.bias_rate * c).clamp_length_max(MAX_BIAS_SPEED)
    }

    /// The impulse of a rigid row: `rigid` is the full response `-m (cdot + bias)`.
    #[inline]
    pub fn respond(&self, rigid: f32, acc: f32) -> f32 {
        self.soft.mass_scale * rigid - self.soft.impulse_scale * acc
    }

    #[inline]
    pub fn respond_vec(&self, rigid: Vec3, acc: Vec3) -> Vec3 {
        self.soft.mass_scale * rigid - self.soft.impulse_scale * acc
    }

    /// Solves a one-sided row (`c >= 0`, impulse >= 0): speculative while apart (the gap may
    /// close within the sub-step), soft push-out in the biased sweep, rigid in the relax
    /// sweep. Returns the impulse change.
    #[inline]
    pub fn limit(&self, mass: f32, cdot: f32, c: f32, acc: &mut f32) -> f32 {
        // No leak of the accumulated impulse here: a limit row sees only the angular (or
        // linear) mass at its own axis, so a leak there sags by the whole mass ratio to the
        // body's inertia about the anchor (0.04 rad for an arm held at its limit).
        let imp = if c > 0.0 {
            -mass * (cdot + c * self.inv_h)
        } else {
            -self.soft.mass_scale * mass * (cdot + self.rigid_bias(c))
        };
        clamp_positive(acc, imp)
    }
}

/// The impulses of a joint as one linear impulse on B (−p on A) and angular impulses on each
/// body including the moments of `p` (A's is subtracted).
#[derive(Clone, Copy, Debug, Default)]
pub struct Wrench {
    pub p: Vec3,
    pub ta: Vec3,
    pub tb: Vec3,
}

impl Bodies {
    #[inline]
    pub fn apply(&mut self, w: &Wrench) {
        self.va -= self.ma * w.p;
        self.wa -= self.ia * w.ta;
        self.vb += self.mb * w.p;
        self.wb += self.ib * w.tb;
    }
}

impl Bodies {
    /// The point rows as one 3×3 block (the anchors coincide), for a ball joint outside the
    /// forest; the same as `Eq::solve_block` on its three rows.
    fn solve_point(&mut self, f: &Frames, acc: &mut Vec3, ctx: &Ctx) {
        let cdot = self.vb + self.wb.cross(f.rb) - self.va - self.wa.cross(f.ra);
        let bias = Vec3::new(ctx.rigid_bias(f.d.x), ctx.rigid_bias(f.d.y), ctx.rigid_bias(f.d.z));
        let (sa, sb) = (skew(f.ra), skew(f.rb));
        let k = Mat3::from_diagonal(self.ma + self.mb) - sa * self.ia * sa - sb * self.ib * sb;
        let det = k.determinant();
        let rhs = -(cdot + bias);
        let x = if det.abs() > f32::MIN_POSITIVE && det.is_finite() {
            k.inverse() * rhs
        } else {
            return;
        };
        let imp = ctx.respond_vec(x, *acc);
        *acc += imp;
        self.va -= self.ma * imp;
        self.wa -= self.ia * f.ra.cross(imp);
        self.vb += self.mb * imp;
        self.wb += self.ib * f.rb.cross(imp);
    }
}

/// The cross-product matrix: `skew(r) v = r × v`.
#[inline]
fn skew(r: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, r.z, -r.y),
        Vec3::new(-r.z, 0.0, r.x),
        Vec3::new(r.y, -r.x, 0.0),
    )
}

/// Adds `imp` to a non-negative accumulated impulse; returns the change actually applied.
#[inline]
pub fn clamp_positive(acc: &mut f32, imp: f32) -> f32 {
    let new = (*acc + imp).max(0.0);
    let delta = new - *acc;
    *acc = new;
    delta
}

/// Solves a soft (spring) row: `mass` effective mass, `cdot` relative speed, `c` position
/// error; returns the impulse change.
#[inline]
pub fn soft_impulse(s: &Softness, mass: f32, cdot: f32, c: f32, acc: &mut f32) -> f32 {
    let imp = -s.mass_scale * mass * (cdot + s.bias_rate * c) - s.impulse_scale * *acc;
    *acc += imp;
    imp
}

/// Builds this step's joint constraints: every unbroken joint with an awake body. Clears the
/// broken report of the previous step.
pub fn prepare(world: &mut World, h: f32) {
    let World {
        joints, bodies, solver, ..
    } = world;
    joints.broken.clear();
    let set = &mut joints.constraints;
    set.list.clear();
    let states = &solver.states;
    for (handle, joint) in joints.pool.iter() {
        if joint.broken {
            continue;
        }
        let ba = bodies.at(joint.a);
        // A joint to a disabled body is inactive until the body is enabled again.
        if !ba.enabled || (joint.b != NONE && !bodies.at(joint.b).enabled) {
            continue;
        }
        let ia = if ba.awake { ba.solver_index } else { 0 };
        let (ib, center_b, frame_b) = if joint.b == NONE {
            (0, Vec3::ZERO, joint.def.frame_b)
        } else {
            let bb = bodies.at(joint.b);
            let ib = if bb.awake { bb.solver_index } else { 0 };
            let frame = Transform::new(
                bb.xf.q * (joint.def.frame_b.p - bb.local_center),
                bb.xf.q * joint.def.frame_b.q,
            );
            (ib, bb.center, frame)
        };
        if ia == 0 && ib == 0 {
            continue;
        }
        if states[ia as usize].inv_mass == 0.0 && states[ib as usize].inv_mass == 0.0 {
            continue;
        }
        let frame_a = Transform::new(
            ba.xf.q * (joint.def.frame_a.p - ba.local_center),
            ba.xf.q * joint.def.frame_a.q,
        );
        let spring = match joint.def.kind {
            JointKind::Hinge(p) if p.enable_spring => Softness::new(p.spring_hertz, p.spring_damping_ratio, h),
            JointKind::Distance(p) if p.enable_spring => Softness::new(p.spring_hertz, p.spring_damping_ratio, h),
            _ => Softness::default(),
        };
        let mut imp = joint.impulses;
        clear_disabled(&joint.def.kind, &mut imp);
        // The slider's linear rows act between the centres, in proportion to the bodies'
        // inverse inertias (a rotation-invariant measure: the trace; ground bodies have
        // none): at the centre of a body joined to the ground. The forest moves them to the
        // child's centre for its joints (`Forest::build`).
        let trace = |s: &BodyState| {
            let m = s.inv_i();
            m.x_axis.x + m.y_axis.y + m.z_axis.z
        };
        let (ta, tb) = (trace(&states[ia as usize]), trace(&states[ib as usize]));
        let slider_point = if tb <= 0.0 {
            0.0
        } else if ta <= 0.0 {
            1.0
        } else {
            tb / (ta + tb)
        };
        set.list.push(JointConstraint {
            joint: handle.index,
            ia,
            ib,
            frame_a,
            frame_b,
            delta_center: center_b - ba.center,
            kind: joint.def.kind,
            imp,
            spring,
            tree: false,
            iterated: false,
            slider_point,
        });
    }
    set.forest.build(&mut set.list, states);
}

/// Zeroes the impulses of rows that are switched off (a limit, motor or spring disabled
/// since the last step).
fn clear_disabled(kind: &JointKind, imp: &mut Impulses) {
    match kind {
        JointKind::Ball(p) => {
            if super::ball::cone_angle(p).is_none() {
                imp.cone = 0.0;
            }
            if !p.enable_twist_limit {
                (imp.lower, imp.upper) = (0.0, 0.0);
            }
        }
        JointKind::Hinge(p) => {
            if !(p.enable_spring && p.spring_hertz > 0.0) {
                imp.axial = 0.0;
            }
            if !p.enable_motor {
                imp.motor = 0.0;
            }
            if !p.enable_limit {
                (imp.lower, imp.upper) = (0.0, 0.0);
            }
        }
        JointKind::Fixed => {}
        JointKind::Distance(p) => {
            if p.enable_spring && p.spring_hertz == 0.0 {
                imp.axial = 0.0;
            }
            if !(p.enable_spring && p.enable_limit) {
                (imp.lower, imp.upper) = (0.0, 0.0);
            }
        }
        JointKind::Slider(p) => {
            if !p.enable_motor {
                imp.motor = 0.0;
            }
            if !p.enable_limit {
                (imp.lower, imp.upper) = (0.0, 0.0);
            }
        }
    }
}

/// True when the joint has rows besides its equality rows (limits, motor, spring).
pub(super) fn has_scalar_rows(kind: &JointKind) -> bool {
    match kind {
        JointKind::Ball(p) => super::ball::has_limits(p),
        JointKind::Hinge(p) => super::hinge::has_axial_rows(p),
        JointKind::Fixed => false,
        JointKind::Distance(p) => p.enable_spring,
        JointKind::Slider(p) => super::slider::has_axial_rows(p),
    }
}

/// Bodies touched by a joint are not integrated by RK4 (they are constrained).
pub fn mark_constrained(set: &JointSet, sims: &mut [BodySim]) {
    for c in &set.list {
        sims[c.ia as usize].rk4 = false;
        sims[c.ib as usize].rk4 = false;
    }
}

#[inline]
pub(crate) fn load(c: &JointConstraint, vel: &[Velocity], states: &[BodyState]) -> (Bodies, Frames) {
    let (sa, sb) = (&states[c.ia as usize], &states[c.ib as usize]);
    let (ua, ub) = (&vel[c.ia as usize], &vel[c.ib as usize]);
    (
        Bodies {
            va: ua.v,
            wa: ua.w,
            vb: ub.v,
            wb: ub.w,
            ma: lock_linear(Vec3::splat(sa.inv_mass), sa.locks),
            mb: lock_linear(Vec3::splat(sb.inv_mass), sb.locks),
            ia: sa.inv_i(),
            ib: sb.inv_i(),
            locked: sa.locks | sb.locks != 0,
            free_a: free_size(sa),
            free_b: free_size(sb),
        },
        Frames::new(c, sa, sb),
    )
}

/// A body's inverse mass and a mean inverse inertia as if nothing were locked.
#[inline]
fn free_size(s: &BodyState) -> (f32, f32) {
    if s.locks != 0 {
        (s.inv_mass, s.free_inv_i)
    } else {
        let m = s.inv_i();
        (s.inv_mass, (m.x_axis.x + m.y_axis.y + m.z_axis.z) / 3.0)
    }
}

/// Writes the velocities back to the dynamic bodies: index 0 (static, sleeping, the world)
/// and kinematic bodies (no inverse mass) keep theirs — a joint never changes them.
#[inline]
pub(crate) fn write(c: &JointConstraint, b: &Bodies, vel: &mut [Velocity]) {
    if c.ia != 0 && (b.ma != Vec3::ZERO || b.ia != Mat3::ZERO) {
        vel[c.ia as usize] = Velocity::new(b.va, b.wa);
    }
    if c.ib != 0 && (b.mb != Vec3::ZERO || b.ib != Mat3::ZERO) {
        vel[c.ib as usize] = Velocity::new(b.vb, b.wb);
    }
}

fn wrench(c: &JointConstraint, f: &Frames) -> Wrench {
    match c.kind {
        JointKind::Ball(p) => super::ball::wrench(&p, &c.imp, f),
        JointKind::Hinge(_) => super::hinge::wrench(&c.imp, f),
        JointKind::Fixed => super::fixed::wrench(&c.imp, f),
        JointKind::Distance(_) => super::distance::wrench(&c.imp, f),
        JointKind::Slider(_) => super::slider::wrench(&c.imp, f),
    }
}

/// Applies the accumulated impulses at the current anchors (start of each sub-step), then
/// leaves the bodies within the speed limits (`limits`: `max_linear_speed`,
/// `max_angular_speed`), as the integration before it does.
///
/// The impulses were found at last sub-step's anchors; on a body of a few milligrams hinged
/// a metre off its centre (inverse inertia 6e11) next to a heavy one, the turn since moves
/// them enough that re-applying them spun the light body ever faster (1e7 rad/s, then 1e25
/// two sub-steps later, then NaN: fuzzer seeds 2 and 3). Capped, the sweeps that follow
/// start from a bounded state.
///
/// The cap applies to each body once all its joints' impulses are in, not joint by joint.
/// A light link between joints that hold a load at a long lever takes large, opposite
/// impulses from them (a 0.6 m link hinged to the world, holding sliders whose children are
/// 200 m along their rails: the hinge's angular impulse alone spins it past the 100π rad/s
/// cap, the slider's takes that back to the chain's slow turn; in 10 s of such a chain the
/// cap cut in after a joint hundreds to thousands of times). Capped after
/// the first joint, the part cut off was never given back: the warm start then changed the
/// velocities by something no joint's rows span, which even an exact solve of the rows keeps,
/// and chains with two unlimited sliders gained energy every sub-step (×3,900 of the scale,
/// `tests/slider_chains.rs`).
pub fn warm_start(set: &JointSet, vel: &mut [Velocity], states: &[BodyState], limits: (f32, f32)) {
    for c in &set.list {
        let (mut b, f) = load(c, vel, states);
        b.apply(&wrench(c, &f));
        write(c, &b, vel);
    }
    for c in &set.list {
        for k in [c.ia, c.ib] {
            let s = &states[k as usize];
            // As `write`: the dynamic bodies, whose velocities a joint changes.
            if k != 0 && (s.inv_mass != 0.0 || s.inv_i() != Mat3::ZERO) {
                let u = &mut vel[k as usize];
                *u = Velocity::new(clamp_length(u.v, limits.0), clamp_length(u.w, limits.1));
            }
        }
    }
}

/// One sweep over the joints: with position bias (`use_bias`, the biased sweep) or without
/// (the relax sweep, which follows a position update). Limits, motors and springs first, and
/// the equality rows of joints outside the forest as one block each; then the forest's
/// equality rows by the direct solve, and its sliders' limits and motors.
pub fn solve(set: &mut JointSet, vel: &mut [Velocity], states: &[BodyState], h: f32, use_bias: bool) {
    let ctx = Ctx::new(h, use_bias);
    for iteration in 0..JOINT_ITERATIONS {
        let (mut locked, mut iterated) = (false, false);
        for c in set.list.iter_mut() {
            locked |= solve_one(c, vel, states, &ctx);
            iterated |= c.iterated;
        }
        // Joints on bodies with locked axes, and those of components the forest leaves to
        // Gauss–Seidel, stay out of the forest: more sweeps over them alone, back and forth
        // along the list.
        if locked || iterated {
            let sweeps = if iterated { ITERATED_SWEEPS } else { LOCKED_ITERATIONS };
            for pass in 1..sweeps {
                let mut one = |c: &mut JointConstraint| {
                    if c.iterated || (pass < LOCKED_ITERATIONS && is_locked(c, states)) {
                        solve_one(c, vel, states, &ctx);
                    }
                };
                if pass % 2 == 1 {
                    set.list.iter_mut().rev().for_each(&mut one);
                } else {
                    set.list.iter_mut().for_each(&mut one);
                }
            }
        }
        set.forest
            .solve(&mut set.list, vel, states, &ctx, !use_bias && iteration == 0);
    }
}

/// Sweeps over the joints on bodies with locked axes in each pass (the first with all the
/// joints, the others with these alone, alternately backwards and forwards). Such bodies stay
/// out of the forest, and one Gauss–Seidel sweep left a 6-link planar hinge chain 1.3 times
/// as stretched as the same chain unlocked (19.6 against 14.8 mm, `tests/locked_joints.rs`);
/// four sweeps: 13.1 mm. Two made the colliding Z+X-locked chain worse on some kicks.
pub const LOCKED_ITERATIONS: u32 = 4;

/// Sweeps per pass over the joints of components the forest leaves to Gauss–Seidel (limits,
/// motors or springs; loops with a slider), the same way. Seeded random rings with limits
/// and springs (`tests/joint_loops.rs`): with one sweep 9 of 300 gained more than 15 % of
/// their energy scale, with four 1 (2.1 times it: two fixed joints between the same two
/// bodies, hinged to the world at a limit), with eight 1, by 32.6 %; rings without
/// limits left 33 of 300 with joint gaps over 6 cm at one sweep, 22 at four.
pub const ITERATED_SWEEPS: u32 = 8;

fn is_locked(c: &JointConstraint, states: &[BodyState]) -> bool {
    (states[c.ia as usize].locks | states[c.ib as usize].locks) != 0
}

/// Solves one joint outside the forest: its limits, motor and spring, then its equality rows
/// as a block (a forest joint's rows are all the forest's); returns whether either body has
/// locked axes.
fn solve_one(c: &mut JointConstraint, vel: &mut [Velocity], states: &[BodyState], ctx: &Ctx) -> bool {
    // A tree joint's rows, equality and scalar, are solved by the forest (scalar rows with
    // its tree's response, `Forest::solve_axial`).
    if c.tree {
        return false;
    }
    let scalars = has_scalar_rows(&c.kind);
    let (mut b, f) = load(c, vel, states);
    let locked = b.locked;
    if !scalars && !b.locked && matches!(c.kind, JointKind::Ball(_)) {
        // A plain ball joint closing a loop (the joint grid's cross links): the 3×3
        // point block in glam, the hot path of large joint meshes. With locked axes
        // the block may be singular: the rows' pivoted factor below.
        b.solve_point(&f, &mut c.imp.linear, ctx);
        write(c, &b, vel);
        return locked;
    }
    let eq = Eq::of(&c.kind, &f);
    let k = eq.factor(&b);
    let imp = &mut c.imp;
    match c.kind {
        JointKind::Ball(p) => super::ball::solve(&p, imp, &f, &mut b, ctx, &eq, k.as_ref()),
        JointKind::Hinge(p) => super::hinge::solve(&p, &c.spring, imp, &f, &mut b, ctx, &eq, k.as_ref()),
        JointKind::Fixed => {}
        JointKind::Distance(p) => super::distance::solve(&p, &c.spring, imp, &f, &mut b, ctx),
        JointKind::Slider(p) => super::slider::solve(&p, imp, &f, &mut b, ctx, &eq, k.as_ref()),
    }
    if !c.tree {
        if let Some(k) = &k {
            eq.solve_block(k, &mut b, &mut c.imp, ctx);
        }
    }
    write(c, &b, vel);
    locked
}

/// After a sweep: a joint whose block was ill-conditioned beyond what f32 and f64 can carry
/// (a 10 km × 1 mm capsule's inertia jointed to a heavy body at 100 km from the origin, found
/// by the API fuzzer) can leave a body with a non-finite or absurd velocity (4e35 m/s, NaN
/// rad/s). Such a body is brought back within the speed limits (NaN components dropped) and
/// the joint's accumulated impulses, which would warm-start the blow-up again, are cleared.
/// Velocities within 100 times the limits are left alone: the sweeps may overshoot the
/// limits on the way and the integration caps them, and capping here would bias the solve.
pub fn guard(set: &mut JointSet, vel: &mut [Velocity], limits: (f32, f32)) {
    let sane = |u: &Velocity| {
        u.v.is_finite()
            && u.w.is_finite()
            && u.v.length_squared() <= (100.0 * limits.0).powi(2)
            && u.w.length_squared() <= (100.0 * limits.1).powi(2)
    };
    for c in set.list.iter_mut() {
        let mut reset = false;
        for k in [c.ia, c.ib] {
            let u = &mut vel[k as usize];
            if k != 0 && !sane(u) {
                *u = Velocity::new(clamp_length(u.v, limits.0), clamp_length(u.w, limits.1));
                reset = true;
            }
        }
        let i = &c.imp;
        let finite = i.linear.is_finite()
            && i.angular.is_finite()
            && [i.axial, i.motor, i.lower, i.upper, i.cone]
                .iter()
                .all(|x| x.is_finite());
        if reset || !finite {
            c.imp = Impulses::default();
        }
    }
}

/// After the sub-steps: keeps the impulses for the next step, records the applied force and
/// torque (impulse per sub-step over the sub-step) and breaks joints past their thresholds.
pub fn store(world: &mut World, h: f32) {
    let World { joints, solver, .. } = world;
    let inv_h = 1.0 / h;
    for c in &joints.constraints.list {
        let (_, f) = load(c, &solver.vel, &solver.states);
        let w = wrench(c, &f);
        let joint = joints.pool.at_mut(c.joint);
        joint.impulses = c.imp;
        joint.force = w.p * inv_h;
        joint.torque = (w.tb - f.rb.cross(w.p)) * inv_h;
        if joint.force.length() > joint.def.break_force || joint.torque.length() > joint.def.break_torque {
            // A broken joint applies nothing, and says so from now on (it leaves the
            // constraint list, so nothing would overwrite what it applied last).
            joint.broken = true;
            joint.impulses = Impulses::default();
            joint.force = Vec3::ZERO;
            joint.torque = Vec3::ZERO;
            let handle = joints.pool.handle_at(c.joint).expect("live joint");
            joints.broken.push(handle);
        }
    }
}
