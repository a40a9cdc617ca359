//! Heightfields: terrain as a grid of heights, colliding like the equivalent triangle mesh
//! without storing triangles.
//!
//! * **Grid.** `rows × columns` samples, row-major: sample `(row, column)` is
//!   `heights[row * columns + column]` at `(column, height, row)` in the heightfield's own
//!   frame, so samples are one unit apart in x and z; a shape's per-axis scale gives the
//!   spacing in x and z and the height scale in y.
//! * **Cells and triangles.** Cell `(row, column)` (for `row < rows − 1`, `column <
//!   columns − 1`) has corners `a = (r, c)`, `b = (r, c+1)`, `c = (r+1, c)`, `d = (r+1, c+1)`
//!   and is split along `a–d` into triangles `2·cell` = `(a, c, d)` and `2·cell + 1` =
//!   `(a, d, b)`, with `cell = row · (columns − 1) + column`, both facing +y.
//! * **Holes.** A per-cell flag: a hole cell has no triangles, and the edges around it are
//!   open (active). Heights must be finite; there is no sentinel height.
//! * **Culling.** A min/max pyramid over blocks of `BLOCK × BLOCK` cells, halved per level up
//!   to one block, lets a query skip regions above or below its box without reading heights.
//! * **Edges.** Active-edge flags are not stored: they depend on the shape's scale, and the
//!   neighbouring heights are at hand, so `triangle` derives them for the scaled grid (same
//!   rule as meshes, `mesh/edges.rs`).
//!
//! Memory: 4 bytes per sample, 8 bytes per block per pyramid level (about 1/6 of a byte
//! per cell) and, when there are holes, a bit per cell: 1024 × 1024 samples take 4.37 MB,
//! 4.50 MB with holes (`tests/heightfield.rs`).

use crate::collision::aabb::Aabb;
use crate::collision::mesh::edges::{edge_active, ALL_EDGES};
use crate::error::{invalid, Result};
use crate::math::Vec3;

/// The neighbouring cell across a triangle edge and the sample opposite the edge in it:
/// `(cell row, cell column, sample row, sample column)`.
type Across = (i64, i64, i64, i64);

/// Cells per side of a level-0 block of the min/max pyramid.
pub const BLOCK: u32 = 8;
/// Most samples along either side.
pub const MAX_SAMPLES: u32 = 32768;

#[derive(Clone, Debug)]
struct Level {
    /// Blocks along x (columns) and z (rows).
    columns: u32,
    rows: u32,
    /// Min and max height per block, row-major.
    range: Vec<[f32; 2]>,
}

/// A heightfield (see the module doc), immutable once built.
#[derive(Clone, Debug)]
pub struct Heightfield {
    rows: u32,
    columns: u32,
    heights: Vec<f32>,
    /// One bit per cell, row-major; set = hole. Empty when there are no holes.
    holes: Vec<u64>,
    /// `levels[0]` covers `BLOCK × BLOCK` cells per entry; the last has one entry.
    levels: Vec<Level>,
    min_height: f32,
    max_height: f32,
}

impl Heightfield {
    /// Builds a heightfield of `rows × columns` samples (each at least 2 and at most
    /// `MAX_SAMPLES`) from row-major `heights` (finite) and optional per-cell hole flags
    /// (`(rows − 1) · (columns − 1)` of them, row-major).
    pub fn new(rows: u32, columns: u32, heights: &[f32], holes: Option<&[bool]>) -> Result<Heightfield> {
        for (name, n) in [("rows", rows), ("columns", columns)] {
            if !(2..=MAX_SAMPLES).contains(&n) {
                return Err(invalid(format!(
                    "heightfield {name} must be in 2..={MAX_SAMPLES} samples, got {n}"
                )));
            }
        }
        let samples = rows as usize * columns as usize;
        if heights.len() != samples {
            return Err(invalid(format!(
                "heightfield needs rows × columns = {samples} heights, got {}",
                heights.len()
            )));
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(invalid(format!(
                "heightfield height {i} (row {}, column {}) must be finite, got {}",
                i / columns as usize,
                i % columns as usize,
                heights[i]
            )));
        }
        let cells = (rows as usize - 1) * (columns as usize - 1);
        let mut bits = Vec::new();
        if let Some(h) = holes {
            if h.len() != cells {
                return Err(invalid(format!(
                    "heightfield holes need one flag per cell, (rows − 1) × (columns − 1) = {cells}, got {}",
                    h.len()
                )));
            }
            if h.iter().any(|&x| x) {
                bits = vec![0u64; cells.div_ceil(64)];
                for (i, _) in h.iter().enumerate().filter(|(_, &x)| x) {
                    bits[i / 64] |= 1 << (i % 64);
                }
            }
        }
        let mut hf = Heightfield {
            rows,
            columns,
            heights: heights.to_vec(),
            holes: bits,
            levels: Vec::new(),
            min_height: 0.0,
            max_height: 0.0,
        };
        hf.build_levels();
        let top = hf.levels.last().expect("at least one level").range[0];
        (hf.min_height, hf.max_height) = (top[0], top[1]);
        Ok(hf)
    }

    fn build_levels(&mut self) {
        let (cc, cr) = (self.columns - 1, self.rows - 1);
        let (bc, br) = (cc.div_ceil(BLOCK), cr.div_ceil(BLOCK));
        let mut range = Vec::with_capacity((bc * br) as usize);
        for by in 0..br {
            for bx in 0..bc {
                let (mut lo, mut hi) = (f32::MAX, f32::MIN);
                for r in by * BLOCK..=((by + 1) * BLOCK).min(cr) {
                    for c in bx * BLOCK..=((bx + 1) * BLOCK).min(cc) {
                        let h = self.height(r, c);
                        lo = lo.min(h);
                        hi = hi.max(h);
                    }
                }
                range.push([lo, hi]);
            }
        }
        self.levels.push(Level {
            columns: bc,
            rows: br,
            range,
        });
        loop {
            let prev = self.levels.last().unwrap();
            if prev.columns == 1 && prev.rows == 1 {
                break;
            }
            let (nc, nr) = (prev.columns.div_ceil(2), prev.rows.div_ceil(2));
            let mut range = Vec::with_capacity((nc * nr) as usize);
            for y in 0..nr {
                for x in 0..nc {
                    let (mut lo, mut hi) = (f32::MAX, f32::MIN);
                    for yy in 2 * y..(2 * y + 2).min(prev.rows) {
                        for xx in 2 * x..(2 * x + 2).min(prev.columns) {
                            let r = prev.range[(yy * prev.columns + xx) as usize];
                            lo = lo.min(r[0]);
                            hi = hi.max(r[1]);
                        }
                    }
                    range.push([lo, hi]);
                }
            }
            self.levels.push(Level {
                columns: nc,
                rows: nr,
                range,
            });
        }
    }

    pub fn rows(&self) -> u32 {
        self.rows
    }

    pub fn columns(&self) -> u32 {
        self.columns
    }

    /// Cells (two triangles each, unless a hole).
    pub fn cell_count(&self) -> usize {
        (self.rows as usize - 1) * (self.columns as usize - 1)
    }

    pub fn hole_count(&self) -> usize {
        self.holes.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// Bounds in the heightfield's own (unscaled) frame.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            Vec3::new(0.0, self.min_height, 0.0),
            Vec3::new((self.columns - 1) as f32, self.max_height, (self.rows - 1) as f32),
        )
    }

    /// Heap and inline bytes the heightfield occupies.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.heights.capacity() * 4
            + self.holes.capacity() * 8
            + self.levels.capacity() * std::mem::size_of::<Level>()
            + self.levels.iter().map(|l| l.range.capacity() * 8).sum::<usize>()
    }

    #[inline]
    pub fn height(&self, row: u32, column: u32) -> f32 {
        self.heights[(row * self.columns + column) as usize]
    }

    #[inline]
    pub fn is_hole(&self, row: u32, column: u32) -> bool {
        if self.holes.is_empty() {
            return false;
        }
        let i = (row * (self.columns - 1) + column) as usize;
        self.holes[i / 64] & (1 << (i % 64)) != 0
    }

    /// Calls `visit(row, column)` for every non-hole cell whose bounds (unscaled frame)
    /// overlap `b`, row by row; `visit` returns false to stop.
    pub fn query(&self, b: &Aabb, mut visit: impl FnMut(u32, u32) -> bool) {
        let (cc, cr) = (self.columns - 1, self.rows - 1);
        if b.max.x < 0.0
            || b.max.z < 0.0
            || b.min.x > cc as f32
            || b.min.z > cr as f32
            || b.max.y < self.min_height
            || b.min.y > self.max_height
        {
            return;
        }
        // Cell ranges (inclusive): column c spans [c, c + 1] in x.
        let (c0, c1) = (
            (b.min.x - 1.0).ceil().max(0.0) as u32,
            b.max.x.floor().min((cc - 1) as f32) as u32,
        );
        let (r0, r1) = (
            (b.min.z - 1.0).ceil().max(0.0) as u32,
            b.max.z.floor().min((cr - 1) as f32) as u32,
        );
        if c0 > c1 || r0 > r1 {
            return;
        }
        // Walk the pyramid from the top down to level-0 blocks inside the range.
        let top = self.levels.len() - 1;
        let mut stack = [(0u32, 0u32, 0u32); 64];
        stack[0] = (top as u32, 0, 0);
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let (level, x, y) = stack[len];
            let l = &self.levels[level as usize];
            let r = l.range[(y * l.columns + x) as usize];
            if r[1] < b.min.y || r[0] > b.max.y {
                continue;
            }
            let span = BLOCK << level; // cells per block at this level
            let (bx0, bx1) = (x * span, ((x + 1) * span).min(cc) - 1);
            let (by0, by1) = (y * span, ((y + 1) * span).min(cr) - 1);
            if bx1 < c0 || bx0 > c1 || by1 < r0 || by0 > r1 {
                continue;
            }
            if level == 0 {
                for row in by0.max(r0)..=by1.min(r1) {
                    for column in bx0.max(c0)..=bx1.min(c1) {
                        if self.is_hole(row, column) {
                            continue;
                        }
                        let h = [
                            self.height(row, column),
                            self.height(row, column + 1),
                            self.height(row + 1, column),
                            self.height(row + 1, column + 1),
                        ];
                        let lo = h[0].min(h[1]).min(h[2]).min(h[3]);
                        let hi = h[0].max(h[1]).max(h[2]).max(h[3]);
                        if hi < b.min.y || lo > b.max.y {
                            continue;
                        }
                        if !visit(row, column) {
                            return;
                        }
                    }
                }
                continue;
            }
            // Children in reverse so they pop in row-major order.
            let below = &self.levels[level as usize - 1];
            for cy in (2 * y..(2 * y + 2).min(below.rows)).rev() {
                for cx in (2 * x..(2 * x + 2).min(below.columns)).rev() {
                    stack[len] = (level - 1, cx, cy);
                    len += 1;
                }
            }
        }
    }

    /// Vertex `(row, column)` scaled by `s`.
    #[inline]
    fn vertex(&self, row: u32, column: u32, s: Vec3) -> Vec3 {
        Vec3::new(column as f32 * s.x, self.height(row, column) * s.y, row as f32 * s.z)
    }

    /// Whether the cell `(row, column)` exists and is not a hole (signed indices).
    #[inline]
    fn solid(&self, row: i64, column: i64) -> bool {
        row >= 0
            && column >= 0
            && row < self.rows as i64 - 1
            && column < self.columns as i64 - 1
            && !self.is_hole(row as u32, column as u32)
    }

    /// Triangle `k` (0 or 1) of cell `(row, column)` under scale `s`: vertices (scaled
    /// heightfield frame), unit normal and active-edge bits.
    #[inline]
    pub fn triangle(&self, row: u32, column: u32, k: u32, s: Vec3) -> ([Vec3; 3], Vec3, u8) {
        let (v, n) = self.triangle_plane(row, column, k, s);
        (v, n, self.triangle_flags(row, column, k, s, &v, n))
    }

    /// The vertices and unit normal of `triangle` (the flags, `triangle_flags`, cost more:
    /// a caller may leave them out for a triangle it rejects on its plane).
    #[inline]
    pub fn triangle_plane(&self, row: u32, column: u32, k: u32, s: Vec3) -> ([Vec3; 3], Vec3) {
        let v = if k == 0 {
            // (a, c, d)
            [
                self.vertex(row, column, s),
                self.vertex(row + 1, column, s),
                self.vertex(row + 1, column + 1, s),
            ]
        } else {
            // (a, d, b)
            [
                self.vertex(row, column, s),
                self.vertex(row + 1, column + 1, s),
                self.vertex(row, column + 1, s),
            ]
        };
        (v, (v[1] - v[0]).cross(v[2] - v[0]).normalize())
    }

    /// The active-edge bits of `triangle`, given its vertices `v` and normal `n` from
    /// `triangle_plane`.
    #[inline]
    pub fn triangle_flags(&self, row: u32, column: u32, k: u32, s: Vec3, v: &[Vec3; 3], n: Vec3) -> u8 {
        let (r, col) = (row as i64, column as i64);
        // For each edge: the neighbouring cell and the sample opposite the edge in it.
        let across: [Across; 3] = if k == 0 {
            // (a, c, d): a→c borders cell (r, c−1), c→d cell (r+1, c), d→a this cell's (a, d, b).
            [
                (r, col - 1, r, col - 1),
                (r + 1, col, r + 2, col + 1),
                (r, col, r, col + 1),
            ]
        } else {
            // (a, d, b): a→d this cell's (a, c, d), d→b cell (r, c+1), b→a cell (r−1, c).
            [
                (r, col, r + 1, col),
                (r, col + 1, r + 1, col + 2),
                (r - 1, col, r - 1, col),
            ]
        };
        let mut flags = ALL_EDGES;
        for (e, &(nr, nc, or, oc)) in across.iter().enumerate() {
            if !self.solid(nr, nc) {
                continue;
            }
            let opp = self.vertex(or as u32, oc as u32, s);
            if !edge_active(n, v[e], v[(e + 1) % 3], opp) {
                flags &= !(1 << e);
            }
        }
        flags
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bumpy(rows: u32, columns: u32) -> Vec<f32> {
        (0..rows * columns)
            .map(|i| {
                let (r, c) = ((i / columns) as f32, (i % columns) as f32);
                (0.3 * r).sin() + 0.5 * (0.2 * c).cos()
            })
            .collect()
    }

    #[test]
    fn query_matches_brute_force() {
        let (rows, cols) = (37, 53);
        let h = bumpy(rows, cols);
        let holes: Vec<bool> = (0..(rows - 1) * (cols - 1)).map(|i| i % 7 == 3).collect();
        let hf = Heightfield::new(rows, cols, &h, Some(&holes)).unwrap();
        let mut seed = 12345u32;
        let mut rnd = || {
            seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for _ in 0..300 {
            let c = Vec3::new(rnd() * 60.0 - 4.0, rnd() * 3.0 - 1.5, rnd() * 44.0 - 4.0);
            let e = Vec3::new(rnd() * 6.0, rnd() * 0.5, rnd() * 6.0);
            let b = Aabb::from_center_extents(c, e);
            let mut got = Vec::new();
            hf.query(&b, |r, c| {
                got.push((r, c));
                true
            });
            let mut want = Vec::new();
            for r in 0..rows - 1 {
                for c in 0..cols - 1 {
                    if hf.is_hole(r, c) {
                        continue;
                    }
                    let (lo, hi) = (
                        Vec3::new(c as f32, f32::MAX, r as f32),
                        Vec3::new((c + 1) as f32, f32::MIN, (r + 1) as f32),
                    );
                    let hs = [
                        hf.height(r, c),
                        hf.height(r, c + 1),
                        hf.height(r + 1, c),
                        hf.height(r + 1, c + 1),
                    ];
                    let (ylo, yhi) = (
                        hs.iter().cloned().fold(f32::MAX, f32::min),
                        hs.iter().cloned().fold(f32::MIN, f32::max),
                    );
                    let cellb = Aabb::new(Vec3::new(lo.x, ylo, lo.z), Vec3::new(hi.x, yhi, hi.z));
                    if cellb.overlaps(&b) {
                        want.push((r, c));
                    }
                }
            }
            got.sort();
            assert_eq!(got, want, "{b:?}");
        }
    }

    #[test]
    fn flat_interior_edges_inactive_and_holes_open_edges() {
        let h = vec![0.0; 16];
        let mut holes = vec![false; 9];
        holes[4] = true; // the middle cell
        let hf = Heightfield::new(4, 4, &h, Some(&holes)).unwrap();
        assert_eq!(hf.hole_count(), 1);
        // Cell (0,0): triangle 0 (a,c,d): a→c is the grid border (active), c→d borders cell
        // (1,0) (flat, inactive), d→a the diagonal (inactive).
        let (_, n, f) = hf.triangle(0, 0, 0, Vec3::ONE);
        assert!((n - Vec3::Y).length() < 1e-6);
        assert_eq!(f, 0b001);
        // Cell (1,0) triangle 1 (a,d,b): d→b borders the hole (1,1): active.
        let (_, _, f) = hf.triangle(1, 0, 1, Vec3::ONE);
        assert_eq!(f, 0b010);
        let e = Heightfield::new(4, 4, &h[..15], None).unwrap_err();
        assert!(e.to_string().contains("16 heights"), "{e}");
        let mut nan = h.clone();
        nan[5] = f32::NAN;
        assert!(Heightfield::new(4, 4, &nan, None)
            .unwrap_err()
            .to_string()
            .contains("row 1, column 1"));
        assert!(Heightfield::new(1, 4, &h[..4], None).is_err());
        assert!(Heightfield::new(4, 4, &h, Some(&holes[..8])).is_err());
    }
}

crate::snap_struct!(Level { columns, rows, range });
crate::snap_struct!(Heightfield {
    rows,
    columns,
    heights,
    holes,
    levels,
    min_height,
    max_height,
});
