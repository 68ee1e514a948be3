//! Sectioning gouge detection (thesis 000 §7.2) against swarf-sim's independent dexel
//! (Z-map) verifier, on two windows of the die experiment (thesis 000 ch. 8: toroidal
//! cutter R = 12.7, r = 6.35 mm, iso-planar passes 60 degrees off X, cross feed 3.5 mm):
//! the passes that come within 12 mm of the middle (-50, -50) and of the corner
//! (-10, -90), each cut down to its contacts within 18 mm of that point (13 passes,
//! 227 poses). The dexel runs the positioned passes as a program (`swarf_sim::verify`,
//! as `swarf verify` does) on 0.5 mm cells, five-axis motions sampled within 0.1 mm.
//!
//! **What is compared.** A cell's dexel height is the lowest of the sampled tool
//! positions over its centre, and `Dexel::last_motion` names the motion that left it
//! there; its depth below the design is compared with the sectioning depth of that
//! motion's two poses (the front curve of the first, the back curve of the second, and
//! the whole tool at both: the check `position` reports). Both sides measure vertically.
//!
//! **Allowance.** The cell size does not enter: the dexel is exact at cell centres. The
//! sampling only leaves the dexel higher than the true swept surface (by at most the
//! 0.1 mm bound; in fact by the cusp between samples about 0.15 mm apart on a torus of
//! radius 6.35 mm, under 1 um), never lower. What sectioning can miss is the depth
//! between its planes, 1 mm apart: where the deepest point is a maximum across the
//! planes, the depth on the nearest plane, `d <= 0.5` mm away, is less by at most
//! `K d^2 / 2`, `K` the vertical curvature of the tool's torus (`1 / r = 0.157` per mm,
//! steepened by the slope of the surface it cuts) plus the design's (under 0.01 per
//! mm): [`ALLOWANCE`] = 0.025 mm allows `K` up to 0.2 per mm. The largest excess
//! measured is 0.012 mm, at the cap of a pass start.
//!
//! **Figures** (dev profile, 2 loaded cores, the two tests in parallel: 19 s).
//! Alpha = 3: sectioning flags 220 of 227 poses, deepest 6.2350 mm; the dexel has
//! 21 949 cells gouged deeper than tolerance + allowance, deepest 6.2351 mm, every one
//! last cut by a motion with a flagged end and under that motion's footprint, none
//! deeper than its motion's sectioning depth + 0.0122 mm; 19 431 of them lie outside
//! the footprints of the motions between unflagged poses (the flagged poses are needed
//! to explain them), and a weak sectioning (planes 8 mm apart, generating curves only)
//! leaves 1 188 cells deeper than its depth + allowance, by up to 2.5 mm. Automatic
//! lead (0.47 to 14.77 degrees): no pose flagged (deepest 0.0087 mm), the dexel's
//! lowest cell 0.0033 mm below the design, 3 074 cells within the tolerance band.
//!
//! At the start of a pass on the part's edge (x = -4.9, corner window) at least one deep
//! cell (0.12 mm) was cut by the cylinder 0.24 mm above the torus, above the wall top
//! where the whole-tool check stops; that pose is flagged deeper on its torus, so the
//! cell is explained here.

use swarf_fiveaxis::CurveOptions;
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::gouge::{GougeOptions, PoseGouge, check_pass, wall_top};
use swarf_fiveaxis::positioning::{Positioning, PositioningReport, mean_direction, position};
use swarf_fiveaxis::sections::Sections;
use swarf_geom::Part;
use swarf_nc::read::{Motion, MotionKind, Program};
use swarf_sim::{Design, Quiet, StockSpec, Verification, VerifyOptions, verify};
use swarf_testkit::die_cc;
use swarf_testkit::parts::die;
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Contact, Pass};

/// The thesis's toroidal cutter.
const CUTTER: &str = "bull:d=38.1,r=6.35";
/// Gouge tolerance, mm (the die jobs').
const TOL: f64 = 0.01;
/// Section plane spacing, mm.
const SECTIONS: f64 = 1.0;
/// Dexel cell, mm.
const CELL: f64 = 0.5;
/// Sampling bound of the dexel's five-axis motions, mm.
const SAMPLE: f64 = 0.1;
/// What sectioning may miss between its planes, mm (module doc).
const ALLOWANCE: f64 = 0.025;
/// Window centres (middle, corner), mm.
const CENTRES: [[f64; 2]; 2] = [[-50.0, -50.0], [-10.0, -90.0]];
/// Passes coming this close to a centre are in its window, mm.
const NEAR: f64 = 12.0;
/// Their contacts this close to the centre are kept, mm.
const CROP: f64 = 18.0;

#[test]
fn every_dexel_gouge_of_a_fixed_lead_is_found_by_sectioning() {
    let (part, cutter, cc) = window();
    let fixed = Positioning::Inclined {
        alpha: 3.0,
        tilt: 0.0,
        sections: SECTIONS,
    };
    let (passes, report) = position(&cutter, &part, &cc, &fixed, TOL).unwrap();
    let per = sectioning(&part, &cutter, &cc, &passes, SECTIONS, true);
    let flagged = agrees_with_report(&per, &report);
    let v = dexel(&part, &cutter, &passes);
    let a = attribute(&v, &cutter, &passes, &per);
    let sect_worst = report.worst_depth;
    let dexel_worst = -v.deviation.summary.min.unwrap();
    println!(
        "alpha = 3: {flagged} of {} poses flagged, deepest {sect_worst:.4} mm; dexel: {} cells \
         deeper than {TOL} + {ALLOWANCE} mm, deepest {dexel_worst:.4} mm; {} last cut by a \
         motion without a flagged end, {} outside a flagged motion's footprint, {} outside \
         the unflagged motions' footprints; largest excess over the motion's sectioning \
         depth {:.4} mm",
        report.poses, a.deep, a.unexplained, a.outside_flagged, a.outside_unflagged, a.excess
    );
    // The window gouges, and not at every pose.
    assert!(a.deep > 5000, "{} deep cells", a.deep);
    assert!(flagged < report.poses);
    // Every deep dexel cell is found by sectioning, at its depth.
    assert_eq!(a.unexplained, 0);
    assert_eq!(a.outside_flagged, 0);
    assert!(a.excess <= ALLOWANCE, "excess {} mm", a.excess);
    assert!(dexel_worst <= sect_worst + ALLOWANCE);
    assert!(
        dexel_worst >= sect_worst - SAMPLE,
        "{dexel_worst} {sect_worst}"
    );
    // Without the flagged poses the gouges are unexplained.
    assert!(a.outside_unflagged > a.deep / 2, "{}", a.outside_unflagged);
    // A weaker sectioning (planes 8 mm apart, generating curves only) misses depth the
    // dexel finds: the comparison can fail.
    let weak = sectioning(&part, &cutter, &cc, &passes, 8.0, false);
    let w = attribute(&v, &cutter, &passes, &weak);
    println!(
        "weak sectioning: {} cells deeper than its depth + {ALLOWANCE} mm, by up to {:.3} mm",
        w.deeper, w.excess
    );
    assert!(
        w.deeper > 100 && w.excess > 1.0,
        "{} {}",
        w.deeper,
        w.excess
    );
}

#[test]
fn the_gouge_free_lead_leaves_no_dexel_gouge() {
    let (part, cutter, cc) = window();
    let auto = Positioning::GougeFree {
        max_alpha: 25.0,
        sections: SECTIONS,
        tilt: 0.0,
        max_rate: 0.5,
        tolerance: None,
    };
    let (passes, report) = position(&cutter, &part, &cc, &auto, TOL).unwrap();
    let per = sectioning(&part, &cutter, &cc, &passes, SECTIONS, true);
    assert_eq!(agrees_with_report(&per, &report), 0);
    assert_eq!(report.gouging_poses, 0);
    let v = dexel(&part, &cutter, &passes);
    let s = &v.deviation.summary;
    let lowest = s.min.unwrap();
    println!(
        "gouge-free: lead {:.2} to {:.2} degrees over {} poses, sectioning deepest {:.4} mm; \
         dexel: {} cells below the design by more than {TOL} mm, lowest deviation {lowest:.4} \
         mm, {} cells within the tolerance band",
        report.alpha_range_deg[0],
        report.alpha_range_deg[1],
        report.poses,
        report.worst_depth,
        s.gouge.cells,
        s.within_cells
    );
    assert!(lowest >= -(TOL + ALLOWANCE), "dexel gouge {lowest} mm");
    // The tool does reach the design (the stock starts 0.5 mm above it): the dexel
    // would see a gouge there.
    assert!(lowest < TOL, "{lowest}");
    assert!(s.within_cells > 1000, "{}", s.within_cells);
}

/// The die, the cutter and the CC paths of the two windows (module doc).
fn window() -> (Part, Cutter, Vec<Vec<Contact>>) {
    let part = die();
    let all = die_cc(&part, CUTTER, 60.0, 3.5, TOL);
    let mut cc = Vec::new();
    for [x, y] in CENTRES {
        let dist = |c: &Contact| (c.point.x - x).hypot(c.point.y - y);
        for pass in &all {
            let near: Vec<Contact> = pass.iter().filter(|c| dist(c) < CROP).copied().collect();
            if near.len() > 1 && near.iter().any(|c| dist(c) < NEAR) {
                cc.push(near);
            }
        }
    }
    (part, CUTTER.parse().unwrap(), cc)
}

/// Per pose, the sectioning check that [`position`] reports with, on planes `spacing`
/// mm apart (`whole_tool` false: generating curves and pass-end caps only).
fn sectioning(
    part: &Part,
    cutter: &Cutter,
    cc: &[Vec<Contact>],
    passes: &[Pass],
    spacing: f64,
    whole_tool: bool,
) -> Vec<Vec<PoseGouge>> {
    let design = DesignSurface::new(part).unwrap();
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let opts = GougeOptions {
        sections: Sections::along(mean_direction(cc), spacing).unwrap(),
        tolerance: TOL,
        curve: CurveOptions::default(),
        cap_meridians: 96,
        whole_tool,
    };
    passes
        .iter()
        .map(|p| {
            let poses: Vec<_> = p.points.iter().map(|q| q.pose).collect();
            check_pass(&design, &table, &poses, &opts)
        })
        .collect()
}

/// The number of flagged poses, checked against the report's count and depth.
fn agrees_with_report(per: &[Vec<PoseGouge>], report: &PositioningReport) -> usize {
    let flagged = per.iter().flatten().filter(|g| g.gouges(TOL)).count();
    let worst = per
        .iter()
        .flatten()
        .map(|g| g.depth)
        .fold(f64::MIN, f64::max);
    assert_eq!(flagged, report.gouging_poses);
    assert!((worst - report.worst_depth).abs() < 1e-12);
    flagged
}

/// The passes as a program, verified on the dexel (module doc).
fn dexel(part: &Part, cutter: &Cutter, passes: &[Pass]) -> Verification {
    let opts = VerifyOptions {
        cell: Some(CELL),
        tol: TOL,
        sample_tol: Some(SAMPLE),
        stock: StockSpec::Offset { allowance: 0.5 },
        ..VerifyOptions::default()
    };
    let (program, _) = program(passes);
    verify(Design::Part(part), &program, cutter, &opts, &Quiet).unwrap()
}

/// One linear motion per pair of consecutive poses, no links between passes (the
/// passes are separate cuts), after a motion that places the tool at the first pose
/// (a program's first motion only places the tool); and per motion, its pass and
/// first pose.
fn program(passes: &[Pass]) -> (Program, Vec<[usize; 2]>) {
    let mut program = Program::new("die windows");
    let first = passes[0].points[0].pose;
    let motion = |start, end, program: &mut Program| {
        let line = program.motions.len() + 1;
        program.motions.push(Motion {
            kind: MotionKind::Linear,
            start,
            end,
            feed: 150.0,
            line,
        });
    };
    motion(first, first, &mut program);
    let mut owner = vec![[0, 0]];
    for (k, pass) in passes.iter().enumerate() {
        for (i, w) in pass.points.windows(2).enumerate() {
            motion(w[0].pose, w[1].pose, &mut program);
            owner.push([k, i]);
        }
    }
    (program, owner)
}

/// How the dexel's deep cells (below the design by more than `TOL + ALLOWANCE`) relate
/// to the sectioning results `per`.
struct Attribution {
    /// Deep cells.
    deep: usize,
    /// Deep cells whose last motion has no flagged end.
    unexplained: usize,
    /// Deep cells outside the footprint of every motion with a flagged end.
    outside_flagged: usize,
    /// Deep cells outside the footprint of every motion between unflagged poses.
    outside_unflagged: usize,
    /// Gouged cells deeper than their motion's sectioning depth + `ALLOWANCE`.
    deeper: usize,
    /// Largest dexel depth less its motion's sectioning depth, over gouged cells, mm.
    excess: f64,
}

/// Attributes every gouged cell of `v` to the motion that last cut it (module doc);
/// a motion's footprint is the XY segment of its tips grown by [`reach`].
fn attribute(
    v: &Verification,
    cutter: &Cutter,
    passes: &[Pass],
    per: &[Vec<PoseGouge>],
) -> Attribution {
    let (_, owner) = program(passes);
    let last = v.stock.last_motion();
    let flagged = |[k, i]: [usize; 2]| per[k][i].gouges(TOL) || per[k][i + 1].gouges(TOL);
    let segments: Vec<([f64; 4], bool, f64)> = owner
        .iter()
        .map(|&[k, i]| {
            let (a, b) = (passes[k].points[i].pose, passes[k].points[i + 1].pose);
            let r = reach(cutter, &a).max(reach(cutter, &b));
            ([a.cl.x, a.cl.y, b.cl.x, b.cl.y], flagged([k, i]), r)
        })
        .collect();
    let mut out = Attribution {
        deep: 0,
        unexplained: 0,
        outside_flagged: 0,
        outside_unflagged: 0,
        deeper: 0,
        excess: f64::NEG_INFINITY,
    };
    for (c, &dev) in v.deviation.values.iter().enumerate() {
        if dev.is_nan() || dev >= -TOL {
            continue;
        }
        let m = last[c] as usize;
        let [k, i] = owner[m];
        let excess = -dev - per[k][i].depth.max(per[k][i + 1].depth);
        out.excess = out.excess.max(excess);
        out.deeper += usize::from(excess > ALLOWANCE);
        if -dev <= TOL + ALLOWANCE {
            continue;
        }
        out.deep += 1;
        out.unexplained += usize::from(!flagged(owner[m]));
        let p = v.grid.centre(c % v.grid.nx, c / v.grid.nx);
        let under = |want: bool| {
            segments
                .iter()
                .any(|(s, f, r)| *f == want && distance(p, s) <= *r)
        };
        out.outside_flagged += usize::from(!under(true));
        out.outside_unflagged += usize::from(!under(false));
    }
    out
}

/// How far from its tip, in XY, the part of the tool that sectioning checks reaches
/// at `pose`: a point `cl + rho u + h a` (`u` a unit vector normal to the axis `a`,
/// `rho <= R + r`, `h` up to the wall top) lies within `rho + h |a_xy|` of the tip.
fn reach(cutter: &Cutter, pose: &Pose) -> f64 {
    let top = wall_top(&cutter.profile(), &CurveOptions::default());
    cutter.radius() + top * pose.axis.xy().norm()
}

/// XY distance from `p` to the segment `[x0, y0, x1, y1]`.
fn distance(p: [f64; 2], s: &[f64; 4]) -> f64 {
    let (dx, dy) = (s[2] - s[0], s[3] - s[1]);
    let (px, py) = (p[0] - s[0], p[1] - s[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        ((px * dx + py * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (px - t * dx).hypot(py - t * dy)
}
