// HearthSimulation.h - the engine-independent core of the plug-in: one Hearth world driven by
// a game's variable frames.
//
// The Unreal files (UHearthWorldSubsystem, UHearthBodyComponent) are thin glue over this
// class: they convert units and axes with HearthConversion.h, shapes with HearthShapes.h, and
// call FSimulation once per frame. Everything here is plain C++17 over hearth.h, compiled and
// tested by g++ (and under valgrind) in the Hearth repository:
// tests/cpp/test_unreal_simulation.cpp, run by `cargo test --release --test bindings_cpp`.
//
// All values are Hearth's: metres, kilograms, seconds, Y up, right-handed.
//
// ---------------------------------------------------------------------------------------
// One frame
//
//   1. the host pushes what gameplay did: SyncFromHost(body, actor pose) for every body
//      (a dynamic or static body whose actor was moved by gameplay is teleported there; a
//      kinematic body takes its actor's pose as the target for this frame), forces, torques
//      and impulses, SetGravity;
//   2. Advance(frame seconds) runs the fixed steps the frame owes (FixedStepAccumulator);
//   3. the host reads GetRenderPose(body) for every dynamic body: the pose interpolated
//      between the last two steps, so motion is smooth at any frame rate.
//
// Forces do not depend on the frame rate. A force (or torque) added during a frame acts for
// that frame's duration, prorated over the fixed steps by time: each step receives the force
// of every frame it overlaps times the overlap, so a constant force is exactly F·h per step
// whether it was added in ten frames at 600 Hz or one at 60 Hz, and a frame shorter than a
// step owes its share to the next step that runs. Time the accumulator drops at its cap (a
// hitch) is not simulated, so forces do not act during it. Impulses act once, at once (an
// instantaneous change of momentum is frame-rate independent by nature).
//
// Kinematic bodies follow their actor: each step's target is the actor's path (from its pose
// at the end of the last frame to its pose at the end of this one) at the moment the step
// ends, so the body moves at its actor's velocity and carries what stands on it, at any frame
// rate; when the actor stops, the body stops. Teleport moves any body at once, without
// sweeping or interpolating.
//
// Rendered poses lag the game clock by one fixed step (the price of interpolating between two
// computed states instead of guessing ahead): a body riding a kinematic platform that moves at
// v is drawn v·h behind where its actor's pose would put it, 1.7 cm at 1 m/s and h = 1/60 s.
//
// Errors of Hearth calls go to one callback with the call's name, the result name and the
// library's message; repeats of the same call's error are held back for an interval
// (FErrorThrottle) and then reported with their count, so a failing step cannot flood the
// log at 60 Hz. A world that stopped after an internal error (HEARTH_ERROR_PANIC) is not
// stepped again.
//
// Shared geometry (hulls, meshes, heightfields) is built once per asset and instanced: AddHull,
// AddMesh and AddHeightfield look the asset up in a small cache (keyed by the asset's
// identity, the element's index and the scale baked into the geometry) and create it only on a
// miss, so two components of one static mesh share one hull or mesh. Each cache entry counts
// the bodies' shapes using it; removing a body (its shapes go with it) releases its uses, and
// the geometry is destroyed when its last user is gone, after the shapes (Hearth refuses to
// destroy geometry in use). A shape that fails to be created releases what it acquired.
// ---------------------------------------------------------------------------------------
#pragma once

#include "HearthConversion.h"
#include "HearthShapes.h"
#include "hearth.h"

#include <cmath>
#include <cstdint>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace HearthCore {

/**
 * Whether the library (hearth_version()) can serve code built against a header
 * (HEARTH_VERSION): the same ABI, which is the major version from 1.0 on and the major and
 * minor while the major is 0 (Cargo's rule, and the library's SONAME: libhearth.so.0.<minor>);
 * from 1.0 on the library must also be at least the header's minor (newer functions).
 */
inline bool IsCompatibleVersion(uint32_t LibraryVersion, uint32_t HeaderVersion) {
    const uint32_t Major = HeaderVersion >> 16;
    if (Major == 0) {
        return (LibraryVersion >> 8) == (HeaderVersion >> 8);
    }
    return (LibraryVersion >> 16) == Major && ((LibraryVersion >> 8) & 0xFFu) >= ((HeaderVersion >> 8) & 0xFFu);
}

/** Receives the plug-in's error messages (UTF-8, NUL-terminated, valid during the call). */
using FErrorCallback = void (*)(void *UserData, const char *Message);

/**
 * Decides which occurrences of repeated errors are reported. The first occurrence of a key is
 * reported at once; later ones of the same key at most once per interval, each report
 * carrying how many were held back since the previous one.
 */
class FErrorThrottle {
public:
    explicit FErrorThrottle(double InIntervalSeconds = 5.0)
        : IntervalSeconds(InIntervalSeconds >= 0.0 && std::isfinite(InIntervalSeconds) ? InIntervalSeconds : 5.0) {}

    /** One occurrence of the error named Key at NowSeconds. Returns true when it is to be
     * reported, with OutHeldBack set to the occurrences of Key not reported since its last
     * report; false when it is held back. */
    bool Admit(const char *Key, double NowSeconds, int &OutHeldBack) {
        OutHeldBack = 0;
        for (FEntry &Entry : Entries) {
            if (Entry.Key == Key) {
                if (NowSeconds - Entry.LastReported >= IntervalSeconds) {
                    OutHeldBack = Entry.HeldBack;
                    Entry.HeldBack = 0;
                    Entry.LastReported = NowSeconds;
                    return true;
                }
                Entry.HeldBack += 1;
                HeldBackTotal += 1;
                return false;
            }
        }
        Entries.push_back(FEntry{std::string(Key), NowSeconds, 0});
        return true;
    }
    /** How many occurrences were held back so far, over all keys. */
    int GetHeldBackTotal() const { return HeldBackTotal; }
    double GetIntervalSeconds() const { return IntervalSeconds; }

private:
    struct FEntry {
        std::string Key;
        double LastReported;
        int HeldBack;
    };
    std::vector<FEntry> Entries; // a handful of keys: a linear search is the fastest lookup
    double IntervalSeconds;
    int HeldBackTotal = 0;
};

/** How a simulation steps. */
struct FSimulationSettings {
    /** The fixed step (s): within Hearth's time-step range, 0.001 to 0.1 s (Create refuses
     * others, since every step would fail). */
    double StepSeconds = 1.0 / 60.0;
    /** At most this many steps per frame; longer frames drop the excess (the game slows down). */
    int MaxStepsPerFrame = 8;
    /** Repeats of one error are reported at most once per this many seconds of frame time. */
    double ErrorIntervalSeconds = 5.0;
    /** When at least this many bodies were added since the last rebuild (a level streamed in
     * body by body), the next Advance rebuilds the broad-phase tree first
     * (hearth_world_rebuild_broadphase: queries and pair searches then test fewer boxes).
     * 0: never. */
    int RebuildBroadphaseAfterBodies = 256;
};

/** Whether two poses are the same up to the rounding of a trip through the host's types:
 * 0.1 mm (plus 1e-6 relative) and a quaternion dot product within 1e-10 of ±1 (0.002°). */
inline bool SamePose(const HearthTransform &A, const HearthTransform &B) {
    const auto Close = [](float X, float Y) {
        const double D = std::fabs(static_cast<double>(X) - static_cast<double>(Y));
        return D <= 1e-4 + 1e-6 * std::fabs(static_cast<double>(X));
    };
    if (!Close(A.position.x, B.position.x) || !Close(A.position.y, B.position.y) ||
        !Close(A.position.z, B.position.z)) {
        return false;
    }
    // Normalised: a float quaternion's length is 1 only to ~1e-7, which would swamp 1e-10.
    const auto Dot4 = [](const HearthQuat &P, const HearthQuat &Q) {
        return static_cast<double>(P.x) * Q.x + static_cast<double>(P.y) * Q.y + static_cast<double>(P.z) * Q.z +
               static_cast<double>(P.w) * Q.w;
    };
    const double Norms = std::sqrt(Dot4(A.rotation, A.rotation) * Dot4(B.rotation, B.rotation));
    return Norms > 0.0 && std::fabs(Dot4(A.rotation, B.rotation)) >= (1.0 - 1e-10) * Norms;
}

/** One Hearth world stepped by a game's frames. Not copyable; owns the world. */
class FSimulation {
public:
    FSimulation() = default;
    ~FSimulation() { Destroy(); }
    FSimulation(const FSimulation &) = delete;
    FSimulation &operator=(const FSimulation &) = delete;

    /** Where errors go; without a callback they are counted but not shown. */
    void SetErrorCallback(FErrorCallback InCallback, void *InUserData) {
        ErrorCallback = InCallback;
        ErrorUserData = InUserData;
    }

    /** Creates the world from Def (from hearth_world_def_default(), edited). Destroys a world
     * created before. Returns false (and reports) when Hearth refuses. */
    bool Create(const HearthWorldDef &Def, const FSimulationSettings &InSettings = FSimulationSettings()) {
        Destroy();
        if (!(InSettings.StepSeconds >= 0.001 && InSettings.StepSeconds <= 0.1)) {
            char Message[160];
            std::snprintf(Message, sizeof Message,
                          "FSimulation::Create: StepSeconds must be within 0.001 to 0.1 s (Hearth's time-step range), got %g",
                          InSettings.StepSeconds);
            ReportError("Create", Message);
            return false;
        }
        Settings = InSettings;
        Accumulator = HearthConversion::FixedStepAccumulator(InSettings.StepSeconds, InSettings.MaxStepsPerFrame);
        Settings.StepSeconds = Accumulator.GetStepSeconds();
        Settings.MaxStepsPerFrame = Accumulator.GetMaxStepsPerFrame();
        Throttle = FErrorThrottle(InSettings.ErrorIntervalSeconds);
        HearthWorld *NewWorld = nullptr;
        if (!Check(hearth_world_create(&Def, &NewWorld), "hearth_world_create")) {
            return false;
        }
        World = NewWorld;
        Gravity = Def.gravity;
        bStopped = false;
        return true;
    }

    /** Destroys the world and forgets every body. */
    void Destroy() {
        hearth_world_destroy(World); // NULL is a no-op
        World = nullptr;
        Bodies.clear();
        Ids.clear();
        Previous.clear();
        Current.clear();
        SlotByIndex.clear();
        Geometry.clear(); // the world freed it
        GeometryUses.clear();
        Accumulator.Reset();
        StepCount = 0;
        TeleportCount = 0;
        bStopped = false;
    }

    HearthWorld *GetWorld() const { return World; }
    /** A world exists and has not stopped after an internal error. */
    bool IsRunning() const { return World != nullptr && !bStopped; }

    // ---- world settings

    /** Follows the host's gravity (m/s²); calls Hearth only when it changed (setting gravity
     * wakes every body). */
    bool SetGravity(const HearthVec3 &NewGravity) {
        if (!World) {
            return false;
        }
        if (NewGravity.x == Gravity.x && NewGravity.y == Gravity.y && NewGravity.z == Gravity.z) {
            return true;
        }
        if (!Check(hearth_world_set_gravity(World, NewGravity), "hearth_world_set_gravity")) {
            return false;
        }
        Gravity = NewGravity;
        return true;
    }
    HearthVec3 GetGravity() const { return Gravity; }

    // ---- bodies

    /** Creates a body and starts tracking it. Returns the null id (and reports) on failure. */
    HearthBodyId AddBody(const HearthBodyDef &Def) {
        HearthBodyId Id{0, 0};
        if (!World || !Check(hearth_body_create(World, &Def, &Id), "hearth_body_create")) {
            return HearthBodyId{0, 0};
        }
        FBody Body;
        Body.Type = Def.type;
        Body.LastShown = Def.transform;
        Body.KinematicFrom = Def.transform;
        Body.KinematicTo = Def.transform;
        if (SlotByIndex.size() <= Id.index) {
            SlotByIndex.resize(static_cast<size_t>(Id.index) + 1, -1);
        }
        SlotByIndex[Id.index] = static_cast<int32_t>(Bodies.size());
        ++BodiesAddedSinceRebuild;
        Bodies.push_back(Body);
        Ids.push_back(Id);
        Previous.push_back(Def.transform);
        Current.push_back(Def.transform);
        return Id;
    }

    bool AddSphere(HearthBodyId Body, const HearthShapeDef &Def, const HearthSphere &Sphere) {
        HearthShapeId Shape{0, 0};
        return World && Check(hearth_shape_create_sphere(World, Body, &Def, &Sphere, &Shape), "hearth_shape_create_sphere");
    }
    bool AddBox(HearthBodyId Body, const HearthShapeDef &Def, const HearthBox &Box) {
        HearthShapeId Shape{0, 0};
        return World && Check(hearth_shape_create_box(World, Body, &Def, &Box, &Shape), "hearth_shape_create_box");
    }
    bool AddCapsule(HearthBodyId Body, const HearthShapeDef &Def, const HearthCapsule &Capsule) {
        HearthShapeId Shape{0, 0};
        return World &&
               Check(hearth_shape_create_capsule(World, Body, &Def, &Capsule, &Shape), "hearth_shape_create_capsule");
    }

    // ---- shared geometry (see the header comment)

    /** The kinds of shared geometry the cache holds. */
    enum class EGeometry : uint32_t { Hull = 0, Mesh = 1, Heightfield = 2 };

    /**
     * A convex element (FKConvexElem::VertexData, cm, in the component's frame) of the asset
     * Asset (any pointer identifying it: the UStaticMesh or its UBodySetup) as a hull shape
     * on Body, under the component's scale (HearthShapes::ConvexScale: uniform in the shape,
     * non-uniform baked). The hull is built on the first use of (Asset, ElementIndex, baked
     * scale) and shared after that. Returns false, reporting why, on failure.
     */
    template <class V>
    bool AddHull(HearthBodyId Body, const HearthShapeDef &Def, const void *Asset, int32_t ElementIndex,
                 const V *VerticesCm, size_t VertexCount, const V &Scale3D) {
        HearthShapes::FGeometryScale Bake;
        if (!HasBody(Body) || !CheckScale(HearthShapes::ConvexScale(Scale3D, Bake), "AddHull", Scale3D)) {
            return false;
        }
        const FGeometryKey Key{Asset, ElementIndex, EGeometry::Hull, Bake.BakeX, Bake.BakeY, Bake.BakeZ};
        int32_t Entry = Find(Key);
        if (Entry < 0) {
            HearthShapes::ConvertPoints(VerticesCm, VertexCount, Bake, Points);
            const HearthHullDef HullDef = hearth_hull_def_default();
            HearthHullId Hull{0, 0};
            if (!Check(hearth_hull_create(World, &HullDef, Points.data(), Points.size(), &Hull), "hearth_hull_create")) {
                return false;
            }
            Entry = Insert(Key, Hull.index, Hull.generation);
        }
        const HearthHullShape Shape{HearthHullId{Geometry[Entry].Index, Geometry[Entry].Generation},
                                    HearthTransform{HearthVec3{0.0f, 0.0f, 0.0f}, HearthQuat{0.0f, 0.0f, 0.0f, 1.0f}},
                                    Bake.Scale.x};
        HearthShapeId Id{0, 0};
        return Use(Body, Entry,
                   Check(hearth_shape_create_hull(World, Body, &Def, &Shape, &Id), "hearth_shape_create_hull"));
    }

    /**
     * An asset's triangles (complex collision: vertices in cm in the component's frame and
     * three indices per triangle in Unreal's winding, as FTriMeshCollisionData holds them) as
     * a mesh shape on a static or kinematic Body, under the component's per-axis scale
     * (mirroring baked; HearthShapes::MeshScale, ConvertIndices). Built on the first use of
     * (Asset, scale signs), shared after that. Returns false, reporting why, on failure.
     */
    template <class V>
    bool AddMesh(HearthBodyId Body, const HearthShapeDef &Def, const void *Asset, const V *VerticesCm,
                 size_t VertexCount, const uint32_t *Indices, size_t IndexCount, const V &Scale3D) {
        HearthShapes::FGeometryScale Bake;
        if (!HasBody(Body) || !CheckScale(HearthShapes::MeshScale(Scale3D, Bake), "AddMesh", Scale3D)) {
            return false;
        }
        const FGeometryKey Key{Asset, -1, EGeometry::Mesh, Bake.BakeX, Bake.BakeY, Bake.BakeZ};
        int32_t Entry = Find(Key);
        if (Entry < 0) {
            HearthShapes::ConvertPoints(VerticesCm, VertexCount, Bake, Points);
            if (Indices != nullptr) {
                HearthShapes::ConvertIndices(Indices, IndexCount, Bake, TriangleIndices);
            }
            HearthMeshId Mesh{0, 0};
            if (!Check(hearth_mesh_create(World, Points.data(), Points.size(),
                                          Indices != nullptr ? TriangleIndices.data() : nullptr, IndexCount, &Mesh),
                       "hearth_mesh_create")) {
                return false;
            }
            Entry = Insert(Key, Mesh.index, Mesh.generation);
        }
        const HearthMeshShape Shape{HearthMeshId{Geometry[Entry].Index, Geometry[Entry].Generation},
                                    HearthTransform{HearthVec3{0.0f, 0.0f, 0.0f}, HearthQuat{0.0f, 0.0f, 0.0f, 1.0f}},
                                    Bake.Scale};
        HearthShapeId Id{0, 0};
        return Use(Body, Entry,
                   Check(hearth_shape_create_mesh(World, Body, &Def, &Shape, &Id), "hearth_shape_create_mesh"));
    }

    /**
     * A landscape's heights (SizeX × SizeY samples, row-major with X fastest, cm in the
     * component's frame, SpacingXCm and SpacingYCm apart; Holes NULL or (SizeX − 1)(SizeY − 1)
     * row-major cell flags, 1 for a hole) as a heightfield shape on a static or kinematic
     * Body, under the component's (positive) scale (HearthShapes::MakeHeightfield), placed by
     * Local in the body's frame (a landscape's collision components sit at their offsets in
     * the landscape actor's frame). Built on the first use of Asset (the landscape collision
     * component), shared after that.
     */
    template <class V>
    bool AddHeightfield(HearthBodyId Body, const HearthShapeDef &Def, const void *Asset, uint32_t SizeX,
                        uint32_t SizeY, const float *HeightsCm, const uint8_t *Holes, double SpacingXCm,
                        double SpacingYCm, const V &Scale3D,
                        const HearthTransform &Local = HearthTransform{HearthVec3{0.0f, 0.0f, 0.0f},
                                                                       HearthQuat{0.0f, 0.0f, 0.0f, 1.0f}}) {
        if (!HasBody(Body)) {
            return false;
        }
        HearthVec3 Scale{1.0f, 1.0f, 1.0f};
        if (!HearthShapes::MakeHeightfield(SizeX, SizeY, HeightsCm, SpacingXCm, SpacingYCm, Scale3D, Heights, Scale)) {
            char Message[256];
            std::snprintf(Message, sizeof Message,
                          "AddHeightfield: a landscape needs at least 2 x 2 samples (got %u x %u), heights, spacing "
                          "above 0 (got %g, %g cm) and a scale of at least 1e-4 on every axis (got %g, %g, %g)",
                          static_cast<unsigned>(SizeX), static_cast<unsigned>(SizeY), SpacingXCm, SpacingYCm,
                          static_cast<double>(Scale3D.X), static_cast<double>(Scale3D.Y),
                          static_cast<double>(Scale3D.Z));
            ReportError("AddHeightfield", Message);
            return false;
        }
        const FGeometryKey Key{Asset, -1, EGeometry::Heightfield, 1.0, 1.0, 1.0};
        int32_t Entry = Find(Key);
        if (Entry < 0) {
            HearthHeightfieldId Field{0, 0};
            if (!Check(hearth_heightfield_create(World, SizeY, SizeX, Heights.data(), Holes, &Field),
                       "hearth_heightfield_create")) {
                return false;
            }
            Entry = Insert(Key, Field.index, Field.generation);
        }
        const HearthHeightfieldShape Shape{
            HearthHeightfieldId{Geometry[Entry].Index, Geometry[Entry].Generation}, Local, Scale};
        HearthShapeId Id{0, 0};
        return Use(Body, Entry,
                   Check(hearth_shape_create_heightfield(World, Body, &Def, &Shape, &Id),
                         "hearth_shape_create_heightfield"));
    }

    /** How many hulls, meshes and heightfields the cache holds. */
    int GetGeometryCount() const { return static_cast<int>(Geometry.size()); }
    /** The shapes using the cached geometry of (Asset, ElementIndex (-1 for meshes and
     * heightfields), Kind, any bake); 0 when none is cached. */
    int GetGeometryUsers(const void *Asset, int32_t ElementIndex, EGeometry Kind) const {
        int Users = 0;
        for (const FGeometry &G : Geometry) {
            if (G.Key.Asset == Asset && G.Key.Element == ElementIndex && G.Key.Kind == Kind) {
                Users += G.Users;
            }
        }
        return Users;
    }
    /** The id (index, generation) of the first cached geometry of (Asset, ElementIndex, Kind);
     * false when none. Ids are HearthHullId, HearthMeshId or HearthHeightfieldId by Kind. */
    bool GetGeometryId(const void *Asset, int32_t ElementIndex, EGeometry Kind, uint32_t &OutIndex,
                       uint32_t &OutGeneration) const {
        for (const FGeometry &G : Geometry) {
            if (G.Key.Asset == Asset && G.Key.Element == ElementIndex && G.Key.Kind == Kind) {
                OutIndex = G.Index;
                OutGeneration = G.Generation;
                return true;
            }
        }
        return false;
    }

    /** Destroys the body and stops tracking it. */
    bool RemoveBody(HearthBodyId Id) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0) {
            return false;
        }
        const bool bOk = Check(hearth_body_destroy(World, Id), "hearth_body_destroy");
        Forget(static_cast<size_t>(Slot));
        return bOk;
    }

    bool HasBody(HearthBodyId Id) const { return SlotOf(Id) >= 0; }
    int GetBodyCount() const { return static_cast<int>(Bodies.size()); }

    // ---- host -> Hearth (before Advance)

    /**
     * The pose of the body's actor at the start of the frame. A kinematic body takes it as its
     * target for this frame. A dynamic or static body whose actor gameplay moved (the pose is
     * not the last one GetRenderPose gave, nor its creation pose) is teleported there instead
     * of snapping back.
     */
    void SyncFromHost(HearthBodyId Id, const HearthTransform &HostPose) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0) {
            return;
        }
        FBody &Body = Bodies[static_cast<size_t>(Slot)];
        if (Body.Type == HEARTH_BODY_KINEMATIC) {
            if (!SamePose(HostPose, Body.KinematicTo)) {
                SetKinematicTarget(Id, HostPose);
            }
        } else if (!SamePose(HostPose, Body.LastShown)) {
            Teleport(Id, HostPose);
        }
    }

    /** Moves the body at once, without sweeping, and shows it there without interpolating
     * from where it was. Velocities are kept, except a kinematic body's (it stops). */
    bool Teleport(HearthBodyId Id, const HearthTransform &Pose) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0 || !Check(hearth_body_set_transform(World, Id, &Pose), "hearth_body_set_transform")) {
            return false;
        }
        ++TeleportCount;
        const size_t At = static_cast<size_t>(Slot);
        FBody &Body = Bodies[At];
        Previous[At] = Pose;
        Current[At] = Pose;
        Body.LastShown = Pose;
        if (Body.Type == HEARTH_BODY_KINEMATIC) {
            const HearthVec3 Zero{0.0f, 0.0f, 0.0f};
            Check(hearth_body_set_linear_velocity(World, Id, Zero), "hearth_body_set_linear_velocity");
            Check(hearth_body_set_angular_velocity(World, Id, Zero), "hearth_body_set_angular_velocity");
            Body.KinematicFrom = Pose;
            Body.KinematicTo = Pose;
            Body.HoldSteps = 0;
        }
        return true;
    }

    /** Kinematic bodies: the actor's pose at the end of this frame. The body follows the path
     * from the previous frame's pose to this one in time with the game clock (see Advance). */
    bool SetKinematicTarget(HearthBodyId Id, const HearthTransform &Target) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0) {
            return false;
        }
        FBody &Body = Bodies[static_cast<size_t>(Slot)];
        if (Body.Type != HEARTH_BODY_KINEMATIC) {
            ReportError("SetKinematicTarget", "SetKinematicTarget: the body is not kinematic");
            return false;
        }
        Body.KinematicTo = Target;
        return true;
    }

    /** A force (N) at the centre of mass for the duration of the current frame. Dynamic
     * bodies only (false for others, as forces do not move them). */
    bool AddForce(HearthBodyId Id, const HearthVec3 &Force) {
        FBody *Body = Dynamic(Id);
        if (!Body || !Finite(Force, "AddForce", "force")) {
            return false;
        }
        Add(Body->FrameForce, Force, 1.0);
        return true;
    }

    /** A force (N) at a world point (m) for the duration of the current frame: the force at the
     * centre of mass plus the torque about it, taken where the body is now. */
    bool AddForceAtPoint(HearthBodyId Id, const HearthVec3 &Force, const HearthVec3 &Point) {
        FBody *Body = Dynamic(Id);
        HearthVec3 Com{0.0f, 0.0f, 0.0f};
        if (!Body || !Finite(Force, "AddForceAtPoint", "force") || !Finite(Point, "AddForceAtPoint", "point") ||
            !Check(hearth_body_get_center_of_mass(World, Id, &Com), "hearth_body_get_center_of_mass")) {
            return false;
        }
        const HearthVec3 Arm{Point.x - Com.x, Point.y - Com.y, Point.z - Com.z};
        Add(Body->FrameForce, Force, 1.0);
        Add(Body->FrameTorque, HearthConversion::Cross(Arm, Force), 1.0);
        return true;
    }

    /** A torque (N·m) for the duration of the current frame. */
    bool AddTorque(HearthBodyId Id, const HearthVec3 &Torque) {
        FBody *Body = Dynamic(Id);
        if (!Body || !Finite(Torque, "AddTorque", "torque")) {
            return false;
        }
        Add(Body->FrameTorque, Torque, 1.0);
        return true;
    }

    /** An impulse (N·s) at the centre of mass, at once; with bVelocityChange it is a change of
     * velocity (m/s) whatever the mass. */
    bool AddImpulse(HearthBodyId Id, const HearthVec3 &Impulse, bool bVelocityChange) {
        if (!Dynamic(Id)) {
            return false;
        }
        HearthVec3 J = Impulse;
        if (bVelocityChange) {
            float Mass = 0.0f;
            if (!Check(hearth_body_get_mass(World, Id, &Mass), "hearth_body_get_mass")) {
                return false;
            }
            J = HearthVec3{Impulse.x * Mass, Impulse.y * Mass, Impulse.z * Mass};
        }
        return Check(hearth_body_apply_linear_impulse(World, Id, J), "hearth_body_apply_linear_impulse");
    }

    /** An impulse (N·s) at a world point (m), at once. */
    bool AddImpulseAtPoint(HearthBodyId Id, const HearthVec3 &Impulse, const HearthVec3 &Point) {
        return Dynamic(Id) &&
               Check(hearth_body_apply_impulse_at_point(World, Id, Impulse, Point), "hearth_body_apply_impulse_at_point");
    }

    /** An angular impulse (N·m·s), at once. */
    bool AddAngularImpulse(HearthBodyId Id, const HearthVec3 &AngularImpulse) {
        return Dynamic(Id) &&
               Check(hearth_body_apply_angular_impulse(World, Id, AngularImpulse), "hearth_body_apply_angular_impulse");
    }

    bool SetLinearVelocity(HearthBodyId Id, const HearthVec3 &Velocity) {
        return HasBody(Id) &&
               Check(hearth_body_set_linear_velocity(World, Id, Velocity), "hearth_body_set_linear_velocity");
    }
    bool SetAngularVelocity(HearthBodyId Id, const HearthVec3 &Velocity) {
        return HasBody(Id) &&
               Check(hearth_body_set_angular_velocity(World, Id, Velocity), "hearth_body_set_angular_velocity");
    }
    bool GetLinearVelocity(HearthBodyId Id, HearthVec3 &Out) {
        return HasBody(Id) &&
               Check(hearth_body_get_linear_velocity(World, Id, &Out), "hearth_body_get_linear_velocity");
    }
    bool GetAngularVelocity(HearthBodyId Id, HearthVec3 &Out) {
        return HasBody(Id) &&
               Check(hearth_body_get_angular_velocity(World, Id, &Out), "hearth_body_get_angular_velocity");
    }
    bool GetMass(HearthBodyId Id, float &Out) {
        return HasBody(Id) && Check(hearth_body_get_mass(World, Id, &Out), "hearth_body_get_mass");
    }
    bool IsAwake(HearthBodyId Id, bool &Out) {
        return HasBody(Id) && Check(hearth_body_is_awake(World, Id, &Out), "hearth_body_is_awake");
    }
    bool SetAwake(HearthBodyId Id, bool bAwake) {
        return HasBody(Id) &&
               Check(hearth_body_set_awake(World, Id, static_cast<uint8_t>(bAwake ? 1 : 0)), "hearth_body_set_awake");
    }

    // ---- stepping

    /**
     * Adds a frame's time (s) and runs the fixed steps it owes; returns how many ran.
     *
     * Time is prorated exactly. The accumulator holds time not yet stepped (less than a
     * step); a step consumes its length from the front: first that carried time, then this
     * frame's. So a step's impulse from forces is what the carried time owed plus this frame's
     * force times the part of the step inside this frame; what is left of the frame after its
     * last step is owed to the next step. A constant force is exactly F·h in every step, at
     * any frame rate. A kinematic body's target at the end of each step is its actor's path
     * (the pose at the end of the last frame to the pose at the end of this one) at the moment
     * the step ends, so its velocity is its actor's, whatever the frames. Transforms are read
     * in one bulk call after each step.
     */
    int Advance(double FrameSeconds) {
        if (!World || bStopped) {
            return 0;
        }
        const double H = Accumulator.GetStepSeconds();
        const double CarriedBefore = Accumulator.GetAccumulated();
        const int Steps = Accumulator.Advance(FrameSeconds);
        const double Frame = Accumulator.GetLastSimulatedSeconds(); // this frame's time, hitches excluded
        if (FrameSeconds > 0.0 && std::isfinite(FrameSeconds)) {
            ClockSeconds += FrameSeconds;
        }
        if (Steps > 0 && Settings.RebuildBroadphaseAfterBodies > 0 &&
            BodiesAddedSinceRebuild >= Settings.RebuildBroadphaseAfterBodies) {
            BodiesAddedSinceRebuild = 0;
            if (Check(hearth_world_rebuild_broadphase(World), "hearth_world_rebuild_broadphase")) {
                ++BroadphaseRebuilds;
            }
        }
        int Ran = 0;
        for (; Ran < Steps; ++Ran) {
            // This step covers [Ran·h, (Ran+1)·h) of the queue (carried time, then the frame).
            const double EndInFrame = static_cast<double>(Ran + 1) * H - CarriedBefore;
            const double StartInFrame = std::fmax(0.0, EndInFrame - H);
            const double InFrame = std::fmax(0.0, EndInFrame - StartInFrame);
            const double Along = Frame > 0.0 ? std::fmin(1.0, std::fmax(0.0, EndInFrame / Frame)) : 1.0;
            for (size_t i = 0; i < Bodies.size(); ++i) {
                PrepareStep(Bodies[i], Ids[i], H, InFrame, Along);
            }
            Previous = Current;
            const HearthResult Stepped = hearth_world_step(World, static_cast<float>(H));
            if (!Check(Stepped, "hearth_world_step")) {
                if (Stepped == HEARTH_ERROR_PANIC) {
                    bStopped = true;
                    ReportError("stopped", "the Hearth world stopped after an internal error and is no longer "
                                           "stepped; recreate it (end and restart play)");
                }
                break; // Previous == Current: shown where it was
            }
            ++StepCount;
            ReadTransforms();
        }
        // What this frame owes after its last step (all of it when no step ran) goes to the
        // next step; the actors' poses now are where the next frame's paths start.
        const double Tail = Steps > 0 ? std::fmax(0.0, CarriedBefore + Frame - static_cast<double>(Steps) * H) : Frame;
        for (FBody &Body : Bodies) {
            Add(Body.CarriedImpulse, Body.FrameForce, Tail);
            Add(Body.CarriedAngularImpulse, Body.FrameTorque, Tail);
            Body.FrameForce = FVec{};
            Body.FrameTorque = FVec{};
            Body.KinematicFrom = Body.KinematicTo;
        }
        return Ran;
    }

    /** The body's pose for rendering now: between its last two steps, at the accumulator's
     * leftover fraction. Remembered, to tell gameplay moves apart in SyncFromHost. */
    bool GetRenderPose(HearthBodyId Id, HearthTransform &Out) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0) {
            return false;
        }
        const size_t At = static_cast<size_t>(Slot);
        Out = HearthConversion::Interpolate(Previous[At], Current[At], Accumulator.Alpha());
        if (Bodies[At].Type != HEARTH_BODY_KINEMATIC) {
            Bodies[At].LastShown = Out;
        }
        return true;
    }

    /** The body's pose after the last step (not interpolated). */
    bool GetSteppedPose(HearthBodyId Id, HearthTransform &Out) const {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0) {
            return false;
        }
        Out = Current[static_cast<size_t>(Slot)];
        return true;
    }

    const HearthConversion::FixedStepAccumulator &GetAccumulator() const { return Accumulator; }
    const FSimulationSettings &GetSettings() const { return Settings; }
    /** Teleports since Create, explicit or of bodies moved by gameplay (SyncFromHost). */
    int GetTeleportCount() const { return TeleportCount; }
    /** Steps run since Create. */
    uint64_t GetStepCount() const { return StepCount; }
    /** Broad-phase rebuilds since Create (FSimulationSettings::RebuildBroadphaseAfterBodies). */
    int GetBroadphaseRebuildCount() const { return BroadphaseRebuilds; }
    /** Frame time passed to Advance since Create (s): the clock of the error throttle. */
    double GetClockSeconds() const { return ClockSeconds; }
    int GetReportedErrorCount() const { return ReportedErrors; }
    int GetHeldBackErrorCount() const { return Throttle.GetHeldBackTotal(); }

    // ---- errors

    /** Reports a failed Hearth call (its name, result name and the library's message) through
     * the throttle; returns Result == HEARTH_OK. The glue's own Hearth calls use it too. */
    bool Check(HearthResult Result, const char *What) {
        if (Result == HEARTH_OK) {
            return true;
        }
        char Detail[256];
        hearth_last_error_message(Detail, sizeof(Detail));
        char Message[512];
        std::snprintf(Message, sizeof(Message), "%s failed: %s (%s)", What, hearth_result_name(Result), Detail);
        ReportError(What, Message);
        return false;
    }

    /** Reports Message under Key through the throttle. */
    void ReportError(const char *Key, const char *Message) {
        int HeldBack = 0;
        if (!Throttle.Admit(Key, ClockSeconds, HeldBack)) {
            return;
        }
        ++ReportedErrors;
        if (!ErrorCallback) {
            return;
        }
        if (HeldBack == 0) {
            ErrorCallback(ErrorUserData, Message);
            return;
        }
        char Full[640];
        std::snprintf(Full, sizeof(Full), "%s (and %d more like it in the last %.0f s)", Message, HeldBack,
                      Throttle.GetIntervalSeconds());
        ErrorCallback(ErrorUserData, Full);
    }

private:
    /** Double-precision accumulators: many small per-frame impulses add up exactly enough. */
    struct FVec {
        double X = 0.0, Y = 0.0, Z = 0.0;
    };
    struct FBody {
        uint32_t Type = HEARTH_BODY_STATIC;
        FVec FrameForce, FrameTorque;                   // added this frame (N, N·m)
        FVec CarriedImpulse, CarriedAngularImpulse;     // owed to the next step (N·s, N·m·s)
        HearthTransform LastShown{};                    // what GetRenderPose last gave
        HearthTransform KinematicFrom{}, KinematicTo{}; // the actor's poses at the ends of the last and this frame
        int HoldSteps = 0;                              // kinematic: steps of holding still left
    };

    static void Add(FVec &To, const FVec &V, double Scale) {
        To.X += V.X * Scale;
        To.Y += V.Y * Scale;
        To.Z += V.Z * Scale;
    }
    static void Add(FVec &To, const HearthVec3 &V, double Scale) {
        To.X += static_cast<double>(V.x) * Scale;
        To.Y += static_cast<double>(V.y) * Scale;
        To.Z += static_cast<double>(V.z) * Scale;
    }
    static bool IsZero(const FVec &V) { return V.X == 0.0 && V.Y == 0.0 && V.Z == 0.0; }
    /** Whether V is finite; if not, reports "<What>: the <Name> is not finite" (the forces are
     * accumulated here, not in Hearth, so this is where they are checked). */
    bool Finite(const HearthVec3 &V, const char *What, const char *Name) {
        if (std::isfinite(V.x) && std::isfinite(V.y) && std::isfinite(V.z)) {
            return true;
        }
        char Message[160];
        std::snprintf(Message, sizeof(Message), "%s: the %s (%g, %g, %g) is not finite; ignored", What, Name,
                      static_cast<double>(V.x), static_cast<double>(V.y), static_cast<double>(V.z));
        ReportError(What, Message);
        return false;
    }
    /** The force (or torque) that delivers Impulse over one step of H seconds. */
    static HearthVec3 PerStep(const FVec &Impulse, double H) {
        return HearthVec3{static_cast<float>(Impulse.X / H), static_cast<float>(Impulse.Y / H),
                          static_cast<float>(Impulse.Z / H)};
    }

    int32_t SlotOf(HearthBodyId Id) const {
        if (Id.index >= SlotByIndex.size()) {
            return -1;
        }
        const int32_t Slot = SlotByIndex[Id.index];
        if (Slot < 0 || Ids[static_cast<size_t>(Slot)].generation != Id.generation) {
            return -1;
        }
        return Slot;
    }
    /** Stops tracking the body in slot At (swap-remove: the arrays stay dense for the bulk read). */
    void Forget(size_t At) {
        ReleaseGeometry(Ids[At]); // its shapes are gone with it
        const size_t Last = Bodies.size() - 1;
        SlotByIndex[Ids[At].index] = -1;
        if (At != Last) {
            Bodies[At] = Bodies[Last];
            Ids[At] = Ids[Last];
            Previous[At] = Previous[Last];
            Current[At] = Current[Last];
            SlotByIndex[Ids[At].index] = static_cast<int32_t>(At);
        }
        Bodies.pop_back();
        Ids.pop_back();
        Previous.pop_back();
        Current.pop_back();
    }
    FBody *Dynamic(HearthBodyId Id) {
        const int32_t Slot = SlotOf(Id);
        if (Slot < 0 || Bodies[static_cast<size_t>(Slot)].Type != HEARTH_BODY_DYNAMIC) {
            return nullptr;
        }
        return &Bodies[static_cast<size_t>(Slot)];
    }

    /** Before one step: the impulse the step owes from forces and torques, as the force that
     * delivers it over the step (the carried part, then InFrame seconds of this frame's), and a
     * kinematic body's target Along its actor's path through this frame (0 = where the last
     * frame ended, 1 = this frame's end). */
    void PrepareStep(FBody &Body, HearthBodyId Id, double H, double InFrame, double Along) {
        if (Body.Type == HEARTH_BODY_DYNAMIC) {
            FVec Impulse = Body.CarriedImpulse, Angular = Body.CarriedAngularImpulse;
            Add(Impulse, Body.FrameForce, InFrame);
            Add(Angular, Body.FrameTorque, InFrame);
            Body.CarriedImpulse = FVec{}; // a step consumes all carried time (less than a step)
            Body.CarriedAngularImpulse = FVec{};
            if (!IsZero(Impulse)) {
                Check(hearth_body_apply_force(World, Id, PerStep(Impulse, H)), "hearth_body_apply_force");
            }
            if (!IsZero(Angular)) {
                Check(hearth_body_apply_torque(World, Id, PerStep(Angular, H)), "hearth_body_apply_torque");
            }
        } else if (Body.Type == HEARTH_BODY_KINEMATIC) {
            if (!SamePose(Body.KinematicFrom, Body.KinematicTo)) {
                const HearthTransform Target = HearthConversion::Interpolate(Body.KinematicFrom, Body.KinematicTo, Along);
                Check(hearth_body_set_target_transform(World, Id, &Target), "hearth_body_set_target_transform");
                Body.HoldSteps = 2;
            } else if (Body.HoldSteps > 0) {
                // The actor stopped: the first step closes the gap to its pose (the body ran
                // behind by the accumulator's leftover), the second holds it there. (Hearth
                // stops a kinematic body at the start of the step after it reached its target;
                // the hold makes the stop explicit and survives a target set in between.)
                Check(hearth_body_set_target_transform(World, Id, &Body.KinematicTo), "hearth_body_set_target_transform");
                Body.HoldSteps -= 1;
            }
        }
    }

    /** Reads every tracked body's transform after a step. A body destroyed behind the
     * simulation's back (hearth_body_destroy on an id it tracks) makes the bulk read fail;
     * such bodies are reported once, dropped, and the read is repeated. */
    void ReadTransforms() {
        if (Ids.empty()) {
            return;
        }
        if (hearth_world_get_transforms(World, Ids.data(), Ids.size(), Current.data()) == HEARTH_OK) {
            return;
        }
        for (size_t i = Ids.size(); i-- > 0;) {
            HearthTransform Probe{};
            if (hearth_body_get_transform(World, Ids[i], &Probe) == HEARTH_ERROR_INVALID_ID) {
                char Message[160];
                std::snprintf(Message, sizeof(Message),
                              "body {%u, %u} was destroyed outside FSimulation::RemoveBody; no longer tracked",
                              static_cast<unsigned>(Ids[i].index), static_cast<unsigned>(Ids[i].generation));
                ReportError("untracked", Message);
                Forget(i);
            }
        }
        if (!Ids.empty()) {
            Check(hearth_world_get_transforms(World, Ids.data(), Ids.size(), Current.data()),
                  "hearth_world_get_transforms");
        }
    }

    struct FGeometryKey {
        const void *Asset;
        int32_t Element;
        EGeometry Kind;
        double BakeX, BakeY, BakeZ;
        bool operator==(const FGeometryKey &O) const {
            return Asset == O.Asset && Element == O.Element && Kind == O.Kind && BakeX == O.BakeX &&
                   BakeY == O.BakeY && BakeZ == O.BakeZ;
        }
    };
    struct FGeometry {
        FGeometryKey Key;
        uint32_t Index, Generation; // the Hearth id, of the kind Key.Kind
        int Users;                  // shapes created through this cache that use it
    };

    int32_t Find(const FGeometryKey &Key) const {
        for (size_t i = 0; i < Geometry.size(); ++i) {
            if (Geometry[i].Key == Key) {
                return static_cast<int32_t>(i);
            }
        }
        return -1;
    }
    int32_t Insert(const FGeometryKey &Key, uint32_t Index, uint32_t Generation) {
        Geometry.push_back(FGeometry{Key, Index, Generation, 0});
        return static_cast<int32_t>(Geometry.size() - 1);
    }
    /** After a shape creation on Body with the geometry in Entry: counts the use when it
     * succeeded, or destroys the geometry if nothing uses it. Returns bCreated. */
    bool Use(HearthBodyId Body, int32_t Entry, bool bCreated) {
        if (bCreated) {
            Geometry[static_cast<size_t>(Entry)].Users += 1;
            GeometryUses.push_back(FUse{Body, Geometry[static_cast<size_t>(Entry)].Key});
        } else {
            DropIfUnused(static_cast<size_t>(Entry));
        }
        return bCreated;
    }
    /** Destroys the geometry in Entry when no shape uses it; Hearth refusing (shapes created
     * outside the cache use it) is reported and the entry kept, to be retried. */
    void DropIfUnused(size_t Entry) {
        const FGeometry G = Geometry[Entry];
        if (G.Users > 0) {
            return;
        }
        bool bDestroyed = false;
        switch (G.Key.Kind) {
        case EGeometry::Hull:
            bDestroyed = Check(hearth_hull_destroy(World, HearthHullId{G.Index, G.Generation}), "hearth_hull_destroy");
            break;
        case EGeometry::Mesh:
            bDestroyed = Check(hearth_mesh_destroy(World, HearthMeshId{G.Index, G.Generation}), "hearth_mesh_destroy");
            break;
        case EGeometry::Heightfield:
            bDestroyed = Check(hearth_heightfield_destroy(World, HearthHeightfieldId{G.Index, G.Generation}),
                               "hearth_heightfield_destroy");
            break;
        }
        if (bDestroyed) {
            Geometry.erase(Geometry.begin() + static_cast<std::ptrdiff_t>(Entry));
        }
    }
    /** Releases the geometry uses of a body that is gone (with its shapes). */
    void ReleaseGeometry(HearthBodyId Body) {
        for (size_t i = GeometryUses.size(); i-- > 0;) {
            const FUse U = GeometryUses[i];
            if (U.Body.index != Body.index || U.Body.generation != Body.generation) {
                continue;
            }
            GeometryUses.erase(GeometryUses.begin() + static_cast<std::ptrdiff_t>(i));
            const int32_t Entry = Find(U.Key);
            if (Entry >= 0) {
                Geometry[static_cast<size_t>(Entry)].Users -= 1;
                DropIfUnused(static_cast<size_t>(Entry));
            }
        }
    }
    template <class V> bool CheckScale(bool bOk, const char *What, const V &Scale3D) {
        if (!bOk) {
            char Message[192];
            std::snprintf(Message, sizeof Message,
                          "%s: every component of the scale must be finite and at least 1e-4 in size, got (%g, %g, %g)",
                          What, static_cast<double>(Scale3D.X), static_cast<double>(Scale3D.Y),
                          static_cast<double>(Scale3D.Z));
            ReportError(What, Message);
        }
        return bOk;
    }

    struct FUse {
        HearthBodyId Body;
        FGeometryKey Key;
    };
    std::vector<FGeometry> Geometry;    // a handful of assets: linear search
    std::vector<FUse> GeometryUses;     // one per shape created through the cache
    std::vector<HearthVec3> Points;     // scratch for conversions
    std::vector<uint32_t> TriangleIndices;
    std::vector<float> Heights;

    HearthWorld *World = nullptr;
    FSimulationSettings Settings;
    HearthConversion::FixedStepAccumulator Accumulator;
    FErrorThrottle Throttle;
    FErrorCallback ErrorCallback = nullptr;
    void *ErrorUserData = nullptr;
    HearthVec3 Gravity{0.0f, 0.0f, 0.0f};
    bool bStopped = false;
    uint64_t StepCount = 0;
    int TeleportCount = 0;
    int BodiesAddedSinceRebuild = 0;
    int BroadphaseRebuilds = 0;
    double ClockSeconds = 0.0;
    int ReportedErrors = 0;

    // One entry per tracked body, dense (swap-removed), in the order of Ids for the bulk read.
    std::vector<FBody> Bodies;
    std::vector<HearthBodyId> Ids;
    std::vector<HearthTransform> Previous; // state before the last step
    std::vector<HearthTransform> Current;  // state after the last step
    std::vector<int32_t> SlotByIndex;      // HearthBodyId.index -> slot, -1 when untracked
};

} // namespace HearthCore
