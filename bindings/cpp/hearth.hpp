/*
 * hearth.hpp - header-only C++17 wrapper of the Hearth C ABI (include/hearth.h).
 *
 * What it adds to the C header, and nothing else (no engine code lives here):
 *   * hearth::World: owns one HearthWorld (move-only RAII; destroyed with everything in it).
 *   * Value handles (Body, Shape, Joint, Particle, SoftBody, Generator): a world pointer and
 *     an id, cheap to copy, compared by id. A handle never keeps anything alive: a stale
 *     handle gives Code::InvalidId, exactly as the C id would.
 *   * Errors as exceptions: hearth::Error (a std::runtime_error) carries the result code
 *     (code()) and the thread's last error message (message()).
 *   * The same API without exceptions: hearth::nothrow::World, Body, ... return
 *     hearth::Result<T> (hearth::Status for Result<void>). This half also compiles with
 *     -fno-exceptions (or with HEARTH_CPP_NO_EXCEPTIONS defined), where hearth::World and
 *     the other throwing types do not exist.
 *   * Lambdas as force and contact generators (World::add_force_generator,
 *     World::add_contact_generator). Each lambda lives in a heap box owned by the World,
 *     released by World::destroy_generator or when the World is destroyed. The C callback
 *     is a noexcept trampoline: an exception thrown by the lambda never crosses the C
 *     boundary; it is caught, the remaining lambdas of that step are skipped, the step runs
 *     to its end, and World::step rethrows the exception (the nothrow World returns it as a
 *     Status with Code::CallbackException). A lambda may also return a Status instead of
 *     void; a failed Status is reported by step() the same way, with its own code.
 *
 * Threads: as the C API. A World (and every handle into it) is used by one thread at a
 * time; error messages are per thread.
 *
 * Units: SI (m, kg, s, N), right-handed, gravity a world setting (default (0, -9.81, 0)).
 *
 * Value types are the C structs themselves (hearth::Vec3 is HearthVec3, ...), so arrays of
 * them pass straight to the bulk functions without copies.
 */
#ifndef HEARTH_HPP
#define HEARTH_HPP

#include "hearth.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#if !defined(HEARTH_CPP_NO_EXCEPTIONS) &&                                                       \
    (defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND))
#define HEARTH_CPP_EXCEPTIONS 1
#include <exception>
#include <stdexcept>
#else
#define HEARTH_CPP_EXCEPTIONS 0
#endif

namespace hearth {

// ------------------------------------------------------------------------------ value types

using Vec3 = HearthVec3;
using Quat = HearthQuat;
using Transform = HearthTransform;
using BodyId = HearthBodyId;
using ShapeId = HearthShapeId;
using JointId = HearthJointId;
using ParticleId = HearthParticleId;
using SoftBodyId = HearthSoftBodyId;
using GeneratorId = HearthGeneratorId;
using HullId = HearthHullId;
using MeshId = HearthMeshId;
using HeightfieldId = HearthHeightfieldId;

using WorldDef = HearthWorldDef;
/** A job system's callbacks (plain function pointers; see HearthWorldDef::enqueue_task). */
using TaskFn = HearthTaskFn;
using EnqueueTaskFn = HearthEnqueueTaskFn;
using FinishTaskFn = HearthFinishTaskFn;
using WorldCounters = HearthWorldCounters;
using RecordDef = HearthRecordDef;
using BodyDef = HearthBodyDef;
using ShapeDef = HearthShapeDef;
using MassData = HearthMassData;
using DebugDraw = HearthDebugDraw;
using Sphere = HearthSphere;
using Box = HearthBox;
using Capsule = HearthCapsule;
using Plane = HearthPlane;
using HullDef = HearthHullDef;
using HullShape = HearthHullShape;
using MeshShape = HearthMeshShape;
using HeightfieldShape = HearthHeightfieldShape;
using Filter = HearthFilter;
using QueryFilter = HearthQueryFilter;
using QueryShape = HearthQueryShape;
using RayInput = HearthRayInput;
using RayHit = HearthRayHit;
using ParticleDef = HearthParticleDef;
using BurstDef = HearthBurstDef;
using ExpiredParticle = HearthExpiredParticle;
using SoftBodyDef = HearthSoftBodyDef;
using ContactEvent = HearthContactEvent;
using ContactHitEvent = HearthContactHitEvent;
using ContactEvents = HearthContactEvents;
using SensorEvent = HearthSensorEvent;
using SensorEvents = HearthSensorEvents;
using BodyMoveEvent = HearthBodyMoveEvent;
using BodyEvents = HearthBodyEvents;
using ManifoldPoint = HearthManifoldPoint;
using PreSolveContact = HearthPreSolveContact;
using SoftBodySettings = HearthSoftBodySettings;
using BallJointDef = HearthBallJointDef;
using HingeJointDef = HearthHingeJointDef;
using FixedJointDef = HearthFixedJointDef;
using DistanceJointDef = HearthDistanceJointDef;
using SliderJointDef = HearthSliderJointDef;
using LinkEnd = HearthLinkEnd;
using GravityGeneratorDef = HearthGravityGeneratorDef;
using DragGeneratorDef = HearthDragGeneratorDef;
using SpringGeneratorDef = HearthSpringGeneratorDef;
using StiffSpringGeneratorDef = HearthStiffSpringGeneratorDef;
using BuoyancyGeneratorDef = HearthBuoyancyGeneratorDef;
using ExplosionGeneratorDef = HearthExplosionGeneratorDef;
using RodGeneratorDef = HearthRodGeneratorDef;
using CableGeneratorDef = HearthCableGeneratorDef;
using UserForceGeneratorDef = HearthUserForceGeneratorDef;
using UserContactGeneratorDef = HearthUserContactGeneratorDef;
using GeneratedContact = HearthGeneratedContact;

inline Vec3 vec3(float x, float y, float z) noexcept { return Vec3{x, y, z}; }
inline Quat quat_identity() noexcept { return Quat{0.0f, 0.0f, 0.0f, 1.0f}; }
inline Transform transform(Vec3 position, Quat rotation = quat_identity()) noexcept {
    return Transform{position, rotation};
}

/** True for the all-zero (null) id of any kind. */
template <class Id> inline bool is_null(Id id) noexcept { return id.index == 0 && id.generation == 0; }
/** Id equality (the C ids are plain structs without operators). */
template <class Id> inline bool same_id(Id a, Id b) noexcept {
    return a.index == b.index && a.generation == b.generation;
}

// Shape descriptions with their local placement (body frame).
inline Sphere sphere(float radius, Vec3 center = Vec3{0, 0, 0}) noexcept { return Sphere{center, radius}; }
inline Box box(Vec3 half_extents, Vec3 center = Vec3{0, 0, 0}, Quat rotation = quat_identity()) noexcept {
    return Box{center, rotation, half_extents};
}
inline Capsule capsule(Vec3 a, Vec3 b, float radius) noexcept { return Capsule{a, b, radius}; }
/** The half-space dot(normal, p) <= offset (static bodies only). */
inline Plane plane(Vec3 normal, float offset) noexcept { return Plane{normal, offset}; }
/** A shape instancing a convex hull, scaled uniformly, then placed by `local`. */
inline HullShape hull_shape(HullId hull, float scale = 1.0f, Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) noexcept {
    return HullShape{hull, local, scale};
}
/** A shape instancing a triangle mesh (static and kinematic bodies), scaled per axis, then placed. */
inline MeshShape mesh_shape(MeshId mesh, Vec3 scale = Vec3{1, 1, 1}, Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) noexcept {
    return MeshShape{mesh, local, scale};
}
/** A shape instancing a heightfield (static and kinematic bodies): scale.x, scale.z the sample
 * spacing, scale.y the height scale. */
inline HeightfieldShape heightfield_shape(HeightfieldId heightfield, Vec3 scale = Vec3{1, 1, 1},
                                          Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) noexcept {
    return HeightfieldShape{heightfield, local, scale};
}

// Collision filters and query shapes.
/** The default shape filter (category 1, every mask bit, group 0). */
inline Filter filter_default() noexcept { return hearth_filter_default(); }
inline Filter filter(uint64_t category_bits, uint64_t mask_bits = ~0ull, int32_t group_index = 0) noexcept {
    Filter f = hearth_filter_default();
    f.category_bits = category_bits;
    f.mask_bits = mask_bits;
    f.group_index = group_index;
    return f;
}
/** A query filter; the defaults are hearth_query_filter_default(). */
inline QueryFilter query_filter(uint64_t category_bits = 1, uint64_t mask_bits = ~0ull) noexcept {
    QueryFilter f = hearth_query_filter_default();
    f.category_bits = category_bits;
    f.mask_bits = mask_bits;
    return f;
}
inline QueryShape query_shape(Sphere s) noexcept {
    QueryShape q{};
    q.type = HEARTH_QUERY_SHAPE_SPHERE;
    q.sphere = s;
    return q;
}
inline QueryShape query_shape(Capsule c) noexcept {
    QueryShape q{};
    q.type = HEARTH_QUERY_SHAPE_CAPSULE;
    q.capsule = c;
    return q;
}
inline QueryShape query_shape(Box b) noexcept {
    QueryShape q{};
    q.type = HEARTH_QUERY_SHAPE_BOX;
    q.box = b;
    return q;
}
inline QueryShape query_shape(HullShape h) noexcept {
    QueryShape q{};
    q.type = HEARTH_QUERY_SHAPE_HULL;
    q.hull = h;
    return q;
}
/** True when a ray or cast hit something (a miss has the null shape id). */
inline bool is_hit(const RayHit &h) noexcept { return !(h.shape.index == 0 && h.shape.generation == 0); }

// Link ends of springs, rods and cables.
inline LinkEnd link_world(Vec3 point) noexcept { return LinkEnd{BodyId{0, 0}, ParticleId{0, 0}, point}; }
inline LinkEnd link_body(BodyId body, Vec3 local_point = Vec3{0, 0, 0}) noexcept {
    return LinkEnd{body, ParticleId{0, 0}, local_point};
}
inline LinkEnd link_particle(ParticleId particle) noexcept {
    return LinkEnd{BodyId{0, 0}, particle, Vec3{0, 0, 0}};
}

enum class BodyType : uint32_t {
    Static = HEARTH_BODY_STATIC,
    Kinematic = HEARTH_BODY_KINEMATIC,
    Dynamic = HEARTH_BODY_DYNAMIC,
};

enum class JointType : uint32_t {
    Ball = HEARTH_JOINT_BALL,
    Hinge = HEARTH_JOINT_HINGE,
    Fixed = HEARTH_JOINT_FIXED,
    Distance = HEARTH_JOINT_DISTANCE,
    Slider = HEARTH_JOINT_SLIDER,
};

enum class GeneratorType : uint32_t {
    Gravity = HEARTH_GENERATOR_GRAVITY,
    Drag = HEARTH_GENERATOR_DRAG,
    Spring = HEARTH_GENERATOR_SPRING,
    Bungee = HEARTH_GENERATOR_BUNGEE,
    StiffSpring = HEARTH_GENERATOR_STIFF_SPRING,
    Buoyancy = HEARTH_GENERATOR_BUOYANCY,
    Explosion = HEARTH_GENERATOR_EXPLOSION,
    Rod = HEARTH_GENERATOR_ROD,
    Cable = HEARTH_GENERATOR_CABLE,
    UserForce = HEARTH_GENERATOR_USER_FORCE,
    UserContact = HEARTH_GENERATOR_USER_CONTACT,
};

// Defaults: always start a def from these (the C layer rejects defs made any other way).
inline WorldDef world_def() noexcept { return hearth_world_def_default(); }
/**
 * The default def stepping on `workers` threads (1..=64): the host's job system when `enqueue`
 * and `finish` are given (`context` is passed to both as `user_context`), else threads the
 * world starts itself. Results are bit for bit those of one thread (`state_hash()`).
 */
inline WorldDef threaded_world_def(uint32_t workers, EnqueueTaskFn enqueue = nullptr, FinishTaskFn finish = nullptr,
                                   void *context = nullptr) noexcept {
    WorldDef d = hearth_world_def_default();
    d.worker_count = workers;
    d.enqueue_task = enqueue;
    d.finish_task = finish;
    d.user_task_context = context;
    return d;
}
inline RecordDef record_def() noexcept { return hearth_record_def_default(); }
inline BodyDef body_def() noexcept { return hearth_body_def_default(); }
inline BodyDef body_def(BodyType type, Vec3 position = Vec3{0, 0, 0}) noexcept {
    BodyDef d = hearth_body_def_default();
    d.type = static_cast<uint32_t>(type);
    d.transform.position = position;
    return d;
}
inline ShapeDef shape_def() noexcept { return hearth_shape_def_default(); }
/** Debug-draw callbacks and flags from `hearth_debug_draw_default()` (nothing drawn); set the
 *  callbacks (captureless lambdas work), `user_data` and flags, then `World::draw`. */
inline DebugDraw debug_draw() noexcept { return hearth_debug_draw_default(); }
inline HullDef hull_def() noexcept { return hearth_hull_def_default(); }
inline ParticleDef particle_def() noexcept { return hearth_particle_def_default(); }
inline BurstDef burst_def() noexcept { return hearth_burst_def_default(); }
inline SoftBodyDef soft_body_def() noexcept { return hearth_soft_body_def_default(); }
inline BallJointDef ball_joint_def() noexcept { return hearth_ball_joint_def_default(); }
inline HingeJointDef hinge_joint_def() noexcept { return hearth_hinge_joint_def_default(); }
inline FixedJointDef fixed_joint_def() noexcept { return hearth_fixed_joint_def_default(); }
inline DistanceJointDef distance_joint_def() noexcept { return hearth_distance_joint_def_default(); }
inline SliderJointDef slider_joint_def() noexcept { return hearth_slider_joint_def_default(); }
inline GravityGeneratorDef gravity_generator_def() noexcept { return hearth_gravity_generator_def_default(); }
inline DragGeneratorDef drag_generator_def() noexcept { return hearth_drag_generator_def_default(); }
inline SpringGeneratorDef spring_generator_def() noexcept { return hearth_spring_generator_def_default(); }
inline StiffSpringGeneratorDef stiff_spring_generator_def() noexcept {
    return hearth_stiff_spring_generator_def_default();
}
inline BuoyancyGeneratorDef buoyancy_generator_def() noexcept { return hearth_buoyancy_generator_def_default(); }
inline ExplosionGeneratorDef explosion_generator_def() noexcept {
    return hearth_explosion_generator_def_default();
}
inline RodGeneratorDef rod_generator_def() noexcept { return hearth_rod_generator_def_default(); }
inline CableGeneratorDef cable_generator_def() noexcept { return hearth_cable_generator_def_default(); }
inline UserForceGeneratorDef user_force_generator_def() noexcept {
    return hearth_user_force_generator_def_default();
}
inline UserContactGeneratorDef user_contact_generator_def() noexcept {
    return hearth_user_contact_generator_def_default();
}

// ----------------------------------------------------------------------------------- errors

/** The C result codes, plus one of the wrapper's own for a failed C++ callback. */
enum class Code : int32_t {
    Ok = HEARTH_OK,
    NullPointer = HEARTH_ERROR_NULL_POINTER,
    InvalidId = HEARTH_ERROR_INVALID_ID,
    InvalidArgument = HEARTH_ERROR_INVALID_ARGUMENT,
    WorldLocked = HEARTH_ERROR_WORLD_LOCKED,
    BufferTooSmall = HEARTH_ERROR_BUFFER_TOO_SMALL,
    Panic = HEARTH_ERROR_PANIC,
    Io = HEARTH_ERROR_IO,
    /** 4,095 worlds are alive at once (hearth_world_create). */
    LimitReached = HEARTH_ERROR_LIMIT_REACHED,
    /** A generator lambda threw something other than hearth::Error (nothrow API only; the
     * throwing API rethrows the original exception). */
    CallbackException = 1000,
};

/** "HEARTH_ERROR_INVALID_ID", ... (static strings). */
inline const char *code_name(Code code) noexcept {
    if (code == Code::CallbackException) {
        return "HEARTH_CPP_CALLBACK_EXCEPTION";
    }
    return hearth_result_name(static_cast<int32_t>(code));
}

/** The calling thread's message for its last failed C call ("" if none failed yet). */
inline std::string last_error_message() {
    const size_t len = hearth_last_error_message(nullptr, 0);
    if (len == 0) {
        return std::string();
    }
    std::string text(len + 1, '\0');
    hearth_last_error_message(&text[0], text.size());
    text.resize(len);
    return text;
}

/** The library's version, (major << 16) | (minor << 8) | patch. */
inline uint32_t version() noexcept { return hearth_version(); }
/** True when the loaded library is the version this header was written for. */
inline bool version_matches() noexcept { return hearth_version() == static_cast<uint32_t>(HEARTH_VERSION); }

#if HEARTH_CPP_EXCEPTIONS
/** A failed call: what() is "NAME: message", code() the result code. */
class Error : public std::runtime_error {
public:
    Error(Code code, const std::string &message)
        : std::runtime_error(std::string(code_name(code)) + ": " + message), code_(code),
          message_(message) {}
    Code code() const noexcept { return code_; }
    /** The C layer's detail message (without the code name). */
    const std::string &message() const noexcept { return message_; }
    const char *name() const noexcept { return code_name(code_); }

private:
    Code code_;
    std::string message_;
};
#endif

namespace detail {
/** value() of a failed Result: throws hearth::Error, or without exceptions prints and aborts. */
[[noreturn]] inline void fail(Code code, const std::string &message) {
#if HEARTH_CPP_EXCEPTIONS
    throw Error(code, message);
#else
    std::fprintf(stderr, "hearth: value() of a failed Result: %s: %s\n", code_name(code), message.c_str());
    std::abort();
#endif
}
} // namespace detail

/**
 * A value or an error (code and message). Check ok() (or the bool conversion) before
 * value(); value() of a failed Result throws hearth::Error, or aborts without exceptions.
 */
template <class T> class [[nodiscard]] Result {
public:
    Result(T value) : code_(Code::Ok), value_(std::move(value)) {}
    Result(Code code, std::string message) : code_(code), message_(std::move(message)), value_() {}

    bool ok() const noexcept { return code_ == Code::Ok; }
    explicit operator bool() const noexcept { return ok(); }
    Code code() const noexcept { return code_; }
    const std::string &message() const noexcept { return message_; }

    T &value() & {
        check();
        return value_;
    }
    const T &value() const & {
        check();
        return value_;
    }
    T &&value() && {
        check();
        return std::move(value_);
    }
    T value_or(T fallback) const & { return ok() ? value_ : std::move(fallback); }
    T &operator*() & { return value(); }
    const T &operator*() const & { return value(); }
    T *operator->() { return &value(); }
    const T *operator->() const { return &value(); }

private:
    void check() const {
        if (!ok()) {
            detail::fail(code_, message_);
        }
    }
    Code code_;
    std::string message_;
    T value_;
};

/** Success or an error, for calls without a value. */
template <> class [[nodiscard]] Result<void> {
public:
    Result() noexcept : code_(Code::Ok) {}
    Result(Code code, std::string message) : code_(code), message_(std::move(message)) {}

    bool ok() const noexcept { return code_ == Code::Ok; }
    explicit operator bool() const noexcept { return ok(); }
    Code code() const noexcept { return code_; }
    const std::string &message() const noexcept { return message_; }
    /** Throws (or aborts) when failed. */
    void value() const {
        if (!ok()) {
            detail::fail(code_, message_);
        }
    }

private:
    Code code_;
    std::string message_;
};
using Status = Result<void>;

// ------------------------------------------------------------------------------------ spans

/** A non-owning view of a contiguous array (what the bulk calls read or fill). */
template <class T> class Span {
public:
    Span() noexcept = default;
    Span(T *data, size_t size) noexcept : data_(data), size_(size) {}
    template <size_t N> Span(T (&array)[N]) noexcept : data_(array), size_(N) {}
    template <class C, class = std::enable_if_t<std::is_convertible<
                           decltype(std::declval<C &>().data()), T *>::value>>
    Span(C &container) noexcept : data_(container.data()), size_(container.size()) {}

    T *data() const noexcept { return data_; }
    size_t size() const noexcept { return size_; }
    bool empty() const noexcept { return size_ == 0; }
    T &operator[](size_t i) const noexcept { return data_[i]; }
    T *begin() const noexcept { return data_; }
    T *end() const noexcept { return data_ + size_; }

private:
    T *data_ = nullptr;
    size_t size_ = 0;
};

// ---------------------------------------------------------------------- error policies

namespace detail {
inline Status status_of(HearthResult r) {
    if (r == HEARTH_OK) {
        return Status();
    }
    return Status(static_cast<Code>(r), last_error_message());
}

/** Results as values: every call returns Result<T>. */
struct NoThrow {
    static constexpr bool throws = false;
    template <class T> using Ret = Result<T>;
    static Status check(HearthResult r) { return status_of(r); }
    template <class T> static Result<T> value(HearthResult r, T v) {
        if (r == HEARTH_OK) {
            return Result<T>(std::move(v));
        }
        return Result<T>(static_cast<Code>(r), last_error_message());
    }
    static Status fail(Code code, std::string message) { return Status(code, std::move(message)); }
    template <class T> static Result<T> fail_value(Code code, std::string message) {
        return Result<T>(code, std::move(message));
    }
};

#if HEARTH_CPP_EXCEPTIONS
/** Errors as exceptions: every call returns T and throws hearth::Error. */
struct Throwing {
    static constexpr bool throws = true;
    template <class T> using Ret = T;
    static void check(HearthResult r) {
        if (r != HEARTH_OK) {
            throw Error(static_cast<Code>(r), last_error_message());
        }
    }
    template <class T> static T value(HearthResult r, T v) {
        check(r);
        return v;
    }
    [[noreturn]] static void fail(Code code, const std::string &message) { throw Error(code, message); }
    template <class T> [[noreturn]] static T fail_value(Code code, const std::string &message) {
        throw Error(code, message);
    }
};
#endif
} // namespace detail

// Reads one output of a C call: `CALL` uses `&out`; returns P's Ret<T>.
#define HEARTH_CPP_READ(T, CALL)                                                                \
    T out{};                                                                                    \
    const HearthResult r_ = (CALL);                                                             \
    return P::template value<T>(r_, std::move(out))

template <class P> class BasicWorldRef;
template <class P> class BasicWorld;
template <class P> class BasicBody;
template <class P> class BasicShape;
template <class P> class BasicJoint;
template <class P> class BasicParticle;
template <class P> class BasicSoftBody;
template <class P> class BasicHull;
template <class P> class BasicMesh;
template <class P> class BasicHeightfield;
template <class P> class BasicGenerator;

/** A hinge or slider motor. */
struct Motor {
    bool enabled = false;
    float speed = 0.0f;
    float max = 0.0f;
};
/** Joint limits (hinge and twist angles in rad, slider and distance lengths in m). */
struct Limits {
    bool enabled = false;
    float lower = 0.0f;
    float upper = 0.0f;
};
/** A ball joint's swing cone. */
struct ConeLimit {
    bool enabled = false;
    float angle = 0.0f;
};
/** A hinge or distance joint's spring. */
struct Spring {
    bool enabled = false;
    float hertz = 0.0f;
    float damping_ratio = 0.0f;
};
/** What a joint applied to body B in the last step (world frame). */
struct JointForce {
    Vec3 force{0, 0, 0};
    Vec3 torque{0, 0, 0};
};
/** How many live bodies and particles a generator acts on. */
struct Attachments {
    uint32_t bodies = 0;
    uint32_t particles = 0;
};

// ---------------------------------------------------------------------------------- handles

/** A body: world pointer and id. Copy freely; destroy() makes every copy stale. */
template <class P> class BasicBody {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicBody() noexcept = default;
    BasicBody(HearthWorld *world, BodyId id) noexcept : world_(world), id_(id) {}
    BodyId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicBody &a, const BasicBody &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicBody &a, const BasicBody &b) noexcept { return !(a == b); }

    Ret<Transform> transform() const { HEARTH_CPP_READ(Transform, hearth_body_get_transform(world_, id_, &out)); }
    Ret<Vec3> position() const {
        Transform t{};
        const HearthResult r = hearth_body_get_transform(world_, id_, &t);
        return P::template value<Vec3>(r, t.position);
    }
    Ret<Vec3> linear_velocity() const {
        HEARTH_CPP_READ(Vec3, hearth_body_get_linear_velocity(world_, id_, &out));
    }
    Ret<Vec3> angular_velocity() const {
        HEARTH_CPP_READ(Vec3, hearth_body_get_angular_velocity(world_, id_, &out));
    }
    Ret<bool> is_awake() const { HEARTH_CPP_READ(bool, hearth_body_is_awake(world_, id_, &out)); }
    Ret<Vec3> center_of_mass() const {
        HEARTH_CPP_READ(Vec3, hearth_body_get_center_of_mass(world_, id_, &out));
    }
    Ret<float> mass() const { HEARTH_CPP_READ(float, hearth_body_get_mass(world_, id_, &out)); }
    Ret<uint64_t> user_data() const { HEARTH_CPP_READ(uint64_t, hearth_body_get_user_data(world_, id_, &out)); }
    Ret<BodyType> type() const {
        uint32_t t = 0;
        const HearthResult r = hearth_body_get_type(world_, id_, &t);
        return P::template value<BodyType>(r, static_cast<BodyType>(t));
    }

    Ret<void> set_transform(const Transform &t) const { return P::check(hearth_body_set_transform(world_, id_, &t)); }
    Ret<void> set_target_transform(const Transform &t) const {
        return P::check(hearth_body_set_target_transform(world_, id_, &t));
    }
    Ret<void> set_linear_velocity(Vec3 v) const { return P::check(hearth_body_set_linear_velocity(world_, id_, v)); }
    Ret<void> set_angular_velocity(Vec3 v) const {
        return P::check(hearth_body_set_angular_velocity(world_, id_, v));
    }
    Ret<void> set_awake(bool awake) const { return P::check(hearth_body_set_awake(world_, id_, awake ? 1 : 0)); }
    Ret<void> set_damping(float linear, float angular) const {
        return P::check(hearth_body_set_damping(world_, id_, linear, angular));
    }
    // Runtime setters (issue 14), each with its getter.
    Ret<void> set_type(BodyType t) const {
        return P::check(hearth_body_set_type(world_, id_, static_cast<uint32_t>(t)));
    }
    Ret<float> gravity_scale() const { HEARTH_CPP_READ(float, hearth_body_get_gravity_scale(world_, id_, &out)); }
    Ret<void> set_gravity_scale(float scale) const {
        return P::check(hearth_body_set_gravity_scale(world_, id_, scale));
    }
    // HEARTH_LOCK_* bits ORed (world axes); setting zeroes the locked velocity components.
    Ret<uint32_t> locked_axes() const { HEARTH_CPP_READ(uint32_t, hearth_body_get_locked_axes(world_, id_, &out)); }
    Ret<void> set_locked_axes(uint32_t locked_axes) const {
        return P::check(hearth_body_set_locked_axes(world_, id_, locked_axes));
    }
    Ret<MassData> mass_data() const { HEARTH_CPP_READ(MassData, hearth_body_get_mass_data(world_, id_, &out)); }
    Ret<void> set_mass_data(const MassData &data) const {
        return P::check(hearth_body_set_mass_data(world_, id_, &data));
    }
    Ret<void> reset_mass_data() const { return P::check(hearth_body_reset_mass_data(world_, id_)); }
    Ret<bool> is_enabled() const { HEARTH_CPP_READ(bool, hearth_body_is_enabled(world_, id_, &out)); }
    Ret<void> enable() const { return P::check(hearth_body_enable(world_, id_)); }
    Ret<void> disable() const { return P::check(hearth_body_disable(world_, id_)); }
    Ret<void> apply_force(Vec3 f) const { return P::check(hearth_body_apply_force(world_, id_, f)); }
    Ret<void> apply_torque(Vec3 t) const { return P::check(hearth_body_apply_torque(world_, id_, t)); }
    Ret<void> apply_linear_impulse(Vec3 j) const {
        return P::check(hearth_body_apply_linear_impulse(world_, id_, j));
    }
    Ret<void> apply_angular_impulse(Vec3 j) const {
        return P::check(hearth_body_apply_angular_impulse(world_, id_, j));
    }
    Ret<void> apply_force_at_point(Vec3 force, Vec3 point) const {
        return P::check(hearth_body_apply_force_at_point(world_, id_, force, point));
    }
    Ret<void> apply_impulse_at_point(Vec3 impulse, Vec3 point) const {
        return P::check(hearth_body_apply_impulse_at_point(world_, id_, impulse, point));
    }

    Ret<BasicShape<P>> add(const Sphere &s, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_sphere(world_, id_, &def, &s, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    Ret<BasicShape<P>> add(const Box &b, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_box(world_, id_, &def, &b, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    Ret<BasicShape<P>> add(const Capsule &c, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_capsule(world_, id_, &def, &c, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    Ret<BasicShape<P>> add(const Plane &p, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_plane(world_, id_, &def, &p, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    Ret<BasicShape<P>> add(const HullShape &h, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_hull(world_, id_, &def, &h, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    /** Static and kinematic bodies only (InvalidArgument on a dynamic body). */
    Ret<BasicShape<P>> add(const MeshShape &m, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_mesh(world_, id_, &def, &m, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }
    /** Static and kinematic bodies only (InvalidArgument on a dynamic body). */
    Ret<BasicShape<P>> add(const HeightfieldShape &h, const ShapeDef &def = shape_def()) const {
        ShapeId id{};
        const HearthResult r = hearth_shape_create_heightfield(world_, id_, &def, &h, &id);
        return P::template value<BasicShape<P>>(r, BasicShape<P>(world_, id));
    }

    /** Destroys the body, its shapes and joints (see hearth_body_destroy). */
    Ret<void> destroy() const { return P::check(hearth_body_destroy(world_, id_)); }

private:
    HearthWorld *world_ = nullptr;
    BodyId id_{0, 0};
};

/** A shape on a body. */
template <class P> class BasicShape {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicShape() noexcept = default;
    BasicShape(HearthWorld *world, ShapeId id) noexcept : world_(world), id_(id) {}
    ShapeId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicShape &a, const BasicShape &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicShape &a, const BasicShape &b) noexcept { return !(a == b); }

    Ret<BasicBody<P>> body() const {
        BodyId b{};
        const HearthResult r = hearth_shape_get_body(world_, id_, &b);
        return P::template value<BasicBody<P>>(r, BasicBody<P>(world_, b));
    }
    Ret<void> destroy() const { return P::check(hearth_shape_destroy(world_, id_)); }
    /** The shape's collision filter. */
    Ret<Filter> filter() const { HEARTH_CPP_READ(Filter, hearth_shape_get_filter(world_, id_, &out)); }
    /** Changes the filter; pairs are re-evaluated at the next step. */
    Ret<void> set_filter(const Filter &f) const { return P::check(hearth_shape_set_filter(world_, id_, f)); }

    // Runtime setters (issue 14), each with its getter.
    /** (static, dynamic) friction coefficients. */
    Ret<std::pair<float, float>> friction() const {
        float s = 0, d = 0;
        const HearthResult r = hearth_shape_get_friction(world_, id_, &s, &d);
        return P::template value<std::pair<float, float>>(r, std::make_pair(s, d));
    }
    Ret<void> set_friction(float static_friction, float dynamic_friction) const {
        return P::check(hearth_shape_set_friction(world_, id_, static_friction, dynamic_friction));
    }
    Ret<float> restitution() const { HEARTH_CPP_READ(float, hearth_shape_get_restitution(world_, id_, &out)); }
    Ret<void> set_restitution(float x) const { return P::check(hearth_shape_set_restitution(world_, id_, x)); }
    Ret<float> rolling_resistance() const {
        HEARTH_CPP_READ(float, hearth_shape_get_rolling_resistance(world_, id_, &out));
    }
    Ret<void> set_rolling_resistance(float x) const {
        return P::check(hearth_shape_set_rolling_resistance(world_, id_, x));
    }
    Ret<float> torsional_friction() const {
        HEARTH_CPP_READ(float, hearth_shape_get_torsional_friction(world_, id_, &out));
    }
    Ret<void> set_torsional_friction(float x) const {
        return P::check(hearth_shape_set_torsional_friction(world_, id_, x));
    }
    Ret<float> density() const { HEARTH_CPP_READ(float, hearth_shape_get_density(world_, id_, &out)); }
    Ret<void> set_density(float x) const { return P::check(hearth_shape_set_density(world_, id_, x)); }
    Ret<uint64_t> user_data() const { HEARTH_CPP_READ(uint64_t, hearth_shape_get_user_data(world_, id_, &out)); }
    Ret<void> set_user_data(uint64_t x) const { return P::check(hearth_shape_set_user_data(world_, id_, x)); }

private:
    HearthWorld *world_ = nullptr;
    ShapeId id_{0, 0};
};

/** A joint between two bodies (or a body and the world). */
template <class P> class BasicJoint {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicJoint() noexcept = default;
    BasicJoint(HearthWorld *world, JointId id) noexcept : world_(world), id_(id) {}
    JointId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicJoint &a, const BasicJoint &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicJoint &a, const BasicJoint &b) noexcept { return !(a == b); }

    Ret<JointType> type() const {
        uint32_t t = 0;
        const HearthResult r = hearth_joint_get_type(world_, id_, &t);
        return P::template value<JointType>(r, static_cast<JointType>(t));
    }
    /** Body A and body B (B is null for a joint to the world). */
    Ret<std::pair<BasicBody<P>, BasicBody<P>>> bodies() const {
        BodyId a{}, b{};
        const HearthResult r = hearth_joint_get_bodies(world_, id_, &a, &b);
        return P::template value<std::pair<BasicBody<P>, BasicBody<P>>>(
            r, std::make_pair(BasicBody<P>(world_, a), BasicBody<P>(world_, b)));
    }
    Ret<void> set_motor(bool enable, float speed, float max) const {
        return P::check(hearth_joint_set_motor(world_, id_, enable ? 1 : 0, speed, max));
    }
    Ret<Motor> motor() const {
        Motor m;
        const HearthResult r = hearth_joint_get_motor(world_, id_, &m.enabled, &m.speed, &m.max);
        return P::template value<Motor>(r, m);
    }
    Ret<void> set_limits(bool enable, float lower, float upper) const {
        return P::check(hearth_joint_set_limits(world_, id_, enable ? 1 : 0, lower, upper));
    }
    Ret<Limits> limits() const {
        Limits l;
        const HearthResult r = hearth_joint_get_limits(world_, id_, &l.enabled, &l.lower, &l.upper);
        return P::template value<Limits>(r, l);
    }
    Ret<void> set_cone_limit(bool enable, float angle) const {
        return P::check(hearth_joint_set_cone_limit(world_, id_, enable ? 1 : 0, angle));
    }
    Ret<ConeLimit> cone_limit() const {
        ConeLimit c;
        const HearthResult r = hearth_joint_get_cone_limit(world_, id_, &c.enabled, &c.angle);
        return P::template value<ConeLimit>(r, c);
    }
    Ret<void> set_spring(bool enable, float hertz, float damping_ratio) const {
        return P::check(hearth_joint_set_spring(world_, id_, enable ? 1 : 0, hertz, damping_ratio));
    }
    Ret<Spring> spring() const {
        Spring s;
        const HearthResult r = hearth_joint_get_spring(world_, id_, &s.enabled, &s.hertz, &s.damping_ratio);
        return P::template value<Spring>(r, s);
    }
    Ret<JointForce> force() const {
        JointForce f;
        const HearthResult r = hearth_joint_get_force(world_, id_, &f.force, &f.torque);
        return P::template value<JointForce>(r, f);
    }
    Ret<bool> is_broken() const { HEARTH_CPP_READ(bool, hearth_joint_is_broken(world_, id_, &out)); }
    Ret<void> destroy() const { return P::check(hearth_joint_destroy(world_, id_)); }

private:
    HearthWorld *world_ = nullptr;
    JointId id_{0, 0};
};

/** A particle (point mass). */
template <class P> class BasicParticle {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicParticle() noexcept = default;
    BasicParticle(HearthWorld *world, ParticleId id) noexcept : world_(world), id_(id) {}
    ParticleId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicParticle &a, const BasicParticle &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicParticle &a, const BasicParticle &b) noexcept { return !(a == b); }

    Ret<Vec3> position() const { HEARTH_CPP_READ(Vec3, hearth_particle_get_position(world_, id_, &out)); }
    Ret<Vec3> velocity() const { HEARTH_CPP_READ(Vec3, hearth_particle_get_velocity(world_, id_, &out)); }
    Ret<bool> is_awake() const { HEARTH_CPP_READ(bool, hearth_particle_is_awake(world_, id_, &out)); }
    Ret<uint64_t> user_data() const {
        HEARTH_CPP_READ(uint64_t, hearth_particle_get_user_data(world_, id_, &out));
    }
    Ret<void> set_position(Vec3 p) const { return P::check(hearth_particle_set_position(world_, id_, p)); }
    Ret<void> set_velocity(Vec3 v) const { return P::check(hearth_particle_set_velocity(world_, id_, v)); }
    Ret<void> apply_force(Vec3 f) const { return P::check(hearth_particle_apply_force(world_, id_, f)); }
    Ret<void> apply_impulse(Vec3 j) const { return P::check(hearth_particle_apply_impulse(world_, id_, j)); }
    Ret<void> set_awake(bool awake) const {
        return P::check(hearth_particle_set_awake(world_, id_, awake ? 1 : 0));
    }
    Ret<void> destroy() const { return P::check(hearth_particle_destroy(world_, id_)); }

private:
    HearthWorld *world_ = nullptr;
    ParticleId id_{0, 0};
};

/** A soft body (XPBD mesh). */
template <class P> class BasicSoftBody {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicSoftBody() noexcept = default;
    BasicSoftBody(HearthWorld *world, SoftBodyId id) noexcept : world_(world), id_(id) {}
    SoftBodyId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicSoftBody &a, const BasicSoftBody &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicSoftBody &a, const BasicSoftBody &b) noexcept { return !(a == b); }

    Ret<size_t> vertex_count() const {
        HEARTH_CPP_READ(size_t, hearth_soft_body_get_vertex_count(world_, id_, &out));
    }
    Ret<size_t> triangle_count() const {
        HEARTH_CPP_READ(size_t, hearth_soft_body_get_triangle_count(world_, id_, &out));
    }
    /** Fills the caller's array with every vertex position; returns the vertex count. */
    Ret<size_t> positions(Span<Vec3> out_positions) const {
        HEARTH_CPP_READ(size_t, hearth_soft_body_get_positions(world_, id_, out_positions.data(),
                                                               out_positions.size(), &out));
    }
    Ret<std::vector<Vec3>> positions() const { return read_all<Vec3>(&hearth_soft_body_get_positions); }
    /** Fills the caller's array with every vertex normal; returns the vertex count. */
    Ret<size_t> normals(Span<Vec3> out_normals) const {
        HEARTH_CPP_READ(size_t, hearth_soft_body_get_normals(world_, id_, out_normals.data(),
                                                             out_normals.size(), &out));
    }
    Ret<std::vector<Vec3>> normals() const { return read_all<Vec3>(&hearth_soft_body_get_normals); }
    Ret<std::vector<uint32_t>> indices() const { return read_all<uint32_t>(&hearth_soft_body_get_indices); }
    Ret<Vec3> vertex_position(uint32_t vertex) const {
        HEARTH_CPP_READ(Vec3, hearth_soft_body_get_vertex_position(world_, id_, vertex, &out));
    }
    Ret<Vec3> vertex_velocity(uint32_t vertex) const {
        HEARTH_CPP_READ(Vec3, hearth_soft_body_get_vertex_velocity(world_, id_, vertex, &out));
    }
    Ret<Vec3> center() const { HEARTH_CPP_READ(Vec3, hearth_soft_body_get_center(world_, id_, &out)); }
    Ret<float> mass() const { HEARTH_CPP_READ(float, hearth_soft_body_get_mass(world_, id_, &out)); }
    Ret<float> volume() const { HEARTH_CPP_READ(float, hearth_soft_body_get_volume(world_, id_, &out)); }
    Ret<float> rest_volume() const {
        HEARTH_CPP_READ(float, hearth_soft_body_get_rest_volume(world_, id_, &out));
    }
    Ret<float> pressure() const { HEARTH_CPP_READ(float, hearth_soft_body_get_pressure(world_, id_, &out)); }
    Ret<uint64_t> user_data() const {
        HEARTH_CPP_READ(uint64_t, hearth_soft_body_get_user_data(world_, id_, &out));
    }
    Ret<void> set_pressure(float nrt) const { return P::check(hearth_soft_body_set_pressure(world_, id_, nrt)); }
    /** The settings the soft body runs with now (those given at creation or set since). */
    Ret<SoftBodySettings> settings() const {
        HEARTH_CPP_READ(SoftBodySettings, hearth_soft_body_get_settings(world_, id_, &out));
    }
    /** Replaces every setting from the next step: read with settings(), edit, write back.
     *  A bad value fails with Code::InvalidArgument and changes nothing. */
    Ret<void> set_settings(const SoftBodySettings &settings) const {
        return P::check(hearth_soft_body_set_settings(world_, id_, &settings));
    }
    /** The three compliances (>= 0): `edge` of the stretch springs (m/N, 0 inextensible),
     *  `bend` of the bending springs (m/N, INFINITY disables bending), `volume` of the volume
     *  constraint (0 incompressible). A bad value fails and changes nothing. */
    Ret<void> set_compliance(float edge, float bend, float volume) const {
        return P::check(hearth_soft_body_set_compliance(world_, id_, edge, bend, volume));
    }
    /** Pins a vertex where it is: to the world (default) or to a body. */
    Ret<void> pin_vertex(uint32_t vertex, BodyId body = BodyId{0, 0}) const {
        return P::check(hearth_soft_body_pin_vertex(world_, id_, vertex, body));
    }
    Ret<void> unpin_vertex(uint32_t vertex) const {
        return P::check(hearth_soft_body_unpin_vertex(world_, id_, vertex));
    }
    Ret<bool> is_vertex_pinned(uint32_t vertex) const {
        HEARTH_CPP_READ(bool, hearth_soft_body_is_vertex_pinned(world_, id_, vertex, &out));
    }
    Ret<void> apply_impulse(uint32_t vertex, Vec3 impulse) const {
        return P::check(hearth_soft_body_apply_impulse(world_, id_, vertex, impulse));
    }
    Ret<void> apply_impulse_all(Vec3 impulse) const {
        return P::check(hearth_soft_body_apply_impulse_all(world_, id_, impulse));
    }
    Ret<void> destroy() const { return P::check(hearth_soft_body_destroy(world_, id_)); }

private:
    // Asks for the count (capacity 0), then reads into a vector of that size.
    template <class T, class Fn> Ret<std::vector<T>> read_all(Fn fn) const {
        size_t count = 0;
        HearthResult r = fn(world_, id_, nullptr, 0, &count);
        std::vector<T> out(r == HEARTH_OK ? count : 0);
        if (r == HEARTH_OK && count > 0) {
            r = fn(world_, id_, out.data(), out.size(), &count);
        }
        return P::template value<std::vector<T>>(r, std::move(out));
    }

    HearthWorld *world_ = nullptr;
    SoftBodyId id_{0, 0};
};

/**
 * Shared geometry (a convex hull, triangle mesh or heightfield): world pointer and id. Shapes
 * instance it (Body::add(hull_shape(...))); destroy() is refused while shapes use it.
 */
template <class P, class Id> class BasicGeometry {
protected:
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicGeometry() noexcept = default;
    BasicGeometry(HearthWorld *world, Id id) noexcept : world_(world), id_(id) {}
    Id id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicGeometry &a, const BasicGeometry &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicGeometry &a, const BasicGeometry &b) noexcept { return !(a == b); }

protected:
    HearthWorld *world_ = nullptr;
    Id id_{0, 0};
};

/** A convex hull (hearth_hull_create). */
template <class P> class BasicHull : public BasicGeometry<P, HullId> {
    using Base = BasicGeometry<P, HullId>;
    template <class T> using Ret = typename P::template Ret<T>;
    using Base::id_;
    using Base::world_;

public:
    using Base::Base;
    /** A shape description instancing this hull. */
    HullShape shape(float scale = 1.0f, Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) const noexcept {
        return hull_shape(id_, scale, local);
    }
    Ret<uint32_t> vertex_count() const { HEARTH_CPP_READ(uint32_t, hearth_hull_get_vertex_count(world_, id_, &out)); }
    Ret<void> destroy() const { return P::check(hearth_hull_destroy(world_, id_)); }
};

/** A triangle mesh (hearth_mesh_create). */
template <class P> class BasicMesh : public BasicGeometry<P, MeshId> {
    using Base = BasicGeometry<P, MeshId>;
    template <class T> using Ret = typename P::template Ret<T>;
    using Base::id_;
    using Base::world_;

public:
    using Base::Base;
    MeshShape shape(Vec3 scale = Vec3{1, 1, 1}, Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) const noexcept {
        return mesh_shape(id_, scale, local);
    }
    Ret<uint32_t> triangle_count() const {
        HEARTH_CPP_READ(uint32_t, hearth_mesh_get_triangle_count(world_, id_, &out));
    }
    Ret<uint32_t> degenerate_count() const {
        HEARTH_CPP_READ(uint32_t, hearth_mesh_get_degenerate_count(world_, id_, &out));
    }
    Ret<void> destroy() const { return P::check(hearth_mesh_destroy(world_, id_)); }
};

/** A heightfield (hearth_heightfield_create). */
template <class P> class BasicHeightfield : public BasicGeometry<P, HeightfieldId> {
    using Base = BasicGeometry<P, HeightfieldId>;
    template <class T> using Ret = typename P::template Ret<T>;
    using Base::id_;
    using Base::world_;

public:
    using Base::Base;
    HeightfieldShape shape(Vec3 scale = Vec3{1, 1, 1},
                           Transform local = Transform{Vec3{0, 0, 0}, quat_identity()}) const noexcept {
        return heightfield_shape(id_, scale, local);
    }
    Ret<void> destroy() const { return P::check(hearth_heightfield_destroy(world_, id_)); }
};

/** A force or contact generator (built-in or user). Destroy through the World. */
template <class P> class BasicGenerator {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicGenerator() noexcept = default;
    BasicGenerator(HearthWorld *world, GeneratorId id) noexcept : world_(world), id_(id) {}
    GeneratorId id() const noexcept { return id_; }
    HearthWorld *world() const noexcept { return world_; }
    bool is_null() const noexcept { return hearth::is_null(id_); }
    friend bool operator==(const BasicGenerator &a, const BasicGenerator &b) noexcept {
        return a.world_ == b.world_ && same_id(a.id_, b.id_);
    }
    friend bool operator!=(const BasicGenerator &a, const BasicGenerator &b) noexcept { return !(a == b); }

    Ret<GeneratorType> type() const {
        uint32_t t = 0;
        const HearthResult r = hearth_generator_get_type(world_, id_, &t);
        return P::template value<GeneratorType>(r, static_cast<GeneratorType>(t));
    }
    Ret<Attachments> attachments() const {
        Attachments a;
        const HearthResult r = hearth_generator_get_attachment_count(world_, id_, &a.bodies, &a.particles);
        return P::template value<Attachments>(r, a);
    }
    Ret<void> attach(const BasicBody<P> &body) const {
        return P::check(hearth_generator_attach_body(world_, id_, body.id()));
    }
    Ret<void> attach(const BasicParticle<P> &particle) const {
        return P::check(hearth_generator_attach_particle(world_, id_, particle.id()));
    }
    /** Attaches many particles at once, all or nothing. */
    Ret<void> attach(Span<const ParticleId> particles) const {
        return P::check(hearth_generator_attach_particles(world_, id_, particles.data(), particles.size()));
    }
    Ret<void> detach(const BasicBody<P> &body) const {
        return P::check(hearth_generator_detach_body(world_, id_, body.id()));
    }
    Ret<void> detach(const BasicParticle<P> &particle) const {
        return P::check(hearth_generator_detach_particle(world_, id_, particle.id()));
    }

private:
    HearthWorld *world_ = nullptr;
    GeneratorId id_{0, 0};
};

/** Iterates over a C array of ids, yielding handles. */
template <class Handle, class Id> class HandleRange {
public:
    class iterator {
    public:
        iterator(HearthWorld *w, const Id *p) noexcept : w_(w), p_(p) {}
        Handle operator*() const noexcept { return Handle(w_, *p_); }
        iterator &operator++() noexcept {
            ++p_;
            return *this;
        }
        bool operator!=(const iterator &o) const noexcept { return p_ != o.p_; }
        bool operator==(const iterator &o) const noexcept { return p_ == o.p_; }

    private:
        HearthWorld *w_;
        const Id *p_;
    };
    HandleRange(HearthWorld *w, const Id *ids, size_t n) noexcept : w_(w), ids_(ids), n_(n) {}
    iterator begin() const noexcept { return iterator(w_, ids_); }
    iterator end() const noexcept { return iterator(w_, ids_ + n_); }
    size_t size() const noexcept { return n_; }
    Handle operator[](size_t i) const noexcept { return Handle(w_, ids_[i]); }

private:
    HearthWorld *w_;
    const Id *ids_;
    size_t n_;
};

// --------------------------------------------------------------------------- the world view

/**
 * A non-owning view of a world: everything except stepping and the lambda generators.
 * Force and contact lambdas get one through their context; World derives from it.
 */
template <class P> class BasicWorldRef {
protected:
    template <class T> using Ret = typename P::template Ret<T>;

public:
    using Body = BasicBody<P>;
    using Shape = BasicShape<P>;
    using Joint = BasicJoint<P>;
    using Particle = BasicParticle<P>;
    using SoftBody = BasicSoftBody<P>;
    using Generator = BasicGenerator<P>;
    using Hull = BasicHull<P>;
    using Mesh = BasicMesh<P>;
    using Heightfield = BasicHeightfield<P>;

    BasicWorldRef() noexcept = default;
    explicit BasicWorldRef(HearthWorld *world) noexcept : world_(world) {}
    /** The C world (to mix in C calls). */
    HearthWorld *get() const noexcept { return world_; }
    explicit operator bool() const noexcept { return world_ != nullptr; }

    // Handles from C ids.
    Body body(BodyId id) const noexcept { return Body(world_, id); }
    Shape shape(ShapeId id) const noexcept { return Shape(world_, id); }
    Joint joint(JointId id) const noexcept { return Joint(world_, id); }
    Particle particle(ParticleId id) const noexcept { return Particle(world_, id); }
    SoftBody soft_body(SoftBodyId id) const noexcept { return SoftBody(world_, id); }
    Generator generator(GeneratorId id) const noexcept { return Generator(world_, id); }

    // World settings and counters.
    Ret<Vec3> gravity() const { HEARTH_CPP_READ(Vec3, hearth_world_get_gravity(world_, &out)); }
    /** `hearth_world_draw`: the world through `d`'s callbacks as its flags ask. */
    Ret<void> draw(const DebugDraw &d) const { return P::check(hearth_world_draw(world_, &d)); }
    Ret<void> set_gravity(Vec3 g) const { return P::check(hearth_world_set_gravity(world_, g)); }
    Ret<WorldCounters> counters() const { HEARTH_CPP_READ(WorldCounters, hearth_world_get_counters(world_, &out)); }
    /** hearth_world_get_hash: equal for equal runs at any worker count and lane width. */
    Ret<uint64_t> state_hash() const { HEARTH_CPP_READ(uint64_t, hearth_world_get_hash(world_, &out)); }
    /** hearth_world_rebuild_broadphase: after loading a level; ids and query results unchanged. */
    Ret<void> rebuild_broadphase() const { return P::check(hearth_world_rebuild_broadphase(world_)); }

    // Events of the last step: arrays owned by the world, valid until the next step or destroy.
    Ret<ContactEvents> contact_events() const {
        HEARTH_CPP_READ(ContactEvents, hearth_world_get_contact_events(world_, &out));
    }
    Ret<SensorEvents> sensor_events() const {
        HEARTH_CPP_READ(SensorEvents, hearth_world_get_sensor_events(world_, &out));
    }
    Ret<BodyEvents> body_events() const { HEARTH_CPP_READ(BodyEvents, hearth_world_get_body_events(world_, &out)); }
    // Snapshots (rollback, replays): docs/snapshot-format.md.
    /** Bytes save_snapshot() returns now (hearth_world_snapshot_size). */
    Ret<size_t> snapshot_size() const { HEARTH_CPP_READ(size_t, hearth_world_snapshot_size(world_, &out)); }
    /** Everything that affects the world's future, as bytes (hearth_world_snapshot_save). */
    Ret<std::vector<uint8_t>> save_snapshot() const {
        size_t size = 0;
        HearthResult r = hearth_world_snapshot_size(world_, &size);
        std::vector<uint8_t> out(r == HEARTH_OK ? size : 0);
        if (r == HEARTH_OK) {
            size_t written = 0;
            r = hearth_world_snapshot_save(world_, out.data(), out.size(), &written);
            out.resize(r == HEARTH_OK ? written : 0);
        }
        return P::template value<std::vector<uint8_t>>(r, std::move(out));
    }
    /**
     * Restores a snapshot of this world or another (hearth_world_snapshot_restore); on error
     * (Code::InvalidArgument: truncated, corrupted, another version) nothing changes. Into
     * the world it came from, lambda generators keep running; into another, set their
     * callbacks again (user_generators_missing_callback lists them).
     */
    Ret<void> restore_snapshot(const uint8_t *data, size_t size) const {
        return P::check(hearth_world_snapshot_restore(world_, data, size));
    }
    Ret<void> restore_snapshot(const std::vector<uint8_t> &bytes) const {
        return restore_snapshot(bytes.data(), bytes.size());
    }
    /** User generators without a callback (hearth_world_get_user_generators_missing_callback). */
    Ret<std::vector<Generator>> user_generators_missing_callback() const {
        size_t count = 0;
        HearthResult r = hearth_world_get_user_generators_missing_callback(world_, nullptr, 0, &count);
        std::vector<GeneratorId> ids(r == HEARTH_OK ? count : 0);
        if (r == HEARTH_OK && count > 0) {
            r = hearth_world_get_user_generators_missing_callback(world_, ids.data(), ids.size(), &count);
        }
        std::vector<Generator> out;
        if (r == HEARTH_OK) {
            for (const GeneratorId &id : ids) {
                out.push_back(Generator(world_, id));
            }
        }
        return P::template value<std::vector<Generator>>(r, std::move(out));
    }
    /** Sets a user force generator's callback (hearth_generator_set_user_force_callback). */
    Ret<void> set_user_force_callback(const Generator &g, const UserForceGeneratorDef &def) const {
        return P::check(hearth_generator_set_user_force_callback(world_, g.id(), &def));
    }
    /** Sets a user contact generator's callback (hearth_generator_set_user_contact_callback). */
    Ret<void> set_user_contact_callback(const Generator &g, const UserContactGeneratorDef &def) const {
        return P::check(hearth_generator_set_user_contact_callback(world_, g.id(), &def));
    }

    // Bodies.
    Ret<Body> create_body(const BodyDef &def) const {
        BodyId id{};
        const HearthResult r = hearth_body_create(world_, &def, &id);
        return P::template value<Body>(r, Body(world_, id));
    }
    Ret<Body> create_body(BodyType type, Vec3 position = Vec3{0, 0, 0}) const {
        return create_body(body_def(type, position));
    }
    /** Bulk read: the transforms of `bodies` into the caller-owned `out` (at least as long). */
    Ret<void> transforms(Span<const BodyId> bodies, Span<Transform> out) const {
        if (out.size() < bodies.size()) {
            return P::fail(Code::BufferTooSmall, "hearth.hpp: transforms: output shorter than the id list");
        }
        return P::check(hearth_world_get_transforms(world_, bodies.data(), bodies.size(), out.data()));
    }
    /** Bulk read into a new vector (allocates; prefer the span form every frame). */
    Ret<std::vector<Transform>> transforms(Span<const BodyId> bodies) const {
        std::vector<Transform> out(bodies.size());
        const HearthResult r = hearth_world_get_transforms(world_, bodies.data(), bodies.size(), out.data());
        return P::template value<std::vector<Transform>>(r, std::move(out));
    }
    /** Bulk read for handles (gathers their ids; allocates). */
    Ret<std::vector<Transform>> transforms(const std::vector<Body> &bodies) const {
        std::vector<BodyId> ids;
        ids.reserve(bodies.size());
        for (const Body &b : bodies) {
            ids.push_back(b.id());
        }
        return transforms(Span<const BodyId>(ids));
    }

    // Particles.
    Ret<Particle> create_particle(const ParticleDef &def) const {
        ParticleId id{};
        const HearthResult r = hearth_particle_create(world_, &def, &id);
        return P::template value<Particle>(r, Particle(world_, id));
    }
    /** Emits a burst; returns the new particles. */
    Ret<std::vector<Particle>> emit_burst(const BurstDef &def) const {
        std::vector<ParticleId> ids(def.count);
        size_t n = 0;
        const HearthResult r = hearth_particle_emit_burst(world_, &def, ids.data(), ids.size(), &n);
        std::vector<Particle> out;
        if (r == HEARTH_OK) {
            out.reserve(n);
            for (size_t i = 0; i < n; i++) {
                out.push_back(Particle(world_, ids[i]));
            }
        }
        return P::template value<std::vector<Particle>>(r, std::move(out));
    }
    Ret<size_t> particle_count() const { HEARTH_CPP_READ(size_t, hearth_world_get_particle_count(world_, &out)); }
    /** Every live particle into caller-owned arrays (each may be empty to skip it, the others
     * at least particle_count() long); returns how many were written. */
    Ret<size_t> particles(Span<ParticleId> ids, Span<Vec3> positions, Span<Vec3> velocities) const {
        size_t capacity = SIZE_MAX;
        for (size_t s : {ids.size(), positions.size(), velocities.size()}) {
            if (s != 0 && s < capacity) {
                capacity = s;
            }
        }
        if (capacity == SIZE_MAX) {
            capacity = 0;
        }
        HEARTH_CPP_READ(size_t, hearth_world_get_particles(world_, ids.empty() ? nullptr : ids.data(),
                                                           positions.empty() ? nullptr : positions.data(),
                                                           velocities.empty() ? nullptr : velocities.data(),
                                                           capacity, &out));
    }
    /** Positions of the given particles into the caller-owned `out`. */
    Ret<void> particle_positions(Span<const ParticleId> particles, Span<Vec3> out) const {
        if (out.size() < particles.size()) {
            return P::fail(Code::BufferTooSmall, "hearth.hpp: particle_positions: output shorter than the id list");
        }
        return P::check(
            hearth_world_get_particle_positions(world_, particles.data(), particles.size(), out.data()));
    }
    /** The particles that expired in the last step (world-owned, valid until the next step). */
    Ret<Span<const ExpiredParticle>> expired_particles() const {
        const ExpiredParticle *array = nullptr;
        size_t n = 0;
        const HearthResult r = hearth_world_get_expired_particles(world_, &array, &n);
        return P::template value<Span<const ExpiredParticle>>(r, Span<const ExpiredParticle>(array, n));
    }
    Ret<void> set_particle_iterations(uint32_t velocity_iterations, uint32_t position_iterations) const {
        return P::check(hearth_world_set_particle_iterations(world_, velocity_iterations, position_iterations));
    }

    // Joints.
    Ret<Joint> create_joint(const BallJointDef &def) const { return joint_from(hearth_joint_create_ball, def); }
    Ret<Joint> create_joint(const HingeJointDef &def) const { return joint_from(hearth_joint_create_hinge, def); }
    Ret<Joint> create_joint(const FixedJointDef &def) const { return joint_from(hearth_joint_create_fixed, def); }
    Ret<Joint> create_joint(const DistanceJointDef &def) const {
        return joint_from(hearth_joint_create_distance, def);
    }
    Ret<Joint> create_joint(const SliderJointDef &def) const {
        return joint_from(hearth_joint_create_slider, def);
    }
    // Queries (they change nothing). A miss has the null shape id (see is_hit).
    /** The nearest hit of the ray from `origin` along `translation`. */
    Ret<RayHit> cast_ray_closest(Vec3 origin, Vec3 translation, const QueryFilter &f = query_filter()) const {
        HEARTH_CPP_READ(RayHit, hearth_world_cast_ray_closest(world_, origin, translation, &f, &out));
    }
    /** Calls `fn(const RayHit &) -> float` for the hits (-1 ignore, 0 stop, a fraction clips,
     * 1 continue). An exception thrown by `fn` stops the cast and is rethrown here. */
    template <class Fn> Ret<void> cast_ray(Vec3 origin, Vec3 translation, Fn &&fn, const QueryFilter &f = query_filter()) const {
        struct Ctx {
            Fn *fn;
#if HEARTH_CPP_EXCEPTIONS
            std::exception_ptr error;
#endif
        } ctx;
        ctx.fn = &fn;
        auto trampoline = [](void *user, const HearthRayHit *hit) noexcept -> float {
            Ctx *c = static_cast<Ctx *>(user);
#if HEARTH_CPP_EXCEPTIONS
            try {
                return static_cast<float>((*c->fn)(*hit));
            } catch (...) {
                c->error = std::current_exception();
                return 0.0f;
            }
#else
            return static_cast<float>((*c->fn)(*hit));
#endif
        };
        const HearthResult r = hearth_world_cast_ray(world_, origin, translation, &f, trampoline, &ctx);
#if HEARTH_CPP_EXCEPTIONS
        if (ctx.error) {
            std::rethrow_exception(ctx.error);
        }
#endif
        return P::check(r);
    }
    /** Casts `rays` into the caller-owned `out` (at least as long), nearest hit each. */
    Ret<void> cast_rays(Span<const RayInput> rays, Span<RayHit> out, const QueryFilter &f = query_filter()) const {
        if (out.size() < rays.size()) {
            return P::fail(Code::BufferTooSmall, "hearth.hpp: cast_rays: output shorter than the rays");
        }
        return P::check(hearth_world_cast_rays(world_, rays.data(), rays.size(), &f, out.data()));
    }
    /** Moves `shape` (query_shape(...)) from `at` along `translation`: the first hit. */
    Ret<RayHit> cast_shape(const QueryShape &shape, const Transform &at, Vec3 translation,
                           const QueryFilter &f = query_filter()) const {
        HEARTH_CPP_READ(RayHit, hearth_world_cast_shape(world_, &shape, &at, translation, &f, &out));
    }
    /** The shapes overlapping `shape` at `at`. */
    Ret<std::vector<Shape>> overlap_shape(const QueryShape &shape, const Transform &at,
                                          const QueryFilter &f = query_filter()) const {
        return overlap([&](ShapeId *ids, size_t cap, size_t *n) {
            return hearth_world_overlap_shape(world_, &shape, &at, &f, ids, cap, n);
        });
    }
    /** The shapes whose bounds overlap the box `lower`..`upper`. */
    Ret<std::vector<Shape>> overlap_aabb(Vec3 lower, Vec3 upper, const QueryFilter &f = query_filter()) const {
        return overlap([&](ShapeId *ids, size_t cap, size_t *n) {
            return hearth_world_overlap_aabb(world_, lower, upper, &f, ids, cap, n);
        });
    }
    /** The solid shapes containing `point`. */
    Ret<std::vector<Shape>> overlap_point(Vec3 point, const QueryFilter &f = query_filter()) const {
        return overlap([&](ShapeId *ids, size_t cap, size_t *n) {
            return hearth_world_overlap_point(world_, point, &f, ids, cap, n);
        });
    }

    /** The joints that broke in the last step. */
    Ret<std::vector<Joint>> broken_joints() const {
        size_t n = 0;
        HearthResult r = hearth_world_get_broken_joints(world_, nullptr, 0, &n);
        std::vector<JointId> ids(r == HEARTH_OK ? n : 0);
        if (r == HEARTH_OK && n > 0) {
            r = hearth_world_get_broken_joints(world_, ids.data(), ids.size(), &n);
        }
        std::vector<Joint> out;
        for (const JointId &id : ids) {
            out.push_back(Joint(world_, id));
        }
        return P::template value<std::vector<Joint>>(r, std::move(out));
    }

    // Built-in generators (destroy them with destroy_generator).
    Ret<Generator> create_gravity_generator(const GravityGeneratorDef &def) const {
        return generator_from(hearth_generator_create_gravity, def);
    }
    Ret<Generator> create_drag_generator(const DragGeneratorDef &def) const {
        return generator_from(hearth_generator_create_drag, def);
    }
    Ret<Generator> create_spring_generator(const SpringGeneratorDef &def) const {
        return generator_from(hearth_generator_create_spring, def);
    }
    Ret<Generator> create_bungee_generator(const SpringGeneratorDef &def) const {
        return generator_from(hearth_generator_create_bungee, def);
    }
    Ret<Generator> create_stiff_spring_generator(const StiffSpringGeneratorDef &def) const {
        return generator_from(hearth_generator_create_stiff_spring, def);
    }
    Ret<Generator> create_buoyancy_generator(const BuoyancyGeneratorDef &def) const {
        return generator_from(hearth_generator_create_buoyancy, def);
    }
    Ret<Generator> create_explosion_generator(const ExplosionGeneratorDef &def) const {
        return generator_from(hearth_generator_create_explosion, def);
    }
    Ret<Generator> create_rod(const RodGeneratorDef &def) const {
        return generator_from(hearth_generator_create_rod, def);
    }
    Ret<Generator> create_cable(const CableGeneratorDef &def) const {
        return generator_from(hearth_generator_create_cable, def);
    }
    /** A user generator with a plain C callback (the lambda form is World::add_*_generator). */
    Ret<Generator> create_user_force_generator(const UserForceGeneratorDef &def) const {
        return generator_from(hearth_generator_create_user_force, def);
    }
    Ret<Generator> create_user_contact_generator(const UserContactGeneratorDef &def) const {
        return generator_from(hearth_generator_create_user_contact, def);
    }
    /** Destroys a generator. (World::destroy_generator also frees a lambda's box.) */
    Ret<void> destroy_generator(const Generator &g) const {
        return P::check(hearth_generator_destroy(world_, g.id()));
    }

    // Soft bodies.
    /** From a triangle mesh; `masses` empty for equal masses. The arrays are copied. */
    Ret<SoftBody> create_soft_body(const SoftBodyDef &def, Span<const Vec3> vertices,
                                   Span<const uint32_t> indices, Span<const float> masses = {}) const {
        if (!masses.empty() && masses.size() != vertices.size()) {
            return P::template fail_value<SoftBody>(Code::InvalidArgument,
                                                    "hearth.hpp: create_soft_body: one mass per vertex");
        }
        SoftBodyId id{};
        const HearthResult r =
            hearth_soft_body_create_mesh(world_, &def, vertices.data(), vertices.size(), indices.data(),
                                         indices.size(), masses.empty() ? nullptr : masses.data(), &id);
        return P::template value<SoftBody>(r, SoftBody(world_, id));
    }
    Ret<SoftBody> create_soft_icosphere(const SoftBodyDef &def, float radius, uint32_t subdivisions) const {
        SoftBodyId id{};
        const HearthResult r = hearth_soft_body_create_icosphere(world_, &def, radius, subdivisions, &id);
        return P::template value<SoftBody>(r, SoftBody(world_, id));
    }
    Ret<SoftBody> create_soft_box(const SoftBodyDef &def, Vec3 half_extents, uint32_t cells_x, uint32_t cells_y,
                                  uint32_t cells_z) const {
        SoftBodyId id{};
        const HearthResult r =
            hearth_soft_body_create_box(world_, &def, half_extents, cells_x, cells_y, cells_z, &id);
        return P::template value<SoftBody>(r, SoftBody(world_, id));
    }
    Ret<SoftBody> create_cloth(const SoftBodyDef &def, float width, float height, uint32_t columns,
                               uint32_t rows) const {
        SoftBodyId id{};
        const HearthResult r = hearth_soft_body_create_cloth(world_, &def, width, height, columns, rows, &id);
        return P::template value<SoftBody>(r, SoftBody(world_, id));
    }
    Ret<size_t> soft_body_count() const { HEARTH_CPP_READ(size_t, hearth_world_get_soft_body_count(world_, &out)); }

    // Shared geometry (the arrays are copied).
    Hull hull(HullId id) const noexcept { return Hull(world_, id); }
    Mesh mesh(MeshId id) const noexcept { return Mesh(world_, id); }
    Heightfield heightfield(HeightfieldId id) const noexcept { return Heightfield(world_, id); }
    /** A convex hull of the points (in its own frame). */
    Ret<Hull> create_hull(Span<const Vec3> points, const HullDef &def = hull_def()) const {
        HullId id{};
        const HearthResult r = hearth_hull_create(world_, &def, points.data(), points.size(), &id);
        return P::template value<Hull>(r, Hull(world_, id));
    }
    /** A triangle mesh: three indices per triangle, counter-clockwise seen from the front. */
    Ret<Mesh> create_mesh(Span<const Vec3> vertices, Span<const uint32_t> indices) const {
        MeshId id{};
        const HearthResult r =
            hearth_mesh_create(world_, vertices.data(), vertices.size(), indices.data(), indices.size(), &id);
        return P::template value<Mesh>(r, Mesh(world_, id));
    }
    /** A heightfield of rows × columns row-major heights; `holes` empty or one 0/1 flag per cell. */
    Ret<Heightfield> create_heightfield(uint32_t rows, uint32_t columns, Span<const float> heights,
                                        Span<const uint8_t> holes = {}) const {
        if (heights.size() != static_cast<size_t>(rows) * columns) {
            return P::template fail_value<Heightfield>(Code::InvalidArgument,
                                                       "hearth.hpp: create_heightfield: heights must hold rows * columns values");
        }
        if (!holes.empty() && rows >= 2 && columns >= 2 && holes.size() != static_cast<size_t>(rows - 1) * (columns - 1)) {
            return P::template fail_value<Heightfield>(
                Code::InvalidArgument, "hearth.hpp: create_heightfield: holes must hold (rows - 1) * (columns - 1) flags");
        }
        HeightfieldId id{};
        const HearthResult r = hearth_heightfield_create(world_, rows, columns, heights.data(),
                                                         holes.empty() ? nullptr : holes.data(), &id);
        return P::template value<Heightfield>(r, Heightfield(world_, id));
    }

protected:
    /** Count, then fill: the ids an overlap query reports, as handles. */
    template <class Fn> Ret<std::vector<Shape>> overlap(Fn fn) const {
        size_t n = 0;
        HearthResult r = fn(nullptr, 0, &n);
        std::vector<ShapeId> ids(r == HEARTH_OK ? n : 0);
        if (r == HEARTH_OK && n > 0) {
            r = fn(ids.data(), ids.size(), &n);
        }
        std::vector<Shape> out;
        for (const ShapeId &id : ids) {
            out.push_back(Shape(world_, id));
        }
        return P::template value<std::vector<Shape>>(r, std::move(out));
    }
    template <class Fn, class Def> Ret<Joint> joint_from(Fn fn, const Def &def) const {
        JointId id{};
        const HearthResult r = fn(world_, &def, &id);
        return P::template value<Joint>(r, Joint(world_, id));
    }
    template <class Fn, class Def> Ret<Generator> generator_from(Fn fn, const Def &def) const {
        GeneratorId id{};
        const HearthResult r = fn(world_, &def, &id);
        return P::template value<Generator>(r, Generator(world_, id));
    }

    HearthWorld *world_ = nullptr;
};

// ------------------------------------------------------------------- generator contexts

/** What a force lambda is given: the step, its generator, its attached bodies and particles,
 * and the world (reads and forces work; structural changes fail with Code::WorldLocked). */
template <class P> class BasicForceContext {
public:
    BasicForceContext(HearthWorld *world, const HearthGeneratorContext *c) noexcept : world_(world), c_(c) {}
    float dt() const noexcept { return c_->dt; }
    BasicGenerator<P> generator() const noexcept { return BasicGenerator<P>(world_.get(), c_->generator); }
    HandleRange<BasicBody<P>, BodyId> bodies() const noexcept {
        return HandleRange<BasicBody<P>, BodyId>(world_.get(), c_->bodies, c_->body_count);
    }
    HandleRange<BasicParticle<P>, ParticleId> particles() const noexcept {
        return HandleRange<BasicParticle<P>, ParticleId>(world_.get(), c_->particles, c_->particle_count);
    }
    const BasicWorldRef<P> &world() const noexcept { return world_; }
    const HearthGeneratorContext &raw() const noexcept { return *c_; }

private:
    BasicWorldRef<P> world_;
    const HearthGeneratorContext *c_;
};

/** What a contact lambda is given: as a force context, plus the sink to add contacts to. */
template <class P> class BasicContactContext : public BasicForceContext<P> {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    BasicContactContext(HearthWorld *world, const HearthGeneratorContext *c, HearthContactSink *sink) noexcept
        : BasicForceContext<P>(world, c), sink_(sink) {}
    /** Adds a contact (Code::BufferTooSmall once the generator's capacity is used up). */
    Ret<void> add(const GeneratedContact &contact) const { return P::check(hearth_contact_sink_add(sink_, &contact)); }
    /** Contacts added so far in this call. */
    Ret<uint32_t> count() const {
        uint32_t n = 0, cap = 0;
        const HearthResult r = hearth_contact_sink_get_count(sink_, &n, &cap);
        return P::template value<uint32_t>(r, n);
    }
    /** Most contacts this call may add. */
    Ret<uint32_t> capacity() const {
        uint32_t n = 0, cap = 0;
        const HearthResult r = hearth_contact_sink_get_count(sink_, &n, &cap);
        return P::template value<uint32_t>(r, cap);
    }

private:
    HearthContactSink *sink_;
};

// ------------------------------------------------------------- lambda boxes and trampolines

namespace detail {
struct WorldState;

/** The heap home of one generator lambda, owned by its World's state. */
struct CallbackBox {
    explicit CallbackBox(WorldState *s) noexcept : state(s) {}
    virtual ~CallbackBox() = default;
    CallbackBox(const CallbackBox &) = delete;
    CallbackBox &operator=(const CallbackBox &) = delete;
    WorldState *state;
};

/** Everything a World owns besides the C world: lambda boxes and the step's first failure. */
struct WorldState {
    HearthWorld *world = nullptr;
    std::map<uint64_t, std::unique_ptr<CallbackBox>> boxes;
    /** The recording's write lambda (World::record_to), kept while it may be called. */
    std::unique_ptr<CallbackBox> record_box;
    /** The pair-filter and pre-solve lambdas (World::set_pair_filter, set_pre_solve). */
    std::unique_ptr<CallbackBox> pair_filter_box;
    std::unique_ptr<CallbackBox> pre_solve_box;
    bool failed = false;
    Code code = Code::Ok;
    std::string message;
#if HEARTH_CPP_EXCEPTIONS
    std::exception_ptr exception;
#endif

    WorldState() = default;
    WorldState(const WorldState &) = delete;
    WorldState &operator=(const WorldState &) = delete;
    // The C world goes first (no callback can run afterwards), then the boxes.
    ~WorldState() { hearth_world_destroy(world); }

    static uint64_t key(GeneratorId id) noexcept {
        return (static_cast<uint64_t>(id.generation) << 32) | static_cast<uint64_t>(id.index);
    }
    void clear_failure() noexcept {
        failed = false;
        code = Code::Ok;
        message.clear();
#if HEARTH_CPP_EXCEPTIONS
        exception = nullptr;
#endif
    }
    /** Keeps the first failure of a step. Must not throw (runs inside the trampolines). */
    void record(Code c, const char *text) noexcept {
        if (failed) {
            return;
        }
        failed = true;
        code = c;
#if HEARTH_CPP_EXCEPTIONS
        try {
            message = text;
        } catch (...) {
            message.clear(); // out of memory: the code alone must do
        }
#else
        message = text;
#endif
    }
};

/** Runs the lambda: void, or a Status whose failure is recorded. */
template <class F, class Ctx> inline void invoke_generator(F &fn, Ctx &ctx, WorldState &state) {
    using R = decltype(fn(ctx));
    static_assert(std::is_void<R>::value || std::is_same<std::decay_t<R>, Status>::value,
                  "a generator lambda returns void or hearth::Status");
    if constexpr (std::is_void<R>::value) {
        fn(ctx);
    } else {
        const Status s = fn(ctx);
        if (!s.ok()) {
            state.record(s.code(), s.message().c_str());
        }
    }
}

/** Calls `run` and turns whatever it throws into the state's failure. Never throws. */
template <class Run> inline void guarded(WorldState &state, Run &&run) noexcept {
    if (state.failed) {
        return; // an earlier lambda of this step failed: skip the rest of the step's lambdas
    }
#if HEARTH_CPP_EXCEPTIONS
    try {
        run();
    } catch (const Error &e) {
        state.record(e.code(), e.message().c_str());
        state.exception = std::current_exception();
    } catch (const std::exception &e) {
        state.record(Code::CallbackException, e.what());
        state.exception = std::current_exception();
    } catch (...) {
        state.record(Code::CallbackException, "unknown exception from a generator lambda");
        state.exception = std::current_exception();
    }
#else
    run();
#endif
}

template <class P, class F> struct ForceBox final : CallbackBox {
    ForceBox(WorldState *s, F f) : CallbackBox(s), fn(std::move(f)) {}
    F fn;
    static void trampoline(void *user_data, HearthWorld *world, const HearthGeneratorContext *c) noexcept {
        ForceBox *self = static_cast<ForceBox *>(user_data);
        guarded(*self->state, [&] {
            BasicForceContext<P> ctx(world, c);
            invoke_generator(self->fn, ctx, *self->state);
        });
    }
};

template <class P, class F> struct ContactBox final : CallbackBox {
    ContactBox(WorldState *s, F f) : CallbackBox(s), fn(std::move(f)) {}
    F fn;
    static void trampoline(void *user_data, HearthWorld *world, const HearthGeneratorContext *c,
                           HearthContactSink *sink) noexcept {
        ContactBox *self = static_cast<ContactBox *>(user_data);
        guarded(*self->state, [&] {
            BasicContactContext<P> ctx(world, c, sink);
            invoke_generator(self->fn, ctx, *self->state);
        });
    }
};
/** The heap home of a recording's write lambda: `bool(const uint8_t *, size_t)`. */
template <class P, class F> struct RecordBox final : CallbackBox {
    RecordBox(WorldState *s, F f) : CallbackBox(s), fn(std::move(f)) {}
    F fn;
    static int32_t trampoline(void *user_data, const uint8_t *bytes, size_t len) noexcept {
        RecordBox *self = static_cast<RecordBox *>(user_data);
        bool ok = false;
        guarded(*self->state, [&] { ok = self->fn(bytes, len); });
        return ok ? 0 : 1;
    }
};
/** The heap home of a pair-filter lambda: `bool(ShapeId a, ShapeId b)`. */
template <class P, class F> struct PairFilterBox final : CallbackBox {
    PairFilterBox(WorldState *s, F f) : CallbackBox(s), fn(std::move(f)) {}
    F fn;
    static uint8_t trampoline(void *user_data, HearthWorld *, HearthShapeId a, HearthShapeId b) noexcept {
        PairFilterBox *self = static_cast<PairFilterBox *>(user_data);
        bool keep = true;
        guarded(*self->state, [&] { keep = self->fn(a, b); });
        return keep ? 1 : 0;
    }
};
/** The heap home of a pre-solve lambda: `bool(const PreSolveContact &)`. */
template <class P, class F> struct PreSolveBox final : CallbackBox {
    PreSolveBox(WorldState *s, F f) : CallbackBox(s), fn(std::move(f)) {}
    F fn;
    static uint8_t trampoline(void *user_data, HearthWorld *, const HearthPreSolveContact *c) noexcept {
        PreSolveBox *self = static_cast<PreSolveBox *>(user_data);
        bool keep = true;
        guarded(*self->state, [&] { keep = self->fn(*c); });
        return keep ? 1 : 0;
    }
};
} // namespace detail

// --------------------------------------------------------------------------- the owner

/**
 * Owns one world and every lambda generator in it. Move-only; the moved-from World is empty
 * (its calls fail with Code::NullPointer). Handles taken from it stay valid across moves.
 */
template <class P> class BasicWorld : public BasicWorldRef<P> {
    template <class T> using Ret = typename P::template Ret<T>;

public:
    using Generator = BasicGenerator<P>;
    using ForceContext = BasicForceContext<P>;
    using ContactContext = BasicContactContext<P>;

    /** An empty World (no C world). */
    BasicWorld() noexcept = default;

    /** Creates a world (throwing API only; the nothrow API has create()). */
    template <class Q = P, std::enable_if_t<Q::throws, int> = 0>
    explicit BasicWorld(const WorldDef &def) : BasicWorld(create(def)) {}

    /** Creates a world from a def (default: world_def()). */
    static Ret<BasicWorld> create(const WorldDef &def = world_def()) {
        HearthWorld *raw = nullptr;
        const HearthResult r = hearth_world_create(&def, &raw);
        BasicWorld w;
        if (r == HEARTH_OK) {
            w.state_.reset(new detail::WorldState());
            w.state_->world = raw;
            w.world_ = raw;
        }
        return P::template value<BasicWorld>(r, std::move(w));
    }

    BasicWorld(BasicWorld &&o) noexcept : BasicWorldRef<P>(o.world_), state_(std::move(o.state_)) {
        o.world_ = nullptr;
    }
    BasicWorld &operator=(BasicWorld &&o) noexcept {
        if (this != &o) {
            state_ = std::move(o.state_); // destroys our old world, if any
            this->world_ = o.world_;
            o.world_ = nullptr;
        }
        return *this;
    }
    BasicWorld(const BasicWorld &) = delete;
    BasicWorld &operator=(const BasicWorld &) = delete;
    ~BasicWorld() = default;

    /** A non-owning view (what lambdas get), valid while this World lives. */
    BasicWorldRef<P> ref() const noexcept { return BasicWorldRef<P>(this->world_); }

    /**
     * Advances the world by dt seconds. If a generator lambda failed during the step (threw,
     * or returned a failed Status) the step still ran to its end, the later lambdas of that
     * step were skipped, and the first failure is reported here: the throwing API rethrows
     * the lambda's exception (or throws hearth::Error for a failed Status); the nothrow API
     * returns it as a Status (Code::CallbackException with what() for an exception).
     */
    Ret<void> step(float dt) {
        if (!state_) {
            return P::check(hearth_world_step(nullptr, dt));
        }
        state_->clear_failure();
        const HearthResult r = hearth_world_step(this->world_, dt);
        if (state_->failed) {
            return report_callback_failure();
        }
        return P::check(r);
    }

    /**
     * A force generator running `fn(ForceContext &)` once per step (after the built-in ones).
     * `fn` returns void or hearth::Status; attach bodies and particles to the generator.
     */
    template <class F> Ret<Generator> add_force_generator(F &&fn) {
        using Box = detail::ForceBox<P, std::decay_t<F>>;
        if (!state_) {
            return P::template fail_value<Generator>(Code::NullPointer, "hearth.hpp: empty World");
        }
        std::unique_ptr<Box> box(new Box(state_.get(), std::forward<F>(fn)));
        UserForceGeneratorDef def = hearth_user_force_generator_def_default();
        def.callback = &Box::trampoline;
        def.user_data = box.get();
        return keep(std::move(box), hearth_generator_create_user_force, def);
    }

    /**
     * A contact generator running `fn(ContactContext &)` once per step after the narrow
     * phase; it adds up to `capacity` contacts per call with ctx.add().
     */
    template <class F> Ret<Generator> add_contact_generator(F &&fn, uint32_t capacity = 16) {
        using Box = detail::ContactBox<P, std::decay_t<F>>;
        if (!state_) {
            return P::template fail_value<Generator>(Code::NullPointer, "hearth.hpp: empty World");
        }
        std::unique_ptr<Box> box(new Box(state_.get(), std::forward<F>(fn)));
        UserContactGeneratorDef def = hearth_user_contact_generator_def_default();
        def.callback = &Box::trampoline;
        def.user_data = box.get();
        def.capacity = capacity;
        return keep(std::move(box), hearth_generator_create_user_contact, def);
    }

    /** Destroys a generator; a lambda generator's box (and the lambda's captures) is freed. */
    Ret<void> destroy_generator(const Generator &g) {
        const HearthResult r = hearth_generator_destroy(this->world_, g.id());
        if (r == HEARTH_OK && state_) {
            state_->boxes.erase(detail::WorldState::key(g.id()));
        }
        return P::check(r);
    }

    /**
     * Records the world into the file at `path` (hearth_world_record_start_file): the
     * current state now, then every step; open the file with viewer/index.html. `contacts`
     * records the contact manifolds too. Ends with stop_recording() or the World.
     */
    Ret<void> record_to_file(const std::string &path, bool contacts = false) {
        RecordDef def = record_def();
        def.record_contacts = contacts ? 1 : 0;
        return P::check(hearth_world_record_start_file(this->world_, path.c_str(), &def));
    }

    /**
     * Records the world through `write(const uint8_t *bytes, size_t len) -> bool`
     * (hearth_world_record_start_callback), called now and after every step on the stepping
     * thread. Returning false, or throwing, stops the recording: a throw is reported like a
     * generator lambda's (by this call or by the step it happened in), and the next step (or
     * stop_recording) fails with Code::Io.
     */
    template <class F> Ret<void> record_to(F &&write, bool contacts = false) {
        using Box = detail::RecordBox<P, std::decay_t<F>>;
        if (!state_) {
            return P::fail(Code::NullPointer, "hearth.hpp: empty World");
        }
        std::unique_ptr<Box> box(new Box(state_.get(), std::forward<F>(write)));
        RecordDef def = record_def();
        def.record_contacts = contacts ? 1 : 0;
        def.write = &Box::trampoline;
        def.user_data = box.get();
        state_->clear_failure();
        const HearthResult r = hearth_world_record_start_callback(this->world_, &def);
        if (r == HEARTH_OK) {
            state_->record_box = std::move(box);
        }
        if (state_->failed) {
            return report_callback_failure();
        }
        return P::check(r);
    }

    /** Ends the recording (hearth_world_record_stop); Code::Io if a write had failed. */
    Ret<void> stop_recording() {
        const HearthResult r = hearth_world_record_stop(this->world_);
        if (state_ && r != HEARTH_ERROR_WORLD_LOCKED) {
            state_->record_box.reset(); // the C world no longer calls it
        }
        return P::check(r);
    }

    /**
     * Sets the pair filter (hearth_world_set_pair_filter_callback) to `fn(ShapeId a, ShapeId b)
     * -> bool`: false keeps the pair from touching until it is proposed again. A throw keeps
     * the pair and is reported by the step it happened in.
     */
    template <class F> Ret<void> set_pair_filter(F &&fn) {
        using Box = detail::PairFilterBox<P, std::decay_t<F>>;
        if (!state_) {
            return P::fail(Code::NullPointer, "hearth.hpp: empty World");
        }
        std::unique_ptr<Box> box(new Box(state_.get(), std::forward<F>(fn)));
        const HearthResult r = hearth_world_set_pair_filter_callback(this->world_, &Box::trampoline, box.get());
        if (r == HEARTH_OK) {
            state_->pair_filter_box = std::move(box);
        }
        return P::check(r);
    }
    /** Clears the pair filter. */
    Ret<void> clear_pair_filter() {
        const HearthResult r = hearth_world_set_pair_filter_callback(this->world_, nullptr, nullptr);
        if (r == HEARTH_OK && state_) {
            state_->pair_filter_box.reset();
        }
        return P::check(r);
    }
    /**
     * Sets the pre-solve callback (hearth_world_set_pre_solve_callback) to
     * `fn(const PreSolveContact &) -> bool`: false disables the contact for this step. A throw
     * keeps the contact and is reported by the step it happened in.
     */
    template <class F> Ret<void> set_pre_solve(F &&fn) {
        using Box = detail::PreSolveBox<P, std::decay_t<F>>;
        if (!state_) {
            return P::fail(Code::NullPointer, "hearth.hpp: empty World");
        }
        std::unique_ptr<Box> box(new Box(state_.get(), std::forward<F>(fn)));
        const HearthResult r = hearth_world_set_pre_solve_callback(this->world_, &Box::trampoline, box.get());
        if (r == HEARTH_OK) {
            state_->pre_solve_box = std::move(box);
        }
        return P::check(r);
    }
    /** Clears the pre-solve callback. */
    Ret<void> clear_pre_solve() {
        const HearthResult r = hearth_world_set_pre_solve_callback(this->world_, nullptr, nullptr);
        if (r == HEARTH_OK && state_) {
            state_->pre_solve_box.reset();
        }
        return P::check(r);
    }

    /** How many lambda generators this World holds (for tests and tools). */
    size_t lambda_count() const noexcept { return state_ ? state_->boxes.size() : 0; }

private:
    template <class Box, class Fn, class Def> Ret<Generator> keep(std::unique_ptr<Box> box, Fn create, const Def &def) {
        GeneratorId id{};
        const HearthResult r = create(this->world_, &def, &id);
        if (r == HEARTH_OK) {
            state_->boxes[detail::WorldState::key(id)] = std::move(box);
        }
        return P::template value<Generator>(r, Generator(this->world_, id));
    }

    Ret<void> report_callback_failure() {
#if HEARTH_CPP_EXCEPTIONS
        if constexpr (P::throws) {
            if (state_->exception) {
                std::exception_ptr e = state_->exception;
                state_->clear_failure();
                std::rethrow_exception(e);
            }
        }
#endif
        const Code code = state_->code;
        std::string message = std::move(state_->message);
        state_->clear_failure();
        return P::fail(code, std::move(message));
    }

    std::unique_ptr<detail::WorldState> state_;
};

#undef HEARTH_CPP_READ

// ----------------------------------------------------------------------- the two APIs

/** The no-exceptions API: every call returns Result<T> / Status. */
namespace nothrow {
using World = BasicWorld<detail::NoThrow>;
using WorldRef = BasicWorldRef<detail::NoThrow>;
using Body = BasicBody<detail::NoThrow>;
using Shape = BasicShape<detail::NoThrow>;
using Joint = BasicJoint<detail::NoThrow>;
using Particle = BasicParticle<detail::NoThrow>;
using SoftBody = BasicSoftBody<detail::NoThrow>;
using Hull = BasicHull<detail::NoThrow>;
using Mesh = BasicMesh<detail::NoThrow>;
using Heightfield = BasicHeightfield<detail::NoThrow>;
using Generator = BasicGenerator<detail::NoThrow>;
using ForceContext = BasicForceContext<detail::NoThrow>;
using ContactContext = BasicContactContext<detail::NoThrow>;
} // namespace nothrow

#if HEARTH_CPP_EXCEPTIONS
/** The throwing API (the default): calls return T and throw hearth::Error. */
using World = BasicWorld<detail::Throwing>;
using WorldRef = BasicWorldRef<detail::Throwing>;
using Body = BasicBody<detail::Throwing>;
using Shape = BasicShape<detail::Throwing>;
using Joint = BasicJoint<detail::Throwing>;
using Particle = BasicParticle<detail::Throwing>;
using SoftBody = BasicSoftBody<detail::Throwing>;
using Hull = BasicHull<detail::Throwing>;
using Mesh = BasicMesh<detail::Throwing>;
using Heightfield = BasicHeightfield<detail::Throwing>;
using Generator = BasicGenerator<detail::Throwing>;
using ForceContext = BasicForceContext<detail::Throwing>;
using ContactContext = BasicContactContext<detail::Throwing>;
#endif

} // namespace hearth

#endif /* HEARTH_HPP */
