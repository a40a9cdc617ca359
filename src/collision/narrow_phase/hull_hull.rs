//! Hull against hull (and box against hull, the box seen as the unit-box hull scaled).
//!
//! Separating-axis test after Gregorius ("The Separating Axis Test between Convex
//! Polyhedra", GDC 2013), in the frame of A:
//!
//! 1. **Cached axis.** The feature that decided last time (`SatCache`: a face of A, a face
//!    of B or an edge pair) is tried first; if it still separates the shapes by more than
//!    the speculative distance, there is no contact and nothing else is computed.
//! 2. **Face axes** of A (B's least projection on each plane, four vertices at a time:
//!    `ConvexHull::min_dot`) and of B, unless the **face hold** decides: after a face
//!    decision the cache keeps the pose and the margins by which that face beat the other
//!    faces (`FaceHold`); a face's separation moves by at most `|ΔR|·reach + |Δt|` with
//!    the pose, so while that bound is under the margins the loops would pick the same
//!    face and are skipped (same result bit for bit). In the loops, a face whose
//!    separation from the other hull's centre of mass (which bounds its own) is under the
//!    separations of the two faces of largest such bound is skipped (`best_face_bounded`).
//! 3. **GJK bound.** GJK's distance (or its overlap verdict) bounds every axis's
//!    separation from above; when it leaves no room for an edge axis to end the test or
//!    to beat the best face by the edge slack, the edge loop below is skipped (same result,
//!    most resting and face-closest pairs).
//! 4. **Edge pairs** only where the two edges' arcs on the Gauss map cross (the pair
//!    builds a face of the Minkowski difference — four dot products reject the rest): the
//!    axis is the cross product, oriented out of A, and the separation is measured between
//!    the two edges. When the cores overlap, only edges that reach near the other hull
//!    across the best face's plane can make the deciding pair (the pair of the deepest
//!    axis crosses within the penetration depth); the others are left out. When they are
//!    apart, only edges whose arcs come near GJK's direction can (an axis separates the
//!    cores by at most its cosine with that direction times GJK's distance, and the pair
//!    must beat the margins and the last test's pair: `apart_cone`).
//!
//! Every axis whose separation exceeds the speculative distance (plus the radii) ends the
//! test early. The least separated axis, biased toward faces (and toward A's faces over
//! B's) so resting contacts keep their features, decides:
//!
//! * a face: the incident face of the other hull (most anti-parallel) is clipped against
//!   the reference face's side planes (each incident edge by Cyrus–Beck, which is
//!   Sutherland–Hodgman one edge at a time, plus the reference corners that lie over the
//!   incident face, plus the incident hull's deepest vertex when it is off the incident
//!   face) and the points reduced to four by area;
//! * an edge pair: one point between the closest points of the two edges.
//!
//! When the cores are apart, the best axis gives the true distance only if a face or an
//! edge pair is closest; GJK measures it and, when it is clearly larger (a corner is
//! closest), the contact is GJK's single point, so speculative contacts never understate
//! the gap.

use super::hull::{feature_id, one_point, Candidate, Candidates, InA, Own, Poly, Relative};
use super::Manifold;
use crate::collision::gjk;
use crate::math::{Mat3, Vec3};
use crate::simd::{Lanes, F4};

/// The feature that decided the last test of a pair (see the module doc).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SatFeature {
    #[default]
    None,
    FaceA(u16),
    FaceB(u16),
    /// Entries of the two hulls' `edges`.
    Edges(u16, u16),
}

/// What a pair keeps between tests (kept in its contact; see the module doc): the
/// deciding feature and, after a face decision, the hold that can skip the next searches.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SatCache {
    pub feature: SatFeature,
    pub hold: FaceHold,
}

/// A face decision and its margins, at B's pose in A's frame when the face loops took it.
/// Every face's separation moves by at most `pose_change` from there, so while the
/// margins exceed that change the face loops would pick the same face again and are
/// skipped (`holds`); GJK and the edge pairs run as after the loops.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FaceHold {
    /// The last full test decided on `feature`, a face, and stored the rest.
    pub valid: bool,
    /// B's rotation and position in A's frame then.
    pub r: Mat3,
    pub t: Vec3,
    /// The largest separation of the chosen hull's other faces then.
    pub same: f32,
    /// The largest separation of the other hull's faces then.
    pub other: f32,
}

/// Face B replaces face A only when better by this relative and absolute slack.
const FACE_REL_TOL: f32 = 0.02;
const FACE_ABS_TOL: f32 = 0.001;
/// An edge axis replaces the best face only when better by this slack.
const EDGE_REL_TOL: f32 = 0.05;
const EDGE_ABS_TOL: f32 = 0.002;
/// Separated cores: GJK's distance replaces the best axis when larger by this slack.
const GJK_REL_TOL: f32 = 0.02;
const GJK_ABS_TOL: f32 = 0.001;
/// Slack of the face hold for rounding (relative to the shapes' reach, m).
const HOLD_ROUNDING: f32 = 1.0e-5;
/// Slack of the edge pairs' pruning under overlap (m, and relative to the shapes' reach).
const EDGE_PRUNE_SLACK: f32 = 1.0e-4;
/// Blocks of four edges of the largest hull (`3 V − 6` edges for `V` vertices).
const MAX_EDGE_BLOCKS: usize = (3 * crate::collision::hull::MAX_HULL_VERTICES - 6).div_ceil(4);

/// What GJK's overlap verdict leaves as a possible separation (its termination tolerance is
/// 1e-7 m; this is far above it and far below `EDGE_ABS_TOL`).
const GJK_OVERLAP_BOUND: f32 = 1.0e-5;

const KIND_FACE_A: u32 = 1;
const KIND_FACE_B: u32 = 2;
const KIND_EDGE: u32 = 3;
const KIND_GJK: u32 = 4;

/// Separation of B from face `f` of A (A's frame): the least `n · (R·v + t) − offset`
/// over B's vertices `v`, taken as `(Rᵀn) · v` in B's frame.
#[inline(always)]
fn face_a_separation(a: &Poly, b: &Poly, rel: &Relative, f: usize) -> f32 {
    let pl = a.plane(f);
    b.hull.min_dot((rel.rt * pl.normal) * b.scale) + pl.normal.dot(rel.t) - pl.offset
}

/// Separation of A from face `f` of B (B's plane in A's frame).
#[inline(always)]
fn face_b_separation(a: &Poly, b: &Poly, rel: &Relative, f: usize) -> f32 {
    let pl = b.plane(f);
    let n = rel.r * pl.normal;
    let d = pl.offset + n.dot(rel.t);
    a.hull.min_dot(n * a.scale) - d
}

/// An edge pair's axis (out of A) and separation, `None` when parallel.
#[inline(always)]
fn edge_pair(a: &Poly, b: &Poly, rel: &Relative, ea: usize, eb: usize) -> Option<(Vec3, f32)> {
    let ga = a.hull.edge_gauss[ea];
    let gb = b.hull.edge_gauss[eb];
    let (pa0, pa1) = (a.vertex(ga.v0 as usize), a.vertex(ga.v1 as usize));
    let pb0 = rel.r * b.vertex(gb.v0 as usize) + rel.t;
    let pb1 = rel.r * b.vertex(gb.v1 as usize) + rel.t;
    edge_axis(pa0, pa1, ga.n1 + ga.n2, pb0, pb1)
}

#[inline(always)]
fn edge_axis(pa0: Vec3, pa1: Vec3, out_a: Vec3, pb0: Vec3, pb1: Vec3) -> Option<(Vec3, f32)> {
    let (da, db) = (pa1 - pa0, pb1 - pb0);
    let axis = da.cross(db);
    let l2 = axis.length_squared();
    if l2 < 1.0e-10 * da.length_squared() * db.length_squared() {
        return None;
    }
    let mut axis = axis / l2.sqrt();
    if axis.dot(out_a) < 0.0 {
        axis = -axis;
    }
    Some((axis, axis.dot(pb0 - pa0)))
}

/// Separation along any axis (out of A) by the support functions: a lower bound of the
/// distance that holds for every axis.
#[inline]
fn support_separation(a: &Poly, b: &Poly, rel: &Relative, axis: Vec3) -> f32 {
    let pa = a.vertex(a.support_index(axis));
    let pb = rel.r * b.vertex(b.support_index(rel.rt * -axis)) + rel.t;
    axis.dot(pb - pa)
}

/// Separation of the cached feature, if it still exists.
fn cached_separation(a: &Poly, b: &Poly, rel: &Relative, feature: SatFeature) -> Option<f32> {
    match feature {
        SatFeature::None => None,
        SatFeature::FaceA(f) if (f as usize) < a.hull.planes.len() => Some(face_a_separation(a, b, rel, f as usize)),
        SatFeature::FaceB(f) if (f as usize) < b.hull.planes.len() => Some(face_b_separation(a, b, rel, f as usize)),
        SatFeature::Edges(ea, eb) if (ea as usize) < a.hull.edges.len() && (eb as usize) < b.hull.edges.len() => {
            edge_pair(a, b, rel, ea as usize, eb as usize).map(|(axis, _)| support_separation(a, b, rel, axis))
        }
        _ => None,
    }
}

/// How far any face's separation (and the cores' distance) can have moved since the
/// hold's pose: B's vertices move in A's frame by at most `|ΔR|·reach(B) + |Δt|`, A's in
/// B's frame by `|ΔR|·reach(A) + |Δ(Rᵀt)|` (the Frobenius norm bounds the rotation's),
/// plus rounding slack.
fn pose_change(a: &Poly, b: &Poly, rel: &Relative, hold: &FaceHold) -> f32 {
    let dr = Mat3::from(rel.r) - hold.r;
    let dr = (dr.x_axis.length_squared() + dr.y_axis.length_squared() + dr.z_axis.length_squared()).sqrt();
    let (reach_a, reach_b) = (a.reach(), b.reach());
    let move_b = dr * reach_b + (rel.t - hold.t).length();
    let move_a = dr * reach_a + (rel.rt * rel.t - hold.r.transpose() * hold.t).length();
    move_a.max(move_b) + HOLD_ROUNDING * (1.0 + reach_a + reach_b + rel.t.length())
}

/// The face hold decides (see `FaceHold`): the held face, at separation `s` now (computed
/// as the full test would), still beats its hull's other faces (each at most `same +
/// delta` now) and the other hull's (with the face bias; `other + delta`), and no face
/// separates the shapes beyond `limit`: the face loops' comparisons, each with its bound,
/// so they would pick this face.
fn holds(hold: &FaceHold, on_b: bool, s: f32, delta: f32, limit: f32) -> bool {
    let bias = |x: f32| x + FACE_REL_TOL * x.abs() + FACE_ABS_TOL;
    let (same, other) = (hold.same + delta, hold.other + delta);
    let beats_other = if on_b { s > bias(other) } else { other <= bias(s) };
    hold.valid && s <= limit && same < s && beats_other && same <= limit && other <= limit
}

/// Hull A against hull B (either may be a box); `cache` carries the deciding feature
/// (and the face hold) between calls for the same pair.
pub(crate) fn hull_hull(a: &Poly, b: &Poly, speculative: f32, cache: &mut SatCache) -> Manifold {
    hull_hull_with(a, b, speculative, cache, true, true)
}

/// `hull_hull`, with the edge pairs' pruning (under overlap and apart) and the face
/// bounds on or off (tests compare).
fn hull_hull_with(
    a: &Poly,
    b: &Poly,
    speculative: f32,
    cache: &mut SatCache,
    prune_edges: bool,
    prune_faces: bool,
) -> Manifold {
    let rel = Relative::new(a, b);
    let r = a.radius + b.radius;
    let limit = speculative + r;
    let previous = cache.feature;
    let mut held = None;
    if let Some(s) = cached_separation(a, b, &rel, cache.feature) {
        if s > limit {
            return Manifold::EMPTY;
        }
        if cache.hold.valid {
            let delta = pose_change(a, b, &rel, &cache.hold);
            held = match cache.feature {
                SatFeature::FaceA(f) if holds(&cache.hold, false, s, delta, limit) => Some((false, f as usize, s)),
                SatFeature::FaceB(f) if holds(&cache.hold, true, s, delta, limit) => Some((true, f as usize, s)),
                _ => None,
            };
        }
    }
    // The hold comes back only when a face decides again.
    let hold = cache.hold;
    cache.hold.valid = false;
    // The best face of A and of B, and which decides (with the margins for a new hold):
    // from the hold, or searched.
    let (use_b, face_a, face_b, best_face, margins) = if let Some((on_b, f, s)) = held {
        (on_b, f, f, s, None)
    } else {
        // Faces of A (with the runner-up, for the face hold), then of B. A face separates
        // the other hull by at most the separation of that hull's centre of mass (a point
        // of its core), which leaves out the faces that cannot be best or runner-up
        // (`best_face_bounded`).
        let slack = HOLD_ROUNDING * (1.0 + a.reach() + b.reach() + rel.t.length());
        let faces_a = best_face_of(
            a,
            b,
            |c| rel.r * c + rel.t,
            prune_faces,
            limit,
            slack,
            |f| face_a_separation(a, b, &rel, f),
        );
        let (sep_a, face_a, second_a) = match faces_a {
            Ok(best) => best,
            Err(f) => {
                cache.feature = SatFeature::FaceA(f as u16);
                return Manifold::EMPTY;
            }
        };
        let faces_b = best_face_of(
            b,
            a,
            |c| rel.rt * (c - rel.t),
            prune_faces,
            limit,
            slack,
            |f| face_b_separation(a, b, &rel, f),
        );
        let (sep_b, face_b, second_b) = match faces_b {
            Ok(best) => best,
            Err(f) => {
                cache.feature = SatFeature::FaceB(f as u16);
                return Manifold::EMPTY;
            }
        };
        let use_b = sep_b > sep_a + FACE_REL_TOL * sep_a.abs() + FACE_ABS_TOL;
        if use_b {
            (true, face_a, face_b, sep_b, Some((second_b, sep_a)))
        } else {
            (false, face_a, face_b, sep_a, Some((second_a, sep_b)))
        }
    };
    // GJK from the best face's normal bounds every axis's separation from above: the
    // distance it returns is that of a point of the Minkowski difference (never less than
    // the true distance), and on overlap every axis separates by at most rounding. When
    // that bound is below both the speculative limit and the margin an edge axis needs to
    // replace the best face, no edge pair can end the test or decide the contact, and the
    // edge loop (the cost of the test, |edges A| × |edges B|) is skipped with the same
    // result: resting contacts with shallow overlap and separated pairs whose closest
    // features are faces.
    let face_start = if use_b {
        -(rel.r * b.plane(face_b).normal)
    } else {
        a.plane(face_a).normal
    };
    //
    // GJK stops as soon as its distance is below every threshold it is compared with
    // (`stop`: the edge margin, the speculative limit and, for separated cores, the margin
    // at which its own point would replace the face): every decision below then goes the
    // way the full iteration's would (its distance can only be smaller, and its overlap
    // bound is under `stop`), so the result is the same, in fewer iterations for resting
    // pairs (their cores overlap, and proving that takes a tetrahedron).
    let edge_margin = best_face + EDGE_REL_TOL * best_face.abs() + EDGE_ABS_TOL;
    let mut stop = edge_margin.min(limit);
    if best_face > 0.0 {
        stop = stop.min(best_face + GJK_REL_TOL * best_face + GJK_ABS_TOL);
    }
    if stop < GJK_OVERLAP_BOUND {
        stop = -1.0;
    }
    let g = gjk::distance_until(&Own(a), &InA { poly: b, rel }, face_start, stop);
    let upper = if g.overlap { GJK_OVERLAP_BOUND } else { g.distance };
    let edges_can_matter = upper > edge_margin || upper > limit;
    // Edge pairs that build a Minkowski face.
    //
    // When the cores overlap, an edge pair decides only as the face of the Minkowski
    // difference nearest the origin (the deepest axis; its separation −D must beat
    // `edge_margin`, so D < `reach`), and the origin then projects into that face: its
    // two edges cross, seen along its axis, at points D apart, so each edge comes within D
    // of the other hull. The decided face's plane (`pn`, `po`, out of its hull) bounds
    // where that can be: the reference hull's edges must reach down to `po + best_face −
    // reach` (the other hull lies above `po + best_face`), the other hull's up to `po +
    // reach`. The rest are left out: the same pair decides, in a fraction of the pairs.
    let prune = prune_edges
        && edges_can_matter
        && g.overlap
        && limit > EDGE_PRUNE_SLACK
        && a.hull.edge_lanes.len() <= MAX_EDGE_BLOCKS;
    let reach = -edge_margin + EDGE_PRUNE_SLACK * (1.0 + a.reach() + b.reach());
    let (pn, po) = if use_b {
        let pl = b.plane(face_b);
        let n = rel.r * pl.normal;
        (n, pl.offset + n.dot(rel.t))
    } else {
        let pl = a.plane(face_a);
        (pl.normal, pl.offset)
    };
    let keep = |p0: Vec3, p1: Vec3, reference: bool| {
        let (h0, h1) = (pn.dot(p0), pn.dot(p1));
        if reference {
            h0.max(h1) >= po + best_face - reach
        } else {
            h0.min(h1) <= po + reach
        }
    };
    //
    // When the cores are apart, a pair's axis `m` (a face normal of the Minkowski difference
    // B − A) separates them by at most `m · v`, `v` GJK's point of that difference (`|v| =
    // D`): a pair can end the test (more than `limit`) or decide (more than `edge_margin`,
    // and at least the pair of last test, if its arcs still cross: the best pair is at
    // least as good) only if `m · v̂` reaches `floor / D`. `m` lies on both edges' arcs on
    // the Gauss map (A's, and B's negated), so an edge whose arc stays outside that cone
    // about `v̂` builds no such pair and is left out: the same pair decides, or ends the
    // test, in a fraction of the pairs.
    let cone = if prune_edges && edges_can_matter && !g.overlap && a.hull.edge_lanes.len() <= MAX_EDGE_BLOCKS {
        apart_cone(a, b, &rel, previous, edge_margin, limit, &g)
    } else {
        None
    };
    // A's edges left in, four lanes per block as `edge_lanes` (bit k: lane k).
    let mut a_lanes = [0x0fu8; MAX_EDGE_BLOCKS];
    if prune {
        for (ka, ga) in a.hull.edge_gauss.iter().enumerate() {
            if !keep(a.vertex(ga.v0 as usize), a.vertex(ga.v1 as usize), !use_b) {
                a_lanes[ka / 4] &= !(1u8 << (ka % 4));
            }
        }
    } else if let Some(cone) = cone {
        for (ka, ga) in a.hull.edge_gauss.iter().enumerate() {
            if !cone.meets_arc(ga.n1, ga.n2) {
                a_lanes[ka / 4] &= !(1u8 << (ka % 4));
            }
        }
    }
    let (mut sep_e, mut edges, mut edge_dir) = (f32::MIN, (usize::MAX, usize::MAX), Vec3::ZERO);
    let b_edges = if edges_can_matter { &b.hull.edge_gauss[..] } else { &[] };
    for (kb, gb) in b_edges.iter().enumerate() {
        // B's arc, negated (Minkowski difference A − B), in A's frame.
        let c = -(rel.r * gb.n1);
        let d = -(rel.r * gb.n2);
        if cone.is_some_and(|cone| !cone.meets_arc(c, d)) {
            continue;
        }
        let pb0 = rel.r * b.vertex(gb.v0 as usize) + rel.t;
        let pb1 = rel.r * b.vertex(gb.v1 as usize) + rel.t;
        if prune && !keep(pb0, pb1, use_b) {
            continue;
        }
        let d_x_c = rel.r * gb.n2_x_n1;
        // Four of A's edges at a time (`EdgeLanes`, in `F4` lanes): the arc test's dot
        // products lane by lane, in the scalar form's order of operations, so the same pairs
        // pass.
        let v = |p: Vec3| (F4::splat(p.x), F4::splat(p.y), F4::splat(p.z));
        let (c4, d4, dxc4) = (v(c), v(d), v(d_x_c));
        let dot = |(x, y, z): (F4, F4, F4), n: &[[f32; 4]; 3]| {
            x * F4::load(&n[0]) + y * F4::load(&n[1]) + z * F4::load(&n[2])
        };
        let zero = F4::zero();
        for (block, l) in a.hull.edge_lanes.iter().enumerate() {
            let lanes = a_lanes.get(block).copied().unwrap_or(0x0f);
            if lanes == 0 {
                continue;
            }
            let (cba, dba) = (dot(c4, &l.n2_x_n1), dot(d4, &l.n2_x_n1));
            let (adc, bdc) = (dot(dxc4, &l.n1), dot(dxc4, &l.n2));
            // cba·dba < 0, adc·bdc < 0 and cba·bdc > 0, lane by lane (bit k: lane k).
            let pass = zero
                .gt(cba * dba)
                .and(zero.gt(adc * bdc))
                .and((cba * bdc).gt(zero))
                .bits()
                & lanes as u32;
            if pass == 0 {
                continue;
            }
            for k in (0..4).filter(|k| pass >> k & 1 != 0) {
                let ka = 4 * block + k;
                let ga = a.hull.edge_gauss[ka];
                let (pa0, pa1) = (a.vertex(ga.v0 as usize), a.vertex(ga.v1 as usize));
                let Some((axis, s)) = edge_axis(pa0, pa1, ga.n1 + ga.n2, pb0, pb1) else {
                    continue;
                };
                if s <= sep_e {
                    continue;
                }
                // The edge-to-edge gap is the gap along the axis only when the pair really
                // builds a face of the Minkowski difference; welded hulls with very short edges
                // can pass the arc test with normals that do not quite fit, so a gap that would
                // decide is measured again by the support functions (rarely: only new maxima).
                let s = s.min(support_separation(a, b, &rel, axis));
                if s > limit {
                    cache.feature = SatFeature::Edges(ka as u16, kb as u16);
                    return Manifold::EMPTY;
                }
                if s > sep_e {
                    sep_e = s;
                    edges = (ka, kb);
                    edge_dir = axis;
                }
            }
        }
    }

    let mut best = best_face;
    let use_edge = edges.0 != usize::MAX && sep_e > edge_margin;
    cache.feature = if use_edge {
        best = sep_e;
        SatFeature::Edges(edges.0 as u16, edges.1 as u16)
    } else if use_b {
        SatFeature::FaceB(face_b as u16)
    } else {
        SatFeature::FaceA(face_a as u16)
    };

    if best > 0.0 {
        // GJK again only when an edge decided (started from its axis, as the faces' was).
        let g = if use_edge {
            gjk::distance_from(&Own(a), &InA { poly: b, rel }, edge_dir)
        } else {
            g
        };
        if !g.overlap && g.distance > best + GJK_REL_TOL * best + GJK_ABS_TOL {
            return one_point(
                a.world_point(g.point_a),
                a.world_point(g.point_b),
                a.rot * g.normal,
                g.distance,
                a.radius,
                b.radius,
                feature_id([KIND_GJK, 0, 0, 0]),
                speculative,
            );
        }
    }

    if use_edge {
        let (ga, gb) = (a.hull.edge_gauss[edges.0], b.hull.edge_gauss[edges.1]);
        let (pa0, pa1) = (a.vertex(ga.v0 as usize), a.vertex(ga.v1 as usize));
        let pb0 = rel.r * b.vertex(gb.v0 as usize) + rel.t;
        let pb1 = rel.r * b.vertex(gb.v1 as usize) + rel.t;
        let (s, t) = super::geom::closest_segment_segment(pa0, pa1, pb0, pb1);
        let ca = pa0 + (pa1 - pa0) * s;
        let cb = pb0 + (pb1 - pb0) * t;
        return one_point(
            a.world_point(ca),
            a.world_point(cb),
            a.rot * edge_dir,
            sep_e,
            a.radius,
            b.radius,
            feature_id([KIND_EDGE, edges.0 as u32, edges.1 as u32, 0]),
            speculative,
        );
    }
    // A face decided (over the edge pairs and GJK's point): hold it, with the margins of
    // this search, or keep the hold it came from.
    cache.hold = match margins {
        Some((same, other)) => FaceHold {
            valid: true,
            r: Mat3::from(rel.r),
            t: rel.t,
            same,
            other,
        },
        None => hold,
    };
    if use_b {
        face_contact(b, a, &Relative::new(b, a), face_b, speculative, true)
    } else {
        face_contact(a, b, &rel, face_a, speculative, false)
    }
}

/// Angular slack of the cone test (on the cosine): an axis computed from the edges may lie
/// off the arcs of the face normals by rounding and by the faces' fit.
const CONE_SLACK: f32 = 0.02;

/// The directions `m` with `m · axis >= cos`: where the axis of an edge pair that can still
/// matter lies (see `hull_hull_with`).
#[derive(Clone, Copy)]
struct Cone {
    axis: Vec3,
    cos: f32,
}

impl Cone {
    /// Whether some direction on the great-circle arc from `n1` to `n2` (unit vectors less
    /// than a half turn apart) lies in the cone: an end does, or the arc's nearest point to
    /// the axis lies between the ends (`x − k·y` and `y − k·x` not negative) and close
    /// enough (`|axis projected on the arc's plane|² = (x² − 2kxy + y²)/(1 − k²)`). Arcs
    /// too short for the division are judged in (nothing is left out that could matter).
    #[inline(always)]
    fn meets_arc(&self, n1: Vec3, n2: Vec3) -> bool {
        let (x, y, k) = (self.axis.dot(n1), self.axis.dot(n2), n1.dot(n2));
        x >= self.cos
            || y >= self.cos
            || (x >= k * y && y >= k * x && x * x - 2.0 * k * x * y + y * y >= self.cos * self.cos * (1.0 - k * k))
    }
}

/// The cone of axes that can still matter when the cores are apart (GJK's `g`, not
/// overlapping): a pair matters when it ends the test (more than `limit`) or when it can
/// decide: more than `edge_margin` and at least the separation of the previous deciding
/// pair, if that pair still passes the arc test (the loop's best is at least that). No axis
/// `m` separates the cores by more than `m · v` (`v`, GJK's point of the Minkowski
/// difference, `|v| = D`), up to rounding (`slack`). `None` when the cone is too wide to
/// leave anything out.
fn apart_cone(
    a: &Poly,
    b: &Poly,
    rel: &Relative,
    previous: SatFeature,
    edge_margin: f32,
    limit: f32,
    g: &gjk::DistanceOutput,
) -> Option<Cone> {
    if !g.distance.is_finite() || g.distance <= GJK_OVERLAP_BOUND {
        return None;
    }
    let mut decides = edge_margin;
    if let SatFeature::Edges(ea, eb) = previous {
        if let Some(s) = pair_separation(a, b, rel, ea as usize, eb as usize) {
            decides = decides.max(s);
        }
    }
    let floor = decides.min(limit);
    let slack = EDGE_PRUNE_SLACK * (1.0 + a.reach() + b.reach());
    let cos = ((floor - slack) / g.distance).min(1.0) - CONE_SLACK;
    (cos > 0.0).then_some(Cone { axis: g.normal, cos })
}

/// The separation the edge loop of `hull_hull_with` gives edge pair (`ea`, `eb`) — the arc
/// test as its lanes compute it, the axis, and the edge gap capped by the support functions
/// — or `None` when the loop would not take the pair.
fn pair_separation(a: &Poly, b: &Poly, rel: &Relative, ea: usize, eb: usize) -> Option<f32> {
    if ea >= a.hull.edge_gauss.len() || eb >= b.hull.edge_gauss.len() {
        return None;
    }
    let gb = b.hull.edge_gauss[eb];
    let c = -(rel.r * gb.n1);
    let d = -(rel.r * gb.n2);
    let d_x_c = rel.r * gb.n2_x_n1;
    let (l, k) = (&a.hull.edge_lanes[ea / 4], ea % 4);
    // The lanes' products and sums in their order: `(x·n_x + y·n_y) + z·n_z`.
    let dot = |p: Vec3, n: &[[f32; 4]; 3]| p.x * n[0][k] + p.y * n[1][k] + p.z * n[2][k];
    let (cba, dba) = (dot(c, &l.n2_x_n1), dot(d, &l.n2_x_n1));
    let (adc, bdc) = (dot(d_x_c, &l.n1), dot(d_x_c, &l.n2));
    if !(0.0 > cba * dba && 0.0 > adc * bdc && cba * bdc > 0.0) {
        return None;
    }
    let ga = a.hull.edge_gauss[ea];
    let pb0 = rel.r * b.vertex(gb.v0 as usize) + rel.t;
    let pb1 = rel.r * b.vertex(gb.v1 as usize) + rel.t;
    let (axis, s) = edge_axis(
        a.vertex(ga.v0 as usize),
        a.vertex(ga.v1 as usize),
        ga.n1 + ga.n2,
        pb0,
        pb1,
    )?;
    Some(s.min(support_separation(a, b, rel, axis)))
}

/// Clips the incident face of `inc` against face `face` of `refp`, in `refp`'s frame
/// (`rel` places `inc` there). `flipped` when the reference is the pair's B: the normal is
/// then reversed so it still points from A to B.
///
/// The two faces' corners (the incident ones placed in `refp`'s frame) and their side
/// normals are worked out once into small arrays when both faces have at most
/// `FACE_CACHE` corners, instead of once per use in the clipping loops; larger faces
/// compute them where used. Either way each value comes from the same expression, so the
/// manifold is the same bit for bit (`face_cache_matches_the_plain_clip`).
fn face_contact(refp: &Poly, inc: &Poly, rel: &Relative, face: usize, speculative: f32, flipped: bool) -> Manifold {
    face_contact_cached(refp, inc, rel, face, speculative, flipped, true)
}

/// Most corners of a face whose corners and side normals `face_contact` keeps at hand.
const FACE_CACHE: usize = 8;

/// The faces of `face_contact`: the reference face `face` of `refp` (plane `pl`, corner
/// `k` at `ref_he[k]`) and the incident face of `inc` (plane normal `n_inc` and offset
/// `d_inc` in `refp`'s frame, corners at `inc_he`).
struct FacePair<'h> {
    pl: crate::collision::hull::Plane,
    inc_face: usize,
    n_inc: Vec3,
    d_inc: f32,
    ref_he: &'h [crate::collision::hull::HalfEdge],
    inc_he: &'h [crate::collision::hull::HalfEdge],
}

/// The faces `face_contact` clips: the reference face and the incident face of `inc`
/// (most anti-parallel to the reference normal).
#[inline(always)]
fn face_pair<'h>(refp: &Poly<'h>, inc: &Poly<'h>, rel: &Relative, face: usize) -> FacePair<'h> {
    let pl = refp.plane(face);
    let n = pl.normal;
    // Incident face: most anti-parallel to n.
    let n_inc_local = rel.rt * n;
    let (mut inc_face, mut best) = (0usize, f32::MAX);
    for (f, p) in inc.hull.planes.iter().enumerate() {
        let x = p.normal.dot(n_inc_local);
        if x < best {
            best = x;
            inc_face = f;
        }
    }
    let inc_pl = inc.plane(inc_face);
    let n_inc = rel.r * inc_pl.normal;
    let d_inc = inc_pl.offset + n_inc.dot(rel.t);
    let ref_face = refp.hull.faces[face];
    let ref_he = &refp.hull.half_edges[ref_face.first as usize..(ref_face.first + ref_face.count) as usize];
    let inc_f = inc.hull.faces[inc_face];
    let inc_he = &inc.hull.half_edges[inc_f.first as usize..(inc_f.first + inc_f.count) as usize];
    FacePair {
        pl,
        inc_face,
        n_inc,
        d_inc,
        ref_he,
        inc_he,
    }
}

/// `face_contact`, with the corners and side normals kept in arrays (`cache`, for faces of
/// at most `FACE_CACHE` corners) or computed where used (tests compare).
fn face_contact_cached(
    refp: &Poly,
    inc: &Poly,
    rel: &Relative,
    face: usize,
    speculative: f32,
    flipped: bool,
    cache: bool,
) -> Manifold {
    let fp = face_pair(refp, inc, rel, face);
    let n = fp.pl.normal;
    let (ref_he, inc_he, n_inc) = (fp.ref_he, fp.inc_he, fp.n_inc);
    let ref_vertex = |k: usize| refp.vertex(ref_he[k % ref_he.len()].origin as usize);
    let inc_vertex = |k: usize| rel.r * inc.vertex(inc_he[k % inc_he.len()].origin as usize) + rel.t;
    let (nr, ni) = (ref_he.len(), inc_he.len());
    if cache && nr <= FACE_CACHE && ni <= FACE_CACHE {
        let ref_c: [Vec3; FACE_CACHE] = std::array::from_fn(|j| if j < nr { ref_vertex(j) } else { Vec3::ZERO });
        let ref_m: [Vec3; FACE_CACHE] = std::array::from_fn(|j| {
            if j < nr {
                (ref_c[(j + 1) % nr] - ref_c[j]).cross(n)
            } else {
                Vec3::ZERO
            }
        });
        let inc_c: [Vec3; FACE_CACHE] = std::array::from_fn(|k| if k < ni { inc_vertex(k) } else { Vec3::ZERO });
        clip_faces(
            refp,
            inc,
            rel,
            face,
            speculative,
            flipped,
            &fp,
            |j| (ref_c[j], ref_m[j]),
            |k| inc_c[k],
            |k| (inc_c[(k + 1) % ni] - inc_c[k]).cross(n_inc),
        )
    } else {
        clip_faces(
            refp,
            inc,
            rel,
            face,
            speculative,
            flipped,
            &fp,
            |j| {
                let a0 = ref_vertex(j);
                (a0, (ref_vertex(j + 1) - a0).cross(n))
            },
            inc_vertex,
            |k| (inc_vertex(k + 1) - inc_vertex(k)).cross(n_inc),
        )
    }
}

/// The clipping of `face_contact` on the faces of `fp`: `ref_side(j)` is the reference
/// face's corner `j` and its side normal `(corner j+1 − corner j) × n`, `inc_corner(k)` the
/// incident face's corner `k` (`k` below the corner count) in `refp`'s frame, `inc_side(k)`
/// its side normal `(corner k+1 − corner k) × n_inc`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn clip_faces(
    refp: &Poly,
    inc: &Poly,
    rel: &Relative,
    face: usize,
    speculative: f32,
    flipped: bool,
    fp: &FacePair,
    ref_side: impl Fn(usize) -> (Vec3, Vec3),
    inc_corner: impl Fn(usize) -> Vec3,
    inc_side: impl Fn(usize) -> Vec3,
) -> Manifold {
    let pl = fp.pl;
    let n = pl.normal;
    let r_total = refp.radius + inc.radius;
    let (ref_he, inc_he, inc_face) = (fp.ref_he, fp.inc_he, fp.inc_face);
    let (side, kind) = if flipped { (1u32, KIND_FACE_B) } else { (0, KIND_FACE_A) };
    let base = [face as u32 | side << 16, inc_face as u32];
    let mut cands = Candidates::new(n);
    let add = |cands: &mut Candidates, x: Vec3, key: u32| {
        let s = n.dot(x) - pl.offset;
        let sep = s - r_total;
        if sep > speculative {
            return;
        }
        let on_ref = x - n * s + n * refp.radius;
        let on_inc = x - n * inc.radius;
        cands.push(Candidate {
            p: 0.5 * (on_ref + on_inc),
            sep,
            id: feature_id([kind, base[0], base[1], key]),
        });
    };
    // Each incident edge clipped to the reference side planes (Cyrus–Beck).
    let (nr, ni) = (ref_he.len(), inc_he.len());
    for (k, he) in inc_he.iter().enumerate() {
        let (p, q) = (inc_corner(k), inc_corner((k + 1) % ni));
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        let (mut enter, mut exit) = (u32::MAX, u32::MAX);
        let mut out = false;
        for j in 0..nr {
            let (a0, m) = ref_side(j);
            let (dp, dq) = (m.dot(p - a0), m.dot(q - a0));
            if dp > 0.0 && dq > 0.0 {
                out = true;
                break;
            }
            if dp > 0.0 {
                let t = dp / (dp - dq);
                if t > t0 {
                    t0 = t;
                    enter = j as u32;
                }
            } else if dq > 0.0 {
                let t = dp / (dp - dq);
                if t < t1 {
                    t1 = t;
                    exit = j as u32;
                }
            }
        }
        if out || t0 > t1 {
            continue;
        }
        if enter == u32::MAX {
            add(&mut cands, p, he.origin as u32);
        } else {
            add(&mut cands, p + (q - p) * t0, 0x1_0000 | (k as u32) << 8 | enter);
        }
        if exit != u32::MAX {
            add(&mut cands, p + (q - p) * t1, 0x2_0000 | (k as u32) << 8 | exit);
        }
    }
    // The incident hull's deepest vertex when it is not on the incident face (the face most
    // anti-parallel to n need not hold it) and lies over the reference face.
    let deepest = inc.support_index(-(rel.rt * n));
    if !inc_he.iter().any(|he| he.origin as usize == deepest) {
        let x = rel.r * inc.vertex(deepest) + rel.t;
        let over = (0..nr).all(|j| {
            let (a0, m) = ref_side(j);
            m.dot(x - a0) <= 0.0
        });
        if over {
            add(&mut cands, x, 0x8_0000 | deepest as u32);
        }
    }
    // Reference corners over the incident face, projected onto it along n.
    let (n_inc, d_inc) = (fp.n_inc, fp.d_inc);
    let denom = n_inc.dot(n);
    if denom < -0.1 {
        for j in 0..nr {
            // Projected first, then tested on the incident plane: a tilted incident face
            // would otherwise accept corners whose projection along n falls off it.
            let c = ref_side(j).0;
            let x = c + n * ((d_inc - n_inc.dot(c)) / denom);
            let inside = (0..ni).all(|k| inc_side(k).dot(x - inc_corner(k)) <= 0.0);
            if inside {
                add(&mut cands, x, 0x4_0000 | j as u32);
            }
        }
    }
    // Deep overlaps of tilted faces can leave nothing over both faces; the deepest vertex
    // then pushes alone (at the gap of the axis, so the solver still separates the pair).
    if cands.n == 0 {
        add(
            &mut cands,
            rel.r * inc.vertex(deepest) + rel.t,
            0x8_0000 | deepest as u32,
        );
    }
    let normal = refp.rot * if flipped { -n } else { n };
    cands.finish(normal, |x| refp.world_point(x))
}

/// A point of the placed core in its own frame, when one is at hand: the centre of mass of
/// an unrounded hull (rounding can move it off the core).
#[inline]
fn inner_point(p: &Poly) -> Option<Vec3> {
    (p.hull.radius == 0.0).then(|| p.hull.unit_mass.center * p.scale)
}

/// The best face of `own` against `other` (`best_face`), skipping faces by their bound from
/// `other`'s inner point (`best_face_bounded`) when `prune` and `other` has one; `to_own`
/// takes a point of `other`'s frame into `own`'s.
fn best_face_of(
    own: &Poly,
    other: &Poly,
    to_own: impl Fn(Vec3) -> Vec3,
    prune: bool,
    limit: f32,
    slack: f32,
    separation: impl Fn(usize) -> f32,
) -> Result<(f32, usize, f32), usize> {
    let count = own.hull.planes.len();
    match inner_point(other) {
        Some(c) if prune => {
            let c = to_own(c);
            let bound = |f: usize| {
                let pl = own.plane(f);
                pl.normal.dot(c) - pl.offset
            };
            best_face_bounded(count, limit, slack, bound, separation)
        }
        _ => best_face(count, limit, separation),
    }
}

/// Most faces whose bounds `best_face_bounded` keeps between its two passes.
const BOUND_CACHE: usize = 64;

/// `best_face` (the same answer) that skips the faces whose `bound` (at least their
/// separation, up to `slack`) is below the separations of the two faces of largest bound:
/// such a face is neither the best nor the runner-up (the two largest separations, the best
/// at its first face) and, being under `limit`, does not end the search; the others are
/// taken in order as `best_face` takes them.
#[inline(always)]
fn best_face_bounded(
    count: usize,
    limit: f32,
    slack: f32,
    bound: impl Fn(usize) -> f32,
    separation: impl Fn(usize) -> f32,
) -> Result<(f32, usize, f32), usize> {
    // The bounds are kept for the search below (hulls of up to `BOUND_CACHE` faces; the
    // rest compute them again): the same values.
    let mut kept = [0.0f32; BOUND_CACHE];
    let cached = count <= BOUND_CACHE;
    let (mut b1, mut f1, mut b2, mut f2) = (f32::MIN, usize::MAX, f32::MIN, usize::MAX);
    for f in 0..count {
        let u = bound(f);
        if let Some(k) = kept.get_mut(f) {
            *k = u;
        }
        if u > b1 {
            (b2, f2) = (b1, f1);
            (b1, f1) = (u, f);
        } else if u > b2 {
            (b2, f2) = (u, f);
        }
    }
    if f2 == usize::MAX {
        return best_face(count, limit, separation);
    }
    let (s1, s2) = (separation(f1), separation(f2));
    // Not below `limit` (or NaN): the search in order finds the face that ends it.
    if !(s1 <= limit && s2 <= limit) {
        return best_face(count, limit, separation);
    }
    let floor = s1.min(s2) - slack;
    best_face(count, limit, |f| {
        if f == f1 {
            s1
        } else if f == f2 {
            s2
        } else if (if cached { kept[f] } else { bound(f) }) < floor {
            // Below the two: changes nothing in the search.
            f32::MIN
        } else {
            separation(f)
        }
    })
}

/// The face of a hull with the largest `separation`, that separation and the runner-up's;
/// `Err(face)` at the first face that separates by more than `limit`.
#[inline(always)]
fn best_face(count: usize, limit: f32, separation: impl Fn(usize) -> f32) -> Result<(f32, usize, f32), usize> {
    let (mut best, mut face, mut second) = (f32::MIN, 0usize, f32::MIN);
    for f in 0..count {
        let s = separation(f);
        if s > limit {
            return Err(f);
        }
        if s > best {
            second = best;
            best = s;
            face = f;
        } else if s > second {
            second = s;
        }
    }
    Ok((best, face, second))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::hull::builder::{build, HullSettings};
    use crate::math::test_rnd::Rnd;
    use crate::math::{Quat, Transform};

    /// GJK between two polytopes, B seen from A.
    fn gjk_of(a: &Poly, b: &Poly) -> gjk::DistanceOutput {
        gjk::distance(
            &Own(a),
            &InA {
                poly: b,
                rel: Relative::new(a, b),
            },
        )
    }

    /// Two random hulls of 8 to 20 points; every third trial A's cloud gets near-duplicates
    /// of a third of its points (short edges whose faces' normals fit them loosely).
    fn hull_pair(rnd: &mut Rnd, trial: usize) -> (crate::ConvexHull, crate::ConvexHull) {
        let mut cloud = rnd.cloud(8, 20.0, 0.2, 0.3);
        if trial % 3 == 0 {
            for i in 0..cloud.len() / 3 {
                let p = cloud[i] + rnd.point(Vec3::splat(2.0e-3));
                cloud.push(p);
            }
        }
        let ha = build(&cloud, &HullSettings::default()).unwrap();
        let hb = build(&rnd.cloud(8, 20.0, 0.2, 0.3), &HullSettings::default()).unwrap();
        (ha, hb)
    }

    /// A of the random pair tests: a box every fifth trial, else hull `ha`, at `xa`.
    fn shape_a<'h>(ha: &'h crate::ConvexHull, half: Vec3, xa: &Transform, trial: usize) -> Poly<'h> {
        if trial % 5 == 0 {
            Poly::boxed(Vec3::ZERO, Quat::IDENTITY, half, xa)
        } else {
            Poly::hull(ha, &Transform::IDENTITY, 1.0, xa)
        }
    }

    /// Moves `xb` (hull `hb`) along `-dir` until its GJK gap to `a` is `gap` (within
    /// 0.1 mm) or the two overlap.
    fn approach(a: &Poly, hb: &crate::ConvexHull, dir: Vec3, xb: &mut Transform, gap: f32) {
        for _ in 0..40 {
            let g = gjk_of(a, &Poly::hull(hb, &Transform::IDENTITY, 1.0, xb));
            if g.overlap || (g.distance - gap).abs() < 1.0e-4 {
                break;
            }
            xb.p -= dir * (g.distance - gap);
        }
    }

    /// `edge_lanes` holds `edge_gauss`'s arcs lane for lane, and its padding lanes (zero
    /// normals) fail the arc test against any arc, so the four-at-a-time loop visits the
    /// same pairs as one edge at a time.
    #[test]
    fn edge_lanes_hold_the_arcs() {
        let mut rnd = Rnd(0x9e37_79b9);
        for n in 4..40 {
            let pts: Vec<Vec3> = (0..n).map(|_| rnd.point(Vec3::ONE)).collect();
            let h = build(&pts, &HullSettings::default()).unwrap();
            assert_eq!(h.edge_lanes.len(), h.edge_gauss.len().div_ceil(4));
            for (ka, g) in h.edge_gauss.iter().enumerate() {
                let l = &h.edge_lanes[ka / 4];
                for axis in 0..3 {
                    assert_eq!(l.n1[axis][ka % 4].to_bits(), g.n1[axis].to_bits());
                    assert_eq!(l.n2[axis][ka % 4].to_bits(), g.n2[axis].to_bits());
                    assert_eq!(l.n2_x_n1[axis][ka % 4].to_bits(), g.n2_x_n1[axis].to_bits());
                }
            }
            for k in h.edge_gauss.len()..4 * h.edge_lanes.len() {
                let l = &h.edge_lanes[k / 4];
                let c = rnd.point(Vec3::ONE);
                let cba = c.x * l.n2_x_n1[0][k % 4] + c.y * l.n2_x_n1[1][k % 4] + c.z * l.n2_x_n1[2][k % 4];
                assert_eq!(cba * cba, 0.0, "padding lane {k} crosses an arc");
            }
        }
    }

    /// The face hold changes nothing: pairs of random hulls (and a box against a hull,
    /// non-uniformly scaled) moved in small random steps from resting contact, tested with
    /// the pair's cache kept from step to step and with a fresh cache each time, give the
    /// same manifolds bit for bit (normal, points, separations, ids), while the hold skips
    /// the face loops in many of the steps.
    #[test]
    fn face_hold_matches_the_full_search() {
        let mut rnd = Rnd(0x0dd1_b1a5_e5e5_7a11);
        let cloud = |rnd: &mut Rnd| rnd.cloud(12, 13.0, 0.25, 0.25);
        let (mut steps, mut held, mut touching) = (0, 0, 0);
        for trial in 0..200 {
            let ha = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let hb = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let (qb, half) = (rnd.quat(), Vec3::new(0.2 + rnd.f(), 0.1 + rnd.f(), 0.3 + rnd.f()) * 0.5);
            // B placed above A along a random direction, then lowered to about touching.
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let mut xb = Transform::new(dir * 2.0, qb);
            let place = |xb: &Transform| {
                let a = if trial % 4 == 0 {
                    Poly::boxed(Vec3::ZERO, Quat::IDENTITY, half, &xa)
                } else {
                    Poly::hull(&ha, &Transform::IDENTITY, 1.0, &xa)
                };
                (a, Poly::hull(&hb, &Transform::IDENTITY, 1.0, xb))
            };
            for _ in 0..40 {
                let (a, b) = place(&xb);
                let g = gjk_of(&a, &b);
                if g.overlap || g.distance < 0.002 {
                    break;
                }
                xb.p -= dir * (g.distance - 0.001 * rnd.f());
            }
            let mut cache = SatCache::default();
            for _ in 0..60 {
                // Millimetres and fractions of a degree per step, now and then more.
                let big = if rnd.f() < 0.1 { 10.0 } else { 1.0 };
                let dp = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5) * 0.004 * big;
                let axis = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
                xb.p += dp - dir * 0.0005 * (rnd.f() - 0.4);
                xb.q = (Quat::from_axis_angle(axis, 0.01 * big * (rnd.f() - 0.5)) * xb.q).normalize();
                let (a, b) = place(&xb);
                let rel = Relative::new(&a, &b);
                if cache.hold.valid {
                    let limit = 0.02 + a.radius + b.radius;
                    if let Some(sep) = cached_separation(&a, &b, &rel, cache.feature) {
                        let delta = pose_change(&a, &b, &rel, &cache.hold);
                        let on_b = matches!(cache.feature, SatFeature::FaceB(_));
                        held += (sep <= limit && holds(&cache.hold, on_b, sep, delta, limit)) as usize;
                    }
                }
                let kept = hull_hull(&a, &b, 0.02, &mut cache);
                let fresh = hull_hull(&a, &b, 0.02, &mut SatCache::default());
                assert_eq!(format!("{kept:?}"), format!("{fresh:?}"), "trial {trial}");
                steps += 1;
                touching += (kept.count > 0) as usize;
            }
        }
        assert!(
            touching > steps / 2 && held > steps / 4,
            "{steps} steps, {touching} touching, {held} held"
        );
    }

    /// The edge pairs' pruning under overlap changes nothing: random hull pairs (and
    /// boxes against hulls) overlapping by up to 6 cm, at random poses, give the same
    /// manifold bit for bit with and without it, edge contacts among them.
    #[test]
    fn edge_pruning_keeps_the_deciding_pair() {
        let mut rnd = Rnd(0x7a3d_91c4_05e2_b86f);
        let cloud = |rnd: &mut Rnd| rnd.cloud(8, 30.0, 0.2, 0.3);
        let (mut overlapping, mut edge_contacts) = (0, 0);
        for trial in 0..3000 {
            let ha = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let hb = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let half = Vec3::new(0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f());
            let a = shape_a(&ha, half, &xa, trial);
            // B moved in from far along a random direction until it touches, then pushed
            // in by up to 6 cm.
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let mut xb = Transform::new(dir * 3.0, rnd.quat());
            approach(&a, &hb, dir, &mut xb, 0.0);
            xb.p -= dir * 0.06 * rnd.f();
            let b = Poly::hull(&hb, &Transform::IDENTITY, 1.0, &xb);
            let pruned = hull_hull_with(&a, &b, 0.02, &mut SatCache::default(), true, true);
            let full = hull_hull_with(&a, &b, 0.02, &mut SatCache::default(), false, true);
            assert_eq!(format!("{pruned:?}"), format!("{full:?}"), "trial {trial}");
            let g = gjk_of(&a, &b);
            overlapping += g.overlap as usize;
            edge_contacts += (g.overlap && full.count == 1) as usize;
        }
        assert!(
            overlapping > 2000 && edge_contacts > 300,
            "{overlapping} overlapping, {edge_contacts} edge contacts"
        );
    }

    /// The cone of axes that can still matter when the cores are apart changes nothing:
    /// random hull pairs (and boxes against hulls; some clouds with near-duplicate points,
    /// so short edges and welded faces), from touching to 4 cm apart, moved in small random
    /// steps with the pair's cache kept, give the same manifold and the same cache bit for
    /// bit with the cone and without it (the loop over every pair); in many of the tests
    /// the cores are apart and an edge pair decides (where the cone leaves edges out).
    #[test]
    fn apart_cone_keeps_the_deciding_pair() {
        let mut rnd = Rnd(0x51c3_a0d2_77e9_4b15);
        let (mut tests, mut apart_edges, mut edge_contacts) = (0, 0, 0);
        for trial in 0..400 {
            let (ha, hb) = hull_pair(&mut rnd, trial);
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let half = Vec3::new(0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f());
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let mut xb = Transform::new(dir * 3.0, rnd.quat());
            let place = |xb: &Transform| {
                (
                    shape_a(&ha, half, &xa, trial),
                    Poly::hull(&hb, &Transform::IDENTITY, 1.0, xb),
                )
            };
            // B moved in from far along a random direction to a gap of 0 to 4 cm.
            let gap = 0.04 * rnd.f();
            approach(&shape_a(&ha, half, &xa, trial), &hb, dir, &mut xb, gap);
            let mut cache = SatCache::default();
            for _ in 0..30 {
                let dp = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5) * 0.004;
                let axis = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
                xb.p += dp;
                xb.q = (Quat::from_axis_angle(axis, 0.02 * (rnd.f() - 0.5)) * xb.q).normalize();
                let (a, b) = place(&xb);
                let apart = !gjk_of(&a, &b).overlap;
                let mut full_cache = cache;
                let kept = hull_hull_with(&a, &b, 0.02, &mut cache, true, true);
                let full = hull_hull_with(&a, &b, 0.02, &mut full_cache, false, true);
                assert_eq!(format!("{kept:?}"), format!("{full:?}"), "trial {trial}");
                assert_eq!(cache, full_cache, "trial {trial}");
                tests += 1;
                let by_edges = matches!(cache.feature, SatFeature::Edges(..));
                apart_edges += (apart && by_edges) as usize;
                edge_contacts += (by_edges && kept.count > 0) as usize;
            }
        }
        assert!(
            apart_edges > tests / 5 && edge_contacts > tests / 10,
            "{tests} tests, {apart_edges} apart and decided by edges, {edge_contacts} edge contacts"
        );
    }

    /// The face bounds change nothing: random hull pairs (and boxes against hulls, one of
    /// them rounded now and then, where no bound is used), at random poses from 8 cm
    /// overlap to 30 cm apart, give the same manifold and the same cache bit for bit with
    /// the faces skipped by their bounds and with every face measured; the bounds skip
    /// faces in most tests, and some tests end on a separating face.
    #[test]
    fn face_bounds_keep_the_search() {
        let mut rnd = Rnd(0x3b9d_0c4f_e261_a857);
        let (mut tests, mut skipped, mut separated) = (0, 0, 0);
        for trial in 0..3000 {
            let settings = HullSettings {
                convex_radius: if trial % 7 == 0 { 0.02 } else { 0.0 },
                ..Default::default()
            };
            let ha = build(&rnd.cloud(6, 20.0, 0.15, 0.3), &settings).unwrap();
            let hb = build(&rnd.cloud(6, 20.0, 0.15, 0.3), &HullSettings::default()).unwrap();
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let half = Vec3::new(0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f());
            let a = shape_a(&ha, half, &xa, trial);
            // B moved in from far along a random direction until it touches, then moved
            // by -8 cm to +30 cm.
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let mut xb = Transform::new(dir * 3.0, rnd.quat());
            approach(&a, &hb, dir, &mut xb, 0.0);
            xb.p += dir * (0.38 * rnd.f() - 0.08);
            let b = Poly::hull(&hb, &Transform::IDENTITY, 1.0, &xb);
            let rel = Relative::new(&a, &b);
            let (mut kept_cache, mut full_cache) = (SatCache::default(), SatCache::default());
            let kept = hull_hull_with(&a, &b, 0.02, &mut kept_cache, true, true);
            let full = hull_hull_with(&a, &b, 0.02, &mut full_cache, true, false);
            assert_eq!(format!("{kept:?}"), format!("{full:?}"), "trial {trial}");
            assert_eq!(kept_cache, full_cache, "trial {trial}");
            tests += 1;
            separated += matches!(full_cache.feature, SatFeature::FaceA(_) | SatFeature::FaceB(_)) as usize
                * (full.count == 0) as usize;
            // Faces whose bound is under the separation of the face of largest bound.
            if let Some(c) = inner_point(&b) {
                let c = rel.r * c + rel.t;
                let bound = |f: usize| a.plane(f).normal.dot(c) - a.plane(f).offset;
                let top = (0..a.hull.planes.len())
                    .max_by(|&x, &y| bound(x).total_cmp(&bound(y)))
                    .unwrap();
                let s = face_a_separation(&a, &b, &rel, top);
                skipped += (0..a.hull.planes.len()).any(|f| bound(f) < s - 1.0e-3) as usize;
            }
        }
        assert!(
            skipped > tests / 2 && separated > tests / 20,
            "{tests} tests, {skipped} with faces skipped, {separated} separated by a face"
        );
    }

    /// The face clipping with the faces' corners and side normals kept in arrays gives the
    /// same manifold bit for bit as with them computed where used: random hull pairs (and
    /// boxes against hulls; some clouds with near-duplicate points, so small faces and
    /// short edges) from 6 cm overlap to 2 cm apart, every face of A as the reference and
    /// every face of B (flipped).
    #[test]
    fn face_cache_matches_the_plain_clip() {
        let mut rnd = Rnd(0x6a09_e667_f3bc_c908);
        let (mut compared, mut touching, mut cached) = (0, 0, 0);
        for trial in 0..300 {
            let (ha, hb) = hull_pair(&mut rnd, trial);
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let half = Vec3::new(0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f(), 0.1 + 0.4 * rnd.f());
            let a = shape_a(&ha, half, &xa, trial);
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let mut xb = Transform::new(dir * 3.0, rnd.quat());
            approach(&a, &hb, dir, &mut xb, 0.0);
            xb.p += dir * (0.08 * rnd.f() - 0.06);
            let b = Poly::hull(&hb, &Transform::IDENTITY, 1.0, &xb);
            for (refp, inc, flipped) in [(&a, &b, false), (&b, &a, true)] {
                let rel = Relative::new(refp, inc);
                for f in 0..refp.hull.planes.len() {
                    let kept = face_contact_cached(refp, inc, &rel, f, 0.02, flipped, true);
                    let plain = face_contact_cached(refp, inc, &rel, f, 0.02, flipped, false);
                    assert_eq!(format!("{kept:?}"), format!("{plain:?}"), "trial {trial} face {f}");
                    let fp = face_pair(refp, inc, &rel, f);
                    cached += (fp.ref_he.len() <= FACE_CACHE && fp.inc_he.len() <= FACE_CACHE) as usize;
                    compared += 1;
                    touching += (kept.count > 1) as usize;
                }
            }
        }
        assert!(
            compared > 5000 && cached > compared * 9 / 10 && touching > compared / 10,
            "{compared} faces compared, {cached} with the arrays, {touching} with two points or more"
        );
    }

    /// The bound that lets `hull_hull` skip its edge loop: for random hull pairs, from
    /// 5 cm overlap to 10 cm apart, no axis — every edge pair's cross product and random
    /// directions — separates the cores by more than GJK's distance (or its overlap bound).
    #[test]
    fn gjk_bounds_every_axis_separation() {
        let mut rnd = Rnd(0x2545_f491_4f6c_dd1d);
        let cloud = |rnd: &mut Rnd| {
            let n = 8 + (rnd.f() * 16.0) as usize;
            (0..n).map(|_| rnd.point(Vec3::new(0.8, 0.6, 0.7))).collect::<Vec<_>>()
        };
        let mut checked = 0;
        for _ in 0..300 {
            let ha = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let hb = build(&cloud(&mut rnd), &HullSettings::default()).unwrap();
            let xa = Transform::new(Vec3::ZERO, rnd.quat());
            let dir = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
            let xb = Transform::new(dir * (0.3 + 0.5 * rnd.f()), rnd.quat());
            let a = Poly::hull(&ha, &Transform::IDENTITY, 1.0, &xa);
            let b = Poly::hull(&hb, &Transform::IDENTITY, 1.0, &xb);
            let rel = Relative::new(&a, &b);
            let g = gjk::distance_from(&Own(&a), &InA { poly: &b, rel }, Vec3::Y);
            let upper = if g.overlap { GJK_OVERLAP_BOUND } else { g.distance };
            if !(-0.05..=0.1).contains(&upper) && !g.overlap {
                continue;
            }
            checked += 1;
            let mut worst = f32::MIN;
            for ka in 0..ha.edge_gauss.len() {
                for kb in 0..hb.edge_gauss.len() {
                    if let Some((axis, _)) = edge_pair(&a, &b, &rel, ka, kb) {
                        worst = worst.max(support_separation(&a, &b, &rel, axis));
                    }
                }
            }
            for _ in 0..64 {
                let axis = Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5).normalize();
                worst = worst.max(support_separation(&a, &b, &rel, axis));
            }
            for f in 0..ha.planes.len() {
                worst = worst.max(face_a_separation(&a, &b, &rel, f));
            }
            for f in 0..hb.planes.len() {
                worst = worst.max(face_b_separation(&a, &b, &rel, f));
            }
            assert!(
                worst <= upper + 1.0e-6,
                "axis separation {worst} over GJK's bound {upper}"
            );
        }
        assert!(checked > 100, "only {checked} pairs in range");
    }
}
