//! Iso-parametric finishing: CC paths along constant-parameter curves of each patch.
//!
//! Paper 004 (iso-parametric section, after Lo 2000): with u the forward direction,
//! the k-th CC path is `C_k(u) = S(u, v_k)`, from the boundary `v = v_min` (or `v_max`,
//! `start = "max"`; `direction = "v"` swaps the roles of u and v). The next value is
//! `v_{k+1} = v_k + dv_k`, where `dv_k` converts the side step `dl` (scallop limit
//! `h`, normal curvature in the side direction `B = N x T`, [`crate::stepping::side_step`]) into
//! the parameter: moving by `dv` moves the CC point by `S_v dv`, whose component
//! across the path is `(B . S_v) dv`, so `dv_i = dl_i / |B . S_v|` at each sample `i`
//! of the path. The path interval is the minimum over the path (the scallop never
//! exceeds `h` anywhere along it) and, since the curvature changes between paths, the
//! minimum of that and the same figure on the next path (one look-ahead). The last
//! path lies on the far boundary. Each path is sampled by the forward stepper
//! ([`crate::stepping::forward_step`]) at the job's chordal tolerance.
//!
//! Across a convex ridge (the surface rising from one path's CC point toward the
//! next and falling beyond it, [`crate::stepping::side_step`], "Convex ridges") a flat or bull
//! end mill touches with facing corners, and the side step allowed there is the
//! ball step of the corner radius (none for a sharp rim: the side step collapses and
//! the ridge is reported uncovered).
//!
//! The report's predicted scallop is the local model's scallop for the actual
//! interval at every sample of both paths; the side-step range is that of
//! `|B . S_v| dv`. The path on the far boundary is left out when the tools of the one
//! before already leave at most `h` all along it (`IsoSetup::covers`). On a part of several patches each patch is planned in turn and
//! CC points under another patch are skipped ([`crate::envelope`]).

use super::IsoParams;
use super::pass_bound::Feed;
use crate::error::PathError;
use crate::ordering::Row;
use crate::params::{Cutting, ParamDir, StartSide};
use crate::plan::{Plan, PlanReport, Uncovered};
use crate::stepping::forward_step::{Sample, sample_curve};
use crate::stepping::side_step::corners_face;
use crate::strategy::iso::setup::{IsoSetup, SideGeom, fit_interval};
use swarf_geom::{Part, Point3, Vec3};
use swarf_toolpath::Pass;

/// Uniform samples used for the side step of a path with no reachable point.
const FALLBACK_SAMPLES: usize = 33;
/// Smallest parameter interval between paths, relative to the parameter range; a
/// smaller one means the surface is degenerate there.
const MIN_PARAM_STEP_REL: f64 = 1e-9;

/// Distance across the path between two paths at one station.
struct Crossing {
    across: f64,
    allowed: f64,
    scallop: Option<f64>,
}

/// Plans iso-parametric finishing of every patch of `part`.
///
/// # Errors
/// [`PathError::InvalidParameter`] naming `scallop` or `tolerance`
/// when out of range; [`PathError::NoPath`] when no CC point can be reached;
/// [`PathError::Geom`] when the part cannot be tessellated for the gouge check.
pub fn plan(part: &Part, cutting: &Cutting, params: &IsoParams) -> Result<Plan, PathError> {
    let setup = IsoSetup::new(part, params.job(cutting, "iso-parametric"))?;
    let mut rows = Vec::new();
    let mut report = PlanReport::default();
    let mut figures = Figures::default();
    for face in 0..part.patches.len() {
        IsoParam::new(&setup, face).plan(&mut rows, &mut figures, &mut report);
    }
    figures.write(&mut report);
    let mut plan = setup.finish(rows, report)?;
    plan.report.pass_bound = setup.pass_bound(Feed::Param(params.direction));
    Ok(plan)
}

/// Scallop and side-step figures gathered while planning.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Figures {
    pub max_scallop: f64,
    pub min_step: f64,
    pub max_step: f64,
}

impl Default for Figures {
    fn default() -> Self {
        Figures {
            max_scallop: 0.0,
            min_step: f64::INFINITY,
            max_step: 0.0,
        }
    }
}

impl Figures {
    pub fn add_step(&mut self, step: f64, scallop: Option<f64>) {
        self.min_step = self.min_step.min(step);
        self.max_step = self.max_step.max(step);
        self.max_scallop = self.max_scallop.max(scallop.unwrap_or(f64::INFINITY));
    }

    pub fn write(&self, report: &mut PlanReport) {
        if self.min_step.is_finite() {
            report.side_step_range = Some([self.min_step, self.max_step]);
            report.predicted_max_scallop = Some(self.max_scallop);
        }
    }
}

/// Iso-parametric paths on one patch.
struct IsoParam<'s, 'a> {
    setup: &'s IsoSetup<'a>,
    map: crate::cl_curve::ClMap<'a>,
    along_u: bool,
    t_range: [f64; 2],
    s_range: [f64; 2],
}

impl<'s, 'a> IsoParam<'s, 'a> {
    fn new(setup: &'s IsoSetup<'a>, face: usize) -> Self {
        let map = setup.cl_map(face);
        let [du, dv] = map.patch().domain();
        let along_u = setup.params.direction == ParamDir::U;
        let (t_range, s_range) = if along_u { (du, dv) } else { (dv, du) };
        IsoParam {
            setup,
            map,
            along_u,
            t_range,
            s_range,
        }
    }

    fn uv(&self, t: f64, s: f64) -> (f64, f64) {
        if self.along_u { (t, s) } else { (s, t) }
    }

    fn plan(&self, rows: &mut Vec<Row>, figures: &mut Figures, report: &mut PlanReport) {
        let (mut s, end, sign) = match self.setup.params.start {
            StartSide::Min => (self.s_range[0], self.s_range[1], 1.0),
            StartSide::Max => (self.s_range[1], self.s_range[0], -1.0),
        };
        let min_ds = MIN_PARAM_STEP_REL * (self.s_range[1] - self.s_range[0]);
        let mut runs = self.pass(s);
        loop {
            rows.push(to_row(&runs));
            if s == end {
                break;
            }
            let Some((next, next_runs)) = self.next(s, end, sign, &runs, figures) else {
                report.uncovered.push(self.collapsed(s));
                break;
            };
            if (next - s).abs() < min_ds && next != end {
                report.uncovered.push(self.collapsed(s));
                break;
            }
            if next == end && self.setup.covers(&to_row(&runs), &to_row(&next_runs)) {
                break;
            }
            s = next;
            runs = next_runs;
        }
    }

    /// The next path after `s` and its samples: the interval from the first-order
    /// conversion, then fitted so that the distance across the path to the next one
    /// (the chord `S(t, s + ds) - S(t, s)` less its part along the path) meets the
    /// side step allowed at both ends at every sample.
    fn next(
        &self,
        s: f64,
        end: f64,
        sign: f64,
        runs: &[Vec<Sample>],
        figures: &mut Figures,
    ) -> Option<(f64, Vec<Vec<Sample>>)> {
        let clamp = |x: f64| if sign > 0.0 { x.min(end) } else { x.max(end) };
        let stations = self.stations(runs);
        let first = self.param_step(s, &stations)?;
        let ds = fit_interval(first, |ds| {
            self.crossings(&stations, s, clamp(s + sign * ds))
                .map(|c| c.across / c.allowed)
                .fold(0.0, f64::max)
        });
        let next = clamp(s + sign * ds);
        for c in self.crossings(&stations, s, next) {
            figures.add_step(c.across, c.scallop);
        }
        Some((next, self.pass(next)))
    }

    /// Forward-stepped samples of the path at side parameter `s`.
    fn pass(&self, s: f64) -> Vec<Vec<Sample>> {
        let f = |t: f64| {
            let (u, v) = self.uv(t, s);
            self.setup.reachable(&self.map, u, v)
        };
        sample_curve(&f, self.t_range[0], self.t_range[1], &self.setup.step)
    }

    /// Path parameters of the samples, or uniform ones when the path has none.
    fn stations(&self, runs: &[Vec<Sample>]) -> Vec<f64> {
        let mut st: Vec<f64> = runs.iter().flatten().map(|p| p.t).collect();
        if st.is_empty() {
            let [t0, t1] = self.t_range;
            st = (0..FALLBACK_SAMPLES)
                .map(|k| t0 + (t1 - t0) * k as f64 / (FALLBACK_SAMPLES - 1) as f64)
                .collect();
        }
        st
    }

    /// Side geometry, `|B . S_s|` and the unit path tangent at `(t, s)`.
    fn side(&self, t: f64, s: f64) -> Option<(SideGeom, f64, Vec3, Point3)> {
        let (u, v) = self.uv(t, s);
        let d = self.map.patch().derivs(u, v);
        let (st, ss) = if self.along_u {
            (d.du, d.dv)
        } else {
            (d.dv, d.du)
        };
        let g = self.setup.side_at(&d, &st)?;
        let tangent = st.try_normalize(0.0)?;
        let conv = g.side.dot(&ss).abs();
        (conv > 0.0 && conv.is_finite()).then_some((g, conv, tangent, d.point))
    }

    /// First-order parameter interval: the least `dl / |B . S_s|` (module doc).
    fn param_step(&self, s: f64, stations: &[f64]) -> Option<f64> {
        stations
            .iter()
            .filter_map(|&t| self.side(t, s).map(|(g, conv, ..)| g.step / conv))
            .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.min(x))))
    }

    /// Distance across the path from `(t, s0)` to `(t, s1)` at each station, with the
    /// side step allowed there and the scallop predicted for it.
    fn crossings<'x>(
        &'x self,
        stations: &'x [f64],
        s0: f64,
        s1: f64,
    ) -> impl Iterator<Item = Crossing> + 'x {
        stations.iter().filter_map(move |&t| {
            let (g0, _, tangent, p0) = self.side(t, s0)?;
            let (g1, _, _, p1) = self.side(t, s1)?;
            let chord = p1 - p0;
            let across = (chord - tangent * tangent.dot(&chord)).norm();
            let side = &self.setup.side;
            let both = |a: Option<f64>, b: Option<f64>| Some(a?.max(b?));
            if corners_face(&g0.normal, &g1.normal, &chord) {
                return Some(Crossing {
                    across,
                    allowed: side.corner_step(g0.kappa).min(side.corner_step(g1.kappa)),
                    scallop: both(
                        side.corner_scallop(across, g0.kappa),
                        side.corner_scallop(across, g1.kappa),
                    ),
                });
            }
            Some(Crossing {
                across,
                allowed: g0.step.min(g1.step),
                scallop: both(
                    side.scallop(across, g0.kappa, g0.tilt),
                    side.scallop(across, g1.kappa, g1.tilt),
                ),
            })
        })
    }

    fn collapsed(&self, s: f64) -> Uncovered {
        let (name, other) = if self.along_u { ("v", "u") } else { ("u", "v") };
        let end = match self.setup.params.start {
            StartSide::Min => self.s_range[1],
            StartSide::Max => self.s_range[0],
        };
        Uncovered {
            region: format!(
                "patch {}, {name} between {s:.6} and {end:.6} (all {other})",
                self.map.face()
            ),
            reason: if self.setup.side.corner() > 0.0 {
                "the side step collapsed: the patch is degenerate there (no normal or no extent across the paths)".into()
            } else {
                "the side step collapsed: a convex ridge lies between the paths, or the patch is degenerate there; the cutter's sharp rim cuts no ridge between two passes (a ball or bull end mill does)".into()
            },
        }
    }
}

/// The runs of a path as the pieces of one row.
fn to_row(runs: &[Vec<Sample>]) -> Row {
    runs.iter()
        .map(|r| Pass {
            points: r.iter().map(|s| s.point).collect(),
            ..Pass::default()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::TestJob;
    use crate::stepping::side_step::ball_scallop;
    use swarf_geom::Point3;
    use swarf_toolpath::PathPoint;

    fn job(h: f64) -> TestJob<IsoParams> {
        TestJob::new("ball:d=8", IsoParams::new(h))
    }

    fn plan(part: &Part, j: &TestJob<IsoParams>) -> Result<Plan, PathError> {
        super::plan(part, &j.cut, &j.params)
    }

    /// The CC point of the pass at its smallest x (passes alternate direction).
    fn cc(p: &Pass) -> Point3 {
        p.points
            .iter()
            .map(|q: &PathPoint| q.contact.unwrap().point)
            .min_by(|a, b| a.x.total_cmp(&b.x))
            .unwrap()
    }

    #[test]
    fn cylinder_paths_are_spaced_by_the_exact_convex_step() {
        let part = swarf_testkit::parts::cylinder(1.0);
        let h = 0.1;
        let plan = plan(&part, &job(h)).unwrap();
        let passes = &plan.toolpath.passes;
        // Uniform curvature: every interval equals the exact step but the last.
        let step = crate::stepping::side_step::ball_step(4.0, -1.0 / 60.0, h).unwrap();
        let n = (60.0 * 60f64.to_radians() / step).ceil() as usize + 1;
        assert_eq!(passes.len(), n);
        for w in passes.windows(2).take(n - 2) {
            let (a, b) = (cc(&w[0]), cc(&w[1]));
            let arc = 60.0 * 2.0 * ((a - b).norm() / 120.0).asin();
            assert!(
                arc <= step * (1.0 + 1e-4) && arc > step * (1.0 - 1e-3),
                "{arc} vs {step}"
            );
            assert!(ball_scallop(4.0, -1.0 / 60.0, arc).unwrap() <= h * (1.0 + 1e-3));
        }
        let pred = plan.report.predicted_max_scallop.unwrap();
        assert!(pred <= h * (1.0 + 1e-3) && pred > 0.99 * h, "{pred}");
        assert_eq!(plan.report.lifted_points, 0);
        // Zigzag: the second pass runs back.
        assert!(passes[1].points[0].pose.cl.x > passes[1].points.last().unwrap().pose.cl.x);
        // Straight paths along x: two points each (max step 4 mm: about 11).
        assert!(passes[0].points.len() <= 12, "{}", passes[0].points.len());
    }

    #[test]
    fn bad_parameters_name_their_field() {
        let part = swarf_testkit::parts::cylinder(1.0);
        let mut j = job(0.1);
        j.scallop = None;
        let e = plan(&part, &j).unwrap_err().to_string();
        assert!(e.starts_with("scallop"), "{e}");
        j.scallop = Some(5.0);
        let e = plan(&part, &j).unwrap_err().to_string();
        assert!(e.starts_with("scallop"), "{e}");
        let mut j = job(0.1);
        j.finish.tolerance = -1.0;
        let e = plan(&part, &j).unwrap_err().to_string();
        assert!(e.starts_with("tolerance"), "{e}");
    }
}
