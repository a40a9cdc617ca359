// What the tests of the Unreal plug-in's engine-independent headers share: CHECK macros and
// stand-ins for Unreal's FVector and FQuat that do what Unreal's do (double members, the
// Hamilton product, FQuat::RotateVector's formula, FVector::CrossProduct's coordinate formula),
// and a small seeded random generator.
#pragma once

#include "hearth.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

static int g_passed = 0;
static int g_failed = 0;

#define CHECK(cond)                                                                             \
    do {                                                                                        \
        if (cond) {                                                                             \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond);       \
        }                                                                                       \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                                   \
    do {                                                                                        \
        const double a_ = (a), b_ = (b);                                                        \
        if (std::fabs(a_ - b_) <= (tol)) {                                                      \
            g_passed++;                                                                         \
        } else {                                                                                \
            g_failed++;                                                                         \
            std::fprintf(stderr, "%s:%d: |%s - %s| = |%g - %g| > %g\n", __FILE__, __LINE__, #a, \
                         #b, a_, b_, (double)(tol));                                            \
        }                                                                                       \
    } while (0)

// ---- stand-ins for Unreal's FVector and FQuat (UE5: double precision)

struct FVector {
    double X, Y, Z;
    FVector(double InX, double InY, double InZ) : X(InX), Y(InY), Z(InZ) {}
    static FVector CrossProduct(const FVector &A, const FVector &B) { // Unreal's coordinate formula
        return FVector(A.Y * B.Z - A.Z * B.Y, A.Z * B.X - A.X * B.Z, A.X * B.Y - A.Y * B.X);
    }
    FVector operator+(const FVector &o) const { return FVector(X + o.X, Y + o.Y, Z + o.Z); }
    FVector operator-(const FVector &o) const { return FVector(X - o.X, Y - o.Y, Z - o.Z); }
    FVector operator*(double s) const { return FVector(X * s, Y * s, Z * s); }
    double Size() const { return std::sqrt(X * X + Y * Y + Z * Z); }
};

struct FQuat {
    double X, Y, Z, W;
    FQuat(double InX, double InY, double InZ, double InW) : X(InX), Y(InY), Z(InZ), W(InW) {}
    FQuat(const FVector &Axis, double AngleRad) { // as Unreal's FQuat(FVector Axis, float AngleRad)
        const double s = std::sin(0.5 * AngleRad);
        X = Axis.X * s;
        Y = Axis.Y * s;
        Z = Axis.Z * s;
        W = std::cos(0.5 * AngleRad);
    }
    FQuat operator*(const FQuat &q) const { // Hamilton product: (this * q) applies q first
        return FQuat(W * q.X + X * q.W + Y * q.Z - Z * q.Y, W * q.Y - X * q.Z + Y * q.W + Z * q.X,
                     W * q.Z + X * q.Y - Y * q.X + Z * q.W, W * q.W - X * q.X - Y * q.Y - Z * q.Z);
    }
    FVector RotateVector(const FVector &V) const { // FQuat::RotateVector
        const FVector Q(X, Y, Z);
        const FVector T = FVector::CrossProduct(Q, V) * 2.0;
        return V + T * W + FVector::CrossProduct(Q, T);
    }
};

// ---- a small deterministic generator for many cases (xorshift64)

static uint64_t g_seed = 0x9E3779B97F4A7C15ull;
static inline double rnd(double lo, double hi) {
    g_seed ^= g_seed << 13;
    g_seed ^= g_seed >> 7;
    g_seed ^= g_seed << 17;
    return lo + (hi - lo) * (double)(g_seed >> 11) / 9007199254740992.0;
}
static inline FVector rnd_vec(double r) { return FVector(rnd(-r, r), rnd(-r, r), rnd(-r, r)); }
static inline FQuat rnd_quat() {
    FVector axis = rnd_vec(1.0);
    const double n = std::sqrt(axis.X * axis.X + axis.Y * axis.Y + axis.Z * axis.Z) + 1e-9;
    return FQuat(axis * (1.0 / n), rnd(-3.1, 3.1));
}

// ---- comparisons

static inline bool near3(const HearthVec3 &a, const HearthVec3 &b, double tol) {
    return std::fabs(a.x - b.x) <= tol && std::fabs(a.y - b.y) <= tol && std::fabs(a.z - b.z) <= tol;
}
static inline bool near3(const FVector &a, const FVector &b, double tol) {
    return std::fabs(a.X - b.X) <= tol && std::fabs(a.Y - b.Y) <= tol && std::fabs(a.Z - b.Z) <= tol;
}
static inline double qlen(const HearthQuat &q) { return std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w); }
// The same rotation: q or -q.
static inline bool same_rotation(const HearthQuat &a, const HearthQuat &b, double tol) {
    const double d = (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z + (double)a.w * b.w;
    return std::fabs(std::fabs(d) - 1.0) <= tol;
}
static inline HearthQuat hq_axis_angle(HearthVec3 axis, double angle) {
    const double n = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    const double s = std::sin(0.5 * angle) / n;
    return HearthQuat{(float)(axis.x * s), (float)(axis.y * s), (float)(axis.z * s), (float)std::cos(0.5 * angle)};
}
