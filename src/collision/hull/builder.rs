//! Quickhull (Barber, Dobkin & Huhdanpaa 1996; Gregorius, "Implementing Quickhull", GDC
//! 2014) in f64, then coplanar triangles merged into polygons.
//!
//! 1. **Initial tetrahedron** from the extreme points: the farthest pair among the six
//!    axis extremes, the point farthest from their line, the point farthest from that
//!    plane. A cloud whose extent, line distance or plane distance is within the tolerance
//!    has no volume: rejected.
//! 2. **Conflict lists.** Every other point goes to the face it is farthest above; only a
//!    point more than the tolerance `tol` above becomes a vertex, so points within `tol` of
//!    the hull are on it (this welds duplicates and near-duplicates: no two hull vertices
//!    end up within `tol`). Points kept within `tol` are measured again against all faces
//!    when the expansion ends, and it goes on if one now lies farther out (a point barely
//!    above a sharp corner's planes can end up outside a face built later).
//! 3. **Expansion.** The point farthest above any face is added: the faces it sees
//!    (distance above a tiny numerical `eps`, so the triangle hull is a true convex hull of
//!    the points taken) are removed, the horizon is walked and a cone of new faces joins
//!    it to the point; orphaned points go to the new face they are farthest above. Taking
//!    the globally farthest point first is what makes the **simplification** good: when
//!    the hull reaches `max_vertices` (255) the expansion stops, so the result is the hull
//!    of the 255 points that each were the farthest outside the hull so far; the points
//!    left out lie within the distance of the last point refused (`tests/hull.rs` measures
//!    it on dense spheres).
//! 4. **Merging.** Adjacent triangles are grown into polygons (largest triangle first)
//!    while all the polygon's vertices stay within `tol` of one plane and the polygon stays
//!    a disk; a polygon that came out not convex (small steep triangles fit in the
//!    tolerance slab) goes back to its triangles. Vertices left between fewer than three
//!    polygons (on a merged edge, or inside a merged face) are removed.
//!
//! The tolerance is relative to the cloud: `tol = max(weld, 1e-5) · diagonal` of the
//! cloud's bounding box (and at least a few f32 ulps of its largest coordinate).

use crate::error::{invalid, Result};
use crate::math::Vec3;
use glam::DVec3;

const NONE: u32 = u32::MAX;
/// Smallest relative tolerance, whatever the caller asks: merges what f32 cannot tell apart.
const MIN_RELATIVE_TOLERANCE: f64 = 1.0e-5;
/// Smallest cloud the builder accepts (bounding-box diagonal, m): the 1 mm floor of shape
/// sizes.
pub const MIN_HULL_EXTENT: f32 = 1.0e-3;
/// Largest relative weld tolerance a caller may ask for.
pub const MAX_WELD_TOLERANCE: f32 = 0.1;
/// Default relative weld tolerance (1 mm on a 1 m object).
pub const DEFAULT_WELD_TOLERANCE: f32 = 1.0e-3;

/// How a hull is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullSettings {
    /// Convex radius (m, >= 0): the shape is the hull grown by this much.
    pub convex_radius: f32,
    /// Points within this fraction of the cloud's bounding-box diagonal of the hull are
    /// welded onto it, and faces within it of one plane are merged (0 ..= 0.1).
    pub weld_tolerance: f32,
}

impl Default for HullSettings {
    fn default() -> Self {
        HullSettings {
            convex_radius: 0.0,
            weld_tolerance: DEFAULT_WELD_TOLERANCE,
        }
    }
}

#[derive(Clone)]
struct Tri {
    v: [u32; 3],
    n: DVec3,
    d: f64,
    /// Face across edge `v[i] → v[i + 1]`.
    adj: [u32; 3],
    alive: bool,
    outside: Vec<u32>,
    /// Farthest outside point and its distance.
    far: u32,
    far_d: f64,
}

impl Tri {
    fn new(pts: &[DVec3], a: u32, b: u32, c: u32) -> Option<Tri> {
        let (pa, pb, pc) = (pts[a as usize], pts[b as usize], pts[c as usize]);
        let n = (pb - pa).cross(pc - pa);
        let l = n.length();
        if l.is_nan() || l <= 0.0 || !l.is_finite() {
            return None;
        }
        let n = n / l;
        Some(Tri {
            v: [a, b, c],
            n,
            d: n.dot(pa),
            adj: [NONE; 3],
            alive: true,
            outside: Vec::new(),
            far: NONE,
            far_d: 0.0,
        })
    }

    #[inline]
    fn dist(&self, p: DVec3) -> f64 {
        self.n.dot(p) - self.d
    }

    fn push_outside(&mut self, i: u32, d: f64) {
        self.outside.push(i);
        if d > self.far_d || self.far == NONE {
            self.far_d = d;
            self.far = i;
        }
    }
}

struct Quickhull<'a> {
    pts: &'a [DVec3],
    tris: Vec<Tri>,
    eps: f64,
    tol: f64,
    vertex_count: usize,
    is_vertex: Vec<bool>,
}

/// Tolerances for a cloud: (`eps` for visibility, `tol` for welding and merging).
fn tolerances(pts: &[DVec3], weld: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
    for p in pts {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let diag = (hi - lo).length();
    let max_coord = lo.abs().max(hi.abs()).max_element();
    let eps = 1.0e-12 * (diag + max_coord);
    let tol = (weld.max(MIN_RELATIVE_TOLERANCE) * diag).max(8.0 * f32::EPSILON as f64 * max_coord);
    (eps, tol)
}

impl<'a> Quickhull<'a> {
    fn initial(&mut self) -> Option<()> {
        let pts = self.pts;
        let mut ext = [0usize; 6];
        for (i, p) in pts.iter().enumerate() {
            for k in 0..3 {
                if p[k] < pts[ext[2 * k]][k] {
                    ext[2 * k] = i;
                }
                if p[k] > pts[ext[2 * k + 1]][k] {
                    ext[2 * k + 1] = i;
                }
            }
        }
        let (mut i0, mut i1, mut best) = (0, 0, -1.0);
        for a in 0..6 {
            for b in a + 1..6 {
                let d = pts[ext[a]].distance_squared(pts[ext[b]]);
                if d > best {
                    best = d;
                    i0 = ext[a];
                    i1 = ext[b];
                }
            }
        }
        if best.sqrt() <= self.tol {
            return None;
        }
        let dir = (pts[i1] - pts[i0]).normalize();
        let (mut i2, mut best) = (0, -1.0);
        for (i, p) in pts.iter().enumerate() {
            let r = *p - pts[i0];
            let d = (r - dir * r.dot(dir)).length_squared();
            if d > best {
                best = d;
                i2 = i;
            }
        }
        if best.sqrt() <= self.tol {
            return None;
        }
        let n = (pts[i1] - pts[i0]).cross(pts[i2] - pts[i0]).normalize();
        let (mut i3, mut best) = (0, -1.0);
        for (i, p) in pts.iter().enumerate() {
            let d = (*p - pts[i0]).dot(n).abs();
            if d > best {
                best = d;
                i3 = i;
            }
        }
        if best <= self.tol {
            return None;
        }
        let (a, b, c, d) = (i0 as u32, i1 as u32, i2 as u32, i3 as u32);
        // Orient so `d` is below face (a, b, c).
        let (b, c) = if (pts[i3] - pts[i0]).dot(n) > 0.0 {
            (c, b)
        } else {
            (b, c)
        };
        for (x, y, z) in [(a, b, c), (a, d, b), (b, d, c), (c, d, a)] {
            self.tris.push(Tri::new(pts, x, y, z)?);
        }
        self.link_all();
        for i in [a, b, c, d] {
            self.is_vertex[i as usize] = true;
        }
        self.vertex_count = 4;
        for i in 0..pts.len() as u32 {
            if self.is_vertex[i as usize] {
                continue;
            }
            self.assign(i, 0..4);
        }
        Some(())
    }

    /// Adjacency by matching opposite edges (used for the initial tetrahedron).
    fn link_all(&mut self) {
        let n = self.tris.len();
        for f in 0..n {
            for i in 0..3 {
                let (u, v) = (self.tris[f].v[i], self.tris[f].v[(i + 1) % 3]);
                for g in 0..n {
                    if g == f {
                        continue;
                    }
                    for j in 0..3 {
                        if self.tris[g].v[j] == v && self.tris[g].v[(j + 1) % 3] == u {
                            self.tris[f].adj[i] = g as u32;
                        }
                    }
                }
            }
        }
    }

    /// The live face among `faces` that point `i` is farthest above (by more than `eps`).
    fn farthest(&self, i: u32, faces: std::ops::Range<usize>) -> (u32, f64) {
        let p = self.pts[i as usize];
        let (mut best, mut best_d) = (NONE, self.eps);
        for f in faces {
            let t = &self.tris[f];
            if t.alive {
                let d = t.dist(p);
                if d > best_d {
                    best_d = d;
                    best = f as u32;
                }
            }
        }
        (best, best_d)
    }

    /// Reassigns every kept point to the face it is farthest above now; true when one is
    /// more than `tol` above it (the expansion must go on).
    fn remeasure(&mut self) -> bool {
        let mut kept = Vec::new();
        for t in self.tris.iter_mut().filter(|t| t.alive) {
            kept.append(&mut t.outside);
            t.far = NONE;
            t.far_d = 0.0;
        }
        let all = self.tris.len();
        for i in kept {
            self.assign(i, 0..all);
        }
        self.tris.iter().any(|t| t.alive && t.far != NONE && t.far_d > self.tol)
    }

    /// Puts point `i` on the face (among `faces`) it is farthest above, if above any by more
    /// than `eps`. Only points more than `tol` above become vertices; the others stay in
    /// the lists so that, should their face go, they are measured against the new faces
    /// (a point barely above a sharp corner's planes may lie far outside the final hull).
    fn assign(&mut self, i: u32, faces: std::ops::Range<usize>) {
        let (best, best_d) = self.farthest(i, faces);
        if best != NONE {
            self.tris[best as usize].push_outside(i, best_d);
        }
    }

    /// Adds the farthest outside point; false when none is left.
    fn expand(&mut self, visible: &mut Vec<u32>, horizon: &mut Vec<(u32, u32, u32)>) -> bool {
        let mut eye_face = NONE;
        let mut far = self.tol;
        for (f, t) in self.tris.iter().enumerate() {
            if t.alive && t.far != NONE && t.far_d > far {
                far = t.far_d;
                eye_face = f as u32;
            }
        }
        if eye_face == NONE {
            return false;
        }
        let eye = self.tris[eye_face as usize].far;
        let p = self.pts[eye as usize];
        // Visible faces (depth-first from the eye face).
        visible.clear();
        horizon.clear();
        let mut stack = vec![eye_face];
        let mut seen = vec![eye_face];
        while let Some(f) = stack.pop() {
            visible.push(f);
            for i in 0..3 {
                let g = self.tris[f as usize].adj[i];
                if seen.contains(&g) {
                    continue;
                }
                if self.tris[g as usize].dist(p) > self.eps {
                    seen.push(g);
                    stack.push(g);
                }
            }
        }
        for &f in visible.iter() {
            for i in 0..3 {
                let g = self.tris[f as usize].adj[i];
                if !visible.contains(&g) {
                    horizon.push((f, i as u32, g));
                }
            }
        }
        // Chain the horizon into a loop (each edge starts where the previous ends).
        let edge = |t: &Self, h: (u32, u32, u32)| {
            let v = t.tris[h.0 as usize].v;
            (v[h.1 as usize], v[(h.1 as usize + 1) % 3])
        };
        for k in 1..horizon.len() {
            let end = edge(self, horizon[k - 1]).1;
            match (k..horizon.len()).find(|&j| edge(self, horizon[j]).0 == end) {
                Some(j) => horizon.swap(k, j),
                None => return self.drop_point(eye_face, eye),
            }
        }
        if horizon.is_empty() || edge(self, horizon[horizon.len() - 1]).1 != edge(self, horizon[0]).0 {
            return self.drop_point(eye_face, eye);
        }
        // The cone of new faces.
        let first = self.tris.len();
        let m = horizon.len();
        for &h in horizon.iter() {
            let (u, v) = edge(self, h);
            match Tri::new(self.pts, u, v, eye) {
                Some(t) => self.tris.push(t),
                None => {
                    self.tris.truncate(first);
                    return self.drop_point(eye_face, eye);
                }
            }
        }
        for (k, &h) in horizon.iter().enumerate() {
            let g = h.2;
            let f = (first + k) as u32;
            let (u, v) = edge(self, h);
            // Across u→v: the outer face; its edge v→u now faces the new triangle.
            let outer = &mut self.tris[g as usize];
            for j in 0..3 {
                if outer.v[j] == v && outer.v[(j + 1) % 3] == u {
                    outer.adj[j] = f;
                }
            }
            let t = &mut self.tris[f as usize];
            t.adj[0] = g;
            t.adj[1] = (first + (k + 1) % m) as u32;
            t.adj[2] = (first + (k + m - 1) % m) as u32;
        }
        self.is_vertex[eye as usize] = true;
        self.vertex_count += 1;
        let mut orphans = Vec::new();
        for &f in visible.iter() {
            let t = &mut self.tris[f as usize];
            t.alive = false;
            orphans.append(&mut t.outside);
        }
        let all = self.tris.len();
        for i in orphans {
            if i == eye {
                continue;
            }
            // The new faces first; a point not clearly outside them may still be farther
            // above a face the eye did not see.
            let (f, d) = self.farthest(i, first..all);
            let (f, d) = if d > self.tol {
                (f, d)
            } else {
                let (g, e) = self.farthest(i, 0..first);
                if e > d {
                    (g, e)
                } else {
                    (f, d)
                }
            };
            if f != NONE {
                self.tris[f as usize].push_outside(i, d);
            }
        }
        true
    }

    /// Removes a point whose cone could not be built (numerically degenerate); it lies
    /// within rounding of the hull.
    fn drop_point(&mut self, face: u32, i: u32) -> bool {
        let t = &mut self.tris[face as usize];
        t.outside.retain(|&x| x != i);
        t.far = NONE;
        t.far_d = 0.0;
        let pts = self.pts;
        let n = t.n;
        let d = t.d;
        for &x in &t.outside {
            let dx = n.dot(pts[x as usize]) - d;
            if t.far == NONE || dx > t.far_d {
                t.far = x;
                t.far_d = dx;
            }
        }
        true
    }
}

/// Builds the convex polyhedron of `points`: vertices (only those used) and
/// counter-clockwise face loops. `weld` is the relative tolerance; the hull keeps at most
/// `max_vertices` vertices (see the module doc). `None` when the cloud has no volume.
pub(crate) fn build_polyhedron(points: &[Vec3], weld: f32, max_vertices: usize) -> Option<(Vec<Vec3>, Vec<Vec<u16>>)> {
    if points.len() < 4 {
        return None;
    }
    let pts: Vec<DVec3> = points.iter().map(|p| p.as_dvec3()).collect();
    let (eps, tol) = tolerances(&pts, weld as f64);
    let mut qh = Quickhull {
        pts: &pts,
        tris: Vec::new(),
        eps,
        tol,
        vertex_count: 0,
        is_vertex: vec![false; pts.len()],
    };
    qh.initial()?;
    let (mut visible, mut horizon) = (Vec::new(), Vec::new());
    loop {
        while qh.vertex_count < max_vertices.max(4) && qh.expand(&mut visible, &mut horizon) {}
        // A point kept on a face within `tol` may have come to lie farther above a face
        // built later elsewhere: measure the kept points against every face again and go
        // on while one is clearly outside.
        if qh.vertex_count >= max_vertices.max(4) || !qh.remeasure() {
            break;
        }
    }
    let tris: Vec<Tri> = qh.tris.into_iter().filter(|t| t.alive).collect();
    merge(&pts, tris, tol)
}

/// Merges coplanar triangles into polygons and removes vertices left between fewer than
/// three of them; returns compacted vertices and face loops.
fn merge(pts: &[DVec3], mut tris: Vec<Tri>, tol: f64) -> Option<(Vec<Vec3>, Vec<Vec<u16>>)> {
    // Re-index adjacency after dropping dead faces.
    let n = tris.len();
    {
        let mut pos = std::collections::HashMap::new();
        for (i, t) in tris.iter().enumerate() {
            pos.insert((t.v[0], t.v[1]), (i, 0));
            pos.insert((t.v[1], t.v[2]), (i, 1));
            pos.insert((t.v[2], t.v[0]), (i, 2));
        }
        for t in tris.iter_mut() {
            for k in 0..3 {
                let (u, v) = (t.v[k], t.v[(k + 1) % 3]);
                t.adj[k] = pos.get(&(v, u))?.0 as u32;
            }
        }
    }
    let area = |t: &Tri| {
        let (a, b, c) = (pts[t.v[0] as usize], pts[t.v[1] as usize], pts[t.v[2] as usize]);
        (b - a).cross(c - a)
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        area(&tris[b])
            .length()
            .total_cmp(&area(&tris[a]).length())
            .then(a.cmp(&b))
    });
    let mut group = vec![NONE; n];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut in_group = vec![0u32; pts.len()];
    for &seed in &order {
        if group[seed] != NONE {
            continue;
        }
        let g = groups.len() as u32;
        let mut members = vec![seed];
        group[seed] = g;
        let mut normal = area(&tris[seed]);
        let mut verts: Vec<u32> = tris[seed].v.to_vec();
        for &v in &tris[seed].v {
            in_group[v as usize] += 1;
        }
        let mut k = 0;
        while k < members.len() {
            let f = members[k];
            k += 1;
            for e in 0..3 {
                let h = tris[f].adj[e] as usize;
                if group[h] != NONE {
                    continue;
                }
                let shared = (0..3).filter(|&j| group[tris[h].adj[j] as usize] == g).count();
                let known = tris[h].v.iter().filter(|&&v| in_group[v as usize] > 0).count();
                if shared < 3 && known != shared + 1 {
                    continue;
                }
                let nn = (normal + area(&tris[h])).normalize();
                if nn.dot(tris[h].n) < 0.0 {
                    continue;
                }
                let (mut lo, mut hi) = (f64::MAX, f64::MIN);
                for &v in verts.iter().chain(tris[h].v.iter()) {
                    let x = nn.dot(pts[v as usize]);
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
                if hi - lo > tol {
                    continue;
                }
                group[h] = g;
                members.push(h);
                normal += area(&tris[h]);
                for &v in &tris[h].v {
                    if in_group[v as usize] == 0 {
                        verts.push(v);
                    }
                    in_group[v as usize] += 1;
                }
            }
        }
        for &v in &verts {
            in_group[v as usize] = 0;
        }
        groups.push(members);
    }
    // Boundary loop of each group; a group that is not a single loop is split back into
    // its triangles.
    let mut loops: Vec<Vec<u32>> = Vec::new();
    for members in &groups {
        let g = group[members[0]];
        let mut boundary: Vec<(u32, u32)> = Vec::new();
        for &f in members {
            for e in 0..3 {
                if group[tris[f].adj[e] as usize] != g {
                    boundary.push((tris[f].v[e], tris[f].v[(e + 1) % 3]));
                }
            }
        }
        let mut lp = vec![boundary[0].0];
        let mut cur = boundary[0].1;
        let mut ok = true;
        while cur != boundary[0].0 {
            if lp.len() > boundary.len() {
                ok = false;
                break;
            }
            lp.push(cur);
            match boundary.iter().filter(|b| b.0 == cur).count() {
                1 => cur = boundary.iter().find(|b| b.0 == cur).unwrap().1,
                _ => {
                    ok = false;
                    break;
                }
            }
        }
        if ok && lp.len() == boundary.len() && convex(pts, &lp, normal_of(pts, members, &tris)) {
            loops.push(lp);
        } else {
            for &f in members {
                loops.push(tris[f].v.to_vec());
            }
        }
    }
    // Vertices between fewer than three polygons.
    let mut faces_at = vec![0u32; pts.len()];
    for lp in &loops {
        for &v in lp {
            faces_at[v as usize] += 1;
        }
    }
    let trimmed: Vec<Vec<u32>> = loops
        .iter()
        .map(|lp| lp.iter().copied().filter(|&v| faces_at[v as usize] >= 3).collect())
        .collect();
    let loops = if std::env::var("NOTRIM").is_err() && trimmed.iter().all(|l: &Vec<u32>| l.len() >= 3) {
        trimmed
    } else {
        loops
    };
    // Compact.
    let mut remap = vec![NONE; pts.len()];
    let mut vertices = Vec::new();
    let mut out = Vec::with_capacity(loops.len());
    for lp in &loops {
        let mut l = Vec::with_capacity(lp.len());
        for &v in lp {
            if remap[v as usize] == NONE {
                remap[v as usize] = vertices.len() as u32;
                vertices.push(pts[v as usize].as_vec3());
            }
            l.push(remap[v as usize] as u16);
        }
        out.push(l);
    }
    if vertices.len() > u16::MAX as usize {
        return None;
    }
    // Euler: V - E + F = 2.
    let e: usize = out.iter().map(|l| l.len()).sum::<usize>() / 2;
    if vertices.len() + out.len() != e + 2 {
        return None;
    }
    Some((vertices, out))
}

/// Area-weighted normal of a group of triangles.
fn normal_of(pts: &[DVec3], members: &[usize], tris: &[Tri]) -> DVec3 {
    members
        .iter()
        .map(|&f| {
            let v = tris[f].v;
            let (a, b, c) = (pts[v[0] as usize], pts[v[1] as usize], pts[v[2] as usize]);
            (b - a).cross(c - a)
        })
        .sum::<DVec3>()
        .normalize()
}

/// True when the loop turns left (about `n`) at every vertex, allowing 0.6° of reflex
/// bend: a merge of nearly coplanar triangles that made a notch is undone.
fn convex(pts: &[DVec3], lp: &[u32], n: DVec3) -> bool {
    let k = lp.len();
    (0..k).all(|i| {
        let a = pts[lp[i] as usize];
        let b = pts[lp[(i + 1) % k] as usize];
        let c = pts[lp[(i + 2) % k] as usize];
        let (ab, bc) = (b - a, c - b);
        ab.cross(bc).dot(n) >= -0.01 * ab.length() * bc.length()
    })
}

/// Builds a hull from a point cloud (see the module doc). Errors (nothing is built): fewer
/// than 4 points, a NaN or infinite coordinate, a negative or non-finite radius, a weld
/// tolerance outside `0 ..= 0.1`, a cloud smaller than 1 mm, or one with no volume
/// (collinear or coplanar within the tolerance).
pub fn build(points: &[Vec3], settings: &HullSettings) -> Result<super::ConvexHull> {
    if points.len() < 4 {
        return Err(invalid(format!(
            "a convex hull needs at least 4 points, got {}",
            points.len()
        )));
    }
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(invalid(format!("convex hull point {i} must be finite, got {p}")));
    }
    let r = settings.convex_radius;
    if !(r.is_finite() && r >= 0.0) {
        return Err(invalid(format!("convex_radius must be finite and >= 0, got {r}")));
    }
    let w = settings.weld_tolerance;
    if !(w.is_finite() && (0.0..=MAX_WELD_TOLERANCE).contains(&w)) {
        return Err(invalid(format!(
            "weld_tolerance must be in 0..={MAX_WELD_TOLERANCE}, got {w}"
        )));
    }
    let lo = points.iter().fold(Vec3::splat(f32::MAX), |m, p| m.min(*p));
    let hi = points.iter().fold(Vec3::splat(f32::MIN), |m, p| m.max(*p));
    let extent = (hi - lo).length();
    if extent < MIN_HULL_EXTENT {
        return Err(invalid(format!(
            "convex hull points span {extent} m; at least {MIN_HULL_EXTENT} m is needed"
        )));
    }
    let (vertices, loops) = build_polyhedron(points, w, super::MAX_HULL_VERTICES)
        .ok_or_else(|| invalid("convex hull points are collinear or coplanar (no volume within the weld tolerance)"))?;
    super::ConvexHull::from_polyhedron(vertices, &loops, r)
        .ok_or_else(|| invalid("convex hull points do not form a closed polyhedron"))
}
