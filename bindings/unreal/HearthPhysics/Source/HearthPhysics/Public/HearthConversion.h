// HearthConversion.h - every unit and axis conversion between Unreal Engine and Hearth, plus
// the fixed-step accumulator and the interpolation the world subsystem uses.
//
// Engine-independent on purpose: it includes only hearth.h and <cmath>, and takes Unreal's
// vector and quaternion types as template parameters (anything with X, Y, Z [, W] members and
// a matching constructor: FVector, FVector3f, FQuat, FQuat4f, or the test's stand-ins). It is
// compiled and tested by g++ in the Hearth repository (tests/cpp/test_unreal_conversion.cpp);
// the rest of the plug-in is not (no Unreal Engine there).
//
// ---------------------------------------------------------------------------------------
// The mapping
//
//   Unreal: centimetres, X forward, Y right, Z up, left-handed.
//   Hearth: metres, Y up, right-handed.
//
//   Hearth (x, y, z) = 0.01 * Unreal (X, Z, Y)        Unreal (X, Y, Z) = 100 * Hearth (x, z, y)
//
//   Unreal forward (+X) is Hearth +x, Unreal up (+Z) is Hearth +y, Unreal right (+Y) is
//   Hearth +z. As a matrix this is the swap of the last two coordinates, M = M^-1 = M^T,
//   with det M = -1: exactly one reflection, which is what turns left-handed coordinates into
//   right-handed ones. (Check: in Hearth, x × y = z reads forward × up = right, true for the
//   right-hand rule; in Unreal, X × Y = Z reads forward × right = up, the left-hand rule.)
//
//   Vectors (positions, velocities, accelerations, forces, impulses, normals) map by M.
//
//   Rotations: a rotation matrix R (Unreal coordinates) becomes M R M^-1 in Hearth
//   coordinates, again a proper rotation. Since M(a × b) = det(M) (Ma × Mb), Rodrigues'
//   formula gives M R(axis, angle) M^-1 = R(M axis, -angle): the axis maps like a vector and
//   the angle changes sign (a positive angle turns by the left-hand rule in Unreal and by the
//   right-hand rule in Hearth). For a quaternion (v sin(θ/2), cos(θ/2)):
//
//       Hearth quat (x, y, z, w) = (-X, -Z, -Y, W) of the Unreal quat, normalised.
//
//   Pseudo-vectors (angular velocity, torque, angular impulse) follow the same rule: they map
//   by -M, so that v = ω × r and τ = r × F hold in both frames.
//
//   Units: lengths × 0.01 (cm → m), forces and impulses × 0.01 (Unreal's kg·cm/s² → N),
//   torques × 0.0001 (kg·cm²/s² → N·m), densities × 1000 (g/cm³ → kg/m³), mass (kg), time
//   (s) and angles (rad) unchanged. Unreal's default gravity (0, 0, -980) is Hearth's
//   (0, -9.8, 0).
// ---------------------------------------------------------------------------------------
#pragma once

#include "hearth.h"

#include <cmath>

namespace HearthConversion {

constexpr double MetresPerCentimetre = 0.01;
constexpr double CentimetresPerMetre = 100.0;
constexpr double NewtonsPerUnrealForce = 0.01;           // kg·cm/s² -> N (also impulses)
constexpr double NewtonMetresPerUnrealTorque = 0.0001;   // kg·cm²/s² -> N·m
constexpr double KgPerM3PerGramPerCm3 = 1000.0;          // Unreal densities are g/cm³

namespace Detail {
inline HearthVec3 Swap(double X, double Y, double Z, double Scale) {
    return HearthVec3{static_cast<float>(X * Scale), static_cast<float>(Z * Scale), static_cast<float>(Y * Scale)};
}
template <class V> inline V Unswap(const HearthVec3 &H, double Scale) {
    return V(static_cast<double>(H.x) * Scale, static_cast<double>(H.z) * Scale, static_cast<double>(H.y) * Scale);
}
} // namespace Detail

// ---- Unreal -> Hearth

/** Positions, velocities, accelerations (cm, cm/s, cm/s²) -> m, m/s, m/s². */
template <class V> inline HearthVec3 ToHearthVector(const V &Cm) {
    return Detail::Swap(Cm.X, Cm.Y, Cm.Z, MetresPerCentimetre);
}
/** Unitless directions (normals, axes): no scale. */
template <class V> inline HearthVec3 ToHearthDirection(const V &D) { return Detail::Swap(D.X, D.Y, D.Z, 1.0); }
/** Angular velocities (rad/s) and other pseudo-vectors without length units: -M. */
template <class V> inline HearthVec3 ToHearthAngular(const V &W) { return Detail::Swap(W.X, W.Y, W.Z, -1.0); }
/** Forces and impulses (kg·cm/s², kg·cm/s) -> N, N·s. */
template <class V> inline HearthVec3 ToHearthForce(const V &F) {
    return Detail::Swap(F.X, F.Y, F.Z, NewtonsPerUnrealForce);
}
/** Torques and angular impulses (kg·cm²/s², kg·cm²/s) -> N·m, N·m·s (pseudo-vectors: -M). */
template <class V> inline HearthVec3 ToHearthTorque(const V &T) {
    return Detail::Swap(T.X, T.Y, T.Z, -NewtonMetresPerUnrealTorque);
}
/** Density g/cm³ -> kg/m³. */
inline float ToHearthDensity(double GramsPerCm3) { return static_cast<float>(GramsPerCm3 * KgPerM3PerGramPerCm3); }

/** A normalised Hearth quaternion for an Unreal one; a zero or non-finite input gives identity. */
template <class Q> inline HearthQuat ToHearthQuat(const Q &U) {
    const double X = -U.X, Y = -U.Z, Z = -U.Y, W = U.W;
    const double LenSq = X * X + Y * Y + Z * Z + W * W;
    if (!(LenSq > 1e-12) || !std::isfinite(LenSq)) {
        return HearthQuat{0.0f, 0.0f, 0.0f, 1.0f};
    }
    const double Inv = 1.0 / std::sqrt(LenSq);
    return HearthQuat{static_cast<float>(X * Inv), static_cast<float>(Y * Inv), static_cast<float>(Z * Inv),
                      static_cast<float>(W * Inv)};
}

/** An Unreal location (cm) and rotation -> a Hearth transform (Unreal scale is not physics: ignored). */
template <class V, class Q> inline HearthTransform ToHearthTransform(const V &LocationCm, const Q &Rotation) {
    return HearthTransform{ToHearthVector(LocationCm), ToHearthQuat(Rotation)};
}

// ---- Hearth -> Unreal (V and Q are constructed as V(X, Y, Z) and Q(X, Y, Z, W))

template <class V> inline V ToUnrealVector(const HearthVec3 &M) { return Detail::Unswap<V>(M, CentimetresPerMetre); }
template <class V> inline V ToUnrealDirection(const HearthVec3 &D) { return Detail::Unswap<V>(D, 1.0); }
template <class V> inline V ToUnrealAngular(const HearthVec3 &W) { return Detail::Unswap<V>(W, -1.0); }
template <class V> inline V ToUnrealForce(const HearthVec3 &F) {
    return Detail::Unswap<V>(F, 1.0 / NewtonsPerUnrealForce);
}
template <class V> inline V ToUnrealTorque(const HearthVec3 &T) {
    return Detail::Unswap<V>(T, -1.0 / NewtonMetresPerUnrealTorque);
}
/** The inverse of ToHearthQuat (normalised; zero or non-finite gives identity). */
template <class Q> inline Q ToUnrealQuat(const HearthQuat &H) {
    const double X = -static_cast<double>(H.x), Y = -static_cast<double>(H.z), Z = -static_cast<double>(H.y),
                 W = static_cast<double>(H.w);
    const double LenSq = X * X + Y * Y + Z * Z + W * W;
    if (!(LenSq > 1e-12) || !std::isfinite(LenSq)) {
        return Q(0.0, 0.0, 0.0, 1.0);
    }
    const double Inv = 1.0 / std::sqrt(LenSq);
    return Q(X * Inv, Y * Inv, Z * Inv, W * Inv);
}

// ---- Hearth-side helpers (used by the subsystem and the tests)

inline HearthVec3 Cross(const HearthVec3 &A, const HearthVec3 &B) {
    return HearthVec3{A.y * B.z - A.z * B.y, A.z * B.x - A.x * B.z, A.x * B.y - A.y * B.x};
}

/** Rotates V by the unit quaternion Q (Hearth coordinates). */
inline HearthVec3 Rotate(const HearthQuat &Q, const HearthVec3 &V) {
    // v' = v + 2w (q × v) + 2 q × (q × v)
    const HearthVec3 U{Q.x, Q.y, Q.z};
    const HearthVec3 T = Cross(U, V);
    const HearthVec3 T2{2.0f * T.x, 2.0f * T.y, 2.0f * T.z};
    const HearthVec3 C = Cross(U, T2);
    return HearthVec3{V.x + Q.w * T2.x + C.x, V.y + Q.w * T2.y + C.y, V.z + Q.w * T2.z + C.z};
}

/** Linear interpolation of positions and spherical (shortest-arc) interpolation of rotations:
 * Alpha 0 gives Previous, 1 gives Current. */
inline HearthTransform Interpolate(const HearthTransform &Previous, const HearthTransform &Current, double Alpha) {
    const float A = static_cast<float>(Alpha < 0.0 ? 0.0 : (Alpha > 1.0 ? 1.0 : Alpha));
    HearthTransform Out;
    Out.position = HearthVec3{Previous.position.x + (Current.position.x - Previous.position.x) * A,
                              Previous.position.y + (Current.position.y - Previous.position.y) * A,
                              Previous.position.z + (Current.position.z - Previous.position.z) * A};
    const HearthQuat &P = Previous.rotation;
    HearthQuat C = Current.rotation;
    double Dot = static_cast<double>(P.x) * C.x + static_cast<double>(P.y) * C.y + static_cast<double>(P.z) * C.z +
                 static_cast<double>(P.w) * C.w;
    if (Dot < 0.0) { // q and -q are the same rotation: take the short way round
        C = HearthQuat{-C.x, -C.y, -C.z, -C.w};
        Dot = -Dot;
    }
    double WP = 1.0 - A, WC = A;
    if (Dot < 0.9995) {
        const double Theta = std::acos(Dot > 1.0 ? 1.0 : Dot);
        const double S = std::sin(Theta);
        WP = std::sin((1.0 - A) * Theta) / S;
        WC = std::sin(A * Theta) / S;
    }
    double X = WP * P.x + WC * C.x, Y = WP * P.y + WC * C.y, Z = WP * P.z + WC * C.z, W = WP * P.w + WC * C.w;
    const double Len = std::sqrt(X * X + Y * Y + Z * Z + W * W);
    if (Len > 1e-12) {
        X /= Len;
        Y /= Len;
        Z /= Len;
        W /= Len;
    } else {
        X = Y = Z = 0.0;
        W = 1.0;
    }
    Out.rotation = HearthQuat{static_cast<float>(X), static_cast<float>(Y), static_cast<float>(Z), static_cast<float>(W)};
    return Out;
}

/**
 * A fixed time step driven by variable frame times: Advance(frame) says how many physics steps
 * of StepSeconds to run now, and Alpha() how far the leftover time reaches into the next step,
 * to interpolate the rendered pose between the last two physics states. More than
 * MaxStepsPerFrame steps in one frame are not run: the excess time is dropped (the game slows
 * down instead of spiralling into ever longer frames).
 */
class FixedStepAccumulator {
public:
    explicit FixedStepAccumulator(double InStepSeconds = 1.0 / 60.0, int InMaxStepsPerFrame = 8)
        : StepSeconds(InStepSeconds > 0.0 ? InStepSeconds : 1.0 / 60.0),
          MaxStepsPerFrame(InMaxStepsPerFrame > 0 ? InMaxStepsPerFrame : 1) {}

    /** Adds a frame's time (negative or non-finite times count as 0); returns the steps to run. */
    int Advance(double FrameSeconds) {
        LastFrameSeconds = 0.0;
        LastDroppedSeconds = 0.0;
        if (FrameSeconds > 0.0 && std::isfinite(FrameSeconds)) {
            Accumulated += FrameSeconds;
            LastFrameSeconds = FrameSeconds;
        }
        // A step is due when the accumulator reaches it up to rounding (1/30 s is two 1/60 s steps).
        const double Due = StepSeconds * (1.0 - 1e-9);
        int Steps = 0;
        while (Accumulated >= Due && Steps < MaxStepsPerFrame) {
            Accumulated -= StepSeconds;
            ++Steps;
        }
        if (Accumulated < 0.0) {
            Accumulated = 0.0;
        }
        if (Accumulated >= Due) { // capped: drop whole steps that did not run, keep the fraction
            const double Kept = std::fmod(Accumulated, StepSeconds);
            LastDroppedSeconds = Accumulated - Kept;
            Accumulated = Kept;
            DroppedFrames += 1;
        }
        return Steps;
    }
    /** The time the last Advance added that the simulation will really cover: its frame time
     * (0 if invalid) minus the time it dropped at the cap. Forces applied during that frame act
     * for this long (HearthSimulation.h). */
    double GetLastSimulatedSeconds() const { return LastFrameSeconds - LastDroppedSeconds; }
    /** Whole steps' worth of time the last Advance dropped at the cap (0 when not capped). */
    double GetLastDroppedSeconds() const { return LastDroppedSeconds; }
    /** Leftover time as a fraction of a step, in [0, 1): the interpolation weight of the newest state. */
    double Alpha() const {
        const double A = Accumulated / StepSeconds;
        return A < 0.0 ? 0.0 : (A >= 1.0 ? 0.0 : A);
    }
    double GetStepSeconds() const { return StepSeconds; }
    double GetAccumulated() const { return Accumulated; }
    int GetMaxStepsPerFrame() const { return MaxStepsPerFrame; }
    /** How many frames hit the cap and dropped time. */
    int GetDroppedFrames() const { return DroppedFrames; }
    void Reset() {
        Accumulated = 0.0;
        LastFrameSeconds = 0.0;
        LastDroppedSeconds = 0.0;
        DroppedFrames = 0;
    }

private:
    double StepSeconds;
    int MaxStepsPerFrame;
    double Accumulated = 0.0;
    double LastFrameSeconds = 0.0;
    double LastDroppedSeconds = 0.0;
    int DroppedFrames = 0;
};

} // namespace HearthConversion
