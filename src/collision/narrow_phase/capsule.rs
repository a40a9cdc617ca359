//! Capsule against capsule, box and plane.
//!
//! Feature ids: a point derived from the capsule end `a` (or the single closest point) has
//! id 0, one derived from the end `b` has id 1.

use super::geom::{
    any_perpendicular, closest_segment_segment, push_point, single_point, WorldBox, WorldPlane, DEGENERATE_DIST_SQ,
    FALLBACK_NORMAL,
};
use super::Manifold;
use crate::math::Vec3;

/// Sine of the largest angle between two capsule axes still treated as side by side.
const PARALLEL_SIN: f32 = 0.05;
/// Capsule axis against a box face: largest |cos| of the axis to the face normal that
/// still counts as lying flat on the face.
const FLAT_AXIS_COS: f32 = 0.2;
/// Two clipped points closer than this (metres) collapse into one.
const MIN_POINT_SPACING: f32 = 0.005;
/// Face axes beat edge axes unless the edge is better by this relative and absolute slack.
const EDGE_REL_TOL: f32 = 0.05;
const EDGE_ABS_TOL: f32 = 0.002;
/// The absolute lengths above shrink to at most this fraction of the capsule radius (the
/// smaller radius for two capsules), so a millimetre capsule lying down still gets two points.
const ABS_TOL_FRACTION: f32 = 0.1;

/// `MIN_POINT_SPACING` for a capsule of radius `r`.
#[inline]
fn min_spacing(r: f32) -> f32 {
    MIN_POINT_SPACING.min(ABS_TOL_FRACTION * r)
}

/// Capsule A (world segment `pa`–`qa`) against capsule B.
pub(crate) fn capsule_capsule(pa: Vec3, qa: Vec3, ra: f32, pb: Vec3, qb: Vec3, rb: f32, speculative: f32) -> Manifold {
    let (s, t) = closest_segment_segment(pa, qa, pb, qb);
    let da = qa - pa;
    let db = qb - pb;
    let ca = pa + s * da;
    let cb = pb + t * db;
    let offset = cb - ca;
    let dist_sq = offset.length_squared();
    let rsum = ra + rb;
    let reach = rsum + speculative;
    if dist_sq > reach * reach {
        return Manifold::EMPTY;
    }
    let la_sq = da.length_squared();
    let lb_sq = db.length_squared();

    // Side by side: clip B's segment to A's extent and make two points.
    if la_sq > DEGENERATE_DIST_SQ && lb_sq > DEGENERATE_DIST_SQ {
        let cross = da.cross(db);
        if cross.length_squared() <= PARALLEL_SIN * PARALLEL_SIN * la_sq * lb_sq {
            let la = la_sq.sqrt();
            let ua = da / la;
            let perp = offset - offset.dot(ua) * ua;
            let n = if perp.length_squared() > DEGENERATE_DIST_SQ {
                perp.normalize()
            } else {
                // Coaxial: any perpendicular, turned toward B's midpoint when possible.
                let w = 0.5 * (pb + qb) - pa;
                let w = w - w.dot(ua) * ua;
                if w.length_squared() > DEGENERATE_DIST_SQ {
                    w.normalize()
                } else {
                    any_perpendicular(ua)
                }
            };
            // B's end points as parameters along A's axis.
            let t1 = (pb - pa).dot(ua);
            let t2 = (qb - pa).dot(ua);
            let dt = t2 - t1;
            if dt.abs() > 1.0e-9 {
                let ua0 = (0.0 - t1) / dt;
                let ua1 = (la - t1) / dt;
                let u0 = ua0.min(ua1).max(0.0);
                let u1 = ua0.max(ua1).min(1.0);
                if (u1 - u0) * lb_sq.sqrt() > min_spacing(ra.min(rb)) {
                    let mut m = Manifold {
                        normal: n,
                        ..Manifold::EMPTY
                    };
                    for (u, id) in [(u0, 0u32), (u1, 1u32)] {
                        let on_b = pb + u * db;
                        let on_a = pa + (t1 + u * dt).clamp(0.0, la) * ua;
                        let sep = (on_b - on_a).dot(n) - rsum;
                        if sep <= speculative {
                            push_point(&mut m, on_b - (rb + 0.5 * sep) * n, sep, id);
                        }
                    }
                    return m;
                }
            }
        }
    }

    let dist = dist_sq.sqrt();
    let normal = if dist_sq > DEGENERATE_DIST_SQ {
        offset / dist
    } else {
        // Axes intersect: use their common perpendicular, oriented from A to B.
        let c = da.cross(db);
        let mut n = if c.length_squared() > DEGENERATE_DIST_SQ {
            c.normalize()
        } else if la_sq > DEGENERATE_DIST_SQ {
            any_perpendicular(da / la_sq.sqrt())
        } else if lb_sq > DEGENERATE_DIST_SQ {
            any_perpendicular(db / lb_sq.sqrt())
        } else {
            FALLBACK_NORMAL
        };
        if n.dot((pb + qb) - (pa + qa)) < 0.0 {
            n = -n;
        }
        n
    };
    let sep = dist - rsum;
    let point = 0.5 * (ca + cb + (ra - rb) * normal);
    single_point(normal, point, sep, 0, speculative)
}

/// Capsule A against plane B: one point per end cap within reach.
pub(crate) fn capsule_plane(pa: Vec3, qa: Vec3, r: f32, plane: &WorldPlane, speculative: f32) -> Manifold {
    let n = plane.n;
    let mut m = Manifold {
        normal: -n,
        ..Manifold::EMPTY
    };
    let spacing = min_spacing(r);
    let degenerate = (qa - pa).length_squared() <= spacing * spacing;
    for (p, id) in [(pa, 0u32), (qa, 1u32)] {
        let sep = plane.distance(p) - r;
        if sep <= speculative {
            if degenerate && m.count == 1 {
                // One end is enough; keep the deeper.
                if sep < m.points[0].separation {
                    m.count = 0;
                } else {
                    continue;
                }
            }
            push_point(&mut m, p - (r + 0.5 * sep) * n, sep, id);
        }
    }
    m
}

/// Closest point parameter `t` on the box-frame segment `p + t d` to the box `[-h, h]`, and
/// the squared distance. The squared distance is piecewise quadratic in `t` between the
/// parameters where the segment crosses the slab planes; minimise each piece exactly.
fn segment_box_closest(p: Vec3, d: Vec3, h: Vec3) -> (f32, f32) {
    let mut ts = [0.0f32; 8];
    let mut n = 1;
    for k in 0..3 {
        if d[k].abs() > 1.0e-12 {
            for bound in [-h[k], h[k]] {
                let t = (bound - p[k]) / d[k];
                if t > 0.0 && t < 1.0 {
                    ts[n] = t;
                    n += 1;
                }
            }
        }
    }
    ts[n] = 1.0;
    n += 1;
    // Insertion sort of at most 8 values.
    for i in 1..n {
        let mut j = i;
        while j > 0 && ts[j - 1] > ts[j] {
            ts.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut best = (0.0f32, f32::MAX);
    for w in 0..n - 1 {
        let (t0, t1) = (ts[w], ts[w + 1]);
        let xm = p + (0.5 * (t0 + t1)) * d;
        let (mut num, mut den) = (0.0f32, 0.0f32);
        for k in 0..3 {
            let b = if xm[k] > h[k] {
                h[k]
            } else if xm[k] < -h[k] {
                -h[k]
            } else {
                continue;
            };
            num -= d[k] * (p[k] - b);
            den += d[k] * d[k];
        }
        let t = if den > 1.0e-12 { (num / den).clamp(t0, t1) } else { t0 };
        let x = p + t * d;
        let dd = (x - x.clamp(-h, h)).length_squared();
        if dd < best.1 {
            best = (t, dd);
        }
    }
    best
}

/// Clips the box-frame segment `p`–`q` to the face `sign * e_k` of the box and reports the
/// clipped ends measured along that face normal. Returns `None` when nothing lies over the face.
#[allow(clippy::too_many_arguments)]
fn capsule_face(bx: &WorldBox, p: Vec3, q: Vec3, r: f32, k: usize, sign: f32, speculative: f32) -> Option<Manifold> {
    let h = bx.half;
    let d = q - p;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for j in [(k + 1) % 3, (k + 2) % 3] {
        if d[j].abs() < 1.0e-9 {
            if p[j].abs() > h[j] {
                return None;
            }
            continue;
        }
        let a = (-h[j] - p[j]) / d[j];
        let b = (h[j] - p[j]) / d[j];
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    if t0 > t1 {
        return None;
    }
    let mut f = Vec3::ZERO;
    f[k] = sign;
    let normal = -(bx.rot * f);
    let s0 = p + t0 * d;
    let s1 = p + t1 * d;
    let sep0 = sign * s0[k] - h[k] - r;
    let sep1 = sign * s1[k] - h[k] - r;
    let mut m = Manifold {
        normal,
        ..Manifold::EMPTY
    };
    let spacing = min_spacing(r);
    if (t1 - t0) * (t1 - t0) * d.length_squared() < spacing * spacing {
        let (s, sep, id) = if sep0 <= sep1 { (s0, sep0, 0) } else { (s1, sep1, 1) };
        if sep <= speculative {
            push_point(&mut m, bx.apply(s - (r + 0.5 * sep) * f), sep, id);
        }
        return Some(m);
    }
    for (s, sep, id) in [(s0, sep0, 0u32), (s1, sep1, 1u32)] {
        if sep <= speculative {
            push_point(&mut m, bx.apply(s - (r + 0.5 * sep) * f), sep, id);
        }
    }
    Some(m)
}

/// Capsule A (world segment `pa`–`qa`) against box B.
pub(crate) fn capsule_box(pa: Vec3, qa: Vec3, r: f32, bx: &WorldBox, speculative: f32) -> Manifold {
    let p = bx.apply_inv(pa);
    let q = bx.apply_inv(qa);
    let d = q - p;
    let h = bx.half;
    let dd = d.length_squared();
    let (t, dist_sq) = segment_box_closest(p, d, h);
    let reach = r + speculative;
    if dist_sq > reach * reach {
        return Manifold::EMPTY;
    }

    if dist_sq > 1.0e-10 {
        // Segment outside the box: closest points give the normal.
        let s = p + t * d;
        let c = s.clamp(-h, h);
        let dist = dist_sq.sqrt();
        let n_bc = (s - c) / dist; // box -> capsule, box frame
        let a = n_bc.abs();
        let k = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        // Lying on a face: the closest point is over the face interior (so the normal is
        // the face normal) and the axis is nearly parallel to the face.
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        let flat = s[k1].abs() <= h[k1]
            && s[k2].abs() <= h[k2]
            && dd > DEGENERATE_DIST_SQ
            && d[k] * d[k] <= FLAT_AXIS_COS * FLAT_AXIS_COS * dd;
        if flat {
            let sign = if n_bc[k] >= 0.0 { 1.0 } else { -1.0 };
            if let Some(m) = capsule_face(bx, p, q, r, k, sign, speculative) {
                if m.count > 0 {
                    return m;
                }
            }
        }
        let sep = dist - r;
        let point = c + (0.5 * sep) * n_bc;
        return single_point(-(bx.rot * n_bc), bx.apply(point), sep, 0, speculative);
    }

    // The segment enters the box: separating-axis search over the 6 faces and the
    // 3 box-edge x capsule-axis directions for the least penetration.
    let mut face_sep = f32::MIN;
    let (mut face_k, mut face_sign) = (0usize, 1.0f32);
    for k in 0..3 {
        let plus = p[k].min(q[k]) - h[k];
        let minus = -p[k].max(q[k]) - h[k];
        if plus > face_sep {
            (face_sep, face_k, face_sign) = (plus, k, 1.0);
        }
        if minus > face_sep {
            (face_sep, face_k, face_sign) = (minus, k, -1.0);
        }
    }
    let mut edge_sep = f32::MIN;
    let (mut edge_k, mut edge_axis) = (0usize, Vec3::ZERO);
    for k in 0..3 {
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        let mut axis = Vec3::ZERO;
        axis[k1] = -d[k2];
        axis[k2] = d[k1];
        let len_sq = axis.length_squared();
        if len_sq < 1.0e-6 * dd || dd <= DEGENERATE_DIST_SQ {
            continue;
        }
        axis /= len_sq.sqrt();
        let mut proj = axis.dot(p);
        if proj < 0.0 {
            axis = -axis;
            proj = -proj;
        }
        let sep = proj - h.dot(axis.abs());
        if sep > edge_sep {
            (edge_sep, edge_k, edge_axis) = (sep, k, axis);
        }
    }

    let abs_tol = EDGE_ABS_TOL.min(ABS_TOL_FRACTION * r.min(h.min_element()));
    if edge_sep > face_sep + EDGE_REL_TOL * face_sep.abs() + abs_tol {
        // Box edge along e_k on the side the axis points to.
        let mut base = Vec3::ZERO;
        for j in 0..3 {
            if j != edge_k {
                base[j] = if edge_axis[j] >= 0.0 { h[j] } else { -h[j] };
            }
        }
        let mut ext = Vec3::ZERO;
        ext[edge_k] = h[edge_k];
        let (e0, e1) = (base - ext, base + ext);
        let (sc, se) = closest_segment_segment(p, q, e0, e1);
        let s = p + sc * d;
        let c = e0 + se * (e1 - e0);
        let sep = (s - c).dot(edge_axis) - r;
        let point = s - (r + 0.5 * sep) * edge_axis;
        return single_point(-(bx.rot * edge_axis), bx.apply(point), sep, 0, speculative);
    }

    if let Some(m) = capsule_face(bx, p, q, r, face_k, face_sign, speculative) {
        if m.count > 0 {
            return m;
        }
    }
    // Nothing of the segment over the face: use its deepest end.
    let mut f = Vec3::ZERO;
    f[face_k] = face_sign;
    let (s, id) = if f.dot(p) <= f.dot(q) { (p, 0) } else { (q, 1) };
    let sep = f.dot(s) - h[face_k] - r;
    let point = s - (r + 0.5 * sep) * f;
    single_point(-(bx.rot * f), bx.apply(point), sep, id, speculative)
}

#[cfg(test)]
#[path = "capsule_tests.rs"]
mod tests;
