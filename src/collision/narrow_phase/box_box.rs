//! Box against box.
//!
//! Separating-axis test over the 15 axes (3 faces of A, 3 faces of B, 9 edge pairs) in the
//! frame of box A. The least-penetrating axis, with a bias toward faces (and toward A's
//! faces over B's) so resting stacks keep the same features from frame to frame, decides:
//!
//! * face axis: the incident face of the other box (the one most anti-parallel to the
//!   reference normal) is clipped against the side planes of the reference face
//!   (Sutherland–Hodgman) and the result reduced to at most four points;
//! * edge axis: one point midway between the closest points of the two edges.
//!
//! Feature ids. Face contacts: bit 13 = reference face on B, bits 10..12 = reference face
//! (`2 * axis + negative`), bits 7..9 = incident face, bits 0..6 = the point: 64 + i near
//! incident vertex i, 68 + j near reference corner j, else the pair of lines crossing
//! there (`8 * incoming + outgoing`, lines 0..3 the incident face's edges, 4..7 the
//! reference face's side planes). Edge contacts: bit 31, then the edge of A (bits 8..11)
//! and of B (bits 0..3), each `4 * axis + side`.

use super::geom::{closest_segment_segment, push_point, WorldBox};
use super::Manifold;
use crate::math::Vec3;

/// Face B replaces face A only when better by this relative and absolute slack.
const FACE_REL_TOL: f32 = 0.02;
const FACE_ABS_TOL: f32 = 0.001;
/// An edge axis replaces the best face only when better by this slack.
const EDGE_REL_TOL: f32 = 0.05;
const EDGE_ABS_TOL: f32 = 0.002;
/// The absolute slacks above (and `REDUCE_DEPTH_TOL`) shrink to at most this fraction of the
/// smaller box's smallest half extent, so millimetre boxes choose axes and points like metre
/// ones (a 1 mm slack on a 1 mm box let any axis win).
const ABS_TOL_FRACTION: f32 = 0.02;
/// Edge pairs whose cross product is shorter than this (squared) are parallel: skipped.
const PARALLEL_EDGE_SQ: f32 = 1.0e-6;
/// Polygon capacity while clipping (a quad against four planes has at most 8 vertices).
const CLIP_CAP: usize = 16;
const EDGE_FLAG: u32 = 1 << 31;
const REF_ON_B_FLAG: u32 = 1 << 13;
/// Clipped points within this fraction of the smallest face half extent (and at most
/// `ANCHOR_MAX_TOL` metres) of an incident vertex or reference corner are named after it.
const ANCHOR_REL_TOL: f32 = 0.1;
const ANCHOR_MAX_TOL: f32 = 0.05;
/// Depth difference (metres) under which reduction treats points as equally deep (at most
/// `ABS_TOL_FRACTION` of the boxes' smallest half extent).
const REDUCE_DEPTH_TOL: f32 = 0.001;

#[derive(Clone, Copy, Default)]
struct ClipVertex {
    p: Vec3,
    /// Line the polygon edge leaving this vertex lies on.
    line: u8,
}

#[derive(Clone, Copy, Default)]
struct Candidate {
    p: Vec3,
    sep: f32,
    id: u32,
    /// Squared distance to the feature named by `id` when that is an anchor (else 0).
    anchor_dist: f32,
}

#[inline]
fn sign(x: f32) -> f32 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// Box A against box B.
pub(crate) fn box_box(a: &WorldBox, b: &WorldBox, speculative: f32) -> Manifold {
    // B's axes and centre in A's frame: rc[j][i] = R_ij = dot(a_i, b_j).
    let rc = [
        a.dir_to_local(b.rot.x_axis),
        a.dir_to_local(b.rot.y_axis),
        a.dir_to_local(b.rot.z_axis),
    ];
    let ac = rc.map(|c| c.abs() + Vec3::splat(1.0e-6));
    let t = a.apply_inv(b.center);
    let (ha, hb) = (a.half, b.half);
    let scale = ABS_TOL_FRACTION * ha.min_element().min(hb.min_element());

    let (mut sep_a, mut face_a) = (f32::MIN, 0usize);
    for i in 0..3 {
        let s = t[i].abs() - ha[i] - (hb.x * ac[0][i] + hb.y * ac[1][i] + hb.z * ac[2][i]);
        if s > speculative {
            return Manifold::EMPTY;
        }
        if s > sep_a {
            (sep_a, face_a) = (s, i);
        }
    }
    let (mut sep_b, mut face_b) = (f32::MIN, 0usize);
    for j in 0..3 {
        let s = t.dot(rc[j]).abs() - hb[j] - ha.dot(ac[j]);
        if s > speculative {
            return Manifold::EMPTY;
        }
        if s > sep_b {
            (sep_b, face_b) = (s, j);
        }
    }
    let (mut sep_e, mut edge) = (f32::MIN, (0usize, 0usize));
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            // L = a_i x b_j has components L[i1] = -R[i2][j], L[i2] = R[i1][j].
            let len_sq = rc[j][i1] * rc[j][i1] + rc[j][i2] * rc[j][i2];
            if len_sq < PARALLEL_EDGE_SQ {
                continue;
            }
            let tl = t[i2] * rc[j][i1] - t[i1] * rc[j][i2];
            let ra = ha[i1] * ac[j][i2] + ha[i2] * ac[j][i1];
            let rb = hb[j1] * ac[j2][i] + hb[j2] * ac[j1][i];
            let s = (tl.abs() - ra - rb) / len_sq.sqrt();
            if s > speculative {
                return Manifold::EMPTY;
            }
            if s > sep_e {
                (sep_e, edge) = (s, (i, j));
            }
        }
    }

    let mut best = sep_a;
    let use_b = sep_b > sep_a + FACE_REL_TOL * sep_a.abs() + FACE_ABS_TOL.min(scale);
    if use_b {
        best = sep_b;
    }
    if sep_e > best + EDGE_REL_TOL * best.abs() + EDGE_ABS_TOL.min(2.0 * scale) {
        return edge_contact(a, &rc, t, ha, hb, edge.0, edge.1, speculative);
    }
    if use_b {
        // A's axes and centre in B's frame are the rows of R.
        let axes = [
            Vec3::new(rc[0].x, rc[1].x, rc[2].x),
            Vec3::new(rc[0].y, rc[1].y, rc[2].y),
            Vec3::new(rc[0].z, rc[1].z, rc[2].z),
        ];
        face_contact(b, face_b, b.apply_inv(a.center), &axes, ha, speculative, true)
    } else {
        face_contact(a, face_a, t, &rc, hb, speculative, false)
    }
}

/// One point between edge `a_i` of A and edge `b_j` of B (everything in A's frame).
#[allow(clippy::too_many_arguments)]
fn edge_contact(
    a: &WorldBox,
    rc: &[Vec3; 3],
    t: Vec3,
    ha: Vec3,
    hb: Vec3,
    i: usize,
    j: usize,
    speculative: f32,
) -> Manifold {
    let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
    let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
    let mut n = Vec3::ZERO;
    n[i1] = -rc[j][i2];
    n[i2] = rc[j][i1];
    n = n.normalize();
    if n.dot(t) < 0.0 {
        n = -n;
    }
    // A's edge on the side n points to.
    let (s1, s2) = (sign(n[i1]), sign(n[i2]));
    let mut base_a = Vec3::ZERO;
    base_a[i1] = s1 * ha[i1];
    base_a[i2] = s2 * ha[i2];
    let mut ext_a = Vec3::ZERO;
    ext_a[i] = ha[i];
    // B's edge on the side -n points to.
    let (u1, u2) = (-sign(n.dot(rc[j1])), -sign(n.dot(rc[j2])));
    let base_b = t + (u1 * hb[j1]) * rc[j1] + (u2 * hb[j2]) * rc[j2];
    let ext_b = hb[j] * rc[j];
    let (pa, qa, pb, qb) = (base_a - ext_a, base_a + ext_a, base_b - ext_b, base_b + ext_b);
    let (sa, sb) = closest_segment_segment(pa, qa, pb, qb);
    let ca = pa + sa * (qa - pa);
    let cb = pb + sb * (qb - pb);
    let sep = (cb - ca).dot(n);
    if sep > speculative {
        return Manifold::EMPTY;
    }
    let side = |x: f32, y: f32| (x > 0.0) as u32 + 2 * (y > 0.0) as u32;
    let id_a = 4 * i as u32 + side(s1, s2);
    let id_b = 4 * j as u32 + side(u1, u2);
    let mut m = Manifold {
        normal: a.rot * n,
        ..Manifold::EMPTY
    };
    push_point(&mut m, a.apply(0.5 * (ca + cb)), sep, EDGE_FLAG | id_a << 8 | id_b);
    m
}

/// Clips `input` to the half-space `side * p[axis] <= limit`; the new edge lies on `line`.
fn clip(input: &[ClipVertex], out: &mut [ClipVertex; CLIP_CAP], axis: usize, side: f32, limit: f32, line: u8) -> usize {
    let mut n = 0;
    let count = input.len();
    for idx in 0..count {
        let cur = input[idx];
        let next = input[(idx + 1) % count];
        let dc = side * cur.p[axis] - limit;
        let dn = side * next.p[axis] - limit;
        if dc <= 0.0 && n < CLIP_CAP {
            out[n] = cur;
            n += 1;
        }
        let crossing = (dc < 0.0 && dn > 0.0) || (dc > 0.0 && dn < 0.0);
        if crossing && n < CLIP_CAP {
            let f = dc / (dc - dn);
            // Leaving: continue along the clip line; entering: along the current edge.
            let l = if dc < 0.0 { line } else { cur.line };
            out[n] = ClipVertex {
                p: cur.p + f * (next.p - cur.p),
                line: l,
            };
            n += 1;
        }
    }
    n
}

/// Face contact with reference face `k` of `rf`. The other box is given in `rf`'s frame
/// (centre `c`, unit axes `axes`, half extents `h_inc`). `on_b` says `rf` is box B.
fn face_contact(
    rf: &WorldBox,
    k: usize,
    c: Vec3,
    axes: &[Vec3; 3],
    h_inc: Vec3,
    speculative: f32,
    on_b: bool,
) -> Manifold {
    let h = rf.half;
    let s = sign(c[k]);
    let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);

    // Incident face: most anti-parallel to the reference normal s * e_k.
    let d = [axes[0][k] * s, axes[1][k] * s, axes[2][k] * s];
    let j = if d[0].abs() >= d[1].abs() && d[0].abs() >= d[2].abs() {
        0
    } else if d[1].abs() >= d[2].abs() {
        1
    } else {
        2
    };
    let sj = -sign(d[j]);
    let (u, v) = ((j + 1) % 3, (j + 2) % 3);
    let fc = c + (sj * h_inc[j]) * axes[j];
    let eu = h_inc[u] * axes[u];
    let ev = h_inc[v] * axes[v];

    let mut buf_a = [ClipVertex::default(); CLIP_CAP];
    let mut buf_b = [ClipVertex::default(); CLIP_CAP];
    buf_a[0] = ClipVertex {
        p: fc + eu + ev,
        line: 0,
    };
    buf_a[1] = ClipVertex {
        p: fc - eu + ev,
        line: 1,
    };
    buf_a[2] = ClipVertex {
        p: fc - eu - ev,
        line: 2,
    };
    buf_a[3] = ClipVertex {
        p: fc + eu - ev,
        line: 3,
    };
    let mut n = 4;
    let quad = [buf_a[0].p, buf_a[1].p, buf_a[2].p, buf_a[3].p];
    n = clip(&buf_a[..n], &mut buf_b, k1, 1.0, h[k1], 4);
    n = clip(&buf_b[..n], &mut buf_a, k1, -1.0, h[k1], 5);
    n = clip(&buf_a[..n], &mut buf_b, k2, 1.0, h[k2], 6);
    n = clip(&buf_b[..n], &mut buf_a, k2, -1.0, h[k2], 7);
    let poly = &buf_a[..n];

    let base = if on_b { REF_ON_B_FLAG } else { 0 }
        | ((2 * k as u32 + (s < 0.0) as u32) << 10)
        | ((2 * j as u32 + (sj < 0.0) as u32) << 7);
    // Points this close (in the reference plane) to an incident vertex or a reference
    // corner take that feature's id and merge, so that coincident corners (equal boxes
    // stacked) do not flip between "vertex", "vertex clipped by a side" and "corner".
    let tol = (ANCHOR_REL_TOL * h[k1].min(h[k2]).min(h_inc[u]).min(h_inc[v])).min(ANCHOR_MAX_TOL);
    let tol_sq = tol * tol;
    let dist2 = |p: Vec3, x: f32, y: f32| (p[k1] - x) * (p[k1] - x) + (p[k2] - y) * (p[k2] - y);
    let mut cand = [Candidate::default(); CLIP_CAP];
    let mut m_count = 0;
    for idx in 0..n {
        let vtx = poly[idx];
        let sep = s * vtx.p[k] - h[k];
        if sep > speculative {
            continue;
        }
        let prev = poly[(idx + n - 1) % n].line as u32;
        let mut code = prev * 8 + vtx.line as u32;
        let mut d_anchor = 0.0;
        if let Some((i, d)) = (0..4)
            .map(|i| (i, dist2(vtx.p, quad[i][k1], quad[i][k2])))
            .find(|e| e.1 < tol_sq)
        {
            (code, d_anchor) = (64 + i as u32, d);
        } else if let Some((i, d)) = (0..4)
            .map(|i| {
                let (x, y) = (
                    if i & 1 == 0 { h[k1] } else { -h[k1] },
                    if i & 2 == 0 { h[k2] } else { -h[k2] },
                );
                (i, dist2(vtx.p, x, y))
            })
            .find(|e| e.1 < tol_sq)
        {
            (code, d_anchor) = (68 + i as u32, d);
        }
        let c = Candidate {
            p: vtx.p,
            sep,
            id: base | code,
            anchor_dist: d_anchor,
        };
        // One point per feature: the one nearest the anchor.
        match cand[..m_count].iter_mut().find(|e| e.id == c.id) {
            Some(e) if c.anchor_dist < e.anchor_dist => *e = c,
            Some(_) => {}
            None => {
                cand[m_count] = c;
                m_count += 1;
            }
        }
    }
    if m_count == 0 {
        return Manifold::EMPTY;
    }

    let mut normal_local = Vec3::ZERO;
    normal_local[k] = s;
    let normal = rf.rot * normal_local;
    let mut m = Manifold {
        normal: if on_b { -normal } else { normal },
        ..Manifold::EMPTY
    };
    let depth_tol = REDUCE_DEPTH_TOL.min(ABS_TOL_FRACTION * h.min_element().min(h_inc.min_element()));
    let (keep, kept) = reduce(&cand[..m_count], k1, k2, depth_tol);
    for &ci in &keep[..kept] {
        let cp = cand[ci];
        push_point(&mut m, rf.apply(cp.p - (0.5 * cp.sep) * normal_local), cp.sep, cp.id);
    }
    m
}

#[inline]
fn cross2(o: Vec3, a: Vec3, b: Vec3, k1: usize, k2: usize) -> f32 {
    (a[k1] - o[k1]) * (b[k2] - o[k2]) - (a[k2] - o[k2]) * (b[k1] - o[k1])
}

/// Picks at most four of the candidates (points on the reference plane, coordinates `k1`,
/// `k2`): the deepest (to within `REDUCE_DEPTH_TOL`), the farthest from it, the one making the largest triangle, then the
/// one adding the most area outside that triangle.
fn reduce(c: &[Candidate], k1: usize, k2: usize, depth_tol: f32) -> ([usize; 4], usize) {
    let n = c.len();
    if n <= 4 {
        return ([0, 1, 2, 3], n);
    }
    // Deepest, where points within REDUCE_DEPTH_TOL of the deepest count as equally deep
    // and the one farthest from the centroid wins: a flat contact then starts from a
    // corner of the patch rather than from whichever point noise made deepest.
    let mut min_sep = c[0].sep;
    let (mut cx, mut cy) = (0.0f32, 0.0f32);
    for ci in c {
        min_sep = min_sep.min(ci.sep);
        cx += ci.p[k1];
        cy += ci.p[k2];
    }
    let (cx, cy) = (cx / n as f32, cy / n as f32);
    let (mut i0, mut best) = (0usize, -1.0f32);
    for (i, ci) in c.iter().enumerate() {
        if ci.sep <= min_sep + depth_tol {
            let (dx, dy) = (ci.p[k1] - cx, ci.p[k2] - cy);
            let d = dx * dx + dy * dy;
            if d > best {
                (i0, best) = (i, d);
            }
        }
    }
    let p0 = c[i0].p;
    let (mut i1, mut best) = (usize::MAX, 1.0e-8f32);
    for (i, ci) in c.iter().enumerate() {
        let (dx, dy) = (ci.p[k1] - p0[k1], ci.p[k2] - p0[k2]);
        let d = dx * dx + dy * dy;
        if d > best {
            (i1, best) = (i, d);
        }
    }
    if i1 == usize::MAX {
        return ([i0, 0, 0, 0], 1);
    }
    let p1 = c[i1].p;
    let (mut i2, mut best, mut area) = (usize::MAX, 1.0e-8f32, 0.0f32);
    for (i, ci) in c.iter().enumerate() {
        let a = cross2(p0, p1, ci.p, k1, k2);
        if a.abs() > best {
            (i2, best, area) = (i, a.abs(), a);
        }
    }
    if i2 == usize::MAX {
        return ([i0, i1, 0, 0], 2);
    }
    let p2 = c[i2].p;
    // Positive when outside an edge of the triangle (p0, p1, p2) oriented by `area`.
    let orient = sign(area);
    let (mut i3, mut best) = (usize::MAX, 1.0e-8f32);
    for (i, ci) in c.iter().enumerate() {
        let out = (-orient * cross2(p0, p1, ci.p, k1, k2))
            .max(-orient * cross2(p1, p2, ci.p, k1, k2))
            .max(-orient * cross2(p2, p0, ci.p, k1, k2));
        if out > best {
            (i3, best) = (i, out);
        }
    }
    if i3 == usize::MAX {
        return ([i0, i1, i2, 0], 3);
    }
    ([i0, i1, i2, i3], 4)
}

#[cfg(test)]
#[path = "box_box_tests.rs"]
mod tests;
