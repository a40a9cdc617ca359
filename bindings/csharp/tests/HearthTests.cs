// HearthTests.cs - tests of the C# binding against the real library: a console program with
// its own small assert helpers. Exits with 1 if any test failed.
//
//   mono HearthTests.exe [layout.txt]
//
// layout.txt (written by a C program that tests/bindings_csharp.rs generates from
// include/hearth.h) lists the size and field offsets of every struct and the value of every
// constant as the C compiler sees them; the layout test compares them with the binding's.

using System;
using System.Text;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Reflection;
using System.Runtime.InteropServices;
using Hearth;

internal sealed class TestFailure : Exception
{
    public TestFailure(string message) : base(message) { }
}

internal static class HearthTests
{
    private const float Dt = 1.0f / 60.0f;
    private static string layoutPath;
    private static int checks;

    // ---- assert helpers ---------------------------------------------------------------------

    private static void Ensure(bool condition, string what)
    {
        checks++;
        if (!condition)
        {
            throw new TestFailure(what);
        }
    }

    private static void Near(float actual, float expected, float tolerance, string what)
    {
        Ensure(Math.Abs(actual - expected) <= tolerance,
            string.Format(CultureInfo.InvariantCulture, "{0}: {1} is not within {2} of {3}", what, actual, tolerance, expected));
    }

    private static void Near(Vec3 actual, Vec3 expected, float tolerance, string what)
    {
        Ensure((actual - expected).Length <= tolerance,
            string.Format(CultureInfo.InvariantCulture, "{0}: {1} is not within {2} of {3}", what, actual, tolerance, expected));
    }

    private static void Equal<T>(T actual, T expected, string what)
    {
        Ensure(EqualityComparer<T>.Default.Equals(actual, expected), what + ": got " + actual + ", expected " + expected);
    }

    /// <summary>Runs action, which must throw HearthException with code expected; returns it.</summary>
    private static HearthException Fails(Result expected, Action action, string what)
    {
        try
        {
            action();
        }
        catch (HearthException e)
        {
            Equal(e.Result, expected, what + ": result");
            Equal(e.ResultName, Native.ResultName(expected), what + ": result name");
            Ensure(e.Detail.Length > 0, what + ": the exception carries the library's detail message");
            Ensure(e.Message.Contains(e.Detail) && e.Message.Contains(e.ResultName), what + ": message " + e.Message);
            return e;
        }
        throw new TestFailure(what + ": no HearthException (expected " + expected + ")");
    }

    private static T Throws<T>(Action action, string what) where T : Exception
    {
        try
        {
            action();
        }
        catch (T e)
        {
            checks++;
            return e;
        }
        throw new TestFailure(what + ": no " + typeof(T).Name);
    }

    // ---- scene helpers ------------------------------------------------------------------------

    private static Body Ground(World world)
    {
        Body ground = world.CreateBody(BodyDef.Default());
        ground.CreatePlane(new Plane(new Vec3(0f, 1f, 0f), 0f));
        return ground;
    }

    private static Body DynamicBox(World world, Vec3 position, float halfExtent)
    {
        Body body = world.CreateBody(BodyType.Dynamic, position);
        body.CreateBox(new Box(new Vec3(halfExtent, halfExtent, halfExtent)));
        return body;
    }

    private static Body DynamicSphere(World world, Vec3 position, float radius)
    {
        Body body = world.CreateBody(BodyType.Dynamic, position);
        body.CreateSphere(new Sphere(Vec3.Zero, radius));
        return body;
    }

    private static void Run(World world, int steps)
    {
        for (int i = 0; i < steps; i++)
        {
            world.Step(Dt);
        }
    }

    // ---- layout, version, defaults ----------------------------------------------------------

    private static string Pascal(string snake)
    {
        var parts = snake.Split('_');
        var result = "";
        foreach (var p in parts)
        {
            result += char.ToUpperInvariant(p[0]) + p.Substring(1);
        }
        return result;
    }

    private static Type BindingType(string cName)
    {
        Ensure(cName.StartsWith("Hearth", StringComparison.Ordinal), "C type name " + cName);
        Type t = typeof(World).Assembly.GetType("Hearth." + cName.Substring("Hearth".Length));
        Ensure(t != null, "the binding has no type for " + cName);
        return t;
    }

    // The C# value of a HEARTH_* constant: an enum member or a Native constant.
    private static long ConstantValue(string cName)
    {
        var families = new[]
        {
            new KeyValuePair<string, Type>("HEARTH_ERROR_", typeof(Result)),
            new KeyValuePair<string, Type>("HEARTH_BODY_", typeof(BodyType)),
            new KeyValuePair<string, Type>("HEARTH_GENERATOR_", typeof(GeneratorType)),
            new KeyValuePair<string, Type>("HEARTH_JOINT_", typeof(JointType)),
            new KeyValuePair<string, Type>("HEARTH_INTEGRATOR_", typeof(Integrator)),
            new KeyValuePair<string, Type>("HEARTH_QUERY_SHAPE_", typeof(QueryShapeType)),
            new KeyValuePair<string, Type>("HEARTH_LOCK_", typeof(LockedAxes)),
        };
        if (cName == "HEARTH_OK")
        {
            return (long)Result.Ok;
        }
        foreach (var f in families)
        {
            if (cName.StartsWith(f.Key, StringComparison.Ordinal))
            {
                string member = Pascal(cName.Substring(f.Key.Length).ToLowerInvariant());
                Ensure(Enum.IsDefined(f.Value, member), f.Value.Name + " has no member " + member + " for " + cName);
                return Convert.ToInt64(Enum.Parse(f.Value, member), CultureInfo.InvariantCulture);
            }
        }
        if (cName.StartsWith("HEARTH_MAX_", StringComparison.Ordinal))
        {
            string field = "Max" + Pascal(cName.Substring("HEARTH_MAX_".Length).ToLowerInvariant());
            FieldInfo fi = typeof(Native).GetField(field);
            Ensure(fi != null, "Native has no constant " + field + " for " + cName);
            return Convert.ToInt64(fi.GetValue(null), CultureInfo.InvariantCulture);
        }
        if (cName.StartsWith("HEARTH_VERSION_", StringComparison.Ordinal))
        {
            string field = "Version" + Pascal(cName.Substring("HEARTH_VERSION_".Length).ToLowerInvariant());
            FieldInfo fi = typeof(Native).GetField(field);
            Ensure(fi != null, "Native has no constant " + field + " for " + cName);
            return Convert.ToInt64(fi.GetValue(null), CultureInfo.InvariantCulture);
        }
        throw new TestFailure("no C# counterpart known for the constant " + cName + " (extend the binding and this map)");
    }

    private static void TestLayoutMatchesC()
    {
        Ensure(layoutPath != null, "layout.txt path given on the command line");
        int sizes = 0, offsets = 0, constants = 0;
        foreach (string line in File.ReadAllLines(layoutPath))
        {
            string[] w = line.Split(' ');
            if (w[0] == "size")
            {
                Type t = BindingType(w[1]);
                Equal(Marshal.SizeOf(t), int.Parse(w[2], CultureInfo.InvariantCulture), "sizeof(" + w[1] + ")");
                sizes++;
            }
            else if (w[0] == "offset")
            {
                Type t = BindingType(w[1]);
                string field = Pascal(w[2]);
                Ensure(t.GetField(field) != null, w[1] + "." + w[2] + " has no field " + field + " in " + t.Name);
                Equal((int)Marshal.OffsetOf(t, field), int.Parse(w[3], CultureInfo.InvariantCulture), "offsetof(" + w[1] + ", " + w[2] + ")");
                offsets++;
            }
            else if (w[0] == "const")
            {
                Equal(ConstantValue(w[1]), long.Parse(w[2], CultureInfo.InvariantCulture), w[1]);
                constants++;
            }
        }
        Ensure(sizes >= 30 && offsets >= 200 && constants >= 20, "layout.txt has " + sizes + " sizes, " + offsets + " offsets, " + constants + " constants");
        // Every struct field of the binding is in the C layout too (no extra fields).
        foreach (string line in File.ReadAllLines(layoutPath))
        {
            string[] w = line.Split(' ');
            if (w[0] == "size")
            {
                Type t = BindingType(w[1]);
                int fields = t.GetFields(BindingFlags.Public | BindingFlags.NonPublic | BindingFlags.Instance).Length;
                int cFields = 0;
                foreach (string l in File.ReadAllLines(layoutPath))
                {
                    if (l.StartsWith("offset " + w[1] + " ", StringComparison.Ordinal)) cFields++;
                }
                Equal(fields, cFields, "field count of " + t.Name);
            }
        }
        Console.WriteLine("    layout: {0} struct sizes, {1} field offsets, {2} constants match C", sizes, offsets, constants);
    }

    private static void TestVersionAndResultNames()
    {
        Equal(Native.hearth_version(), Native.Version, "library version == binding's header version");
        // The ABI check World's constructor makes: major, and minor before 1.0; patch is free.
        Ensure(Native.IsCompatible(Native.Version), "the binding's own version is compatible");
        Ensure(Native.IsCompatible(Native.Version + 7), "another patch version is compatible");
        Ensure(!Native.IsCompatible(Native.Version + (1u << 8)), "another minor version before 1.0 is not");
        Ensure(!Native.IsCompatible(Native.Version + (1u << 16)), "another major version is not");
        Ensure(Native.IsCompatible((1u << 16) | (3u << 8)) == (Native.VersionMajor == 1),
            "after 1.0 the minor may differ");
        Native.EnsureCompatibleLibrary(); // the loaded library: no exception
        Equal(Native.ResultName(Result.Ok), "HEARTH_OK", "name of Ok");
        Equal(Native.ResultName(Result.InvalidId), "HEARTH_ERROR_INVALID_ID", "name of InvalidId");
        Equal(Native.ResultName(Result.BufferTooSmall), "HEARTH_ERROR_BUFFER_TOO_SMALL", "name of BufferTooSmall");
        Equal(Native.ResultName(Result.LimitReached), "HEARTH_ERROR_LIMIT_REACHED", "name of LimitReached");
        Equal(Native.ResultName((Result)12345), "HEARTH_ERROR_UNKNOWN", "name of an unknown code");
        foreach (Result r in Enum.GetValues(typeof(Result)))
        {
            Ensure(Native.ResultName(r).StartsWith("HEARTH_", StringComparison.Ordinal), "name of " + r);
        }
    }

    // Struct returns of every size class (12 bytes in registers up to large ones in memory)
    // arrive with the documented defaults.
    private static void TestDefaultsComeFromTheLibrary()
    {
        WorldDef w = WorldDef.Default();
        Near(w.Gravity, new Vec3(0f, -9.81f, 0f), 0f, "world gravity");
        Equal(w.Substeps, 6u, "world substeps");
        Equal((bool)w.EnableSleep, true, "world sleep");
        Equal(w.Integrator, Integrator.SemiImplicitEuler, "world integrator");
        Ensure(w.InternalValue != 0, "world def cookie set");
        Near(w.MaxAngularSpeed, 314.159265f, 1e-3f, "world max angular speed (100 pi)");
        BodyDef b = BodyDef.Default();
        Equal(b.Type, BodyType.Static, "body type");
        Equal(b.Transform, Transform.Identity, "body transform");
        Equal((bool)b.AllowSleep, true, "body allow sleep");
        Equal(b.GravityScale, 1f, "body gravity scale");
        ShapeDef s = ShapeDef.Default();
        Equal(s.Density, 1000f, "shape density");
        Near(s.StaticFriction, 0.6f, 1e-6f, "shape friction");
        Near(s.RollingResistance, 0.05f, 1e-7f, "shape rolling resistance");
        Near(s.TorsionalFriction, 0.05f, 1e-7f, "shape torsional friction");
        DragGeneratorDef d = DragGeneratorDef.Default();
        Near(d.K1, 0.1f, 1e-7f, "drag k1");
        Near(d.K2, 0.01f, 1e-8f, "drag k2");
        Near(GravityGeneratorDef.Default().Acceleration, new Vec3(0f, -9.81f, 0f), 0f, "gravity generator");
        Equal(UserContactGeneratorDef.Default().Capacity, 16u, "contact generator capacity");
        Equal(UserForceGeneratorDef.Default().Callback, IntPtr.Zero, "force generator callback");
        Equal(SpringGeneratorDef.Default().RestLength, 1f, "spring rest length");
        Equal(StiffSpringGeneratorDef.Default().Stiffness, 1000f, "stiff spring stiffness");
        Equal(BuoyancyGeneratorDef.Default().LiquidDensity, 1000f, "buoyancy liquid density");
        Equal(ExplosionGeneratorDef.Default().MaxRadius, 20f, "explosion max radius");
        Equal(RodGeneratorDef.Default().Length, 1f, "rod length");
        Equal(CableGeneratorDef.Default().MaxLength, 1f, "cable length");
        Near(BallJointDef.Default().SwingLimit, (float)Math.PI / 4f, 1e-6f, "ball swing limit");
        Equal(BallJointDef.Default().Base.BreakForce, float.MaxValue, "joint break force");
        Near(HingeJointDef.Default().Upper, (float)Math.PI / 2f, 1e-6f, "hinge upper");
        Ensure(FixedJointDef.Default().InternalValue != 0, "fixed joint cookie");
        Equal(DistanceJointDef.Default().MaxLength, 1e6f, "distance max length");
        Equal(SliderJointDef.Default().Lower, -1f, "slider lower");
        ParticleDef p = ParticleDef.Default();
        Equal(p.InverseMass, 1f, "particle inverse mass");
        Equal(p.Radius, 0.05f, "particle radius");
        Ensure(float.IsPositiveInfinity(p.Lifetime), "particle lives forever");
        BurstDef burst = BurstDef.Default();
        Equal(burst.Count, 16u, "burst count");
        Equal(burst.Seed, 1UL, "burst seed");
        Equal(burst.Particle.Radius, 0.05f, "burst particle radius");
        SoftBodyDef soft = SoftBodyDef.Default();
        Equal(soft.Substeps, 20u, "soft substeps");
        Equal(soft.Mass, 1f, "soft mass");
        Equal(soft.VertexRadius, 0.01f, "soft vertex radius");
        Equal(soft.DeformationDamping, 2f, "soft deformation damping");
        Equal(soft.Iterations, 2u, "soft stretch passes");
        Equal((bool)soft.Collide, true, "soft collides");
    }

    // ---- rigid bodies -----------------------------------------------------------------------

    private static void TestBoxFallsAndRestsOnThePlane()
    {
        using (var world = new World())
        {
            Ground(world);
            Body box = DynamicBox(world, new Vec3(0f, 3f, 0f), 0.5f);
            Body ball = DynamicSphere(world, new Vec3(3f, 2f, 0f), 0.25f);
            Near(box.Mass, 1000f, 1e-2f, "1 m³ of water");
            Equal(box.Type, BodyType.Dynamic, "type");
            Run(world, 60);
            WorldCounters c = world.Counters;
            Equal(c.BodyCount, 3u, "body count");
            Equal(c.TouchingContactCount, 2u, "both bodies touch the ground");
            Run(world, 120);
            Near(box.Position, new Vec3(0f, 0.5f, 0f), 0.005f, "box rests on its half extent");
            Near(ball.Position, new Vec3(3f, 0.25f, 0f), 0.005f, "sphere rests on its radius");
            Near(box.LinearVelocity, Vec3.Zero, 0.01f, "box at rest");
            Near(box.Transform.Rotation.W, 1f, 1e-3f, "box not rotated");
            Run(world, 120);
            Ensure(!box.IsAwake && !ball.IsAwake, "resting bodies fall asleep");
            box.IsAwake = true;
            Ensure(box.IsAwake, "woken up");
        }
    }

    private static void TestFreeFallMatchesGravity()
    {
        using (var world = new World())
        {
            Body box = DynamicBox(world, new Vec3(0f, 100f, 0f), 0.5f);
            Run(world, 60);
            // Semi-implicit Euler with h = dt/6 over n = 360 sub-steps: y0 - g h² n(n+1)/2.
            double h = Dt / 6.0;
            double expected = 100.0 - 9.81 * h * h * 360 * 361 / 2;
            Near(box.Position.Y, (float)expected, 2e-3f, "free fall after 1 s");
            Near(box.LinearVelocity.Y, -9.81f, 1e-3f, "velocity after 1 s");
            world.Gravity = Vec3.Zero;
            Equal(world.Gravity, Vec3.Zero, "gravity set");
            Vec3 v = box.LinearVelocity;
            Run(world, 10);
            Near(box.LinearVelocity, v, 1e-5f, "no gravity: constant velocity");
        }
    }

    private static void TestBodySettersAndForces()
    {
        using (var world = new World())
        {
            world.Gravity = Vec3.Zero;
            BodyDef def = BodyDef.Default();
            def.Type = BodyType.Dynamic;
            def.UserData = 0xDEADBEEFCAFEUL;
            def.AllowSleep = false;
            Body body = world.CreateBody(def);
            body.CreateSphere(new Sphere(Vec3.Zero, 0.5f));
            Equal(body.UserData, 0xDEADBEEFCAFEUL, "user data");
            var t = new Transform(new Vec3(1f, 2f, 3f), Quat.Identity);
            body.Transform = t;
            Equal(body.Transform, t, "transform set");
            body.LinearVelocity = new Vec3(1f, 0f, 0f);
            body.AngularVelocity = new Vec3(0f, 2f, 0f);
            Equal(body.LinearVelocity, new Vec3(1f, 0f, 0f), "linear velocity set");
            Equal(body.AngularVelocity, new Vec3(0f, 2f, 0f), "angular velocity set");
            body.LinearVelocity = Vec3.Zero;
            body.AngularVelocity = Vec3.Zero;
            float m = body.Mass;
            body.ApplyLinearImpulse(new Vec3(0f, m * 2f, 0f));
            world.Step(Dt);
            Near(body.LinearVelocity.Y, 2f, 1e-4f, "impulse / mass");
            body.LinearVelocity = Vec3.Zero;
            body.ApplyForce(new Vec3(m * 60f, 0f, 0f));
            world.Step(Dt);
            Near(body.LinearVelocity.X, 1f, 1e-4f, "force · dt / mass");
            body.LinearVelocity = Vec3.Zero;
            body.ApplyForceAtPoint(new Vec3(m, 0f, 0f), body.CenterOfMass + new Vec3(0f, 1f, 0f));
            body.ApplyTorque(new Vec3(0f, 1f, 0f));
            body.ApplyAngularImpulse(new Vec3(0f, 0f, 1f));
            body.ApplyImpulseAtPoint(new Vec3(0f, 0f, 1f), body.CenterOfMass);
            world.Step(Dt);
            Ensure(body.AngularVelocity.Length > 0f, "torques and off-centre forces spin it");
            body.SetDamping(0.5f, 0.5f);
            Body kinematic = world.CreateBody(BodyType.Kinematic, Vec3.Zero);
            kinematic.SetTargetTransform(new Transform(new Vec3(0f, 1f, 0f), Quat.Identity));
            world.Step(Dt);
            Near(kinematic.Position, new Vec3(0f, 1f, 0f), 1e-4f, "kinematic body reaches its target");
            Equal(kinematic.Mass, 0f, "kinematic mass");
            Shape shape = DynamicBox(world, new Vec3(5f, 0f, 0f), 0.5f).CreateSphere(new Sphere(new Vec3(1f, 0f, 0f), 0.1f));
            Body owner = shape.Body;
            Equal(owner.Position, new Vec3(5f, 0f, 0f), "shape's body");
            float before = owner.Mass;
            shape.Destroy();
            Ensure(owner.Mass < before, "mass recomputed without the shape");
            owner.CreateCapsule(new Capsule(new Vec3(0f, -0.5f, 0f), new Vec3(0f, 0.5f, 0f), 0.2f));
            Ensure(owner.Mass > 1000f, "capsule adds mass");
        }
    }

    private static void TestLockedAxes()
    {
        using (var world = new World())
        {
            BodyDef def = BodyDef.Default();
            def.Type = BodyType.Dynamic;
            def.Transform = new Transform(new Vec3(0f, 5f, 0f), Quat.Identity);
            def.LockedAxes = LockedAxes.LinearZ;
            Body body = world.CreateBody(def);
            body.CreateBox(new Box(Vec3.Zero, Quat.Identity, new Vec3(0.5f, 0.5f, 0.5f)));
            Equal(body.LockedAxes, LockedAxes.LinearZ, "locked axes from the def");
            body.LinearVelocity = new Vec3(1f, 2f, 3f);
            Equal(body.LinearVelocity.Z, 0f, "locked z velocity");
            body.LockedAxes = LockedAxes.LinearY | LockedAxes.Angular;
            Equal(body.LinearVelocity.Y, 0f, "y velocity zeroed at once");
            for (int i = 0; i < 30; i++) world.Step(Dt);
            Equal(body.Position.Y, 5f, "locked in y: it floats");
            Equal(body.AngularVelocity.X, 0f, "no spin");
            Fails(Result.InvalidArgument, () => body.LockedAxes = (LockedAxes)64, "unknown lock bit");
            Equal(body.LockedAxes, LockedAxes.LinearY | LockedAxes.Angular, "unchanged after the error");
        }
    }

    private static void TestRuntimeSetters()
    {
        using (var world = new World())
        {
            Ground(world);
            Body body = DynamicBox(world, new Vec3(0f, 5f, 0f), 0.5f);
            Shape shape = body.CreateSphere(new Sphere(Vec3.Zero, 0.25f));
            float m0 = body.Mass;
            shape.Density = 0f;
            Equal(shape.Density, 0f, "density set");
            Ensure(body.Mass < m0, "a massless sphere lowers the mass");
            shape.SetFriction(0.75f, 0.25f);
            float fs, fd;
            shape.GetFriction(out fs, out fd);
            Equal(fs, 0.75f, "static friction");
            Equal(fd, 0.25f, "dynamic friction");
            shape.Restitution = 0.5f;
            shape.RollingResistance = 0.25f;
            shape.TorsionalFriction = 0.125f;
            shape.UserData = 42UL;
            Equal(shape.Restitution, 0.5f, "restitution");
            Equal(shape.RollingResistance, 0.25f, "rolling resistance");
            Equal(shape.TorsionalFriction, 0.125f, "torsional friction");
            Equal(shape.UserData, 42UL, "shape user data");
            Fails(Result.InvalidArgument, () => shape.Density = -1f, "negative density");
            Fails(Result.InvalidArgument, () => shape.SetFriction(float.NaN, 0f), "NaN friction");
            Equal(shape.Density, 0f, "density unchanged");

            body.GravityScale = 0f;
            Equal(body.GravityScale, 0f, "gravity scale");
            for (int i = 0; i < 30; i++) world.Step(Dt);
            Equal(body.Position.Y, 5f, "gravity scale 0 floats");
            Fails(Result.InvalidArgument, () => body.GravityScale = float.PositiveInfinity, "infinite gravity scale");
            body.MassData = new MassData(4f, Vec3.Zero, new Vec3(2f, 4f, 8f));
            Equal(body.MassData.Mass, 4f, "mass override");
            body.ApplyLinearImpulse(new Vec3(2f, 0f, 0f));
            Equal(body.LinearVelocity.X, 0.5f, "dv = J/m");
            Fails(Result.InvalidArgument, () => body.MassData = new MassData(0f, Vec3.Zero, new Vec3(1f, 1f, 1f)), "zero mass");
            body.ResetMassData();
            Near(body.Mass, 1000f, 1e-2f, "mass from the shapes again");

            body.Type = BodyType.Static;
            Equal(body.Type, BodyType.Static, "type set");
            Equal(body.Mass, 0f, "static mass");
            Fails(Result.InvalidArgument, () => body.Type = (BodyType)9, "bad type code");
            body.Type = BodyType.Dynamic;
            body.GravityScale = 1f;
            Ensure(body.Enabled, "enabled at creation");
            body.Enabled = false;
            Ensure(!body.Enabled, "disabled");
            float y = body.Position.Y;
            for (int i = 0; i < 30; i++) world.Step(Dt);
            Equal(body.Position.Y, y, "a disabled body stays");
            body.Enabled = true;
            for (int i = 0; i < 240; i++) world.Step(Dt);
            Near(body.Position.Y, 0.5f, 0.01f, "enabled, it falls to the ground");
        }
    }

    private sealed class DrawCounter : IDebugDrawer
    {
        public int Segments, Polygons, Spheres, Capsules, Transforms, Points;
        public uint SphereColor;
        public bool Throw;
        public void Segment(Vec3 a, Vec3 b, uint color) { Segments++; }
        public void Polygon(Vec3[] vertices, uint color) { Polygons++; if (vertices.Length < 3) throw new Exception("short polygon"); }
        public void Sphere(Vec3 center, float radius, uint color) { Spheres++; SphereColor = color; if (Throw) throw new InvalidOperationException("boom"); }
        public void Capsule(Vec3 a, Vec3 b, float radius, uint color) { Capsules++; }
        public void Transform(Transform t) { Transforms++; }
        public void Point(Vec3 p, float size, uint color) { Points++; }
    }

    private static void TestDebugDraw()
    {
        using (var world = new World())
        {
            Ground(world);
            Body box = DynamicBox(world, new Vec3(0f, 0.5f, 0f), 0.5f);
            Body ball = DynamicSphere(world, new Vec3(3f, 0.5f, 0f), 0.5f);
            var c = new DrawCounter();
            world.Draw(c);
            Equal(c.Polygons, 7, "plane patch and six box faces");
            Equal(c.Spheres, 1, "one sphere");
            Equal(c.SphereColor, 0xE68C33FFu, "awake colour");
            for (int i = 0; i < 30; i++) world.Step(Dt);
            c = new DrawCounter();
            world.Draw(c, shapes: false, aabbs: true, centersOfMass: true);
            Equal(c.Segments, 24, "two boxes of 12 segments");
            Equal(c.Transforms, 2, "two centres of mass");
            ball.IsAwake = false;
            c = new DrawCounter();
            world.Draw(c);
            Equal(c.SphereColor, 0x8C7359FFu, "sleeping colour");
            c = new DrawCounter { Throw = true };
            Throws<InvalidOperationException>(() => world.Draw(c), "a drawer's exception is rethrown");
            DebugDraw bad = DebugDraw.Default();
            bad.DrawShapes = 2;
            Fails(Result.InvalidArgument, () => world.Draw(bad), "flag 2");
            world.Step(Dt); // not left locked
            Ensure(box.Mass > 0f, "still usable");
        }
    }

    private static void TestBulkTransformsEqualSingleReads()
    {
        using (var world = new World())
        {
            Ground(world);
            var ids = new BodyId[20];
            for (int i = 0; i < ids.Length; i++)
            {
                Body b = i % 2 == 0
                    ? DynamicBox(world, new Vec3(i * 0.3f, 1f + i, 0f), 0.25f)
                    : DynamicSphere(world, new Vec3(i * 0.3f, 1f + i, 0.1f), 0.25f);
                ids[i] = b.Id;
            }
            Run(world, 50);
            var transforms = new Transform[ids.Length];
            world.GetTransforms(ids, transforms);
            for (int i = 0; i < ids.Length; i++)
            {
                Equal(transforms[i], world.GetBody(ids[i]).Transform, "bulk transform " + i);
            }
            var partial = new Transform[ids.Length];
            world.GetTransforms(ids, partial, 5);
            Equal(partial[4], transforms[4], "first 5");
            Equal(partial[5], default(Transform), "nothing past count");
            Throws<ArgumentOutOfRangeException>(() => world.GetTransforms(ids, new Transform[3]), "results too short");
        }
    }

    // ---- errors -------------------------------------------------------------------------------

    private static void TestErrorPaths()
    {
        using (var world = new World())
        using (var other = new World())
        {
            Ground(world);
            Body box = DynamicBox(world, new Vec3(0f, 1f, 0f), 0.5f);
            Body doomed = DynamicBox(world, new Vec3(3f, 1f, 0f), 0.5f);
            BodyId stale = doomed.Id;
            doomed.Destroy();
            HearthException e = Fails(Result.InvalidId, () => { var p = doomed.Position; }, "stale id after destroy");
            Equal(e.Function, "hearth_body_get_transform", "failing function named");
            Ensure(e.Detail.Contains("body"), "detail names the body: " + e.Detail);
            Fails(Result.InvalidId, () => doomed.Destroy(), "destroy twice");
            Fails(Result.InvalidId, () => world.GetBody(BodyId.Null).ApplyForce(Vec3.Zero), "null id");
            Fails(Result.InvalidId, () => { var p = other.GetBody(box.Id).Position; }, "id from another world");
            Fails(Result.InvalidId, () => world.GetTransforms(new[] { box.Id, stale }, new Transform[2]), "bulk read with a stale id");
            Equal(Native.LastErrorMessage().Length > 0, true, "last error message kept");

            // NaN and friends: InvalidArgument, and nothing changes.
            uint bodies = world.Counters.BodyCount;
            BodyDef def = BodyDef.Default();
            def.Type = BodyType.Dynamic;
            def.Transform.Position = new Vec3(float.NaN, 0f, 0f);
            Fails(Result.InvalidArgument, () => world.CreateBody(def), "NaN position");
            def = BodyDef.Default();
            def.Transform.Rotation = new Quat(0f, 0f, 0f, 0f);
            Fails(Result.InvalidArgument, () => world.CreateBody(def), "zero quaternion");
            def = BodyDef.Default();
            def.AllowSleep = new Flag(2);
            Fails(Result.InvalidArgument, () => world.CreateBody(def), "flag byte 2");
            def = BodyDef.Default();
            def.Type = (BodyType)7;
            Fails(Result.InvalidArgument, () => world.CreateBody(def), "unknown body type");
            Fails(Result.InvalidArgument, () => world.CreateBody(new BodyDef()), "def not from Default()");
            Equal(world.Counters.BodyCount, bodies, "no body created by failing calls");

            Vec3 v = box.LinearVelocity;
            Transform t = box.Transform;
            Fails(Result.InvalidArgument, () => box.LinearVelocity = new Vec3(float.NaN, 0f, 0f), "NaN velocity");
            Fails(Result.InvalidArgument, () => box.ApplyForce(new Vec3(0f, float.PositiveInfinity, 0f)), "infinite force");
            Fails(Result.InvalidArgument, () => box.Transform = new Transform(new Vec3(0f, float.NaN, 0f), Quat.Identity), "NaN transform");
            Fails(Result.InvalidArgument, () => box.SetDamping(-1f, 0f), "negative damping");
            Equal(box.LinearVelocity, v, "velocity unchanged");
            Equal(box.Transform, t, "transform unchanged");
            Fails(Result.InvalidArgument, () => box.CreateSphere(new Sphere(Vec3.Zero, -1f)), "negative radius");
            Fails(Result.InvalidArgument, () => box.CreatePlane(new Plane(new Vec3(0f, 1f, 0f), 0f)), "plane on a dynamic body");
            Fails(Result.InvalidArgument, () => world.Step(float.NaN), "NaN dt");
            Fails(Result.InvalidArgument, () => world.Step(-1f), "negative dt");

            WorldDef wd = WorldDef.Default();
            wd.Substeps = 0;
            Fails(Result.InvalidArgument, () => new World(wd), "world with 0 substeps");

            // NULL pointers can only come through the raw layer.
            Equal(Native.hearth_world_get_transforms(world.Handle, null, (UIntPtr)3, null), Result.NullPointer, "NULL arrays");
            UIntPtr count;
            Equal(Native.hearth_world_get_broken_joints(world.Handle, null, (UIntPtr)4, out count), Result.NullPointer, "NULL array with a capacity");
            var contact = new GeneratedContact();
            Equal(Native.hearth_contact_sink_add(IntPtr.Zero, ref contact), Result.NullPointer, "NULL sink");
        }
    }

    // ---- SafeHandle and lifetime ------------------------------------------------------------

    // In its own method so no local keeps a world reachable from the caller's frame.
    [System.Runtime.CompilerServices.MethodImpl(System.Runtime.CompilerServices.MethodImplOptions.NoInlining)]
    private static WeakReference[] MakeUndisposedWorlds(int n)
    {
        var refs = new WeakReference[n];
        for (int i = 0; i < n; i++)
        {
            var w = new World();
            DynamicBox(w, Vec3.Zero, 0.5f);
            w.Step(Dt);
            refs[i] = new WeakReference(w.Handle, true);
        }
        return refs;
    }

    private static void TestDisposal()
    {
        var world = new World();
        Body box = DynamicBox(world, Vec3.Zero, 0.5f);
        WorldHandle handle = world.Handle;
        Ensure(!handle.IsInvalid && !handle.IsClosed, "live handle");
        world.Dispose();
        Ensure(world.IsDisposed && handle.IsClosed, "disposed handle is closed");
        Throws<ObjectDisposedException>(() => world.Step(Dt), "Step after Dispose");
        Throws<ObjectDisposedException>(() => { var p = box.Position; }, "body of a disposed world");
        Throws<ObjectDisposedException>(() => Native.hearth_world_step(handle, Dt), "raw call with the closed handle");
        world.Dispose(); // twice is fine

        // Worlds nobody disposes are destroyed by the handle's finalizer: a long weak reference
        // (one that survives finalization) to each handle is dead only once the finalizer ran
        // ReleaseHandle (hearth_world_destroy) and the handle was reclaimed.
        // Made on a thread that has ended, so Mono's conservative scan of this thread's stack
        // cannot find a stale pointer to the last one.
        WeakReference[] handles = null;
        var maker = new System.Threading.Thread(() => { handles = MakeUndisposedWorlds(50); });
        maker.Start();
        maker.Join();
        // The collector and the finalizer thread run when they will: give them up to 100 rounds.
        int alive = handles.Length;
        for (int round = 0; round < 100 && alive > 0; round++)
        {
            GC.Collect();
            GC.WaitForPendingFinalizers();
            GC.Collect();
            alive = 0;
            foreach (var h in handles) alive += h.IsAlive ? 1 : 0;
            if (alive > 0) System.Threading.Thread.Sleep(10);
        }
        Ensure(alive == 0, "finalizers destroyed every undisposed world (" + alive + " of 50 left)");

        // A failed creation leaves no handle behind.
        WorldDef bad = WorldDef.Default();
        bad.Gravity = new Vec3(float.NaN, 0f, 0f);
        Fails(Result.InvalidArgument, () => new World(bad), "NaN gravity");
        bad = WorldDef.Default();
        bad.MaxAngularSpeed = 0f;
        Fails(Result.InvalidArgument, () => new World(bad), "zero max angular speed");

        // The angular speed limit: a set velocity above it is refused, an impulse is capped.
        WorldDef limited = WorldDef.Default();
        limited.MaxAngularSpeed = 5f;
        using (var limitedWorld = new World(limited))
        {
            Body spun = DynamicBox(limitedWorld, new Vec3(0f, 3f, 0f), 0.5f);
            HearthException e = Fails(Result.InvalidArgument, () => spun.AngularVelocity = new Vec3(0f, 6f, 0f), "angular velocity above the limit");
            Ensure(e.Message.Contains("max_angular_speed"), "the message names the limit");
            spun.ApplyAngularImpulse(new Vec3(0f, 1.0e6f, 0f));
            Near(spun.AngularVelocity, new Vec3(0f, 5f, 0f), 1e-4f, "angular velocity capped at the limit");
        }
    }

    // ---- threads and the state hash -------------------------------------------------------------

    private static ulong PileHash(WorldDef def)
    {
        using (var w = new World(def))
        {
            Ground(w);
            for (int i = 0; i < 200; i++)
            {
                var p = new Vec3((i % 10) * 1.05f - 5f, 0.5f + (i / 10 % 4) * 1.1f, (i / 40) * 1.05f);
                if (i % 2 == 0) DynamicSphere(w, p, 0.5f); else DynamicBox(w, p, 0.5f);
            }
            ulong before = w.StateHash;
            Run(w, 30);
            Ensure(w.StateHash != before, "the pile moved");
            return w.StateHash;
        }
    }

    // A managed job system: each task's ranges are dealt to two System.Threading threads,
    // which run them last first; FinishTask joins them.
    private static int enqueued;
    private static IntPtr ManagedEnqueue(IntPtr task, uint count, uint minRange, IntPtr taskContext, IntPtr userContext)
    {
        enqueued++;
        var run = Marshal.GetDelegateForFunctionPointer<TaskFn>(task);
        uint chunk = Math.Max(minRange, 1u);
        uint chunks = (count + chunk - 1) / chunk;
        var threads = new System.Threading.Thread[2];
        for (uint t = 0; t < 2; t++)
        {
            uint worker = t;
            threads[t] = new System.Threading.Thread(() =>
            {
                for (uint k = chunks; k-- > 0;)
                {
                    if (k % 2 != worker) continue;
                    uint start = k * chunk;
                    run(start, Math.Min(start + chunk, count), worker, taskContext);
                }
            });
            threads[t].Start();
        }
        return GCHandle.ToIntPtr(GCHandle.Alloc(threads));
    }

    private static void ManagedFinish(IntPtr userTask, IntPtr userContext)
    {
        var handle = GCHandle.FromIntPtr(userTask);
        foreach (var t in (System.Threading.Thread[])handle.Target) t.Join();
        handle.Free();
    }

    private static readonly EnqueueTaskFn managedEnqueue = ManagedEnqueue;
    private static readonly FinishTaskFn managedFinish = ManagedFinish;

    private static void TestWorkerCountsAndAJobSystemGiveTheSameHash()
    {
        Equal(WorldDef.Default().WorkerCount, 1u, "default worker count");
        ulong one = PileHash(WorldDef.Default());
        Equal(PileHash(WorldDef.Default()), one, "twice in a process");
        WorldDef threaded = WorldDef.Default();
        threaded.WorkerCount = 3;
        Equal(PileHash(threaded), one, "three threads of the world's own");
        WorldDef hosted = WorldDef.Default();
        hosted.WorkerCount = 2;
        hosted.EnqueueTask = Marshal.GetFunctionPointerForDelegate(managedEnqueue);
        hosted.FinishTask = Marshal.GetFunctionPointerForDelegate(managedFinish);
        enqueued = 0;
        Equal(PileHash(hosted), one, "a managed job system on two threads");
        Ensure(enqueued > 0, "the job system was used");
        WorldDef bad = WorldDef.Default();
        bad.WorkerCount = 65;
        HearthException e = Fails(Result.InvalidArgument, () => new World(bad), "65 workers");
        Ensure(e.Message.Contains("worker_count"), "the message names worker_count");
        bad = WorldDef.Default();
        bad.EnqueueTask = hosted.EnqueueTask;
        e = Fails(Result.InvalidArgument, () => new World(bad), "enqueue without finish");
        Ensure(e.Message.Contains("finish_task"), "the message names finish_task");
    }

    // ---- callbacks ----------------------------------------------------------------------------

    private static void TestForceGeneratorMakesABodyHover()
    {
        using (var world = new World())
        {
            Body box = DynamicBox(world, new Vec3(0f, 5f, 0f), 0.5f);
            Body free = DynamicBox(world, new Vec3(3f, 5f, 0f), 0.5f);
            int calls = 0;
            float seenDt = 0f;
            Generator hover = world.CreateUserForceGenerator(call =>
            {
                calls++;
                seenDt = call.Dt;
                for (int i = 0; i < call.BodyCount; i++)
                {
                    Body b = call.GetBody(i);
                    b.ApplyForce(new Vec3(0f, b.Mass * 9.81f, 0f));
                }
            });
            hover.AttachBody(box);
            Equal(hover.Type, GeneratorType.UserForce, "generator type");
            uint nb, np;
            hover.GetAttachmentCount(out nb, out np);
            Equal(nb, 1u, "one body attached");
            Equal(world.RegisteredCallbackCount, 1, "callback registered");

            // The world keeps the delegate alive although nothing else refers to it.
            GC.Collect();
            GC.WaitForPendingFinalizers();
            Run(world, 120);
            Equal(calls, 120, "called once per step");
            Equal(seenDt, Dt, "dt passed through");
            Near(box.Position, new Vec3(0f, 5f, 0f), 1e-3f, "hovering");
            Ensure(free.Position.Y < 0f, "the other box fell");

            hover.DetachBody(box);
            Run(world, 10);
            Ensure(box.Position.Y < 4.9f, "falls once detached");
            Equal(calls, 130, "still called with no bodies");
            hover.Destroy();
            Equal(world.RegisteredCallbackCount, 0, "callback released by destroy");
            Run(world, 5);
            Equal(calls, 130, "not called after destroy");
            Fails(Result.InvalidId, () => hover.Destroy(), "destroy twice");
        }
    }

    private sealed class CallbackBoom : Exception
    {
        public CallbackBoom(string message) : base(message) { }
    }

    private static void ThrowFromHandler(int step)
    {
        throw new CallbackBoom("boom at step " + step);
    }

    private static void TestCallbackExceptionIsRethrownFromStep()
    {
        using (var world = new World())
        {
            Body box = DynamicBox(world, new Vec3(0f, 5f, 0f), 0.5f);
            int steps = 0;
            bool secondRan = false;
            Generator g = world.CreateUserForceGenerator(call =>
            {
                steps++;
                if (steps == 3)
                {
                    ThrowFromHandler(steps);
                }
            });
            world.CreateUserForceGenerator(call => { secondRan = steps == 3; });
            world.Step(Dt);
            world.Step(Dt);
            CallbackBoom e = Throws<CallbackBoom>(() => world.Step(Dt), "exception from the callback");
            Equal(e.Message, "boom at step 3", "original exception");
            Ensure(e.StackTrace.Contains("ThrowFromHandler"), "original stack trace kept: " + e.StackTrace);
            Ensure(secondRan, "the other generators of the step still ran");
            world.Step(Dt);
            Equal(steps, 4, "world keeps stepping after the exception");
            Ensure(box.Position.Y < 5f, "the step that threw was completed");

            // Structural changes from a callback: WORLD_LOCKED, rethrown from Step.
            g.Destroy();
            world.CreateUserForceGenerator(call => call.World.CreateBody(BodyDef.Default()));
            uint before = world.Counters.BodyCount;
            Fails(Result.WorldLocked, () => world.Step(Dt), "create a body inside a callback");
            Equal(world.Counters.BodyCount, before, "no body created");
        }
    }

    private static void TestGeneratorCallIsOnlyValidInsideTheCallback()
    {
        using (var world = new World())
        {
            GeneratorCall saved = null;
            ContactSink savedSink = null;
            world.CreateUserForceGenerator(call => saved = call);
            world.CreateUserContactGenerator((call, sink) => savedSink = sink);
            world.Step(Dt);
            Throws<InvalidOperationException>(() => { var dt = saved.Dt; }, "context after the callback");
            Fails(Result.NullPointer, () => savedSink.Add(new GeneratedContact()), "sink after the callback");
            Equal(saved.Generator.Type, GeneratorType.UserForce, "generator of the call");
        }
    }

    // IL2CPP can hand native code pointers only to static methods marked [MonoPInvokeCallback]:
    // every user generator goes through the two static trampolines, with a GCHandle of its
    // registration as user_data, freed by DestroyGenerator and Dispose.
    private static void TestCallbacksGoThroughStaticTrampolines()
    {
        foreach (string name in new[] { "ForceTrampoline", "ContactTrampoline" })
        {
            MethodInfo method = typeof(World).GetMethod(name, BindingFlags.NonPublic | BindingFlags.Static);
            Ensure(method != null, name + " is a static method of World");
            bool marked = false;
            foreach (object attribute in method.GetCustomAttributes(false))
            {
                marked |= attribute.GetType().Name == "MonoPInvokeCallbackAttribute";
            }
            Ensure(marked, name + " carries [MonoPInvokeCallback]");
        }
        Ensure(World.ForceCallbackPointer != IntPtr.Zero && World.ContactCallbackPointer != IntPtr.Zero, "trampoline pointers");
        Ensure(World.ForceCallbackPointer != World.ContactCallbackPointer, "one trampoline per kind");

        int before = World.LiveCallbackHandles;
        int forceCalls = 0, contactCalls = 0;
        var a = new World();
        var b = new World();
        Generator fa = a.CreateUserForceGenerator(call => forceCalls += 1);
        b.CreateUserForceGenerator(call => forceCalls += 100);
        b.CreateUserContactGenerator((call, sink) => contactCalls++);
        Equal(World.LiveCallbackHandles, before + 3, "one GCHandle per user generator");
        GC.Collect();
        GC.WaitForPendingFinalizers();
        a.Step(Dt);
        b.Step(Dt);
        Equal(forceCalls, 101, "each world's handler reached through user_data");
        Equal(contactCalls, 1, "contact handler reached");
        fa.Destroy();
        Equal(World.LiveCallbackHandles, before + 2, "DestroyGenerator frees the handle");
        a.Dispose();
        b.Dispose();
        Equal(World.LiveCallbackHandles, before, "Dispose frees the rest");
        // A generator that cannot be made leaves no handle behind.
        var c = new World();
        Fails(Result.InvalidArgument, () => c.CreateUserContactGenerator((call, sink) => { }, 2000000u), "capacity too large");
        Equal(World.LiveCallbackHandles, before, "no handle leaked by a refused generator");
        c.Dispose();
        Throws<ObjectDisposedException>(() => c.CreateUserForceGenerator(call => { }), "disposed world");
        Equal(World.LiveCallbackHandles, before, "no handle leaked on a disposed world");
    }

    // Dispose from inside a callback: the native world outlives the running step (the
    // SafeHandle is in use by it) and is destroyed when the step returns.
    private static void TestDisposeInsideACallback()
    {
        var world = new World();
        Body box = DynamicBox(world, new Vec3(0f, 5f, 0f), 0.5f);
        int calls = 0;
        Generator g = world.CreateUserForceGenerator(call =>
        {
            calls++;
            call.World.Dispose();
        });
        g.AttachBody(box);
        WorldHandle handle = world.Handle;
        world.Step(Dt);
        Equal(calls, 1, "callback ran");
        Ensure(world.IsDisposed, "disposed");
        Ensure(handle.IsClosed, "native world destroyed once the step returned");
        Equal(world.RegisteredCallbackCount, 0, "callbacks released after the step");
        Throws<ObjectDisposedException>(() => world.Step(Dt), "no more steps");
        Equal(World.LiveCallbackHandles, 0, "the callback's GCHandle freed after the step");

        // An exception after the Dispose in the same callback still reaches the caller.
        var second = new World();
        second.CreateUserForceGenerator(call =>
        {
            call.World.Dispose();
            call.World.Gravity = Vec3.Zero;
        });
        Throws<ObjectDisposedException>(() => second.Step(Dt), "use after Dispose inside the callback");
    }

    // A contact generator holds a sphere on an invisible floor at y = 1.
    private static void TestContactGeneratorMakesAFloor()
    {
        using (var world = new World())
        {
            Body ball = DynamicSphere(world, new Vec3(0f, 3f, 0f), 0.5f);
            uint capacity = 0, added = 0;
            Generator floor = world.CreateUserContactGenerator((call, sink) =>
            {
                capacity = sink.Capacity;
                for (int i = 0; i < call.BodyCount; i++)
                {
                    Body b = call.GetBody(i);
                    float bottom = b.Position.Y - 0.5f;
                    if (bottom < 1.1f)
                    {
                        var c = new GeneratedContact();
                        c.BodyB = b.Id; // side A: the world
                        c.Point = new Vec3(b.Position.X, bottom, b.Position.Z);
                        c.Normal = new Vec3(0f, 1f, 0f);
                        c.Penetration = 1f - bottom;
                        c.Friction = 0.5f;
                        sink.Add(c);
                    }
                }
                added = sink.Count;
            }, 4);
            floor.AttachBody(ball);
            Run(world, 180);
            Equal(capacity, 4u, "sink capacity from the def");
            Equal(added, 1u, "one contact per step");
            Near(ball.Position.Y, 1.5f, 0.02f, "ball rests on the generated floor");
            Equal(floor.Type, GeneratorType.UserContact, "type");
        }
    }

    // ---- built-in generators ------------------------------------------------------------------

    private static void TestBuiltInGenerators()
    {
        using (var world = new World())
        {
            Body box = DynamicBox(world, new Vec3(0f, 10f, 0f), 0.5f);
            GravityGeneratorDef gd = GravityGeneratorDef.Default();
            gd.Acceleration = new Vec3(0f, 9.81f, 0f);
            Generator antigravity = world.CreateGravityGenerator(gd);
            antigravity.AttachBody(box);
            Run(world, 30);
            Near(box.Position, new Vec3(0f, 10f, 0f), 1e-4f, "extra gravity cancels world gravity");
            Fails(Result.InvalidArgument, () => antigravity.AttachBody(box), "attached twice");
            antigravity.Destroy();

            var created = new List<Generator>
            {
                world.CreateDragGenerator(DragGeneratorDef.Default()),
                world.CreateSpringGenerator(SpringGeneratorDef.Default()),
                world.CreateBungeeGenerator(SpringGeneratorDef.Default()),
                world.CreateStiffSpringGenerator(StiffSpringGeneratorDef.Default()),
                world.CreateBuoyancyGenerator(BuoyancyGeneratorDef.Default()),
                world.CreateExplosionGenerator(ExplosionGeneratorDef.Default()),
            };
            var types = new[] { GeneratorType.Drag, GeneratorType.Spring, GeneratorType.Bungee, GeneratorType.StiffSpring, GeneratorType.Buoyancy, GeneratorType.Explosion };
            for (int i = 0; i < types.Length; i++)
            {
                Equal(created[i].Type, types[i], "generator type " + i);
            }
            RodGeneratorDef rod = RodGeneratorDef.Default();
            rod.A = LinkEnd.OnBody(box.Id, Vec3.Zero);
            rod.B = LinkEnd.AtWorldPoint(new Vec3(0f, 12f, 0f));
            rod.Length = 2f;
            Equal(world.CreateRodGenerator(rod).Type, GeneratorType.Rod, "rod");
            CableGeneratorDef cable = CableGeneratorDef.Default();
            cable.A = LinkEnd.OnBody(box.Id, Vec3.Zero);
            cable.B = LinkEnd.AtWorldPoint(new Vec3(0f, 12f, 0f));
            cable.MaxLength = 3f;
            Generator cableGen = world.CreateCableGenerator(cable);
            Fails(Result.InvalidArgument, () => cableGen.AttachBody(box), "cables take no attachments");
            DragGeneratorDef bad = DragGeneratorDef.Default();
            bad.K1 = -1f;
            Fails(Result.InvalidArgument, () => world.CreateDragGenerator(bad), "negative drag");
            Run(world, 60);
            Near((box.Position - new Vec3(0f, 12f, 0f)).Length, 2f, 0.01f, "rod holds the box 2 m from its anchor");
        }
    }

    // ---- joints -------------------------------------------------------------------------------

    private static void TestJoints()
    {
        using (var world = new World())
        {
            Body bob = DynamicSphere(world, new Vec3(2f, 5f, 0f), 0.2f);
            DistanceJointDef dd = DistanceJointDef.Default();
            dd.Base.BodyA = bob.Id;
            dd.Base.FrameB = new Transform(new Vec3(0f, 5f, 0f), Quat.Identity); // world anchor
            dd.Length = 2f;
            Joint pendulum = world.CreateDistanceJoint(dd);
            Equal(pendulum.Type, JointType.Distance, "distance type");
            Body a, b;
            pendulum.GetBodies(out a, out b);
            Equal(a.Id, bob.Id, "body A");
            Ensure(b.Id.IsNull, "body B is the world");
            Run(world, 120);
            Near((bob.Position - new Vec3(0f, 5f, 0f)).Length, 2f, 0.02f, "pendulum keeps its length");
            Ensure(bob.Position.Y < 4.5f, "pendulum swung down");
            Vec3 force, torque;
            pendulum.GetForce(out force, out torque);
            Ensure(force.Length > 0f, "joint force read");
            pendulum.SetSpring(true, 2f, 0.5f);
            bool on;
            float hz, ratio;
            pendulum.GetSpring(out on, out hz, out ratio);
            Ensure(on && hz == 2f && ratio == 0.5f, "distance spring round trip");

            Body wheel = DynamicBox(world, new Vec3(10f, 5f, 0f), 0.5f);
            HingeJointDef hd = HingeJointDef.Default();
            hd.Base.BodyA = wheel.Id;
            hd.Base.FrameB = new Transform(new Vec3(10f, 5f, 0f), Quat.Identity);
            Joint hinge = world.CreateHingeJoint(hd);
            hinge.SetMotor(true, 3f, 1e5f);
            float speed, max, lower, upper;
            hinge.GetMotor(out on, out speed, out max);
            Ensure(on && speed == 3f && max == 1e5f, "motor round trip");
            hinge.SetLimits(true, -1f, 1f);
            hinge.GetLimits(out on, out lower, out upper);
            Ensure(on && lower == -1f && upper == 1f, "limits round trip");
            hinge.SetLimits(false, -1f, 1f);
            Run(world, 30);
            // The motor speed is B's (the world's) relative to A: the wheel turns at -3 rad/s.
            Near(wheel.AngularVelocity.Z, -3f, 0.05f, "motor drives the wheel about Z");
            Near(wheel.Position, new Vec3(10f, 5f, 0f), 0.01f, "hinge holds the wheel");
            Fails(Result.InvalidArgument, () => hinge.SetConeLimit(true, 0.5f), "cone limit on a hinge");
            Fails(Result.InvalidArgument, () => hinge.SetLimits(true, 1f, -1f), "lower > upper");

            BallJointDef bd = BallJointDef.Default();
            bd.Base.BodyA = DynamicBox(world, new Vec3(20f, 5f, 0f), 0.5f).Id;
            bd.Base.FrameB = new Transform(new Vec3(20f, 6f, 0f), Quat.Identity);
            bd.Base.FrameA = new Transform(new Vec3(0f, 1f, 0f), Quat.Identity);
            Joint ball = world.CreateBallJoint(bd);
            ball.SetConeLimit(true, 0.3f);
            float angle;
            ball.GetConeLimit(out on, out angle);
            Ensure(on && angle == 0.3f, "cone round trip");

            FixedJointDef fd = FixedJointDef.Default();
            fd.Base.BodyA = DynamicBox(world, new Vec3(30f, 5f, 0f), 0.5f).Id;
            fd.Base.FrameB = new Transform(new Vec3(30f, 5f, 0f), Quat.Identity);
            fd.Base.BreakForce = 1f; // the box weighs ~9810 N: it breaks at once
            Joint weak = world.CreateFixedJoint(fd);
            SliderJointDef sd = SliderJointDef.Default();
            sd.Base.BodyA = DynamicBox(world, new Vec3(40f, 5f, 0f), 0.5f).Id;
            sd.Base.FrameB = new Transform(new Vec3(40f, 5f, 0f), Quat.Identity);
            Joint slider = world.CreateSliderJoint(sd);
            Equal(slider.Type, JointType.Slider, "slider type");
            world.Step(Dt);
            Ensure(weak.IsBroken, "weak joint broke");
            JointId[] broken = world.GetBrokenJoints();
            Equal(broken.Length, 1, "one broken joint");
            Equal(broken[0], weak.Id, "the weak one");
            Equal(world.GetBrokenJoints(null), 1, "count only");
            weak.Destroy();
            Fails(Result.InvalidId, () => { var x = weak.Type; }, "destroyed joint");

            HingeJointDef badHinge = HingeJointDef.Default();
            badHinge.Base.BodyA = wheel.Id;
            badHinge.Lower = float.NaN;
            Fails(Result.InvalidArgument, () => world.CreateHingeJoint(badHinge), "NaN hinge limit");
        }
    }

    // ---- particles ----------------------------------------------------------------------------

    private static void TestParticles()
    {
        using (var world = new World())
        {
            Ground(world);
            ParticleDef pd = ParticleDef.Default();
            pd.Position = new Vec3(0f, 2f, 0f);
            pd.UserData = 77;
            Particle p = world.CreateParticle(pd);
            Equal(p.UserData, 77UL, "particle user data");
            Run(world, 120);
            Near(p.Position.Y, pd.Radius, 0.01f, "particle rests on the ground at its radius");
            p.Velocity = new Vec3(1f, 0f, 0f);
            Equal(p.Velocity, new Vec3(1f, 0f, 0f), "velocity set");
            p.Position = new Vec3(0f, 3f, 0f);
            Equal(p.Position, new Vec3(0f, 3f, 0f), "position set");
            p.ApplyImpulse(new Vec3(0f, 1f, 0f));
            p.ApplyForce(new Vec3(0f, 1f, 0f));
            p.IsAwake = true;
            Ensure(p.IsAwake, "awake");
            Fails(Result.InvalidArgument, () => p.Position = new Vec3(float.NaN, 0f, 0f), "NaN particle position");

            BurstDef burst = BurstDef.Default();
            burst.Position = new Vec3(0f, 5f, 0f);
            burst.Count = 32;
            burst.LifetimeMin = 0.2f;
            burst.LifetimeMax = 0.4f;
            burst.Particle.UserData = 5;
            ParticleId[] ids = world.EmitBurst(burst);
            Equal(ids.Length, 32, "burst ids");
            Equal(world.ParticleCount, 33, "particle count");
            Fails(Result.BufferTooSmall, () => world.EmitBurst(burst, new ParticleId[4]), "burst ids array too small");
            Equal(world.ParticleCount, 33, "nothing emitted on error");

            Run(world, 3);
            var all = new ParticleId[64];
            var positions = new Vec3[64];
            var velocities = new Vec3[64];
            int n = world.GetParticles(all, positions, velocities);
            Equal(n, 33, "bulk particles");
            for (int i = 0; i < n; i++)
            {
                Particle q = world.GetParticle(all[i]);
                Equal(positions[i], q.Position, "bulk position " + i);
                Equal(velocities[i], q.Velocity, "bulk velocity " + i);
            }
            Equal(world.GetParticles(null, positions, null), 33, "positions only");
            Equal(world.GetParticles(null, null, null), 33, "count only");
            Fails(Result.BufferTooSmall, () => world.GetParticles(new ParticleId[3], null, null), "ids array too small");
            var byId = new Vec3[ids.Length];
            world.GetParticlePositions(ids, byId);
            for (int i = 0; i < ids.Length; i++)
            {
                Equal(byId[i], world.GetParticle(ids[i]).Position, "position by id " + i);
            }

            Generator drag = world.CreateDragGenerator(DragGeneratorDef.Default());
            drag.AttachParticles(ids);
            uint nb, np;
            drag.GetAttachmentCount(out nb, out np);
            Equal(np, 32u, "particles attached at once");
            drag.DetachParticle(ids[0]);
            drag.AttachParticle(p.Id);
            drag.DetachParticle(p);

            int expired = 0;
            for (int i = 0; i < 30; i++)
            {
                world.Step(Dt);
                foreach (ExpiredParticle e in world.GetExpiredParticles())
                {
                    Equal(e.UserData, 5UL, "expired user data");
                    expired++;
                }
            }
            Equal(expired, 32, "every burst particle expired and was reported");
            Equal(world.ParticleCount, 1, "only the long-lived particle is left");
            Fails(Result.InvalidId, () => { var x = world.GetParticle(ids[0]).Position; }, "expired particle id is stale");
            drag.GetAttachmentCount(out nb, out np);
            Equal(np, 0u, "expired particles detached");
            world.SetParticleIterations(4, 2);
            Fails(Result.InvalidArgument, () => world.SetParticleIterations(0, 2), "0 iterations");
            p.Destroy();
            Equal(world.ParticleCount, 0, "destroyed");
        }
    }

    // ---- soft bodies --------------------------------------------------------------------------

    private static void TestSoftBodies()
    {
        using (var world = new World())
        {
            Ground(world);
            SoftBodyDef def = SoftBodyDef.Default();
            def.Transform.Position = new Vec3(0f, 2f, 0f);
            def.Pressure = 10f;
            def.UserData = 9;
            SoftBody ball = world.CreateSoftBodyIcosphere(def, 0.5f, 1);
            Equal(ball.VertexCount, 42, "icosphere vertices");
            Equal(ball.TriangleCount, 80, "icosphere triangles");
            Equal(ball.UserData, 9UL, "soft user data");
            Near(ball.Mass, 1f, 1e-5f, "soft mass");
            Near(ball.Pressure, 10f, 0f, "pressure");
            Ensure(ball.RestVolume > 0.3f && ball.RestVolume < 4.2f * 0.125f, "rest volume of a r=0.5 icosphere");
            Run(world, 300);
            Near(ball.Center.Y, 0.5f, 0.05f, "soft ball (bouncing, then rolling) ends on the ground");
            Ensure(ball.Volume > 0.5f * ball.RestVolume, "pressure keeps its volume");

            var positions = new Vec3[ball.VertexCount];
            Equal(ball.GetPositions(positions), 42, "bulk positions count");
            for (uint i = 0; i < positions.Length; i++)
            {
                Equal(positions[i], ball.GetVertexPosition(i), "bulk vertex " + i);
            }
            Vec3[] normals = ball.GetNormals();
            foreach (Vec3 nrm in normals)
            {
                Near(nrm.Length, 1f, 1e-4f, "unit normal");
            }
            uint[] indices = ball.GetIndices();
            Equal(indices.Length, 240, "3 indices per triangle");
            var small = new Vec3[3];
            Fails(Result.BufferTooSmall, () => ball.GetPositions(small), "positions array too small");
            Equal(small[0], Vec3.Zero, "nothing written on error");
            Equal(ball.GetPositions(null), 42, "count only");
            Fails(Result.InvalidArgument, () => ball.GetVertexPosition(42), "vertex out of range");
            ball.GetVertexVelocity(0);
            ball.Pressure = 20f;
            Equal(ball.Pressure, 20f, "pressure set");
            Fails(Result.InvalidArgument, () => ball.Pressure = -1f, "negative pressure");
            ball.ApplyImpulse(0, new Vec3(0f, 0.01f, 0f));
            ball.ApplyImpulseAll(new Vec3(0.1f, 0f, 0f));

            // A cloth pinned by two corners hangs.
            SoftBodyDef cd = SoftBodyDef.Default();
            cd.Transform.Position = new Vec3(5f, 3f, 0f);
            SoftBody cloth = world.CreateSoftBodyCloth(cd, 1f, 1f, 4, 4);
            Equal(cloth.VertexCount, 25, "cloth vertices");
            cloth.PinVertex(0);
            Body hook = world.CreateBody(BodyType.Kinematic, new Vec3(5.5f, 3f, -0.5f));
            cloth.PinVertex(4, hook.Id);
            Ensure(cloth.IsVertexPinned(0) && cloth.IsVertexPinned(4) && !cloth.IsVertexPinned(5), "pins");
            Vec3 corner = cloth.GetVertexPosition(0);
            Run(world, 30); // half a swing: the free edge passes below the pinned one
            Near(cloth.GetVertexPosition(0), corner, 1e-5f, "pinned corner stays");
            Ensure(cloth.GetVertexPosition(24).Y < 2.5f, "free corner swings down");
            cloth.UnpinVertex(4);
            Ensure(!cloth.IsVertexPinned(4), "unpinned");

            SoftBody box = world.CreateSoftBodyBox(SoftBodyDef.Default(), new Vec3(0.5f, 0.5f, 0.5f), 2, 2, 2);
            Equal(box.VertexCount, 27, "soft box vertices");
            var tetra = new[] { new Vec3(0f, 0f, 0f), new Vec3(1f, 0f, 0f), new Vec3(0f, 0f, 1f), new Vec3(0f, 1f, 0f) };
            var tris = new uint[] { 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2 };
            SoftBodyDef md = SoftBodyDef.Default();
            md.Transform.Position = new Vec3(-5f, 1f, 0f);
            SoftBody mesh = world.CreateSoftBodyMesh(md, tetra, tris, new[] { 1f, 2f, 3f, 4f });
            Near(mesh.Mass, 10f, 1e-5f, "per-vertex masses");
            Fails(Result.InvalidArgument, () => world.CreateSoftBodyMesh(md, tetra, new uint[] { 0, 1, 7 }, null), "index out of range");
            Equal(world.SoftBodyCount, 4, "soft body count");
            mesh.Destroy();
            Equal(world.SoftBodyCount, 3, "destroyed");
            Fails(Result.InvalidId, () => { var m = mesh.Mass; }, "destroyed soft body");
        }
    }

    // The settings part of a def (the like-named fields).
    private static SoftBodySettings SettingsOf(SoftBodyDef d)
    {
        var s = new SoftBodySettings();
        s.EdgeCompliance = d.EdgeCompliance;
        s.BendCompliance = d.BendCompliance;
        s.PreserveVolume = d.PreserveVolume;
        s.VolumeCompliance = d.VolumeCompliance;
        s.Pressure = d.Pressure;
        s.Damping = d.Damping;
        s.DeformationDamping = d.DeformationDamping;
        s.Friction = d.Friction;
        s.Restitution = d.Restitution;
        s.VertexRadius = d.VertexRadius;
        s.GravityScale = d.GravityScale;
        s.Substeps = d.Substeps;
        s.Iterations = d.Iterations;
        s.Collide = d.Collide;
        return s;
    }

    private static void TestSoftBodySettings()
    {
        using (var world = new World())
        {
            SoftBody plain = world.CreateSoftBodyCloth(SoftBodyDef.Default(), 1f, 1f, 2, 2);
            Equal(plain.Settings, SettingsOf(SoftBodyDef.Default()), "settings of a default def");

            SoftBodyDef def = SoftBodyDef.Default();
            def.EdgeCompliance = 1e-4f;
            def.BendCompliance = float.PositiveInfinity;
            def.PreserveVolume = true;
            def.VolumeCompliance = 0.01f;
            def.Pressure = 30f;
            def.Damping = 0.25f;
            def.DeformationDamping = 3.5f;
            def.Friction = 0.8f;
            def.Restitution = 0.1f;
            def.VertexRadius = 0.02f;
            def.GravityScale = 0.5f;
            def.Substeps = 12;
            def.Iterations = 4;
            def.Collide = false;
            SoftBody ball = world.CreateSoftBodyIcosphere(def, 0.5f, 1);
            SoftBodySettings s = ball.Settings;
            Equal(s, SettingsOf(def), "settings are the def given at creation");
            Equal(s.Iterations, 4u, "iterations read back");
            Equal(s.DeformationDamping, 3.5f, "deformation damping read back");
            Equal(ball.Pressure, s.Pressure, "the pressure getter agrees");

            // Set, then get returns them.
            s.EdgeCompliance = 0.001f;
            s.BendCompliance = 0.5f;
            s.PreserveVolume = false;
            s.Pressure = 12f;
            s.Damping = 1.5f;
            s.DeformationDamping = 0f;
            s.Friction = 0.125f;
            s.VertexRadius = 0.0625f;
            s.GravityScale = -1f;
            s.Substeps = 64;
            s.Iterations = 16;
            s.Collide = true;
            ball.Settings = s;
            Equal(ball.Settings, s, "set, then get");
            Equal(ball.Pressure, 12f, "the pressure getter sees the new settings");
            ball.Pressure = 7f;
            Equal(ball.Settings.Pressure, 7f, "the settings see the pressure setter");
            s.Pressure = 7f;

            // SetCompliance changes those three and nothing else.
            ball.SetCompliance(0.002f, float.PositiveInfinity, 0.25f);
            SoftBodySettings c = ball.Settings;
            Equal(c.EdgeCompliance, 0.002f, "edge compliance");
            Ensure(float.IsPositiveInfinity(c.BendCompliance), "bend compliance infinity: no bending");
            Equal(c.VolumeCompliance, 0.25f, "volume compliance");
            c.EdgeCompliance = s.EdgeCompliance;
            c.BendCompliance = s.BendCompliance;
            c.VolumeCompliance = s.VolumeCompliance;
            Equal(c, s, "SetCompliance leaves the other settings");
            s = ball.Settings;

            // Bad values: InvalidArgument, nothing changes.
            var bad = new List<KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>>
            {
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("NaN damping", x => { x.Damping = float.NaN; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("negative deformation damping", x => { x.DeformationDamping = -1f; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("NaN deformation damping", x => { x.DeformationDamping = float.NaN; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("negative friction", x => { x.Friction = -0.5f; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("infinite pressure", x => { x.Pressure = float.PositiveInfinity; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("infinite edge compliance", x => { x.EdgeCompliance = float.PositiveInfinity; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("NaN bend compliance", x => { x.BendCompliance = float.NaN; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("infinite gravity scale", x => { x.GravityScale = float.NegativeInfinity; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("0 iterations", x => { x.Iterations = 0; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("17 iterations", x => { x.Iterations = 17; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("0 substeps", x => { x.Substeps = 0; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("65 substeps", x => { x.Substeps = 65; return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("flag 2", x => { x.PreserveVolume = new Flag(2); return x; }),
                new KeyValuePair<string, Func<SoftBodySettings, SoftBodySettings>>("all zero", x => default(SoftBodySettings)),
            };
            foreach (var b in bad)
            {
                SoftBodySettings value = b.Value(s);
                Fails(Result.InvalidArgument, () => ball.Settings = value, b.Key);
                Equal(ball.Settings, s, b.Key + ": settings unchanged");
            }
            Fails(Result.InvalidArgument, () => ball.SetCompliance(float.NaN, 0f, 0f), "NaN edge compliance");
            Fails(Result.InvalidArgument, () => ball.SetCompliance(0f, -1e-3f, 0f), "negative bend compliance");
            Fails(Result.InvalidArgument, () => ball.SetCompliance(0f, 0f, float.PositiveInfinity), "infinite volume compliance");
            Equal(ball.Settings, s, "failed SetCompliance: settings unchanged");

            // The new settings run: gravity scale -1 lifts it.
            float y = ball.Center.Y;
            world.Step(Dt);
            Ensure(ball.Center.Y > y, "gravity scale -1: it rises");

            // Stale ids.
            ball.Destroy();
            Fails(Result.InvalidId, () => { var x = ball.Settings; }, "settings of a destroyed soft body");
            Fails(Result.InvalidId, () => ball.Settings = s, "set settings of a destroyed soft body");
            Fails(Result.InvalidId, () => ball.SetCompliance(0f, 0.01f, 0f), "set compliance of a destroyed soft body");
            SoftBody other = world.CreateSoftBodyIcosphere(SoftBodyDef.Default(), 0.5f, 1);
            Ensure(other.Id.Index == ball.Id.Index && other.Id != ball.Id, "the slot is reused with a new generation");
            Fails(Result.InvalidId, () => ball.SetCompliance(0f, 0.01f, 0f), "stale id of a reused slot");
            Equal(other.Settings, SettingsOf(SoftBodyDef.Default()), "the new soft body is untouched");
        }
    }

    // ---- shared geometry -----------------------------------------------------------------------

    private static void TestQueriesAndFilters()
    {
        using (var world = new World())
        {
            Body ground = world.CreateBody(BodyType.Static, Vec3.Zero);
            ShapeId plane = ground.CreatePlane(new Plane(new Vec3(0f, 1f, 0f), 0f)).Id;
            Body ball = world.CreateBody(BodyType.Static, new Vec3(0f, 2f, 0f));
            Shape s = ball.CreateSphere(new Sphere(Vec3.Zero, 0.5f));
            // A sphere at distance 4 of radius 0.5: hit at 3.5 of a 10 m ray.
            RayHit hit = world.CastRayClosest(new Vec3(-4f, 2f, 0f), new Vec3(10f, 0f, 0f));
            Ensure(hit.IsHit && hit.Shape == s.Id, "the ball is hit");
            Near(hit.Fraction, 0.35f, 1e-5f, "fraction (d - r) / |v|");
            Ensure(!world.CastRayClosest(new Vec3(-4f, 9f, 0f), new Vec3(10f, 0f, 0f)).IsHit, "a miss");
            world.RebuildBroadphase();
            RayHit again = world.CastRayClosest(new Vec3(-4f, 2f, 0f), new Vec3(10f, 0f, 0f));
            Ensure(again.Shape == s.Id && again.Fraction == hit.Fraction, "a rebuilt broad-phase tree answers the same");
            int calls = 0;
            world.CastRay(new Vec3(-4f, 2f, 0f), new Vec3(10f, -10f, 0f), QueryFilter.Default(), h => { calls++; return 1f; });
            Equal(calls, 1, "the plane only");
            Throws<InvalidOperationException>(() => world.CastRay(new Vec3(-4f, 2f, 0f), new Vec3(10f, 0f, 0f), QueryFilter.Default(), h => { throw new InvalidOperationException("boom"); }), "exception from the ray callback");
            var rays = new[] { new RayInput(new Vec3(-4f, 2f, 0f), new Vec3(10f, 0f, 0f)), new RayInput(new Vec3(9f, 9f, 9f), new Vec3(1f, 0f, 0f)) };
            var hits = new RayHit[2];
            world.CastRays(rays, hits, QueryFilter.Default());
            Ensure(hits[0].IsHit && !hits[1].IsHit, "batch");
            RayHit c = world.CastShape(QueryShape.Of(new Sphere(Vec3.Zero, 0.5f)), new Transform(new Vec3(5f, 5f, 0f), Quat.Identity), new Vec3(0f, -10f, 0f), QueryFilter.Default());
            Ensure(c.Shape == plane, "the plane is hit");
            Near(c.Fraction, 0.45f, 1e-6f, "time of impact (5 - 0.5) / 10");
            Equal(world.OverlapShape(QueryShape.Of(new Box(new Vec3(0.3f, 0.3f, 0.3f))), new Transform(new Vec3(0.5f, 2.5f, 0f), Quat.Identity), QueryFilter.Default()).Length, 1, "box overlap");
            Equal(world.OverlapAabb(new Vec3(-1f, -1f, -1f), new Vec3(1f, 3f, 1f), QueryFilter.Default()).Length, 2, "plane and ball");
            Equal(world.OverlapPoint(new Vec3(0f, 2.2f, 0f), QueryFilter.Default()).Length, 1, "point in the ball");
            Filter f = s.Filter;
            Ensure(f.CategoryBits == 1 && f.MaskBits == ulong.MaxValue && f.GroupIndex == 0, "default filter");
            s.Filter = new Filter(4, ulong.MaxValue, 0);
            Equal(s.Filter.CategoryBits, 4UL, "filter set");
            Ensure(!world.CastRayClosest(new Vec3(-4f, 2f, 0f), new Vec3(10f, 0f, 0f), new QueryFilter(1, 3)).IsHit, "filtered out");
            Fails(Result.InvalidArgument, () => world.CastRayClosest(Vec3.Zero, Vec3.Zero), "zero translation");
        }
    }

    private static void TestGeometry()
    {
        using (var world = new World())
        {
            // A 4 × 4 grid of unit cells at y = 0 (counter-clockwise seen from +y), plus one
            // degenerate triangle, scaled to 8 m × 8 m: a unit box rests with its centre 0.5 m up.
            const int n = 4;
            var v = new Vec3[(n + 1) * (n + 1)];
            for (int r = 0; r <= n; r++)
                for (int c = 0; c <= n; c++)
                    v[r * (n + 1) + c] = new Vec3(c - 0.5f * n, 0f, r - 0.5f * n);
            var idx = new List<uint>();
            for (int r = 0; r < n; r++)
                for (int c = 0; c < n; c++)
                {
                    uint a = (uint)(r * (n + 1) + c), b = a + 1, cc = a + (uint)(n + 1), d = cc + 1;
                    idx.AddRange(new[] { a, cc, d, a, d, b });
                }
            idx.AddRange(new uint[] { 0, 0, 1 });
            Mesh mesh = world.CreateMesh(v, idx.ToArray());
            Equal(mesh.TriangleCount, 32, "triangles kept");
            Equal(mesh.DegenerateCount, 1, "degenerate triangles counted");
            Body ground = world.CreateBody(BodyType.Static, Vec3.Zero);
            ground.CreateMesh(mesh.Shape(Transform.Identity, new Vec3(2f, 1f, 2f)));
            Body box = DynamicBox(world, new Vec3(0.3f, 1.5f, -0.2f), 0.5f);
            HearthException e = Fails(Result.InvalidArgument, () => box.CreateMesh(mesh.Shape(Transform.Identity, new Vec3(1f, 1f, 1f))), "mesh on a dynamic body");
            Ensure(e.Detail.Contains("static or kinematic"), "the refusal says why: " + e.Detail);

            // A hull cube on a heightfield whose ground is at y = 0.5 rests with its centre at 1.0.
            var cube = new Vec3[8];
            for (int i = 0; i < 8; i++)
                cube[i] = new Vec3((i & 1) != 0 ? 0.5f : -0.5f, (i & 2) != 0 ? 0.5f : -0.5f, (i & 4) != 0 ? 0.5f : -0.5f);
            Hull hull = world.CreateHull(cube);
            Equal(hull.VertexCount, 8, "hull vertices");
            Fails(Result.InvalidArgument, () => world.CreateHull(new[] { cube[0], cube[1], cube[2] }), "three points");
            HullDef bad = HullDef.Default();
            bad.ConvexRadius = -1f;
            Fails(Result.InvalidArgument, () => world.CreateHull(bad, cube), "negative convex radius");
            var heights = new float[6 * 5];
            for (int i = 0; i < heights.Length; i++) heights[i] = 0.25f;
            Heightfield field = world.CreateHeightfield(6, 5, heights, null);
            Fails(Result.InvalidArgument, () => world.CreateHeightfield(2, 2, new float[4], new byte[] { 2 }), "hole flag 2");
            Body terrain = world.CreateBody(BodyType.Static, new Vec3(20f, 0f, 0f));
            terrain.CreateHeightfield(field.Shape(Transform.Identity, new Vec3(2f, 2f, 2f)));
            Body dropped = world.CreateBody(BodyType.Dynamic, new Vec3(25.1f, 2f, 5.1f));
            dropped.CreateHull(hull.Shape(Transform.Identity, 1f));
            Near(dropped.Mass, 1000f, 1e-2f, "1 m³ hull of water");
            Fails(Result.InvalidArgument, () => dropped.CreateHull(hull.Shape(Transform.Identity, 0f)), "scale 0");
            Run(world, 240);
            Near(box.Position.Y, 0.5f, 0.005f, "box on the mesh floor");
            Near(dropped.Position.Y, 1.0f, 0.005f, "hull cube on the heightfield");

            e = Fails(Result.InvalidArgument, () => hull.Destroy(), "hull in use");
            Ensure(e.Detail.Contains("1 shape"), "the refusal counts the users: " + e.Detail);
            dropped.Destroy();
            hull.Destroy();
            Fails(Result.InvalidId, () => hull.Destroy(), "hull destroyed twice");
            Fails(Result.InvalidArgument, () => mesh.Destroy(), "mesh in use");
            ground.Destroy();
            mesh.Destroy();
            Fails(Result.InvalidId, () => { int unused = mesh.TriangleCount; }, "stale mesh");
            terrain.Destroy();
            field.Destroy();
            Fails(Result.InvalidId, () => field.Destroy(), "heightfield destroyed twice");
        }
    }

    // ---- driver -------------------------------------------------------------------------------

    private static bool SameBytes(byte[] a, byte[] b)
    {
        if (a.Length != b.Length)
        {
            return false;
        }
        for (int i = 0; i < a.Length; i++)
        {
            if (a[i] != b[i])
            {
                return false;
            }
        }
        return true;
    }

    private static void TestSnapshots()
    {
        using (var world = new World())
        {
            Ground(world);
            Body box = DynamicBox(world, new Vec3(0f, 3f, 0f), 0.5f);
            int calls = 0;
            world.CreateUserForceGenerator(call => { calls++; });
            for (int i = 0; i < 10; i++)
            {
                world.Step(Dt);
            }
            byte[] snap = world.SaveSnapshot();
            Equal(snap.Length, world.SnapshotSize, "SnapshotSize");
            for (int i = 0; i < 20; i++)
            {
                world.Step(Dt);
            }
            Transform first = box.Transform;
            byte[] after = world.SaveSnapshot();
            world.RestoreSnapshot(snap);
            Ensure(SameBytes(world.SaveSnapshot(), snap), "save, restore, save: the same bytes");
            for (int i = 0; i < 20; i++)
            {
                world.Step(Dt);
            }
            Ensure(box.Transform.Equals(first), "the same handle, the same pose");
            Ensure(SameBytes(world.SaveSnapshot(), after), "the replay is bit for bit");
            Equal(calls, 50, "the handler kept in the same world");
            Equal(world.GetUserGeneratorsMissingCallback().Length, 0, "no callback missing");
            byte[] bad = (byte[])snap.Clone();
            bad[bad.Length / 2] ^= 1;
            Fails(Result.InvalidArgument, () => world.RestoreSnapshot(bad), "a flipped bit");
            Fails(Result.InvalidArgument, () => world.RestoreSnapshot(new byte[10]), "truncated");
            Ensure(SameBytes(world.SaveSnapshot(), after), "failed restores change nothing");

            using (var fresh = new World())
            {
                fresh.RestoreSnapshot(snap);
                GeneratorId[] missing = fresh.GetUserGeneratorsMissingCallback();
                Equal(missing.Length, 1, "the user generator is listed");
                Equal(fresh.GetGenerator(missing[0]).Type, GeneratorType.UserForce, "its type");
                int freshCalls = 0;
                Fails(Result.InvalidArgument, () => fresh.SetUserContactCallback(missing[0], (call, sink) => { }, 4), "other kind");
                fresh.SetUserForceCallback(missing[0], call => { freshCalls++; });
                Equal(fresh.GetUserGeneratorsMissingCallback().Length, 0, "set again");
                fresh.Step(Dt);
                Equal(freshCalls, 1, "the new handler runs");
            }
        }
    }

    private static void TestRecording()
    {
        string path = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "hearth_csharp_test_" + System.Diagnostics.Process.GetCurrentProcess().Id + ".hrec");
        using (var world = new World())
        {
            Body ball = DynamicBox(world, new Vec3(0f, 5f, 0f), 0.5f);
            world.RecordToFile(path, true);
            Fails(Result.InvalidArgument, () => world.RecordToFile(path), "already recording");
            for (int i = 0; i < 10; i++)
            {
                world.Step(Dt);
            }
            world.StopRecording();
            Fails(Result.InvalidArgument, () => world.StopRecording(), "not recording");
            byte[] file = System.IO.File.ReadAllBytes(path);
            Equal(Encoding.ASCII.GetString(file, 0, 8), "HEARTHRC", "magic");
            Equal((int)file[12], 1, "contacts flag");
            Ensure(file.Length > 16 + 10 * 31, "a falling box's 31-byte record every step: " + file.Length);
            System.IO.File.Delete(path);
            Fails(Result.Io, () => world.RecordToFile("/nonexistent-dir/x.hrec"), "bad directory");

            var chunks = new List<byte[]>();
            world.RecordTo(chunks.Add);
            Equal(chunks.Count, 1, "the start is written at once");
            world.Step(Dt);
            Equal(chunks.Count, 2, "then once per step");
            Ensure(world.KeepsRecordCallback, "the callback is kept while recording");
            world.StopRecording();
            Ensure(!world.KeepsRecordCallback, "and released by StopRecording");

            int writes = 0;
            world.RecordTo(data =>
            {
                if (++writes == 2)
                {
                    throw new CallbackBoom("disk full");
                }
            });
            CallbackBoom e = Throws<CallbackBoom>(() => world.Step(Dt), "the write's exception");
            Equal(e.Message, "disk full", "original exception");
            float y = ball.Position.Y;
            Fails(Result.Io, () => world.Step(Dt), "the next step reports the failed recording");
            Equal(ball.Position.Y, y, "and does not step");
            world.Step(Dt);
            Ensure(ball.Position.Y < y, "then the world steps again");
            Throws<CallbackBoom>(() => world.RecordTo(data => { throw new CallbackBoom("at once"); }), "first write fails");
            Fails(Result.InvalidArgument, () => world.StopRecording(), "not recording after a failed start");
        }
    }

    // Rolling resistance and torsional friction (the shape def's last fields): range errors
    // name the field; a rolling ball stops after 7v²/(10cg) and a spinning one after
    // 2rω/(5tg), within 5 %.
    private static void TestRollingResistanceAndTorsionalFriction()
    {
        using (var world = new World())
        {
            Body body = world.CreateBody(BodyType.Dynamic, new Vec3(0f, 5f, 0f));
            foreach (float bad in new[] { -0.1f, 1.5f, float.NaN, float.PositiveInfinity })
            {
                ShapeDef def = ShapeDef.Default();
                def.RollingResistance = bad;
                HearthException e = Fails(Result.InvalidArgument, () => body.CreateSphere(def, new Sphere(Vec3.Zero, 0.3f)), "rolling resistance " + bad);
                Ensure(e.Detail.Contains("rolling_resistance"), "the message names rolling_resistance");
                def = ShapeDef.Default();
                def.TorsionalFriction = bad;
                e = Fails(Result.InvalidArgument, () => body.CreateSphere(def, new Sphere(Vec3.Zero, 0.3f)), "torsional friction " + bad);
                Ensure(e.Detail.Contains("torsional_friction"), "the message names torsional_friction");
            }
            body.Destroy();

            Ground(world);
            const float r = 0.3f, v = 2f, c = 0.2f, t = 0.3f, spin = 6f, g = 9.81f;
            ShapeDef ball = ShapeDef.Default();
            ball.RollingResistance = c;
            ball.TorsionalFriction = t;
            Body rolling = world.CreateBody(BodyType.Dynamic, new Vec3(0f, r, 0f));
            rolling.CreateSphere(ball, new Sphere(Vec3.Zero, r));
            rolling.LinearVelocity = new Vec3(v, 0f, 0f);
            rolling.AngularVelocity = new Vec3(0f, 0f, -v / r);
            Body spinning = world.CreateBody(BodyType.Dynamic, new Vec3(5f, r, 0f));
            spinning.CreateSphere(ball, new Sphere(Vec3.Zero, r));
            spinning.AngularVelocity = new Vec3(0f, spin, 0f);
            int stopped = -1;
            for (int i = 1; i <= 600; i++)
            {
                world.Step(Dt);
                if (stopped < 0 && spinning.AngularVelocity.Y <= 1e-3f) stopped = i;
            }
            float distance = 7f * v * v / (10f * c * g), time = 2f * r * spin / (5f * t * g);
            Near(rolling.Position.X, distance, 0.05f * distance, "rolling distance");
            Near(stopped * Dt, time, 0.05f * time + Dt, "spin-down time");
            Ensure(!rolling.IsAwake && !spinning.IsAwake, "both sleep");
        }
    }


    private static void TestEventsAndStepCallbacks()
    {
        using (var w = new World(WorldDef.Default()))
        {
            BodyDef gd = BodyDef.Default();
            Body ground = w.CreateBody(gd);
            ShapeDef sd = ShapeDef.Default();
            Ensure(!sd.IsSensor && sd.EnableContactEvents && !sd.EnableHitEvents && sd.EnableSensorEvents, "event flag defaults");
            ground.CreatePlane(sd, new Plane { Normal = new Vec3(0, 1, 0), Offset = 0 });
            // A dropped box: one begin, one hit at sqrt(2gh) within 1 %, move events.
            float h = 2.0f;
            BodyDef bd = BodyDef.Default();
            bd.Type = BodyType.Dynamic;
            bd.Transform = new Transform(new Vec3(0, 0.5f + h, 0), Quat.Identity);
            Body box = w.CreateBody(bd);
            ShapeDef hits = ShapeDef.Default();
            hits.EnableHitEvents = true;
            box.CreateBox(hits, new Box { Center = Vec3.Zero, Rotation = Quat.Identity, HalfExtents = new Vec3(0.5f, 0.5f, 0.5f) });
            int begins = 0, nhits = 0, moves = 0;
            float speed = 0;
            for (int i = 0; i < 120; i++)
            {
                w.Step(1.0f / 60.0f);
                ContactEvent[] b, e;
                ContactHitEvent[] hit;
                w.GetContactEvents(out b, out e, out hit);
                begins += b.Length;
                nhits += hit.Length;
                if (hit.Length > 0) speed = hit[0].ApproachSpeed;
                moves += w.GetBodyEvents().Length;
            }
            Ensure(begins == 1 && nhits == 1 && moves > 30, "one begin, one hit, moves");
            float expected = (float)Math.Sqrt(2 * 9.81 * h);
            Ensure(Math.Abs(speed - expected) < 0.01f * expected, "hit speed " + speed + " against " + expected);
            // A kinematic box through a sensor.
            ShapeDef sensor = ShapeDef.Default();
            sensor.IsSensor = true;
            BodyDef zd = BodyDef.Default();
            zd.Transform = new Transform(new Vec3(10, 3, 0), Quat.Identity);
            w.CreateBody(zd).CreateBox(sensor, new Box { Center = Vec3.Zero, Rotation = Quat.Identity, HalfExtents = new Vec3(1, 1, 1) });
            BodyDef kd = BodyDef.Default();
            kd.Type = BodyType.Kinematic;
            kd.Transform = new Transform(new Vec3(5, 3, 0), Quat.Identity);
            kd.LinearVelocity = new Vec3(2, 0, 0);
            w.CreateBody(kd).CreateBox(sd, new Box { Center = Vec3.Zero, Rotation = Quat.Identity, HalfExtents = new Vec3(0.25f, 0.25f, 0.25f) });
            int sb = 0, se = 0;
            for (int i = 0; i < 300; i++)
            {
                w.Step(1.0f / 60.0f);
                SensorEvent[] b, e;
                w.GetSensorEvents(out b, out e);
                sb += b.Length;
                se += e.Length;
            }
            Ensure(sb == 1 && se == 1, "one sensor begin and end, got " + sb + ", " + se);
            // A pair filter and a pre-solve callback that disables every contact: the box falls through.
            int asked = 0;
            w.SetPairFilter((world, a, b2) => { asked++; return true; });
            w.SetPreSolve((world, c, points) => points.Length < 0);
            BodyDef fd = BodyDef.Default();
            fd.Type = BodyType.Dynamic;
            fd.Transform = new Transform(new Vec3(-5, 0.5f, 0), Quat.Identity);
            Body faller = w.CreateBody(fd);
            faller.CreateBox(sd, new Box { Center = Vec3.Zero, Rotation = Quat.Identity, HalfExtents = new Vec3(0.5f, 0.5f, 0.5f) });
            for (int i = 0; i < 60; i++) w.Step(1.0f / 60.0f);
            Ensure(asked > 0, "the pair filter was asked");
            Ensure(faller.Transform.Position.Y < -1.0f, "every contact disabled: it fell through, y = " + faller.Transform.Position.Y);
            // An exception in a callback is rethrown by Step.
            w.SetPreSolve((world, c, points) => { throw new InvalidOperationException("boom"); });
            bool caught = false;
            BodyDef rd = BodyDef.Default();
            rd.Type = BodyType.Dynamic;
            rd.Transform = new Transform(new Vec3(-8, 0.5f, 0), Quat.Identity);
            w.CreateBody(rd).CreateBox(sd, new Box { Center = Vec3.Zero, Rotation = Quat.Identity, HalfExtents = new Vec3(0.5f, 0.5f, 0.5f) });
            try { w.Step(1.0f / 60.0f); } catch (InvalidOperationException) { caught = true; }
            Ensure(caught, "the pre-solve exception surfaced from Step");
            w.SetPreSolve(null);
            w.SetPairFilter(null);
            w.Step(1.0f / 60.0f);
        }
    }

    private static int Main(string[] args)
    {
        layoutPath = args.Length > 0 ? args[0] : null;
        var tests = new List<KeyValuePair<string, Action>>
        {
            new KeyValuePair<string, Action>("layout matches C", TestLayoutMatchesC),
            new KeyValuePair<string, Action>("version and result names", TestVersionAndResultNames),
            new KeyValuePair<string, Action>("defaults come from the library", TestDefaultsComeFromTheLibrary),
            new KeyValuePair<string, Action>("box falls and rests on the plane", TestBoxFallsAndRestsOnThePlane),
            new KeyValuePair<string, Action>("free fall matches gravity", TestFreeFallMatchesGravity),
            new KeyValuePair<string, Action>("body setters and forces", TestBodySettersAndForces),
            new KeyValuePair<string, Action>("runtime setters", TestRuntimeSetters),
            new KeyValuePair<string, Action>("locked axes", TestLockedAxes),
            new KeyValuePair<string, Action>("debug draw", TestDebugDraw),
            new KeyValuePair<string, Action>("bulk transforms equal single reads", TestBulkTransformsEqualSingleReads),
            new KeyValuePair<string, Action>("error paths", TestErrorPaths),
            new KeyValuePair<string, Action>("rolling resistance and torsional friction", TestRollingResistanceAndTorsionalFriction),
            new KeyValuePair<string, Action>("disposal", TestDisposal),
            new KeyValuePair<string, Action>("worker counts and a job system give the same hash", TestWorkerCountsAndAJobSystemGiveTheSameHash),
            new KeyValuePair<string, Action>("force generator makes a body hover", TestForceGeneratorMakesABodyHover),
            new KeyValuePair<string, Action>("callback exception is rethrown from Step", TestCallbackExceptionIsRethrownFromStep),
            new KeyValuePair<string, Action>("generator call only valid inside the callback", TestGeneratorCallIsOnlyValidInsideTheCallback),
            new KeyValuePair<string, Action>("dispose inside a callback", TestDisposeInsideACallback),
            new KeyValuePair<string, Action>("callbacks go through static trampolines", TestCallbacksGoThroughStaticTrampolines),
            new KeyValuePair<string, Action>("contact generator makes a floor", TestContactGeneratorMakesAFloor),
            new KeyValuePair<string, Action>("built-in generators", TestBuiltInGenerators),
            new KeyValuePair<string, Action>("joints", TestJoints),
            new KeyValuePair<string, Action>("particles", TestParticles),
            new KeyValuePair<string, Action>("soft bodies", TestSoftBodies),
            new KeyValuePair<string, Action>("soft body settings", TestSoftBodySettings),
            new KeyValuePair<string, Action>("recording", TestRecording),
            new KeyValuePair<string, Action>("snapshots", TestSnapshots),
            new KeyValuePair<string, Action>("shared geometry", TestGeometry),
            new KeyValuePair<string, Action>("queries and filters", TestQueriesAndFilters),
            new KeyValuePair<string, Action>("events, sensors and step callbacks", TestEventsAndStepCallbacks),
        };
        int passed = 0, failed = 0;
        foreach (var test in tests)
        {
            try
            {
                test.Value();
                passed++;
                Console.WriteLine("ok   {0}", test.Key);
            }
            catch (Exception e)
            {
                failed++;
                Console.WriteLine("FAIL {0}: {1}", test.Key, e is TestFailure ? e.Message : e.ToString());
            }
        }
        Console.WriteLine("C# binding: {0} passed, {1} failed ({2} checks)", passed, failed, checks);
        return failed == 0 ? 0 : 1;
    }
}
