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

} // namespace HearthShapes
