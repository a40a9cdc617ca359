"""The raw C ABI of Hearth, mirrored one to one from include/hearth.h.

Every struct, callback type and constant of the header has a counterpart here under the
same name, and FUNCTIONS gives every exported function's ctypes signature (restype,
argtypes) in header order. The tests check all of it against the header (names, field
order and types, sizes and offsets as a C compiler sees them), so when the header changes
this file must change with it.

Nothing here loads the library; see _lib.py.
"""

from ctypes import (
    CFUNCTYPE,
    POINTER,
    Structure,
    c_bool,
    c_char,
    c_char_p,
    c_float,
    c_int32,
    c_size_t,
    c_uint8,
    c_uint32,
    c_uint64,
    c_void_p,
)

# ---------------------------------------------------------------------------- constants

HEARTH_VERSION_MAJOR = 0
HEARTH_VERSION_MINOR = 2
HEARTH_VERSION_PATCH = 0
HEARTH_VERSION = (HEARTH_VERSION_MAJOR << 16) | (HEARTH_VERSION_MINOR << 8) | HEARTH_VERSION_PATCH

HEARTH_BODY_STATIC = 0
HEARTH_BODY_KINEMATIC = 1
HEARTH_BODY_DYNAMIC = 2

HEARTH_LOCK_LINEAR_X = 1
HEARTH_LOCK_LINEAR_Y = 2
HEARTH_LOCK_LINEAR_Z = 4
HEARTH_LOCK_ANGULAR_X = 8
HEARTH_LOCK_ANGULAR_Y = 16
HEARTH_LOCK_ANGULAR_Z = 32
HEARTH_LOCK_LINEAR = 7
HEARTH_LOCK_ANGULAR = 56

HEARTH_QUERY_SHAPE_SPHERE = 0
HEARTH_QUERY_SHAPE_CAPSULE = 1
HEARTH_QUERY_SHAPE_BOX = 2
HEARTH_QUERY_SHAPE_HULL = 3

HEARTH_GENERATOR_GRAVITY = 0
HEARTH_GENERATOR_DRAG = 1
HEARTH_GENERATOR_SPRING = 2
HEARTH_GENERATOR_BUNGEE = 3
HEARTH_GENERATOR_STIFF_SPRING = 4
HEARTH_GENERATOR_BUOYANCY = 5
HEARTH_GENERATOR_EXPLOSION = 6
HEARTH_GENERATOR_ROD = 7
HEARTH_GENERATOR_CABLE = 8
HEARTH_GENERATOR_USER_FORCE = 9
HEARTH_GENERATOR_USER_CONTACT = 10

HEARTH_JOINT_BALL = 0
HEARTH_JOINT_HINGE = 1
HEARTH_JOINT_FIXED = 2
HEARTH_JOINT_DISTANCE = 3
HEARTH_JOINT_SLIDER = 4

HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER = 0
HEARTH_INTEGRATOR_RK4 = 1

HEARTH_MAX_HULL_POINTS = 1048576
HEARTH_MAX_MESH_VERTICES = 67108864
HEARTH_MAX_MESH_INDICES = 201326592
HEARTH_MAX_HEIGHTFIELD_SAMPLES = 32768


# enum HearthResult: an int32_t in C. A subclass (not c_int32 itself) so that the loader can
# tell the functions that return a result from any that return a plain int32_t, and make
# each of them raise on failure.
class HearthResult(c_int32):
    pass


HEARTH_OK = 0
HEARTH_ERROR_NULL_POINTER = 1
HEARTH_ERROR_INVALID_ID = 2
HEARTH_ERROR_INVALID_ARGUMENT = 3
HEARTH_ERROR_WORLD_LOCKED = 4
HEARTH_ERROR_BUFFER_TOO_SMALL = 5
HEARTH_ERROR_PANIC = 6
HEARTH_ERROR_IO = 7
HEARTH_ERROR_LIMIT_REACHED = 8

# ---------------------------------------------------------------------------- types


class _Struct(Structure):
    """Base of the mirrored structs: a readable repr."""

    def __repr__(self):
        fields = ", ".join(f"{name}={getattr(self, name)!r}" for name, *_ in self._fields_)
        return f"{type(self).__name__}({fields})"


class HearthWorld(Structure):
    """Opaque: only ever used through a pointer."""


class HearthContactSink(Structure):
    """Opaque: only ever used through a pointer, valid during a contact callback."""


class HearthVec3(_Struct):
    _fields_ = [
        ("x", c_float),
        ("y", c_float),
        ("z", c_float),
    ]


class HearthQuat(_Struct):
    _fields_ = [
        ("x", c_float),
        ("y", c_float),
        ("z", c_float),
        ("w", c_float),
    ]


class HearthTransform(_Struct):
    _fields_ = [
        ("position", HearthVec3),
        ("rotation", HearthQuat),
    ]


class HearthBodyDef(_Struct):
    _fields_ = [
        ("type", c_uint32),
        ("transform", HearthTransform),
        ("linear_velocity", HearthVec3),
        ("angular_velocity", HearthVec3),
        ("linear_damping", c_float),
        ("angular_damping", c_float),
        ("allow_sleep", c_uint8),
        ("user_data", c_uint64),
        ("gravity_scale", c_float),
        ("is_awake", c_uint8),
        ("internal_value", c_uint32),
        ("enable_move_events", c_uint8),
        ("locked_axes", c_uint32),
    ]


class HearthBodyId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthGeneratorId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthParticleId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthGeneratorContext(_Struct):
    _fields_ = [
        ("generator", HearthGeneratorId),
        ("dt", c_float),
        ("bodies", POINTER(HearthBodyId)),
        ("body_count", c_size_t),
        ("particles", POINTER(HearthParticleId)),
        ("particle_count", c_size_t),
    ]


# void (*HearthForceCallback)(void *user_data, HearthWorld *world, const HearthGeneratorContext *context)
HearthForceCallback = CFUNCTYPE(None, c_void_p, POINTER(HearthWorld), POINTER(HearthGeneratorContext))

# void (*HearthContactCallback)(void *user_data, HearthWorld *world, const HearthGeneratorContext *context,
#                               HearthContactSink *sink)
HearthContactCallback = CFUNCTYPE(
    None, c_void_p, POINTER(HearthWorld), POINTER(HearthGeneratorContext), POINTER(HearthContactSink)
)


class HearthUserForceGeneratorDef(_Struct):
    _fields_ = [
        ("callback", HearthForceCallback),
        ("user_data", c_void_p),
        ("internal_value", c_uint32),
    ]


class HearthUserContactGeneratorDef(_Struct):
    _fields_ = [
        ("callback", HearthContactCallback),
        ("user_data", c_void_p),
        ("capacity", c_uint32),
        ("internal_value", c_uint32),
    ]


class HearthGeneratedContact(_Struct):
    _fields_ = [
        ("body_a", HearthBodyId),
        ("particle_a", HearthParticleId),
        ("body_b", HearthBodyId),
        ("particle_b", HearthParticleId),
        ("point", HearthVec3),
        ("normal", HearthVec3),
        ("penetration", c_float),
        ("restitution", c_float),
        ("friction", c_float),
    ]


class HearthGravityGeneratorDef(_Struct):
    _fields_ = [
        ("acceleration", HearthVec3),
        ("internal_value", c_uint32),
    ]


class HearthDragGeneratorDef(_Struct):
    _fields_ = [
        ("k1", c_float),
        ("k2", c_float),
        ("internal_value", c_uint32),
    ]


class HearthLinkEnd(_Struct):
    _fields_ = [
        ("body", HearthBodyId),
        ("particle", HearthParticleId),
        ("point", HearthVec3),
    ]


class HearthSpringGeneratorDef(_Struct):
    _fields_ = [
        ("other", HearthLinkEnd),
        ("local_point", HearthVec3),
        ("rest_length", c_float),
        ("stiffness", c_float),
        ("damping", c_float),
        ("internal_value", c_uint32),
    ]


class HearthStiffSpringGeneratorDef(_Struct):
    _fields_ = [
        ("anchor", HearthLinkEnd),
        ("local_point", HearthVec3),
        ("stiffness", c_float),
        ("damping", c_float),
        ("internal_value", c_uint32),
    ]


class HearthBuoyancyGeneratorDef(_Struct):
    _fields_ = [
        ("surface_normal", HearthVec3),
        ("surface_offset", c_float),
        ("max_depth", c_float),
        ("volume", c_float),
        ("liquid_density", c_float),
        ("local_point", HearthVec3),
        ("internal_value", c_uint32),
    ]


class HearthExplosionGeneratorDef(_Struct):
    _fields_ = [
        ("center", HearthVec3),
        ("blast_radius", c_float),
        ("blast_impulse", c_float),
        ("shock_speed", c_float),
        ("shock_thickness", c_float),
        ("shock_force", c_float),
        ("max_radius", c_float),
        ("affect_all", c_uint8),
        ("internal_value", c_uint32),
    ]


class HearthRodGeneratorDef(_Struct):
    _fields_ = [
        ("a", HearthLinkEnd),
        ("b", HearthLinkEnd),
        ("length", c_float),
        ("internal_value", c_uint32),
    ]


class HearthCableGeneratorDef(_Struct):
    _fields_ = [
        ("a", HearthLinkEnd),
        ("b", HearthLinkEnd),
        ("max_length", c_float),
        ("restitution", c_float),
        ("internal_value", c_uint32),
    ]


class HearthJointBase(_Struct):
    _fields_ = [
        ("body_a", HearthBodyId),
        ("body_b", HearthBodyId),
        ("frame_a", HearthTransform),
        ("frame_b", HearthTransform),
        ("collide_connected", c_uint8),
        ("break_force", c_float),
        ("break_torque", c_float),
    ]


class HearthBallJointDef(_Struct):
    _fields_ = [
        ("base", HearthJointBase),
        ("enable_swing_limit", c_uint8),
        ("swing_limit", c_float),
        ("enable_twist_limit", c_uint8),
        ("lower_twist", c_float),
        ("upper_twist", c_float),
        ("internal_value", c_uint32),
    ]


class HearthJointId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthHingeJointDef(_Struct):
    _fields_ = [
        ("base", HearthJointBase),
        ("enable_limit", c_uint8),
        ("lower", c_float),
        ("upper", c_float),
        ("enable_motor", c_uint8),
        ("motor_speed", c_float),
        ("max_motor_torque", c_float),
        ("enable_spring", c_uint8),
        ("spring_hertz", c_float),
        ("spring_damping_ratio", c_float),
        ("internal_value", c_uint32),
    ]


class HearthFixedJointDef(_Struct):
    _fields_ = [
        ("base", HearthJointBase),
        ("internal_value", c_uint32),
    ]


class HearthDistanceJointDef(_Struct):
    _fields_ = [
        ("base", HearthJointBase),
        ("length", c_float),
        ("enable_limit", c_uint8),
        ("min_length", c_float),
        ("max_length", c_float),
        ("enable_spring", c_uint8),
        ("spring_hertz", c_float),
        ("spring_damping_ratio", c_float),
        ("internal_value", c_uint32),
    ]


class HearthSliderJointDef(_Struct):
    _fields_ = [
        ("base", HearthJointBase),
        ("enable_limit", c_uint8),
        ("lower", c_float),
        ("upper", c_float),
        ("enable_motor", c_uint8),
        ("motor_speed", c_float),
        ("max_motor_force", c_float),
        ("internal_value", c_uint32),
    ]


class HearthParticleDef(_Struct):
    _fields_ = [
        ("position", HearthVec3),
        ("velocity", HearthVec3),
        ("acceleration", HearthVec3),
        ("inverse_mass", c_float),
        ("radius", c_float),
        ("damping", c_float),
        ("gravity_scale", c_float),
        ("restitution", c_float),
        ("friction", c_float),
        ("lifetime", c_float),
        ("collide", c_uint8),
        ("allow_sleep", c_uint8),
        ("user_data", c_uint64),
        ("internal_value", c_uint32),
    ]


class HearthBurstDef(_Struct):
    _fields_ = [
        ("position", HearthVec3),
        ("direction", HearthVec3),
        ("cone_half_angle", c_float),
        ("count", c_uint32),
        ("speed_min", c_float),
        ("speed_max", c_float),
        ("lifetime_min", c_float),
        ("lifetime_max", c_float),
        ("seed", c_uint64),
        ("particle", HearthParticleDef),
        ("internal_value", c_uint32),
    ]


class HearthExpiredParticle(_Struct):
    _fields_ = [
        ("id", HearthParticleId),
        ("position", HearthVec3),
        ("velocity", HearthVec3),
        ("user_data", c_uint64),
    ]


class HearthFilter(_Struct):
    _fields_ = [
        ("category_bits", c_uint64),
        ("mask_bits", c_uint64),
        ("group_index", c_int32),
    ]


class HearthShapeDef(_Struct):
    _fields_ = [
        ("density", c_float),
        ("static_friction", c_float),
        ("dynamic_friction", c_float),
        ("restitution", c_float),
        ("user_data", c_uint64),
        ("internal_value", c_uint32),
        ("rolling_resistance", c_float),
        ("torsional_friction", c_float),
        ("filter", HearthFilter),
        ("is_sensor", c_uint8),
        ("enable_contact_events", c_uint8),
        ("enable_hit_events", c_uint8),
        ("enable_sensor_events", c_uint8),
    ]


class HearthMassData(_Struct):
    _fields_ = [
        ("mass", c_float),
        ("center", HearthVec3),
        ("inertia", HearthVec3),
    ]


class HearthSphere(_Struct):
    _fields_ = [
        ("center", HearthVec3),
        ("radius", c_float),
    ]


class HearthShapeId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthBox(_Struct):
    _fields_ = [
        ("center", HearthVec3),
        ("rotation", HearthQuat),
        ("half_extents", HearthVec3),
    ]


class HearthCapsule(_Struct):
    _fields_ = [
        ("a", HearthVec3),
        ("b", HearthVec3),
        ("radius", c_float),
    ]


class HearthPlane(_Struct):
    _fields_ = [
        ("normal", HearthVec3),
        ("offset", c_float),
    ]


class HearthHullId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthMeshId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthHeightfieldId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthHullDef(_Struct):
    _fields_ = [
        ("convex_radius", c_float),
        ("weld_tolerance", c_float),
        ("internal_value", c_uint32),
    ]


class HearthHullShape(_Struct):
    _fields_ = [
        ("hull", HearthHullId),
        ("local", HearthTransform),
        ("scale", c_float),
    ]


class HearthMeshShape(_Struct):
    _fields_ = [
        ("mesh", HearthMeshId),
        ("local", HearthTransform),
        ("scale", HearthVec3),
    ]


class HearthHeightfieldShape(_Struct):
    _fields_ = [
        ("heightfield", HearthHeightfieldId),
        ("local", HearthTransform),
        ("scale", HearthVec3),
    ]


class HearthSoftBodyDef(_Struct):
    _fields_ = [
        ("transform", HearthTransform),
        ("velocity", HearthVec3),
        ("mass", c_float),
        ("edge_compliance", c_float),
        ("bend_compliance", c_float),
        ("preserve_volume", c_uint8),
        ("volume_compliance", c_float),
        ("pressure", c_float),
        ("damping", c_float),
        ("deformation_damping", c_float),
        ("friction", c_float),
        ("restitution", c_float),
        ("vertex_radius", c_float),
        ("gravity_scale", c_float),
        ("substeps", c_uint32),
        ("iterations", c_uint32),
        ("collide", c_uint8),
        ("user_data", c_uint64),
        ("internal_value", c_uint32),
    ]


class HearthSoftBodyId(_Struct):
    _fields_ = [
        ("index", c_uint32),
        ("generation", c_uint32),
    ]


class HearthSoftBodySettings(_Struct):
    _fields_ = [
        ("edge_compliance", c_float),
        ("bend_compliance", c_float),
        ("preserve_volume", c_uint8),
        ("volume_compliance", c_float),
        ("pressure", c_float),
        ("damping", c_float),
        ("deformation_damping", c_float),
        ("friction", c_float),
        ("restitution", c_float),
        ("vertex_radius", c_float),
        ("gravity_scale", c_float),
        ("substeps", c_uint32),
        ("iterations", c_uint32),
        ("collide", c_uint8),
    ]


# void (*HearthTaskFn)(uint32_t start, uint32_t end, uint32_t worker_index, void *task_context)
HearthTaskFn = CFUNCTYPE(None, c_uint32, c_uint32, c_uint32, c_void_p)
# void *(*HearthEnqueueTaskFn)(HearthTaskFn task, uint32_t item_count, uint32_t min_range, void *task_context,
#                              void *user_context)
HearthEnqueueTaskFn = CFUNCTYPE(c_void_p, HearthTaskFn, c_uint32, c_uint32, c_void_p, c_void_p)
# void (*HearthFinishTaskFn)(void *user_task, void *user_context)
HearthFinishTaskFn = CFUNCTYPE(None, c_void_p, c_void_p)


class HearthWorldDef(_Struct):
    _fields_ = [
        ("gravity", HearthVec3),
        ("substeps", c_uint32),
        ("integrator", c_uint32),
        ("enable_sleep", c_uint8),
        ("sleep_threshold", c_float),
        ("time_to_sleep", c_float),
        ("contact_hertz", c_float),
        ("contact_damping_ratio", c_float),
        ("contact_push_max_velocity", c_float),
        ("restitution_threshold", c_float),
        ("max_linear_speed", c_float),
        ("velocity_iterations", c_uint32),
        ("internal_value", c_uint32),
        ("max_angular_speed", c_float),
        ("hit_event_threshold", c_float),
        ("worker_count", c_uint32),
        ("enqueue_task", HearthEnqueueTaskFn),
        ("finish_task", HearthFinishTaskFn),
        ("user_task_context", c_void_p),
    ]


class HearthWorldCounters(_Struct):
    _fields_ = [
        ("body_count", c_uint32),
        ("awake_body_count", c_uint32),
        ("contact_count", c_uint32),
        ("touching_contact_count", c_uint32),
        ("tree_height", c_uint32),
    ]


# int32_t (*HearthRecordWriteFn)(void *user_data, const uint8_t *bytes, size_t len)
HearthRecordWriteFn = CFUNCTYPE(c_int32, c_void_p, POINTER(c_uint8), c_size_t)

# Debug draw (src/capi/draw.rs).
HearthDrawSegment = CFUNCTYPE(None, c_void_p, POINTER(HearthVec3), POINTER(HearthVec3), c_uint32)
HearthDrawPolygon = CFUNCTYPE(None, c_void_p, POINTER(HearthVec3), c_uint32, c_uint32)
HearthDrawSphere = CFUNCTYPE(None, c_void_p, POINTER(HearthVec3), c_float, c_uint32)
HearthDrawCapsule = CFUNCTYPE(None, c_void_p, POINTER(HearthVec3), POINTER(HearthVec3), c_float, c_uint32)
HearthDrawTransform = CFUNCTYPE(None, c_void_p, POINTER(HearthTransform))
HearthDrawPoint = CFUNCTYPE(None, c_void_p, POINTER(HearthVec3), c_float, c_uint32)


class HearthDebugDraw(_Struct):
    _fields_ = [
        ("draw_segment", HearthDrawSegment),
        ("draw_polygon", HearthDrawPolygon),
        ("draw_sphere", HearthDrawSphere),
        ("draw_capsule", HearthDrawCapsule),
        ("draw_transform", HearthDrawTransform),
        ("draw_point", HearthDrawPoint),
        ("user_data", c_void_p),
        ("draw_shapes", c_uint8),
        ("draw_aabbs", c_uint8),
        ("draw_contacts", c_uint8),
        ("draw_joints", c_uint8),
        ("draw_centers_of_mass", c_uint8),
        ("internal_value", c_uint32),
    ]



class HearthRecordDef(_Struct):
    _fields_ = [
        ("record_contacts", c_uint8),
        ("write", HearthRecordWriteFn),
        ("user_data", c_void_p),
        ("internal_value", c_uint32),
    ]


# ---------------------------------------------------------------------------- functions

# name -> (restype, argtypes), in header order.
FUNCTIONS = {}

# Exported functions and types that the Pythonic layer deliberately does not wrap, with the
# reason. The parity test fails for any header item that is neither wrapped nor listed here.
class HearthQueryFilter(_Struct):
    _fields_ = [
        ("category_bits", c_uint64),
        ("mask_bits", c_uint64),
    ]


class HearthRayInput(_Struct):
    _fields_ = [
        ("origin", HearthVec3),
        ("translation", HearthVec3),
    ]


class HearthRayHit(_Struct):
    _fields_ = [
        ("shape", HearthShapeId),
        ("body", HearthBodyId),
        ("point", HearthVec3),
        ("normal", HearthVec3),
        ("fraction", c_float),
    ]


class HearthQueryShape(_Struct):
    _fields_ = [
        ("type", c_uint32),
        ("sphere", HearthSphere),
        ("capsule", HearthCapsule),
        ("box", HearthBox),
        ("hull", HearthHullShape),
    ]


HearthRayCallback = CFUNCTYPE(c_float, c_void_p, POINTER(HearthRayHit))

NOT_WRAPPED = {
    "HearthTaskFn": "a job system in Python would run the ranges under the GIL, one at a time:"
    " World(worker_count=n) uses the library's own threads instead",
    "HearthEnqueueTaskFn": "see HearthTaskFn",
    "HearthFinishTaskFn": "see HearthTaskFn",
}


def _fn(name, restype, *argtypes):
    FUNCTIONS[name] = (restype, list(argtypes))


_fn("hearth_version", c_uint32)
_fn("hearth_result_name", c_char_p, c_int32)
_fn("hearth_last_error_message", c_size_t, POINTER(c_char), c_size_t)
_fn("hearth_body_def_default", HearthBodyDef)
_fn("hearth_body_create", HearthResult, POINTER(HearthWorld), POINTER(HearthBodyDef), POINTER(HearthBodyId))
_fn("hearth_body_destroy", HearthResult, POINTER(HearthWorld), HearthBodyId)
_fn("hearth_body_get_transform", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthTransform))
_fn("hearth_body_get_linear_velocity", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthVec3))
_fn("hearth_body_get_angular_velocity", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthVec3))
_fn("hearth_body_is_awake", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_bool))
_fn("hearth_body_get_center_of_mass", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthVec3))
_fn("hearth_body_get_mass", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_float))
_fn("hearth_body_get_user_data", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_uint64))
_fn("hearth_body_get_type", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_uint32))
_fn("hearth_body_set_transform", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthTransform))
_fn(
    "hearth_body_set_target_transform", HearthResult, POINTER(HearthWorld), HearthBodyId,
    POINTER(HearthTransform),
)
_fn("hearth_body_set_linear_velocity", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn("hearth_body_set_angular_velocity", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn("hearth_body_apply_force", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn("hearth_body_apply_torque", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn("hearth_body_apply_linear_impulse", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn("hearth_body_apply_angular_impulse", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3)
_fn(
    "hearth_body_apply_force_at_point", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3,
    HearthVec3,
)
_fn(
    "hearth_body_apply_impulse_at_point", HearthResult, POINTER(HearthWorld), HearthBodyId, HearthVec3,
    HearthVec3,
)
_fn("hearth_body_set_awake", HearthResult, POINTER(HearthWorld), HearthBodyId, c_uint8)
_fn("hearth_body_set_damping", HearthResult, POINTER(HearthWorld), HearthBodyId, c_float, c_float)
_fn("hearth_debug_draw_default", HearthDebugDraw)
_fn("hearth_world_draw", HearthResult, POINTER(HearthWorld), POINTER(HearthDebugDraw))
# Runtime setters (src/capi/setters.rs).
for _name in ("restitution", "rolling_resistance", "torsional_friction", "density"):
    _fn(f"hearth_shape_set_{_name}", HearthResult, POINTER(HearthWorld), HearthShapeId, c_float)
    _fn(f"hearth_shape_get_{_name}", HearthResult, POINTER(HearthWorld), HearthShapeId, POINTER(c_float))
_fn("hearth_shape_set_friction", HearthResult, POINTER(HearthWorld), HearthShapeId, c_float, c_float)
_fn(
    "hearth_shape_get_friction", HearthResult, POINTER(HearthWorld), HearthShapeId, POINTER(c_float),
    POINTER(c_float),
)
_fn("hearth_shape_set_user_data", HearthResult, POINTER(HearthWorld), HearthShapeId, c_uint64)
_fn("hearth_shape_get_user_data", HearthResult, POINTER(HearthWorld), HearthShapeId, POINTER(c_uint64))
_fn("hearth_body_set_gravity_scale", HearthResult, POINTER(HearthWorld), HearthBodyId, c_float)
_fn("hearth_body_get_gravity_scale", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_float))
_fn("hearth_body_set_locked_axes", HearthResult, POINTER(HearthWorld), HearthBodyId, c_uint32)
_fn("hearth_body_get_locked_axes", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_uint32))
_fn("hearth_body_set_mass_data", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthMassData))
_fn("hearth_body_get_mass_data", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthMassData))
_fn("hearth_body_reset_mass_data", HearthResult, POINTER(HearthWorld), HearthBodyId)
_fn("hearth_body_set_type", HearthResult, POINTER(HearthWorld), HearthBodyId, c_uint32)
_fn("hearth_body_disable", HearthResult, POINTER(HearthWorld), HearthBodyId)
_fn("hearth_body_enable", HearthResult, POINTER(HearthWorld), HearthBodyId)
_fn("hearth_body_is_enabled", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(c_bool))
_fn("hearth_user_force_generator_def_default", HearthUserForceGeneratorDef)
_fn(
    "hearth_generator_create_user_force", HearthResult, POINTER(HearthWorld),
    POINTER(HearthUserForceGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_user_contact_generator_def_default", HearthUserContactGeneratorDef)
_fn(
    "hearth_generator_create_user_contact", HearthResult, POINTER(HearthWorld),
    POINTER(HearthUserContactGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_contact_sink_add", HearthResult, POINTER(HearthContactSink), POINTER(HearthGeneratedContact))
_fn(
    "hearth_contact_sink_get_count", HearthResult, POINTER(HearthContactSink), POINTER(c_uint32),
    POINTER(c_uint32),
)
_fn("hearth_gravity_generator_def_default", HearthGravityGeneratorDef)
_fn(
    "hearth_generator_create_gravity", HearthResult, POINTER(HearthWorld),
    POINTER(HearthGravityGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_drag_generator_def_default", HearthDragGeneratorDef)
_fn(
    "hearth_generator_create_drag", HearthResult, POINTER(HearthWorld), POINTER(HearthDragGeneratorDef),
    POINTER(HearthGeneratorId),
)
_fn("hearth_spring_generator_def_default", HearthSpringGeneratorDef)
_fn(
    "hearth_generator_create_spring", HearthResult, POINTER(HearthWorld), POINTER(HearthSpringGeneratorDef),
    POINTER(HearthGeneratorId),
)
_fn(
    "hearth_generator_create_bungee", HearthResult, POINTER(HearthWorld), POINTER(HearthSpringGeneratorDef),
    POINTER(HearthGeneratorId),
)
_fn("hearth_stiff_spring_generator_def_default", HearthStiffSpringGeneratorDef)
_fn(
    "hearth_generator_create_stiff_spring", HearthResult, POINTER(HearthWorld),
    POINTER(HearthStiffSpringGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_buoyancy_generator_def_default", HearthBuoyancyGeneratorDef)
_fn(
    "hearth_generator_create_buoyancy", HearthResult, POINTER(HearthWorld),
    POINTER(HearthBuoyancyGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_explosion_generator_def_default", HearthExplosionGeneratorDef)
_fn(
    "hearth_generator_create_explosion", HearthResult, POINTER(HearthWorld),
    POINTER(HearthExplosionGeneratorDef), POINTER(HearthGeneratorId),
)
_fn("hearth_rod_generator_def_default", HearthRodGeneratorDef)
_fn(
    "hearth_generator_create_rod", HearthResult, POINTER(HearthWorld), POINTER(HearthRodGeneratorDef),
    POINTER(HearthGeneratorId),
)
_fn("hearth_cable_generator_def_default", HearthCableGeneratorDef)
_fn(
    "hearth_generator_create_cable", HearthResult, POINTER(HearthWorld), POINTER(HearthCableGeneratorDef),
    POINTER(HearthGeneratorId),
)
_fn("hearth_generator_destroy", HearthResult, POINTER(HearthWorld), HearthGeneratorId)
_fn("hearth_generator_attach_body", HearthResult, POINTER(HearthWorld), HearthGeneratorId, HearthBodyId)
_fn("hearth_generator_detach_body", HearthResult, POINTER(HearthWorld), HearthGeneratorId, HearthBodyId)
_fn(
    "hearth_generator_attach_particle", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    HearthParticleId,
)
_fn(
    "hearth_generator_attach_particles", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    POINTER(HearthParticleId), c_size_t,
)
_fn(
    "hearth_generator_detach_particle", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    HearthParticleId,
)
_fn(
    "hearth_generator_get_attachment_count", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    POINTER(c_uint32), POINTER(c_uint32),
)
_fn("hearth_generator_get_type", HearthResult, POINTER(HearthWorld), HearthGeneratorId, POINTER(c_uint32))
_fn("hearth_ball_joint_def_default", HearthBallJointDef)
_fn(
    "hearth_joint_create_ball", HearthResult, POINTER(HearthWorld), POINTER(HearthBallJointDef),
    POINTER(HearthJointId),
)
_fn("hearth_hinge_joint_def_default", HearthHingeJointDef)
_fn(
    "hearth_joint_create_hinge", HearthResult, POINTER(HearthWorld), POINTER(HearthHingeJointDef),
    POINTER(HearthJointId),
)
_fn("hearth_fixed_joint_def_default", HearthFixedJointDef)
_fn(
    "hearth_joint_create_fixed", HearthResult, POINTER(HearthWorld), POINTER(HearthFixedJointDef),
    POINTER(HearthJointId),
)
_fn("hearth_distance_joint_def_default", HearthDistanceJointDef)
_fn(
    "hearth_joint_create_distance", HearthResult, POINTER(HearthWorld), POINTER(HearthDistanceJointDef),
    POINTER(HearthJointId),
)
_fn("hearth_slider_joint_def_default", HearthSliderJointDef)
_fn(
    "hearth_joint_create_slider", HearthResult, POINTER(HearthWorld), POINTER(HearthSliderJointDef),
    POINTER(HearthJointId),
)
_fn("hearth_joint_destroy", HearthResult, POINTER(HearthWorld), HearthJointId)
_fn("hearth_joint_get_type", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_uint32))
_fn(
    "hearth_joint_get_bodies", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(HearthBodyId),
    POINTER(HearthBodyId),
)
_fn("hearth_joint_set_motor", HearthResult, POINTER(HearthWorld), HearthJointId, c_uint8, c_float, c_float)
_fn(
    "hearth_joint_get_motor", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_bool),
    POINTER(c_float), POINTER(c_float),
)
_fn("hearth_joint_set_limits", HearthResult, POINTER(HearthWorld), HearthJointId, c_uint8, c_float, c_float)
_fn(
    "hearth_joint_get_limits", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_bool),
    POINTER(c_float), POINTER(c_float),
)
_fn("hearth_joint_set_cone_limit", HearthResult, POINTER(HearthWorld), HearthJointId, c_uint8, c_float)
_fn(
    "hearth_joint_get_cone_limit", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_bool),
    POINTER(c_float),
)
_fn("hearth_joint_set_spring", HearthResult, POINTER(HearthWorld), HearthJointId, c_uint8, c_float, c_float)
_fn(
    "hearth_joint_get_spring", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_bool),
    POINTER(c_float), POINTER(c_float),
)
_fn(
    "hearth_joint_get_force", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(HearthVec3),
    POINTER(HearthVec3),
)
_fn("hearth_joint_is_broken", HearthResult, POINTER(HearthWorld), HearthJointId, POINTER(c_bool))
_fn(
    "hearth_world_get_broken_joints", HearthResult, POINTER(HearthWorld), POINTER(HearthJointId), c_size_t,
    POINTER(c_size_t),
)
_fn("hearth_particle_def_default", HearthParticleDef)
_fn(
    "hearth_particle_create", HearthResult, POINTER(HearthWorld), POINTER(HearthParticleDef),
    POINTER(HearthParticleId),
)
_fn("hearth_particle_destroy", HearthResult, POINTER(HearthWorld), HearthParticleId)
_fn("hearth_particle_get_position", HearthResult, POINTER(HearthWorld), HearthParticleId, POINTER(HearthVec3))
_fn("hearth_particle_get_velocity", HearthResult, POINTER(HearthWorld), HearthParticleId, POINTER(HearthVec3))
_fn("hearth_particle_is_awake", HearthResult, POINTER(HearthWorld), HearthParticleId, POINTER(c_bool))
_fn("hearth_particle_get_user_data", HearthResult, POINTER(HearthWorld), HearthParticleId, POINTER(c_uint64))
_fn("hearth_particle_set_position", HearthResult, POINTER(HearthWorld), HearthParticleId, HearthVec3)
_fn("hearth_particle_set_velocity", HearthResult, POINTER(HearthWorld), HearthParticleId, HearthVec3)
_fn("hearth_particle_apply_force", HearthResult, POINTER(HearthWorld), HearthParticleId, HearthVec3)
_fn("hearth_particle_apply_impulse", HearthResult, POINTER(HearthWorld), HearthParticleId, HearthVec3)
_fn("hearth_particle_set_awake", HearthResult, POINTER(HearthWorld), HearthParticleId, c_uint8)
_fn("hearth_burst_def_default", HearthBurstDef)
_fn(
    "hearth_particle_emit_burst", HearthResult, POINTER(HearthWorld), POINTER(HearthBurstDef),
    POINTER(HearthParticleId), c_size_t, POINTER(c_size_t),
)
_fn("hearth_world_get_particle_count", HearthResult, POINTER(HearthWorld), POINTER(c_size_t))
_fn(
    "hearth_world_get_particles", HearthResult, POINTER(HearthWorld), POINTER(HearthParticleId),
    POINTER(HearthVec3), POINTER(HearthVec3), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_world_get_particle_positions", HearthResult, POINTER(HearthWorld), POINTER(HearthParticleId),
    c_size_t, POINTER(HearthVec3),
)
_fn(
    "hearth_world_get_expired_particles", HearthResult, POINTER(HearthWorld),
    POINTER(POINTER(HearthExpiredParticle)), POINTER(c_size_t),
)
_fn("hearth_world_set_particle_iterations", HearthResult, POINTER(HearthWorld), c_uint32, c_uint32)
_fn("hearth_record_def_default", HearthRecordDef)
_fn("hearth_world_record_start_file", HearthResult, POINTER(HearthWorld), c_char_p, POINTER(HearthRecordDef))
_fn("hearth_world_record_start_callback", HearthResult, POINTER(HearthWorld), POINTER(HearthRecordDef))
_fn("hearth_world_record_stop", HearthResult, POINTER(HearthWorld))
_fn("hearth_world_snapshot_size", HearthResult, POINTER(HearthWorld), POINTER(c_size_t))
_fn("hearth_world_snapshot_save", HearthResult, POINTER(HearthWorld), POINTER(c_uint8), c_size_t, POINTER(c_size_t))
_fn("hearth_world_snapshot_restore", HearthResult, POINTER(HearthWorld), POINTER(c_uint8), c_size_t)
_fn(
    "hearth_world_get_user_generators_missing_callback", HearthResult, POINTER(HearthWorld),
    POINTER(HearthGeneratorId), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_generator_set_user_force_callback", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    POINTER(HearthUserForceGeneratorDef),
)
_fn(
    "hearth_generator_set_user_contact_callback", HearthResult, POINTER(HearthWorld), HearthGeneratorId,
    POINTER(HearthUserContactGeneratorDef),
)
_fn("hearth_shape_def_default", HearthShapeDef)
_fn(
    "hearth_shape_create_sphere", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthSphere), POINTER(HearthShapeId),
)
_fn(
    "hearth_shape_create_box", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthBox), POINTER(HearthShapeId),
)
_fn(
    "hearth_shape_create_capsule", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthCapsule), POINTER(HearthShapeId),
)
_fn(
    "hearth_shape_create_plane", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthPlane), POINTER(HearthShapeId),
)
_fn("hearth_hull_def_default", HearthHullDef)
_fn(
    "hearth_hull_create", HearthResult, POINTER(HearthWorld), POINTER(HearthHullDef), POINTER(HearthVec3), c_size_t,
    POINTER(HearthHullId),
)
_fn("hearth_hull_destroy", HearthResult, POINTER(HearthWorld), HearthHullId)
_fn("hearth_hull_get_vertex_count", HearthResult, POINTER(HearthWorld), HearthHullId, POINTER(c_uint32))
_fn(
    "hearth_mesh_create", HearthResult, POINTER(HearthWorld), POINTER(HearthVec3), c_size_t, POINTER(c_uint32),
    c_size_t, POINTER(HearthMeshId),
)
_fn("hearth_mesh_destroy", HearthResult, POINTER(HearthWorld), HearthMeshId)
_fn("hearth_mesh_get_triangle_count", HearthResult, POINTER(HearthWorld), HearthMeshId, POINTER(c_uint32))
_fn("hearth_mesh_get_degenerate_count", HearthResult, POINTER(HearthWorld), HearthMeshId, POINTER(c_uint32))
_fn(
    "hearth_heightfield_create", HearthResult, POINTER(HearthWorld), c_uint32, c_uint32, POINTER(c_float),
    POINTER(c_uint8), POINTER(HearthHeightfieldId),
)
_fn("hearth_heightfield_destroy", HearthResult, POINTER(HearthWorld), HearthHeightfieldId)
_fn(
    "hearth_shape_create_hull", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthHullShape), POINTER(HearthShapeId),
)
_fn(
    "hearth_shape_create_mesh", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthMeshShape), POINTER(HearthShapeId),
)
_fn(
    "hearth_shape_create_heightfield", HearthResult, POINTER(HearthWorld), HearthBodyId, POINTER(HearthShapeDef),
    POINTER(HearthHeightfieldShape), POINTER(HearthShapeId),
)
_fn("hearth_shape_destroy", HearthResult, POINTER(HearthWorld), HearthShapeId)
_fn("hearth_shape_get_body", HearthResult, POINTER(HearthWorld), HearthShapeId, POINTER(HearthBodyId))
_fn("hearth_soft_body_def_default", HearthSoftBodyDef)
_fn(
    "hearth_soft_body_create_mesh", HearthResult, POINTER(HearthWorld), POINTER(HearthSoftBodyDef),
    POINTER(HearthVec3), c_size_t, POINTER(c_uint32), c_size_t, POINTER(c_float), POINTER(HearthSoftBodyId),
)
_fn(
    "hearth_soft_body_create_icosphere", HearthResult, POINTER(HearthWorld), POINTER(HearthSoftBodyDef),
    c_float, c_uint32, POINTER(HearthSoftBodyId),
)
_fn(
    "hearth_soft_body_create_box", HearthResult, POINTER(HearthWorld), POINTER(HearthSoftBodyDef),
    HearthVec3, c_uint32, c_uint32, c_uint32, POINTER(HearthSoftBodyId),
)
_fn(
    "hearth_soft_body_create_cloth", HearthResult, POINTER(HearthWorld), POINTER(HearthSoftBodyDef), c_float,
    c_float, c_uint32, c_uint32, POINTER(HearthSoftBodyId),
)
_fn("hearth_soft_body_destroy", HearthResult, POINTER(HearthWorld), HearthSoftBodyId)
_fn("hearth_world_get_soft_body_count", HearthResult, POINTER(HearthWorld), POINTER(c_size_t))
_fn(
    "hearth_soft_body_get_vertex_count", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(c_size_t),
)
_fn(
    "hearth_soft_body_get_triangle_count", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(c_size_t),
)
_fn(
    "hearth_soft_body_get_positions", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(HearthVec3), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_soft_body_get_normals", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(HearthVec3), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_soft_body_get_indices", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(c_uint32),
    c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_soft_body_get_vertex_position", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32,
    POINTER(HearthVec3),
)
_fn(
    "hearth_soft_body_get_vertex_velocity", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32,
    POINTER(HearthVec3),
)
_fn("hearth_soft_body_get_center", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(HearthVec3))
_fn("hearth_soft_body_get_mass", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(c_float))
_fn("hearth_soft_body_get_volume", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(c_float))
_fn(
    "hearth_soft_body_get_rest_volume", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(c_float),
)
_fn("hearth_soft_body_get_pressure", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(c_float))
_fn("hearth_soft_body_get_user_data", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, POINTER(c_uint64))
_fn("hearth_soft_body_set_pressure", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_float)
_fn(
    "hearth_soft_body_pin_vertex", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32,
    HearthBodyId,
)
_fn("hearth_soft_body_unpin_vertex", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32)
_fn(
    "hearth_soft_body_is_vertex_pinned", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32,
    POINTER(c_bool),
)
_fn(
    "hearth_soft_body_apply_impulse", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_uint32,
    HearthVec3,
)
_fn("hearth_soft_body_apply_impulse_all", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, HearthVec3)
_fn(
    "hearth_soft_body_get_settings", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(HearthSoftBodySettings),
)
_fn(
    "hearth_soft_body_set_settings", HearthResult, POINTER(HearthWorld), HearthSoftBodyId,
    POINTER(HearthSoftBodySettings),
)
_fn(
    "hearth_soft_body_set_compliance", HearthResult, POINTER(HearthWorld), HearthSoftBodyId, c_float, c_float,
    c_float,
)
_fn("hearth_filter_default", HearthFilter)
_fn("hearth_query_filter_default", HearthQueryFilter)
_fn("hearth_shape_set_filter", HearthResult, POINTER(HearthWorld), HearthShapeId, HearthFilter)
_fn("hearth_shape_get_filter", HearthResult, POINTER(HearthWorld), HearthShapeId, POINTER(HearthFilter))
_fn(
    "hearth_world_cast_ray_closest", HearthResult, POINTER(HearthWorld), HearthVec3, HearthVec3,
    POINTER(HearthQueryFilter), POINTER(HearthRayHit),
)
_fn(
    "hearth_world_cast_ray", HearthResult, POINTER(HearthWorld), HearthVec3, HearthVec3, POINTER(HearthQueryFilter),
    HearthRayCallback, c_void_p,
)
_fn(
    "hearth_world_cast_rays", HearthResult, POINTER(HearthWorld), POINTER(HearthRayInput), c_size_t,
    POINTER(HearthQueryFilter), POINTER(HearthRayHit),
)
_fn(
    "hearth_world_cast_shape", HearthResult, POINTER(HearthWorld), POINTER(HearthQueryShape),
    POINTER(HearthTransform), HearthVec3, POINTER(HearthQueryFilter), POINTER(HearthRayHit),
)
_fn(
    "hearth_world_overlap_shape", HearthResult, POINTER(HearthWorld), POINTER(HearthQueryShape),
    POINTER(HearthTransform), POINTER(HearthQueryFilter), POINTER(HearthShapeId), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_world_overlap_aabb", HearthResult, POINTER(HearthWorld), HearthVec3, HearthVec3,
    POINTER(HearthQueryFilter), POINTER(HearthShapeId), c_size_t, POINTER(c_size_t),
)
_fn(
    "hearth_world_overlap_point", HearthResult, POINTER(HearthWorld), HearthVec3, POINTER(HearthQueryFilter),
    POINTER(HearthShapeId), c_size_t, POINTER(c_size_t),
)
_fn("hearth_world_def_default", HearthWorldDef)
_fn("hearth_world_create", HearthResult, POINTER(HearthWorldDef), POINTER(POINTER(HearthWorld)))
_fn("hearth_world_destroy", None, POINTER(HearthWorld))
_fn("hearth_world_step", HearthResult, POINTER(HearthWorld), c_float)
_fn("hearth_world_set_gravity", HearthResult, POINTER(HearthWorld), HearthVec3)
_fn("hearth_world_get_gravity", HearthResult, POINTER(HearthWorld), POINTER(HearthVec3))
_fn("hearth_world_get_counters", HearthResult, POINTER(HearthWorld), POINTER(HearthWorldCounters))
_fn("hearth_world_get_hash", HearthResult, POINTER(HearthWorld), POINTER(c_uint64))
_fn("hearth_world_rebuild_broadphase", HearthResult, POINTER(HearthWorld))
_fn(
    "hearth_world_get_transforms", HearthResult, POINTER(HearthWorld), POINTER(HearthBodyId), c_size_t,
    POINTER(HearthTransform),
)


# ---------------------------------------------------------------- events and step callbacks
class HearthContactEvent(_Struct):
    _fields_ = [
        ("shape_a", HearthShapeId),
        ("shape_b", HearthShapeId),
        ("body_a", HearthBodyId),
        ("body_b", HearthBodyId),
    ]


class HearthContactHitEvent(_Struct):
    _fields_ = [
        ("shape_a", HearthShapeId),
        ("shape_b", HearthShapeId),
        ("body_a", HearthBodyId),
        ("body_b", HearthBodyId),
        ("point", HearthVec3),
        ("normal", HearthVec3),
        ("approach_speed", c_float),
    ]


class HearthContactEvents(_Struct):
    _fields_ = [
        ("begin", POINTER(HearthContactEvent)),
        ("begin_count", c_size_t),
        ("end", POINTER(HearthContactEvent)),
        ("end_count", c_size_t),
        ("hit", POINTER(HearthContactHitEvent)),
        ("hit_count", c_size_t),
    ]


class HearthSensorEvent(_Struct):
    _fields_ = [
        ("sensor_shape", HearthShapeId),
        ("visitor_shape", HearthShapeId),
        ("sensor_body", HearthBodyId),
        ("visitor_body", HearthBodyId),
    ]


class HearthSensorEvents(_Struct):
    _fields_ = [
        ("begin", POINTER(HearthSensorEvent)),
        ("begin_count", c_size_t),
        ("end", POINTER(HearthSensorEvent)),
        ("end_count", c_size_t),
    ]


class HearthBodyMoveEvent(_Struct):
    _fields_ = [
        ("body", HearthBodyId),
        ("transform", HearthTransform),
        ("user_data", c_uint64),
        ("fell_asleep", c_uint8),
    ]


class HearthBodyEvents(_Struct):
    _fields_ = [
        ("moves", POINTER(HearthBodyMoveEvent)),
        ("move_count", c_size_t),
    ]


class HearthManifoldPoint(_Struct):
    _fields_ = [
        ("point", HearthVec3),
        ("separation", c_float),
    ]


class HearthPreSolveContact(_Struct):
    _fields_ = [
        ("shape_a", HearthShapeId),
        ("shape_b", HearthShapeId),
        ("body_a", HearthBodyId),
        ("body_b", HearthBodyId),
        ("normal", HearthVec3),
        ("points", POINTER(HearthManifoldPoint)),
        ("point_count", c_uint32),
    ]


# uint8_t (*HearthPairFilterCallback)(void *user_data, HearthWorld *world, HearthShapeId a, HearthShapeId b)
HearthPairFilterCallback = CFUNCTYPE(c_uint8, c_void_p, POINTER(HearthWorld), HearthShapeId, HearthShapeId)
# uint8_t (*HearthPreSolveCallback)(void *user_data, HearthWorld *world, const HearthPreSolveContact *contact)
HearthPreSolveCallback = CFUNCTYPE(c_uint8, c_void_p, POINTER(HearthWorld), POINTER(HearthPreSolveContact))

_fn("hearth_world_get_contact_events", HearthResult, POINTER(HearthWorld), POINTER(HearthContactEvents))
_fn("hearth_world_get_sensor_events", HearthResult, POINTER(HearthWorld), POINTER(HearthSensorEvents))
_fn("hearth_world_get_body_events", HearthResult, POINTER(HearthWorld), POINTER(HearthBodyEvents))
_fn(
    "hearth_world_set_pair_filter_callback", HearthResult, POINTER(HearthWorld), HearthPairFilterCallback, c_void_p
)
_fn("hearth_world_set_pre_solve_callback", HearthResult, POINTER(HearthWorld), HearthPreSolveCallback, c_void_p)
