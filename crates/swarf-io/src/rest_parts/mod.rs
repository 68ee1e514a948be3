//! Built-in mesh parts for rest-material detection and cleanup (issue 11, item 7)
//! and for steep/shallow classification (issue 12, item 7) and the holder check
//! (issue 19), built in code from their formulas (all mm, z up; `parts/README.md`
//! lists them).
//!
//! Each mesh is the part's upper surface as seen along +z, with the material below:
//! the top, the pocket or groove walls (vertical faces included) and floors, wound
//! counter-clockwise seen from outside the material (normals up on tops and floors,
//! into the pocket or groove on walls). The block's outer sides and bottom are left
//! out. Every vertex is computed directly from the surface formula (never
//! accumulated), so it lies on the analytic surface to rounding; every curved face is
//! cut into as few segments as keep each triangle within [`MESH_PART_CHORD`] of it.
//! Output is deterministic.
//!
//! - `fillet-pocket` (`fillet_pocket.rs`): 100 x 80 block, top z = 20, a pocket with
//!   vertical corner radius 5 and a floor fillet of radius 3. A ball of radius
//!   R > 3 finishing the floor/wall corner leaves rest `(R - 3)(sqrt 2 - 1)` along
//!   the 45-degree bisector (2D: the ball touching wall and floor has its centre
//!   `R sqrt 2` from the sharp corner, its surface `R (sqrt 2 - 1)`; the fillet's
//!   surface is `3 (sqrt 2 - 1)` from it); R = 6: 1.2426 mm. A ball of radius R > 5
//!   cannot enter the vertical corner.
//! - `v-grooves` (`grooves.rs`): 140 x 60 block, top z = 10, three V-grooves
//!   along y of included angles 60, 90 and 120 degrees, depth 10. A ball of radius R
//!   in a V of half-angle `a/2` touches both flanks with its centre `R / sin(a/2)`
//!   above the bottom, so it leaves `R / sin(a/2) - R` at the bottom (thesis 002
//!   §1.1) and touches at height `R / sin(a/2) - R sin(a/2)`; for R = 6 that is 9.0,
//!   4.243 and 1.732 mm, below the groove top (10) on all three.
//! - `short-grooves` (`grooves.rs`): 70 x 60 block, top z = 0, four
//!   90-degree V-grooves of depth 4 along x with vertical end walls, in two pairs
//!   1.5 mm and 5 mm apart. The valley rest of each groove is a strip along its bottom
//!   ending at its end walls, so merging regions at 2 mm joins the first pair but not
//!   the second: 4 regions become 3.
//! - `boss` (`walls.rs`): 80 x 140 plate at z = 0 with four ribs along x, 10 high,
//!   flat tops 6 wide, both sides of rib k at `a_k` = 45, 65, 80 and 90 degrees from
//!   horizontal (centre lines y = 30, 65, 95, 120; at least 14.3 of floor between
//!   ribs, room for a ball d = 10). Wall areas, two sides of 80 x `10 / sin a` each:
//!   3D `1600 / sin a` = 2262.742, 1765.405, 1624.683 and 1600 mm²; projected on XY
//!   `1600 / tan a` = 1600, 746.092, 282.123 and 0 mm² (6400 mm² of steep surface,
//!   2628.215 mm² of it seen from above). A raster along x steps across the walls:
//!   passes `s` apart in y lie `w = s / cos a` apart along a wall, and a ball of
//!   radius R leaves the scallop `R - sqrt(R² - w²/4)` between them. For a ball
//!   d = 10 and h = 0.01 the flat-model step is `s = 2 sqrt(2 R h - h²)` = 0.632,
//!   which leaves 0.020, 0.056 and 0.343 mm on the 45, 65 and 80 degree walls; the
//!   vertical walls are not covered at all (their whole height lies over one y, and
//!   a pass touches a vertical face along one line at most).
//! - `ramp-step` (`walls.rs`): 120 x 40 block, plateau z = 20 for x <= 40, a
//!   45-degree wall down to the floor z = 0 at x = 60, extruded along y: a raster
//!   along x with a ramp limit of 20 degrees (thesis 002 §3.1.3) cannot follow it.
//!   For a ball of radius 5 the limited CL profile leaves the plateau edge where the
//!   ball rolling over it descends at 20 degrees (CL x = 40 + 5 sin 20 = 41.710, tip
//!   z = 15 + 5 cos 20 = 19.698), goes down straight at `tan 20` and lands on the
//!   floor at x = 41.710 + 19.698 / tan 20 = 95.831: the ramp rest spans x in
//!   [40, 95.831] (contacts on the edge and on the floor), lifted most (12.288) at
//!   CL x = 55 + 5 sqrt 2 = 62.071, where the free ball first touches the floor.
//!
//! - `deep-pocket` (`deep_pocket.rs`): 60 x 60 block, top z = 40, a pocket 10 wide
//!   (x in [25, 35]) and 40 long (y in [10, 50]), 40 deep with vertical walls: the
//!   holder and shank check of issue 19 (a tool centred in it clears a holder of
//!   bottom radius >= 5 only with the holder face at or above the top).
//!
//! Segment count: the chord of an arc of radius r over angle t / n sags
//! `r (1 - cos(t / 2n))` from it, so an arc needs the smallest n with that at most the
//! tolerance (`arc_segments`). On a doubly curved patch (the pocket's corner tori)
//! the sags of the two directions add at a quad's centre, so each direction gets half
//! the tolerance.

mod deep_pocket;
mod fillet_pocket;
mod grooves;
mod walls;

use swarf_geom::{Point3, TriMesh};

/// Chord tolerance of the curved built-in mesh parts: every triangle lies within this
/// of the analytic surface.
///
/// # Units
/// mm.
pub const MESH_PART_CHORD: f64 = 0.001;

/// Names of the built-in mesh parts: `"fillet-pocket"`, `"v-grooves"`,
/// `"short-grooves"`, `"boss"`, `"ramp-step"`, `"deep-pocket"`.
pub fn builtin_mesh_names() -> [&'static str; 6] {
    [
        "fillet-pocket",
        "v-grooves",
        "short-grooves",
        "boss",
        "ramp-step",
        "deep-pocket",
    ]
}

/// The built-in mesh part `name` (with or without a `.stl` suffix), built exactly from
/// its formulas; `None` for another name.
///
/// # Units
/// Vertex coordinates in mm.
///
/// # Example
/// ```
/// let m = swarf_io::builtin_mesh("v-grooves.stl").unwrap();
/// assert_eq!(m.len(), 20);
/// assert!(swarf_io::builtin_mesh("bracket").is_none());
/// ```
pub fn builtin_mesh(name: &str) -> Option<TriMesh> {
    match name.strip_suffix(".stl").unwrap_or(name) {
        "fillet-pocket" => Some(fillet_pocket::fillet_pocket()),
        "v-grooves" => Some(grooves::v_grooves()),
        "short-grooves" => Some(grooves::short_grooves()),
        "boss" => Some(walls::boss()),
        "ramp-step" => Some(walls::ramp_step()),
        "deep-pocket" => Some(deep_pocket::deep_pocket()),
        _ => None,
    }
}

/// The cross-section `section` (a polyline of `[across, z]` in increasing `across`)
/// extruded over `[0, length]`, one quad per segment: along x (`across` is y) when
/// `along_x`, else along y (`across` is x). Each quad is wound counter-clockwise seen
/// from above the section (normals up on rising and falling faces alike, into the
/// open side on vertical ones).
fn extrude(section: &[[f64; 2]], length: f64, along_x: bool) -> TriMesh {
    let at = |q: [f64; 2], t: f64| {
        if along_x {
            Point3::new(t, q[0], q[1])
        } else {
            Point3::new(q[0], t, q[1])
        }
    };
    let tris: Vec<[Point3; 3]> = section
        .windows(2)
        .flat_map(|s| {
            let [a, b, c, d] = if along_x {
                [
                    at(s[0], 0.0),
                    at(s[0], length),
                    at(s[1], length),
                    at(s[1], 0.0),
                ]
            } else {
                [
                    at(s[0], 0.0),
                    at(s[1], 0.0),
                    at(s[1], length),
                    at(s[0], length),
                ]
            };
            [[a, b, c], [a, c, d]]
        })
        .collect();
    TriMesh::from_triangles(&tris)
}

/// The fewest segments `n` that keep the chords of an arc of `radius` over `angle`
/// (radians) within `tol` of it: `radius (1 - cos(angle / 2n)) <= tol`.
///
/// # Units
/// `radius` and `tol` in mm.
fn arc_segments(radius: f64, angle: f64, tol: f64) -> usize {
    let sag = |n: usize| radius * (1.0 - (angle / (2.0 * n as f64)).cos());
    let half_step = (1.0 - tol / radius).clamp(-1.0, 1.0).acos();
    let mut n = ((angle / (2.0 * half_step)).ceil() as usize).max(1);
    while sag(n) > tol {
        n += 1;
    }
    while n > 1 && sag(n - 1) <= tol {
        n -= 1;
    }
    n
}

/// `(cos, sin)` of `quadrant * 90 + 90 * j / n` degrees, exact at the quadrant ends
/// (`j = 0` and `j = n`), so that arcs meet straight segments and axis-parallel planes
/// without rounding.
fn quarter_turn(quadrant: usize, j: usize, n: usize) -> [f64; 2] {
    let [c, s] = if j == 0 {
        [1.0, 0.0]
    } else if j >= n {
        [0.0, 1.0]
    } else {
        let t = std::f64::consts::FRAC_PI_2 * j as f64 / n as f64;
        [t.cos(), t.sin()]
    };
    match quadrant % 4 {
        0 => [c, s],
        1 => [-s, c],
        2 => [-c, -s],
        _ => [s, -c],
    }
}

#[cfg(test)]
mod oracles;
#[cfg(test)]
mod tests;
