// Pyramid.cs - the scene of examples/c/pyramid.c through the C# binding, printing the same
// text (tests/bindings_csharp.rs checks that line by line; Hearth is deterministic).
//
// Builds a pyramid of unit boxes on a ground plane, drops a "pile" of 60 alternating
// spheres and boxes onto it from a grid above, and steps 30 s at 60 Hz. Every three seconds it
// prints the time, the height of the pyramid's top box and how many bodies are awake (all
// asleep by the end, or it exits with status 1).
//
// Build and run from the repository root, after `cargo build --release`:
//   mcs -out:target/Pyramid.exe bindings/csharp/Hearth.Native.cs bindings/csharp/Hearth.cs \
//       examples/csharp/Pyramid.cs
//   LD_LIBRARY_PATH=target/release mono target/Pyramid.exe

using System;
using System.Globalization;
using Hearth;

internal static class Pyramid
{
    private const int Base = 5;          // boxes per side in the bottom layer: 25+16+9+4+1 = 55 boxes
    private const int PyramidBoxes = 55;
    private const int PileBodies = 60;   // alternating spheres (r = 0.5) and unit boxes
    private const int PileRow = 8;       // the pile starts as an 8 x 8 grid (60 of its 64 cells used)
    private const int MaxBodies = PyramidBoxes + PileBodies;

    private static readonly float Dt = 1.0f / 60.0f;
    private const int Steps = 1800; // 30 s
    private const int ReportEvery = 180;

    // A dynamic body at p with no shapes yet.
    private static Body DynamicBody(World world, Vec3 p)
    {
        BodyDef def = BodyDef.Default(); // always start from the defaults
        def.Type = BodyType.Dynamic;
        def.Transform.Position = p;
        return world.CreateBody(def);
    }

    private static Body AddBox(World world, Vec3 p)
    {
        Body body = DynamicBody(world, p);
        body.CreateBox(ShapeDef.Default(), new Box(Vec3.Zero, Quat.Identity, new Vec3(0.5f, 0.5f, 0.5f)));
        return body;
    }

    // FNV-1a over the bits of every body's position, rotation, linear and angular velocity (13
    // floats), folded into h: the "state hash" column, as in pyramid.c.
    private static ulong HashState(ulong h, World world, BodyId[] bodies, Transform[] transforms, int count)
    {
        world.GetTransforms(bodies, transforms, count);
        for (int b = 0; b < count; b++)
        {
            var body = world.GetBody(bodies[b]);
            Transform x = transforms[b];
            Vec3 v = body.LinearVelocity, w = body.AngularVelocity;
            float[] state = { x.Position.X, x.Position.Y, x.Position.Z, x.Rotation.X, x.Rotation.Y,
                              x.Rotation.Z, x.Rotation.W, v.X, v.Y, v.Z, w.X, w.Y, w.Z };
            foreach (float f in state)
            {
                h = unchecked((h ^ BitConverter.ToUInt32(BitConverter.GetBytes(f), 0)) * 0x100000001b3UL);
            }
        }
        return h;
    }

    private static Body AddSphere(World world, Vec3 p)
    {
        Body body = DynamicBody(world, p);
        body.CreateSphere(ShapeDef.Default(), new Sphere(Vec3.Zero, 0.5f));
        return body;
    }

    // The static ground: the half-space y <= 0, a plane on a static body.
    private static void AddGround(World world)
    {
        Body ground = world.CreateBody(BodyDef.Default()); // static by default
        ground.CreatePlane(ShapeDef.Default(), new Plane(new Vec3(0f, 1f, 0f), 0f));
    }

    // printf("%*.*f") of a float widened to double: fixed notation, rounded half to even on
    // the exact binary value as glibc does. value * 10^decimals is exact in a double for a
    // float and decimals <= 6 (24 + 20 bits of mantissa), so Math.Round sees the true value.
    private static string Fixed(float value, int decimals, int width)
    {
        if (float.IsNaN(value) || float.IsInfinity(value))
        {
            return (float.IsNaN(value) ? "nan" : value > 0 ? "inf" : "-inf").PadLeft(width);
        }
        bool negative = value < 0f || (value == 0f && float.IsNegativeInfinity(1f / value));
        double scale = Math.Pow(10.0, decimals);
        double units = Math.Round(Math.Abs((double)value) * scale, MidpointRounding.ToEven);
        string digits = units.ToString("F0", CultureInfo.InvariantCulture).PadLeft(decimals + 1, '0');
        string text = decimals == 0
            ? digits
            : digits.Substring(0, digits.Length - decimals) + "." + digits.Substring(digits.Length - decimals);
        return ((negative ? "-" : "") + text).PadLeft(width);
    }

    private static int Main()
    {
        if (Native.hearth_version() != Native.Version)
        {
            Console.Error.WriteLine("error: header version {0}, library version {1}", Native.Version, Native.hearth_version());
            return 1;
        }

        int awake;
        try
        {
            using (var world = new World(WorldDef.Default()))
            {
                AddGround(world);

                var bodies = new BodyId[MaxBodies];
                int count = 0;

                // Pyramid: layer L has (Base - L)^2 boxes, centred on the y axis; the last is the top.
                for (int layer = 0; layer < Base; layer++)
                {
                    int n = Base - layer;
                    float offset = -0.5f * (float)(n - 1);
                    for (int i = 0; i < n; i++)
                    {
                        for (int k = 0; k < n; k++)
                        {
                            var p = new Vec3(offset + (float)i, 0.5f + (float)layer, offset + (float)k);
                            bodies[count++] = AddBox(world, p).Id;
                        }
                    }
                }
                int top = count - 1;

                // Pile: a grid 1.5 m apart, 10 m up, centred over the pyramid.
                for (int j = 0; j < PileBodies; j++)
                {
                    float x = -5.25f + 1.5f * (float)(j % PileRow);
                    float z = -5.25f + 1.5f * (float)(j / PileRow);
                    var p = new Vec3(x, 10.0f, z);
                    bodies[count++] = (j % 2 == 0) ? AddSphere(world, p).Id : AddBox(world, p).Id;
                }

                Console.WriteLine("Hearth {0}.{1}.{2} C# example: pyramid of {3} boxes (base {4}) + pile of {5} spheres/boxes",
                    Native.VersionMajor, Native.VersionMinor, Native.VersionPatch, PyramidBoxes, Base, PileBodies);
                Console.WriteLine("{0,8} {1,14} {2,16} {3,8}", "t [s]", "top box y [m]", "state hash", "awake");
                ulong hash = 0xcbf29ce484222325UL;

                var transforms = new Transform[MaxBodies]; // caller-owned, filled in one call per report
                awake = count;
                for (int step = 1; step <= Steps; step++)
                {
                    world.Step(Dt);
                    hash = HashState(hash, world, bodies, transforms, count); // after every step
                    if (step % ReportEvery != 0)
                    {
                        continue;
                    }
                    world.GetTransforms(bodies, transforms, count);
                    awake = 0;
                    for (int b = 0; b < count; b++)
                    {
                        awake += world.GetBody(bodies[b]).IsAwake ? 1 : 0;
                    }
                    float t = (float)((float)step * Dt); // rounded to float as in C
                    Console.WriteLine("{0} {1} {2} {3,4}/{4}", Fixed(t, 2, 8), Fixed(transforms[top].Position.Y, 3, 14),
                        hash.ToString("x16", CultureInfo.InvariantCulture), awake, count);
                }
            }
        }
        catch (HearthException e)
        {
            Console.Error.WriteLine("error: {0}", e.Message);
            return 1;
        }
        if (awake != 0)
        {
            Console.Error.WriteLine("error: {0} bodies still awake after {1} steps", awake, Steps);
            return 1;
        }
        Console.WriteLine("done");
        return 0;
    }
}
