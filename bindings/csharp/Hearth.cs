// Hearth.cs - the managed layer of the Hearth C# binding, over the P/Invoke declarations of
// Hearth.Native.cs.
//
// A World owns a WorldHandle (a SafeHandle: Dispose or the finalizer destroys the native
// world once). Bodies, shapes, joints, generators, particles and soft bodies are value types
// holding their World and their id; their properties and methods call the C function of
// the same name. Every failing call throws HearthException with the result code, its name
// and the library's detail message. Defs always start from the library's defaults
// (BodyDef.Default(), ...).
//
// User generators: native code calls one of two static trampolines (ForceTrampoline,
// ContactTrampoline), marked [MonoPInvokeCallback] as Unity's IL2CPP requires (it can only
// hand native code pointers to static methods known ahead of time, never to lambdas); the
// generator's user_data is a GCHandle of its registration, which holds the handler. The
// World frees the handle on DestroyGenerator or Dispose. An exception thrown by a handler is
// caught before it reaches native code and rethrown by the Step() that ran it.
//
// Like the C API, a World is used by one thread at a time.

using System;
using System.Collections.Generic;
using System.Runtime.ExceptionServices;
using System.Runtime.InteropServices;
using System.Text;
using System.Threading;
#if UNITY_5_3_OR_NEWER
using AOT; // Unity's MonoPInvokeCallbackAttribute
#endif

#if !UNITY_5_3_OR_NEWER
namespace AOT
{
    /// <summary>
    /// Marks a static method that native code calls through a function pointer. Unity defines
    /// this attribute (AOT.MonoPInvokeCallbackAttribute) and IL2CPP compiles a native entry
    /// point for every method carrying it; outside Unity it is defined here and changes nothing.
    /// </summary>
    [AttributeUsage(AttributeTargets.Method)]
    public sealed class MonoPInvokeCallbackAttribute : Attribute
    {
        public MonoPInvokeCallbackAttribute(Type type) { Type = type; }

        /// <summary>The delegate type native code calls the method as.</summary>
        public Type Type { get; private set; }
    }
}
#endif

namespace Hearth
{
    using AOT;

    /// <summary>A failed Hearth call: the result code, its name and the library's detail message.</summary>
    public class HearthException : Exception
    {
        /// <summary>The code the C function returned.</summary>
        public Result Result { get; private set; }

        /// <summary>hearth_result_name of the code, e.g. "HEARTH_ERROR_INVALID_ID".</summary>
        public string ResultName { get; private set; }

        /// <summary>hearth_last_error_message right after the failure.</summary>
        public string Detail { get; private set; }

        /// <summary>The C function that failed.</summary>
        public string Function { get; private set; }

        public HearthException(Result result, string function, string detail)
            : base(function + " failed: " + Native.ResultName(result) + ": " + detail)
        {
            Result = result;
            ResultName = Native.ResultName(result);
            Detail = detail;
            Function = function;
        }

        /// <summary>Throws for anything but Result.Ok, with the calling thread's detail message.</summary>
        public static void Check(Result result, string function)
        {
            if (result != Result.Ok)
            {
                throw new HearthException(result, function, Native.LastErrorMessage());
            }
        }
    }

    /// <summary>What a user force generator's handler is told (valid only during the call).</summary>
    public delegate void UserForceHandler(GeneratorCall call);

    /// <summary>What a user contact generator's handler is told; it adds contacts to the sink.</summary>
    public delegate void UserContactHandler(GeneratorCall call, ContactSink sink);

    /// <summary>
    /// The HearthGeneratorContext of one running user generator callback: its generator, the
    /// step's dt and the attached bodies and particles. Valid only inside the callback (one
    /// object per generator, reused every step: reading it allocates nothing).
    /// </summary>
    public sealed class GeneratorCall
    {
        // Field offsets of HearthGeneratorContext, read one by one so that a call allocates nothing.
        private static readonly int DtOffset = (int)Marshal.OffsetOf(typeof(GeneratorContext), "Dt");
        private static readonly int BodiesOffset = (int)Marshal.OffsetOf(typeof(GeneratorContext), "Bodies");
        private static readonly int BodyCountOffset = (int)Marshal.OffsetOf(typeof(GeneratorContext), "BodyCount");
        private static readonly int ParticlesOffset = (int)Marshal.OffsetOf(typeof(GeneratorContext), "Particles");
        private static readonly int ParticleCountOffset = (int)Marshal.OffsetOf(typeof(GeneratorContext), "ParticleCount");

        // Reinterprets the bits of a float (BitConverter.Int32BitsToSingle is not in every profile).
        [StructLayout(LayoutKind.Explicit)]
        private struct FloatBits
        {
            [FieldOffset(0)] public int Bits;
            [FieldOffset(0)] public float Value;
        }

        private readonly World world;
        private readonly GeneratorId generator;
        private GeneratorContext context;
        private bool active;

        internal GeneratorCall(World world, GeneratorId generator)
        {
            this.world = world;
            this.generator = generator;
        }

        internal void Enter(IntPtr nativeContext)
        {
            context.Generator = generator;
            var dt = new FloatBits();
            dt.Bits = Marshal.ReadInt32(nativeContext, DtOffset);
            context.Dt = dt.Value;
            context.Bodies = Marshal.ReadIntPtr(nativeContext, BodiesOffset);
            context.BodyCount = (UIntPtr)(ulong)(long)Marshal.ReadIntPtr(nativeContext, BodyCountOffset);
            context.Particles = Marshal.ReadIntPtr(nativeContext, ParticlesOffset);
            context.ParticleCount = (UIntPtr)(ulong)(long)Marshal.ReadIntPtr(nativeContext, ParticleCountOffset);
            active = true;
        }

        internal void Leave()
        {
            active = false;
            context = default(GeneratorContext);
        }

        private GeneratorContext Context
        {
            get
            {
                if (!active)
                {
                    throw new InvalidOperationException("a GeneratorCall is valid only inside its callback");
                }
                return context;
            }
        }

        /// <summary>The world being stepped.</summary>
        public World World { get { return world; } }

        /// <summary>The generator being run.</summary>
        public Generator Generator { get { return new Generator(world, generator); } }

        /// <summary>The step's duration (s).</summary>
        public float Dt { get { return Context.Dt; } }

        /// <summary>Number of live bodies attached to the generator.</summary>
        public int BodyCount { get { return (int)(ulong)Context.BodyCount; } }

        /// <summary>Number of live particles attached to the generator.</summary>
        public int ParticleCount { get { return (int)(ulong)Context.ParticleCount; } }

        /// <summary>The i-th attached body's id, in attachment order.</summary>
        public BodyId GetBodyId(int i)
        {
            var c = Context;
            if (i < 0 || (ulong)i >= (ulong)c.BodyCount)
            {
                throw new ArgumentOutOfRangeException("i");
            }
            IntPtr p = IntPtr.Add(c.Bodies, i * 8);
            return new BodyId((uint)Marshal.ReadInt32(p, 0), (uint)Marshal.ReadInt32(p, 4));
        }

        /// <summary>The i-th attached body.</summary>
        public Body GetBody(int i) { return new Body(world, GetBodyId(i)); }

        /// <summary>The i-th attached particle's id, in attachment order.</summary>
        public ParticleId GetParticleId(int i)
        {
            var c = Context;
            if (i < 0 || (ulong)i >= (ulong)c.ParticleCount)
            {
                throw new ArgumentOutOfRangeException("i");
            }
            IntPtr p = IntPtr.Add(c.Particles, i * 8);
            return new ParticleId((uint)Marshal.ReadInt32(p, 0), (uint)Marshal.ReadInt32(p, 4));
        }

        /// <summary>The i-th attached particle.</summary>
        public Particle GetParticle(int i) { return new Particle(world, GetParticleId(i)); }
    }

    /// <summary>
    /// HearthContactSink: where a user contact generator adds its contacts. Valid only inside
    /// the callback; afterwards every call fails with Result.NullPointer.
    /// </summary>
    public sealed class ContactSink
    {
        internal IntPtr Pointer;

        internal ContactSink() { }

        /// <summary>hearth_contact_sink_add; throws HearthException (BufferTooSmall when the capacity is used up).</summary>
        public void Add(GeneratedContact contact)
        {
            HearthException.Check(TryAdd(contact), "hearth_contact_sink_add");
        }

        /// <summary>hearth_contact_sink_add without throwing.</summary>
        public Result TryAdd(GeneratedContact contact)
        {
            return Native.hearth_contact_sink_add(Pointer, ref contact);
        }

        /// <summary>Contacts added so far in this call.</summary>
        public uint Count
        {
            get
            {
                uint count, capacity;
                HearthException.Check(Native.hearth_contact_sink_get_count(Pointer, out count, out capacity), "hearth_contact_sink_get_count");
                return count;
            }
        }

        /// <summary>Most contacts this call may add.</summary>
        public uint Capacity
        {
            get
            {
                uint count, capacity;
                HearthException.Check(Native.hearth_contact_sink_get_count(Pointer, out count, out capacity), "hearth_contact_sink_get_count");
                return capacity;
            }
        }
    }

    /// <summary>
    /// A Hearth world: owns every body, shape, joint, generator, particle and soft body in it.
    /// Dispose it when done (the SafeHandle's finalizer destroys a forgotten one).
    /// </summary>
    public sealed class World : IDisposable
    {
        // A registered user generator: its handler, and the GCHandle native code passes back to
        // the trampoline as user_data (freed with Release).
        private sealed class Registration
        {
            public World World;
            public UserForceHandler ForceHandler;
            public UserContactHandler ContactHandler;
            public GeneratorCall Call;
            public ContactSink Sink;
            public GCHandle Handle;

            public void Release()
            {
                if (Handle.IsAllocated)
                {
                    Handle.Free();
                    Interlocked.Decrement(ref liveCallbackHandles);
                }
            }
        }

        // The trampolines native code calls for every user generator, and the delegates whose
        // function pointers it gets: static, so they live as long as the program.
        private static readonly ForceCallback ForceTrampolineDelegate = ForceTrampoline;
        private static readonly ContactCallback ContactTrampolineDelegate = ContactTrampoline;
        private static readonly IntPtr ForceTrampolinePointer = Marshal.GetFunctionPointerForDelegate(ForceTrampolineDelegate);
        private static readonly IntPtr ContactTrampolinePointer = Marshal.GetFunctionPointerForDelegate(ContactTrampolineDelegate);
        private static int liveCallbackHandles;

        /// <summary>The function pointer every user force generator is created with (one for all).</summary>
        public static IntPtr ForceCallbackPointer { get { return ForceTrampolinePointer; } }

        /// <summary>The function pointer every user contact generator is created with (one for all).</summary>
        public static IntPtr ContactCallbackPointer { get { return ContactTrampolinePointer; } }

        /// <summary>GCHandles of user generators not yet released, over all worlds.</summary>
        public static int LiveCallbackHandles { get { return Volatile.Read(ref liveCallbackHandles); } }

        // The registration a native call's user_data names, or null (never throws).
        private static Registration FromUserData(IntPtr userData)
        {
            if (userData == IntPtr.Zero)
            {
                return null;
            }
            try
            {
                GCHandle handle = GCHandle.FromIntPtr(userData);
                return handle.IsAllocated ? handle.Target as Registration : null;
            }
            catch (InvalidOperationException)
            {
                return null; // not a live handle: nothing to call (an exception must not reach native code)
            }
        }

        [MonoPInvokeCallback(typeof(ForceCallback))]
        private static void ForceTrampoline(IntPtr userData, IntPtr world, IntPtr context)
        {
            Registration registration = FromUserData(userData);
            if (registration == null)
            {
                return;
            }
            try
            {
                registration.Call.Enter(context);
                registration.ForceHandler(registration.Call);
            }
            catch (Exception e)
            {
                registration.World.StoreCallbackException(e);
            }
            finally
            {
                registration.Call.Leave();
            }
        }

        [MonoPInvokeCallback(typeof(ContactCallback))]
        private static void ContactTrampoline(IntPtr userData, IntPtr world, IntPtr context, IntPtr sink)
        {
            Registration registration = FromUserData(userData);
            if (registration == null)
            {
                return;
            }
            try
            {
                registration.Call.Enter(context);
                registration.Sink.Pointer = sink;
                registration.ContactHandler(registration.Call, registration.Sink);
            }
            catch (Exception e)
            {
                registration.World.StoreCallbackException(e);
            }
            finally
            {
                registration.Sink.Pointer = IntPtr.Zero;
                registration.Call.Leave();
            }
        }

        // Frees every registration's GCHandle and forgets them.
        private void ReleaseRegistrations()
        {
            foreach (Registration registration in registrations.Values)
            {
                registration.Release();
            }
            registrations.Clear();
            ReleaseRecordSink();
            if (hooksHandle.IsAllocated)
            {
                hooksHandle.Free();
            }
            pairFilter = null;
            preSolve = null;
        }

        private readonly WorldHandle handle;
        private readonly Dictionary<GeneratorId, Registration> registrations = new Dictionary<GeneratorId, Registration>();
        private ExceptionDispatchInfo callbackException;
        private GCHandle recordSink; // the recording's RecordSink, allocated while recording to a callback
        private int stepDepth;
        private bool disposed; // set at once, while the handle may stay open until a running step returns

        /// <summary>A world with the library's default settings.</summary>
        public World() : this(WorldDef.Default()) { }

        /// <summary>hearth_world_create; start the def from WorldDef.Default().</summary>
        public World(WorldDef def)
        {
            Native.EnsureCompatibleLibrary();
            WorldHandle created;
            Result result = Native.hearth_world_create(ref def, out created);
            if (result != Result.Ok)
            {
                string detail = Native.LastErrorMessage();
                created.Dispose();
                throw new HearthException(result, "hearth_world_create", detail);
            }
            handle = created;
        }

        /// <summary>The native handle, for calls through Native; throws ObjectDisposedException after Dispose.</summary>
        public WorldHandle Handle
        {
            get
            {
                if (disposed || handle.IsClosed)
                {
                    throw new ObjectDisposedException("Hearth.World");
                }
                return handle;
            }
        }

        /// <summary>True after Dispose.</summary>
        public bool IsDisposed { get { return disposed || handle.IsClosed; } }

        /// <summary>Whether this world keeps a recording's write callback alive (RecordTo until StopRecording).</summary>
        public bool KeepsRecordCallback { get { return recordSink.IsAllocated; } }

        /// <summary>Number of user generators whose callbacks this world keeps alive.</summary>
        public int RegisteredCallbackCount { get { return registrations.Count; } }

        /// <summary>
        /// Destroys the native world and releases the callbacks. Safe to call twice. From
        /// inside a callback the native world is destroyed when the running step returns.
        /// </summary>
        public void Dispose()
        {
            disposed = true;
            handle.Dispose();
            if (stepDepth == 0)
            {
                ReleaseRegistrations();
            }
        }

        private static void Check(Result result, string function)
        {
            HearthException.Check(result, function);
        }

        // ---- the world -------------------------------------------------------------------

        /// <summary>
        /// hearth_world_step. User generator callbacks run inside; the first exception one of
        /// them threw is rethrown here (with its original stack trace) after the step.
        /// </summary>
        public void Step(float dt)
        {
            WorldHandle h = Handle;
            if (stepDepth == 0)
            {
                callbackException = null;
            }
            Result result;
            stepDepth++;
            try
            {
                result = Native.hearth_world_step(h, dt);
            }
            finally
            {
                stepDepth--;
                if (stepDepth == 0 && disposed)
                {
                    ReleaseRegistrations(); // Dispose was called from a callback
                }
            }
            if (stepDepth == 0 && callbackException != null)
            {
                ExceptionDispatchInfo pending = callbackException;
                callbackException = null;
                pending.Throw();
            }
            Check(result, "hearth_world_step");
        }

        // ---- debug draw: static trampolines (IL2CPP needs them), user_data a GCHandle of the session.
        private sealed class DrawSession
        {
            public IDebugDrawer Drawer;
            public ExceptionDispatchInfo Failure;
        }

        private static readonly DrawSegment SegmentDelegate = SegmentTrampoline;
        private static readonly DrawPolygon PolygonDelegate = PolygonTrampoline;
        private static readonly DrawSphere SphereDelegate = SphereTrampoline;
        private static readonly DrawCapsule CapsuleDelegate = CapsuleTrampoline;
        private static readonly DrawTransform TransformDelegate = TransformTrampoline;
        private static readonly DrawPoint PointDelegate = PointTrampoline;
        private static readonly IntPtr SegmentPointer = Marshal.GetFunctionPointerForDelegate(SegmentDelegate);
        private static readonly IntPtr PolygonPointer = Marshal.GetFunctionPointerForDelegate(PolygonDelegate);
        private static readonly IntPtr SpherePointer = Marshal.GetFunctionPointerForDelegate(SphereDelegate);
        private static readonly IntPtr CapsulePointer = Marshal.GetFunctionPointerForDelegate(CapsuleDelegate);
        private static readonly IntPtr TransformPointer = Marshal.GetFunctionPointerForDelegate(TransformDelegate);
        private static readonly IntPtr PointPointer = Marshal.GetFunctionPointerForDelegate(PointDelegate);

        private static DrawSession Session(IntPtr userData)
        {
            try
            {
                DrawSession s = GCHandle.FromIntPtr(userData).Target as DrawSession;
                return s != null && s.Failure == null ? s : null;
            }
            catch (InvalidOperationException)
            {
                return null;
            }
        }

        private static Vec3 V(IntPtr p) { return (Vec3)Marshal.PtrToStructure(p, typeof(Vec3)); }

        // Runs one drawer call; an exception is kept for Draw to rethrow and stops the rest.
        private static void Guard(IntPtr userData, Action<IDebugDrawer> call)
        {
            DrawSession s = Session(userData);
            if (s == null)
            {
                return;
            }
            try
            {
                call(s.Drawer);
            }
            catch (Exception e)
            {
                s.Failure = ExceptionDispatchInfo.Capture(e);
            }
        }

        [MonoPInvokeCallback(typeof(DrawSegment))]
        private static void SegmentTrampoline(IntPtr u, IntPtr a, IntPtr b, uint color)
        {
            Guard(u, d => d.Segment(V(a), V(b), color));
        }

        [MonoPInvokeCallback(typeof(DrawPolygon))]
        private static void PolygonTrampoline(IntPtr u, IntPtr vertices, uint count, uint color)
        {
            Guard(u, d =>
            {
                var v = new Vec3[count];
                int size = Marshal.SizeOf(typeof(Vec3));
                for (int i = 0; i < v.Length; i++) v[i] = V(IntPtr.Add(vertices, i * size));
                d.Polygon(v, color);
            });
        }

        [MonoPInvokeCallback(typeof(DrawSphere))]
        private static void SphereTrampoline(IntPtr u, IntPtr center, float radius, uint color)
        {
            Guard(u, d => d.Sphere(V(center), radius, color));
        }

        [MonoPInvokeCallback(typeof(DrawCapsule))]
        private static void CapsuleTrampoline(IntPtr u, IntPtr a, IntPtr b, float radius, uint color)
        {
            Guard(u, d => d.Capsule(V(a), V(b), radius, color));
        }

        [MonoPInvokeCallback(typeof(DrawTransform))]
        private static void TransformTrampoline(IntPtr u, IntPtr transform)
        {
            Guard(u, d => d.Transform((Transform)Marshal.PtrToStructure(transform, typeof(Transform))));
        }

        [MonoPInvokeCallback(typeof(DrawPoint))]
        private static void PointTrampoline(IntPtr u, IntPtr point, float size, uint color)
        {
            Guard(u, d => d.Point(V(point), size, color));
        }

        /// <summary>hearth_world_draw: describes the world to <paramref name="drawer"/> as the flags ask
        /// (colours 0xRRGGBBAA, listed at HearthDebugDraw in include/hearth.h). An exception the
        /// drawer throws stops the drawing and is rethrown here.</summary>
        public void Draw(IDebugDrawer drawer, bool shapes = true, bool aabbs = false, bool contacts = false,
                         bool joints = false, bool centersOfMass = false)
        {
            if (drawer == null) throw new ArgumentNullException("drawer");
            var session = new DrawSession { Drawer = drawer };
            GCHandle handle = GCHandle.Alloc(session);
            try
            {
                DebugDraw d = DebugDraw.Default();
                d.DrawSegment = SegmentPointer;
                d.DrawPolygon = PolygonPointer;
                d.DrawSphere = SpherePointer;
                d.DrawCapsule = CapsulePointer;
                d.DrawTransform = TransformPointer;
                d.DrawPoint = PointPointer;
                d.UserData = GCHandle.ToIntPtr(handle);
                d.DrawShapes = (byte)(shapes ? 1 : 0);
                d.DrawAabbs = (byte)(aabbs ? 1 : 0);
                d.DrawContacts = (byte)(contacts ? 1 : 0);
                d.DrawJoints = (byte)(joints ? 1 : 0);
                d.DrawCentersOfMass = (byte)(centersOfMass ? 1 : 0);
                Check(Native.hearth_world_draw(Handle, ref d), "hearth_world_draw");
            }
            finally
            {
                handle.Free();
            }
            if (session.Failure != null) session.Failure.Throw();
        }

        /// <summary>hearth_world_draw with a DebugDraw the caller fills (its own function pointers and flags).</summary>
        public void Draw(DebugDraw draw)
        {
            Check(Native.hearth_world_draw(Handle, ref draw), "hearth_world_draw");
        }

        /// <summary>hearth_world_get_gravity / hearth_world_set_gravity (m/s²; setting wakes every body).</summary>
        public Vec3 Gravity
        {
            get
            {
                Vec3 value;
                Check(Native.hearth_world_get_gravity(Handle, out value), "hearth_world_get_gravity");
                return value;
            }
            set { Check(Native.hearth_world_set_gravity(Handle, value), "hearth_world_set_gravity"); }
        }

        /// <summary>hearth_world_get_hash: a 64-bit hash of the world's motion state, equal for equal runs at any worker count.</summary>
        public ulong StateHash
        {
            get
            {
                ulong value;
                Check(Native.hearth_world_get_hash(Handle, out value), "hearth_world_get_hash");
                return value;
            }
        }

        /// <summary>hearth_world_rebuild_broadphase: rebuilds the broad-phase tree (after loading a
        /// level, so that queries and pair searches test fewer boxes); ids and query results are unchanged.</summary>
        public void RebuildBroadphase()
        {
            Check(Native.hearth_world_rebuild_broadphase(Handle), "hearth_world_rebuild_broadphase");
        }

        /// <summary>hearth_world_get_counters.</summary>
        public WorldCounters Counters
        {
            get
            {
                WorldCounters value;
                Check(Native.hearth_world_get_counters(Handle, out value), "hearth_world_get_counters");
                return value;
            }
        }

        /// <summary>
        /// hearth_world_get_transforms: the transforms of bodies[0..count) into results, in one
        /// call. On a bad id nothing is written (HearthException, InvalidId).
        /// </summary>
        public void GetTransforms(BodyId[] bodies, Transform[] results, int count)
        {
            CheckRange(bodies, count, "bodies");
            CheckRange(results, count, "results");
            Check(Native.hearth_world_get_transforms(Handle, bodies, (UIntPtr)(uint)count, results), "hearth_world_get_transforms");
        }

        /// <summary>GetTransforms of every id in <paramref name="bodies"/>.</summary>
        public void GetTransforms(BodyId[] bodies, Transform[] results)
        {
            if (bodies == null)
            {
                throw new ArgumentNullException("bodies");
            }
            GetTransforms(bodies, results, bodies.Length);
        }

        private static void CheckRange<T>(T[] array, int count, string name)
        {
            if (array == null)
            {
                throw new ArgumentNullException(name);
            }
            if (count < 0 || count > array.Length)
            {
                throw new ArgumentOutOfRangeException(name, "count " + count + " does not fit " + name + " of length " + array.Length);
            }
        }

        // ---- bodies and shapes -------------------------------------------------------------

        /// <summary>hearth_body_create; start the def from BodyDef.Default().</summary>
        public Body CreateBody(BodyDef def)
        {
            BodyId id;
            Check(Native.hearth_body_create(Handle, ref def, out id), "hearth_body_create");
            return new Body(this, id);
        }

        /// <summary>A body of the given type at a position, other settings default.</summary>
        public Body CreateBody(BodyType type, Vec3 position)
        {
            BodyDef def = BodyDef.Default();
            def.Type = type;
            def.Transform.Position = position;
            return CreateBody(def);
        }

        /// <summary>The wrapper of an existing id (no check; a stale id fails on use).</summary>
        public Body GetBody(BodyId id) { return new Body(this, id); }

        /// <summary>The wrapper of an existing shape id.</summary>
        public Shape GetShape(ShapeId id) { return new Shape(this, id); }

        // ---- generators --------------------------------------------------------------------

        /// <summary>hearth_generator_create_gravity.</summary>
        public Generator CreateGravityGenerator(GravityGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_gravity(Handle, ref def, out id), "hearth_generator_create_gravity");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_drag.</summary>
        public Generator CreateDragGenerator(DragGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_drag(Handle, ref def, out id), "hearth_generator_create_drag");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_spring.</summary>
        public Generator CreateSpringGenerator(SpringGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_spring(Handle, ref def, out id), "hearth_generator_create_spring");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_bungee (a spring that only pulls).</summary>
        public Generator CreateBungeeGenerator(SpringGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_bungee(Handle, ref def, out id), "hearth_generator_create_bungee");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_stiff_spring.</summary>
        public Generator CreateStiffSpringGenerator(StiffSpringGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_stiff_spring(Handle, ref def, out id), "hearth_generator_create_stiff_spring");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_buoyancy.</summary>
        public Generator CreateBuoyancyGenerator(BuoyancyGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_buoyancy(Handle, ref def, out id), "hearth_generator_create_buoyancy");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_explosion.</summary>
        public Generator CreateExplosionGenerator(ExplosionGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_explosion(Handle, ref def, out id), "hearth_generator_create_explosion");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_rod.</summary>
        public Generator CreateRodGenerator(RodGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_rod(Handle, ref def, out id), "hearth_generator_create_rod");
            return new Generator(this, id);
        }

        /// <summary>hearth_generator_create_cable.</summary>
        public Generator CreateCableGenerator(CableGeneratorDef def)
        {
            GeneratorId id;
            Check(Native.hearth_generator_create_cable(Handle, ref def, out id), "hearth_generator_create_cable");
            return new Generator(this, id);
        }

        /// <summary>
        /// hearth_generator_create_user_force: <paramref name="handler"/> runs once per step
        /// (after the built-in force generators) and may apply forces to anything. The world
        /// keeps it alive until DestroyGenerator or Dispose.
        /// </summary>
        public Generator CreateUserForceGenerator(UserForceHandler handler)
        {
            if (handler == null)
            {
                throw new ArgumentNullException("handler");
            }
            WorldHandle world = Handle; // throws when disposed, before anything is allocated
            var registration = new Registration { World = this, ForceHandler = handler };
            UserForceGeneratorDef def = UserForceGeneratorDef.Default();
            def.Callback = ForceTrampolinePointer;
            def.UserData = Allocate(registration);
            GeneratorId id;
            Result result = Native.hearth_generator_create_user_force(world, ref def, out id);
            if (result != Result.Ok)
            {
                string detail = Native.LastErrorMessage();
                registration.Release();
                throw new HearthException(result, "hearth_generator_create_user_force", detail);
            }
            registration.Call = new GeneratorCall(this, id);
            registrations[id] = registration;
            return new Generator(this, id);
        }

        // A GCHandle of the registration, as the user_data native code passes back.
        private static IntPtr Allocate(Registration registration)
        {
            registration.Handle = GCHandle.Alloc(registration);
            Interlocked.Increment(ref liveCallbackHandles);
            return GCHandle.ToIntPtr(registration.Handle);
        }

        /// <summary>CreateUserContactGenerator with the default capacity.</summary>
        public Generator CreateUserContactGenerator(UserContactHandler handler)
        {
            return CreateUserContactGenerator(handler, UserContactGeneratorDef.Default().Capacity);
        }

        /// <summary>
        /// hearth_generator_create_user_contact: <paramref name="handler"/> runs once per step
        /// after the narrow phase and adds up to <paramref name="capacity"/> contacts to its sink.
        /// The world keeps it alive until DestroyGenerator or Dispose.
        /// </summary>
        public Generator CreateUserContactGenerator(UserContactHandler handler, uint capacity)
        {
            if (handler == null)
            {
                throw new ArgumentNullException("handler");
            }
            WorldHandle world = Handle; // throws when disposed, before anything is allocated
            var registration = new Registration { World = this, ContactHandler = handler, Sink = new ContactSink() };
            UserContactGeneratorDef def = UserContactGeneratorDef.Default();
            def.Callback = ContactTrampolinePointer;
            def.UserData = Allocate(registration);
            def.Capacity = capacity;
            GeneratorId id;
            Result result = Native.hearth_generator_create_user_contact(world, ref def, out id);
            if (result != Result.Ok)
            {
                string detail = Native.LastErrorMessage();
                registration.Release();
                throw new HearthException(result, "hearth_generator_create_user_contact", detail);
            }
            registration.Call = new GeneratorCall(this, id);
            registrations[id] = registration;
            return new Generator(this, id);
        }

        // ---- snapshots (rollback, replays; docs/snapshot-format.md) ------------------------

        /// <summary>hearth_world_snapshot_size: bytes SaveSnapshot returns now.</summary>
        public int SnapshotSize
        {
            get
            {
                UIntPtr size;
                Check(Native.hearth_world_snapshot_size(Handle, out size), "hearth_world_snapshot_size");
                return checked((int)(ulong)size);
            }
        }

        /// <summary>hearth_world_snapshot_save: everything that affects the world's future
        /// (user generator callbacks and a running recording excepted).</summary>
        public byte[] SaveSnapshot()
        {
            var buffer = new byte[SnapshotSize];
            UIntPtr written;
            Check(Native.hearth_world_snapshot_save(Handle, buffer, (UIntPtr)(uint)buffer.Length, out written), "hearth_world_snapshot_save");
            if ((int)(ulong)written != buffer.Length)
            {
                Array.Resize(ref buffer, (int)(ulong)written);
            }
            return buffer;
        }

        /// <summary>
        /// hearth_world_snapshot_restore: a snapshot of this world or another. On error
        /// (InvalidArgument: truncated, corrupted, another version) nothing changes. Into the
        /// world it came from, handlers keep running; into another, set them again with
        /// SetUserForceCallback / SetUserContactCallback (GetUserGeneratorsMissingCallback).
        /// </summary>
        public void RestoreSnapshot(byte[] snapshot)
        {
            if (snapshot == null)
            {
                throw new ArgumentNullException("snapshot");
            }
            Check(Native.hearth_world_snapshot_restore(Handle, snapshot, (UIntPtr)(uint)snapshot.Length), "hearth_world_snapshot_restore");
        }

        /// <summary>hearth_world_get_user_generators_missing_callback: user generators a
        /// restore brought in without a callback (skipped by Step until set).</summary>
        public GeneratorId[] GetUserGeneratorsMissingCallback()
        {
            UIntPtr count;
            Check(Native.hearth_world_get_user_generators_missing_callback(Handle, null, UIntPtr.Zero, out count), "hearth_world_get_user_generators_missing_callback");
            var ids = new GeneratorId[(int)(ulong)count];
            if (ids.Length > 0)
            {
                Check(Native.hearth_world_get_user_generators_missing_callback(Handle, ids, (UIntPtr)(uint)ids.Length, out count), "hearth_world_get_user_generators_missing_callback");
            }
            return ids;
        }

        /// <summary>hearth_generator_set_user_force_callback: <paramref name="handler"/> for a
        /// user force generator (after a restore into another world, or to replace it).</summary>
        public void SetUserForceCallback(GeneratorId generator, UserForceHandler handler)
        {
            if (handler == null)
            {
                throw new ArgumentNullException("handler");
            }
            WorldHandle world = Handle;
            var registration = new Registration { World = this, ForceHandler = handler };
            UserForceGeneratorDef def = UserForceGeneratorDef.Default();
            def.Callback = ForceTrampolinePointer;
            def.UserData = Allocate(registration);
            Replace(generator, registration, Native.hearth_generator_set_user_force_callback(world, generator, ref def), "hearth_generator_set_user_force_callback");
        }

        /// <summary>hearth_generator_set_user_contact_callback: <paramref name="handler"/> for a
        /// user contact generator, adding up to <paramref name="capacity"/> contacts a step.</summary>
        public void SetUserContactCallback(GeneratorId generator, UserContactHandler handler, uint capacity)
        {
            if (handler == null)
            {
                throw new ArgumentNullException("handler");
            }
            WorldHandle world = Handle;
            var registration = new Registration { World = this, ContactHandler = handler, Sink = new ContactSink() };
            UserContactGeneratorDef def = UserContactGeneratorDef.Default();
            def.Callback = ContactTrampolinePointer;
            def.UserData = Allocate(registration);
            def.Capacity = capacity;
            Replace(generator, registration, Native.hearth_generator_set_user_contact_callback(world, generator, ref def), "hearth_generator_set_user_contact_callback");
        }

        private void Replace(GeneratorId generator, Registration registration, Result result, string function)
        {
            if (result != Result.Ok)
            {
                string detail = Native.LastErrorMessage();
                registration.Release();
                throw new HearthException(result, function, detail);
            }
            registration.Call = new GeneratorCall(this, generator);
            Registration old;
            if (registrations.TryGetValue(generator, out old))
            {
                old.Release();
            }
            registrations[generator] = registration;
        }

        // Called inside a native callback: must not throw.
        // ---- recording (for the browser viewer, viewer/index.html) -------------------------

        /// <summary>
        /// hearth_world_record_start_file: records the world into the file at
        /// <paramref name="path"/> — the current state now, then every step. With
        /// <paramref name="contacts"/> the contact manifolds too. Ends with StopRecording or Dispose.
        /// </summary>
        public void RecordToFile(string path, bool contacts = false)
        {
            if (path == null)
            {
                throw new ArgumentNullException("path");
            }
            RecordDef def = RecordDef.Default();
            def.RecordContacts = new Flag((byte)(contacts ? 1 : 0));
            byte[] utf8 = Encoding.UTF8.GetBytes(path + "\0");
            Check(Native.hearth_world_record_start_file(Handle, utf8, ref def), "hearth_world_record_start_file");
        }

        /// <summary>
        /// hearth_world_record_start_callback: <paramref name="write"/> receives the recording's
        /// bytes now and after every step. An exception from it stops the recording: it is
        /// rethrown by the call or step it happened in, and the next Step (or StopRecording)
        /// throws with Result.Io.
        /// </summary>
        public void RecordTo(Action<byte[]> write, bool contacts = false)
        {
            if (write == null)
            {
                throw new ArgumentNullException("write");
            }
            var sink = new RecordSink(this, write);
            GCHandle sinkHandle = GCHandle.Alloc(sink);
            RecordDef def = RecordDef.Default();
            def.RecordContacts = new Flag((byte)(contacts ? 1 : 0));
            def.Write = RecordTrampolinePointer;
            def.UserData = GCHandle.ToIntPtr(sinkHandle);
            callbackException = null;
            Result result = Native.hearth_world_record_start_callback(Handle, ref def);
            if (result == Result.Ok)
            {
                ReleaseRecordSink();
                recordSink = sinkHandle;
            }
            else
            {
                sinkHandle.Free();
            }
            if (callbackException != null)
            {
                ExceptionDispatchInfo pending = callbackException;
                callbackException = null;
                pending.Throw();
            }
            Check(result, "hearth_world_record_start_callback");
        }

        // What a recording's user_data names: the world (for exceptions) and the host's writer.
        private sealed class RecordSink
        {
            public readonly World World;
            public readonly Action<byte[]> Write;

            public RecordSink(World world, Action<byte[]> write)
            {
                World = world;
                Write = write;
            }
        }

        private static readonly RecordWriteFn RecordTrampolineDelegate = RecordTrampoline;
        private static readonly IntPtr RecordTrampolinePointer = Marshal.GetFunctionPointerForDelegate(RecordTrampolineDelegate);

        // The one write function every callback recording is started with; user_data is a
        // GCHandle of the RecordSink. An exception never reaches native code: it is stored and
        // rethrown, and the non-zero result stops the recording.
        [MonoPInvokeCallback(typeof(RecordWriteFn))]
        private static int RecordTrampoline(IntPtr userData, IntPtr bytes, UIntPtr len)
        {
            RecordSink sink = null;
            try
            {
                sink = GCHandle.FromIntPtr(userData).Target as RecordSink;
            }
            catch (InvalidOperationException)
            {
            }
            if (sink == null)
            {
                return 1;
            }
            try
            {
                var data = new byte[(int)len.ToUInt64()];
                Marshal.Copy(bytes, data, 0, data.Length);
                sink.Write(data);
                return 0;
            }
            catch (Exception e)
            {
                sink.World.StoreCallbackException(e);
                return 1;
            }
        }

        private void ReleaseRecordSink()
        {
            if (recordSink.IsAllocated)
            {
                recordSink.Free();
            }
        }

        /// <summary>hearth_world_record_stop: ends the recording (Result.Io if a write had failed).</summary>
        public void StopRecording()
        {
            Result result = Native.hearth_world_record_stop(Handle);
            if (result != Result.WorldLocked)
            {
                ReleaseRecordSink();
            }
            Check(result, "hearth_world_record_stop");
        }

        private void StoreCallbackException(Exception e)
        {
            if (callbackException == null)
            {
                callbackException = ExceptionDispatchInfo.Capture(e);
            }
        }

        /// <summary>hearth_generator_destroy; releases a user generator's callback.</summary>
        public void DestroyGenerator(GeneratorId generator)
        {
            Check(Native.hearth_generator_destroy(Handle, generator), "hearth_generator_destroy");
            Registration registration;
            if (registrations.TryGetValue(generator, out registration))
            {
                registration.Release();
                registrations.Remove(generator);
            }
        }

        /// <summary>The wrapper of an existing generator id.</summary>
        public Generator GetGenerator(GeneratorId id) { return new Generator(this, id); }

        // ---- joints ------------------------------------------------------------------------

        /// <summary>hearth_joint_create_ball.</summary>
        public Joint CreateBallJoint(BallJointDef def)
        {
            JointId id;
            Check(Native.hearth_joint_create_ball(Handle, ref def, out id), "hearth_joint_create_ball");
            return new Joint(this, id);
        }

        /// <summary>hearth_joint_create_hinge.</summary>
        public Joint CreateHingeJoint(HingeJointDef def)
        {
            JointId id;
            Check(Native.hearth_joint_create_hinge(Handle, ref def, out id), "hearth_joint_create_hinge");
            return new Joint(this, id);
        }

        /// <summary>hearth_joint_create_fixed.</summary>
        public Joint CreateFixedJoint(FixedJointDef def)
        {
            JointId id;
            Check(Native.hearth_joint_create_fixed(Handle, ref def, out id), "hearth_joint_create_fixed");
            return new Joint(this, id);
        }

        /// <summary>hearth_joint_create_distance.</summary>
        public Joint CreateDistanceJoint(DistanceJointDef def)
        {
            JointId id;
            Check(Native.hearth_joint_create_distance(Handle, ref def, out id), "hearth_joint_create_distance");
            return new Joint(this, id);
        }

        /// <summary>hearth_joint_create_slider.</summary>
        public Joint CreateSliderJoint(SliderJointDef def)
        {
            JointId id;
            Check(Native.hearth_joint_create_slider(Handle, ref def, out id), "hearth_joint_create_slider");
            return new Joint(this, id);
        }

        /// <summary>The wrapper of an existing joint id.</summary>
        public Joint GetJoint(JointId id) { return new Joint(this, id); }

        // ---- events and step callbacks -----------------------------------------------

        private static T[] CopyArray<T>(IntPtr pointer, UIntPtr count) where T : struct
        {
            int n = (int)(ulong)count;
            var result = new T[n];
            int size = Marshal.SizeOf(typeof(T));
            for (int i = 0; i < n; i++)
            {
                result[i] = (T)Marshal.PtrToStructure(new IntPtr(pointer.ToInt64() + (long)i * size), typeof(T));
            }
            return result;
        }

        /// <summary>hearth_world_get_contact_events: the last step's begin, end and hit events, copied.</summary>
        public void GetContactEvents(out ContactEvent[] begin, out ContactEvent[] end, out ContactHitEvent[] hit)
        {
            ContactEvents ev;
            Check(Native.hearth_world_get_contact_events(Handle, out ev), "hearth_world_get_contact_events");
            begin = CopyArray<ContactEvent>(ev.Begin, ev.BeginCount);
            end = CopyArray<ContactEvent>(ev.End, ev.EndCount);
            hit = CopyArray<ContactHitEvent>(ev.Hit, ev.HitCount);
        }

        /// <summary>hearth_world_get_sensor_events: the last step's sensor begin and end events, copied.</summary>
        public void GetSensorEvents(out SensorEvent[] begin, out SensorEvent[] end)
        {
            SensorEvents ev;
            Check(Native.hearth_world_get_sensor_events(Handle, out ev), "hearth_world_get_sensor_events");
            begin = CopyArray<SensorEvent>(ev.Begin, ev.BeginCount);
            end = CopyArray<SensorEvent>(ev.End, ev.EndCount);
        }

        /// <summary>hearth_world_get_body_events: the last step's move events, copied.</summary>
        public BodyMoveEvent[] GetBodyEvents()
        {
            BodyEvents ev;
            Check(Native.hearth_world_get_body_events(Handle, out ev), "hearth_world_get_body_events");
            return CopyArray<BodyMoveEvent>(ev.Moves, ev.MoveCount);
        }

        /// <summary>A pair filter: false keeps the two shapes from touching until the pair is proposed again.</summary>
        public delegate bool PairFilterHandler(World world, ShapeId a, ShapeId b);

        /// <summary>A pre-solve handler: false disables the contact for this step. <paramref name="points"/> is a copy.</summary>
        public delegate bool PreSolveHandler(World world, PreSolveContact contact, ManifoldPoint[] points);

        private PairFilterHandler pairFilter;
        private PreSolveHandler preSolve;
        private GCHandle hooksHandle; // this world, as the user_data of both callbacks

        private static readonly PairFilterCallback PairFilterTrampolineDelegate = PairFilterTrampoline;
        private static readonly PreSolveCallback PreSolveTrampolineDelegate = PreSolveTrampoline;
        private static readonly IntPtr PairFilterTrampolinePointer = Marshal.GetFunctionPointerForDelegate(PairFilterTrampolineDelegate);
        private static readonly IntPtr PreSolveTrampolinePointer = Marshal.GetFunctionPointerForDelegate(PreSolveTrampolineDelegate);

        private IntPtr HooksUserData()
        {
            if (!hooksHandle.IsAllocated)
            {
                hooksHandle = GCHandle.Alloc(this, GCHandleType.Weak);
            }
            return GCHandle.ToIntPtr(hooksHandle);
        }

        private static World WorldFromUserData(IntPtr userData)
        {
            try
            {
                GCHandle handle = GCHandle.FromIntPtr(userData);
                return handle.IsAllocated ? handle.Target as World : null;
            }
            catch (InvalidOperationException)
            {
                return null;
            }
        }

        /// <summary>hearth_world_set_pair_filter_callback with a managed handler (null clears it). An exception keeps the pair and is rethrown by Step.</summary>
        public void SetPairFilter(PairFilterHandler handler)
        {
            WorldHandle world = Handle;
            Check(Native.hearth_world_set_pair_filter_callback(world, handler == null ? IntPtr.Zero : PairFilterTrampolinePointer, handler == null ? IntPtr.Zero : HooksUserData()), "hearth_world_set_pair_filter_callback");
            pairFilter = handler;
        }

        /// <summary>hearth_world_set_pre_solve_callback with a managed handler (null clears it). An exception keeps the contact and is rethrown by Step.</summary>
        public void SetPreSolve(PreSolveHandler handler)
        {
            WorldHandle world = Handle;
            Check(Native.hearth_world_set_pre_solve_callback(world, handler == null ? IntPtr.Zero : PreSolveTrampolinePointer, handler == null ? IntPtr.Zero : HooksUserData()), "hearth_world_set_pre_solve_callback");
            preSolve = handler;
        }

        [MonoPInvokeCallback(typeof(PairFilterCallback))]
        private static byte PairFilterTrampoline(IntPtr userData, IntPtr world, ShapeId a, ShapeId b)
        {
            World w = WorldFromUserData(userData);
            if (w == null || w.pairFilter == null)
            {
                return 1;
            }
            try
            {
                return w.pairFilter(w, a, b) ? (byte)1 : (byte)0;
            }
            catch (Exception e)
            {
                w.StoreCallbackException(e);
                return 1;
            }
        }

        [MonoPInvokeCallback(typeof(PreSolveCallback))]
        private static byte PreSolveTrampoline(IntPtr userData, IntPtr world, IntPtr contact)
        {
            World w = WorldFromUserData(userData);
            if (w == null || w.preSolve == null)
            {
                return 1;
            }
            try
            {
                var c = (PreSolveContact)Marshal.PtrToStructure(contact, typeof(PreSolveContact));
                ManifoldPoint[] points = CopyArray<ManifoldPoint>(c.Points, (UIntPtr)c.PointCount);
                return w.preSolve(w, c, points) ? (byte)1 : (byte)0;
            }
            catch (Exception e)
            {
                w.StoreCallbackException(e);
                return 1;
            }
        }

        /// <summary>
        /// hearth_world_get_broken_joints into a caller-owned array: returns how many joints broke
        /// in the last step. A zero-length buffer only counts; a non-empty one that is too small
        /// throws (BufferTooSmall).
        /// </summary>
        public int GetBrokenJoints(JointId[] buffer)
        {
            UIntPtr count;
            int capacity = buffer == null ? 0 : buffer.Length;
            Check(Native.hearth_world_get_broken_joints(Handle, capacity == 0 ? null : buffer, (UIntPtr)(uint)capacity, out count), "hearth_world_get_broken_joints");
            return (int)(ulong)count;
        }

        /// <summary>The joints that broke in the last step, in a new array.</summary>
        public JointId[] GetBrokenJoints()
        {
            var result = new JointId[GetBrokenJoints(null)];
            if (result.Length > 0)
            {
                GetBrokenJoints(result);
            }
            return result;
        }

        // ---- queries (they change nothing) ------------------------------------------------

        /// <summary>hearth_world_cast_ray_closest: the nearest hit (IsHit false for a miss).</summary>
        public RayHit CastRayClosest(Vec3 origin, Vec3 translation, QueryFilter filter)
        {
            RayHit hit;
            Check(Native.hearth_world_cast_ray_closest(Handle, origin, translation, ref filter, out hit), "hearth_world_cast_ray_closest");
            return hit;
        }

        /// <summary>CastRayClosest with the default query filter.</summary>
        public RayHit CastRayClosest(Vec3 origin, Vec3 translation) { return CastRayClosest(origin, translation, QueryFilter.Default()); }

        /// <summary>
        /// hearth_world_cast_ray: calls <paramref name="onHit"/> for the hits; it returns -1 to
        /// ignore, 0 to stop, a fraction to clip, 1 to continue. An exception thrown by it stops
        /// the cast and is rethrown here.
        /// </summary>
        public void CastRay(Vec3 origin, Vec3 translation, QueryFilter filter, Func<RayHit, float> onHit)
        {
            var state = new RayCastState { OnHit = onHit };
            GCHandle handle = GCHandle.Alloc(state);
            Result r;
            try
            {
                r = Native.hearth_world_cast_ray(Handle, origin, translation, ref filter, RayTrampolineDelegate, GCHandle.ToIntPtr(handle));
            }
            finally
            {
                handle.Free();
            }
            if (state.Failure != null)
            {
                throw state.Failure;
            }
            Check(r, "hearth_world_cast_ray");
        }

        private sealed class RayCastState
        {
            public Func<RayHit, float> OnHit;
            public Exception Failure;
        }

        // A static trampoline (IL2CPP needs one); the handler arrives through user_data.
        private static readonly RayCallback RayTrampolineDelegate = RayTrampoline;

        [MonoPInvokeCallback(typeof(RayCallback))]
        private static float RayTrampoline(IntPtr userData, ref RayHit hit)
        {
            var state = (RayCastState)GCHandle.FromIntPtr(userData).Target;
            try
            {
                return state.OnHit(hit);
            }
            catch (Exception e)
            {
                state.Failure = e;
                return 0f;
            }
        }

        /// <summary>hearth_world_cast_rays into the caller-owned <paramref name="hits"/> (at least as long as <paramref name="rays"/>).</summary>
        public void CastRays(RayInput[] rays, RayHit[] hits, QueryFilter filter)
        {
            if (hits.Length < rays.Length)
            {
                throw new ArgumentException("hits is shorter than rays");
            }
            Check(Native.hearth_world_cast_rays(Handle, rays, (UIntPtr)(uint)rays.Length, ref filter, hits), "hearth_world_cast_rays");
        }

        /// <summary>hearth_world_cast_shape: the first hit of <paramref name="shape"/> moved from <paramref name="at"/> along <paramref name="translation"/>.</summary>
        public RayHit CastShape(QueryShape shape, Transform at, Vec3 translation, QueryFilter filter)
        {
            RayHit hit;
            Check(Native.hearth_world_cast_shape(Handle, ref shape, ref at, translation, ref filter, out hit), "hearth_world_cast_shape");
            return hit;
        }

        private delegate Result OverlapCall(ShapeId[] buffer, UIntPtr capacity, out UIntPtr count);

        private ShapeId[] Overlap(OverlapCall call, string name)
        {
            UIntPtr count;
            Check(call(null, UIntPtr.Zero, out count), name);
            var ids = new ShapeId[(int)(ulong)count];
            if (ids.Length > 0)
            {
                Check(call(ids, (UIntPtr)(uint)ids.Length, out count), name);
            }
            return ids;
        }

        /// <summary>hearth_world_overlap_shape: the shapes overlapping <paramref name="shape"/> at <paramref name="at"/>.</summary>
        public ShapeId[] OverlapShape(QueryShape shape, Transform at, QueryFilter filter)
        {
            return Overlap((ShapeId[] b, UIntPtr c, out UIntPtr n) => Native.hearth_world_overlap_shape(Handle, ref shape, ref at, ref filter, b, c, out n), "hearth_world_overlap_shape");
        }

        /// <summary>hearth_world_overlap_aabb: the shapes whose bounds overlap the box.</summary>
        public ShapeId[] OverlapAabb(Vec3 min, Vec3 max, QueryFilter filter)
        {
            return Overlap((ShapeId[] b, UIntPtr c, out UIntPtr n) => Native.hearth_world_overlap_aabb(Handle, min, max, ref filter, b, c, out n), "hearth_world_overlap_aabb");
        }

        /// <summary>hearth_world_overlap_point: the solid shapes containing the point.</summary>
        public ShapeId[] OverlapPoint(Vec3 point, QueryFilter filter)
        {
            return Overlap((ShapeId[] b, UIntPtr c, out UIntPtr n) => Native.hearth_world_overlap_point(Handle, point, ref filter, b, c, out n), "hearth_world_overlap_point");
        }

        // ---- particles ---------------------------------------------------------------------

        /// <summary>hearth_particle_create; start the def from ParticleDef.Default().</summary>
        public Particle CreateParticle(ParticleDef def)
        {
            ParticleId id;
            Check(Native.hearth_particle_create(Handle, ref def, out id), "hearth_particle_create");
            return new Particle(this, id);
        }

        /// <summary>The wrapper of an existing particle id.</summary>
        public Particle GetParticle(ParticleId id) { return new Particle(this, id); }

        /// <summary>hearth_particle_emit_burst: the new ids go to <paramref name="outIds"/> (null: not kept); returns how many were emitted.</summary>
        public int EmitBurst(BurstDef def, ParticleId[] outIds)
        {
            UIntPtr count;
            int capacity = outIds == null ? 0 : outIds.Length;
            Check(Native.hearth_particle_emit_burst(Handle, ref def, outIds, (UIntPtr)(uint)capacity, out count), "hearth_particle_emit_burst");
            return (int)(ulong)count;
        }

        /// <summary>hearth_particle_emit_burst, returning the new ids.</summary>
        public ParticleId[] EmitBurst(BurstDef def)
        {
            var ids = new ParticleId[def.Count];
            int emitted = EmitBurst(def, ids);
            if (emitted != ids.Length)
            {
                Array.Resize(ref ids, emitted);
            }
            return ids;
        }

        /// <summary>hearth_world_get_particle_count.</summary>
        public int ParticleCount
        {
            get
            {
                UIntPtr count;
                Check(Native.hearth_world_get_particle_count(Handle, out count), "hearth_world_get_particle_count");
                return (int)(ulong)count;
            }
        }

        /// <summary>
        /// hearth_world_get_particles: every live particle's id, position and velocity (each
        /// array optional) in one call, the same order in all three; returns the count. Each
        /// given array must hold at least ParticleCount elements (else BufferTooSmall); with
        /// no array, or only empty ones, it returns the count (hearth_world_get_particle_count).
        /// </summary>
        public int GetParticles(ParticleId[] ids, Vec3[] positions, Vec3[] velocities)
        {
            int capacity = int.MaxValue;
            if (ids != null) capacity = Math.Min(capacity, ids.Length);
            if (positions != null) capacity = Math.Min(capacity, positions.Length);
            if (velocities != null) capacity = Math.Min(capacity, velocities.Length);
            if (capacity == int.MaxValue || capacity == 0)
            {
                return ParticleCount; // count only (the C function at capacity 0)
            }
            UIntPtr count;
            Check(Native.hearth_world_get_particles(Handle, ids, positions, velocities, (UIntPtr)(uint)capacity, out count), "hearth_world_get_particles");
            return (int)(ulong)count;
        }

        /// <summary>hearth_world_get_particle_positions: positions of particles[0..count) in one call.</summary>
        public void GetParticlePositions(ParticleId[] particles, Vec3[] positions, int count)
        {
            CheckRange(particles, count, "particles");
            CheckRange(positions, count, "positions");
            Check(Native.hearth_world_get_particle_positions(Handle, particles, (UIntPtr)(uint)count, positions), "hearth_world_get_particle_positions");
        }

        /// <summary>GetParticlePositions of every id in <paramref name="particles"/>.</summary>
        public void GetParticlePositions(ParticleId[] particles, Vec3[] positions)
        {
            if (particles == null)
            {
                throw new ArgumentNullException("particles");
            }
            GetParticlePositions(particles, positions, particles.Length);
        }

        /// <summary>hearth_world_get_expired_particles: the particles that expired in the last step, copied out of the world's array.</summary>
        public ExpiredParticle[] GetExpiredParticles()
        {
            IntPtr array;
            UIntPtr count;
            Check(Native.hearth_world_get_expired_particles(Handle, out array, out count), "hearth_world_get_expired_particles");
            var result = new ExpiredParticle[(int)(ulong)count];
            int size = Marshal.SizeOf(typeof(ExpiredParticle));
            for (int i = 0; i < result.Length; i++)
            {
                result[i] = (ExpiredParticle)Marshal.PtrToStructure(IntPtr.Add(array, i * size), typeof(ExpiredParticle));
            }
            return result;
        }

        /// <summary>hearth_world_set_particle_iterations (each 1..=64).</summary>
        public void SetParticleIterations(uint velocityIterations, uint positionIterations)
        {
            Check(Native.hearth_world_set_particle_iterations(Handle, velocityIterations, positionIterations), "hearth_world_set_particle_iterations");
        }

        // ---- soft bodies -------------------------------------------------------------------

        /// <summary>hearth_soft_body_create_mesh (masses null: def.Mass shared equally).</summary>
        public SoftBody CreateSoftBodyMesh(SoftBodyDef def, Vec3[] vertices, uint[] indices, float[] masses)
        {
            if (vertices == null) throw new ArgumentNullException("vertices");
            if (indices == null) throw new ArgumentNullException("indices");
            if (masses != null && masses.Length != vertices.Length)
            {
                throw new ArgumentException("masses must have one value per vertex", "masses");
            }
            SoftBodyId id;
            Check(Native.hearth_soft_body_create_mesh(Handle, ref def, vertices, (UIntPtr)(uint)vertices.Length, indices, (UIntPtr)(uint)indices.Length, masses, out id), "hearth_soft_body_create_mesh");
            return new SoftBody(this, id);
        }

        /// <summary>hearth_soft_body_create_icosphere.</summary>
        public SoftBody CreateSoftBodyIcosphere(SoftBodyDef def, float radius, uint subdivisions)
        {
            SoftBodyId id;
            Check(Native.hearth_soft_body_create_icosphere(Handle, ref def, radius, subdivisions, out id), "hearth_soft_body_create_icosphere");
            return new SoftBody(this, id);
        }

        /// <summary>hearth_soft_body_create_box.</summary>
        public SoftBody CreateSoftBodyBox(SoftBodyDef def, Vec3 halfExtents, uint cellsX, uint cellsY, uint cellsZ)
        {
            SoftBodyId id;
            Check(Native.hearth_soft_body_create_box(Handle, ref def, halfExtents, cellsX, cellsY, cellsZ, out id), "hearth_soft_body_create_box");
            return new SoftBody(this, id);
        }

        /// <summary>hearth_soft_body_create_cloth.</summary>
        public SoftBody CreateSoftBodyCloth(SoftBodyDef def, float width, float height, uint columns, uint rows)
        {
            SoftBodyId id;
            Check(Native.hearth_soft_body_create_cloth(Handle, ref def, width, height, columns, rows, out id), "hearth_soft_body_create_cloth");
            return new SoftBody(this, id);
        }

        // ---- shared geometry (the arrays are copied) --------------------------------------

        /// <summary>hearth_hull_create with HullDef.Default().</summary>
        public Hull CreateHull(Vec3[] points) { return CreateHull(HullDef.Default(), points); }

        /// <summary>hearth_hull_create: a convex hull of the points (in its own frame).</summary>
        public Hull CreateHull(HullDef def, Vec3[] points)
        {
            if (points == null) throw new ArgumentNullException("points");
            HullId id;
            Check(Native.hearth_hull_create(Handle, ref def, points, (UIntPtr)(uint)points.Length, out id), "hearth_hull_create");
            return new Hull(this, id);
        }

        /// <summary>hearth_mesh_create: three indices per triangle, counter-clockwise seen from the front.</summary>
        public Mesh CreateMesh(Vec3[] vertices, uint[] indices)
        {
            if (vertices == null) throw new ArgumentNullException("vertices");
            if (indices == null) throw new ArgumentNullException("indices");
            MeshId id;
            Check(Native.hearth_mesh_create(Handle, vertices, (UIntPtr)(uint)vertices.Length, indices, (UIntPtr)(uint)indices.Length, out id), "hearth_mesh_create");
            return new Mesh(this, id);
        }

        /// <summary>hearth_heightfield_create: rows × columns row-major heights; holes null or one 0/1 flag per cell.</summary>
        public Heightfield CreateHeightfield(uint rows, uint columns, float[] heights, byte[] holes)
        {
            if (heights == null) throw new ArgumentNullException("heights");
            if ((ulong)heights.Length != (ulong)rows * columns)
            {
                throw new ArgumentException("heights must hold rows * columns values", "heights");
            }
            if (holes != null && rows >= 2 && columns >= 2 && (ulong)holes.Length != (ulong)(rows - 1) * (columns - 1))
            {
                throw new ArgumentException("holes must hold (rows - 1) * (columns - 1) flags", "holes");
            }
            HeightfieldId id;
            Check(Native.hearth_heightfield_create(Handle, rows, columns, heights, holes, out id), "hearth_heightfield_create");
            return new Heightfield(this, id);
        }

        /// <summary>The wrapper of an existing soft body id.</summary>
        public SoftBody GetSoftBody(SoftBodyId id) { return new SoftBody(this, id); }

        /// <summary>hearth_world_get_soft_body_count.</summary>
        public int SoftBodyCount
        {
            get
            {
                UIntPtr count;
                Check(Native.hearth_world_get_soft_body_count(Handle, out count), "hearth_world_get_soft_body_count");
                return (int)(ulong)count;
            }
        }
    }

    /// <summary>A body (its World and BodyId). Every member calls the hearth_body_* function of the same name.</summary>
    public struct Body : IEquatable<Body>
    {
        public readonly World World;
        public readonly BodyId Id;

        public Body(World world, BodyId id)
        {
            World = world;
            Id = id;
        }

        private WorldHandle H { get { return World.Handle; } }

        /// <summary>hearth_body_destroy: also its shapes, contacts and joints; the id becomes stale.</summary>
        public void Destroy()
        {
            HearthException.Check(Native.hearth_body_destroy(H, Id), "hearth_body_destroy");
        }

        /// <summary>hearth_body_get_transform / hearth_body_set_transform.</summary>
        public Transform Transform
        {
            get
            {
                Transform value;
                HearthException.Check(Native.hearth_body_get_transform(H, Id, out value), "hearth_body_get_transform");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_transform(H, Id, ref value), "hearth_body_set_transform"); }
        }

        /// <summary>The position of the body origin (from hearth_body_get_transform).</summary>
        public Vec3 Position { get { return Transform.Position; } }

        /// <summary>hearth_body_set_target_transform (kinematic bodies: reach it by the next step).</summary>
        public void SetTargetTransform(Transform target)
        {
            HearthException.Check(Native.hearth_body_set_target_transform(H, Id, ref target), "hearth_body_set_target_transform");
        }

        /// <summary>hearth_body_get_linear_velocity / hearth_body_set_linear_velocity (m/s).</summary>
        public Vec3 LinearVelocity
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_body_get_linear_velocity(H, Id, out value), "hearth_body_get_linear_velocity");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_linear_velocity(H, Id, value), "hearth_body_set_linear_velocity"); }
        }

        /// <summary>hearth_body_get_angular_velocity / hearth_body_set_angular_velocity (rad/s, world frame).</summary>
        public Vec3 AngularVelocity
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_body_get_angular_velocity(H, Id, out value), "hearth_body_get_angular_velocity");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_angular_velocity(H, Id, value), "hearth_body_set_angular_velocity"); }
        }

        /// <summary>hearth_body_is_awake / hearth_body_set_awake (wakes or sleeps the island).</summary>
        public bool IsAwake
        {
            get
            {
                bool value;
                HearthException.Check(Native.hearth_body_is_awake(H, Id, out value), "hearth_body_is_awake");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_awake(H, Id, value ? (byte)1 : (byte)0), "hearth_body_set_awake"); }
        }

        /// <summary>hearth_body_get_center_of_mass (world space).</summary>
        public Vec3 CenterOfMass
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_body_get_center_of_mass(H, Id, out value), "hearth_body_get_center_of_mass");
                return value;
            }
        }

        /// <summary>hearth_body_get_mass (kg; 0 for static and kinematic bodies).</summary>
        public float Mass
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_body_get_mass(H, Id, out value), "hearth_body_get_mass");
                return value;
            }
        }

        /// <summary>hearth_body_get_user_data.</summary>
        public ulong UserData
        {
            get
            {
                ulong value;
                HearthException.Check(Native.hearth_body_get_user_data(H, Id, out value), "hearth_body_get_user_data");
                return value;
            }
        }

        /// <summary>hearth_body_get_type.</summary>
        public BodyType Type
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_body_get_type(H, Id, out value), "hearth_body_get_type");
                return (BodyType)value;
            }
            set { HearthException.Check(Native.hearth_body_set_type(H, Id, (uint)value), "hearth_body_set_type"); }
        }

        /// <summary>hearth_body_get_gravity_scale / hearth_body_set_gravity_scale (-100..=100).</summary>
        public float GravityScale
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_body_get_gravity_scale(H, Id, out value), "hearth_body_get_gravity_scale");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_gravity_scale(H, Id, value), "hearth_body_set_gravity_scale"); }
        }

        /// <summary>hearth_body_get_locked_axes / hearth_body_set_locked_axes: setting zeroes the locked velocity components at once and wakes the body.</summary>
        public LockedAxes LockedAxes
        {
            get
            {
                LockedAxes value;
                HearthException.Check(Native.hearth_body_get_locked_axes(H, Id, out value), "hearth_body_get_locked_axes");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_locked_axes(H, Id, value), "hearth_body_set_locked_axes"); }
        }

        /// <summary>hearth_body_get_mass_data / hearth_body_set_mass_data (an override kept until ResetMassData).</summary>
        public MassData MassData
        {
            get
            {
                MassData value;
                HearthException.Check(Native.hearth_body_get_mass_data(H, Id, out value), "hearth_body_get_mass_data");
                return value;
            }
            set { HearthException.Check(Native.hearth_body_set_mass_data(H, Id, ref value), "hearth_body_set_mass_data"); }
        }

        /// <summary>hearth_body_reset_mass_data: the mass comes from the shapes again.</summary>
        public void ResetMassData()
        {
            HearthException.Check(Native.hearth_body_reset_mass_data(H, Id), "hearth_body_reset_mass_data");
        }

        /// <summary>hearth_body_is_enabled; setting it calls hearth_body_enable or hearth_body_disable.</summary>
        public bool Enabled
        {
            get
            {
                bool value;
                HearthException.Check(Native.hearth_body_is_enabled(H, Id, out value), "hearth_body_is_enabled");
                return value;
            }
            set
            {
                if (value) HearthException.Check(Native.hearth_body_enable(H, Id), "hearth_body_enable");
                else HearthException.Check(Native.hearth_body_disable(H, Id), "hearth_body_disable");
            }
        }

        /// <summary>hearth_body_apply_force (N, at the centre of mass, for the next step).</summary>
        public void ApplyForce(Vec3 force)
        {
            HearthException.Check(Native.hearth_body_apply_force(H, Id, force), "hearth_body_apply_force");
        }

        /// <summary>hearth_body_apply_torque (N·m).</summary>
        public void ApplyTorque(Vec3 torque)
        {
            HearthException.Check(Native.hearth_body_apply_torque(H, Id, torque), "hearth_body_apply_torque");
        }

        /// <summary>hearth_body_apply_linear_impulse (N·s).</summary>
        public void ApplyLinearImpulse(Vec3 impulse)
        {
            HearthException.Check(Native.hearth_body_apply_linear_impulse(H, Id, impulse), "hearth_body_apply_linear_impulse");
        }

        /// <summary>hearth_body_apply_angular_impulse (N·m·s).</summary>
        public void ApplyAngularImpulse(Vec3 impulse)
        {
            HearthException.Check(Native.hearth_body_apply_angular_impulse(H, Id, impulse), "hearth_body_apply_angular_impulse");
        }

        /// <summary>hearth_body_apply_force_at_point (N at a world point).</summary>
        public void ApplyForceAtPoint(Vec3 force, Vec3 point)
        {
            HearthException.Check(Native.hearth_body_apply_force_at_point(H, Id, force, point), "hearth_body_apply_force_at_point");
        }

        /// <summary>hearth_body_apply_impulse_at_point (N·s at a world point).</summary>
        public void ApplyImpulseAtPoint(Vec3 impulse, Vec3 point)
        {
            HearthException.Check(Native.hearth_body_apply_impulse_at_point(H, Id, impulse, point), "hearth_body_apply_impulse_at_point");
        }

        /// <summary>hearth_body_set_damping (1/s, each &gt;= 0).</summary>
        public void SetDamping(float linearDamping, float angularDamping)
        {
            HearthException.Check(Native.hearth_body_set_damping(H, Id, linearDamping, angularDamping), "hearth_body_set_damping");
        }

        /// <summary>hearth_shape_create_sphere with ShapeDef.Default().</summary>
        public Shape CreateSphere(Sphere sphere) { return CreateSphere(ShapeDef.Default(), sphere); }

        /// <summary>hearth_shape_create_sphere.</summary>
        public Shape CreateSphere(ShapeDef def, Sphere sphere)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_sphere(H, Id, ref def, ref sphere, out id), "hearth_shape_create_sphere");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_box with ShapeDef.Default().</summary>
        public Shape CreateBox(Box box) { return CreateBox(ShapeDef.Default(), box); }

        /// <summary>hearth_shape_create_box.</summary>
        public Shape CreateBox(ShapeDef def, Box box)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_box(H, Id, ref def, ref box, out id), "hearth_shape_create_box");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_capsule with ShapeDef.Default().</summary>
        public Shape CreateCapsule(Capsule capsule) { return CreateCapsule(ShapeDef.Default(), capsule); }

        /// <summary>hearth_shape_create_capsule.</summary>
        public Shape CreateCapsule(ShapeDef def, Capsule capsule)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_capsule(H, Id, ref def, ref capsule, out id), "hearth_shape_create_capsule");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_plane with ShapeDef.Default() (static bodies only).</summary>
        public Shape CreatePlane(Plane plane) { return CreatePlane(ShapeDef.Default(), plane); }

        /// <summary>hearth_shape_create_plane (static bodies only).</summary>
        public Shape CreatePlane(ShapeDef def, Plane plane)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_plane(H, Id, ref def, ref plane, out id), "hearth_shape_create_plane");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_hull with ShapeDef.Default().</summary>
        public Shape CreateHull(HullShape hull) { return CreateHull(ShapeDef.Default(), hull); }

        /// <summary>hearth_shape_create_hull.</summary>
        public Shape CreateHull(ShapeDef def, HullShape hull)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_hull(H, Id, ref def, ref hull, out id), "hearth_shape_create_hull");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_mesh with ShapeDef.Default() (static and kinematic bodies only).</summary>
        public Shape CreateMesh(MeshShape mesh) { return CreateMesh(ShapeDef.Default(), mesh); }

        /// <summary>hearth_shape_create_mesh (static and kinematic bodies only).</summary>
        public Shape CreateMesh(ShapeDef def, MeshShape mesh)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_mesh(H, Id, ref def, ref mesh, out id), "hearth_shape_create_mesh");
            return new Shape(World, id);
        }

        /// <summary>hearth_shape_create_heightfield with ShapeDef.Default() (static and kinematic bodies only).</summary>
        public Shape CreateHeightfield(HeightfieldShape heightfield) { return CreateHeightfield(ShapeDef.Default(), heightfield); }

        /// <summary>hearth_shape_create_heightfield (static and kinematic bodies only).</summary>
        public Shape CreateHeightfield(ShapeDef def, HeightfieldShape heightfield)
        {
            ShapeId id;
            HearthException.Check(Native.hearth_shape_create_heightfield(H, Id, ref def, ref heightfield, out id), "hearth_shape_create_heightfield");
            return new Shape(World, id);
        }

        public bool Equals(Body other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Body && Equals((Body)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Body(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>What World.Draw calls: the debug-draw primitives (world space, metres; colours 0xRRGGBBAA).</summary>
    public interface IDebugDrawer
    {
        void Segment(Vec3 a, Vec3 b, uint color);
        /// <summary>A convex planar polygon (a face; three vertices for a triangle).</summary>
        void Polygon(Vec3[] vertices, uint color);
        void Sphere(Vec3 center, float radius, uint color);
        void Capsule(Vec3 a, Vec3 b, float radius, uint color);
        /// <summary>A frame: a centre of mass and the body's orientation.</summary>
        void Transform(Transform transform);
        void Point(Vec3 point, float size, uint color);
    }

    /// <summary>A shape (its World and ShapeId).</summary>
    public struct Shape : IEquatable<Shape>
    {
        public readonly World World;
        public readonly ShapeId Id;

        public Shape(World world, ShapeId id)
        {
            World = world;
            Id = id;
        }

        /// <summary>hearth_shape_get_body.</summary>
        public Body Body
        {
            get
            {
                BodyId body;
                HearthException.Check(Native.hearth_shape_get_body(World.Handle, Id, out body), "hearth_shape_get_body");
                return new Body(World, body);
            }
        }

        /// <summary>hearth_shape_destroy (the body's mass is recomputed).</summary>
        public void Destroy()
        {
            HearthException.Check(Native.hearth_shape_destroy(World.Handle, Id), "hearth_shape_destroy");
        }

        /// <summary>hearth_shape_get_filter / hearth_shape_set_filter (pairs re-evaluated at the next step).</summary>
        public Filter Filter
        {
            get
            {
                Filter f;
                HearthException.Check(Native.hearth_shape_get_filter(World.Handle, Id, out f), "hearth_shape_get_filter");
                return f;
            }
            set { HearthException.Check(Native.hearth_shape_set_filter(World.Handle, Id, value), "hearth_shape_set_filter"); }
        }

        /// <summary>hearth_shape_get_restitution / hearth_shape_set_restitution.</summary>
        public float Restitution
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_shape_get_restitution(World.Handle, Id, out value), "hearth_shape_get_restitution");
                return value;
            }
            set { HearthException.Check(Native.hearth_shape_set_restitution(World.Handle, Id, value), "hearth_shape_set_restitution"); }
        }

        /// <summary>hearth_shape_get_rolling_resistance / hearth_shape_set_rolling_resistance.</summary>
        public float RollingResistance
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_shape_get_rolling_resistance(World.Handle, Id, out value), "hearth_shape_get_rolling_resistance");
                return value;
            }
            set { HearthException.Check(Native.hearth_shape_set_rolling_resistance(World.Handle, Id, value), "hearth_shape_set_rolling_resistance"); }
        }

        /// <summary>hearth_shape_get_torsional_friction / hearth_shape_set_torsional_friction.</summary>
        public float TorsionalFriction
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_shape_get_torsional_friction(World.Handle, Id, out value), "hearth_shape_get_torsional_friction");
                return value;
            }
            set { HearthException.Check(Native.hearth_shape_set_torsional_friction(World.Handle, Id, value), "hearth_shape_set_torsional_friction"); }
        }

        /// <summary>hearth_shape_get_density / hearth_shape_set_density.</summary>
        public float Density
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_shape_get_density(World.Handle, Id, out value), "hearth_shape_get_density");
                return value;
            }
            set { HearthException.Check(Native.hearth_shape_set_density(World.Handle, Id, value), "hearth_shape_set_density"); }
        }

        /// <summary>hearth_shape_get_user_data / hearth_shape_set_user_data.</summary>
        public ulong UserData
        {
            get
            {
                ulong value;
                HearthException.Check(Native.hearth_shape_get_user_data(World.Handle, Id, out value), "hearth_shape_get_user_data");
                return value;
            }
            set { HearthException.Check(Native.hearth_shape_set_user_data(World.Handle, Id, value), "hearth_shape_set_user_data"); }
        }

        /// <summary>hearth_shape_get_friction: (static, dynamic) coefficients.</summary>
        public void GetFriction(out float staticFriction, out float dynamicFriction)
        {
            HearthException.Check(Native.hearth_shape_get_friction(World.Handle, Id, out staticFriction, out dynamicFriction), "hearth_shape_get_friction");
        }

        /// <summary>hearth_shape_set_friction (each &gt;= 0).</summary>
        public void SetFriction(float staticFriction, float dynamicFriction)
        {
            HearthException.Check(Native.hearth_shape_set_friction(World.Handle, Id, staticFriction, dynamicFriction), "hearth_shape_set_friction");
        }

        public bool Equals(Shape other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Shape && Equals((Shape)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Shape(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A force or contact generator (its World and GeneratorId).</summary>
    public struct Generator : IEquatable<Generator>
    {
        public readonly World World;
        public readonly GeneratorId Id;

        public Generator(World world, GeneratorId id)
        {
            World = world;
            Id = id;
        }

        private WorldHandle H { get { return World.Handle; } }

        /// <summary>hearth_generator_get_type.</summary>
        public GeneratorType Type
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_generator_get_type(H, Id, out value), "hearth_generator_get_type");
                return (GeneratorType)value;
            }
        }

        /// <summary>hearth_generator_attach_body.</summary>
        public void AttachBody(BodyId body)
        {
            HearthException.Check(Native.hearth_generator_attach_body(H, Id, body), "hearth_generator_attach_body");
        }

        /// <summary>hearth_generator_attach_body.</summary>
        public void AttachBody(Body body) { AttachBody(body.Id); }

        /// <summary>hearth_generator_detach_body.</summary>
        public void DetachBody(BodyId body)
        {
            HearthException.Check(Native.hearth_generator_detach_body(H, Id, body), "hearth_generator_detach_body");
        }

        /// <summary>hearth_generator_detach_body.</summary>
        public void DetachBody(Body body) { DetachBody(body.Id); }

        /// <summary>hearth_generator_attach_particle.</summary>
        public void AttachParticle(ParticleId particle)
        {
            HearthException.Check(Native.hearth_generator_attach_particle(H, Id, particle), "hearth_generator_attach_particle");
        }

        /// <summary>hearth_generator_attach_particle.</summary>
        public void AttachParticle(Particle particle) { AttachParticle(particle.Id); }

        /// <summary>hearth_generator_attach_particles: all of <paramref name="particles"/> or none.</summary>
        public void AttachParticles(ParticleId[] particles)
        {
            if (particles == null)
            {
                throw new ArgumentNullException("particles");
            }
            HearthException.Check(Native.hearth_generator_attach_particles(H, Id, particles, (UIntPtr)(uint)particles.Length), "hearth_generator_attach_particles");
        }

        /// <summary>hearth_generator_detach_particle.</summary>
        public void DetachParticle(ParticleId particle)
        {
            HearthException.Check(Native.hearth_generator_detach_particle(H, Id, particle), "hearth_generator_detach_particle");
        }

        /// <summary>hearth_generator_detach_particle.</summary>
        public void DetachParticle(Particle particle) { DetachParticle(particle.Id); }

        /// <summary>hearth_generator_get_attachment_count.</summary>
        public void GetAttachmentCount(out uint bodyCount, out uint particleCount)
        {
            HearthException.Check(Native.hearth_generator_get_attachment_count(H, Id, out bodyCount, out particleCount), "hearth_generator_get_attachment_count");
        }

        /// <summary>hearth_generator_destroy (through World.DestroyGenerator, which releases a user callback).</summary>
        public void Destroy() { World.DestroyGenerator(Id); }

        public bool Equals(Generator other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Generator && Equals((Generator)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Generator(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A joint (its World and JointId).</summary>
    public struct Joint : IEquatable<Joint>
    {
        public readonly World World;
        public readonly JointId Id;

        public Joint(World world, JointId id)
        {
            World = world;
            Id = id;
        }

        private WorldHandle H { get { return World.Handle; } }

        /// <summary>hearth_joint_destroy.</summary>
        public void Destroy()
        {
            HearthException.Check(Native.hearth_joint_destroy(H, Id), "hearth_joint_destroy");
        }

        /// <summary>hearth_joint_get_type.</summary>
        public JointType Type
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_joint_get_type(H, Id, out value), "hearth_joint_get_type");
                return (JointType)value;
            }
        }

        /// <summary>hearth_joint_get_bodies (bodyB's id is null for a joint to the world).</summary>
        public void GetBodies(out Body bodyA, out Body bodyB)
        {
            BodyId a, b;
            HearthException.Check(Native.hearth_joint_get_bodies(H, Id, out a, out b), "hearth_joint_get_bodies");
            bodyA = new Body(World, a);
            bodyB = new Body(World, b);
        }

        /// <summary>hearth_joint_set_motor (hinge: rad/s and N·m; slider: m/s and N).</summary>
        public void SetMotor(bool enable, float speed, float max)
        {
            HearthException.Check(Native.hearth_joint_set_motor(H, Id, enable ? (byte)1 : (byte)0, speed, max), "hearth_joint_set_motor");
        }

        /// <summary>hearth_joint_get_motor.</summary>
        public void GetMotor(out bool enabled, out float speed, out float max)
        {
            HearthException.Check(Native.hearth_joint_get_motor(H, Id, out enabled, out speed, out max), "hearth_joint_get_motor");
        }

        /// <summary>hearth_joint_set_limits (hinge angles, slider translations, distance lengths, ball twist).</summary>
        public void SetLimits(bool enable, float lower, float upper)
        {
            HearthException.Check(Native.hearth_joint_set_limits(H, Id, enable ? (byte)1 : (byte)0, lower, upper), "hearth_joint_set_limits");
        }

        /// <summary>hearth_joint_get_limits.</summary>
        public void GetLimits(out bool enabled, out float lower, out float upper)
        {
            HearthException.Check(Native.hearth_joint_get_limits(H, Id, out enabled, out lower, out upper), "hearth_joint_get_limits");
        }

        /// <summary>hearth_joint_set_cone_limit (ball joints; half-angle in rad).</summary>
        public void SetConeLimit(bool enable, float angle)
        {
            HearthException.Check(Native.hearth_joint_set_cone_limit(H, Id, enable ? (byte)1 : (byte)0, angle), "hearth_joint_set_cone_limit");
        }

        /// <summary>hearth_joint_get_cone_limit.</summary>
        public void GetConeLimit(out bool enabled, out float angle)
        {
            HearthException.Check(Native.hearth_joint_get_cone_limit(H, Id, out enabled, out angle), "hearth_joint_get_cone_limit");
        }

        /// <summary>hearth_joint_set_spring (hinge and distance joints).</summary>
        public void SetSpring(bool enable, float hertz, float dampingRatio)
        {
            HearthException.Check(Native.hearth_joint_set_spring(H, Id, enable ? (byte)1 : (byte)0, hertz, dampingRatio), "hearth_joint_set_spring");
        }

        /// <summary>hearth_joint_get_spring.</summary>
        public void GetSpring(out bool enabled, out float hertz, out float dampingRatio)
        {
            HearthException.Check(Native.hearth_joint_get_spring(H, Id, out enabled, out hertz, out dampingRatio), "hearth_joint_get_spring");
        }

        /// <summary>hearth_joint_get_force: force (N) and torque (N·m) on body B in the last step.</summary>
        public void GetForce(out Vec3 force, out Vec3 torque)
        {
            HearthException.Check(Native.hearth_joint_get_force(H, Id, out force, out torque), "hearth_joint_get_force");
        }

        /// <summary>hearth_joint_is_broken.</summary>
        public bool IsBroken
        {
            get
            {
                bool value;
                HearthException.Check(Native.hearth_joint_is_broken(H, Id, out value), "hearth_joint_is_broken");
                return value;
            }
        }

        public bool Equals(Joint other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Joint && Equals((Joint)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Joint(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A particle (its World and ParticleId).</summary>
    public struct Particle : IEquatable<Particle>
    {
        public readonly World World;
        public readonly ParticleId Id;

        public Particle(World world, ParticleId id)
        {
            World = world;
            Id = id;
        }

        private WorldHandle H { get { return World.Handle; } }

        /// <summary>hearth_particle_destroy.</summary>
        public void Destroy()
        {
            HearthException.Check(Native.hearth_particle_destroy(H, Id), "hearth_particle_destroy");
        }

        /// <summary>hearth_particle_get_position / hearth_particle_set_position (m).</summary>
        public Vec3 Position
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_particle_get_position(H, Id, out value), "hearth_particle_get_position");
                return value;
            }
            set { HearthException.Check(Native.hearth_particle_set_position(H, Id, value), "hearth_particle_set_position"); }
        }

        /// <summary>hearth_particle_get_velocity / hearth_particle_set_velocity (m/s).</summary>
        public Vec3 Velocity
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_particle_get_velocity(H, Id, out value), "hearth_particle_get_velocity");
                return value;
            }
            set { HearthException.Check(Native.hearth_particle_set_velocity(H, Id, value), "hearth_particle_set_velocity"); }
        }

        /// <summary>hearth_particle_is_awake / hearth_particle_set_awake.</summary>
        public bool IsAwake
        {
            get
            {
                bool value;
                HearthException.Check(Native.hearth_particle_is_awake(H, Id, out value), "hearth_particle_is_awake");
                return value;
            }
            set { HearthException.Check(Native.hearth_particle_set_awake(H, Id, value ? (byte)1 : (byte)0), "hearth_particle_set_awake"); }
        }

        /// <summary>hearth_particle_get_user_data.</summary>
        public ulong UserData
        {
            get
            {
                ulong value;
                HearthException.Check(Native.hearth_particle_get_user_data(H, Id, out value), "hearth_particle_get_user_data");
                return value;
            }
        }

        /// <summary>hearth_particle_apply_force (N, for the next step).</summary>
        public void ApplyForce(Vec3 force)
        {
            HearthException.Check(Native.hearth_particle_apply_force(H, Id, force), "hearth_particle_apply_force");
        }

        /// <summary>hearth_particle_apply_impulse (N·s).</summary>
        public void ApplyImpulse(Vec3 impulse)
        {
            HearthException.Check(Native.hearth_particle_apply_impulse(H, Id, impulse), "hearth_particle_apply_impulse");
        }

        public bool Equals(Particle other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Particle && Equals((Particle)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Particle(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A convex hull shared by shapes (its World and HullId). Destroy is refused while shapes use it.</summary>
    public struct Hull : IEquatable<Hull>
    {
        public readonly World World;
        public readonly HullId Id;

        public Hull(World world, HullId id)
        {
            World = world;
            Id = id;
        }

        /// <summary>A shape description instancing this hull at <c>local</c> with a uniform scale.</summary>
        public HullShape Shape(Transform local, float scale) { return new HullShape(Id, local, scale); }

        /// <summary>hearth_hull_get_vertex_count.</summary>
        public int VertexCount
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_hull_get_vertex_count(World.Handle, Id, out value), "hearth_hull_get_vertex_count");
                return (int)value;
            }
        }

        /// <summary>hearth_hull_destroy.</summary>
        public void Destroy() { HearthException.Check(Native.hearth_hull_destroy(World.Handle, Id), "hearth_hull_destroy"); }

        public bool Equals(Hull other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Hull && Equals((Hull)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Hull(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A triangle mesh shared by shapes (its World and MeshId), for static and kinematic bodies.</summary>
    public struct Mesh : IEquatable<Mesh>
    {
        public readonly World World;
        public readonly MeshId Id;

        public Mesh(World world, MeshId id)
        {
            World = world;
            Id = id;
        }

        /// <summary>A shape description instancing this mesh at <c>local</c>, scaled per axis.</summary>
        public MeshShape Shape(Transform local, Vec3 scale) { return new MeshShape(Id, local, scale); }

        /// <summary>hearth_mesh_get_triangle_count: triangles kept.</summary>
        public int TriangleCount
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_mesh_get_triangle_count(World.Handle, Id, out value), "hearth_mesh_get_triangle_count");
                return (int)value;
            }
        }

        /// <summary>hearth_mesh_get_degenerate_count: triangles skipped at creation.</summary>
        public int DegenerateCount
        {
            get
            {
                uint value;
                HearthException.Check(Native.hearth_mesh_get_degenerate_count(World.Handle, Id, out value), "hearth_mesh_get_degenerate_count");
                return (int)value;
            }
        }

        /// <summary>hearth_mesh_destroy.</summary>
        public void Destroy() { HearthException.Check(Native.hearth_mesh_destroy(World.Handle, Id), "hearth_mesh_destroy"); }

        public bool Equals(Mesh other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Mesh && Equals((Mesh)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Mesh(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A heightfield shared by shapes (its World and HeightfieldId), for static and kinematic bodies.</summary>
    public struct Heightfield : IEquatable<Heightfield>
    {
        public readonly World World;
        public readonly HeightfieldId Id;

        public Heightfield(World world, HeightfieldId id)
        {
            World = world;
            Id = id;
        }

        /// <summary>A shape description: <c>scale.X</c>, <c>scale.Z</c> the spacing (m), <c>scale.Y</c> the height scale.</summary>
        public HeightfieldShape Shape(Transform local, Vec3 scale) { return new HeightfieldShape(Id, local, scale); }

        /// <summary>hearth_heightfield_destroy.</summary>
        public void Destroy() { HearthException.Check(Native.hearth_heightfield_destroy(World.Handle, Id), "hearth_heightfield_destroy"); }

        public bool Equals(Heightfield other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is Heightfield && Equals((Heightfield)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "Heightfield(" + Id.Index + ", " + Id.Generation + ")"; }
    }

    /// <summary>A soft body (its World and SoftBodyId).</summary>
    public struct SoftBody : IEquatable<SoftBody>
    {
        public readonly World World;
        public readonly SoftBodyId Id;

        public SoftBody(World world, SoftBodyId id)
        {
            World = world;
            Id = id;
        }

        private WorldHandle H { get { return World.Handle; } }

        /// <summary>hearth_soft_body_destroy.</summary>
        public void Destroy()
        {
            HearthException.Check(Native.hearth_soft_body_destroy(H, Id), "hearth_soft_body_destroy");
        }

        /// <summary>hearth_soft_body_get_vertex_count.</summary>
        public int VertexCount
        {
            get
            {
                UIntPtr value;
                HearthException.Check(Native.hearth_soft_body_get_vertex_count(H, Id, out value), "hearth_soft_body_get_vertex_count");
                return (int)(ulong)value;
            }
        }

        /// <summary>hearth_soft_body_get_triangle_count.</summary>
        public int TriangleCount
        {
            get
            {
                UIntPtr value;
                HearthException.Check(Native.hearth_soft_body_get_triangle_count(H, Id, out value), "hearth_soft_body_get_triangle_count");
                return (int)(ulong)value;
            }
        }

        /// <summary>
        /// hearth_soft_body_get_positions into a caller-owned array (one call per frame):
        /// returns the vertex count. An empty array only counts; a non-empty one smaller than
        /// the vertex count throws (BufferTooSmall) and is left untouched.
        /// </summary>
        public int GetPositions(Vec3[] buffer)
        {
            UIntPtr count;
            int capacity = buffer == null ? 0 : buffer.Length;
            HearthException.Check(Native.hearth_soft_body_get_positions(H, Id, capacity == 0 ? null : buffer, (UIntPtr)(uint)capacity, out count), "hearth_soft_body_get_positions");
            return (int)(ulong)count;
        }

        /// <summary>hearth_soft_body_get_positions into a new array.</summary>
        public Vec3[] GetPositions()
        {
            var result = new Vec3[VertexCount];
            GetPositions(result);
            return result;
        }

        /// <summary>hearth_soft_body_get_normals into a caller-owned array; as GetPositions.</summary>
        public int GetNormals(Vec3[] buffer)
        {
            UIntPtr count;
            int capacity = buffer == null ? 0 : buffer.Length;
            HearthException.Check(Native.hearth_soft_body_get_normals(H, Id, capacity == 0 ? null : buffer, (UIntPtr)(uint)capacity, out count), "hearth_soft_body_get_normals");
            return (int)(ulong)count;
        }

        /// <summary>hearth_soft_body_get_normals into a new array.</summary>
        public Vec3[] GetNormals()
        {
            var result = new Vec3[VertexCount];
            GetNormals(result);
            return result;
        }

        /// <summary>hearth_soft_body_get_indices into a caller-owned array (3 per triangle); returns the index count.</summary>
        public int GetIndices(uint[] buffer)
        {
            UIntPtr count;
            int capacity = buffer == null ? 0 : buffer.Length;
            HearthException.Check(Native.hearth_soft_body_get_indices(H, Id, capacity == 0 ? null : buffer, (UIntPtr)(uint)capacity, out count), "hearth_soft_body_get_indices");
            return (int)(ulong)count;
        }

        /// <summary>hearth_soft_body_get_indices into a new array.</summary>
        public uint[] GetIndices()
        {
            var result = new uint[3 * TriangleCount];
            GetIndices(result);
            return result;
        }

        /// <summary>hearth_soft_body_get_vertex_position.</summary>
        public Vec3 GetVertexPosition(uint vertex)
        {
            Vec3 value;
            HearthException.Check(Native.hearth_soft_body_get_vertex_position(H, Id, vertex, out value), "hearth_soft_body_get_vertex_position");
            return value;
        }

        /// <summary>hearth_soft_body_get_vertex_velocity.</summary>
        public Vec3 GetVertexVelocity(uint vertex)
        {
            Vec3 value;
            HearthException.Check(Native.hearth_soft_body_get_vertex_velocity(H, Id, vertex, out value), "hearth_soft_body_get_vertex_velocity");
            return value;
        }

        /// <summary>hearth_soft_body_get_center (mass-weighted, world space).</summary>
        public Vec3 Center
        {
            get
            {
                Vec3 value;
                HearthException.Check(Native.hearth_soft_body_get_center(H, Id, out value), "hearth_soft_body_get_center");
                return value;
            }
        }

        /// <summary>hearth_soft_body_get_mass (kg).</summary>
        public float Mass
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_soft_body_get_mass(H, Id, out value), "hearth_soft_body_get_mass");
                return value;
            }
        }

        /// <summary>hearth_soft_body_get_volume (m³, closed meshes).</summary>
        public float Volume
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_soft_body_get_volume(H, Id, out value), "hearth_soft_body_get_volume");
                return value;
            }
        }

        /// <summary>hearth_soft_body_get_rest_volume (m³).</summary>
        public float RestVolume
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_soft_body_get_rest_volume(H, Id, out value), "hearth_soft_body_get_rest_volume");
                return value;
            }
        }

        /// <summary>hearth_soft_body_get_pressure / hearth_soft_body_set_pressure (n·R·T, J).</summary>
        public float Pressure
        {
            get
            {
                float value;
                HearthException.Check(Native.hearth_soft_body_get_pressure(H, Id, out value), "hearth_soft_body_get_pressure");
                return value;
            }
            set { HearthException.Check(Native.hearth_soft_body_set_pressure(H, Id, value), "hearth_soft_body_set_pressure"); }
        }

        /// <summary>hearth_soft_body_get_user_data.</summary>
        public ulong UserData
        {
            get
            {
                ulong value;
                HearthException.Check(Native.hearth_soft_body_get_user_data(H, Id, out value), "hearth_soft_body_get_user_data");
                return value;
            }
        }

        /// <summary>
        /// hearth_soft_body_get_settings / hearth_soft_body_set_settings: the settings the soft
        /// body runs with now (those given at creation or set since). Setting replaces them all
        /// from the next step; read, edit, write back (<c>var s = soft.Settings; s.Damping = 1f;
        /// soft.Settings = s;</c>). A bad value throws (InvalidArgument) and changes nothing.
        /// </summary>
        public SoftBodySettings Settings
        {
            get
            {
                SoftBodySettings value;
                HearthException.Check(Native.hearth_soft_body_get_settings(H, Id, out value), "hearth_soft_body_get_settings");
                return value;
            }
            set { HearthException.Check(Native.hearth_soft_body_set_settings(H, Id, ref value), "hearth_soft_body_set_settings"); }
        }

        /// <summary>
        /// hearth_soft_body_set_compliance: the three compliances (the inverse of stiffness, &gt;= 0)
        /// in one call: <paramref name="edge"/> of the stretch springs (m/N, 0 inextensible),
        /// <paramref name="bend"/> of the bending springs (m/N, <c>float.PositiveInfinity</c>
        /// disables bending), <paramref name="volume"/> of the volume constraint (0 incompressible).
        /// Takes effect at the next step; a bad value throws (InvalidArgument) and changes nothing.
        /// </summary>
        public void SetCompliance(float edge, float bend, float volume)
        {
            HearthException.Check(Native.hearth_soft_body_set_compliance(H, Id, edge, bend, volume), "hearth_soft_body_set_compliance");
        }

        /// <summary>hearth_soft_body_pin_vertex to the world (it stays where it is now).</summary>
        public void PinVertex(uint vertex) { PinVertex(vertex, BodyId.Null); }

        /// <summary>hearth_soft_body_pin_vertex to a body (it follows the body), or to the world for the null id.</summary>
        public void PinVertex(uint vertex, BodyId body)
        {
            HearthException.Check(Native.hearth_soft_body_pin_vertex(H, Id, vertex, body), "hearth_soft_body_pin_vertex");
        }

        /// <summary>hearth_soft_body_unpin_vertex.</summary>
        public void UnpinVertex(uint vertex)
        {
            HearthException.Check(Native.hearth_soft_body_unpin_vertex(H, Id, vertex), "hearth_soft_body_unpin_vertex");
        }

        /// <summary>hearth_soft_body_is_vertex_pinned.</summary>
        public bool IsVertexPinned(uint vertex)
        {
            bool value;
            HearthException.Check(Native.hearth_soft_body_is_vertex_pinned(H, Id, vertex, out value), "hearth_soft_body_is_vertex_pinned");
            return value;
        }

        /// <summary>hearth_soft_body_apply_impulse (N·s to one vertex).</summary>
        public void ApplyImpulse(uint vertex, Vec3 impulse)
        {
            HearthException.Check(Native.hearth_soft_body_apply_impulse(H, Id, vertex, impulse), "hearth_soft_body_apply_impulse");
        }

        /// <summary>hearth_soft_body_apply_impulse_all (N·s spread over the vertices by mass).</summary>
        public void ApplyImpulseAll(Vec3 impulse)
        {
            HearthException.Check(Native.hearth_soft_body_apply_impulse_all(H, Id, impulse), "hearth_soft_body_apply_impulse_all");
        }

        public bool Equals(SoftBody other) { return ReferenceEquals(World, other.World) && Id == other.Id; }
        public override bool Equals(object obj) { return obj is SoftBody && Equals((SoftBody)obj); }
        public override int GetHashCode() { return Id.GetHashCode(); }
        public override string ToString() { return "SoftBody(" + Id.Index + ", " + Id.Generation + ")"; }
    }
}
