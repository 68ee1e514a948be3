//! Arc centres from G2/G3 words, with LinuxCNC's checks and tolerances.
//!
//! Work in the arc plane's own coordinates `(a, b)` with normal `n` such that
//! `(a, b, n)` is right-handed: G17 `(X, Y, Z)`, G18 `(Z, X, Y)`, G19 `(Y, Z, X)`.
//! G3 turns counter-clockwise about `n` (positive from `a` toward `b`), G2 clockwise:
//! these are the `rotation` signs of LinuxCNC's canonical `ARC_FEED` in all three
//! planes (checked with `rs274 -g`). The centre offsets are `(I, J)` in G17, `(K, I)` in
//! G18, `(J, K)` in G19, relative to the start (G91.1, the default) or absolute
//! (G90.1); a missing offset word is 0.
//!
//! **Centre format.** With `r1 = |start - c|`, `r2 = |end - c|` (in the plane),
//! `abs_err = |r1 - r2|`, `rel_err = abs_err / max(r1, r2)`, LinuxCNC (2.9, the
//! interpreter installed as `rs274`, `interp_arc.cc: arc_data_ijk`) refuses
//!
//! ```text
//! r1 or r2 < radius_tol                                   (zero-radius arc)
//! abs_err > 100 spiral_tol  or  (rel_err > 0.001 and abs_err > spiral_tol)
//! ```
//!
//! with `radius_tol` = 0.00005 in / 0.00127 mm and `spiral_tol` = `2 sqrt(2)` times the
//! resolution 0.001 in / 0.01 mm (0.0028284 in / 0.028284 mm), all in program units.
//! (LinuxCNC's older documentation quotes 0.0005 in / 0.005 mm and 0.05 in / 0.5 mm;
//! the interpreter as shipped uses the values above, and the tests pin them against
//! `rs274`.) An accepted arc whose radii differ spirals from `r1` to `r2`.
//!
//! **Radius format.** For `R` (positive: at most half a turn, negative: the long way),
//! the centre lies on the perpendicular bisector of the chord of half-length `h` at
//! distance `sqrt(R^2 - h^2)`, to the right of the chord for G2 with `R > 0` (or G3
//! with `R < 0`), to the left otherwise. LinuxCNC (`arc_data_r`) refuses a chord of
//! zero length and `h - |R| > radius_tol`, and treats `h / |R| > 1 - 1e-12` as a
//! half circle.

use std::f64::consts::FRAC_PI_2;
use swarf_geom::Point3;
use swarf_geom::units::MM_PER_INCH;

/// LinuxCNC `RADIUS_TOLERANCE_INCH`: smallest arc radius, and the slack of `R` arcs, in.
pub const RADIUS_TOLERANCE_INCH: f64 = 0.00005;
/// LinuxCNC `RADIUS_TOLERANCE_MM` (the inch value converted), mm.
pub const RADIUS_TOLERANCE_MM: f64 = RADIUS_TOLERANCE_INCH * MM_PER_INCH;
/// LinuxCNC `CENTER_ARC_RADIUS_TOLERANCE_INCH` (`2 sqrt(2) 0.001`), in.
pub const SPIRAL_TOLERANCE_INCH: f64 = 2.0 * 0.001 * std::f64::consts::SQRT_2;
/// LinuxCNC `CENTER_ARC_RADIUS_TOLERANCE_MM` (`2 sqrt(2) 0.01`), mm.
pub const SPIRAL_TOLERANCE_MM: f64 = 2.0 * 0.01 * std::f64::consts::SQRT_2;
/// LinuxCNC `SPIRAL_RELATIVE_TOLERANCE`: radius mismatch relative to the radius.
pub const SPIRAL_RELATIVE_TOLERANCE: f64 = 0.001;
/// LinuxCNC `TINY`: `R` arcs this close to a half circle are half circles.
const HALF_CIRCLE_SLACK: f64 = 1e-12;

/// The plane of G2/G3 arcs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Plane {
    /// G17: XY, normal +Z.
    #[default]
    Xy,
    /// G18: ZX, normal +Y.
    Xz,
    /// G19: YZ, normal +X.
    Yz,
}

impl Plane {
    /// Coordinate indices `[a, b, n]` of the plane's right-handed frame.
    pub fn indices(self) -> [usize; 3] {
        match self {
            Plane::Xy => [0, 1, 2],
            Plane::Xz => [2, 0, 1],
            Plane::Yz => [1, 2, 0],
        }
    }

    /// Axis letters of `a` and `b`.
    pub fn axis_letters(self) -> [char; 2] {
        let [a, b, _] = self.indices();
        [['X', 'Y', 'Z'][a], ['X', 'Y', 'Z'][b]]
    }

    /// Centre-offset letters for `a` and `b`.
    pub fn offset_letters(self) -> [char; 2] {
        let [a, b, _] = self.indices();
        [['I', 'J', 'K'][a], ['I', 'J', 'K'][b]]
    }

    /// The offset letter that does not belong to this plane.
    pub fn foreign_offset(self) -> char {
        ['I', 'J', 'K'][self.indices()[2]]
    }

    /// Name for messages.
    pub fn name(self) -> &'static str {
        match self {
            Plane::Xy => "XY (G17)",
            Plane::Xz => "XZ (G18)",
            Plane::Yz => "YZ (G19)",
        }
    }
}

/// How the block gives the centre, in program units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CenterWords {
    /// `R` word (signed).
    Radius(f64),
    /// Offsets (or absolute centre coordinates) for the plane's `a` and `b` axes.
    Offsets([f64; 2]),
}

/// One G2/G3 block's geometry in program units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcRequest {
    /// Arc plane.
    pub plane: Plane,
    /// G2 rather than G3.
    pub clockwise: bool,
    /// Start point, program units.
    pub start: Point3,
    /// End point, program units.
    pub end: Point3,
    /// Centre words.
    pub center: CenterWords,
    /// G90.1 (absolute centre coordinates) rather than G91.1.
    pub ijk_absolute: bool,
    /// G20 rather than G21 (selects the tolerances).
    pub inch: bool,
}

/// The centre of the arc, in program units, in the plane of the start point.
///
/// # Errors
/// The message LinuxCNC would give (radius mismatch, zero radius, radius too small,
/// start = end for an `R` arc), with values in program units.
pub fn arc_center(req: &ArcRequest) -> Result<Point3, String> {
    let [ia, ib, _] = req.plane.indices();
    let start = [req.start[ia], req.start[ib]];
    let end = [req.end[ia], req.end[ib]];
    let (radius_tol, spiral_tol) = if req.inch {
        (RADIUS_TOLERANCE_INCH, SPIRAL_TOLERANCE_INCH)
    } else {
        (RADIUS_TOLERANCE_MM, SPIRAL_TOLERANCE_MM)
    };
    let c = match req.center {
        CenterWords::Offsets(o) => {
            let c = if req.ijk_absolute {
                o
            } else {
                [start[0] + o[0], start[1] + o[1]]
            };
            check_radii(req, start, c, end, radius_tol, spiral_tol)?;
            c
        }
        CenterWords::Radius(r) => radius_center(req.clockwise, start, end, r, radius_tol)?,
    };
    let mut center = req.start;
    center[ia] = c[0];
    center[ib] = c[1];
    Ok(center)
}

fn check_radii(
    req: &ArcRequest,
    start: [f64; 2],
    c: [f64; 2],
    end: [f64; 2],
    radius_tol: f64,
    spiral_tol: f64,
) -> Result<(), String> {
    let r1 = (start[0] - c[0]).hypot(start[1] - c[1]);
    let r2 = (end[0] - c[0]).hypot(end[1] - c[1]);
    let [la, lb] = req.plane.axis_letters();
    let places = format!(
        "start=({la}{:.4},{lb}{:.4}) center=({la}{:.4},{lb}{:.4}) end=({la}{:.4},{lb}{:.4})",
        start[0], start[1], c[0], c[1], end[0], end[1]
    );
    if r1 < radius_tol || r2 < radius_tol {
        return Err(format!("zero-radius arc: {places} r1={r1:.4} r2={r2:.4}"));
    }
    let abs_err = (r1 - r2).abs();
    let rel_err = abs_err / r1.max(r2);
    if abs_err > 100.0 * spiral_tol || (rel_err > SPIRAL_RELATIVE_TOLERANCE && abs_err > spiral_tol)
    {
        let unit = if req.inch { "in" } else { "mm" };
        return Err(format!(
            "radius to end of arc differs from radius to start: {places} r1={r1:.4} r2={r2:.4} \
             abs_err={abs_err:.4} rel_err={:.4}% (LinuxCNC accepts a difference up to \
             {spiral_tol:.4} {unit}, or up to 0.1% of the radius when that is at most {:.4} {unit})",
            rel_err * 100.0,
            100.0 * spiral_tol
        ));
    }
    Ok(())
}

fn radius_center(
    clockwise: bool,
    start: [f64; 2],
    end: [f64; 2],
    radius: f64,
    radius_tol: f64,
) -> Result<[f64; 2], String> {
    if start == end {
        return Err(
            "R arc whose end point equals its start point in the arc plane: \
                    the centre is undefined (use I/J/K for a full circle)"
                .to_string(),
        );
    }
    let abs_radius = radius.abs();
    let mid = [0.5 * (start[0] + end[0]), 0.5 * (start[1] + end[1])];
    let mut half = (mid[0] - end[0]).hypot(mid[1] - end[1]);
    if half - abs_radius > radius_tol {
        return Err(format!(
            "arc radius too small to reach end point: R{radius:.4}, half the chord is {half:.4}"
        ));
    }
    if half / abs_radius > 1.0 - HALF_CIRCLE_SLACK {
        half = abs_radius;
    }
    let chord_angle = (end[1] - start[1]).atan2(end[0] - start[0]);
    let right = clockwise == (radius > 0.0);
    let theta = if right {
        chord_angle - FRAC_PI_2
    } else {
        chord_angle + FRAC_PI_2
    };
    let offset = abs_radius * (half / abs_radius).asin().cos();
    Ok([mid[0] + offset * theta.cos(), mid[1] + offset * theta.sin()])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn req(plane: Plane, cw: bool, end: Point3, center: CenterWords) -> ArcRequest {
        ArcRequest {
            plane,
            clockwise: cw,
            start: Point3::new(10.0, 0.0, 0.0),
            end,
            center,
            ijk_absolute: false,
            inch: false,
        }
    }

    #[test]
    fn centre_formats_agree() {
        let end = Point3::new(0.0, 0.0, -1.0);
        let ijk = arc_center(&req(
            Plane::Xy,
            true,
            end,
            CenterWords::Offsets([-5.0, 0.0]),
        ));
        assert_eq!(ijk, Ok(Point3::new(5.0, 0.0, 0.0)));
        let r = arc_center(&req(Plane::Xy, true, end, CenterWords::Radius(5.0))).unwrap();
        assert!((r - Point3::new(5.0, 0.0, 0.0)).norm() < 1e-12);
        // rs274: G2 X20 R-5.1 from X10 gives centre (15, 1.0050)
        let long = req(
            Plane::Xy,
            true,
            Point3::new(20.0, 0.0, 0.0),
            CenterWords::Radius(-5.1),
        );
        let c = arc_center(&long).unwrap();
        assert!((c - Point3::new(15.0, (5.1f64 * 5.1 - 25.0).sqrt(), 0.0)).norm() < 1e-12);
    }

    #[test]
    fn linuxcnc_limits() {
        // abs error just under / over 2 sqrt(2) 0.01 mm at r = 5 (rel error 0.56%)
        let ok = req(
            Plane::Xy,
            true,
            Point3::new(-0.0282, 0.0, 0.0),
            CenterWords::Offsets([-5.0, 0.0]),
        );
        assert!(arc_center(&ok).is_ok());
        let bad = req(
            Plane::Xy,
            true,
            Point3::new(-0.0284, 0.0, 0.0),
            CenterWords::Offsets([-5.0, 0.0]),
        );
        let message = arc_center(&bad).unwrap_err();
        assert!(message.contains("r1=5.0000 r2=5.0284"), "{message}");
        // large radius: relative error rules, up to 100 x the absolute limit
        let mut big = req(
            Plane::Xy,
            true,
            Point3::new(-0.4, 0.0, 0.0),
            CenterWords::Offsets([-500.0, 0.0]),
        );
        big.start = Point3::new(1000.0, 0.0, 0.0);
        assert!(arc_center(&big).is_ok());
        big.end = Point3::new(-0.6, 0.0, 0.0);
        assert!(arc_center(&big).is_err());
        let zero = req(
            Plane::Xy,
            true,
            Point3::new(10.0, 0.0, 0.0),
            CenterWords::Offsets([0.0, 0.0]),
        );
        assert!(arc_center(&zero).unwrap_err().starts_with("zero-radius"));
    }

    #[test]
    fn r_arc_errors() {
        let small = req(
            Plane::Xy,
            true,
            Point3::new(0.0, 0.0, 0.0),
            CenterWords::Radius(4.9985),
        );
        assert!(arc_center(&small).unwrap_err().contains("too small"));
        let slack = req(
            Plane::Xy,
            true,
            Point3::new(0.0, 0.0, 0.0),
            CenterWords::Radius(4.999),
        );
        assert!(arc_center(&slack).is_ok());
        let same = req(
            Plane::Xy,
            true,
            Point3::new(10.0, 0.0, -3.0),
            CenterWords::Radius(4.0),
        );
        assert!(arc_center(&same).is_err());
    }

    #[test]
    fn plane_frames_are_right_handed() {
        for plane in [Plane::Xy, Plane::Xz, Plane::Yz] {
            let [a, b, n] = plane.indices();
            let unit = |k: usize| swarf_geom::Vec3::ith(k, 1.0);
            assert_eq!(unit(a).cross(&unit(b)), unit(n));
        }
        assert_eq!(Plane::Xz.offset_letters(), ['K', 'I']);
        assert_eq!(Plane::Yz.axis_letters(), ['Y', 'Z']);
        assert_eq!(Plane::Xy.foreign_offset(), 'K');
    }
}
