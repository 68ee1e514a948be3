//! Independent oracles for the iso strategies' tests: the true scallop left by a ball
//! tool path, and a brute-force gouge check. Nothing here uses the planners' models or
//! code: the machined surface is the union of the swept balls (capsules around the
//! polyline of ball centres), and the material left at a surface point is where the
//! ray along its normal first enters that union, found by sphere tracing on the
//! distance to the ball centres' paths (the planners intersect rays with capsules in
//! closed form instead).

#![allow(dead_code)]

pub mod moves;
pub mod swept;

use moves::Moves;

use rayon::prelude::*;
use swarf_geom::math::point_segment_distance;
use swarf_geom::{Part, Patch, Point3, Vec3};
use swarf_path::strategy::iso::planar::{self, IsoPlanarParams};
use swarf_path::strategy::iso::{IsoParams, parametric, scallop};
use swarf_path::{Cutting, Finish, PathError, Plan};
use swarf_tool::Cutter;
use swarf_toolpath::Pass;

#[allow(unused_imports)]
pub use swarf_testkit::parts::wave;

/// An iso strategy's parameters.
#[derive(Debug, Clone)]
pub enum Iso {
    /// Iso-parametric.
    Parametric(IsoParams),
    /// Iso-planar.
    Planar(IsoPlanarParams),
    /// Iso-scallop.
    Scallop(IsoParams),
}

impl Iso {
    /// The iso strategy `kind` with the parameters of its strategy `table` (TOML,
    /// without `kind`), checked for `tool`.
    ///
    /// # Errors
    /// The table's or the check's message.
    pub fn parse(kind: &str, table: &str, tool: &Cutter) -> Result<Iso, String> {
        let iso = match kind {
            "iso-parametric" => Iso::Parametric(toml::from_str(table).map_err(|e| e.to_string())?),
            "iso-planar" => Iso::Planar(toml::from_str(table).map_err(|e| e.to_string())?),
            "iso-scallop" => Iso::Scallop(toml::from_str(table).map_err(|e| e.to_string())?),
            other => return Err(format!("not an iso strategy: {other}")),
        };
        iso.validate(tool).map_err(|e| e.to_string())?;
        Ok(iso)
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// The field and what was expected.
    pub fn validate(&self, tool: &Cutter) -> Result<(), PathError> {
        match self {
            Iso::Parametric(p) | Iso::Scallop(p) => p.validate(tool),
            Iso::Planar(p) => p.validate(tool),
        }
    }

    /// The scallop limit.
    pub fn scallop_mut(&mut self) -> &mut Option<f64> {
        match self {
            Iso::Parametric(p) | Iso::Scallop(p) => &mut p.scallop,
            Iso::Planar(p) => &mut p.scallop,
        }
    }

    /// The tolerance and zigzag.
    pub fn finish_mut(&mut self) -> &mut Finish {
        match self {
            Iso::Parametric(p) | Iso::Scallop(p) => &mut p.finish,
            Iso::Planar(p) => &mut p.finish,
        }
    }
}

/// An iso strategy with the cutting it is planned with.
#[derive(Debug, Clone)]
pub struct IsoJob {
    /// The cutter.
    pub tool: Cutter,
    /// Tool, feeds (300 mm/min, 1500 rev/min), linking.
    pub cut: Cutting,
    /// The strategy.
    pub iso: Iso,
}

impl IsoJob {
    /// Plans the strategy on `part`.
    ///
    /// # Errors
    /// The strategy's.
    pub fn plan(&self, part: &Part) -> Result<Plan, PathError> {
        match &self.iso {
            Iso::Parametric(p) => parametric::plan(part, &self.cut, p),
            Iso::Planar(p) => planar::plan(part, &self.cut, p),
            Iso::Scallop(p) => scallop::plan(part, &self.cut, p),
        }
    }
}

/// The iso strategy `kind` with `tool` (a spec) and the strategy `table`.
pub fn iso_job(kind: &str, tool: &str, table: &str) -> IsoJob {
    let tool: Cutter = tool.parse().expect("a cutter spec");
    let iso = Iso::parse(kind, table, &tool).expect("a good strategy table");
    IsoJob {
        tool,
        cut: Cutting::new(tool),
        iso,
    }
}

/// A job on wave for `kind` with scallop `h` and tolerance `tol`, ball d = 8.
pub fn wave_job(kind: &str, h: f64, tol: f64) -> IsoJob {
    iso_job(
        kind,
        "ball:d=8",
        &format!("scallop = {h}\ntolerance = {tol}\n"),
    )
}

/// How far along the normal the oracle looks for the tool, in ball radii: material
/// thicker than the tool's diameter counts as never cut.
const RAY_REACH_RADII: f64 = 2.0;
/// Sphere tracing stops this close to the swept balls, mm.
const TRACE_TOL: f64 = 1e-10;
/// Most sphere-tracing steps of one ray (a ray grazing a ball advances slowly).
const TRACE_STEPS: usize = 100_000;

/// The paths of the ball centres.
pub struct Envelope {
    r: f64,
    moves: Moves,
}

impl Envelope {
    /// The swept envelope of the cutting moves of `plan` for a ball of radius `r`.
    pub fn new(plan: &Plan, r: f64) -> Envelope {
        Envelope {
            r,
            moves: Moves::new(plan, r),
        }
    }

    /// Material left above surface point `p` along its unit normal `n`: the distance
    /// to the first swept ball the ray `p + t n` enters (0 when `p` is inside one;
    /// `f64::INFINITY` when the ray leaves the tool's reach without entering one).
    ///
    /// Sphere tracing: the distance from a point to the union of the swept balls,
    /// `gap(q) = min_k |q - move_k| - r`, changes by at most the step along the ray, so
    /// stepping `t` by `gap(p + t n)` never passes the first entry and converges to it.
    pub fn residual(&self, p: &Point3, n: &Vec3) -> f64 {
        let reach = RAY_REACH_RADII * self.r;
        let end = p + reach * n;
        let lo = [p.x.min(end.x), p.y.min(end.y)];
        let hi = [p.x.max(end.x), p.y.max(end.y)];
        let mut near = Vec::new();
        self.moves
            .for_each_near(lo, hi, self.r, &mut |k| near.push(self.moves.segs[k]));
        if near.is_empty() {
            return f64::INFINITY;
        }
        let gap = |t: f64| {
            let q = p + t * n;
            near.iter()
                .map(|(a, b)| point_segment_distance(&q, a, b))
                .fold(f64::INFINITY, f64::min)
                - self.r
        };
        let mut t = 0.0;
        for _ in 0..TRACE_STEPS {
            let d = gap(t);
            if d <= TRACE_TOL {
                return t;
            }
            t += d;
            if t > reach {
                return f64::INFINITY;
            }
        }
        t
    }
}

/// Scallop crests between adjacent passes: for each station (every `spacing` mm
/// along the CC polyline of pass `k`), the nearest point of pass `k + 1` (skipped when
/// it is an end of that pass or farther than `max_gap`), and the largest residual on
/// the surface between them (`samples` points, projected onto the patch).
pub struct Crests {
    /// Crest heights, mm.
    pub heights: Vec<f64>,
    /// Area each crest stands for (station spacing x distance between the passes), mm^2.
    pub weights: Vec<f64>,
    /// The station and the nearest point of the next pass each crest lies between.
    pub between: Vec<(Point3, Point3)>,
}

impl Crests {
    /// Largest crest.
    pub fn max(&self) -> f64 {
        self.heights.iter().copied().fold(0.0, f64::max)
    }

    /// Smallest crest.
    pub fn min(&self) -> f64 {
        self.heights.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Area-weighted mean crest.
    pub fn mean(&self) -> f64 {
        let w: f64 = self.weights.iter().sum();
        self.heights
            .iter()
            .zip(&self.weights)
            .map(|(h, w)| h * w)
            .sum::<f64>()
            / w
    }

    /// Fraction of the area whose crest is within `[lo, hi]`.
    pub fn fraction_within(&self, lo: f64, hi: f64) -> f64 {
        let w: f64 = self.weights.iter().sum();
        let inside: f64 = self
            .heights
            .iter()
            .zip(&self.weights)
            .filter(|(h, _)| (lo..=hi).contains(*h))
            .map(|(_, w)| w)
            .sum();
        inside / w
    }
}

/// The CC polyline (point, uv) of a pass.
fn cc_line(pass: &Pass) -> Vec<(Point3, [f64; 2])> {
    pass.points
        .iter()
        .filter_map(|p| p.contact.map(|c| (c.point, c.uv)))
        .collect()
}

/// Crests of a single-patch plan of a ball of radius `r` (module doc).
pub fn crests(
    plan: &Plan,
    patch: &Patch,
    r: f64,
    spacing: f64,
    samples: usize,
    max_gap: f64,
) -> Crests {
    let env = Envelope::new(plan, r);
    crests_by(
        plan,
        patch,
        &|p, n| env.residual(p, n),
        spacing,
        samples,
        max_gap,
    )
}

/// One crest: height, area it stands for, the two points it lies between.
type Crest = (f64, f64, (Point3, Point3));

/// Golden-section steps refining the largest sample of a crest.
const CREST_STEPS: usize = 16;

/// Crests of a single-patch plan with the material left measured by `residual` (at a
/// surface point along its unit normal): the largest of `samples + 1` points across
/// the gap, refined by golden-section search between the neighbours of the largest
/// (the crest is a sharp ridge that may lie between samples).
pub fn crests_by(
    plan: &Plan,
    patch: &Patch,
    residual: &(dyn Fn(&Point3, &Vec3) -> f64 + Sync),
    spacing: f64,
    samples: usize,
    max_gap: f64,
) -> Crests {
    let lines: Vec<_> = plan.toolpath.passes.iter().map(cc_line).collect();
    let per_pair: Vec<Vec<Crest>> = (0..lines.len().saturating_sub(1))
        .into_par_iter()
        .map(|k| {
            let (a, b) = (&lines[k], &lines[k + 1]);
            if b.len() < 2 {
                return Vec::new();
            }
            stations(a, spacing)
                .into_iter()
                .filter_map(|(p, uv)| {
                    let (q, quv, gap) = nearest_interior(&p, b)?;
                    if gap > max_gap {
                        return None;
                    }
                    let at = |t: f64| {
                        let x = p + t * (q - p);
                        let pr = patch.project_from(
                            &x,
                            uv[0] + t * (quv[0] - uv[0]),
                            uv[1] + t * (quv[1] - uv[1]),
                        );
                        let d = patch.derivs(pr.u, pr.v);
                        let n = d.du.cross(&d.dv).normalize();
                        residual(&pr.point, &if n.z < 0.0 { -n } else { n })
                    };
                    Some((crest_max(&at, samples), spacing * gap, (p, q)))
                })
                .collect()
        })
        .collect();
    let mut out = Crests {
        heights: Vec::new(),
        weights: Vec::new(),
        between: Vec::new(),
    };
    for (h, w, b) in per_pair.into_iter().flatten() {
        out.heights.push(h);
        out.weights.push(w);
        out.between.push(b);
    }
    out
}

/// Largest of `f` over `[0, 1]`: `samples + 1` samples, the largest refined.
fn crest_max(f: &impl Fn(f64) -> f64, samples: usize) -> f64 {
    let ts: Vec<f64> = (0..=samples).map(|s| s as f64 / samples as f64).collect();
    let vals: Vec<f64> = ts.iter().map(|&t| f(t)).collect();
    let Some(best) = (0..vals.len()).max_by(|&i, &j| vals[i].total_cmp(&vals[j])) else {
        return 0.0;
    };
    let (a, b) = (ts[best.saturating_sub(1)], ts[(best + 1).min(samples)]);
    let neg = |t: f64| -f(t);
    let (a, b) = swept::golden_min(&neg, a, b, CREST_STEPS);
    vals[best].max(f(0.5 * (a + b)))
}

/// Points every `spacing` mm along a polyline, with interpolated parameters.
fn stations(line: &[(Point3, [f64; 2])], spacing: f64) -> Vec<(Point3, [f64; 2])> {
    let mut out = Vec::new();
    for w in line.windows(2) {
        let len = (w[1].0 - w[0].0).norm();
        let n = (len / spacing).ceil().max(1.0) as usize;
        for s in 0..n {
            let t = s as f64 / n as f64;
            out.push((w[0].0 + t * (w[1].0 - w[0].0), lerp(w[0].1, w[1].1, t)));
        }
    }
    out
}

fn lerp(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Nearest point of a polyline to `p` when it is not one of its ends: point, params,
/// distance.
fn nearest_interior(p: &Point3, line: &[(Point3, [f64; 2])]) -> Option<(Point3, [f64; 2], f64)> {
    let mut best: Option<(Point3, [f64; 2], f64, bool)> = None;
    let last = line.len() - 2;
    for (k, w) in line.windows(2).enumerate() {
        let d = w[1].0 - w[0].0;
        let dd = d.norm_squared();
        let t = if dd > 0.0 {
            ((p - w[0].0).dot(&d) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = w[0].0 + t * d;
        let dist = (p - q).norm();
        let end = (k == 0 && t == 0.0) || (k == last && t == 1.0);
        if best.is_none_or(|b| dist < b.2) {
            best = Some((q, lerp(w[0].1, w[1].1, t), dist, end));
        }
    }
    best.filter(|b| !b.3).map(|b| (b.0, b.1, b.2))
}

/// Deepest entry (mm, >= 0) of the cutter at any CL point of `plan` into the surface
/// points `surface` (a dense sampling of the part), by brute force over the points
/// within the cutter's reach.
pub fn max_penetration(plan: &Plan, cutter: &Cutter, surface: &[Point3]) -> f64 {
    let r = cutter.radius();
    let cell = r;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in surface {
        lo = [lo[0].min(p.x), lo[1].min(p.y)];
        hi = [hi[0].max(p.x), hi[1].max(p.y)];
    }
    let dims = [0, 1].map(|k| ((hi[k] - lo[k]) / cell).floor() as usize + 1);
    let mut grid = vec![Vec::new(); dims[0] * dims[1]];
    let ix = |v: f64, k: usize| (((v - lo[k]) / cell).floor().max(0.0) as usize).min(dims[k] - 1);
    for (n, p) in surface.iter().enumerate() {
        grid[ix(p.y, 1) * dims[0] + ix(p.x, 0)].push(n as u32);
    }
    let mut worst: f64 = 0.0;
    for pose in plan
        .toolpath
        .passes
        .iter()
        .flat_map(|p| &p.points)
        .map(|p| p.pose)
    {
        let c = pose.cl;
        for j in ix(c.y - r, 1)..=ix(c.y + r, 1) {
            for i in ix(c.x - r, 0)..=ix(c.x + r, 0) {
                for &n in &grid[j * dims[0] + i] {
                    let p = &surface[n as usize];
                    // Outside the cutter's cylinder or below its tip: cannot be inside.
                    if (p.x - c.x).powi(2) + (p.y - c.y).powi(2) > r * r || p.z < c.z {
                        continue;
                    }
                    worst = worst.max(-cutter.signed_distance(&pose, p));
                }
            }
        }
    }
    worst
}

/// Largest material height left anywhere on `part` (a dense parameter grid with
/// neighbours about `spacing` apart, boundaries included, points outside a face's
/// trimming loops skipped) by the ball passes of `plan`, and where.
pub fn max_residual(plan: &Plan, part: &Part, r: f64, spacing: f64) -> (f64, Point3) {
    let env = Envelope::new(plan, r);
    let mut worst = (0.0, Point3::origin());
    for k in 0..part.patches.len() {
        for (p, n) in dense_frames(part, k, spacing) {
            let h = env.residual(&p, &n);
            if h > worst.0 {
                worst = (h, p);
            }
        }
    }
    worst
}

/// Points and unit normals (toward +z) on a parameter grid of patch `k` of `part`,
/// inside its face's trimming loops if it has any.
fn dense_frames(part: &Part, k: usize, spacing: f64) -> Vec<(Point3, Vec3)> {
    let patch = &part.patches[k];
    let trim = part.trim(k);
    let [[u0, u1], [v0, v1]] = patch.domain();
    let (nu, nv) = grid_size(patch, spacing);
    let mut out = Vec::with_capacity((nu + 1) * (nv + 1));
    for i in 0..=nu {
        for j in 0..=nv {
            let (u, v) = (
                u0 + (u1 - u0) * i as f64 / nu as f64,
                v0 + (v1 - v0) * j as f64 / nv as f64,
            );
            if trim.is_some_and(|t| !t.contains(u, v)) {
                continue;
            }
            let d = patch.derivs(u, v);
            let n = d.du.cross(&d.dv).normalize();
            out.push((d.point, if n.z < 0.0 { -n } else { n }));
        }
    }
    out
}

/// Grid intervals per direction so that neighbours are at most about `spacing` apart.
fn grid_size(patch: &Patch, spacing: f64) -> (usize, usize) {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let mut speed: [f64; 2] = [0.0, 0.0];
    for a in 0..=16 {
        for b in 0..=16 {
            let d = patch.derivs(
                u0 + (u1 - u0) * a as f64 / 16.0,
                v0 + (v1 - v0) * b as f64 / 16.0,
            );
            speed = [speed[0].max(d.du.norm()), speed[1].max(d.dv.norm())];
        }
    }
    let nu = (1.3 * speed[0] * (u1 - u0) / spacing).ceil() as usize + 1;
    let nv = (1.3 * speed[1] * (v1 - v0) / spacing).ceil() as usize + 1;
    (nu, nv)
}

/// Points and unit normals of every face on the grids of [`dense_points`].
pub fn dense_face_frames(part: &Part, spacing: f64) -> Vec<(Point3, Vec3)> {
    (0..part.patches.len())
        .flat_map(|k| dense_frames(part, k, spacing))
        .collect()
}

/// `(n + 1)^2`-ish surface points of every patch on a uniform parameter grid whose
/// neighbours are at most `spacing` apart (a fine structured tessellation's vertices),
/// inside the faces' trimming loops.
pub fn dense_points(part: &Part, spacing: f64) -> Vec<Point3> {
    (0..part.patches.len())
        .flat_map(|k| dense_frames(part, k, spacing).into_iter().map(|(p, _)| p))
        .collect()
}
