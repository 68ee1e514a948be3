//! The drop-and-spin claim on a part's valley (paper 003, issue 13): the snug
//! drop-and-spin passes (both bands, at the zone's limit) against the best
//! three-axis pass and inclined single-point positioning along the same edge, each
//! written as APT CL, read back and cut on a dexel stock over the strip along the
//! edge between the outer stations measured ([`swarf_sim::verify()`] with a window;
//! cells of [`CELL`], motions sampled to [`SAMPLE_TOL`]: the tilted sweeps dominate
//! the time).
//!
//! - **Three-axis**: the vertical tool touching both faces, dropped at `T1` of each
//!   station (the dropped tool's first touch of the second face): no vertical tool
//!   comes nearer the edge without gouging it.
//! - **Inclined single-point**: the tool inclined at [`INCLINED_LEAD`] toward the feed
//!   (thesis 000 eq. 7.3, no side tilt) touching one face at the contact nearest the
//!   edge that keeps it clear of the other face, in both bands; the offset is found by
//!   scanning and Illinois on the clearance.
//!
//! The table gives the material left at the edge at three stations (a quarter, half
//! and three quarters along), the passes and the deepest gouge below the design; the
//! ball bound `r (sec b - 1)` (the insert's ball wedged between faces sloping at `b`
//! across the edge) is the least a spun tool can leave. The spun tool's axis stays
//! at the face's slope from its normal (the spin cone), so where its flute binds
//! before the ball limit, an inclined tool whose axis is near the normal (its flat
//! bottom almost in the face's tangent plane, reaching toward the edge) can leave
//! less: the table says which.

use crate::drop_spin::plan_drop_spin;
use crate::error::{Context, Result, bail};
use crate::job::Job;
use crate::strategy::Strategy;
use serde::Serialize;
use swarf_fiveaxis::dsm::ZoneChoice;
use swarf_fiveaxis::dsm::{Dsm, Station};
use swarf_fiveaxis::inclined::{Inclination, inclined_pose};
use swarf_geom::solve::illinois;
use swarf_geom::{Part, Point3, Vec3};
use swarf_path::{Plan, PlanReport};
use swarf_sim::{Design, Quiet, StockSpec, VerifyOptions, verify};
use swarf_tool::Pose;
use swarf_toolpath::{Contact, Pass, PathPoint};

/// Lead angle of the inclined single-point comparison, radians (thesis 000 ch. 8's
/// smaller lead, 3 degrees).
pub const INCLINED_LEAD: f64 = 3.0 * std::f64::consts::PI / 180.0;
/// Dexel cell of the comparison, mm.
pub const CELL: f64 = 0.1;
/// Sampling bound of the simulated motions, mm.
pub const SAMPLE_TOL: f64 = 0.02;
/// Offsets scanned (over two tool radii) for the inclined contact nearest the edge.
const INCLINED_SCAN: usize = 40;

/// One method's figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeRow {
    /// The method.
    pub method: String,
    /// Passes along the edge.
    pub passes: usize,
    /// Material left at the edge at each of the comparison's stations, mm.
    pub left_mm: Vec<f64>,
    /// Deepest gouge below the design in the strip, mm (0 where none beyond the
    /// tolerance).
    pub gouge_mm: f64,
}

/// The comparison on one part.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeComparison {
    /// The part.
    pub part: String,
    /// The tool.
    pub tool: String,
    /// Where the material left is measured, mm along the edge direction.
    pub stations: Vec<f64>,
    /// The ball bound at those stations, mm.
    pub ball_bound_mm: Vec<f64>,
    /// Drop-and-spin, three-axis, inclined single-point.
    pub rows: Vec<EdgeRow>,
}

/// Compares the methods on the valley of `part` with drop-spin job `job` (its zone
/// is taken snug; module doc).
///
/// # Errors
/// As [`plan_drop_spin`]; a station without an edge or a zone; the verification's
/// errors.
pub fn compare_edge(job: &Job, part: &Part) -> Result<EdgeComparison> {
    let mut job = job.clone();
    let mut params = *crate::drop_spin::params_of(&job)?;
    params.zone = ZoneChoice::Snug;
    job.strategy = Strategy::DropSpin(params);
    let snug = plan_drop_spin(&job, part, None)?;
    let a = params.angle;
    let along = Vec3::new(a.cos(), a.sin(), 0.0);
    let dsm = Dsm::new(part, params.faces, &job.tool, along)?;
    let zones: Vec<(f64, f64)> = snug
        .passes
        .zones
        .iter()
        .filter(|z| z.band == 0)
        .filter_map(|z| z.zone.map(|zone| (z.station, zone.t1)))
        .collect();
    let first = zones.first().map_or(0.0, |z| z.0);
    let last = zones.last().map_or(0.0, |z| z.0);
    let at: Vec<Station> = [0.25, 0.5, 0.75]
        .iter()
        .map(|f| dsm.station(first + f * (last - first)))
        .collect::<std::result::Result<_, _>>()?;
    let three = zones
        .iter()
        .map(|&(s, t1)| {
            let st = dsm.station(s)?;
            Ok(dsm.drop_on(0, dsm.footprint(&st, 0, t1))?.pose)
        })
        .collect::<Result<Vec<Pose>>>()?;
    let inclined = [0, 1]
        .into_iter()
        .map(|k| {
            zones
                .iter()
                .map(|&(s, _)| inclined_nearest(&dsm, &dsm.station(s)?, k))
                .collect::<Result<Vec<Pose>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    let passes = |runs: Vec<Vec<Pose>>| -> Vec<Pass> {
        runs.into_iter()
            .map(|poses| Pass {
                points: poses.into_iter().map(PathPoint::new).collect(),
                ..Pass::default()
            })
            .collect()
    };
    let methods = [
        (
            "drop-and-spin, snug (both bands)".to_string(),
            snug.plan.toolpath.passes.clone(),
        ),
        (
            "three-axis, vertical double contact".to_string(),
            passes(vec![three]),
        ),
        (
            format!(
                "inclined single-point, lead {:.0} deg (both bands)",
                INCLINED_LEAD.to_degrees()
            ),
            passes(inclined),
        ),
    ];
    let window = window(&at, job.tool.radius());
    let ball_bound_mm = at
        .iter()
        .map(|st| ball_bound(&dsm, st))
        .collect::<Result<Vec<f64>>>()?;
    let rows = methods
        .into_iter()
        .map(|(method, passes)| measure(&job, part, method, passes, window, &at))
        .collect::<Result<Vec<_>>>()?;
    Ok(EdgeComparison {
        part: part.name.clone(),
        tool: job.tool.to_string(),
        stations: at.iter().map(|s| s.s).collect(),
        ball_bound_mm,
        rows,
    })
}

/// The ball bound `r (sec b - 1)` at `st`, `b` face 0's slope across the edge there.
fn ball_bound(dsm: &Dsm, st: &Station) -> Result<f64> {
    let (r, _) = dsm.insert();
    let n = dsm.drop_on(0, dsm.footprint(st, 0, 0.0))?.normal;
    let b = n.dot(&st.across).abs().atan2(n.z);
    Ok(r * (1.0 / b.cos() - 1.0))
}

/// The inclined tool touching face `k` at the contact nearest `st`'s edge that
/// clears the other face (module doc).
fn inclined_nearest(dsm: &Dsm, st: &Station, k: usize) -> Result<Pose> {
    let radius = dsm.cutter().radius();
    let pose = |w: f64| -> Option<Pose> {
        let xy = dsm.footprint(st, k, -w);
        let h = dsm.surface_at(k, xy)?;
        let contact = Contact {
            point: Point3::new(xy[0], xy[1], h.z),
            normal: h.normal,
            face: dsm.ids()[k],
            uv: h.uv,
        };
        inclined_pose(
            dsm.profile(),
            &contact,
            &st.tangent,
            Inclination::lead(INCLINED_LEAD),
        )
    };
    // Out of reach (farther than a tool radius) counts as clear.
    let gap = |w: f64| {
        pose(w).map_or(f64::NAN, |p| {
            dsm.clearance(1 - k, &p).map_or(radius, |c| c.distance)
        })
    };
    let reach = 2.0 * radius;
    let mut prev = (0.0, gap(0.0));
    if prev.1 >= 0.0 {
        return pose(0.0)
            .with_context(|| format!("station {:.4}: no inclined pose at the edge", st.s));
    }
    for i in 1..=INCLINED_SCAN {
        let w = reach * i as f64 / INCLINED_SCAN as f64;
        let g = gap(w);
        if prev.1 < 0.0 && g >= 0.0 {
            let [_, clear] = illinois(gap, prev.0, w, prev.1, g, 1e-9, 200);
            if let Some(p) = pose(clear.0) {
                return Ok(p);
            }
        }
        if g.is_finite() {
            prev = (w, g);
        }
    }
    bail!(
        "station {:.4}: no inclined contact on face {k} within {reach:.3} mm of the edge clears the other face",
        st.s
    )
}

/// The XY box of the edge points of `at` (the outer ones bound the strip), grown by
/// a tool radius across and a millimetre along.
fn window(at: &[Station], radius: f64) -> [[f64; 2]; 2] {
    let mut b = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];
    for st in at {
        let m = st.across * (radius + 1.0);
        for p in [st.edge + m + st.tangent, st.edge - m - st.tangent] {
            b = [
                [b[0][0].min(p.x), b[0][1].min(p.y)],
                [b[1][0].max(p.x), b[1][1].max(p.y)],
            ];
        }
    }
    b
}

/// `passes` linked as `job` links them, written as APT CL, read back and cut on a
/// box stock over `window`: the material left at the edge points of `at` and the
/// deepest gouge.
fn measure(
    job: &Job,
    part: &Part,
    method: String,
    passes: Vec<Pass>,
    window: [[f64; 2]; 2],
    at: &[Station],
) -> Result<EdgeRow> {
    let n = passes.len();
    let plan = Plan::from_passes(passes, &job.cutting(), PlanReport::default(), Vec::new());
    let tp = &plan.toolpath;
    let text = swarf_nc::write_cl(
        &tp.moves(),
        &tp.feeds,
        &job.tool,
        &part.name,
        job.output.units,
    )?;
    let program = swarf_nc::read::parse_cl(&text, "edge.cl")?;
    let opts = VerifyOptions {
        cell: Some(CELL),
        tol: job.tolerance(),
        stock: StockSpec::Box { top: None },
        sample_tol: Some(SAMPLE_TOL),
        window: Some(window),
        ..VerifyOptions::default()
    };
    let v = verify(Design::Part(part), &program, &job.tool, &opts, &Quiet)?;
    let left_mm = at
        .iter()
        .map(|st| {
            let (i, j) = v.grid.cell_of(st.edge.x, st.edge.y).unwrap_or((0, 0));
            v.stock.height(i, j) - st.edge.z
        })
        .collect();
    Ok(EdgeRow {
        method,
        passes: n,
        left_mm,
        gouge_mm: (-v.deviation.summary.gouge.worst).max(0.0),
    })
}

/// The comparisons as a markdown table.
pub fn edge_markdown(cmp: &[EdgeComparison]) -> String {
    let mut s = String::from(
        "| part | method | passes | left at the edge, mm (three stations) | ball bound, mm | deepest gouge, mm |\n|---|---|---|---|---|---|\n",
    );
    for c in cmp {
        let bound: Vec<String> = c.ball_bound_mm.iter().map(|b| format!("{b:.3}")).collect();
        for r in &c.rows {
            let left: Vec<String> = r.left_mm.iter().map(|l| format!("{l:.3}")).collect();
            s += &format!(
                "| {} | {} | {} | {} | {} | {:.4} |\n",
                c.part,
                r.method,
                r.passes,
                left.join(" / "),
                bound.join(" / "),
                r.gouge_mm
            );
        }
    }
    s
}
