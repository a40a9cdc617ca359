// HearthShapes.h - Unreal simple-collision elements as Hearth shapes.
//
// Engine-independent like HearthConversion.h: it takes Unreal's vector and quaternion types as
// template parameters (FVector and FQuat in the plug-in, stand-ins in the test) and plain
// numbers for the sizes, so the glue passes each element's fields straight from
// UBodySetup::AggGeom:
//
//   FKSphereElem  Center, Radius                      -> MakeSphere
//   FKBoxElem     Center, Rotation, X, Y, Z (edges)   -> MakeBox
//   FKSphylElem   Center, Rotation, Radius, Length    -> MakeCapsule
//   FKConvexElem  VertexData (component space)        -> MakeConvex      (points of a hull)
//   complex collision (GetPhysicsTriMeshData)         -> MakeTriangleMesh (a mesh)
//   landscape heights (row-major, X fastest)          -> MakeHeightfield  (a heightfield)
//
// Hulls, meshes and heightfields are shared geometry: built once per asset and instanced by
// shapes (FSimulation::AddHull/AddMesh/AddHeightfield cache them by asset). So the asset's own
// data is converted unscaled where it can be, and the component's scale goes into the shape:
// a hull takes a uniform scale only, so a non-uniform scale is baked into its points (one
// hull per asset and scale); a mesh or heightfield takes a per-axis scale, with a mirroring
// (negative) component baked into a mesh's vertices (one mesh per asset and sign pattern).
//
// Shapes are placed in the body's frame, which is the component's world transform without
// its scale; the component's scale is baked into the shapes as Unreal bakes it (FKShapeElem's
// GetFinalScaled): centres scale componentwise, a sphere's radius by the smallest absolute
// scale component, a box's edges by the absolute scale along each of its own axes, a
// capsule's radius by the larger of |X| and |Y| scale and its total length by |Z| scale.
// Negative scale components mirror the centres only (Hearth shapes have no mirrored form).
//
// Compiled and tested by g++ in the Hearth repository (tests/cpp/test_unreal_simulation.cpp).
#pragma once

#include "HearthConversion.h"
#include "hearth.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace HearthShapes {

namespace Detail {
inline bool Finite3(double X, double Y, double Z) { return std::isfinite(X) && std::isfinite(Y) && std::isfinite(Z); }

/** A centre scaled componentwise by the (signed) scale. */
template <class V> inline V ScaleCenter(const V &CenterCm, const V &Scale3D) {
    return V(CenterCm.X * Scale3D.X, CenterCm.Y * Scale3D.Y, CenterCm.Z * Scale3D.Z);
}
} // namespace Detail

/**
 * An FKSphereElem (centre and radius in cm, in the component's frame) under the component's
 * scale. Returns false, leaving Out alone, when the result is not a valid sphere (radius not
 * positive, or any number not finite).
 */
template <class V> inline bool MakeSphere(const V &CenterCm, double RadiusCm, const V &Scale3D, HearthSphere &Out) {
    const double MinScale =
        std::fmin(std::fabs(Scale3D.X), std::fmin(std::fabs(Scale3D.Y), std::fabs(Scale3D.Z)));
    const double Radius = RadiusCm * MinScale * HearthConversion::MetresPerCentimetre;
    const V Center = Detail::ScaleCenter(CenterCm, Scale3D);
    if (!(Radius > 0.0) || !std::isfinite(Radius) || !Detail::Finite3(Center.X, Center.Y, Center.Z)) {
        return false;
    }
    Out = HearthSphere{HearthConversion::ToHearthVector(Center), static_cast<float>(Radius)};
    return true;
}

/**
 * An FKBoxElem (centre in cm, rotation, full edge lengths X, Y, Z in cm along its own axes)
 * under the component's scale. Returns false, leaving Out alone, for an edge that is not
 * positive or a number that is not finite.
 */
template <class V, class Q>
inline bool MakeBox(const V &CenterCm, const Q &Rotation, double EdgeXCm, double EdgeYCm, double EdgeZCm,
                    const V &Scale3D, HearthBox &Out) {
    // Half edges along the box's own X, Y, Z; its axes map like vectors (M R M^-1 turns
    // M e_i into M R e_i), so the half extents are swapped like a vector.
    const V Half(0.5 * EdgeXCm * std::fabs(Scale3D.X), 0.5 * EdgeYCm * std::fabs(Scale3D.Y),
                 0.5 * EdgeZCm * std::fabs(Scale3D.Z));
    const V Center = Detail::ScaleCenter(CenterCm, Scale3D);
    if (!(Half.X > 0.0 && Half.Y > 0.0 && Half.Z > 0.0) || !Detail::Finite3(Half.X, Half.Y, Half.Z) ||
        !Detail::Finite3(Center.X, Center.Y, Center.Z)) {
        return false;
    }
    Out = HearthBox{HearthConversion::ToHearthVector(Center), HearthConversion::ToHearthQuat(Rotation),
                    HearthConversion::ToHearthVector(Half)};
    return true;
}

/**
 * An FKSphylElem: a capsule along its rotation's local Z, Radius in cm, Length the distance
 * between the centres of its two end spheres (cm). Returns false, leaving Out alone, for a
 * radius that is not positive, a negative length or a number that is not finite. A capsule
 * squashed below its diameter by the scale becomes a sphere-ended capsule of zero length, as
 * in Unreal.
 */
template <class V, class Q>
inline bool MakeCapsule(const V &CenterCm, const Q &Rotation, double RadiusCm, double LengthCm, const V &Scale3D,
                        HearthCapsule &Out) {
    const double RadiusScale = std::fmax(std::fabs(Scale3D.X), std::fabs(Scale3D.Y));
    double Radius = RadiusCm * RadiusScale;
    const double HalfTotal = (0.5 * LengthCm + RadiusCm) * std::fabs(Scale3D.Z);
    if (Radius > HalfTotal) {
        Radius = HalfTotal;
    }
    const double HalfSegment = HalfTotal - Radius;
    const V Center = Detail::ScaleCenter(CenterCm, Scale3D);
    if (!(Radius > 0.0) || !(LengthCm >= 0.0) || !std::isfinite(Radius) || !std::isfinite(HalfSegment) ||
        !Detail::Finite3(Center.X, Center.Y, Center.Z)) {
        return false;
    }
    const HearthVec3 C = HearthConversion::ToHearthVector(Center);
    // Unreal's local +Z is Hearth's local +y; turned by the element's rotation.
    const HearthVec3 Axis = HearthConversion::Rotate(HearthConversion::ToHearthQuat(Rotation), HearthVec3{0.0f, 1.0f, 0.0f});
    const float H = static_cast<float>(HalfSegment * HearthConversion::MetresPerCentimetre);
    Out = HearthCapsule{HearthVec3{C.x - Axis.x * H, C.y - Axis.y * H, C.z - Axis.z * H},
                        HearthVec3{C.x + Axis.x * H, C.y + Axis.y * H, C.z + Axis.z * H},
                        static_cast<float>(Radius * HearthConversion::MetresPerCentimetre)};
    return true;
}

// ---- shared geometry

/** What a component's scale does to an asset's geometry: Bake is multiplied into the asset's
 * vertices (Unreal axes; part of the cache key, since it changes the geometry) and Scale is
 * the shape's scale (Hearth axes; a hull uses Scale.x, uniform). */
struct FGeometryScale {
    double BakeX = 1.0, BakeY = 1.0, BakeZ = 1.0;
    HearthVec3 Scale{1.0f, 1.0f, 1.0f};
};

namespace Detail {
inline double Sign(double X) { return X < 0.0 ? -1.0 : 1.0; }
inline bool UsableScale(double X) { return std::isfinite(X) && std::fabs(X) >= 1e-4; }
} // namespace Detail

/**
 * How a convex element is instanced under the component's scale: a uniform scale (equal
 * absolute components, to 1e-6 relative) is the hull shape's scale and only its signs are
 * baked (a mirrored hull is a different point set); a non-uniform scale is baked whole, shape
 * scale 1. Returns false for a scale component that is not finite or under 1e-4 in size.
 */
template <class V> inline bool ConvexScale(const V &Scale3D, FGeometryScale &Out) {
    if (!Detail::UsableScale(Scale3D.X) || !Detail::UsableScale(Scale3D.Y) || !Detail::UsableScale(Scale3D.Z)) {
        return false;
    }
    const double AX = std::fabs(Scale3D.X), AY = std::fabs(Scale3D.Y), AZ = std::fabs(Scale3D.Z);
    const double Tol = 1e-6 * AX;
    if (std::fabs(AY - AX) <= Tol && std::fabs(AZ - AX) <= Tol) {
        Out.BakeX = Detail::Sign(Scale3D.X);
        Out.BakeY = Detail::Sign(Scale3D.Y);
        Out.BakeZ = Detail::Sign(Scale3D.Z);
        const float S = static_cast<float>(AX);
        Out.Scale = HearthVec3{S, S, S};
    } else {
        Out.BakeX = Scale3D.X;
        Out.BakeY = Scale3D.Y;
        Out.BakeZ = Scale3D.Z;
        Out.Scale = HearthVec3{1.0f, 1.0f, 1.0f};
    }
    return true;
}

/**
 * How a triangle mesh is instanced: the signs of the scale are baked (mirroring), the
 * absolute values are the shape's per-axis scale, swapped to Hearth's axes. Returns false for
 * a component that is not finite or under 1e-4 in size.
 */
template <class V> inline bool MeshScale(const V &Scale3D, FGeometryScale &Out) {
    if (!Detail::UsableScale(Scale3D.X) || !Detail::UsableScale(Scale3D.Y) || !Detail::UsableScale(Scale3D.Z)) {
        return false;
    }
    Out.BakeX = Detail::Sign(Scale3D.X);
    Out.BakeY = Detail::Sign(Scale3D.Y);
    Out.BakeZ = Detail::Sign(Scale3D.Z);
    Out.Scale = HearthVec3{static_cast<float>(std::fabs(Scale3D.X)), static_cast<float>(std::fabs(Scale3D.Z)),
                           static_cast<float>(std::fabs(Scale3D.Y))};
    return true;
}

/** An asset's vertices (cm, component space) times Bake, in Hearth's axes and metres. */
template <class V>
inline void ConvertPoints(const V *VerticesCm, size_t Count, const FGeometryScale &Bake, std::vector<HearthVec3> &Out) {
    Out.clear();
    Out.reserve(Count);
    for (size_t i = 0; i < Count; ++i) {
        const V &P = VerticesCm[i];
        Out.push_back(HearthConversion::ToHearthVector(V(P.X * Bake.BakeX, P.Y * Bake.BakeY, P.Z * Bake.BakeZ)));
    }
}

/**
 * Triangle indices for Hearth from Unreal's. Unreal winds a triangle (A, B, C) so that its
 * front normal is (C − A) × (B − A) in Unreal coordinates (clockwise seen from the front in
 * its left-handed frame; the static-mesh builder computes normals that way, and
 * UStaticMesh::GetPhysicsTriMeshData sets bFlipNormals for right-handed physics cookers).
 * Hearth's front is (B − A) × (C − A) (counter-clockwise, right-handed). The axis swap M has
 * det −1, so (MB − MA) × (MC − MA) = −M((B − A) × (C − A)) = M((C − A) × (B − A)): the same
 * index order faces the same way after conversion. A mirroring bake (an odd number of
 * negative scale components) reverses it, so then B and C are swapped.
 */
inline void ConvertIndices(const uint32_t *Indices, size_t IndexCount, const FGeometryScale &Bake,
                           std::vector<uint32_t> &Out) {
    const bool bMirrored = (Bake.BakeX * Bake.BakeY * Bake.BakeZ) < 0.0;
    Out.assign(Indices, Indices + IndexCount);
    if (bMirrored) {
        for (size_t i = 0; i + 2 < Out.size(); i += 3) {
            const uint32_t B = Out[i + 1];
            Out[i + 1] = Out[i + 2];
            Out[i + 2] = B;
        }
    }
}

/**
 * A landscape's heights as a heightfield. Unreal stores SizeX × SizeY samples row-major with
 * X fastest (sample (x, y) at HeightsCm[y · SizeX + x], at (x · SpacingXCm, y · SpacingYCm,
 * height) in the component's frame, heights in cm already decoded from the 16-bit data).
 * That point is Hearth (x · SpacingX, height, y · SpacingY) / 100: Unreal X is the
 * heightfield's columns (Hearth x), Unreal Y its rows (Hearth z), so the data is used as it
 * is: rows = SizeY, columns = SizeX, heights in metres. OutScale is the shape's scale: the
 * spacing in metres times the component's X and Y scale, and its Z scale for the heights.
 * Returns false (nothing written) for a size under 2, spacing not positive and finite, or a
 * scale component not positive, finite and at least 1e-4 (a mirrored landscape would turn
 * the ground's front face down).
 */
template <class V>
inline bool MakeHeightfield(uint32_t SizeX, uint32_t SizeY, const float *HeightsCm, double SpacingXCm,
                            double SpacingYCm, const V &Scale3D, std::vector<float> &OutHeights, HearthVec3 &OutScale) {
    if (SizeX < 2 || SizeY < 2 || HeightsCm == nullptr || !(SpacingXCm > 0.0) || !(SpacingYCm > 0.0) ||
        !std::isfinite(SpacingXCm) || !std::isfinite(SpacingYCm) || !(Scale3D.X >= 1e-4) || !(Scale3D.Y >= 1e-4) ||
        !(Scale3D.Z >= 1e-4) || !Detail::Finite3(Scale3D.X, Scale3D.Y, Scale3D.Z)) {
        return false;
    }
    const size_t Count = static_cast<size_t>(SizeX) * SizeY;
    OutHeights.resize(Count);
    for (size_t i = 0; i < Count; ++i) {
        OutHeights[i] = static_cast<float>(HeightsCm[i] * HearthConversion::MetresPerCentimetre);
    }
    OutScale = HearthVec3{static_cast<float>(SpacingXCm * Scale3D.X * HearthConversion::MetresPerCentimetre),
                          static_cast<float>(Scale3D.Z),
                          static_cast<float>(SpacingYCm * Scale3D.Y * HearthConversion::MetresPerCentimetre)};
    return true;
}

} // namespace HearthShapes
