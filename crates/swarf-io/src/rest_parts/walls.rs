//! The two planar wall parts, `boss` and `ramp-step`: cross-sections extruded
//! straight, one quad per segment (exact with a few triangles).
//!
//! `boss`: a plate x in [0, 80], y in [0, 140] at z = 0 with four ribs along x, each
//! a trapezoid in y and z: flat top 6 wide at z = 10, both sides at the rib's angle
//! `a` from horizontal, so each side runs `10 / tan a` in y (10, 4.663, 1.763 and 0
//! for 45, 65, 80 and 90 degrees). Rib centre lines at y = 30, 65, 95 and 120: the
//! bases span [17, 43], [57.337, 72.663], [90.237, 99.763] and [117, 123], leaving
//! at least 14.3 of floor between ribs and 17 at both ends. The section runs in
//! increasing y and is extruded along x.
//!
//! `ramp-step`: a block x in [0, 120], y in [0, 40]: plateau z = 20 for x <= 40, a
//! 45-degree wall down to x = 60, floor z = 0 beyond. The section runs in increasing
//! x and is extruded along y.

use super::extrude;

/// Length of the `boss` ribs (the plate's extent in x) and the plate's extent in y
/// (mm).
const BOSS_SIZE: [f64; 2] = [80.0, 140.0];
/// Height of the ribs above the plate (mm).
const RIB_HEIGHT: f64 = 10.0;
/// Half of a rib's flat top (mm).
const RIB_HALF_TOP: f64 = 3.0;
/// The ribs as (y of the centre line in mm, side angle from horizontal in degrees).
const RIBS: [(f64, f64); 4] = [(30.0, 45.0), (65.0, 65.0), (95.0, 80.0), (120.0, 90.0)];

/// Extent of the `ramp-step` block in x and y (mm).
const STEP_SIZE: [f64; 2] = [120.0, 40.0];
/// Height of the plateau (mm); the wall drops it to z = 0 at 45 degrees.
const STEP_HEIGHT: f64 = 20.0;
/// x of the plateau's edge, where the wall starts down (mm).
const STEP_EDGE: f64 = 40.0;

/// The `boss` mesh: plate and ribs, extruded along x.
pub(super) fn boss() -> swarf_geom::TriMesh {
    let mut section = vec![[0.0, 0.0]];
    for (yc, deg) in RIBS {
        let run = side_run(deg);
        let (base, top) = (RIB_HALF_TOP + run, RIB_HALF_TOP);
        section.extend([
            [yc - base, 0.0],
            [yc - top, RIB_HEIGHT],
            [yc + top, RIB_HEIGHT],
            [yc + base, 0.0],
        ]);
    }
    section.push([BOSS_SIZE[1], 0.0]);
    extrude(&section, BOSS_SIZE[0], true)
}

/// The `ramp-step` mesh: plateau, 45-degree wall and floor, extruded along y.
pub(super) fn ramp_step() -> swarf_geom::TriMesh {
    let section = [
        [0.0, STEP_HEIGHT],
        [STEP_EDGE, STEP_HEIGHT],
        [STEP_EDGE + STEP_HEIGHT, 0.0],
        [STEP_SIZE[0], 0.0],
    ];
    extrude(&section, STEP_SIZE[1], false)
}

/// Horizontal run of a rib side at `deg` degrees from horizontal, `10 / tan a`:
/// zero for a vertical side (not the rounding of `cos 90`), exactly 10 at 45.
fn side_run(deg: f64) -> f64 {
    if deg == 90.0 {
        0.0
    } else {
        let a = deg.to_radians();
        RIB_HEIGHT * a.cos() / a.sin()
    }
}
