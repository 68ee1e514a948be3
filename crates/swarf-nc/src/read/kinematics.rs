//! Forward kinematics for reading five-axis G-code: what the G-code reader needs to
//! know about a machine to turn its axis positions (`X Y Z` and two rotary words) into
//! part-frame poses of the tool.
//!
//! A five-axis program moves machine axes, not the tool over the part: without
//! tool-centre-point control every block moves all axes linearly from one position to
//! the next (joint interpolation), and the tool tip then runs on a curve over the part.
//! The reader follows that curve through [`Kinematics::path`]: the part-frame poses of
//! the straight move in axis space, subdivided until the straight pieces between them
//! are within a chordal tolerance of the curve; each piece becomes one straight motion
//! (the tool axis turning between poses by spherical interpolation, see
//! [`swarf_toolpath::program`]). The swarf-fiveaxis crate implements this trait for its
//! machine files (`swarf_fiveaxis::machine::reader`); this crate sits below it and sees
//! only the trait.
//!
//! Two properties of serial machines with three linear axes are assumed (both hold for
//! table-table, head-head and table-head chains, since the linear axes translate the
//! head and the rotary axes then turn rigid bodies): with the rotary axes held, the map
//! from `X Y Z` to the tool tip in the part frame is a rigid motion (so a G2/G3 arc
//! without rotary words is an arc over the part, with its centre and plane normal
//! mapped by the same motion, and a straight move a straight motion); and with both
//! rotary axes at 0 the map is a translation, which places the program's start
//! ([`crate::read::GcodeReadOptions::initial`]).

use std::fmt;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// Default chordal tolerance of the motions a five-axis move is split into, mm.
pub const DEFAULT_KINEMATICS_TOL: f64 = 1e-3;

/// A machine axis position as the program gives it: `X`, `Y`, `Z` in mm and the two
/// rotary axes in radians, in the order of [`Kinematics::rotary_letters`].
pub type AxisPosition = [f64; 5];

/// The forward kinematics of a five-axis machine, for the G-code reader (module docs).
///
/// The tool length, pivot lengths and where the part sits are the implementor's: the
/// poses are those of the tool tip (CL point) and the unit tool axis (tip toward
/// shank) in the part frame.
pub trait Kinematics: fmt::Debug {
    /// The G-code letters of the two rotary axes (`A`, `B` or `C`), in the order of
    /// the last two values of an [`AxisPosition`].
    fn rotary_letters(&self) -> [char; 2];

    /// The part-frame pose of the tool at the axis position `axes`.
    ///
    /// # Units
    /// mm and radians in, mm out.
    fn pose(&self, axes: &AxisPosition) -> Pose;

    /// The part-frame poses of the straight move in axis space from `from` to `to`,
    /// `from` excluded and `to` included, subdivided until the tool tip's path is
    /// within `tol` of the straight pieces between consecutive poses (one pose when
    /// the rotary axes do not move).
    ///
    /// # Units
    /// mm and radians; `tol` in mm.
    fn path(&self, from: &AxisPosition, to: &AxisPosition, tol: f64) -> Vec<Pose>;
}

/// An arc's centre and plane normal, given at the axis position `at` in program
/// coordinates, carried into the part frame by the rigid motion that the kinematics
/// apply with the rotary axes held (module docs).
///
/// # Units
/// mm.
pub fn arc_in_part_frame(
    kinematics: &dyn Kinematics,
    at: &AxisPosition,
    center: &Point3,
    normal: &Vec3,
) -> (Point3, Vec3) {
    let moved = |p: Point3| {
        let mut axes = *at;
        axes[..3].copy_from_slice(p.coords.as_slice());
        kinematics.pose(&axes).cl
    };
    let origin = moved(Point3::new(at[0], at[1], at[2]));
    let tip = moved(Point3::new(at[0], at[1], at[2]) + normal);
    let mapped = (tip - origin)
        .try_normalize(swarf_geom::tol::LENGTH_EPS)
        .unwrap_or(*normal);
    (moved(*center), mapped)
}

/// The axis position whose tool tip is at `tip` in the part frame with both rotary
/// axes at 0 (module docs: a translation there).
///
/// # Units
/// mm.
pub fn home_position(kinematics: &dyn Kinematics, tip: &Point3) -> AxisPosition {
    let offset = kinematics.pose(&[0.0; 5]).cl;
    [
        tip.x - offset.x,
        tip.y - offset.y,
        tip.z - offset.z,
        0.0,
        0.0,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::{GcodeReadOptions, MotionKind, Program, parse_gcode};

    /// An A/C tilt-rotary table in closed form: A turns the cradle about X, C the
    /// table about Z, both axes through the machine origin; the part's origin sits at
    /// `origin` on the table. A part point `x` is at `R_A R_C (x + origin)`, so the tip
    /// programmed at `L` is at `R_C^-1 R_A^-1 L - origin` and the tool axis is
    /// `R_C^-1 R_A^-1 Z`. Straight moves are split into equal steps of the axes, their
    /// number doubled until the tip at every step's middle is within `tol` of the chord.
    #[derive(Debug)]
    struct Trunnion {
        origin: Vec3,
    }

    fn rx(t: f64, v: Vec3) -> Vec3 {
        let (s, c) = t.sin_cos();
        Vec3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z)
    }

    fn rz(t: f64, v: Vec3) -> Vec3 {
        let (s, c) = t.sin_cos();
        Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
    }

    fn lerp(a: &AxisPosition, b: &AxisPosition, t: f64) -> AxisPosition {
        let mut j = *a;
        for (i, v) in j.iter_mut().enumerate() {
            *v += (b[i] - a[i]) * t;
        }
        j
    }

    impl Kinematics for Trunnion {
        fn rotary_letters(&self) -> [char; 2] {
            ['A', 'C']
        }

        fn pose(&self, j: &AxisPosition) -> Pose {
            let back = |v: Vec3| rz(-j[4], rx(-j[3], v));
            Pose {
                cl: Point3::from(back(Vec3::new(j[0], j[1], j[2])) - self.origin),
                axis: back(Vec3::z()),
            }
        }

        fn path(&self, a: &AxisPosition, b: &AxisPosition, tol: f64) -> Vec<Pose> {
            let at = |t: f64| self.pose(&lerp(a, b, t)).cl;
            let mut n = 1;
            while n < 4096
                && (1..=n).any(|k| {
                    let (t0, t1) = ((k - 1) as f64 / n as f64, k as f64 / n as f64);
                    (at(0.5 * (t0 + t1)) - (at(t0) + (at(t1) - at(t0)) * 0.5)).norm() > tol
                })
            {
                n *= 2;
            }
            (1..=n)
                .map(|k| self.pose(&lerp(a, b, k as f64 / n as f64)))
                .collect()
        }
    }

    const TABLE: Trunnion = Trunnion {
        origin: Vec3::new(5.0, -3.0, 2.0),
    };

    fn read(text: &str) -> Program {
        let opts = GcodeReadOptions {
            kinematics: Some(&TABLE),
            ..GcodeReadOptions::default()
        };
        parse_gcode(text, "5x.ngc", &opts).unwrap()
    }

    fn deg(d: f64) -> f64 {
        d.to_radians()
    }

    /// The length of the tip's path of the axis move `a -> b`, finely sampled.
    fn true_length(a: &AxisPosition, b: &AxisPosition) -> f64 {
        let n = 20_000;
        let at = |k: usize| TABLE.pose(&lerp(a, b, k as f64 / n as f64)).cl;
        (1..=n).map(|k| (at(k) - at(k - 1)).norm()).sum()
    }

    #[test]
    fn rotary_moves_follow_the_machine() {
        let p = read("G21 G90 G94\nG0 X10 Y0 Z20\nG1 X20 A30 C45 F100\nM30\n");
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        // The start: the tip at the origin with the axes at 0 (home_position).
        assert!((p.motions[0].start.cl - Point3::origin()).norm() < 1e-12);
        let a = [10.0, 0.0, 20.0, 0.0, 0.0];
        let b = [20.0, 0.0, 20.0, deg(30.0), deg(45.0)];
        assert_eq!(p.motions[0].end, TABLE.pose(&a));
        let cut: Vec<_> = p.motions.iter().filter(|m| m.line == 3).collect();
        assert!(cut.len() >= 16, "{}", cut.len());
        for (k, m) in cut.iter().enumerate() {
            assert_eq!(m.kind, MotionKind::Linear);
            let want = TABLE.pose(&lerp(&a, &b, (k + 1) as f64 / cut.len() as f64));
            assert!((m.end.cl - want.cl).norm() < 1e-12);
            assert!((m.end.axis - want.axis).norm() < 1e-12);
        }
        for w in p.motions.windows(2) {
            assert_eq!(w[0].end, w[1].start);
        }
        // G94 with X Y Z moving: the block lasts |dXYZ| / F = 0.1 min.
        let length: f64 = cut.iter().map(|m| m.length()).sum();
        assert!((cut[0].feed - length / 0.1).abs() < 1e-9);
        assert!(cut[0].feed > 100.0);
    }

    #[test]
    fn incremental_rotary_words_in_degrees_whatever_the_units() {
        let p = read("G20 G91 G94 F10\nG1 X1 A10\nA10 C-5\nM30\n");
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        // Where the axes stood before the program is unknown, so is the path of the
        // first block: one motion to its end.
        assert_eq!(p.motions.iter().filter(|m| m.line == 2).count(), 1);
        // The axes start where the tip is at the part's origin: X Y Z = TABLE.origin.
        let want = TABLE.pose(&[5.0 + 25.4, -3.0, 2.0, deg(20.0), deg(-5.0)]);
        let end = p.motions.last().unwrap().end;
        assert!((end.cl - want.cl).norm() < 1e-12);
        assert!((end.axis - want.axis).norm() < 1e-12);
        // The second block turns only: F10 is 10 degrees/min along |(dA, dC)|.
        let turn: Vec<_> = p.motions.iter().filter(|m| m.line == 3).collect();
        let length: f64 = turn.iter().map(|m| m.length()).sum();
        let minutes = 10f64.hypot(5.0) / 10.0;
        assert!((turn[0].feed - length / minutes).abs() < 1e-9);
    }

    #[test]
    fn inverse_time_feeds_are_tip_length_over_block_time() {
        let text = "G21 G90 G93\nG0 X10 Z20\nG1 X20 Y5 A40 C90 F2\nG1 X30 F4\nG0 X0\nM30\n";
        let p = read(text);
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        // Y stays where the start put it (TABLE.origin.y) until the G1.
        let a = [10.0, -3.0, 20.0, 0.0, 0.0];
        let b = [20.0, 5.0, 20.0, deg(40.0), deg(90.0)];
        let cut: Vec<_> = p.motions.iter().filter(|m| m.line == 3).collect();
        let time: f64 = cut.iter().map(|m| m.length() / m.feed).sum();
        assert!((time - 0.5).abs() < 1e-12, "{time}");
        // The feed is that of the true tip path less what the chords, at most 1
        // micrometre off the path, cut short: 8 s^2 / 3c per chord of length c and
        // sagitta s, so 8 n^2 s^2 / 3L for n chords over a path of length L.
        let exact = true_length(&a, &b);
        let n = cut.len() as f64;
        let short = 8.0 * n * n * 1e-6 / (3.0 * exact);
        let got = cut[0].feed / 2.0;
        assert!(
            got <= exact + 1e-9 && got >= exact - short,
            "{got} vs {exact}"
        );
        // A straight block with the rotary axes held: 10 mm in 1/4 minute.
        let last = p.motions.iter().find(|m| m.line == 4).unwrap();
        assert!((last.feed - 40.0).abs() < 1e-9);
        assert_eq!(p.motions.last().unwrap().feed, 0.0);
    }

    #[test]
    fn feed_mode_errors_name_the_line() {
        let stop = |text: &str| {
            let p = read(text);
            let d = p.stopped.expect("stops");
            (d.line, d.column, d.message)
        };
        let (line, column, m) = stop("G21 G93\nG1 X1 A1 F10\nX2\nM30\n");
        assert_eq!((line, column), (3, 1));
        assert!(m.contains("F word missing") && m.contains("G93"), "{m}");
        let (line, column, m) = stop("G21 G93\nG1 X1 F0\nM30\n");
        assert_eq!((line, column), (2, 7));
        assert!(m.contains("F0"), "{m}");
        // G94 sets the feed rate to 0, as rs274 does: F is needed again.
        let (line, _, m) = stop("G21 G93\nG1 X1 F10\nG94\nG1 X2\nM30\n");
        assert_eq!(line, 4);
        assert!(m.contains("zero feed rate"), "{m}");
        let p = read("G21 G93\nG1 X1 F10\nG94 F100 G1 X2\nM30\n");
        assert!(p.stopped.is_none());
        assert_eq!(p.motions.last().unwrap().feed, 100.0);
    }

    #[test]
    fn letters_the_machine_lacks_and_rotary_arcs_are_refused() {
        let p = read("G21 G94 F100\nG1 X1\nG1 X2 B5\nM30\n");
        let d = p.stopped.unwrap();
        assert_eq!((d.line, d.column), (3, 7));
        assert!(
            d.message
                .contains("B: the machine's rotary axes are A and C")
        );
        assert_eq!(p.motions.len(), 1);
        let p = read("G21 G94 F100\nG1 X10\nG2 X0 I-5 C30\nM30\n");
        let d = p.stopped.unwrap();
        assert_eq!((d.line, d.column), (3, 11));
        assert!(d.message.contains("arc"), "{}", d.message);
    }

    #[test]
    fn arcs_with_the_table_tilted_are_arcs_over_the_part() {
        let p = read("G21 G94 F100\nG0 A30 C20\nG0 X10 Y0 Z5\nG3 X0 Y10 I-10 J0\nM30\n");
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        let arc = p.motions.last().unwrap();
        assert!(matches!(arc.kind, MotionKind::Arc { .. }));
        assert_eq!(arc.feed, 100.0);
        for k in 0..=10 {
            // The machine runs the quarter circle about (0, 0, 5); the part-frame arc
            // is its image under the table's rotation.
            let phi = std::f64::consts::FRAC_PI_2 * k as f64 / 10.0;
            let j = [
                10.0 * phi.cos(),
                10.0 * phi.sin(),
                5.0,
                deg(30.0),
                deg(20.0),
            ];
            let want = TABLE.pose(&j);
            let got = arc.point_at(k as f64 / 10.0);
            assert!((got.cl - want.cl).norm() < 1e-9, "{k}: {got:?} vs {want:?}");
            assert!((got.axis - want.axis).norm() < 1e-12);
        }
        assert!((arc.length() - 5.0 * std::f64::consts::PI).abs() < 1e-9);
    }

    #[test]
    fn without_rotary_words_the_machine_changes_only_the_frame() {
        // At A = C = 0 the table only shifts the part: every tip is the program point
        // less the part's origin, and the feeds are the programmed ones.
        let text = "G21 G90 G94 F250\nG0 X1 Y2 Z3\nG1 X4\nG2 X8 I2\nM30\n";
        let plain = parse_gcode(text, "3x.ngc", &GcodeReadOptions::default()).unwrap();
        let five = read(text);
        assert_eq!(plain.motions.len(), five.motions.len());
        for (a, b) in plain.motions.iter().zip(&five.motions) {
            assert!((a.end.cl - (b.end.cl + TABLE.origin)).norm() < 1e-12);
            assert_eq!((a.feed, a.line), (b.feed, b.line));
        }
    }

    #[test]
    fn a_bad_tolerance_is_an_option_error() {
        let opts = GcodeReadOptions {
            kinematics: Some(&TABLE),
            kinematics_tol: 0.0,
            ..GcodeReadOptions::default()
        };
        let e = parse_gcode("G21\nM30\n", "a.ngc", &opts).unwrap_err();
        assert!(e.to_string().contains("kinematics_tol"), "{e}");
    }
}
