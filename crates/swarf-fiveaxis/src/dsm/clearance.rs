//! The clearance between a cutter and one face: the least exact signed distance from
//! the tool solid (its whole profile closed by the top disc,
//! [`swarf_tool::Profile::signed_distance`]) to the face's points, negative where the
//! tool is in the face's material.
//!
//! The face is sampled once on an even parameter grid (about [`SAMPLE_SPACING`]
//! times the corner radius apart in space), kept in square blocks of [`BLOCK`]
//! samples a side with their bounding spheres; per pose the samples in the tool's
//! bounding sphere are measured (only those of blocks whose sphere meets it are
//! looked at, so a query costs what lies near the tool, not the whole face), and the best local minima of the grid are refined
//! by Newton steps on the distance over `(u, v)` (central differences, a gradient
//! step where the Hessian is not positive definite, backtracking so the distance
//! never grows, the parameter box enforced). Outside the tool the distance is C1 in
//! `(u, v)` (the tool is convex), so a touching contact converges quadratically; where
//! the tool is in the material the answer is the deepest point found, which is all a
//! sign test needs.

use swarf_geom::{Patch, Point3, Vec3};
use swarf_tool::{Pose, Profile};

/// Grid spacing in space as a fraction of the cutter's smallest feature (the corner
/// radius, or the radius of a flat end).
pub const SAMPLE_SPACING: f64 = 0.5;
/// Most grid samples along one parameter direction.
pub const MAX_SAMPLES: usize = 400;
/// Samples along each side of a block.
pub const BLOCK: usize = 8;
/// Local minima of the grid refined per query, best first.
pub const STARTS: usize = 3;
/// Newton iterations per start.
pub const MAX_ITERATIONS: usize = 60;
/// Central-difference step, as a fraction of the parameter range.
pub const FD_STEP: f64 = 1e-6;
/// Iterations stop when a step moves the parameters by less than this fraction of
/// their range.
pub const PARAM_TOL: f64 = 1e-13;

/// Where a face comes nearest the tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    /// The signed distance, mm (negative: the tool is in the material).
    pub distance: f64,
    /// The face's parameters there.
    pub uv: [f64; 2],
    /// The face's point there, mm.
    pub point: Point3,
}

/// A face prepared for clearance queries.
#[derive(Debug, Clone)]
pub struct Face {
    patch: Patch,
    dom: [[f64; 2]; 2],
    n: [usize; 2],
    samples: Vec<Point3>,
    blocks: Vec<Block>,
    /// Distance between neighbouring samples along u and v, mm (longest iso curve).
    spacing: [f64; 2],
}

/// A square of the sample grid, `[i0, i1) x [j0, j1)`, and a sphere holding its
/// samples.
#[derive(Debug, Clone, Copy)]
struct Block {
    i: [usize; 2],
    j: [usize; 2],
    centre: Point3,
    radius: f64,
}

impl Face {
    /// Samples `patch` at about `spacing` mm (at most [`MAX_SAMPLES`] a side).
    pub fn new(patch: &Patch, spacing: f64) -> Face {
        let dom = patch.domain();
        let lengths = [iso_length(patch, dom, 0), iso_length(patch, dom, 1)];
        let per =
            |k: usize| ((lengths[k] / spacing.max(1e-3)).ceil() as usize).clamp(8, MAX_SAMPLES);
        let n = [per(0), per(1)];
        let mut samples = Vec::with_capacity((n[0] + 1) * (n[1] + 1));
        for i in 0..=n[0] {
            for j in 0..=n[1] {
                let (u, v) = param(dom, n, i, j);
                samples.push(patch.eval(u, v));
            }
        }
        let blocks = blocks(&samples, n);
        Face {
            patch: patch.clone(),
            dom,
            n,
            samples,
            blocks,
            spacing: [lengths[0] / n[0] as f64, lengths[1] / n[1] as f64],
        }
    }

    /// The samples a query whose bounding sphere has radius `bound` (mm) measures, at
    /// most: those of the sphere's widest section through the face at this sampling,
    /// and never more than the face has.
    pub fn samples_within(&self, bound: f64) -> f64 {
        let area = std::f64::consts::PI * bound * bound;
        (area / (self.spacing[0] * self.spacing[1]).max(f64::MIN_POSITIVE))
            .min(self.samples.len() as f64)
    }

    /// The patch.
    pub fn patch(&self) -> &Patch {
        &self.patch
    }

    /// The face's point at `uv`.
    pub fn eval(&self, uv: [f64; 2]) -> Point3 {
        self.patch.eval(uv[0], uv[1])
    }

    /// Whether `uv` lies on the parameter box's boundary (within a millionth of it).
    pub fn on_boundary(&self, uv: [f64; 2]) -> bool {
        (0..2).any(|k| {
            let [lo, hi] = self.dom[k];
            let eps = 1e-6 * (hi - lo);
            uv[k] <= lo + eps || uv[k] >= hi - eps
        })
    }

    /// The clearance of the tool `profile` at `pose` from this face (module doc);
    /// `None` when no sample lies within the tool's bounding sphere plus
    /// `reach` mm (the face is farther than `reach` from the tool).
    pub fn clearance(&self, profile: &Profile, pose: &Pose, reach: f64) -> Option<Clearance> {
        let centre = pose.cl + pose.axis * (0.5 * profile.length());
        let bound = query_radius(profile, reach);
        let d = |p: &Point3| profile.signed_distance(pose, p);
        let stride = self.n[1] + 1;
        let near: Vec<&Block> = self
            .blocks
            .iter()
            .filter(|b| (b.centre - centre).norm() <= bound + b.radius)
            .collect();
        // The window of the grid the near blocks span; every sample outside it is
        // farther than `bound` and counts as unmeasured (infinite).
        let lo = [
            near.iter().map(|b| b.i[0]).min()?,
            near.iter().map(|b| b.j[0]).min()?,
        ];
        let hi = [
            near.iter().map(|b| b.i[1]).max()?,
            near.iter().map(|b| b.j[1]).max()?,
        ];
        let width = hi[1] - lo[1];
        let mut values = vec![f64::INFINITY; (hi[0] - lo[0]) * width];
        for b in &near {
            for i in b.i[0]..b.i[1] {
                for j in b.j[0]..b.j[1] {
                    let p = &self.samples[i * stride + j];
                    if (p - centre).norm() <= bound {
                        values[(i - lo[0]) * width + j - lo[1]] = d(p);
                    }
                }
            }
        }
        let at = |i: usize, j: usize| values[(i - lo[0]) * width + j - lo[1]];
        let mut starts: Vec<(f64, usize)> = Vec::new();
        for i in lo[0]..hi[0] {
            for j in lo[1]..hi[1] {
                let v = at(i, j);
                if !v.is_finite() {
                    continue;
                }
                let neighbours = [
                    (i > lo[0]).then(|| (i - 1, j)),
                    (i + 1 < hi[0]).then(|| (i + 1, j)),
                    (j > lo[1]).then(|| (i, j - 1)),
                    (j + 1 < hi[1]).then(|| (i, j + 1)),
                ];
                if neighbours.iter().flatten().all(|&(a, c)| at(a, c) >= v) {
                    starts.push((v, i * stride + j));
                }
            }
        }
        starts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let f = |uv: [f64; 2]| d(&self.patch.eval(uv[0], uv[1]));
        starts
            .iter()
            .take(STARTS)
            .map(|&(_, k)| {
                let start = param(self.dom, self.n, k / stride, k % stride);
                let (uv, distance) = minimise(&f, [start.0, start.1], self.dom);
                Clearance {
                    distance,
                    uv,
                    point: self.eval(uv),
                }
            })
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
    }
}

/// The longest of three iso-parameter curves along direction `k` (polylines of 32
/// chords), mm.
fn iso_length(patch: &Patch, dom: [[f64; 2]; 2], k: usize) -> f64 {
    let at = |t: f64, s: f64| {
        let lerp = |r: [f64; 2], f: f64| r[0] + (r[1] - r[0]) * f;
        if k == 0 {
            patch.eval(lerp(dom[0], t), lerp(dom[1], s))
        } else {
            patch.eval(lerp(dom[0], s), lerp(dom[1], t))
        }
    };
    [0.0, 0.5, 1.0]
        .iter()
        .map(|&s| {
            (0..32)
                .map(|i| (at((i + 1) as f64 / 32.0, s) - at(i as f64 / 32.0, s)).norm())
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

/// The radius of a clearance query's sphere (the tool's bounding sphere about its
/// middle, grown by `reach`), mm.
pub fn query_radius(profile: &Profile, reach: f64) -> f64 {
    let half = 0.5 * profile.length();
    (half * half + profile.radius().powi(2)).sqrt() + reach
}

/// The grid's samples (`n[1] + 1` to a row) in blocks of [`BLOCK`] a side.
fn blocks(samples: &[Point3], n: [usize; 2]) -> Vec<Block> {
    let stride = n[1] + 1;
    let mut out = Vec::new();
    for i0 in (0..=n[0]).step_by(BLOCK) {
        for j0 in (0..=n[1]).step_by(BLOCK) {
            let (i1, j1) = ((i0 + BLOCK).min(n[0] + 1), (j0 + BLOCK).min(n[1] + 1));
            let points = || (i0..i1).flat_map(move |i| (j0..j1).map(move |j| i * stride + j));
            let count = ((i1 - i0) * (j1 - j0)) as f64;
            let sum = points().fold(Vec3::zeros(), |a, k| a + samples[k].coords);
            let centre = Point3::from(sum / count);
            let radius = points()
                .map(|k| (samples[k] - centre).norm())
                .fold(0.0, f64::max);
            out.push(Block {
                i: [i0, i1],
                j: [j0, j1],
                centre,
                radius,
            });
        }
    }
    out
}

fn param(dom: [[f64; 2]; 2], n: [usize; 2], i: usize, j: usize) -> (f64, f64) {
    let t = |k: usize, m: usize| dom[k][0] + (dom[k][1] - dom[k][0]) * m as f64 / n[k] as f64;
    (t(0, i), t(1, j))
}

/// Newton on `f` over the box `dom` from `x` (module doc): the point and its value.
fn minimise(f: &impl Fn([f64; 2]) -> f64, mut x: [f64; 2], dom: [[f64; 2]; 2]) -> ([f64; 2], f64) {
    let w = [dom[0][1] - dom[0][0], dom[1][1] - dom[1][0]];
    let clamp = |p: [f64; 2]| {
        [
            p[0].clamp(dom[0][0], dom[0][1]),
            p[1].clamp(dom[1][0], dom[1][1]),
        ]
    };
    let mut fx = f(x);
    for _ in 0..MAX_ITERATIONS {
        let (g, h) = derivatives(f, x, fx, w, &clamp);
        // Newton where the Hessian is positive definite, else steepest descent scaled
        // to a hundredth of the range.
        let det = h[0] * h[2] - h[1] * h[1];
        let mut step = if h[0] > 0.0 && det > 0.0 {
            [
                -(h[2] * g[0] - h[1] * g[1]) / det,
                -(h[0] * g[1] - h[1] * g[0]) / det,
            ]
        } else {
            let gn = (g[0] * g[0] * w[0] * w[0] + g[1] * g[1] * w[1] * w[1]).sqrt();
            if gn == 0.0 {
                break;
            }
            [
                -0.01 * g[0] * w[0] * w[0] / gn,
                -0.01 * g[1] * w[1] * w[1] / gn,
            ]
        };
        // A parameter on its bound that the step pushes outward stays there.
        for k in 0..2 {
            let at_lo = x[k] <= dom[k][0] && step[k] < 0.0;
            let at_hi = x[k] >= dom[k][1] && step[k] > 0.0;
            if at_lo || at_hi {
                step[k] = 0.0;
            }
        }
        let mut t = 1.0;
        let mut moved = false;
        while t > 1e-12 {
            let y = clamp([x[0] + t * step[0], x[1] + t * step[1]]);
            let fy = f(y);
            if fy <= fx {
                let small = (0..2).all(|k| (y[k] - x[k]).abs() <= PARAM_TOL * w[k]);
                moved = !small;
                x = y;
                fx = fy;
                break;
            }
            t *= 0.5;
        }
        if !moved {
            break;
        }
    }
    (x, fx)
}

/// Central-difference gradient and Hessian `[huu, huv, hvv]` of `f` at `x` (one-sided
/// where `x` is on the box).
fn derivatives(
    f: &impl Fn([f64; 2]) -> f64,
    x: [f64; 2],
    fx: f64,
    w: [f64; 2],
    clamp: &impl Fn([f64; 2]) -> [f64; 2],
) -> ([f64; 2], [f64; 3]) {
    let mut g = [0.0; 2];
    let mut hd = [0.0; 2];
    for k in 0..2 {
        let mut d = [0.0; 2];
        d[k] = FD_STEP * w[k];
        let (p, m) = (
            clamp([x[0] + d[0], x[1] + d[1]]),
            clamp([x[0] - d[0], x[1] - d[1]]),
        );
        let (hp, hm) = (p[k] - x[k], x[k] - m[k]);
        let (fp, fm) = (f(p), f(m));
        g[k] = (fp - fm) / (hp + hm);
        let tiny = f64::MIN_POSITIVE;
        hd[k] = 2.0 * ((fp - fx) / hp.max(tiny) - (fx - fm) / hm.max(tiny)) / (hp + hm).max(tiny);
    }
    let (du, dv) = (FD_STEP * w[0], FD_STEP * w[1]);
    let pp = clamp([x[0] + du, x[1] + dv]);
    let mm = clamp([x[0] - du, x[1] - dv]);
    let pm = clamp([x[0] + du, x[1] - dv]);
    let mp = clamp([x[0] - du, x[1] + dv]);
    let span =
        (pp[0] - mm[0]).abs().max(f64::MIN_POSITIVE) * (pp[1] - mm[1]).abs().max(f64::MIN_POSITIVE);
    let huv = (f(pp) - f(pm) - f(mp) + f(mm)) / span;
    (g, [hd[0], huv, hd[1]])
}
