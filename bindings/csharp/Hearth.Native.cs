// Hearth.Native.cs - the low-level C# binding of Hearth: every type of include/hearth.h as a
// blittable struct with the C layout, and every exported function as a [DllImport] with the
// C name (class Native). The managed layer (World, Body, ...) is in Hearth.cs.
//
// Naming: a C type HearthX is X here (HearthBodyDef -> BodyDef), a field snake_case is
// PascalCase (linear_velocity -> LinearVelocity), HEARTH_* constants are enum members.
// Layouts are LayoutKind.Sequential with the C field order and types; the tests compare
// Marshal.SizeOf and Marshal.OffsetOf of every struct and field with the C compiler's.
//
// Marshalling: uint8_t flags are Flag (one byte, converts to and from bool); bool outputs are
// 1-byte (UnmanagedType.I1); size_t is UIntPtr; pointers inside structs (arrays the world
// owns, callbacks, user data) are IntPtr; caller-owned arrays are blittable arrays, pinned
// for the call and never copied.

using System;
using System.Runtime.InteropServices;

namespace Hearth
{
    /// <summary>HearthResult: the result of every fallible call (HEARTH_OK or HEARTH_ERROR_*).</summary>
    public enum Result : int
    {
        /// <summary>HEARTH_OK: success.</summary>
        Ok = 0,
        /// <summary>HEARTH_ERROR_NULL_POINTER: a required pointer argument was NULL.</summary>
        NullPointer = 1,
        /// <summary>HEARTH_ERROR_INVALID_ID: an id is null, stale, never existed or belongs to another world.</summary>
        InvalidId = 2,
        /// <summary>HEARTH_ERROR_INVALID_ARGUMENT: NaN, infinite or out-of-range value, or a def not made by its Default().</summary>
        InvalidArgument = 3,
        /// <summary>HEARTH_ERROR_WORLD_LOCKED: a structural change from inside a callback during a step.</summary>
        WorldLocked = 4,
        /// <summary>HEARTH_ERROR_BUFFER_TOO_SMALL: a caller-owned array is too small; nothing was written.</summary>
        BufferTooSmall = 5,
        /// <summary>HEARTH_ERROR_PANIC: an internal bug caught at the boundary; the world refuses further steps.</summary>
        Panic = 6,
        /// <summary>HEARTH_ERROR_IO: writing a recording (a file, or the write callback) failed.</summary>
        Io = 7,
        /// <summary>HEARTH_ERROR_LIMIT_REACHED: a fixed capacity is used up (4,095 worlds alive at once).</summary>
        LimitReached = 8,
    }

    /// <summary>HEARTH_BODY_*: body type codes (BodyDef.Type, Body.Type).</summary>
    public enum BodyType : uint
    {
        /// <summary>HEARTH_BODY_STATIC: never moves; infinite mass. Planes go on static bodies.</summary>
        Static = 0,
        /// <summary>HEARTH_BODY_KINEMATIC: moves by its velocity or a target transform; infinite mass.</summary>
        Kinematic = 1,
        /// <summary>HEARTH_BODY_DYNAMIC: moves under gravity, forces and contacts.</summary>
        Dynamic = 2,
    }

    /// <summary>HEARTH_QUERY_SHAPE_*: which member of a QueryShape is used.</summary>
    public enum QueryShapeType : uint
    {
        /// <summary>HEARTH_QUERY_SHAPE_SPHERE.</summary>
        Sphere = 0,
        /// <summary>HEARTH_QUERY_SHAPE_CAPSULE.</summary>
        Capsule = 1,
        /// <summary>HEARTH_QUERY_SHAPE_BOX.</summary>
        Box = 2,
        /// <summary>HEARTH_QUERY_SHAPE_HULL.</summary>
        Hull = 3,
    }

    /// <summary>HEARTH_GENERATOR_*: generator type codes (Generator.Type).</summary>
    public enum GeneratorType : uint
    {
        Gravity = 0,
        Drag = 1,
        Spring = 2,
        Bungee = 3,
        StiffSpring = 4,
        Buoyancy = 5,
        Explosion = 6,
        Rod = 7,
        Cable = 8,
        UserForce = 9,
        UserContact = 10,
    }

    /// <summary>HEARTH_JOINT_*: joint type codes (Joint.Type).</summary>
    public enum JointType : uint
    {
        Ball = 0,
        Hinge = 1,
        Fixed = 2,
        Distance = 3,
        Slider = 4,
    }

    /// <summary>HEARTH_INTEGRATOR_*: WorldDef.Integrator.</summary>
    public enum Integrator : uint
    {
        /// <summary>HEARTH_INTEGRATOR_SEMI_IMPLICIT_EULER (default).</summary>
        SemiImplicitEuler = 0,
        /// <summary>HEARTH_INTEGRATOR_RK4: fourth-order Runge-Kutta for bodies no contact touches.</summary>
        Rk4 = 1,
    }

    /// <summary>
    /// A uint8_t flag field of a def (0 or 1; the library rejects anything else). Converts
    /// implicitly to and from bool; <c>new Flag(2)</c> builds an invalid byte for tests.
    /// </summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Flag : IEquatable<Flag>
    {
        /// <summary>The raw byte.</summary>
        public byte Value;

        public Flag(byte value) { Value = value; }

        public static implicit operator Flag(bool value) { return new Flag(value ? (byte)1 : (byte)0); }
        public static implicit operator bool(Flag flag) { return flag.Value != 0; }

        public bool Equals(Flag other) { return Value == other.Value; }
        public override bool Equals(object obj) { return obj is Flag && Equals((Flag)obj); }
        public override int GetHashCode() { return Value; }
        public override string ToString() { return Value == 1 ? "true" : Value == 0 ? "false" : "Flag(" + Value + ")"; }
    }

    /// <summary>
    /// HearthForceCallback: <c>void (*)(void *user_data, HearthWorld *world, const HearthGeneratorContext *context)</c>.
    /// The managed layer (World.CreateUserForceGenerator) builds and keeps these alive for you.
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void ForceCallback(IntPtr userData, IntPtr world, IntPtr context);

    /// <summary>
    /// HearthContactCallback: <c>void (*)(void *user_data, HearthWorld *world, const HearthGeneratorContext *context, HearthContactSink *sink)</c>.
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void ContactCallback(IntPtr userData, IntPtr world, IntPtr context, IntPtr sink);

    /// <summary>
    /// HearthRecordWriteFn: <c>int32_t (*)(void *user_data, const uint8_t *bytes, size_t len)</c>;
    /// returns 0 when the bytes were written.
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate int RecordWriteFn(IntPtr userData, IntPtr bytes, UIntPtr len);

    /// <summary>
    /// HearthRayCallback: <c>float (*)(void *user_data, const HearthRayHit *hit)</c>; returns -1 to
    /// ignore the hit, 0 to stop, a fraction to clip the ray, 1 to continue. World.CastRay builds it.
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate float RayCallback(IntPtr userData, ref RayHit hit);
    /// <summary>HearthDrawSegment: <c>void (*)(void *user_data, const HearthVec3 *a, const HearthVec3 *b, uint32_t color)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawSegment(IntPtr userData, IntPtr a, IntPtr b, uint color);

    /// <summary>HearthDrawPolygon: <c>void (*)(void *user_data, const HearthVec3 *vertices, uint32_t count, uint32_t color)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawPolygon(IntPtr userData, IntPtr vertices, uint count, uint color);

    /// <summary>HearthDrawSphere: <c>void (*)(void *user_data, const HearthVec3 *center, float radius, uint32_t color)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawSphere(IntPtr userData, IntPtr center, float radius, uint color);

    /// <summary>HearthDrawCapsule: <c>void (*)(void *user_data, const HearthVec3 *a, const HearthVec3 *b, float radius, uint32_t color)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawCapsule(IntPtr userData, IntPtr a, IntPtr b, float radius, uint color);

    /// <summary>HearthDrawTransform: <c>void (*)(void *user_data, const HearthTransform *transform)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawTransform(IntPtr userData, IntPtr transform);

    /// <summary>HearthDrawPoint: <c>void (*)(void *user_data, const HearthVec3 *point, float size, uint32_t color)</c>.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void DrawPoint(IntPtr userData, IntPtr point, float size, uint color);

    /// <summary>Debug draw: callbacks (function pointers, any may be zero), user data and flags (0 or 1). World.Draw fills one for an IDebugDrawer.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct DebugDraw
    {
        /// <summary>The defaults of <c>hearth_debug_draw_default()</c>: no callbacks, nothing drawn.</summary>
        public static DebugDraw Default() { return Native.hearth_debug_draw_default(); }

        public IntPtr DrawSegment;
        public IntPtr DrawPolygon;
        public IntPtr DrawSphere;
        public IntPtr DrawCapsule;
        public IntPtr DrawTransform;
        public IntPtr DrawPoint;
        public IntPtr UserData;
        public byte DrawShapes;
        public byte DrawAabbs;
        public byte DrawContacts;
        public byte DrawJoints;
        public byte DrawCentersOfMass;
        /// <summary>Set by <c>hearth_debug_draw_default()</c>; do not change.</summary>
        public uint InternalValue;
    }
    /// HearthTaskFn: <c>void (*)(uint32_t start, uint32_t end, uint32_t worker_index, void *task_context)</c>,
    /// the range task Hearth hands a job system's <see cref="EnqueueTaskFn"/>: call it over disjoint ranges
    /// covering <c>0..item_count</c> once, on any threads, with a worker index below the world's worker count.
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void TaskFn(uint start, uint end, uint workerIndex, IntPtr taskContext);

    /// <summary>
    /// HearthEnqueueTaskFn: <c>void *(*)(HearthTaskFn task, uint32_t item_count, uint32_t min_range, void *task_context, void *user_context)</c>.
    /// Returns a handle for <see cref="FinishTaskFn"/>, or IntPtr.Zero when the task already ran. Set
    /// <c>WorldDef.EnqueueTask</c> to <c>Marshal.GetFunctionPointerForDelegate</c> of one (and keep the
    /// delegate alive as long as the world).
    /// </summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate IntPtr EnqueueTaskFn(IntPtr task, uint itemCount, uint minRange, IntPtr taskContext, IntPtr userContext);

    /// <summary>HearthFinishTaskFn: <c>void (*)(void *user_task, void *user_context)</c>: waits for every range of the task.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate void FinishTaskFn(IntPtr userTask, IntPtr userContext);

    /// <summary>A 3D vector of <c>float</c> (metres, m/s, N, ... by context).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Vec3 : IEquatable<Vec3>
    {
        public float X;
        public float Y;
        public float Z;

        public Vec3(float x, float y, float z) { X = x; Y = y; Z = z; }

        public static readonly Vec3 Zero = new Vec3(0f, 0f, 0f);

        public static Vec3 operator +(Vec3 a, Vec3 b) { return new Vec3(a.X + b.X, a.Y + b.Y, a.Z + b.Z); }
        public static Vec3 operator -(Vec3 a, Vec3 b) { return new Vec3(a.X - b.X, a.Y - b.Y, a.Z - b.Z); }
        public static Vec3 operator -(Vec3 a) { return new Vec3(-a.X, -a.Y, -a.Z); }
        public static Vec3 operator *(Vec3 a, float s) { return new Vec3(a.X * s, a.Y * s, a.Z * s); }
        public static Vec3 operator *(float s, Vec3 a) { return new Vec3(a.X * s, a.Y * s, a.Z * s); }

        /// <summary>Euclidean length.</summary>
        public float Length { get { return (float)Math.Sqrt(X * X + Y * Y + Z * Z); } }

        public bool Equals(Vec3 other) { return X.Equals(other.X) && Y.Equals(other.Y) && Z.Equals(other.Z); }
        public override bool Equals(object obj) { return obj is Vec3 && Equals((Vec3)obj); }
        public override int GetHashCode() { return X.GetHashCode() ^ (Y.GetHashCode() * 397) ^ (Z.GetHashCode() * 7919); }
        public override string ToString()
        {
            return string.Format(System.Globalization.CultureInfo.InvariantCulture, "({0}, {1}, {2})", X, Y, Z);
        }
    }

    /// <summary>A rotation quaternion <c>{x, y, z, w}</c>; need not be normalised, must not be zero.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Quat : IEquatable<Quat>
    {
        public float X;
        public float Y;
        public float Z;
        public float W;

        public Quat(float x, float y, float z, float w) { X = x; Y = y; Z = z; W = w; }

        /// <summary>The identity rotation (0, 0, 0, 1).</summary>
        public static readonly Quat Identity = new Quat(0f, 0f, 0f, 1f);

        /// <summary>A rotation of <paramref name="angle"/> radians about a unit <paramref name="axis"/>.</summary>
        public static Quat FromAxisAngle(Vec3 axis, float angle)
        {
            float s = (float)Math.Sin(0.5 * angle);
            return new Quat(axis.X * s, axis.Y * s, axis.Z * s, (float)Math.Cos(0.5 * angle));
        }

        public bool Equals(Quat other) { return X.Equals(other.X) && Y.Equals(other.Y) && Z.Equals(other.Z) && W.Equals(other.W); }
        public override bool Equals(object obj) { return obj is Quat && Equals((Quat)obj); }
        public override int GetHashCode() { return X.GetHashCode() ^ (Y.GetHashCode() * 397) ^ (Z.GetHashCode() * 7919) ^ (W.GetHashCode() * 104729); }
        public override string ToString()
        {
            return string.Format(System.Globalization.CultureInfo.InvariantCulture, "({0}, {1}, {2}, {3})", X, Y, Z, W);
        }
    }

    /// <summary>A rigid transform: rotation, then translation.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Transform : IEquatable<Transform>
    {
        public Vec3 Position;
        public Quat Rotation;

        public Transform(Vec3 position, Quat rotation) { Position = position; Rotation = rotation; }

        /// <summary>At the origin, not rotated.</summary>
        public static readonly Transform Identity = new Transform(Vec3.Zero, Quat.Identity);

        public bool Equals(Transform other) { return Position.Equals(other.Position) && Rotation.Equals(other.Rotation); }
        public override bool Equals(object obj) { return obj is Transform && Equals((Transform)obj); }
        public override int GetHashCode() { return Position.GetHashCode() ^ (Rotation.GetHashCode() * 31); }
        public override string ToString() { return "{" + Position + ", " + Rotation + "}"; }
    }

    /// <summary>How to create a body. Get one from <c>hearth_body_def_default()</c>, then edit it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BodyDef
    {

        /// <summary>The defaults of <c>hearth_body_def_default()</c>; start every def from here.</summary>
        public static BodyDef Default() { return Native.hearth_body_def_default(); }

        /// <summary><c>HEARTH_BODY_STATIC</c> (default), <c>HEARTH_BODY_KINEMATIC</c> or <c>HEARTH_BODY_DYNAMIC</c>.</summary>
        public BodyType Type;
        /// <summary>Pose of the body origin (m); the rotation is normalised, must not be zero.</summary>
        public Transform Transform;
        /// <summary>Initial velocity of the centre of mass (m/s).</summary>
        public Vec3 LinearVelocity;
        /// <summary>Initial angular velocity (rad/s, world frame).</summary>
        public Vec3 AngularVelocity;
        /// <summary>Linear damping (1/s, &gt;= 0). Default 0.</summary>
        public float LinearDamping;
        /// <summary>Angular damping (1/s, &gt;= 0). Default 0.</summary>
        public float AngularDamping;
        /// <summary>1 (default) lets the body sleep when still; 0 keeps it awake.</summary>
        public Flag AllowSleep;
        /// <summary>Host data, returned by <c>hearth_body_get_user_data</c>.</summary>
        public ulong UserData;
        /// <summary>Multiplier of world gravity for this body. Default 1.</summary>
        public float GravityScale;
        /// <summary>1 (default) creates the body awake; 0 creates it asleep.</summary>
        public Flag IsAwake;
        /// <summary>Set by <c>hearth_body_def_default()</c>; do not change.</summary>
        public uint InternalValue;
        /// <summary>1 (default) reports the body in move events when it moves or falls asleep; 0 never.</summary>
        public Flag EnableMoveEvents;
        /// <summary>Locked axes: <c>HEARTH_LOCK_*</c> bits ORed (<see cref="LockedAxes"/>). Default none.</summary>
        public LockedAxes LockedAxes;
    }

    /// <summary>Locked axes of a body, in world axes (<c>HEARTH_LOCK_*</c>).</summary>
    [Flags]
    public enum LockedAxes : uint
    {
        None = 0,
        LinearX = 1,
        LinearY = 2,
        LinearZ = 4,
        AngularX = 8,
        AngularY = 16,
        AngularZ = 32,
        Linear = 7,
        Angular = 56,
    }

    /// <summary>Id of a body inside its world. All-zero is the null id. Ids of destroyed bodies and of other worlds are rejected with <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BodyId : IEquatable<BodyId>
    {
        public uint Index;
        public uint Generation;

        public BodyId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly BodyId Null = default(BodyId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(BodyId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is BodyId && Equals((BodyId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(BodyId a, BodyId b) { return a.Equals(b); }
        public static bool operator !=(BodyId a, BodyId b) { return !a.Equals(b); }
        public override string ToString() { return "BodyId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Id of a generator inside its world. All-zero is the null id; a destroyed generator's id is stale (<c>HEARTH_ERROR_INVALID_ID</c>).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GeneratorId : IEquatable<GeneratorId>
    {
        /// <summary>Slot of the generator.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public GeneratorId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly GeneratorId Null = default(GeneratorId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(GeneratorId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is GeneratorId && Equals((GeneratorId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(GeneratorId a, GeneratorId b) { return a.Equals(b); }
        public static bool operator !=(GeneratorId a, GeneratorId b) { return !a.Equals(b); }
        public override string ToString() { return "GeneratorId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Id of a particle inside its world. All-zero is the null id. A particle that expired or was destroyed leaves a stale id: <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ParticleId : IEquatable<ParticleId>
    {
        /// <summary>Slot of the particle.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public ParticleId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly ParticleId Null = default(ParticleId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(ParticleId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is ParticleId && Equals((ParticleId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(ParticleId a, ParticleId b) { return a.Equals(b); }
        public static bool operator !=(ParticleId a, ParticleId b) { return !a.Equals(b); }
        public override string ToString() { return "ParticleId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>What a user generator callback is told. The arrays are owned by the world and valid only during the call.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GeneratorContext
    {
        /// <summary>The generator being run.</summary>
        public GeneratorId Generator;
        /// <summary>The step's duration (s).</summary>
        public float Dt;
        /// <summary>The live bodies attached to the generator, in attachment order.</summary>
        public IntPtr Bodies;
        /// <summary>Number of entries in <c>bodies</c>.</summary>
        public UIntPtr BodyCount;
        /// <summary>The live particles attached to the generator, in attachment order.</summary>
        public IntPtr Particles;
        /// <summary>Number of entries in <c>particles</c>.</summary>
        public UIntPtr ParticleCount;
    }

    /// <summary>A force generator written in C.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct UserForceGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_user_force_generator_def_default()</c>; start every def from here.</summary>
        public static UserForceGeneratorDef Default() { return Native.hearth_user_force_generator_def_default(); }

        /// <summary>Called once per step (must not be NULL). Default NULL.</summary>
        public IntPtr Callback;
        /// <summary>Passed to the callback as is. Default NULL.</summary>
        public IntPtr UserData;
        /// <summary>Set by <c>hearth_user_force_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A contact generator written in C.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct UserContactGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_user_contact_generator_def_default()</c>; start every def from here.</summary>
        public static UserContactGeneratorDef Default() { return Native.hearth_user_contact_generator_def_default(); }

        /// <summary>Called once per step (must not be NULL). Default NULL.</summary>
        public IntPtr Callback;
        /// <summary>Passed to the callback as is. Default NULL.</summary>
        public IntPtr UserData;
        /// <summary>Most contacts one call may add (0..=1048576). Default 16.</summary>
        public uint Capacity;
        /// <summary>Set by <c>hearth_user_contact_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A contact for <c>hearth_contact_sink_add</c>. Each side is a body, a particle, or the world (both ids null); at least one side must be an object and the two must differ. Between bodies (or a body and the world) the rigid solver resolves it with collision contacts; with a particle, the particle stage does.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GeneratedContact
    {
        /// <summary>Side A: a body, or the null id.</summary>
        public BodyId BodyA;
        /// <summary>Side A: a particle, or the null id.</summary>
        public ParticleId ParticleA;
        /// <summary>Side B: a body, or the null id.</summary>
        public BodyId BodyB;
        /// <summary>Side B: a particle, or the null id.</summary>
        public ParticleId ParticleB;
        /// <summary>World point where the two touch (m).</summary>
        public Vec3 Point;
        /// <summary>From A to B: B is pushed along it, A the other way (need not be unit length, must not be zero).</summary>
        public Vec3 Normal;
        /// <summary>Overlap along the normal (m): &gt; 0 violated, &lt; 0 a gap that may close this step.</summary>
        public float Penetration;
        /// <summary>Bounce (&gt;= 0).</summary>
        public float Restitution;
        /// <summary>Coulomb friction (&gt;= 0).</summary>
        public float Friction;
    }

    /// <summary>Extra gravity on every attached body and particle, on top of world gravity.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct GravityGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_gravity_generator_def_default()</c>; start every def from here.</summary>
        public static GravityGeneratorDef Default() { return Native.hearth_gravity_generator_def_default(); }

        /// <summary>Acceleration (m/s²). Default (0, -9.81, 0).</summary>
        public Vec3 Acceleration;
        /// <summary>Set by <c>hearth_gravity_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Drag <c>-v̂ (k1 |v| + k2 |v|²)</c> on every attached body (at its centre of mass) and particle.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct DragGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_drag_generator_def_default()</c>; start every def from here.</summary>
        public static DragGeneratorDef Default() { return Native.hearth_drag_generator_def_default(); }

        /// <summary>Linear coefficient (N·s/m, &gt;= 0). Default 0.1.</summary>
        public float K1;
        /// <summary>Quadratic coefficient (N·s²/m², &gt;= 0). Default 0.01.</summary>
        public float K2;
        /// <summary>Set by <c>hearth_drag_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>One end of a spring, rod or cable: a point on a body (<c>body</c> set, <c>point</c> in the body frame), a particle (<c>particle</c> set, <c>point</c> ignored), or a fixed point in the world (both ids null, <c>point</c> in world space). Setting both ids is an error.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct LinkEnd
    {
        /// <summary>A body, or the null id.</summary>
        public BodyId Body;
        /// <summary>A particle, or the null id.</summary>
        public ParticleId Particle;
        /// <summary>Body-frame attachment point, or the world anchor point (m).</summary>
        public Vec3 Point;

        /// <summary>A point on a body, in the body frame.</summary>
        public static LinkEnd OnBody(BodyId body, Vec3 localPoint) { var e = new LinkEnd(); e.Body = body; e.Point = localPoint; return e; }

        /// <summary>A particle.</summary>
        public static LinkEnd OnParticle(ParticleId particle) { var e = new LinkEnd(); e.Particle = particle; return e; }

        /// <summary>A fixed point in the world.</summary>
        public static LinkEnd AtWorldPoint(Vec3 point) { var e = new LinkEnd(); e.Point = point; return e; }
    }

    /// <summary>A spring from each attached body or particle to <c>other</c>. With <c>other</c> a world point it is an anchored spring; with <c>other</c> a dynamic body or a particle that end feels the equal and opposite force (a spring between two objects: attach one, name the other).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SpringGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_spring_generator_def_default()</c>; start every def from here.</summary>
        public static SpringGeneratorDef Default() { return Native.hearth_spring_generator_def_default(); }

        /// <summary>The other end. Default: the world origin.</summary>
        public LinkEnd Other;
        /// <summary>Attachment point on each attached body, body frame (m). Default (0, 0, 0).</summary>
        public Vec3 LocalPoint;
        /// <summary>Rest length (m, &gt;= 0). Default 1.</summary>
        public float RestLength;
        /// <summary>Stiffness (N/m, &gt;= 0). Default 100.</summary>
        public float Stiffness;
        /// <summary>Damping along the spring (N·s/m, &gt;= 0). Default 0.</summary>
        public float Damping;
        /// <summary>Set by <c>hearth_spring_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A stiff damped spring (rest length 0) from each attached object to <c>anchor</c>, whose force makes the step reproduce the exact damped harmonic motion: the discrete motion has the continuous system's frequency and decay for any stiffness, where an explicit spring would explode. The anchor end is followed but feels no reaction.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct StiffSpringGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_stiff_spring_generator_def_default()</c>; start every def from here.</summary>
        public static StiffSpringGeneratorDef Default() { return Native.hearth_stiff_spring_generator_def_default(); }

        /// <summary>The anchor. Default: the world origin.</summary>
        public LinkEnd Anchor;
        /// <summary>Attachment point on each attached body, body frame (m). Default (0, 0, 0).</summary>
        public Vec3 LocalPoint;
        /// <summary>Stiffness (N/m, &gt; 0). Default 1000.</summary>
        public float Stiffness;
        /// <summary>Damping (N·s/m, &gt;= 0). Default 10.</summary>
        public float Damping;
        /// <summary>Set by <c>hearth_stiff_spring_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Buoyancy of a liquid below the plane <c>dot(surface_normal, p) = surface_offset</c>: a force <c>liquid_density · volume · |g| · f</c> along the normal, where <c>f</c>, the submerged fraction, rises linearly from 0 when the centre of buoyancy is <c>max_depth</c> above the surface to 1 when it is <c>max_depth</c> below. At rest <c>f = mass / (liquid_density · volume)</c> (Archimedes).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BuoyancyGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_buoyancy_generator_def_default()</c>; start every def from here.</summary>
        public static BuoyancyGeneratorDef Default() { return Native.hearth_buoyancy_generator_def_default(); }

        /// <summary>Up out of the liquid (need not be unit length, must not be zero). Default +Y.</summary>
        public Vec3 SurfaceNormal;
        /// <summary>Height of the surface along the normal (m). Default 0.</summary>
        public float SurfaceOffset;
        /// <summary>Half the depth over which an object goes from dry to submerged (m, &gt; 0). Default 0.5.</summary>
        public float MaxDepth;
        /// <summary>Displaced volume when submerged (m³, &gt;= 0). Default 0.001.</summary>
        public float Volume;
        /// <summary>Density of the liquid (kg/m³, &gt;= 0). Default 1000 (water).</summary>
        public float LiquidDensity;
        /// <summary>Centre of buoyancy on attached bodies, body frame (m). Default (0, 0, 0).</summary>
        public Vec3 LocalPoint;
        /// <summary>Set by <c>hearth_buoyancy_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>An explosion at <c>center</c>. In the first step after creation, objects within <c>blast_radius</c> get an impulse <c>blast_impulse · (1 - d / blast_radius)</c> away from the centre; then a shock wave, a shell <c>shock_thickness</c> thick expanding at <c>shock_speed</c> up to <c>max_radius</c>, pushes objects inside it with up to <c>shock_force</c> (falling off linearly across the shell). Forces act at centres of mass.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ExplosionGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_explosion_generator_def_default()</c>; start every def from here.</summary>
        public static ExplosionGeneratorDef Default() { return Native.hearth_explosion_generator_def_default(); }

        /// <summary>Where it goes off (m).</summary>
        public Vec3 Center;
        /// <summary>Reach of the blast (m, &gt;= 0). Default 5.</summary>
        public float BlastRadius;
        /// <summary>Impulse at the centre (N·s, &gt;= 0). Default 50.</summary>
        public float BlastImpulse;
        /// <summary>Speed of the shock wave (m/s, &gt;= 0). Default 20.</summary>
        public float ShockSpeed;
        /// <summary>Thickness of the shell (m, &gt;= 0). Default 1.</summary>
        public float ShockThickness;
        /// <summary>Peak force of the shock wave (N, &gt;= 0). Default 100.</summary>
        public float ShockForce;
        /// <summary>The wave stops at this radius (m, &gt;= 0). Default 20.</summary>
        public float MaxRadius;
        /// <summary>1 (default): acts on every body and particle in range; 0: only on attached ones.</summary>
        public Flag AffectAll;
        /// <summary>Set by <c>hearth_explosion_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A rod: ends <c>a</c> and <c>b</c> stay <c>length</c> apart (it pushes and pulls). Between bodies (or a body and the world) the rigid solver resolves it with the collision contacts; with a particle end it is solved in the particle stage, exactly together with the other rods.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct RodGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_rod_generator_def_default()</c>; start every def from here.</summary>
        public static RodGeneratorDef Default() { return Native.hearth_rod_generator_def_default(); }

        /// <summary>First end. Default: the world origin.</summary>
        public LinkEnd A;
        /// <summary>Second end. Default: the world origin.</summary>
        public LinkEnd B;
        /// <summary>Length (m, &gt;= 0). Default 1.</summary>
        public float Length;
        /// <summary>Set by <c>hearth_rod_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A cable: ends <c>a</c> and <c>b</c> stay at most <c>max_length</c> apart (it only pulls, and goes slack when they come closer); a cable snapping taut bounces with <c>restitution</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct CableGeneratorDef
    {

        /// <summary>The defaults of <c>hearth_cable_generator_def_default()</c>; start every def from here.</summary>
        public static CableGeneratorDef Default() { return Native.hearth_cable_generator_def_default(); }

        /// <summary>First end. Default: the world origin.</summary>
        public LinkEnd A;
        /// <summary>Second end. Default: the world origin.</summary>
        public LinkEnd B;
        /// <summary>Maximum length (m, &gt;= 0). Default 1.</summary>
        public float MaxLength;
        /// <summary>Bounce when it snaps taut (&gt;= 0). Default 0.</summary>
        public float Restitution;
        /// <summary>Set by <c>hearth_cable_generator_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>The fields every joint def starts with.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct JointBase
    {
        /// <summary>Body A (required, any type; at least one of the two bodies must not be static).</summary>
        public BodyId BodyA;
        /// <summary>Body B, or the null id to join body A to the world.</summary>
        public BodyId BodyB;
        /// <summary>Joint frame on A, relative to A's origin. Default identity.</summary>
        public Transform FrameA;
        /// <summary>Joint frame on B relative to B's origin, or in world space when <c>body_b</c> is null. Default identity.</summary>
        public Transform FrameB;
        /// <summary>1 to let the two bodies collide with each other; 0 (default) filters the pair and destroys contacts between them when the joint is created.</summary>
        public Flag CollideConnected;
        /// <summary>Force (N, &gt; 0) above which the joint breaks. Default <c>FLT_MAX</c> (never).</summary>
        public float BreakForce;
        /// <summary>Torque (N·m, &gt; 0) above which the joint breaks. Default <c>FLT_MAX</c> (never).</summary>
        public float BreakTorque;
    }

    /// <summary>Ball-and-socket: the anchors coincide; optional cone (swing) and twist limits about Z.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BallJointDef
    {

        /// <summary>The defaults of <c>hearth_ball_joint_def_default()</c>; start every def from here.</summary>
        public static BallJointDef Default() { return Native.hearth_ball_joint_def_default(); }

        /// <summary>Bodies, frames, collision, breaking.</summary>
        public JointBase Base;
        /// <summary>1 to keep B's Z axis within <c>swing_limit</c> of A's. Default 0.</summary>
        public Flag EnableSwingLimit;
        /// <summary>Cone half-angle (rad, 0..=π). Default π/4.</summary>
        public float SwingLimit;
        /// <summary>1 to keep B's twist about Z within <c>lower_twist..=upper_twist</c>. Default 0.</summary>
        public Flag EnableTwistLimit;
        /// <summary>Twist limits (rad, -π..=π, lower &lt;= upper). Defaults -π/4 and π/4.</summary>
        public float LowerTwist;
        /// <summary>Upper twist limit (rad).</summary>
        public float UpperTwist;
        /// <summary>Set by <c>hearth_ball_joint_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Id of a joint inside its world. All-zero is the null id; a destroyed joint's id is stale (<c>HEARTH_ERROR_INVALID_ID</c>).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct JointId : IEquatable<JointId>
    {
        /// <summary>Slot of the joint.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public JointId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly JointId Null = default(JointId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(JointId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is JointId && Equals((JointId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(JointId a, JointId b) { return a.Equals(b); }
        public static bool operator !=(JointId a, JointId b) { return !a.Equals(b); }
        public override string ToString() { return "JointId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Hinge: the anchors coincide and the Z axes stay aligned; B turns about Z. The angle is B's turn relative to A (0 where the frames coincide); the motor speed is B's angular speed relative to A about Z.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HingeJointDef
    {

        /// <summary>The defaults of <c>hearth_hinge_joint_def_default()</c>; start every def from here.</summary>
        public static HingeJointDef Default() { return Native.hearth_hinge_joint_def_default(); }

        /// <summary>Bodies, frames, collision, breaking.</summary>
        public JointBase Base;
        /// <summary>1 to keep the angle within <c>lower..=upper</c>. Default 0.</summary>
        public Flag EnableLimit;
        /// <summary>Lower angle limit (rad, -π..=π). Default -π/2.</summary>
        public float Lower;
        /// <summary>Upper angle limit (rad, -π..=π, &gt;= lower). Default π/2.</summary>
        public float Upper;
        /// <summary>1 to drive the hinge at <c>motor_speed</c>. Default 0.</summary>
        public Flag EnableMotor;
        /// <summary>Target speed (rad/s). Default 0.</summary>
        public float MotorSpeed;
        /// <summary>Largest motor torque (N·m, &gt;= 0). Default 0.</summary>
        public float MaxMotorTorque;
        /// <summary>1 for a spring toward angle 0. Default 0.</summary>
        public Flag EnableSpring;
        /// <summary>Spring frequency (Hz, &gt;= 0; 0 exerts no force). Default 0.</summary>
        public float SpringHertz;
        /// <summary>Spring damping ratio (&gt;= 0). Default 0.</summary>
        public float SpringDampingRatio;
        /// <summary>Set by <c>hearth_hinge_joint_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Fixed (weld): the frames stay together.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct FixedJointDef
    {

        /// <summary>The defaults of <c>hearth_fixed_joint_def_default()</c>; start every def from here.</summary>
        public static FixedJointDef Default() { return Native.hearth_fixed_joint_def_default(); }

        /// <summary>Bodies, frames, collision, breaking.</summary>
        public JointBase Base;
        /// <summary>Set by <c>hearth_fixed_joint_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Distance: the frames' origins (the anchors) stay <c>length</c> apart. With the spring off the joint is rigid; with it on, the spring pulls toward <c>length</c> and the limits (when enabled) bound the length — a spring of 0 Hz is a rope, free within the limits.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct DistanceJointDef
    {

        /// <summary>The defaults of <c>hearth_distance_joint_def_default()</c>; start every def from here.</summary>
        public static DistanceJointDef Default() { return Native.hearth_distance_joint_def_default(); }

        /// <summary>Bodies, frames, collision, breaking.</summary>
        public JointBase Base;
        /// <summary>Rest length (m, &gt;= 0). Default 1.</summary>
        public float Length;
        /// <summary>1 to keep the length within <c>min_length..=max_length</c> (with the spring on). Default 0.</summary>
        public Flag EnableLimit;
        /// <summary>Shortest length (m, &gt;= 0). Default 0.</summary>
        public float MinLength;
        /// <summary>Longest length (m, &gt;= min_length). Default 1e6.</summary>
        public float MaxLength;
        /// <summary>1 for a spring instead of a rigid rod. Default 0.</summary>
        public Flag EnableSpring;
        /// <summary>Spring frequency (Hz, &gt;= 0). Default 0.</summary>
        public float SpringHertz;
        /// <summary>Spring damping ratio (&gt;= 0). Default 0.</summary>
        public float SpringDampingRatio;
        /// <summary>Set by <c>hearth_distance_joint_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Slider (prismatic): B keeps A's orientation and moves only along A's Z axis. The translation is B's anchor along A's Z from A's anchor; the motor speed is B's speed relative to A along Z.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SliderJointDef
    {

        /// <summary>The defaults of <c>hearth_slider_joint_def_default()</c>; start every def from here.</summary>
        public static SliderJointDef Default() { return Native.hearth_slider_joint_def_default(); }

        /// <summary>Bodies, frames, collision, breaking.</summary>
        public JointBase Base;
        /// <summary>1 to keep the translation within <c>lower..=upper</c>. Default 0.</summary>
        public Flag EnableLimit;
        /// <summary>Lower translation limit (m). Default -1.</summary>
        public float Lower;
        /// <summary>Upper translation limit (m, &gt;= lower). Default 1.</summary>
        public float Upper;
        /// <summary>1 to drive the slider at <c>motor_speed</c>. Default 0.</summary>
        public Flag EnableMotor;
        /// <summary>Target speed (m/s). Default 0.</summary>
        public float MotorSpeed;
        /// <summary>Largest motor force (N, &gt;= 0). Default 0.</summary>
        public float MaxMotorForce;
        /// <summary>Set by <c>hearth_slider_joint_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>How to create a particle. Get one from <c>hearth_particle_def_default()</c>, then edit it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ParticleDef
    {

        /// <summary>The defaults of <c>hearth_particle_def_default()</c>; start every def from here.</summary>
        public static ParticleDef Default() { return Native.hearth_particle_def_default(); }

        /// <summary>Position (m).</summary>
        public Vec3 Position;
        /// <summary>Velocity (m/s).</summary>
        public Vec3 Velocity;
        /// <summary>Constant acceleration of this particle (m/s²), on top of world gravity. Default 0.</summary>
        public Vec3 Acceleration;
        /// <summary>Inverse mass (1/kg, &gt;= 0); 0 is an infinite mass (a pinned particle, moved only by its velocity). Default 1 (1 kg).</summary>
        public float InverseMass;
        /// <summary>Radius of the small sphere it collides as (m, &gt;= 0). Default 0.05.</summary>
        public float Radius;
        /// <summary>Linear damping (1/s, &gt;= 0): <c>v /= 1 + h·damping</c> per sub-step. Default 0.</summary>
        public float Damping;
        /// <summary>Multiplier of world gravity. Default 1.</summary>
        public float GravityScale;
        /// <summary>Bounciness against shapes (&gt;= 0; the pair uses the larger of the particle's and the shape's). Default 0.</summary>
        public float Restitution;
        /// <summary>Coulomb friction against shapes (&gt;= 0; the pair uses the geometric mean with the shape's static friction). Default 0.5.</summary>
        public float Friction;
        /// <summary>Seconds until the particle expires (&gt; 0; <c>INFINITY</c>, the default, lives forever). Expired particles are removed and reported by <c>hearth_world_get_expired_particles</c>.</summary>
        public float Lifetime;
        /// <summary>1 (default) collides with shapes; 0 passes through everything.</summary>
        public Flag Collide;
        /// <summary>1 (default) lets the particle sleep when still; 0 keeps it awake.</summary>
        public Flag AllowSleep;
        /// <summary>Host data, returned by <c>hearth_particle_get_user_data</c> and in the expired report.</summary>
        public ulong UserData;
        /// <summary>Set by <c>hearth_particle_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A burst of particles from one point. Get one from <c>hearth_burst_def_default()</c>, then edit it. The same def (same seed) always gives the same burst.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BurstDef
    {

        /// <summary>The defaults of <c>hearth_burst_def_default()</c>; start every def from here.</summary>
        public static BurstDef Default() { return Native.hearth_burst_def_default(); }

        /// <summary>Where every particle starts (m).</summary>
        public Vec3 Position;
        /// <summary>Axis of the cone (need not be unit length, must not be zero). Default +Y.</summary>
        public Vec3 Direction;
        /// <summary>Half-angle of the cone (radians, 0..=π; π is every direction). Directions are uniform over the cone's solid angle. Default 0.5.</summary>
        public float ConeHalfAngle;
        /// <summary>Particles to emit (0..=1048576). Default 16.</summary>
        public uint Count;
        /// <summary>Slowest speed (m/s, &gt;= 0); speeds are uniform in [min, max]. Default 5.</summary>
        public float SpeedMin;
        /// <summary>Fastest speed (m/s, &gt;= speed_min). Default 10.</summary>
        public float SpeedMax;
        /// <summary>Shortest lifetime (s, &gt; 0); lifetimes are uniform in [min, max]. Default 1.</summary>
        public float LifetimeMin;
        /// <summary>Longest lifetime (s, &gt;= lifetime_min; <c>INFINITY</c> lives forever). Default 2.</summary>
        public float LifetimeMax;
        /// <summary>Seed of the random sequence. Default 1.</summary>
        public ulong Seed;
        /// <summary>Every other property of the particles, from <c>hearth_particle_def_default()</c>; its position, lifetime and (added to each particle's own) velocity are per burst.</summary>
        public ParticleDef Particle;
        /// <summary>Set by <c>hearth_burst_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A particle that expired (its lifetime ran out) in the last step. Its id is stale.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ExpiredParticle
    {
        /// <summary>Its (now stale) id.</summary>
        public ParticleId Id;
        /// <summary>Where it was when it expired (m).</summary>
        public Vec3 Position;
        /// <summary>Its velocity then (m/s).</summary>
        public Vec3 Velocity;
        /// <summary>The particle's <c>user_data</c>.</summary>
        public ulong UserData;
    }

    /// <summary>Material of a shape. Get one from <c>hearth_shape_def_default()</c>, then edit it. Where two shapes touch, friction combines as the geometric mean and restitution as the maximum.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ShapeDef
    {

        /// <summary>The defaults of <c>hearth_shape_def_default()</c>; start every def from here.</summary>
        public static ShapeDef Default() { return Native.hearth_shape_def_default(); }

        /// <summary>kg/m³ (&gt;= 0). Default 1000 (water).</summary>
        public float Density;
        /// <summary>Coulomb friction coefficient while the surfaces stick (&gt;= 0). Default 0.6.</summary>
        public float StaticFriction;
        /// <summary>Coulomb friction coefficient while they slide (&gt;= 0; the pair uses at most the static value). Default 0.6.</summary>
        public float DynamicFriction;
        /// <summary>Bounciness: 0 none, 1 elastic (&gt;= 0). Default 0.</summary>
        public float Restitution;
        /// <summary>Host data.</summary>
        public ulong UserData;
        /// <summary>Set by <c>hearth_shape_def_default()</c>; do not change.</summary>
        public uint InternalValue;
        /// <summary>Rolling resistance, 0..=1. Default 0.05: a torque against relative rolling of up to rolling_resistance × radius × normal force (radius: the larger sphere or capsule radius of the pair). The pair uses the larger value.</summary>
        public float RollingResistance;
        /// <summary>Torsional (spin) friction, 0..=1. Default 0.05: a torque against relative spin about the contact normal of up to torsional_friction × radius × normal force. The pair uses the larger value.</summary>
        public float TorsionalFriction;
        /// <summary>Which shapes this one collides with and which queries see it. Default: Filter.Default().</summary>
        public Filter Filter;
        /// <summary>1 makes the shape a sensor: it reports overlaps as sensor events, never pushes, adds no mass. Default 0.</summary>
        public Flag IsSensor;
        /// <summary>1 (default): contact begin and end events (both shapes must enable them).</summary>
        public Flag EnableContactEvents;
        /// <summary>1: hit events (either shape may enable them). Default 0.</summary>
        public Flag EnableHitEvents;
        /// <summary>1 (default): sensor events (both shapes must enable them).</summary>
        public Flag EnableSensorEvents;
    }

    /// <summary>A shape's collision filter (Box2D's rules): the same positive GroupIndex always collides, the same negative one never; otherwise each CategoryBits must share a bit with the other's MaskBits.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Filter
    {
        /// <summary>hearth_filter_default(): category 1, every mask bit, group 0.</summary>
        public static Filter Default() { return Native.hearth_filter_default(); }

        public ulong CategoryBits;
        public ulong MaskBits;
        public int GroupIndex;

        public Filter(ulong categoryBits, ulong maskBits, int groupIndex) { CategoryBits = categoryBits; MaskBits = maskBits; GroupIndex = groupIndex; }
    }

    /// <summary>The filter of a query: reports a shape when CategoryBits shares a bit with its mask and its category shares a bit with MaskBits.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct QueryFilter
    {
        /// <summary>hearth_query_filter_default(): category 1, every mask bit.</summary>
        public static QueryFilter Default() { return Native.hearth_query_filter_default(); }

        public ulong CategoryBits;
        public ulong MaskBits;

        public QueryFilter(ulong categoryBits, ulong maskBits) { CategoryBits = categoryBits; MaskBits = maskBits; }
    }

    /// <summary>One ray of World.CastRays: from Origin along Translation.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct RayInput
    {
        public Vec3 Origin;
        public Vec3 Translation;

        public RayInput(Vec3 origin, Vec3 translation) { Origin = origin; Translation = translation; }
    }

    /// <summary>A ray's or shape cast's hit; a miss has the null Shape id (see IsHit).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct RayHit
    {
        public ShapeId Shape;
        public BodyId Body;
        public Vec3 Point;
        public Vec3 Normal;
        public float Fraction;

        /// <summary>False for a miss (null shape id).</summary>
        public bool IsHit { get { return !Shape.IsNull; } }
    }

    /// <summary>A shape for shape casts and overlaps: Type says which member is used.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct QueryShape
    {
        public QueryShapeType Type;
        public Sphere Sphere;
        public Capsule Capsule;
        public Box Box;
        public HullShape Hull;

        public static QueryShape Of(Sphere s) { var q = default(QueryShape); q.Type = QueryShapeType.Sphere; q.Sphere = s; return q; }
        public static QueryShape Of(Capsule c) { var q = default(QueryShape); q.Type = QueryShapeType.Capsule; q.Capsule = c; return q; }
        public static QueryShape Of(Box b) { var q = default(QueryShape); q.Type = QueryShapeType.Box; q.Box = b; return q; }
        public static QueryShape Of(HullShape h) { var q = default(QueryShape); q.Type = QueryShapeType.Hull; q.Hull = h; return q; }
    }

    /// <summary>A body's mass (kg), centre of mass in the body frame (m) and principal moments of inertia along the body axes (kg·m²): hearth_body_set_mass_data / hearth_body_get_mass_data.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MassData
    {
        public float Mass;
        public Vec3 Center;
        public Vec3 Inertia;

        public MassData(float mass, Vec3 center, Vec3 inertia) { Mass = mass; Center = center; Inertia = inertia; }
    }

    /// <summary>Sphere: centre in the body frame and radius (m, &gt; 0).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Sphere
    {
        public Vec3 Center;
        public float Radius;

        public Sphere(Vec3 center, float radius) { Center = center; Radius = radius; }
    }

    /// <summary>Id of a shape inside its world. All-zero is the null id.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ShapeId : IEquatable<ShapeId>
    {
        public uint Index;
        public uint Generation;

        public ShapeId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly ShapeId Null = default(ShapeId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(ShapeId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is ShapeId && Equals((ShapeId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(ShapeId a, ShapeId b) { return a.Equals(b); }
        public static bool operator !=(ShapeId a, ShapeId b) { return !a.Equals(b); }
        public override string ToString() { return "ShapeId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Box: centre and rotation in the body frame, half extents (m, each &gt; 0).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Box
    {
        public Vec3 Center;
        public Quat Rotation;
        public Vec3 HalfExtents;

        public Box(Vec3 center, Quat rotation, Vec3 halfExtents) { Center = center; Rotation = rotation; HalfExtents = halfExtents; }

        /// <summary>A box centred on the body origin, not rotated.</summary>
        public Box(Vec3 halfExtents) : this(Vec3.Zero, Quat.Identity, halfExtents) { }
    }

    /// <summary>Capsule: segment end points <c>a</c>, <c>b</c> in the body frame and radius (m, &gt; 0).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Capsule
    {
        public Vec3 A;
        public Vec3 B;
        public float Radius;

        public Capsule(Vec3 a, Vec3 b, float radius) { A = a; B = b; Radius = radius; }
    }

    /// <summary>Plane (static bodies only), in the body frame: points <c>p</c> with <c>dot(normal, p) &lt;= offset</c> are inside. The normal need not be unit length (it is normalised together with the offset) but must not be zero.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Plane
    {
        public Vec3 Normal;
        public float Offset;

        public Plane(Vec3 normal, float offset) { Normal = normal; Offset = offset; }
    }

    /// <summary>Id of a convex hull (shared geometry) inside its world. All-zero is the null id. Ids of destroyed objects and of other worlds are rejected with <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HullId : IEquatable<HullId>
    {
        /// <summary>Slot of the convex hull.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public HullId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly HullId Null = default(HullId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(HullId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is HullId && Equals((HullId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(HullId a, HullId b) { return a.Equals(b); }
        public static bool operator !=(HullId a, HullId b) { return !a.Equals(b); }
        public override string ToString() { return "HullId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Id of a triangle mesh (shared geometry) inside its world. All-zero is the null id. Ids of destroyed objects and of other worlds are rejected with <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MeshId : IEquatable<MeshId>
    {
        /// <summary>Slot of the triangle mesh.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public MeshId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly MeshId Null = default(MeshId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(MeshId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is MeshId && Equals((MeshId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(MeshId a, MeshId b) { return a.Equals(b); }
        public static bool operator !=(MeshId a, MeshId b) { return !a.Equals(b); }
        public override string ToString() { return "MeshId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>Id of a heightfield (shared geometry) inside its world. All-zero is the null id. Ids of destroyed objects and of other worlds are rejected with <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HeightfieldId : IEquatable<HeightfieldId>
    {
        /// <summary>Slot of the heightfield.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public HeightfieldId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly HeightfieldId Null = default(HeightfieldId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(HeightfieldId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is HeightfieldId && Equals((HeightfieldId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(HeightfieldId a, HeightfieldId b) { return a.Equals(b); }
        public static bool operator !=(HeightfieldId a, HeightfieldId b) { return !a.Equals(b); }
        public override string ToString() { return "HeightfieldId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>How a convex hull is built. Get one from <c>hearth_hull_def_default()</c>, then edit it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HullDef
    {

        /// <summary>The defaults of <c>hearth_hull_def_default()</c>; start every def from here.</summary>
        public static HullDef Default() { return Native.hearth_hull_def_default(); }

        /// <summary>Convex radius (m, &gt;= 0): the shape is the hull of the points grown by this much. Default 0.</summary>
        public float ConvexRadius;
        /// <summary>Weld and merge tolerance as a fraction of the cloud's size (0 ..= 0.1). Default 0.001.</summary>
        public float WeldTolerance;
        /// <summary>Set by <c>hearth_hull_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>A convex hull instanced by a shape: scaled uniformly by <c>Scale</c> (&gt; 0), then placed by <c>Local</c> in the body frame.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HullShape
    {
        public HullId Hull;
        public Transform Local;
        public float Scale;

        public HullShape(HullId hull, Transform local, float scale) { Hull = hull; Local = local; Scale = scale; }
    }

    /// <summary>A triangle mesh instanced by a shape (static and kinematic bodies): scaled per axis (each &gt;= 1e-4), then placed by <c>Local</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct MeshShape
    {
        public MeshId Mesh;
        public Transform Local;
        public Vec3 Scale;

        public MeshShape(MeshId mesh, Transform local, Vec3 scale) { Mesh = mesh; Local = local; Scale = scale; }
    }

    /// <summary>A heightfield instanced by a shape (static and kinematic bodies): <c>Scale.X</c>, <c>Scale.Z</c> the sample spacing (m), <c>Scale.Y</c> the height scale.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct HeightfieldShape
    {
        public HeightfieldId Heightfield;
        public Transform Local;
        public Vec3 Scale;

        public HeightfieldShape(HeightfieldId heightfield, Transform local, Vec3 scale) { Heightfield = heightfield; Local = local; Scale = scale; }
    }

    /// <summary>How to create a soft body (everything except its mesh). Get one from <c>hearth_soft_body_def_default()</c>, then edit it. The solver is XPBD with sub-steps: stiffness is given as compliance (the inverse of stiffness), does not depend on the time step, and any value is stable.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SoftBodyDef
    {

        /// <summary>The defaults of <c>hearth_soft_body_def_default()</c>; start every def from here.</summary>
        public static SoftBodyDef Default() { return Native.hearth_soft_body_def_default(); }

        /// <summary>Placement of the mesh: its vertices (given in the mesh's own frame) are rotated, then moved by <c>transform.position</c> (m). Default: identity.</summary>
        public Transform Transform;
        /// <summary>Initial velocity of every vertex (m/s). Default 0.</summary>
        public Vec3 Velocity;
        /// <summary>Total mass (kg, &gt; 0), shared equally by the vertices unless per-vertex masses are given to <c>hearth_soft_body_create_mesh</c>. Default 1.</summary>
        public float Mass;
        /// <summary>Compliance of the stretch springs along the mesh edges (m/N, &gt;= 0; 0 is inextensible). Default 0.</summary>
        public float EdgeCompliance;
        /// <summary>Compliance of the bending springs across edges shared by two triangles (m/N, &gt;= 0; <c>INFINITY</c> disables bending). Default 0.01.</summary>
        public float BendCompliance;
        /// <summary>1 keeps the enclosed volume at its rest value (closed, outward-wound meshes); 0 (default) does not.</summary>
        public Flag PreserveVolume;
        /// <summary>Compliance of the volume constraint (&gt;= 0; 0 is incompressible). Default 0.</summary>
        public float VolumeCompliance;
        /// <summary>Gas pressure as n·R·T (J = Pa·m³, &gt;= 0): each face is pushed out along its normal by <c>nRT / V · area</c>, V the current enclosed volume. 0 (default) is no gas.</summary>
        public float Pressure;
        /// <summary>Linear damping of the vertices (1/s, &gt;= 0): slows every motion, like air drag. Default 0.5.</summary>
        public float Damping;
        /// <summary>Damping of deformation (1/s, &gt;= 0): each vertex's velocity relaxes at this rate towards the rigid motion of the whole soft body, so wobbling and bouncing on the gas die out while flight and spin are untouched. Default 2.</summary>
        public float DeformationDamping;
        /// <summary>Coulomb friction against shapes (&gt;= 0; the pair uses the geometric mean with the shape's static friction). Default 0.5.</summary>
        public float Friction;
        /// <summary>Bounce against shapes (&gt;= 0; the pair uses the larger of the two). Default 0.</summary>
        public float Restitution;
        /// <summary>Radius of each vertex for collision (m, &gt;= 0). Default 0.01.</summary>
        public float VertexRadius;
        /// <summary>Multiplier of world gravity (finite). Default 1.</summary>
        public float GravityScale;
        /// <summary>XPBD sub-steps per world step (1..=64). Default 20.</summary>
        public uint Substeps;
        /// <summary>Gauss–Seidel passes over the stretch springs per sub-step (1..=16). Default 2 (one pass rings and stretches a large cloth).</summary>
        public uint Iterations;
        /// <summary>1 (default) collides with rigid shapes and planes; 0 passes through everything.</summary>
        public Flag Collide;
        /// <summary>Host data, returned by <c>hearth_soft_body_get_user_data</c>.</summary>
        public ulong UserData;
        /// <summary>Set by <c>hearth_soft_body_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Id of a soft body inside its world. All-zero is the null id. Ids of destroyed soft bodies and of other worlds are rejected with <c>HEARTH_ERROR_INVALID_ID</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SoftBodyId : IEquatable<SoftBodyId>
    {
        /// <summary>Slot of the soft body.</summary>
        public uint Index;
        /// <summary>Generation of the slot (0 only in the null id).</summary>
        public uint Generation;

        public SoftBodyId(uint index, uint generation) { Index = index; Generation = generation; }

        /// <summary>The null id (all zero).</summary>
        public static readonly SoftBodyId Null = default(SoftBodyId);

        /// <summary>True for the null id.</summary>
        public bool IsNull { get { return Index == 0 && Generation == 0; } }

        public bool Equals(SoftBodyId other) { return Index == other.Index && Generation == other.Generation; }
        public override bool Equals(object obj) { return obj is SoftBodyId && Equals((SoftBodyId)obj); }
        public override int GetHashCode() { return (int)(Index * 397u ^ Generation); }
        public static bool operator ==(SoftBodyId a, SoftBodyId b) { return a.Equals(b); }
        public static bool operator !=(SoftBodyId a, SoftBodyId b) { return !a.Equals(b); }
        public override string ToString() { return "SoftBodyId(" + Index + ", " + Generation + ")"; }
    }

    /// <summary>The settings of a soft body that may change after creation: the fields of <c>HearthSoftBodyDef</c> with the same names, units, ranges and defaults. Read them with <c>hearth_soft_body_get_settings</c>, edit, write them back with <c>hearth_soft_body_set_settings</c>.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SoftBodySettings
    {
        /// <summary>Compliance of the stretch springs (m/N, &gt;= 0; 0 is inextensible).</summary>
        public float EdgeCompliance;
        /// <summary>Compliance of the bending springs (m/N, &gt;= 0; <c>INFINITY</c> disables bending).</summary>
        public float BendCompliance;
        /// <summary>1 keeps the enclosed volume at its rest value, 0 does not.</summary>
        public Flag PreserveVolume;
        /// <summary>Compliance of the volume constraint (&gt;= 0; 0 is incompressible).</summary>
        public float VolumeCompliance;
        /// <summary>Gas pressure as n·R·T (J, &gt;= 0).</summary>
        public float Pressure;
        /// <summary>Linear damping of the vertices (1/s, &gt;= 0).</summary>
        public float Damping;
        /// <summary>Damping of deformation towards the rigid motion of the whole body (1/s, &gt;= 0).</summary>
        public float DeformationDamping;
        /// <summary>Coulomb friction against shapes (&gt;= 0).</summary>
        public float Friction;
        /// <summary>Bounce against shapes (&gt;= 0).</summary>
        public float Restitution;
        /// <summary>Radius of each vertex for collision (m, &gt;= 0).</summary>
        public float VertexRadius;
        /// <summary>Multiplier of world gravity (finite).</summary>
        public float GravityScale;
        /// <summary>XPBD sub-steps per world step (1..=64).</summary>
        public uint Substeps;
        /// <summary>Passes over the stretch springs per sub-step (1..=16).</summary>
        public uint Iterations;
        /// <summary>1 collides with rigid shapes and planes, 0 passes through everything.</summary>
        public Flag Collide;
    }

    /// <summary>Settings of a world. Get one from <c>hearth_world_def_default()</c>, then edit it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct WorldDef
    {

        /// <summary>The defaults of <c>hearth_world_def_default()</c>; start every def from here.</summary>
        public static WorldDef Default() { return Native.hearth_world_def_default(); }

        /// <summary>Gravity (m/s²). Default (0, -9.81, 0).</summary>
        public Vec3 Gravity;
        /// <summary>Solver sub-steps per step, 1..=64. Default 6.</summary>
        public uint Substeps;
        /// <summary><c>HEARTH_INTEGRATOR_*</c>. Default semi-implicit Euler.</summary>
        public Integrator Integrator;
        /// <summary>1 to let still islands sleep (default), 0 to keep everything awake.</summary>
        public Flag EnableSleep;
        /// <summary>Speed (m/s and rad/s) below which a body counts as still. Default 0.05.</summary>
        public float SleepThreshold;
        /// <summary>Seconds an island must stay still before it sleeps. Default 0.5.</summary>
        public float TimeToSleep;
        /// <summary>Contact stiffness (Hz), capped at a quarter of the sub-step rate. Default 120.</summary>
        public float ContactHertz;
        /// <summary>Contact damping ratio. Default 10.</summary>
        public float ContactDampingRatio;
        /// <summary>Fastest speed at which overlapping bodies are pushed apart (m/s). Default 3.</summary>
        public float ContactPushMaxVelocity;
        /// <summary>Approach speed below which contacts do not bounce (m/s). Default 1.</summary>
        public float RestitutionThreshold;
        /// <summary>Largest speed a body's centre of mass may reach (m/s), &gt; 0. Default 400. Every velocity a body gets is capped at it, keeping its direction.</summary>
        public float MaxLinearSpeed;
        /// <summary>Soft velocity sweeps per sub-step (each sub-step also runs one rigid relax sweep), 1..=64. Default 1: more sub-steps converge better than more sweeps.</summary>
        public uint VelocityIterations;
        /// <summary>Set by <c>hearth_world_def_default()</c>; do not change.</summary>
        public uint InternalValue;
        /// <summary>Largest angular speed a body may reach (rad/s), &gt; 0. Default 100π ≈ 314.16. Capped like <c>MaxLinearSpeed</c>.</summary>
        public float MaxAngularSpeed;
        /// <summary>Approach speed above which a contact with hit events reports a hit (m/s, 0..=1e4). Default 1.</summary>
        public float HitEventThreshold;
        /// <summary>Threads a step may use, 1..=64. Default 1. Above 1 the world runs its parallel stages on the job system of <c>EnqueueTask</c>/<c>FinishTask</c>, or on threads of its own. Results are bit for bit the same at every count (<c>World.StateHash</c>).</summary>
        public uint WorkerCount;
        /// <summary>A <see cref="EnqueueTaskFn"/> function pointer, or IntPtr.Zero (default). Set both or neither.</summary>
        public IntPtr EnqueueTask;
        /// <summary>A <see cref="FinishTaskFn"/> function pointer, or IntPtr.Zero (default).</summary>
        public IntPtr FinishTask;
        /// <summary>Passed to <c>EnqueueTask</c> and <c>FinishTask</c> as <c>user_context</c>. Default IntPtr.Zero.</summary>
        public IntPtr UserTaskContext;
    }

    /// <summary>How to record a world (hearth_world_record_start_file / _callback).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct RecordDef
    {
        /// <summary>The defaults of <c>hearth_record_def_default()</c>; start every def from here.</summary>
        public static RecordDef Default() { return Native.hearth_record_def_default(); }

        /// <summary>1 to record every touching contact manifold each step. Default 0.</summary>
        public Flag RecordContacts;
        /// <summary>A RecordWriteFn for hearth_world_record_start_callback (NULL for a file). Default NULL.</summary>
        public IntPtr Write;
        /// <summary>Passed to Write as is. Default NULL.</summary>
        public IntPtr UserData;
        /// <summary>Set by <c>hearth_record_def_default()</c>; do not change.</summary>
        public uint InternalValue;
    }

    /// <summary>Counters of a world, for tools and tests.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct WorldCounters
    {
        /// <summary>Live bodies of every type.</summary>
        public uint BodyCount;
        /// <summary>Awake kinematic and dynamic bodies.</summary>
        public uint AwakeBodyCount;
        /// <summary>Live contacts (shape pairs whose bounds overlap).</summary>
        public uint ContactCount;
        /// <summary>Contacts with manifold points in the last step.</summary>
        public uint TouchingContactCount;
        /// <summary>Height of the broad-phase tree.</summary>
        public uint TreeHeight;
    }

    /// <summary>
    /// HearthWorld*: the owner of a world. Releasing it (Dispose, or the finalizer of a
    /// handle nobody disposed) calls hearth_world_destroy exactly once.
    /// </summary>
    public sealed class WorldHandle : SafeHandle
    {
        public WorldHandle() : base(IntPtr.Zero, true) { }

        public override bool IsInvalid { get { return handle == IntPtr.Zero; } }

        protected override bool ReleaseHandle()
        {
            Native.hearth_world_destroy(handle);
            return true;
        }
    }

    /// <summary>
    /// Every function of include/hearth.h, with its C name and signature. Results are returned
    /// as is (no exceptions); the managed layer checks them. HearthWorld* is a WorldHandle
    /// (a SafeHandle that destroys the world), HearthContactSink* an IntPtr.
    /// </summary>
    public static class Native
    {
        /// <summary>The library name given to DllImport: libhearth.so, libhearth.dylib or hearth.dll.</summary>
        public const string Lib = "hearth";

        /// <summary>HEARTH_VERSION_MAJOR of the header this binding was written against.</summary>
        public const uint VersionMajor = 0;
        /// <summary>HEARTH_VERSION_MINOR.</summary>
        public const uint VersionMinor = 2;
        /// <summary>HEARTH_VERSION_PATCH.</summary>
        public const uint VersionPatch = 0;
        /// <summary>HEARTH_VERSION: compare with hearth_version() to detect a mismatched library.</summary>
        public const uint Version = (VersionMajor << 16) | (VersionMinor << 8) | VersionPatch;
        /// <summary>HEARTH_MAX_HULL_POINTS: most points hearth_hull_create accepts.</summary>
        public const uint MaxHullPoints = 1048576;
        /// <summary>HEARTH_MAX_MESH_VERTICES: most vertices hearth_mesh_create accepts.</summary>
        public const uint MaxMeshVertices = 67108864;
        /// <summary>HEARTH_MAX_MESH_INDICES: most indices hearth_mesh_create accepts.</summary>
        public const uint MaxMeshIndices = 201326592;
        /// <summary>HEARTH_MAX_HEIGHTFIELD_SAMPLES: most samples along either side of a heightfield.</summary>
        public const uint MaxHeightfieldSamples = 32768;

        /// <summary>
        /// Whether a library of version <paramref name="library"/> (hearth_version()) has this
        /// binding's ABI: the same major version, and the same minor while the major is 0.
        /// Patch versions may differ.
        /// </summary>
        public static bool IsCompatible(uint library)
        {
            uint major = library >> 16, minor = (library >> 8) & 0xFF;
            return major == VersionMajor && (major != 0 || minor == VersionMinor);
        }

        private static bool versionChecked;

        /// <summary>
        /// Throws InvalidOperationException when the loaded library's ABI is not this binding's
        /// (a stale libhearth next to a newer binding: every struct layout could differ).
        /// World's constructor calls it; the check runs once per process.
        /// </summary>
        public static void EnsureCompatibleLibrary()
        {
            if (versionChecked)
            {
                return;
            }
            uint library = hearth_version();
            if (!IsCompatible(library))
            {
                throw new InvalidOperationException(string.Format(
                    "the loaded Hearth library is version {0}.{1}.{2}, this binding was written for {3}.{4}.{5}; " +
                    "the ABI versions must match (the major version, and the minor before 1.0)",
                    library >> 16, (library >> 8) & 0xFF, library & 0xFF, VersionMajor, VersionMinor, VersionPatch));
            }
            versionChecked = true;
        }

        /// <summary>hearth_result_name as a string ("HEARTH_ERROR_INVALID_ID"; never null).</summary>
        public static string ResultName(Result result)
        {
            return Marshal.PtrToStringAnsi(hearth_result_name((int)result));
        }

        /// <summary>hearth_last_error_message as a string: the calling thread's detail message of its last failure ("" if none).</summary>
        public static string LastErrorMessage()
        {
            ulong length = (ulong)hearth_last_error_message(null, UIntPtr.Zero);
            if (length == 0)
            {
                return "";
            }
            var buffer = new byte[length + 1];
            hearth_last_error_message(buffer, (UIntPtr)buffer.Length);
            return System.Text.Encoding.UTF8.GetString(buffer, 0, (int)length);
        }

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern uint hearth_version();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern IntPtr hearth_result_name(int result);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern UIntPtr hearth_last_error_message([Out] byte[] buf, UIntPtr len);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern BodyDef hearth_body_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_create(WorldHandle world, [In] ref BodyDef def, out BodyId outBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_destroy(WorldHandle world, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_transform(WorldHandle world, BodyId body, out Transform value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_linear_velocity(WorldHandle world, BodyId body, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_angular_velocity(WorldHandle world, BodyId body, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_is_awake(WorldHandle world, BodyId body, [MarshalAs(UnmanagedType.I1)] out bool value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_center_of_mass(WorldHandle world, BodyId body, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_mass(WorldHandle world, BodyId body, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_user_data(WorldHandle world, BodyId body, out ulong value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_type(WorldHandle world, BodyId body, out uint value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_transform(WorldHandle world, BodyId body, [In] ref Transform transform);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_target_transform(WorldHandle world, BodyId body, [In] ref Transform target);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_linear_velocity(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_angular_velocity(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_force(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_torque(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_linear_impulse(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_angular_impulse(WorldHandle world, BodyId body, Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_force_at_point(WorldHandle world, BodyId body, Vec3 force, Vec3 point);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_apply_impulse_at_point(WorldHandle world, BodyId body, Vec3 impulse, Vec3 point);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_awake(WorldHandle world, BodyId body, byte awake);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_damping(WorldHandle world, BodyId body, float linearDamping, float angularDamping);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern DebugDraw hearth_debug_draw_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_draw(WorldHandle world, [In] ref DebugDraw draw);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_friction(WorldHandle world, ShapeId shape, float staticFriction, float dynamicFriction);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_friction(WorldHandle world, ShapeId shape, out float outStaticFriction, out float outDynamicFriction);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_restitution(WorldHandle world, ShapeId shape, float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_restitution(WorldHandle world, ShapeId shape, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_rolling_resistance(WorldHandle world, ShapeId shape, float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_rolling_resistance(WorldHandle world, ShapeId shape, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_torsional_friction(WorldHandle world, ShapeId shape, float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_torsional_friction(WorldHandle world, ShapeId shape, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_density(WorldHandle world, ShapeId shape, float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_density(WorldHandle world, ShapeId shape, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_user_data(WorldHandle world, ShapeId shape, ulong userData);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_user_data(WorldHandle world, ShapeId shape, out ulong value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_gravity_scale(WorldHandle world, BodyId body, float gravityScale);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_gravity_scale(WorldHandle world, BodyId body, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_locked_axes(WorldHandle world, BodyId body, LockedAxes lockedAxes);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_locked_axes(WorldHandle world, BodyId body, out LockedAxes value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_mass_data(WorldHandle world, BodyId body, [In] ref MassData data);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_get_mass_data(WorldHandle world, BodyId body, out MassData value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_reset_mass_data(WorldHandle world, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_set_type(WorldHandle world, BodyId body, uint type);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_disable(WorldHandle world, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_enable(WorldHandle world, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_body_is_enabled(WorldHandle world, BodyId body, [MarshalAs(UnmanagedType.U1)] out bool value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern UserForceGeneratorDef hearth_user_force_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_user_force(WorldHandle world, [In] ref UserForceGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern UserContactGeneratorDef hearth_user_contact_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_user_contact(WorldHandle world, [In] ref UserContactGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_contact_sink_add(IntPtr sink, [In] ref GeneratedContact contact);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_contact_sink_get_count(IntPtr sink, out uint outCount, out uint outCapacity);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern GravityGeneratorDef hearth_gravity_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_gravity(WorldHandle world, [In] ref GravityGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern DragGeneratorDef hearth_drag_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_drag(WorldHandle world, [In] ref DragGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern SpringGeneratorDef hearth_spring_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_spring(WorldHandle world, [In] ref SpringGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_bungee(WorldHandle world, [In] ref SpringGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern StiffSpringGeneratorDef hearth_stiff_spring_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_stiff_spring(WorldHandle world, [In] ref StiffSpringGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern BuoyancyGeneratorDef hearth_buoyancy_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_buoyancy(WorldHandle world, [In] ref BuoyancyGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern ExplosionGeneratorDef hearth_explosion_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_explosion(WorldHandle world, [In] ref ExplosionGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern RodGeneratorDef hearth_rod_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_rod(WorldHandle world, [In] ref RodGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern CableGeneratorDef hearth_cable_generator_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_create_cable(WorldHandle world, [In] ref CableGeneratorDef def, out GeneratorId outGenerator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_destroy(WorldHandle world, GeneratorId generator);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_attach_body(WorldHandle world, GeneratorId generator, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_detach_body(WorldHandle world, GeneratorId generator, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_attach_particle(WorldHandle world, GeneratorId generator, ParticleId particle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_attach_particles(WorldHandle world, GeneratorId generator, [In] ParticleId[] particles, UIntPtr count);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_detach_particle(WorldHandle world, GeneratorId generator, ParticleId particle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_get_attachment_count(WorldHandle world, GeneratorId generator, out uint outBodyCount, out uint outParticleCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_get_type(WorldHandle world, GeneratorId generator, out uint outType);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern BallJointDef hearth_ball_joint_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_create_ball(WorldHandle world, [In] ref BallJointDef def, out JointId outJoint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern HingeJointDef hearth_hinge_joint_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_create_hinge(WorldHandle world, [In] ref HingeJointDef def, out JointId outJoint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern FixedJointDef hearth_fixed_joint_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_create_fixed(WorldHandle world, [In] ref FixedJointDef def, out JointId outJoint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern DistanceJointDef hearth_distance_joint_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_create_distance(WorldHandle world, [In] ref DistanceJointDef def, out JointId outJoint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern SliderJointDef hearth_slider_joint_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_create_slider(WorldHandle world, [In] ref SliderJointDef def, out JointId outJoint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_destroy(WorldHandle world, JointId joint);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_type(WorldHandle world, JointId joint, out uint outType);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_bodies(WorldHandle world, JointId joint, out BodyId outBodyA, out BodyId outBodyB);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_set_motor(WorldHandle world, JointId joint, byte enable, float speed, float max);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_motor(WorldHandle world, JointId joint, [MarshalAs(UnmanagedType.I1)] out bool outEnabled, out float outSpeed, out float outMax);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_set_limits(WorldHandle world, JointId joint, byte enable, float lower, float upper);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_limits(WorldHandle world, JointId joint, [MarshalAs(UnmanagedType.I1)] out bool outEnabled, out float outLower, out float outUpper);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_set_cone_limit(WorldHandle world, JointId joint, byte enable, float angle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_cone_limit(WorldHandle world, JointId joint, [MarshalAs(UnmanagedType.I1)] out bool outEnabled, out float outAngle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_set_spring(WorldHandle world, JointId joint, byte enable, float hertz, float dampingRatio);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_spring(WorldHandle world, JointId joint, [MarshalAs(UnmanagedType.I1)] out bool outEnabled, out float outHertz, out float outDampingRatio);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_get_force(WorldHandle world, JointId joint, out Vec3 outForce, out Vec3 outTorque);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_joint_is_broken(WorldHandle world, JointId joint, [MarshalAs(UnmanagedType.I1)] out bool outBroken);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_broken_joints(WorldHandle world, [Out] JointId[] outJoints, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern ParticleDef hearth_particle_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_create(WorldHandle world, [In] ref ParticleDef def, out ParticleId outParticle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_destroy(WorldHandle world, ParticleId particle);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_get_position(WorldHandle world, ParticleId particle, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_get_velocity(WorldHandle world, ParticleId particle, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_is_awake(WorldHandle world, ParticleId particle, [MarshalAs(UnmanagedType.I1)] out bool value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_get_user_data(WorldHandle world, ParticleId particle, out ulong value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_set_position(WorldHandle world, ParticleId particle, Vec3 position);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_set_velocity(WorldHandle world, ParticleId particle, Vec3 velocity);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_apply_force(WorldHandle world, ParticleId particle, Vec3 force);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_apply_impulse(WorldHandle world, ParticleId particle, Vec3 impulse);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_set_awake(WorldHandle world, ParticleId particle, byte awake);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern BurstDef hearth_burst_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_particle_emit_burst(WorldHandle world, [In] ref BurstDef def, [Out] ParticleId[] outIds, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_particle_count(WorldHandle world, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_particles(WorldHandle world, [Out] ParticleId[] outIds, [Out] Vec3[] outPositions, [Out] Vec3[] outVelocities, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_particle_positions(WorldHandle world, [In] ParticleId[] particles, UIntPtr count, [Out] Vec3[] outPositions);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_expired_particles(WorldHandle world, out IntPtr outArray, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_set_particle_iterations(WorldHandle world, uint velocityIterations, uint positionIterations);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern RecordDef hearth_record_def_default();

        /// <summary><paramref name="path"/>: NUL-terminated UTF-8 (see World.RecordToFile).</summary>
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_record_start_file(WorldHandle world, [In] byte[] path, ref RecordDef def);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_record_start_callback(WorldHandle world, ref RecordDef def);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_record_stop(WorldHandle world);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_snapshot_size(WorldHandle world, out UIntPtr outSize);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_snapshot_save(WorldHandle world, [Out] byte[] buffer, UIntPtr capacity, out UIntPtr outWritten);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_snapshot_restore(WorldHandle world, [In] byte[] buffer, UIntPtr size);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_user_generators_missing_callback(WorldHandle world, [Out] GeneratorId[] outGenerators, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_set_user_force_callback(WorldHandle world, GeneratorId generator, [In] ref UserForceGeneratorDef def);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_generator_set_user_contact_callback(WorldHandle world, GeneratorId generator, [In] ref UserContactGeneratorDef def);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern ShapeDef hearth_shape_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_sphere(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref Sphere sphere, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_box(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref Box box, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_capsule(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref Capsule capsule, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_plane(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref Plane plane, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_hull(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref HullShape hull, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_mesh(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref MeshShape mesh, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_create_heightfield(WorldHandle world, BodyId body, [In] ref ShapeDef def, [In] ref HeightfieldShape heightfield, out ShapeId outShape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern HullDef hearth_hull_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_hull_create(WorldHandle world, [In] ref HullDef def, [In] Vec3[] points, UIntPtr pointCount, out HullId outHull);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_hull_destroy(WorldHandle world, HullId hull);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_hull_get_vertex_count(WorldHandle world, HullId hull, out uint outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_mesh_create(WorldHandle world, [In] Vec3[] vertices, UIntPtr vertexCount, [In] uint[] indices, UIntPtr indexCount, out MeshId outMesh);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_mesh_destroy(WorldHandle world, MeshId mesh);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_mesh_get_triangle_count(WorldHandle world, MeshId mesh, out uint outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_mesh_get_degenerate_count(WorldHandle world, MeshId mesh, out uint outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_heightfield_create(WorldHandle world, uint rows, uint columns, [In] float[] heights, [In] byte[] holes, out HeightfieldId outHeightfield);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_heightfield_destroy(WorldHandle world, HeightfieldId heightfield);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_destroy(WorldHandle world, ShapeId shape);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_body(WorldHandle world, ShapeId shape, out BodyId outBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Filter hearth_filter_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern QueryFilter hearth_query_filter_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_set_filter(WorldHandle world, ShapeId shape, Filter filter);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_shape_get_filter(WorldHandle world, ShapeId shape, out Filter outFilter);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_cast_ray_closest(WorldHandle world, Vec3 origin, Vec3 translation, ref QueryFilter filter, out RayHit outHit);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_cast_ray(WorldHandle world, Vec3 origin, Vec3 translation, ref QueryFilter filter, RayCallback callback, IntPtr userData);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_cast_rays(WorldHandle world, [In] RayInput[] rays, UIntPtr count, ref QueryFilter filter, [Out] RayHit[] outHits);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_cast_shape(WorldHandle world, ref QueryShape shape, ref Transform transform, Vec3 translation, ref QueryFilter filter, out RayHit outHit);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_overlap_shape(WorldHandle world, ref QueryShape shape, ref Transform transform, ref QueryFilter filter, [Out] ShapeId[] outShapes, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_overlap_aabb(WorldHandle world, Vec3 min, Vec3 max, ref QueryFilter filter, [Out] ShapeId[] outShapes, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_overlap_point(WorldHandle world, Vec3 point, ref QueryFilter filter, [Out] ShapeId[] outShapes, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern SoftBodyDef hearth_soft_body_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_create_mesh(WorldHandle world, [In] ref SoftBodyDef def, [In] Vec3[] vertices, UIntPtr vertexCount, [In] uint[] indices, UIntPtr indexCount, [In] float[] masses, out SoftBodyId outSoftBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_create_icosphere(WorldHandle world, [In] ref SoftBodyDef def, float radius, uint subdivisions, out SoftBodyId outSoftBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_create_box(WorldHandle world, [In] ref SoftBodyDef def, Vec3 halfExtents, uint cellsX, uint cellsY, uint cellsZ, out SoftBodyId outSoftBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_create_cloth(WorldHandle world, [In] ref SoftBodyDef def, float width, float height, uint columns, uint rows, out SoftBodyId outSoftBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_destroy(WorldHandle world, SoftBodyId softBody);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_soft_body_count(WorldHandle world, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_vertex_count(WorldHandle world, SoftBodyId softBody, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_triangle_count(WorldHandle world, SoftBodyId softBody, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_positions(WorldHandle world, SoftBodyId softBody, [Out] Vec3[] outPositions, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_normals(WorldHandle world, SoftBodyId softBody, [Out] Vec3[] outNormals, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_indices(WorldHandle world, SoftBodyId softBody, [Out] uint[] outIndices, UIntPtr capacity, out UIntPtr outCount);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_vertex_position(WorldHandle world, SoftBodyId softBody, uint vertex, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_vertex_velocity(WorldHandle world, SoftBodyId softBody, uint vertex, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_center(WorldHandle world, SoftBodyId softBody, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_mass(WorldHandle world, SoftBodyId softBody, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_volume(WorldHandle world, SoftBodyId softBody, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_rest_volume(WorldHandle world, SoftBodyId softBody, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_pressure(WorldHandle world, SoftBodyId softBody, out float value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_user_data(WorldHandle world, SoftBodyId softBody, out ulong value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_set_pressure(WorldHandle world, SoftBodyId softBody, float pressure);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_pin_vertex(WorldHandle world, SoftBodyId softBody, uint vertex, BodyId body);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_unpin_vertex(WorldHandle world, SoftBodyId softBody, uint vertex);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_is_vertex_pinned(WorldHandle world, SoftBodyId softBody, uint vertex, [MarshalAs(UnmanagedType.I1)] out bool outPinned);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_apply_impulse(WorldHandle world, SoftBodyId softBody, uint vertex, Vec3 impulse);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_apply_impulse_all(WorldHandle world, SoftBodyId softBody, Vec3 impulse);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_get_settings(WorldHandle world, SoftBodyId softBody, out SoftBodySettings outSettings);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_set_settings(WorldHandle world, SoftBodyId softBody, [In] ref SoftBodySettings settings);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_soft_body_set_compliance(WorldHandle world, SoftBodyId softBody, float edge, float bend, float volume);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern WorldDef hearth_world_def_default();

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_create([In] ref WorldDef def, out WorldHandle outWorld);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern void hearth_world_destroy(IntPtr world);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_step(WorldHandle world, float dt);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_set_gravity(WorldHandle world, Vec3 gravity);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_gravity(WorldHandle world, out Vec3 value);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_counters(WorldHandle world, out WorldCounters value);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_hash(WorldHandle world, out ulong hash);
        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_rebuild_broadphase(WorldHandle world);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_transforms(WorldHandle world, [In] BodyId[] bodies, UIntPtr count, [Out] Transform[] outTransforms);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_contact_events(WorldHandle world, out ContactEvents outEvents);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_sensor_events(WorldHandle world, out SensorEvents outEvents);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_get_body_events(WorldHandle world, out BodyEvents outEvents);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_set_pair_filter_callback(WorldHandle world, IntPtr callback, IntPtr userData);

        [DllImport(Lib, CallingConvention = CallingConvention.Cdecl)]
        public static extern Result hearth_world_set_pre_solve_callback(WorldHandle world, IntPtr callback, IntPtr userData);

    }

    /// <summary>HearthPairFilterCallback: <c>uint8_t (*)(void *user_data, HearthWorld *world, HearthShapeId a, HearthShapeId b)</c>; 0 keeps the pair apart.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate byte PairFilterCallback(IntPtr userData, IntPtr world, ShapeId shapeA, ShapeId shapeB);

    /// <summary>HearthPreSolveCallback: <c>uint8_t (*)(void *user_data, HearthWorld *world, const HearthPreSolveContact *contact)</c>; 0 disables the contact for the step.</summary>
    [UnmanagedFunctionPointer(CallingConvention.Cdecl)]
    public delegate byte PreSolveCallback(IntPtr userData, IntPtr world, IntPtr contact);

    /// <summary>Two shapes (and their bodies) that started or stopped touching.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ContactEvent
    {
        public ShapeId ShapeA;
        public ShapeId ShapeB;
        public BodyId BodyA;
        public BodyId BodyB;
    }

    /// <summary>Two shapes that met faster than the world's hit_event_threshold.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ContactHitEvent
    {
        public ShapeId ShapeA;
        public ShapeId ShapeB;
        public BodyId BodyA;
        public BodyId BodyB;
        /// <summary>Where they met (world, m).</summary>
        public Vec3 Point;
        /// <summary>Unit normal from A to B.</summary>
        public Vec3 Normal;
        /// <summary>Approach speed along the normal at impact (m/s).</summary>
        public float ApproachSpeed;
    }

    /// <summary>The contact events of the last step: native arrays, valid until the next step or destroy (World.GetContactEvents copies them).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ContactEvents
    {
        public IntPtr Begin;
        public UIntPtr BeginCount;
        public IntPtr End;
        public UIntPtr EndCount;
        public IntPtr Hit;
        public UIntPtr HitCount;
    }

    /// <summary>A sensor shape and a shape that started or stopped overlapping it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SensorEvent
    {
        public ShapeId SensorShape;
        public ShapeId VisitorShape;
        public BodyId SensorBody;
        public BodyId VisitorBody;
    }

    /// <summary>The sensor events of the last step (native arrays, as ContactEvents).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct SensorEvents
    {
        public IntPtr Begin;
        public UIntPtr BeginCount;
        public IntPtr End;
        public UIntPtr EndCount;
    }

    /// <summary>A body that moved in the last step, or fell asleep in it.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BodyMoveEvent
    {
        public BodyId Body;
        public Transform Transform;
        public ulong UserData;
        /// <summary>1 when it fell asleep in this step.</summary>
        public byte FellAsleep;
    }

    /// <summary>The body move events of the last step (native array, as ContactEvents).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct BodyEvents
    {
        public IntPtr Moves;
        public UIntPtr MoveCount;
    }

    /// <summary>A contact manifold point: midway between the surfaces, and the signed separation (m, negative overlapping).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct ManifoldPoint
    {
        public Vec3 Point;
        public float Separation;
    }

    /// <summary>What the pre-solve callback sees (valid only during the call; World.SetPreSolve copies the points).</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct PreSolveContact
    {
        public ShapeId ShapeA;
        public ShapeId ShapeB;
        public BodyId BodyA;
        public BodyId BodyB;
        /// <summary>Unit normal from A to B.</summary>
        public Vec3 Normal;
        /// <summary>Native array of PointCount ManifoldPoint.</summary>
        public IntPtr Points;
        public uint PointCount;
    }
}
