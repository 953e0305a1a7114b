//! The clipmap the water is drawn on: square rings of (2M + 1)² grid points around the eye,
//! each twice as coarse as the one inside it, snapped to their own grids so that vertices do
//! not swim as the eye moves.

/// Most rings of the clipmap (the size of the uniforms' ring table).
pub const MAX_RINGS: usize = 16;
/// Vertex spacing of the finest ring, m.
pub const FINEST_SPACING: f32 = 0.25;
/// The rings reach at least this far from the eye, m (the horizon seen from 500 m up is
/// 80 km away).
pub const MESH_REACH: f32 = 120_000.0;
/// Where a ring's hole (the next finer ring's square) sits in its cells, (dx, dz) ∈ {0, 1}²:
/// the index of a ring's mesh among the four [`grid_indices`] meshes with a hole.
pub const HOLES: [(u32, u32); 4] = [(0, 0), (1, 0), (0, 1), (1, 1)];

/// One ring of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Ring {
    /// Centre (x, z), m: on the grid of twice the spacing.
    pub centre: [f32; 2],
    /// Distance between neighbouring vertices, m.
    pub spacing: f32,
    /// Which of the [`HOLES`] meshes draws it (`None`: the finest ring, a full square).
    pub hole: Option<usize>,
}

/// The rings around an eye at (x, z) = `eye`, `height` m above the water, for rings `half_cells`
/// cells from centre to edge: written to `out` from the finest, their number returned. The
/// finest ring's spacing is [`FINEST_SPACING`]·2^l with l growing with the height (so that its
/// cells stay near a pixel's footprint below the eye); rings are added until they reach
/// [`MESH_REACH`].
pub fn rings(eye: [f32; 2], height: f32, half_cells: u32, out: &mut [Ring; MAX_RINGS]) -> usize {
    let first = ((height.abs().max(1.0) / 8.0).log2().floor().max(0.0) as usize).min(6);
    let half = half_cells as f32;
    let mut count = 0;
    for l in first..first + MAX_RINGS {
        let spacing = FINEST_SPACING * (1u32 << l) as f32;
        let snap = 2.0 * spacing;
        let centre = [
            (eye[0] / snap).floor() * snap,
            (eye[1] / snap).floor() * snap,
        ];
        let hole = (count > 0).then(|| {
            // Where the finer ring's square sits in this ring's cells: 0 or 1 on each axis.
            let finer = out[count - 1].centre;
            let offset = |a: f32, b: f32| ((a - b) / spacing).round().clamp(0.0, 1.0) as usize;
            offset(finer[0], centre[0]) + 2 * offset(finer[1], centre[1])
        });
        out[count] = Ring {
            centre,
            spacing,
            hole,
        };
        count += 1;
        if half * spacing >= MESH_REACH {
            break;
        }
    }
    count
}

/// Triangle indices of the clipmap grid of (2m + 1)² vertices (index j·(2m + 1) + i): every
/// cell, or for a ring every cell outside the m × m square of the next finer ring (whose
/// lower corner lies at cell (m/2 + dx, m/2 + dz)) but its outermost cells: the ring overlaps
/// the finer ring's border by one of its cells, where the finer ring is fully morphed into
/// this ring's grid, so the two draw the same surface there (meeting edge to edge, they left
/// hairline cracks in the rasterised picture). Each cell is split along the diagonal from
/// (i + 1, j) to (i, j + 1), as the crate's `triangle_indices`, so that a morphed 2×2 block
/// of a finer ring has the triangles of the coarser cell.
pub fn grid_indices(m: u32, hole: Option<(u32, u32)>) -> Vec<u32> {
    let side = 2 * m + 1;
    let mut indices = Vec::with_capacity((24 * m * m) as usize);
    for j in 0..2 * m {
        for i in 0..2 * m {
            if let Some((dx, dz)) = hole {
                let inside = |c: u32, d: u32| c > m / 2 + d && c + 1 < 3 * m / 2 + d;
                if inside(i, dx) && inside(j, dz) {
                    continue;
                }
            }
            let a = j * side + i;
            let (b, c, d) = (a + 1, a + side, a + side + 1);
            indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }
    indices
}

/// Grid point `index` of a (2m + 1)² grid as (i − m, j − m): cells from the centre.
pub fn grid_point(m: u32, index: u32) -> [f32; 2] {
    let side = 2 * m + 1;
    [
        (index % side) as f32 - m as f32,
        (index / side) as f32 - m as f32,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring leaves out the inside of the finer ring's square (m × m of its cells) less a
    /// border of one cell, for each hole offset: the cells it draws, counted one by one, are
    /// those outside the (m − 2)² square whose lower corner is at (m/2 + 1 + dx, m/2 + 1 + dz).
    #[test]
    fn rings_leave_out_the_finer_square_less_its_border() {
        let m = 8;
        let side = 2 * m + 1;
        let full = grid_indices(m, None).len() / 6;
        assert_eq!(full, (4 * m * m) as usize);
        for (dx, dz) in HOLES {
            let indices = grid_indices(m, Some((dx, dz)));
            assert_eq!(indices.len() / 6 + ((m - 2) * (m - 2)) as usize, full);
            for cell in indices.chunks(6) {
                let (i, j) = (cell[0] % side, cell[0] / side);
                let hole = |c: u32, d: u32| (m / 2 + 1 + d..m / 2 + m - 1 + d).contains(&c);
                assert!(
                    !(hole(i, dx) && hole(j, dz)),
                    "cell ({i}, {j}) drawn in the hole"
                );
            }
        }
    }

    /// Every ring's square holds the next finer ring's square where its hole says, for eyes
    /// anywhere: the finer square (half the side, centred on the finer centre) starts at cell
    /// m/2 + dx, m/2 + dz of this ring (the hole `grid_indices` leaves out).
    #[test]
    fn each_ring_holds_the_finer_one_where_its_hole_is() {
        let m = 32;
        for (x, z, height) in [(0.0, 0.0, 2.0), (13.7, -0.3, 40.0), (-1234.5, 777.7, 600.0)] {
            let mut out = [Ring::default(); MAX_RINGS];
            let count = rings([x, z], height, m, &mut out);
            assert!(count >= 2 && out[count - 1].spacing * m as f32 >= MESH_REACH);
            assert_eq!(out[0].hole, None);
            for r in 1..count {
                let (finer, ring) = (out[r - 1], out[r]);
                assert_eq!(ring.spacing, 2.0 * finer.spacing);
                let (dx, dz) = HOLES[ring.hole.unwrap()];
                // The finer square's lower corner, in this ring's cells from its lower corner.
                let corner = |f: f32, c: f32| {
                    ((f - finer.spacing * m as f32) - (c - ring.spacing * m as f32)) / ring.spacing
                };
                assert_eq!(corner(finer.centre[0], ring.centre[0]), (m / 2 + dx) as f32);
                assert_eq!(corner(finer.centre[1], ring.centre[1]), (m / 2 + dz) as f32);
            }
        }
    }
}
