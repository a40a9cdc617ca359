//! Runtime changes a game makes to live bodies and shapes (issue 14): shape materials and
//! density, body gravity scale, mass override, body type, enable and disable. Every setter
//! validates first and changes nothing on error; it wakes the body where the change needs it.

use crate::collision::contact::mix_materials;
use crate::collision::shape::{MassProperties, ShapeDef};
use crate::dynamics::body::{BodyHandle, BodyType, ShapeHandle};
use crate::error::{check_gravity_scale, check_position, check_range, invalid, Error, Result, MAX_INVERSE_MASS};
use crate::math::{Mat3, Vec3};
use crate::world::World;

/// Smallest mass `World::set_mass_data` accepts (kg): the inverse of `MAX_INVERSE_MASS`.
pub const MIN_MASS: f32 = 1.0 / MAX_INVERSE_MASS;
/// Largest mass `World::set_mass_data` accepts (kg): the largest density filling the largest
/// box (1e5 kg/m³ · (1e4 m)³).
pub const MAX_MASS: f32 = 1.0e17;
/// Range of each principal moment of inertia `World::set_mass_data` accepts (kg·m²): those
/// the supported masses and sizes give.
pub const MIN_INERTIA: f32 = 1.0e-18;
pub const MAX_INERTIA: f32 = 1.0e26;

/// A body's mass, centre of mass (body frame) and principal moments of inertia about the
/// centre of mass along the body axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassData {
    pub mass: f32,
    pub center: Vec3,
    pub inertia: Vec3,
}

impl World {
    fn shape_index(&self, h: ShapeHandle) -> Result<u32> {
        self.shapes.get(h).map(|_| h.index).ok_or(Error::InvalidId("shape"))
    }

    /// Changes a shape's material: `edit` changes a copy, which is validated, stored and mixed
    /// into the shape's contacts. The body is woken (a body resting on ice that becomes
    /// rough, or the reverse, must move again).
    pub fn edit_shape_material(&mut self, h: ShapeHandle, edit: impl FnOnce(&mut ShapeDef)) -> Result<()> {
        let s = self.shape_index(h)?;
        let old = self.shapes.at(s).def;
        let mut def = old;
        edit(&mut def);
        def.validate()?;
        self.shapes.at_mut(s).def = def;
        let bi = self.shapes.at(s).body;
        if def.density != old.density {
            self.update_mass(bi);
        }
        let contacts = self.bodies.at(bi).contacts.clone();
        for c in contacts {
            let ct = self.contacts.at(c);
            if ct.shape_a != s && ct.shape_b != s {
                continue;
            }
            let (a, b) = (self.shapes.at(ct.shape_a), self.shapes.at(ct.shape_b));
            let m = mix_materials(&a.def, ct.radius_a, &b.def, ct.radius_b);
            let ct = self.contacts.at_mut(c);
            ct.static_friction = m.static_friction;
            ct.dynamic_friction = m.dynamic_friction;
            ct.restitution = m.restitution;
            ct.rolling_resistance = m.rolling_resistance;
            ct.torsional_friction = m.torsional_friction;
        }
        self.wake_body(bi);
        Ok(())
    }

    /// The shape's material (density, friction, restitution, rolling resistance, torsional
    /// friction, user data).
    pub fn shape_material(&self, h: ShapeHandle) -> Result<ShapeDef> {
        Ok(self.shape(h)?.def)
    }

    /// Sets a shape's host data. Does not wake the body.
    pub fn set_shape_user_data(&mut self, h: ShapeHandle, user_data: u64) -> Result<()> {
        let s = self.shape_index(h)?;
        self.shapes.at_mut(s).def.user_data = user_data;
        Ok(())
    }

    /// Sets the multiplier of world gravity for one body (−100..=100). Wakes it.
    pub fn set_gravity_scale(&mut self, h: BodyHandle, scale: f32) -> Result<()> {
        let i = self.body_index(h)?;
        check_gravity_scale("gravity_scale", scale)?;
        self.bodies.at_mut(i).gravity_scale = scale;
        self.wake_body(i);
        Ok(())
    }

    pub fn gravity_scale(&self, h: BodyHandle) -> Result<f32> {
        Ok(self.body(h)?.gravity_scale)
    }

    /// Locks a body's linear and angular axes (`body::LOCK_*` bits, world axes; 0 unlocks
    /// all): its velocity along each locked axis becomes zero at once and stays exactly zero
    /// through contacts, joints, forces, impulses and gravity. Locks act on dynamic bodies
    /// (static and kinematic ones move as told) and are kept through type changes. Unknown
    /// bits are refused. Wakes the body.
    pub fn set_locked_axes(&mut self, h: BodyHandle, locks: u32) -> Result<()> {
        let i = self.body_index(h)?;
        crate::dynamics::body::check_locked_axes("locked_axes", locks)?;
        let b = self.bodies.at_mut(i);
        b.locked_axes = locks as u8;
        b.v = crate::dynamics::body::lock_linear(b.v, b.locks());
        b.w = crate::dynamics::body::lock_angular(b.w, b.locks());
        b.update_world_inertia();
        if b.enabled {
            self.wake_body(i);
        }
        Ok(())
    }

    /// A body's locked axes (`body::LOCK_*` bits).
    pub fn locked_axes(&self, h: BodyHandle) -> Result<u32> {
        Ok(self.body(h)?.locked_axes as u32)
    }

    /// Overrides a body's mass, centre of mass (body frame) and principal moments of inertia
    /// (along the body axes). Kept through later shape and density changes until
    /// `reset_mass_data`. Static and kinematic bodies keep infinite mass, but the override
    /// applies if they become dynamic. Wakes the body.
    pub fn set_mass_data(&mut self, h: BodyHandle, data: &MassData) -> Result<()> {
        let i = self.body_index(h)?;
        check_range("mass", data.mass, MIN_MASS, MAX_MASS, " kg")?;
        check_position("center", data.center)?;
        for (name, x) in [
            ("inertia.x", data.inertia.x),
            ("inertia.y", data.inertia.y),
            ("inertia.z", data.inertia.z),
        ] {
            check_range(name, x, MIN_INERTIA, MAX_INERTIA, " kg·m²")?;
        }
        self.bodies.at_mut(i).mass_override = Some(MassProperties {
            mass: data.mass,
            center: data.center,
            inertia: Mat3::from_diagonal(data.inertia),
        });
        self.update_mass(i);
        self.wake_body(i);
        Ok(())
    }

    /// Drops a mass override: the mass comes from the shapes again. Wakes the body.
    pub fn reset_mass_data(&mut self, h: BodyHandle) -> Result<()> {
        let i = self.body_index(h)?;
        self.bodies.at_mut(i).mass_override = None;
        self.update_mass(i);
        self.wake_body(i);
        Ok(())
    }

    /// The body's mass, centre of mass (body frame) and the diagonal of its inertia about the
    /// centre of mass in the body frame (zero for static and kinematic bodies).
    pub fn mass_data(&self, h: BodyHandle) -> Result<MassData> {
        let b = self.body(h)?;
        let i = b.inertia_local;
        Ok(MassData {
            mass: b.mass,
            center: b.local_center,
            inertia: Vec3::new(i.x_axis.x, i.y_axis.y, i.z_axis.z),
        })
    }

    /// Is a mass override set?
    pub fn has_mass_override(&self, h: BodyHandle) -> Result<bool> {
        Ok(self.body(h)?.mass_override.is_some())
    }

    /// Changes a body's type. A body becoming static stops (velocities zero) and leaves the
    /// awake list; one leaving static is woken. Contacts that no longer have a dynamic body
    /// are dropped, the shapes are queued for new pairs, the mass is recomputed, and every
    /// body it touched or is jointed to is woken. A plane keeps its body static, and a mesh or
    /// heightfield keeps its body from becoming dynamic (`InvalidArgument`, nothing changed).
    pub fn set_body_type(&mut self, h: BodyHandle, t: BodyType) -> Result<()> {
        let i = self.body_index(h)?;
        let old = self.bodies.at(i).body_type;
        if old == t {
            return Ok(());
        }
        for s in &self.bodies.at(i).shapes {
            let g = &self.shapes.at(s.index).geometry;
            if g.is_unbounded() && t != BodyType::Static {
                return Err(invalid("type: a body with a plane must stay static"));
            }
            if g.is_triangles() && t == BodyType::Dynamic {
                return Err(invalid(
                    "type: a body with a triangle mesh or heightfield cannot be dynamic",
                ));
            }
        }
        let enabled = self.bodies.at(i).enabled;
        if enabled {
            self.wake_body(i);
            self.wake_neighbours(i);
        }
        {
            let b = self.bodies.at_mut(i);
            b.body_type = t;
            b.kinematic_target = None;
            b.kinematic_stop = false;
            b.sleep_time = 0.0;
            if t == BodyType::Static {
                b.v = Vec3::ZERO;
                b.w = Vec3::ZERO;
            }
            b.force = Vec3::ZERO;
            b.torque = Vec3::ZERO;
        }
        self.update_mass(i);
        {
            // Becoming dynamic puts the body's locks in force.
            let b = self.bodies.at_mut(i);
            b.v = crate::dynamics::body::lock_linear(b.v, b.locks());
            b.w = crate::dynamics::body::lock_angular(b.w, b.locks());
        }
        if !enabled {
            return Ok(());
        }
        if t == BodyType::Static {
            self.remove_awake_body(i);
        } else {
            self.wake_body(i);
        }
        let contacts = self.bodies.at(i).contacts.clone();
        for c in contacts {
            let ct = self.contacts.at(c);
            let (a, b) = (self.bodies.at(ct.body_a), self.bodies.at(ct.body_b));
            if !a.is_dynamic() && !b.is_dynamic() {
                self.destroy_contact(c);
            } else if a.awake || b.awake {
                self.add_awake_contact(c);
            }
        }
        for k in 0..self.bodies.at(i).shapes.len() {
            let s = self.bodies.at(i).shapes[k].index;
            self.refresh_proxy(s, Vec3::ZERO, true);
        }
        Ok(())
    }

    /// Wakes every body touching `i` or jointed to it.
    fn wake_neighbours(&mut self, i: u32) {
        let mut others: Vec<u32> = self
            .bodies
            .at(i)
            .contacts
            .iter()
            .map(|&c| {
                let ct = self.contacts.at(c);
                if ct.body_a == i {
                    ct.body_b
                } else {
                    ct.body_a
                }
            })
            .collect();
        others.extend(self.joint_partners(i));
        for o in others {
            self.wake_body(o);
        }
    }

    /// Disables a body without destroying it: its shapes leave the broad phase, its contacts
    /// are destroyed (the bodies it touched are woken), it is not simulated, and joints to it
    /// are inactive (not solved, not breaking) until it is enabled. Its transform, velocities,
    /// shapes, mass and joints are kept. Disabling a disabled body does nothing.
    pub fn disable_body(&mut self, h: BodyHandle) -> Result<()> {
        let i = self.body_index(h)?;
        if !self.bodies.at(i).enabled {
            return Ok(());
        }
        // Waking dissolves a sleeping island it belongs to, so no island keeps it.
        self.wake_body(i);
        self.wake_neighbours(i);
        while let Some(&c) = self.bodies.at(i).contacts.last() {
            self.destroy_contact(c);
        }
        for k in 0..self.bodies.at(i).shapes.len() {
            let s = self.bodies.at(i).shapes[k].index;
            self.remove_shape_proxy(s);
        }
        self.remove_awake_body(i);
        let b = self.bodies.at_mut(i);
        b.enabled = false;
        b.force = Vec3::ZERO;
        b.torque = Vec3::ZERO;
        Ok(())
    }

    /// Enables a disabled body: its shapes return to the broad phase (contacts form at the
    /// next step) and a kinematic or dynamic body is woken, moving on with the velocities it
    /// had. Enabling an enabled body does nothing.
    pub fn enable_body(&mut self, h: BodyHandle) -> Result<()> {
        let i = self.body_index(h)?;
        if self.bodies.at(i).enabled {
            return Ok(());
        }
        self.bodies.at_mut(i).enabled = true;
        for k in 0..self.bodies.at(i).shapes.len() {
            let s = self.bodies.at(i).shapes[k].index;
            self.add_shape_proxy(s);
        }
        self.wake_body(i);
        self.wake_neighbours(i);
        Ok(())
    }

    pub fn is_body_enabled(&self, h: BodyHandle) -> Result<bool> {
        Ok(self.body(h)?.enabled)
    }
}
