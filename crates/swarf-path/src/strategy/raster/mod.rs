//! Raster finishing on a triangle mesh: parallel drop-cutter passes.
//!
//! The iso-planar strategy for meshes (thesis 002 §6.2: parallel planes through the
//! tool offset surface, "the point that has the maximum Z value is used as the final
//! tool location point"). Passes run along the feed direction `d = (cos a, sin a)`
//! (`a` = `angle`) on lines `p . n = c` with side direction
//! `n = (-sin a, cos a)`; each is sampled by exact drop-cutter
//! ([`swarf_tool::drop::MeshDropper`]) adaptively to the tolerance
//! (`raster_pass.rs`).
//!
//! - **Side step**: `stepover` when given, else from `scallop`
//!   ([`crate::stepping::raster_step`]: exact for a ball on a horizontal plane, a conservative
//!   effective radius for the other shapes); with `max_slope`, from the scallop on
//!   every slope up to it ([`crate::stepping::slope_step`]). The side range is divided evenly
//!   so that no step exceeds it.
//! - **Region**: with `boundary = [xmin, ymin, xmax, ymax]` the tool centre stays in
//!   that rectangle; without it the side range is the mesh's extent across the passes
//!   and each pass runs over the mesh's extent along them plus the tool radius, kept
//!   where the cutter touches the mesh: passes are clipped to the contact and split
//!   where the cutter leaves the mesh (holes, separate islands). Both are clipped by
//!   contact.
//! - **Order**: passes from the `start` side; with `zigzag` every other row is cut
//!   backwards, else all run along `+d`. Rows are planned in parallel and collected in
//!   order, so the result does not depend on the thread count.
//! - **Ramp limit**: with `max_ramp`, each pass's CL profile is limited to that
//!   slope ([`crate::ramp`]); the ramp points of every lifted run go to
//!   [`Plan::double_contacts`] marked `ramp`.
//! - **Contacts**: each pose records its CC point and triangle (face = triangle index,
//!   normal = the triangle's upward normal, `uv` NaN). Double contacts found at any
//!   sample go to [`Plan::double_contacts`] (`raster_double.rs`).
//!
//! Report: `side_step_range` is the even spacing used (both ends), and
//! `predicted_max_scallop` the exact scallop it leaves on a horizontal plane, or with
//! `max_slope` the largest over the planes sloping up to it across the passes.

pub(crate) mod double;
pub(crate) mod frame;
pub(crate) mod pass;

use crate::error::PathError;
use crate::params::{
    Cutting, Finish, StartSide, check_angle, check_boundary, check_open_angle, check_scallop,
    check_stepover, require_spacing,
};
use crate::plan::{DoubleContact, Plan, PlanReport};
use crate::ramp::limit_ramp;
use crate::stepping::raster_step::flat_scallop;
use crate::stepping::slope_step::raster_max_scallop;
use crate::strategy::raster::frame::Frame;
use crate::strategy::raster::pass::Sampler;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::TriMesh;
use swarf_geom::domain::{SCALLOP, STEP};
use swarf_tool::Cutter;
use swarf_tool::drop::MeshDropper;
use swarf_toolpath::Pass;

/// First sampling step along a pass, as a fraction of the tool radius.
pub const INIT_STEP_RADII: f64 = 0.25;
/// Smallest refinement step, mm (the tolerance, but not below this).
pub const MIN_STEP_FLOOR: f64 = 1e-3;
/// Contacts this many tool radii apart can make a double contact.
pub const DOUBLE_SEPARATION_RADII: f64 = 0.05;

/// Parameters of the drop-cutter raster.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RasterParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop height limit on a flat floor, mm: the line spacing follows from it
    /// (or give `stepover`).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// Fixed distance between raster lines, mm (wins over `scallop`).
    #[schemars(extend("unit" = "mm", "domain" = STEP.to_string()))]
    pub stepover: Option<f64>,
    /// Feed direction in the XY plane, degrees from +X.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees"))]
    pub angle: f64,
    /// Side the first line is on.
    pub start: StartSide,
    /// Raster boundary `[xmin, ymin, xmax, ymax]`, mm: the tool centre stays inside
    /// (default: the mesh outline).
    #[schemars(extend("unit" = "mm"))]
    pub boundary: Option<[f64; 4]>,
    /// Ramp angle limit, degrees in `(0, 90)`: passes climb and descend no steeper
    /// (thesis 002 §3.1.3, [`crate::ramp`]); the rest it leaves is ramp rest for a
    /// cleanup job. None by default.
    #[serde(with = "swarf_geom::units::serde_degrees_opt")]
    #[schemars(with = "Option<f64>", extend("unit" = "degrees", "domain" = "(0, 90)"))]
    pub max_ramp: Option<f64>,
    /// Steepest slope across the passes on which `scallop` must hold, degrees in
    /// `(0, 90)`: the stepover then keeps the scallop within it on every plane
    /// sloping up to this angle ([`crate::stepping::slope_step::raster_spacing`]).
    /// None by default (a level floor).
    #[serde(with = "swarf_geom::units::serde_degrees_opt")]
    #[schemars(with = "Option<f64>", extend("unit" = "degrees", "domain" = "(0, 90)"))]
    pub max_slope: Option<f64>,
}

impl RasterParams {
    /// Lines `stepover` mm apart along +X over the whole mesh.
    pub fn new(stepover: f64) -> RasterParams {
        RasterParams {
            stepover: Some(stepover),
            ..RasterParams::default()
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a tolerance, scallop,
    /// stepover, angle, boundary, ramp or slope limit out of range; neither a
    /// scallop nor a stepover.
    pub fn validate(&self, tool: &Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        check_scallop(self.scallop, tool)?;
        check_stepover(self.stepover)?;
        require_spacing(self.scallop, self.stepover)?;
        check_angle(self.angle)?;
        check_boundary(self.boundary)?;
        check_open_angle("max_ramp", self.max_ramp, "an angle")?;
        check_open_angle("max_slope", self.max_slope, "a slope")
    }
}

/// The even XY spacing of the passes [`plan`] makes for `params` over `mesh`, mm,
/// without planning them.
///
/// # Errors
/// As [`plan`] for the stepover, the scallop and the slope limit.
pub fn spacing(mesh: &TriMesh, tool: &Cutter, params: &RasterParams) -> Result<f64, PathError> {
    Ok(Frame::new(mesh, tool, params)?.spacing)
}

/// Plans raster passes over `mesh` for `job` (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::NoPath`] for an empty mesh, one without finite triangles, or when the
/// cutter touches the mesh nowhere in the region; [`PathError::InvalidParameter`] for
/// a stepover wider than the tool or a scallop the tool cannot leave.
pub fn plan(mesh: &TriMesh, cutting: &Cutting, params: &RasterParams) -> Result<Plan, PathError> {
    let tool = &cutting.tool;
    if mesh.is_empty() {
        return Err(PathError::NoPath(
            "raster: the mesh has no triangles".into(),
        ));
    }
    let dropper = MeshDropper::new(mesh, tool);
    if dropper.is_empty() {
        return Err(PathError::NoPath(
            "raster: no triangle of the mesh has finite corners".into(),
        ));
    }
    let slope = ramp_slope(params)?;
    let frame = Frame::new(mesh, tool, params)?;
    let sampler = Sampler::new(mesh, &dropper, params.finish.tolerance, true);
    let rows = frame.rows(&sampler);
    let mut passes = Vec::new();
    let mut double_contacts = Vec::new();
    let mut backwards = false;
    for (k_row, row) in rows.into_iter().enumerate() {
        double_contacts.extend(
            row.doubles
                .into_iter()
                .map(|d| DoubleContact { pass: k_row, ..d }),
        );
        if row.pieces.is_empty() {
            continue;
        }
        let mut pieces: Vec<Pass> = row
            .pieces
            .into_iter()
            .map(|mut points| {
                if let Some(k) = slope {
                    let tol = params.finish.tolerance;
                    double_contacts.extend(limit_ramp(&mut points, k, tol, k_row));
                }
                points
            })
            .map(|points| Pass {
                points,
                ..Pass::default()
            })
            .collect();
        if backwards {
            pieces.reverse();
            pieces.iter_mut().for_each(|p| p.points.reverse());
        }
        backwards = params.finish.zigzag && !backwards;
        passes.extend(pieces);
    }
    if passes.is_empty() {
        return Err(PathError::NoPath(format!(
            "raster: the cutter {} touches the mesh nowhere inside the {}",
            tool,
            if params.boundary.is_some() {
                "boundary"
            } else {
                "mesh outline"
            }
        )));
    }
    let report = PlanReport {
        predicted_max_scallop: match params.max_slope {
            Some(slope) => raster_max_scallop(tool, frame.spacing, slope),
            None => flat_scallop(tool, frame.spacing),
        },
        side_step_range: Some([frame.spacing, frame.spacing]),
        ..PlanReport::default()
    };
    Ok(Plan::from_passes(passes, cutting, report, double_contacts))
}

/// `tan` of the ramp angle limit, if any.
///
/// # Errors
/// [`PathError::InvalidParameter`] for an angle outside `(0, pi/2)`.
fn ramp_slope(params: &RasterParams) -> Result<Option<f64>, PathError> {
    match params.max_ramp {
        None => Ok(None),
        Some(a) if a > 0.0 && a < std::f64::consts::FRAC_PI_2 => Ok(Some(a.tan())),
        Some(a) => Err(PathError::InvalidParameter {
            field: "max_ramp".into(),
            message: format!(
                "{} degrees: expected an angle between 0 and 90 degrees",
                swarf_geom::units::shown_degrees(a)
            ),
        }),
    }
}

/// Contact-only crease scans (thesis 002 §5.1 with a reference tool): lines at
/// `angle` (radians from +X) every `spacing` mm across the whole mesh, sampled as
/// raster passes are but without refinement, and the double contacts found where the
/// contact jumps across a valley; `pass` is the line's index. `dropper` is made
/// from `mesh` and the scanning tool. A valley parallel to
/// the lines is only crossed by lines across it: scan in two directions.
///
/// # Errors
/// As [`plan`] (an empty mesh, a spacing outside `(0, tool diameter]`).
pub fn crease_scan(
    mesh: &TriMesh,
    dropper: &MeshDropper,
    angle: f64,
    spacing: f64,
    tolerance: f64,
) -> Result<Vec<DoubleContact>, PathError> {
    let tool = dropper.tool().cutter();
    let params = RasterParams {
        angle,
        finish: Finish {
            tolerance,
            ..Finish::default()
        },
        ..RasterParams::new(spacing)
    };
    if dropper.is_empty() {
        return Err(PathError::NoPath(
            "crease scan: the mesh has no triangle with finite corners".into(),
        ));
    }
    let frame = Frame::new(mesh, tool, &params)?;
    let sampler = Sampler::new(mesh, dropper, tolerance, false);
    Ok(frame
        .rows(&sampler)
        .into_iter()
        .enumerate()
        .flat_map(|(k, row)| {
            row.doubles
                .into_iter()
                .map(move |d| DoubleContact { pass: k, ..d })
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{StartSide, TestJob};
    use swarf_geom::Point3;
    use swarf_tool::drop::triangle_drop;

    /// Raster parameters for the cutter `tool` with the defaults of a job file and
    /// no spacing yet.
    fn raster(tool: &str) -> TestJob<RasterParams> {
        TestJob::new(tool, RasterParams::default())
    }

    fn scallop(tool: &str, h: f64) -> TestJob<RasterParams> {
        let mut j = raster(tool);
        j.scallop = Some(h);
        j
    }

    fn stepover(tool: &str, s: f64) -> TestJob<RasterParams> {
        let mut j = raster(tool);
        j.stepover = Some(s);
        j
    }

    fn plan(mesh: &TriMesh, j: &TestJob<RasterParams>) -> Result<Plan, PathError> {
        super::plan(mesh, &j.cut, &j.params)
    }

    fn grid(nx: usize, ny: usize, step: f64, z: impl Fn(f64, f64) -> f64) -> TriMesh {
        let p = |i: usize, j: usize| {
            let (x, y) = (step * i as f64, step * j as f64);
            Point3::new(x, y, z(x, y))
        };
        let mut soup = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                soup.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                soup.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
            }
        }
        TriMesh::from_triangles(&soup)
    }

    /// Every CL point (drops and staircase corners) against every triangle, without
    /// the index: no triangle reaches above it by more than 1e-9.
    fn assert_gouge_free(mesh: &TriMesh, j: &TestJob<RasterParams>, plan: &Plan) {
        let tool = swarf_tool::drop::DropCutter::new(&j.cut.tool);
        let r = tool.radius();
        for p in plan.toolpath.passes.iter().flat_map(|p| &p.points) {
            let cl = p.pose.cl;
            for t in 0..mesh.len() {
                let tri = mesh.triangle(t);
                let near = tri
                    .iter()
                    .any(|q| (q.x - cl.x).abs() <= r + 1.0 && (q.y - cl.y).abs() <= r + 1.0);
                if near && let Some(c) = triangle_drop(&tool, [cl.x, cl.y], &tri) {
                    assert!(
                        c.z <= cl.z + 1e-9,
                        "{cl:?} gouges triangle {t} by {}",
                        c.z - cl.z
                    );
                }
            }
        }
    }

    #[test]
    fn ball_on_a_plane_steps_evenly_in_zigzag() {
        let mesh = grid(20, 10, 1.0, |x, y| 0.1 * x + 0.05 * y);
        let j = scallop("ball:d=4", 0.05);
        let plan = plan(&mesh, &j).unwrap();
        let s = 2.0 * (0.05f64 * (4.0 - 0.05)).sqrt();
        let [lo, hi] = plan.report.side_step_range.unwrap();
        assert!(lo == hi && lo <= s && lo > 0.9 * s, "{lo} vs {s}");
        assert!((plan.report.predicted_max_scallop.unwrap() - 0.05).abs() < 0.01);
        // Passes along +x at y = 0, lo, 2 lo, ...; zigzag alternates the direction.
        let passes = &plan.toolpath.passes;
        assert_eq!(passes.len(), (10.0 / lo).round() as usize + 1);
        for (k, p) in passes.iter().enumerate() {
            let (a, b) = (p.points[0].pose.cl, p.points.last().unwrap().pose.cl);
            assert!((a.y - k as f64 * lo).abs() < 1e-9 && (b.y - a.y).abs() < 1e-12);
            assert_eq!(b.x > a.x, k % 2 == 0, "pass {k}");
            // On a plane the drop is exact: the ball sits R (1/cos - 1) above it.
            let q = p.points[p.points.len() / 2];
            let n = Vec3::new(-0.1, -0.05, 1.0).normalize();
            let want = 0.1 * q.pose.cl.x + 0.05 * q.pose.cl.y + 2.0 * (1.0 / n.z - 1.0);
            let (x, y) = (q.pose.cl.x, q.pose.cl.y);
            if (2.0..18.0).contains(&x) && (2.0..8.0).contains(&y) {
                assert!(
                    (q.pose.cl.z - want).abs() < 1e-9,
                    "{:?} vs {want}",
                    q.pose.cl
                );
            }
            let c = q.contact.unwrap();
            assert!(c.uv[0].is_nan() && (c.normal - n).norm() < 1e-9);
        }
        assert_gouge_free(&mesh, &j, &plan);
    }

    use swarf_geom::Vec3;

    #[test]
    fn boundary_angle_start_and_one_way() {
        let mesh = grid(20, 20, 1.0, |x, y| (0.3 * x).sin() + 0.2 * y);
        let mut j = stepover("bull:d=6,r=1", 1.5);
        j.angle = 90f64.to_radians();
        j.start = StartSide::Max;
        j.boundary = Some([5.0, 4.0, 12.0, 15.0]);
        j.finish.zigzag = false;
        let plan = plan(&mesh, &j).unwrap();
        let passes = &plan.toolpath.passes;
        assert_eq!(passes.len(), 6);
        let mut last_x = f64::NEG_INFINITY;
        for p in passes {
            let (a, b) = (p.points[0].pose.cl, p.points.last().unwrap().pose.cl);
            // Along +y (angle 90: the side direction n is -x, so the high side of the
            // offsets is x = 5), from x = 5 to x = 12, inside the boundary.
            assert!((a.x - b.x).abs() < 1e-9 && b.y > a.y && a.x > last_x);
            last_x = a.x;
            for q in &p.points {
                let c = q.pose.cl;
                assert!(
                    c.x >= 5.0 - 1e-9
                        && c.x <= 12.0 + 1e-9
                        && c.y >= 4.0 - 1e-9
                        && c.y <= 15.0 + 1e-9
                );
            }
        }
        assert_gouge_free(&mesh, &j, &plan);
    }

    #[test]
    fn passes_split_between_islands_and_refine_at_walls() {
        // Two plateaus 4 mm high with a 6 mm gap: a flat end leaves one, drops off
        // the edge (the contact ends R beyond it) and comes back on the other.
        let mut mesh = grid(5, 4, 2.0, |_, _| 4.0);
        let other = grid(5, 4, 2.0, |_, _| 4.0);
        let shifted = TriMesh::new(
            other
                .vertices
                .iter()
                .map(|p| p + Vec3::new(26.0, 0.0, 0.0))
                .collect(),
            other.triangles.clone(),
        )
        .unwrap();
        mesh.append(&shifted);
        let j = stepover("flat:d=4", 2.0);
        let plan = plan(&mesh, &j).unwrap();
        let rows = plan.toolpath.passes.len();
        assert!(rows >= 8 && rows.is_multiple_of(2), "{rows}");
        for p in &plan.toolpath.passes {
            let xs: Vec<f64> = p.points.iter().map(|q| q.pose.cl.x).collect();
            let (lo, hi) = (
                xs.iter().cloned().fold(f64::MAX, f64::min),
                xs.iter().cloned().fold(f64::MIN, f64::max),
            );
            // Each piece covers one plateau plus up to the radius beyond.
            assert!(hi - lo <= 10.0 + 4.0 + 0.01, "{lo}..{hi}");
            assert!(p.points.iter().all(|q| (q.pose.cl.z - 4.0).abs() < 1e-12));
        }
        assert_gouge_free(&mesh, &j, &plan);
    }

    #[test]
    fn a_wall_gets_a_staircase_and_stays_gouge_free() {
        // Two plates joined by a vertical wall at x = 10, 5 mm high: a flat end of
        // radius 2 jumps from 0 to 5 at x = 8 and climbs it vertically.
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let quad = |a: Point3, b: Point3, c: Point3, d: Point3| [[a, b, c], [a, c, d]];
        let mut soup = Vec::new();
        soup.extend(quad(
            p(0.0, 0.0, 0.0),
            p(10.0, 0.0, 0.0),
            p(10.0, 4.0, 0.0),
            p(0.0, 4.0, 0.0),
        ));
        soup.extend(quad(
            p(10.0, 0.0, 0.0),
            p(10.0, 4.0, 0.0),
            p(10.0, 4.0, 5.0),
            p(10.0, 0.0, 5.0),
        ));
        soup.extend(quad(
            p(10.0, 0.0, 5.0),
            p(20.0, 0.0, 5.0),
            p(20.0, 4.0, 5.0),
            p(10.0, 4.0, 5.0),
        ));
        let mesh = TriMesh::from_triangles(&soup);
        for start in [0.0, 0.013, 0.31] {
            let mut j = stepover("flat:d=4", 1.3);
            j.boundary = Some([start, 0.0, 20.0, 4.0]);
            let plan = plan(&mesh, &j).unwrap();
            for pass in &plan.toolpath.passes {
                for w in pass.points.windows(2) {
                    let (a, b) = (w[0].pose.cl, w[1].pose.cl);
                    // Every move is level or vertical: the path climbs the jump.
                    let level = (a.z - b.z).abs() < 1e-9;
                    let vertical = (a.x - b.x).abs() < 1e-12 && (a.y - b.y).abs() < 1e-12;
                    assert!(level || vertical, "{a:?} -> {b:?}");
                }
            }
            assert_gouge_free(&mesh, &j, &plan);
        }
    }

    #[test]
    fn a_ball_in_a_v_groove_records_double_contacts() {
        let mesh = grid(20, 20, 1.0, |_, y| (y - 10.0).abs());
        let j = stepover("ball:d=6", 1.0);
        let plan = plan(&mesh, &j).unwrap();
        assert!(!plan.double_contacts.is_empty());
        for d in &plan.double_contacts {
            assert!((d.cl.y - 10.0).abs() < 1e-9, "{:?}", d.cl);
            assert!(d.contacts.len() >= 2);
        }
        assert!(
            plan.double_contacts_csv()
                .unwrap()
                .starts_with("x,y,z,cx,cy,cz\n")
        );
        // Passes across the groove find its crease: one double contact each, at its
        // bottom, where the path now goes down to.
        let mut across = stepover("ball:d=6", 2.0);
        across.angle = 90f64.to_radians();
        let cross = super::plan(&mesh, &across.cut, &across.params).unwrap();
        let crossings = cross.toolpath.passes.len();
        assert!(
            cross.double_contacts.len() >= crossings,
            "{} < {crossings}",
            cross.double_contacts.len()
        );
        let bottom = 3.0 * 2f64.sqrt() - 3.0;
        for d in &cross.double_contacts {
            assert!(
                (d.cl.y - 10.0).abs() < 1e-6 && (d.cl.z - bottom).abs() < 1e-6,
                "{:?}",
                d.cl
            );
        }
        for p in &cross.toolpath.passes {
            let low = p
                .points
                .iter()
                .map(|q| q.pose.cl.z)
                .fold(f64::INFINITY, f64::min);
            assert!((low - bottom).abs() < 1e-6, "{low}");
        }
    }

    #[test]
    fn bad_inputs_are_errors() {
        let j = scallop("ball:d=8", 0.1);
        let e = plan(&TriMesh::default(), &j).unwrap_err();
        assert!(e.to_string().contains("no triangles"), "{e}");
        let nan = TriMesh::from_triangles(&[[
            Point3::new(f64::NAN, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ]]);
        assert!(plan(&nan, &j).unwrap_err().to_string().contains("finite"));
        let mesh = grid(4, 4, 1.0, |_, _| 0.0);
        let e = plan(&mesh, &stepover("ball:d=8", 9.0)).unwrap_err();
        assert!(e.to_string().contains("stepover"), "{e}");
        let mut off = stepover("ball:d=8", 1.0);
        off.boundary = Some([100.0, 100.0, 110.0, 110.0]);
        let e = plan(&mesh, &off).unwrap_err();
        assert!(e.to_string().contains("nowhere"), "{e}");
        // A tool much larger than the mesh still plans.
        let big = plan(&mesh, &stepover("flat:d=40", 2.0)).unwrap();
        assert!(
            big.toolpath
                .passes
                .iter()
                .all(|p| p.points.iter().all(|q| q.pose.cl.z == 0.0))
        );
    }

    #[test]
    fn plans_are_identical_for_any_thread_count() {
        let mesh = grid(30, 20, 0.7, |x, y| (0.2 * x).sin() * (0.3 * y).cos() * 3.0);
        let mut j = scallop("bull:d=6,r=1.5", 0.05);
        j.angle = 30f64.to_radians();
        let run = |n: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap();
            pool.install(|| plan(&mesh, &j).unwrap())
        };
        // Debug text compares NaN uv equal, as it should here.
        let text = |p: &Plan| format!("{:?} {:?}", p.toolpath, p.double_contacts);
        assert_eq!(text(&run(1)), text(&run(3)));
    }
}
