//! Forward step along a pass from a chordal tolerance on the CL curve.
//!
//! A pass is a CC curve `C(t)` with its CL curve `L(t) = C(t) + offset(n(t))`; the
//! machine moves on the chords between consecutive CL points, so the chord must stay
//! within `tolerance` of `L` (the deviation of the chord from the arc it replaces).
//! For an arc of curvature `k` and chord `c` that deviation is the sagitta
//! `e ~ k c^2 / 8`, so the chord allowed by the tolerance is `c = sqrt(8 tol / k)`
//! (Lo 2000, the chord-error step of the CNC surface interpolator; paper 004 fig. 1,
//! "forward step"). The curvature is estimated from the step just tried:
//! `k ~ 8 e / c^2` with `e` the largest deviation of `L` at 1/4, 1/2 and 3/4 of the
//! step from its chord; so the next step is the last one scaled by `sqrt(tol / e)`
//! (with a safety factor and at most doubling). Every step is verified by those
//! midpoint checks and shortened until it passes: the tolerance is measured, not
//! assumed. Steps are also capped in length (`max_step`, so that the gouge check sees
//! points at least that dense).
//!
//! Where the CL point is undefined (a degenerate normal, a region the strategy
//! excludes), the curve is cut: a coarse scan finds the defined intervals, their ends
//! are refined by bisection, and each interval is sampled on its own.

use swarf_geom::Point3;
use swarf_geom::math::point_segment_distance;
use swarf_toolpath::PathPoint;

/// Safety factor on the curvature-predicted step (dimensionless).
const STEP_SAFETY: f64 = 0.9;
/// Part of the chordal tolerance kept back for the NC output's rounding, mm: the
/// posts write 4 decimals in mm (a CL point moves by at most 0.87e-4 mm in 3D), so a
/// chord planned to `tolerance - OUTPUT_ROUNDING` stays within `tolerance` as written.
pub const OUTPUT_ROUNDING: f64 = 1e-4;
/// Safety factor on the length-limited step (dimensionless; absorbs rounding).
const LENGTH_SAFETY: f64 = 1.0 - 1e-9;
/// Largest growth of the parameter step from one accepted step to the next.
const MAX_GROWTH: f64 = 2.0;
/// Smallest parameter step, relative to the curve's parameter range.
const MIN_STEP_REL: f64 = 1e-9;
/// Intervals of the coarse scan for undefined points.
const SCAN_INTERVALS: usize = 32;
/// Bisection steps refining the end of a defined interval.
const END_BISECTIONS: usize = 40;

/// Options of the forward stepper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepOptions {
    /// Largest deviation of a chord from the CL curve, mm.
    pub tolerance: f64,
    /// Longest chord, mm.
    pub max_step: f64,
}

/// One sampled point of a pass: its curve parameter and the pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Parameter along the CC curve.
    pub t: f64,
    /// The pose with its contact.
    pub point: PathPoint,
}

/// Samples the CL curve `f` over `[t0, t1]` so that every chord is within
/// `opts.tolerance` of the curve and at most `opts.max_step` long; returns one run of
/// samples per interval where `f` is defined (runs of one sample are kept).
pub fn sample_curve<F>(f: &F, t0: f64, t1: f64, opts: &StepOptions) -> Vec<Vec<Sample>>
where
    F: Fn(f64) -> Option<PathPoint>,
{
    defined_intervals(f, t0, t1)
        .into_iter()
        .map(|(a, b)| sample_interval(f, a, b, opts))
        .filter(|run| !run.is_empty())
        .collect()
}

/// The intervals of `[t0, t1]` where `f` is defined (scan, then bisect the ends).
fn defined_intervals<F>(f: &F, t0: f64, t1: f64) -> Vec<(f64, f64)>
where
    F: Fn(f64) -> Option<PathPoint>,
{
    let at = |k: usize| t0 + (t1 - t0) * k as f64 / SCAN_INTERVALS as f64;
    let ok: Vec<bool> = (0..=SCAN_INTERVALS).map(|k| f(at(k)).is_some()).collect();
    let mut out = Vec::new();
    let mut start = None;
    for (k, &defined) in ok.iter().enumerate() {
        match (defined, start) {
            (true, None) => {
                start = Some(if k == 0 {
                    t0
                } else {
                    edge(f, at(k - 1), at(k))
                });
            }
            (false, Some(s)) => {
                out.push((s, edge(f, at(k), at(k - 1))));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, t1));
    }
    out
}

/// The defined end nearest `bad` between a defined parameter `good` and `bad`.
fn edge<F>(f: &F, bad: f64, good: f64) -> f64
where
    F: Fn(f64) -> Option<PathPoint>,
{
    let (mut bad, mut good) = (bad, good);
    for _ in 0..END_BISECTIONS {
        let m = 0.5 * (bad + good);
        if f(m).is_some() {
            good = m;
        } else {
            bad = m;
        }
    }
    good
}

/// Adaptive sampling of one defined interval (module doc).
fn sample_interval<F>(f: &F, a: f64, b: f64, opts: &StepOptions) -> Vec<Sample>
where
    F: Fn(f64) -> Option<PathPoint>,
{
    let Some(first) = f(a) else {
        return Vec::new();
    };
    let mut out = vec![Sample { t: a, point: first }];
    let span = b - a;
    if span <= 0.0 {
        return out;
    }
    let min_dt = MIN_STEP_REL * span.abs().max(1.0);
    let mut dt = span / 8.0;
    let mut t = a;
    while t < b {
        let last = out[out.len() - 1].point.pose.cl;
        let Some((sample, next_dt)) = accept_step(f, &last, t, dt.min(b - t), min_dt, opts) else {
            break;
        };
        t = sample.t;
        out.push(sample);
        dt = next_dt;
    }
    out
}

/// Tries steps from `(t, p0)` of `dt` and shorter until one passes the checks;
/// returns the accepted sample and the step to try next.
fn accept_step<F>(
    f: &F,
    p0: &Point3,
    t: f64,
    dt: f64,
    min_dt: f64,
    opts: &StepOptions,
) -> Option<(Sample, f64)>
where
    F: Fn(f64) -> Option<PathPoint>,
{
    let mut dt = dt;
    loop {
        let Some(end) = f(t + dt) else {
            dt *= 0.5;
            if dt < min_dt {
                return None;
            }
            continue;
        };
        let p1 = end.pose.cl;
        let chord = (p1 - p0).norm();
        let dev = [0.25, 0.5, 0.75]
            .iter()
            .map(|s| {
                f(t + s * dt).map_or(f64::INFINITY, |m| {
                    point_segment_distance(&m.pose.cl, p0, &p1)
                })
            })
            .fold(0.0, f64::max);
        let by_tol = if dev > 0.0 {
            STEP_SAFETY * (opts.tolerance / dev).sqrt()
        } else {
            MAX_GROWTH
        };
        let by_len = if chord > 0.0 {
            LENGTH_SAFETY * opts.max_step / chord
        } else {
            MAX_GROWTH
        };
        let factor = by_tol.min(by_len);
        if (dev <= opts.tolerance && chord <= opts.max_step) || dt <= min_dt {
            let sample = Sample {
                t: t + dt,
                point: end,
            };
            return Some((sample, dt * factor.clamp(0.5, MAX_GROWTH)));
        }
        dt *= factor.clamp(0.1, STEP_SAFETY);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_tool::Pose;

    fn circle(r: f64) -> impl Fn(f64) -> Option<PathPoint> {
        move |t: f64| {
            let (s, c) = t.sin_cos();
            Some(PathPoint::new(Pose::vertical(Point3::new(
                r * c,
                r * s,
                0.0,
            ))))
        }
    }

    #[test]
    fn circle_chords_meet_the_sagitta_formula() {
        let (r, tol) = (50.0, 0.01);
        let opts = StepOptions {
            tolerance: tol,
            max_step: 100.0,
        };
        let runs = sample_curve(&circle(r), 0.0, 3.0, &opts);
        assert_eq!(runs.len(), 1);
        let run = &runs[0];
        assert_eq!(run[0].t, 0.0);
        assert_eq!(run.last().unwrap().t, 3.0);
        // Exact sagitta of each chord: r (1 - cos(dt / 2)).
        let ideal = 2.0 * (1.0 - tol / r).acos();
        for w in run.windows(2) {
            let dt = w[1].t - w[0].t;
            assert!(r * (1.0 - (0.5 * dt).cos()) <= tol * (1.0 + 1e-9));
        }
        // Not wastefully short: within a factor 2 of the ideal count.
        let ideal_count = (3.0 / ideal).ceil() as usize;
        assert!(
            run.len() - 1 <= 2 * ideal_count + 2,
            "{} vs {ideal_count}",
            run.len()
        );
    }

    #[test]
    fn max_step_caps_straight_lines() {
        let line = |t: f64| Some(PathPoint::new(Pose::vertical(Point3::new(t, 0.0, 0.0))));
        let opts = StepOptions {
            tolerance: 0.01,
            max_step: 2.0,
        };
        let run = &sample_curve(&line, 0.0, 10.0, &opts)[0];
        assert!(run.windows(2).all(|w| w[1].t - w[0].t <= 2.0 + 1e-12));
        assert!(run.len() <= 8, "{}", run.len());
    }

    #[test]
    fn undefined_parts_cut_the_curve() {
        let holed = |t: f64| {
            (!(0.3..0.6).contains(&t))
                .then(|| PathPoint::new(Pose::vertical(Point3::new(t, 0.0, 0.0))))
        };
        let opts = StepOptions {
            tolerance: 0.01,
            max_step: 0.1,
        };
        let runs = sample_curve(&holed, 0.0, 1.0, &opts);
        assert_eq!(runs.len(), 2);
        assert!((runs[0].last().unwrap().t - 0.3).abs() < 1e-9);
        assert!((runs[1][0].t - 0.6).abs() < 1e-9);
        assert!(sample_curve(&|_| None, 0.0, 1.0, &opts).is_empty());
    }
}
