//! What the readers produce: a program as a list of motions in the part frame, with
//! the diagnostics found on the way.
//!
//! # Motions
//!
//! Every motion runs from `start` to `end` (poses: tool tip on the axis and unit tool
//! axis). A straight motion (`Rapid`, `Linear`) moves the tip along the segment
//! `start.cl -> end.cl`; when the axes differ (five-axis CL data) the axis turns along
//! the great circle between them, uniformly in the motion parameter (spherical linear
//! interpolation), which is how a control with tool-centre-point management moves a
//! tool between two CL records.
//!
//! An arc (`Arc`) turns about the line through `center` with unit direction `normal`,
//! counter-clockwise (right-handed about `normal`) unless `clockwise`. Writing
//! `u = (start - center)` projected on the plane, `r1 = |u|`, `r2` the same for `end`,
//! and `h = (end - start) . normal`, the tip at parameter `t` in `[0, 1]` is
//!
//! ```text
//! p(t) = center + r(t) (cos(s phi(t)) û + sin(s phi(t)) (n x û)) + t h n
//! r(t) = r1 + t (r2 - r1),   phi(t) = t Θ,   s = +1 (ccw) or -1 (cw)
//! ```
//!
//! where `Θ` is the swept angle: the angle from `start` to `end` in the direction of
//! rotation, in `(0, 2π]` (a full turn `2π` when start and end coincide in the plane),
//! plus `2π (turns - 1)`. With `r1 = r2` this is a circle or a helix, exactly what
//! LinuxCNC's `ARC_FEED` traces. G-code readers admit a small mismatch `r1 != r2`
//! within LinuxCNC's tolerance (see `swarf_nc::read::arc`); the motion then spirals so
//! that it still ends exactly at `end`.

use std::f64::consts::TAU;
use std::fmt;
use swarf_geom::domain::COORDINATE;
use swarf_geom::math::slerp;
use swarf_geom::{Point3, Vec3};
use swarf_tool::{Cutter, Pose};

/// A message about a place in a program: 1-based line and column (in characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// What is wrong, for a user.
    pub message: String,
    /// The file the line is in, when it is not the program itself (a subroutine file).
    pub file: Option<String>,
}

impl Diagnostic {
    /// A diagnostic at `line`, `column` (both 1-based).
    pub fn new(line: usize, column: usize, message: impl Into<String>) -> Self {
        Diagnostic {
            line,
            column,
            message: message.into(),
            file: None,
        }
    }

    /// The same diagnostic in `file` (a subroutine file).
    pub fn in_file(mut self, file: impl Into<String>) -> Self {
        self.file = Some(file.into());
        self
    }

    /// `"source:line:column: message"`, the form compilers and editors understand
    /// (the diagnostic's own file instead of `source` when it has one).
    ///
    /// ```
    /// use swarf_toolpath::Diagnostic;
    /// let d = Diagnostic::new(12, 5, "unknown G code G12");
    /// assert_eq!(d.with_source("part.ngc"), "part.ngc:12:5: unknown G code G12");
    /// let d = d.in_file("subs/hole.ngc");
    /// assert_eq!(d.with_source("part.ngc"), "subs/hole.ngc:12:5: unknown G code G12");
    /// ```
    pub fn with_source(&self, source: &str) -> String {
        format!("{}:{self}", self.file.as_deref().unwrap_or(source))
    }
}

impl fmt::Display for Diagnostic {
    /// `"line:column: message"`; see [`Diagnostic::with_source`] for the full form.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.line, self.column, self.message)
    }
}

/// How a motion moves the tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MotionKind {
    /// Straight positioning at the machine's rapid rate (G0, APT `RAPID`).
    Rapid,
    /// Straight cutting move at the motion's feed (G1, APT `GOTO`, pose CSV rows).
    Linear,
    /// Circular or helical cutting move (G2/G3); see the module documentation.
    Arc {
        /// Centre of the arc, in the plane of the start point (mm).
        center: Point3,
        /// Unit normal of the arc plane: +Z for G17, +Y for G18, +X for G19.
        normal: Vec3,
        /// Clockwise about `normal` (G2) rather than counter-clockwise (G3).
        clockwise: bool,
        /// Turns as the G-code `P` word gives them (1 without `P`): the arc makes
        /// `turns - 1` full circles besides the partial arc from start to end.
        turns: u32,
    },
}

/// One motion of a program, in program order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Straight, rapid or circular.
    pub kind: MotionKind,
    /// Pose where the motion begins (the previous motion's `end`).
    pub start: Pose,
    /// Pose where the motion ends.
    pub end: Pose,
    /// Feed rate of the tool tip over the part, mm/min; 0 for rapids, for cutting
    /// moves whose feed the file does not give (APT CL without `FEDRAT`, pose CSV
    /// without `# feed=`) and for five-axis blocks that turn the tool about its tip
    /// (see `swarf_nc::read::feed`).
    pub feed: f64,
    /// 1-based source line of the block or record that commanded the motion; for a
    /// motion of a subroutine read from another file, the line of the program's call
    /// that led there.
    pub line: usize,
}

impl Motion {
    /// The motions of a planned tool path's `moves`, straight from `start`: rapids
    /// and straight feeds, move `k` on line `k + 1` (a program not yet written).
    pub fn of_moves(moves: &[crate::path::Move], start: Pose) -> Vec<Motion> {
        let mut at = start;
        moves
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let motion = Motion {
                    kind: match m.kind {
                        crate::path::MoveKind::Rapid => MotionKind::Rapid,
                        crate::path::MoveKind::Feed => MotionKind::Linear,
                    },
                    start: at,
                    end: m.to,
                    feed: m.feed,
                    line: k + 1,
                };
                at = m.to;
                motion
            })
            .collect()
    }

    /// The pose at parameter `t` (clamped to `[0, 1]`): `start` at 0, `end` at 1,
    /// uniform in arc angle on arcs and helices, uniform in distance on straight
    /// motions (see the module documentation for the exact formulas).
    ///
    /// # Units
    /// mm; `t` dimensionless.
    pub fn point_at(&self, t: f64) -> Pose {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        if t == 1.0 {
            return self.end;
        }
        match self.kind {
            MotionKind::Rapid | MotionKind::Linear => Pose {
                cl: self.start.cl + (self.end.cl - self.start.cl) * t,
                axis: slerp(&self.start.axis, &self.end.axis, t),
            },
            MotionKind::Arc { .. } => {
                let geometry = self.arc_geometry();
                Pose {
                    cl: geometry.map_or(self.start.cl, |g| g.point(t)),
                    axis: slerp(&self.start.axis, &self.end.axis, t),
                }
            }
        }
    }

    /// Length of the tool tip's path, mm: the chord of straight motions; for arcs
    /// `sqrt((r Θ)^2 + h^2)` with `r` the mean of the start and end radii (exact for
    /// circles and helices; for the slight spirals a G-code tolerance admits, the
    /// error is second order in the radius mismatch).
    ///
    /// # Units
    /// mm.
    pub fn length(&self) -> f64 {
        match self.kind {
            MotionKind::Rapid | MotionKind::Linear => (self.end.cl - self.start.cl).norm(),
            MotionKind::Arc { .. } => self.arc_geometry().map_or(0.0, |g| {
                let r = 0.5 * (g.r1 + g.r2);
                (r * g.sweep).hypot(g.height)
            }),
        }
    }

    /// The angle an arc sweeps, radians: `Θ` of the module documentation (partial
    /// arc plus `2π (turns - 1)`); `None` for straight motions and degenerate arcs.
    ///
    /// ```
    /// use swarf_geom::{Point3, Vec3};
    /// use swarf_toolpath::{Motion, MotionKind};
    /// use swarf_tool::Pose;
    /// let m = Motion {
    ///     kind: MotionKind::Arc { center: Point3::origin(), normal: Vec3::z(), clockwise: true, turns: 1 },
    ///     start: Pose::vertical(Point3::new(1.0, 0.0, 0.0)),
    ///     end: Pose::vertical(Point3::new(0.0, 1.0, 0.0)),
    ///     feed: 100.0,
    ///     line: 1,
    /// };
    /// assert!((m.sweep().unwrap() - 1.5 * std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn sweep(&self) -> Option<f64> {
        self.arc_geometry().map(|g| g.sweep)
    }

    /// The arc's frame and sweep; `None` for straight motions or a degenerate arc
    /// (start on the centre line, non-unit normal).
    fn arc_geometry(&self) -> Option<ArcGeometry> {
        let MotionKind::Arc {
            center,
            normal,
            clockwise,
            turns,
        } = self.kind
        else {
            return None;
        };
        let n = normal.try_normalize(swarf_geom::tol::LENGTH_EPS)?;
        let to_start = self.start.cl - center;
        let to_end = self.end.cl - center;
        let height = (self.end.cl - self.start.cl).dot(&n);
        let u_full = to_start - n * to_start.dot(&n);
        let e = to_end - n * to_end.dot(&n);
        let r1 = u_full.norm();
        if r1 <= swarf_geom::tol::LENGTH_EPS {
            return None;
        }
        let u = u_full / r1;
        let v = n.cross(&u);
        let sense = if clockwise { -1.0 } else { 1.0 };
        let sweep =
            sweep_angle(&u, &v, &e, (e - u_full).norm(), sense) + TAU * f64::from(turns.max(1) - 1);
        Some(ArcGeometry {
            center_in_plane: self.start.cl - u_full,
            u,
            v,
            n,
            r1,
            r2: e.norm(),
            sweep,
            sense,
            height,
        })
    }
}

/// The swept angle in `(0, 2π]` from direction `u` to the in-plane end offset `e` in
/// the sense `sense` (+1 ccw about `n = u x v`, -1 cw); a full turn when the chord
/// between start and end in the plane is zero.
pub(crate) fn sweep_angle(u: &Vec3, v: &Vec3, e: &Vec3, chord: f64, sense: f64) -> f64 {
    if chord <= swarf_geom::tol::LENGTH_EPS {
        return TAU;
    }
    let angle = (sense * e.dot(v)).atan2(e.dot(u));
    if angle <= 0.0 { angle + TAU } else { angle }
}

/// An arc resolved into its frame: `u` towards the start, `v = n x u`.
struct ArcGeometry {
    center_in_plane: Point3,
    u: Vec3,
    v: Vec3,
    n: Vec3,
    r1: f64,
    r2: f64,
    sweep: f64,
    sense: f64,
    height: f64,
}

impl ArcGeometry {
    fn point(&self, t: f64) -> Point3 {
        let phi = self.sense * t * self.sweep;
        let r = self.r1 + t * (self.r2 - self.r1);
        self.center_in_plane
            + (self.u * phi.cos() + self.v * phi.sin()) * r
            + self.n * (t * self.height)
    }
}

/// A program read from G-code, APT CL or pose CSV.
///
/// Reading never fails half-way: when a block or record cannot be understood, the
/// reader stops there, keeps the motions before it and sets [`Program::stopped`], so
/// that a verifier can still report on what was read. Only a file that cannot be read
/// at all is an `Err`.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// Motions in program order, mm and mm/min, part frame.
    pub motions: Vec<Motion>,
    /// Words and records that were read but not simulated (each with line and column).
    pub warnings: Vec<Diagnostic>,
    /// Tool from an APT `CUTTER` record (G-code: `None`, T words only number tools).
    pub tool: Option<Cutter>,
    /// File name, for messages.
    pub source: String,
    /// Set when reading stopped at an error: `motions` hold what came before it.
    pub stopped: Option<Diagnostic>,
    /// What the program says to the operator: `(MSG, ...)` and `(DEBUG, ...)` comments
    /// (parameters expanded), with their lines.
    pub messages: Vec<Diagnostic>,
    /// G-code: each tool the program cuts with (T word and M6), in order, from its
    /// first motion; empty when it loads none.
    pub tools: Vec<ToolUse>,
}

/// A tool a program cuts with from one of its motions on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ToolUse {
    /// Index of the first motion made with it.
    pub first_motion: usize,
    /// Its T number.
    pub number: u32,
    /// The line of that motion.
    pub line: usize,
}

impl Program {
    /// The program cut into one program per tool it cuts with: the motions from each
    /// tool's first to the next tool's (the motions before the first tool go with
    /// it), each named `SOURCE T<n>`; warnings and messages go with the first, a stop
    /// with the last. A program with one tool or none is returned whole.
    pub fn split_by_tool(self) -> Vec<Program> {
        if self.tools.len() < 2 {
            return vec![self];
        }
        let n = self.tools.len();
        let mut out = Vec::with_capacity(n);
        let mut motions = self.motions;
        let (mut warnings, mut messages) = (self.warnings, self.messages);
        let mut stopped = self.stopped;
        let mut rest = Vec::new();
        for k in (0..n).rev() {
            let from = if k == 0 {
                0
            } else {
                self.tools[k].first_motion.min(motions.len())
            };
            let tail = motions.split_off(from);
            rest.push((k, tail));
        }
        rest.reverse();
        for (k, part) in rest {
            let mut p = Program::new(format!("{} T{}", self.source, self.tools[k].number));
            p.motions = part;
            p.tool = self.tool;
            p.tools = vec![ToolUse {
                first_motion: 0,
                ..self.tools[k]
            }];
            if k == 0 {
                p.warnings = std::mem::take(&mut warnings);
                p.messages = std::mem::take(&mut messages);
            }
            if k + 1 == n {
                p.stopped = stopped.take();
            }
            out.push(p);
        }
        out
    }

    /// An empty program read from `source`.
    pub fn new(source: impl Into<String>) -> Self {
        Program {
            motions: Vec::new(),
            warnings: Vec::new(),
            tool: None,
            source: source.into(),
            stopped: None,
            messages: Vec::new(),
            tools: Vec::new(),
        }
    }

    /// Stops the program at its first motion with a point outside the coordinate
    /// domain ([`swarf_geom::domain::COORDINATE`]) or a feed that is not a finite,
    /// non-negative number: the motions from it on are dropped and [`Program::stopped`] names its line
    /// (unless the program stopped earlier). So no length or time computed from a
    /// program is infinite.
    pub fn check_domain(&mut self) {
        let bad = self.motions.iter().enumerate().find_map(|(k, m)| {
            let mut points = vec![("start", m.start.cl), ("end", m.end.cl)];
            if let MotionKind::Arc { center, .. } = m.kind {
                points.push(("arc centre", center));
            }
            let outside = points.into_iter().find_map(|(what, p)| {
                let c = p.coords;
                let worst = c.iter().copied().fold(0.0f64, |a, v| {
                    if v.is_nan() || v.abs() > a.abs() {
                        v
                    } else {
                        a
                    }
                });
                COORDINATE
                    .check(worst)
                    .err()
                    .map(|e| format!("the motion's {what}: {e}"))
            });
            let feed = (!(m.feed.is_finite() && m.feed >= 0.0))
                .then(|| format!("the motion's feed {} is not a finite rate >= 0", m.feed));
            outside.or(feed).map(|why| (k, m.line, why))
        });
        if let Some((k, line, why)) = bad {
            self.motions.truncate(k);
            if self.stopped.is_none() {
                self.stopped = Some(Diagnostic::new(line, 1, why));
            }
        }
    }

    /// `"source:line:column: message"` for one of this program's diagnostics.
    pub fn located(&self, diagnostic: &Diagnostic) -> String {
        diagnostic.with_source(&self.source)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn pose(x: f64, y: f64, z: f64) -> Pose {
        Pose {
            cl: Point3::new(x, y, z),
            axis: Vec3::z(),
        }
    }

    fn arc(start: Pose, end: Pose, center: Point3, clockwise: bool, turns: u32) -> Motion {
        Motion {
            kind: MotionKind::Arc {
                center,
                normal: Vec3::z(),
                clockwise,
                turns,
            },
            start,
            end,
            feed: 100.0,
            line: 1,
        }
    }

    #[test]
    fn quarter_arcs_both_ways() {
        let ccw = arc(
            pose(1.0, 0.0, 0.0),
            pose(0.0, 1.0, 0.0),
            Point3::origin(),
            false,
            1,
        );
        let mid = ccw.point_at(0.5).cl;
        let h = (0.5f64).sqrt();
        assert!((mid - Point3::new(h, h, 0.0)).norm() < 1e-12);
        assert!((ccw.length() - FRAC_PI_2).abs() < 1e-12);
        let cw = arc(
            pose(1.0, 0.0, 0.0),
            pose(0.0, 1.0, 0.0),
            Point3::origin(),
            true,
            1,
        );
        let mid = cw.point_at(0.5).cl;
        assert!((mid - Point3::new(-h, -h, 0.0)).norm() < 1e-12);
        assert!((cw.length() - 3.0 * FRAC_PI_2).abs() < 1e-12);
    }

    #[test]
    fn full_circle_helix_with_turns() {
        let m = arc(
            pose(1.0, 0.0, 0.0),
            pose(1.0, 0.0, -2.0),
            Point3::origin(),
            false,
            2,
        );
        // two full turns, dropping 2 mm
        let expect = (2.0 * TAU).hypot(2.0);
        assert!((m.length() - expect).abs() < 1e-12);
        let q = m.point_at(0.125).cl; // a quarter turn
        assert!((q - Point3::new(0.0, 1.0, -0.25)).norm() < 1e-12);
        assert_eq!(m.point_at(1.0), m.end);
        assert_eq!(m.point_at(0.0).cl, m.start.cl);
    }

    #[test]
    fn straight_motion_and_axis_slerp() {
        let start = Pose {
            cl: Point3::origin(),
            axis: Vec3::z(),
        };
        let end = Pose {
            cl: Point3::new(2.0, 0.0, 0.0),
            axis: Vec3::x(),
        };
        let m = Motion {
            kind: MotionKind::Linear,
            start,
            end,
            feed: 1.0,
            line: 3,
        };
        let p = m.point_at(0.5);
        assert!((p.cl - Point3::new(1.0, 0.0, 0.0)).norm() < 1e-15);
        let s = (0.5f64).sqrt();
        assert!((p.axis - Vec3::new(s, 0.0, s)).norm() < 1e-12);
        assert!((m.length() - 2.0).abs() < 1e-15);
        assert_eq!(m.point_at(-3.0).cl, start.cl);
        assert_eq!(m.point_at(7.0), end);
    }

    #[test]
    fn half_circle_is_pi_r() {
        let m = arc(
            pose(2.0, 0.0, 0.0),
            pose(-2.0, 0.0, 0.0),
            Point3::origin(),
            true,
            1,
        );
        assert!((m.length() - 2.0 * PI).abs() < 1e-12);
        assert!((m.point_at(0.5).cl - Point3::new(0.0, -2.0, 0.0)).norm() < 1e-12);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// Arcs and helices in any orientation: `point_at` stays on the helix, runs
        /// monotonically from start to end, and `length` equals the length of a fine
        /// polyline through `point_at` samples.
        #[test]
        fn helices_are_consistent(
            cx in -50.0..50.0f64, cy in -50.0..50.0f64, cz in -50.0..50.0f64,
            nx in -1.0..1.0f64, ny in -1.0..1.0f64, nz in -1.0..1.0f64,
            radius in 0.1..40.0f64, sweep in 0.05..6.2f64, height in -20.0..20.0f64,
            turns in 1u32..3, clockwise in proptest::prelude::any::<bool>(),
        ) {
            let Some(n) = Vec3::new(nx, ny, nz).try_normalize(1e-3) else { return Ok(()) };
            let u = n.cross(&Vec3::x()).try_normalize(1e-3).unwrap_or_else(|| n.cross(&Vec3::y()).normalize());
            let v = n.cross(&u);
            let center = Point3::new(cx, cy, cz);
            let s = if clockwise { -1.0 } else { 1.0 };
            let total = sweep + TAU * f64::from(turns - 1);
            let at = |phi: f64, h: f64| center + (u * phi.cos() + v * (s * phi).sin()) * radius + n * h;
            let start = Pose { cl: at(0.0, 0.0), axis: Vec3::z() };
            let end = Pose { cl: at(sweep, height), axis: Vec3::z() };
            let m = Motion {
                kind: MotionKind::Arc { center, normal: n, clockwise, turns },
                start, end, feed: 100.0, line: 1,
            };
            proptest::prop_assert!((m.point_at(0.0).cl - start.cl).norm() < 1e-9);
            proptest::prop_assert_eq!(m.point_at(1.0), end);
            let samples = 4000;
            let mut polyline = 0.0;
            let mut prev = start.cl;
            for k in 1..=samples {
                let t = f64::from(k) / f64::from(samples);
                let p = m.point_at(t).cl;
                let expect = at(t * total, t * height);
                proptest::prop_assert!((p - expect).norm() < 1e-8 * (1.0 + radius), "t {}: {:?} vs {:?}", t, p, expect);
                polyline += (p - prev).norm();
                prev = p;
            }
            let exact = (radius * total).hypot(height);
            proptest::prop_assert!((m.length() - exact).abs() < 1e-9 * exact);
            proptest::prop_assert!((polyline - exact).abs() < 1e-5 * exact);
        }
    }

    #[test]
    fn diagnostic_formats() {
        let d = Diagnostic::new(3, 7, "bad");
        assert_eq!(d.to_string(), "3:7: bad");
        let p = Program::new("a.ngc");
        assert_eq!(p.located(&d), "a.ngc:3:7: bad");
    }
}
