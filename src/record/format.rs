//! The byte-level pieces of the recording format shared by the writer and the reader:
//! magic, version, chunk tags, record kinds, and the compact encodings (LEB128 varints,
//! IEEE half floats, smallest-three quaternions). `docs/recording-format.md` is the spec.

use crate::math::Quat;

/// First eight bytes of every recording.
pub const MAGIC: [u8; 8] = *b"HEARTHRC";
/// Format version written after the magic; a reader refuses newer major layouts.
pub const VERSION: u32 = 1;
/// Size of the file header: magic, version, flags.
pub const HEADER_LEN: usize = 16;
/// Header flag: the step chunks carry contact manifolds.
pub const FLAG_CONTACTS: u32 = 1;

/// Chunk tags (four ASCII bytes, read as a little-endian u32).
pub const TAG_WORLD: [u8; 4] = *b"WRLD";
pub const TAG_DEFS: [u8; 4] = *b"DEFS";
pub const TAG_STEP: [u8; 4] = *b"STEP";
/// Bytes before a chunk's payload: tag and payload length.
pub const CHUNK_HEADER_LEN: usize = 8;

/// Records inside a `DEFS` chunk.
pub const DEF_BODY: u8 = 1;
pub const DEF_BODY_REMOVED: u8 = 2;
pub const DEF_SOFT: u8 = 3;
pub const DEF_SOFT_REMOVED: u8 = 4;

/// Shape kinds inside a body record.
pub const SHAPE_SPHERE: u8 = 0;
pub const SHAPE_BOX: u8 = 1;
pub const SHAPE_CAPSULE: u8 = 2;
pub const SHAPE_PLANE: u8 = 3;

/// Body types.
pub const BODY_STATIC: u8 = 0;
pub const BODY_KINEMATIC: u8 = 1;
pub const BODY_DYNAMIC: u8 = 2;

/// Joint kinds.
pub const JOINT_BALL: u8 = 0;
pub const JOINT_HINGE: u8 = 1;
pub const JOINT_FIXED: u8 = 2;
pub const JOINT_DISTANCE: u8 = 3;
pub const JOINT_SLIDER: u8 = 4;
/// A joint kind this version of the format has no code for.
pub const JOINT_OTHER: u8 = 255;

/// "No body": the world side of a joint.
pub const NO_BODY: u32 = u32::MAX;

/// Counters in a step chunk, in this order (u32 each).
pub const STEP_COUNTERS: usize = 10;

/// Largest magnitude of the three smallest components of a unit quaternion: 1/√2.
const SMALLEST_THREE_RANGE: f32 = std::f32::consts::FRAC_1_SQRT_2;
/// Each of the three components gets 15 bits.
const SMALLEST_THREE_STEPS: f32 = 32767.0;

/// Packs a rotation into 48 bits: the index of the largest component (2 bits), then the other
/// three in order, each mapped from [-1/√2, 1/√2] to 15 bits. The largest is made positive
/// (q and -q are the same rotation) and rebuilt as √(1 − Σc²). Error per component ≤ 2.2e-5;
/// a rotated unit vector is off by less than 1.5e-4 (about 0.01°).
#[inline]
pub fn pack_quat(q: Quat) -> [u8; 6] {
    // Bodies keep unit rotations; renormalise only one that drifted.
    let q = if (q.length_squared() - 1.0).abs() > 1.0e-5 {
        q.normalize()
    } else {
        q
    };
    let c = [q.x, q.y, q.z, q.w];
    let mut largest = 0;
    for i in 1..4 {
        if c[i].abs() > c[largest].abs() {
            largest = i;
        }
    }
    let sign = if c[largest] < 0.0 { -1.0 } else { 1.0 };
    let mut bits: u64 = largest as u64;
    let mut shift = 2;
    for (i, &v) in c.iter().enumerate() {
        if i == largest {
            continue;
        }
        let unit = (sign * v / SMALLEST_THREE_RANGE * 0.5 + 0.5).clamp(0.0, 1.0);
        let quantised = (unit * SMALLEST_THREE_STEPS + 0.5) as u64;
        bits |= quantised << shift;
        shift += 15;
    }
    let b = bits.to_le_bytes();
    [b[0], b[1], b[2], b[3], b[4], b[5]]
}

/// The inverse of `pack_quat` (a unit quaternion).
pub fn unpack_quat(b: [u8; 6]) -> Quat {
    let bits = u64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], 0, 0]);
    let largest = (bits & 3) as usize;
    let mut c = [0.0f32; 4];
    let mut shift = 2;
    let mut sum = 0.0;
    for (i, slot) in c.iter_mut().enumerate() {
        if i == largest {
            continue;
        }
        let quantised = ((bits >> shift) & 0x7fff) as f32;
        let v = (quantised / SMALLEST_THREE_STEPS - 0.5) * 2.0 * SMALLEST_THREE_RANGE;
        *slot = v;
        sum += v * v;
        shift += 15;
    }
    c[largest] = (1.0 - sum).max(0.0).sqrt();
    Quat::from_xyzw(c[0], c[1], c[2], c[3]).normalize()
}

/// IEEE 754 binary16 of `v`, rounded to nearest even; beyond ±65504 it saturates there (a
/// recording never holds an infinity), NaN stays NaN.
#[inline]
pub fn f32_to_f16(v: f32) -> u16 {
    let x = v.to_bits();
    let abs = x & 0x7fff_ffff;
    // Fast path: results that are normal halves and cannot round up to infinity
    // (2^-14 <= |v| < 65520). Adding 0x0fff plus the lowest kept bit rounds to nearest even;
    // a carry moves into the exponent, which is still right.
    if (0x3880_0000..0x477f_f000).contains(&abs) {
        let sign = ((x >> 16) & 0x8000) as u16;
        return sign | ((abs + 0x0fff + ((abs >> 13) & 1) - 0x3800_0000) >> 13) as u16;
    }
    f32_to_f16_general(v)
}

/// `f32_to_f16` for every input: zero, subnormal results, saturation, NaN.
fn f32_to_f16_general(v: f32) -> u16 {
    let x = v.to_bits();
    let sign = ((x >> 16) & 0x8000) as u16;
    let exp = ((x >> 23) & 0xff) as i32;
    let man = x & 0x7f_ffff;
    if exp == 0xff {
        return if man != 0 { sign | 0x7e00 } else { sign | 0x7bff };
    }
    let e = exp - 127 + 15;
    if e >= 0x1f {
        return sign | 0x7bff;
    }
    if e <= 0 {
        if e < -10 {
            return sign;
        }
        // Subnormal: shift the mantissa (with its implicit 1) into place, rounding.
        let m = man | 0x80_0000;
        let shift = (14 - e) as u32;
        let half = 1u32 << (shift - 1);
        let rest = m & ((1 << shift) - 1);
        let mut h = m >> shift;
        if rest > half || (rest == half && h & 1 == 1) {
            h += 1;
        }
        return sign | h as u16;
    }
    let mut h = ((e as u32) << 10) | (man >> 13);
    let rest = man & 0x1fff;
    if rest > 0x1000 || (rest == 0x1000 && h & 1 == 1) {
        h += 1; // may carry into the exponent, which is still right
    }
    if h >= 0x7c00 {
        return sign | 0x7bff;
    }
    sign | h as u16
}

/// The f32 value of an IEEE binary16.
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let man = (h & 0x3ff) as f32;
    match exp {
        0 => sign * man * 2f32.powi(-24),
        0x1f => {
            if man != 0.0 {
                f32::NAN
            } else {
                sign * f32::INFINITY
            }
        }
        _ => sign * (1.0 + man / 1024.0) * 2f32.powi(exp - 15),
    }
}

/// Appends `v` as an unsigned LEB128 varint (7 bits per byte, high bit = more).
#[inline]
pub fn put_varint(out: &mut Vec<u8>, mut v: u32) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn quaternions_survive_smallest_three_within_its_stated_error() {
        // Seeded sweep over random rotations, plus the axes and their negatives.
        let mut s = 0x2545_f491_u32;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            s as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        let mut worst = 0.0f32;
        let mut quats: Vec<Quat> = (0..4)
            .flat_map(|i| {
                let mut c = [0.0; 4];
                c[i] = 1.0;
                [Quat::from_array(c), -Quat::from_array(c)]
            })
            .collect();
        for _ in 0..10_000 {
            quats.push(Quat::from_xyzw(next(), next(), next(), next()).normalize());
        }
        for q in quats {
            let r = unpack_quat(pack_quat(q));
            // Same rotation: q and -q are equal; compare the rotated axes.
            for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
                worst = worst.max((q * axis - r * axis).length());
            }
        }
        // Each of three components is off by at most half a step (2.2e-5), the rebuilt one
        // follows; a rotated unit vector moves by about twice the quaternion's error.
        // Measured worst: 1.04e-4.
        assert!(worst < 1.5e-4, "worst rotated-axis error {worst}");
    }

    #[test]
    fn half_floats_round_to_nearest_and_saturate() {
        for v in [0.0f32, 1.0, -2.5, 0.1, 1000.0, 65504.0, 6.1e-5, 1.0e-7, -3.3e-6] {
            let back = f16_to_f32(f32_to_f16(v));
            let tolerance = (v.abs() * 4.9e-4).max(3.0e-8);
            assert!((back - v).abs() <= tolerance, "{v} -> {back}");
        }
        assert_eq!(f16_to_f32(f32_to_f16(1.0e6)), 65504.0);
        assert_eq!(f16_to_f32(f32_to_f16(-1.0e6)), -65504.0);
        assert_eq!(f16_to_f32(f32_to_f16(f32::INFINITY)), 65504.0);
        assert!(f16_to_f32(f32_to_f16(f32::NAN)).is_nan());
        // Every half float converts exactly to f32 and back.
        for h in 0..=0xffffu16 {
            let v = f16_to_f32(h);
            if v.is_finite() {
                assert_eq!(f32_to_f16(v), h, "{h:#06x} = {v}");
            }
        }
    }

    #[test]
    fn the_fast_half_float_path_agrees_with_the_general_one() {
        let mut s = 0x9e37_79b9_u32;
        for i in 0..2_000_000u32 {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            // Random bit patterns, and a dense sweep around the fast path's edges.
            let bits = if i % 2 == 0 {
                s
            } else {
                0x3880_0000u32.wrapping_sub(50_000).wrapping_add(i)
            };
            let v = f32::from_bits(bits);
            let (a, b) = (f32_to_f16(v), f32_to_f16_general(v));
            assert!(
                a == b || (v.is_nan() && a & 0x7e00 == 0x7e00),
                "{v:e} ({bits:#x}): {a:#x} vs {b:#x}"
            );
        }
        for bits in 0x477f_0000u32..0x4780_1000 {
            let v = f32::from_bits(bits);
            assert_eq!(f32_to_f16(v), f32_to_f16_general(v), "{v}");
            assert_eq!(f32_to_f16(-v), f32_to_f16_general(-v), "{}", -v);
        }
    }

    #[test]
    fn varints_use_seven_bits_a_byte() {
        for (v, len) in [
            (0u32, 1usize),
            (127, 1),
            (128, 2),
            (16_383, 2),
            (16_384, 3),
            (u32::MAX, 5),
        ] {
            let mut out = Vec::new();
            put_varint(&mut out, v);
            assert_eq!(out.len(), len, "{v}");
            let mut r = super::super::read::Cursor::new(&out);
            assert_eq!(r.varint().unwrap(), v);
        }
    }
}
