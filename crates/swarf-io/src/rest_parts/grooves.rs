//! The two planar groove parts, `v-grooves` and `short-grooves`: exact with a few
//! triangles, one quad per planar face.
//!
//! `v-grooves`: a block x in [0, 140], y in [0, 60] with its top at z = 10 and three
//! V-grooves along y, bottoms at z = 0 on x = 20, 55 and 105, of included angles 60,
//! 90 and 120 degrees. A groove of half-angle `a` is `z = |x - x0| / tan a` below the
//! top, so it is `10 tan a` wide each side at the top (5.774, 10, 17.321): the grooves
//! span [14.23, 25.77], [45, 65] and [87.68, 122.32], with flat top between them and
//! at both ends. The cross-section polyline is extruded along y.
//!
//! `short-grooves`: a block x in [0, 70], y in [0, 60] with its top at z = 0 and four
//! 90-degree V-grooves along x, depth 4 (so 4 wide each side at the top), each closed
//! at both ends by a vertical triangle on a plane x = const: on y = 15, A over
//! x in [10, 30] and B over [31.5, 51.5] (a 1.5 mm web between them); on y = 45, C over
//! [10, 30] and D over [35, 55] (5 mm apart). The top is cut into horizontal bands:
//! in a groove band (y0 +- 4) a rectangle between each two grooves; between bands a
//! strip whose two edges carry the breaks of the bands beside it, triangulated by
//! zipping the two sorted break lists, so no vertex lies inside another edge.

use super::extrude;
use std::f64::consts::{FRAC_PI_3, FRAC_PI_4, FRAC_PI_6};
use swarf_geom::{Point3, TriMesh};

/// Extent of the `v-grooves` block in x and y (mm).
const V_SIZE: [f64; 2] = [140.0, 60.0];
/// Height of the `v-grooves` top, and so the grooves' depth (mm).
const V_TOP: f64 = 10.0;
/// The V-grooves as (x of the bottom line in mm, half of the included angle).
const V_GROOVES: [(f64, f64); 3] = [(20.0, FRAC_PI_6), (55.0, FRAC_PI_4), (105.0, FRAC_PI_3)];

/// Extent of the `short-grooves` block in x and y (mm).
const S_SIZE: [f64; 2] = [70.0, 60.0];
/// Depth of the short grooves, and (90 degrees included) their half-width (mm).
const S_DEPTH: f64 = 4.0;
/// The short grooves in pairs: (y of the pair's bottom line, [x start, x end] of each
/// groove, in increasing x), in increasing y (mm).
const S_PAIRS: [(f64, [[f64; 2]; 2]); 2] = [
    (15.0, [[10.0, 30.0], [31.5, 51.5]]),
    (45.0, [[10.0, 30.0], [35.0, 55.0]]),
];

/// The `v-grooves` mesh: the cross-section extruded along y, one quad per segment.
pub(super) fn v_grooves() -> TriMesh {
    let mut section = vec![[0.0, V_TOP]];
    for (x0, half_angle) in V_GROOVES {
        let w = V_TOP * half_angle.tan();
        section.extend([[x0 - w, V_TOP], [x0, 0.0], [x0 + w, V_TOP]]);
    }
    section.push([V_SIZE[0], V_TOP]);
    extrude(&section, V_SIZE[1], false)
}

/// The `short-grooves` mesh: top bands, groove flanks and end walls.
pub(super) fn short_grooves() -> TriMesh {
    let mut tris = Vec::new();
    let mut below = (0.0, vec![0.0, S_SIZE[0]]);
    for (y0, grooves) in S_PAIRS {
        let (lo, hi) = (y0 - S_DEPTH, y0 + S_DEPTH);
        let mut breaks = vec![0.0];
        breaks.extend(grooves.as_flattened());
        breaks.push(S_SIZE[0]);
        zip_strip(&below.1, below.0, &breaks, lo, &mut tris);
        for cell in breaks.chunks_exact(2) {
            let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
            tris.extend(quad(
                p(cell[0], lo),
                p(cell[1], lo),
                p(cell[1], hi),
                p(cell[0], hi),
            ));
        }
        for [xs, xe] in grooves {
            groove(xs, xe, y0, &mut tris);
        }
        below = (hi, breaks);
    }
    zip_strip(&below.1, below.0, &[0.0, S_SIZE[0]], S_SIZE[1], &mut tris);
    TriMesh::from_triangles(&tris)
}

/// The two flanks and two end walls of the short groove over x in [xs, xe] with its
/// bottom line on y = y0.
fn groove(xs: f64, xe: f64, y0: f64, tris: &mut Vec<[Point3; 3]>) {
    let (lo, hi) = (y0 - S_DEPTH, y0 + S_DEPTH);
    let rim = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let bottom = |x: f64| Point3::new(x, y0, -S_DEPTH);
    tris.extend(quad(rim(xs, lo), rim(xe, lo), bottom(xe), bottom(xs)));
    tris.extend(quad(bottom(xs), bottom(xe), rim(xe, hi), rim(xs, hi)));
    tris.push([rim(xs, lo), bottom(xs), rim(xs, hi)]);
    tris.push([rim(xe, lo), rim(xe, hi), bottom(xe)]);
}

/// The flat strip at z = 0 between y = `yb` (vertices at the increasing `bottom` x
/// values) and y = `yt` > `yb` (at `top`), both lists running between the same two
/// ends: each triangle advances along whichever edge is behind, so every triangle has
/// positive area and they tile the strip.
fn zip_strip(bottom: &[f64], yb: f64, top: &[f64], yt: f64, tris: &mut Vec<[Point3; 3]>) {
    let b = |i: usize| Point3::new(bottom[i], yb, 0.0);
    let t = |j: usize| Point3::new(top[j], yt, 0.0);
    let (m, n) = (bottom.len() - 1, top.len() - 1);
    let (mut i, mut j) = (0, 0);
    while i < m || j < n {
        if j == n || (i < m && bottom[i + 1] <= top[j + 1]) {
            tris.push([b(i), b(i + 1), t(j)]);
            i += 1;
        } else {
            tris.push([b(i), t(j + 1), t(j)]);
            j += 1;
        }
    }
}

/// The quad `a b c d` (counter-clockwise seen from outside) as two triangles.
fn quad(a: Point3, b: Point3, c: Point3, d: Point3) -> [[Point3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}
