//! A constant stepover along the surface for families of offset passes (the rings
//! of follow-pocket, the parallel passes of flow-cut; thesis 002 §5.4).
//!
//! Offsetting a curve in XY by `s` moves the tool's contact by `s / cos(slope)` on
//! a slope and by `s rho / (rho - r)` in a concave bend of radius `rho`: a fixed XY
//! step leaves tall scallops exactly where the cleanup works, on the steep sides of
//! valleys. So each next offset is found by trial: the step in XY starts at twice
//! the last accepted one (at most `s`), and is halved until every contact of the new
//! passes is within `s` (in 3D) of some contact of the previous ones, or until the
//! step reaches the floor `min_step` (where the contact jumps, at the foot of a wall,
//! no XY step keeps it close; there the floor bounds the number of passes).
//! Nearest contacts are looked up in a hash of cells of size `s`.

use std::collections::HashMap;
use swarf_geom::Point3;
use swarf_toolpath::Pass;

/// The contacts of a set of passes, hashed by cells of size `cell`.
struct Contacts {
    cell: f64,
    cells: HashMap<(i64, i64, i64), Vec<Point3>>,
}

impl Contacts {
    fn new(passes: &[Pass], cell: f64) -> Contacts {
        let mut cells: HashMap<(i64, i64, i64), Vec<Point3>> = HashMap::new();
        for c in passes
            .iter()
            .flat_map(|p| &p.points)
            .filter_map(|p| p.contact)
        {
            cells.entry(key(&c.point, cell)).or_default().push(c.point);
        }
        Contacts { cell, cells }
    }

    /// True when some contact lies within `d` (at most the cell size) of `p`.
    fn near(&self, p: &Point3, d: f64) -> bool {
        let (i, j, k) = key(p, self.cell);
        (-1..=1).any(|a| {
            (-1..=1).any(|b| {
                (-1..=1).any(|c| {
                    self.cells
                        .get(&(i + a, j + b, k + c))
                        .is_some_and(|v| v.iter().any(|q| (q - p).norm() <= d))
                })
            })
        })
    }
}

fn key(p: &Point3, cell: f64) -> (i64, i64, i64) {
    let f = |v: f64| (v / cell).floor() as i64;
    (f(p.x), f(p.y), f(p.z))
}

/// True when every contact of `next` is within `s` of a contact of `prev`.
fn close(prev: &Contacts, next: &[Pass], s: f64) -> bool {
    next.iter()
        .flat_map(|p| &p.points)
        .filter_map(|p| p.contact)
        .all(|c| prev.near(&c.point, s * (1.0 + 1e-9)))
}

/// The offsets after `first` (at offset 0): up to `count` further sets of passes
/// (or until `at` gives `None` even at the smallest step: nothing left), each found
/// as in the module doc.
/// `at(d)` drops the passes at XY offset `d`.
pub fn step_out(
    first: &[Pass],
    stepover: f64,
    min_step: f64,
    count: usize,
    mut at: impl FnMut(f64) -> Option<Vec<Pass>>,
) -> Vec<Vec<Pass>> {
    let mut out: Vec<Vec<Pass>> = Vec::new();
    let mut prev = Contacts::new(first, stepover);
    let (mut d, mut last) = (0.0, stepover);
    while out.len() < count {
        let mut step = (2.0 * last).min(stepover);
        let found = loop {
            let Some(next) = at(d + step) else {
                // Nothing left that far: come closer, down to the floor, so that the
                // last set lies within `min_step` of where the family ends.
                if step <= min_step {
                    break None;
                }
                step = (0.5 * step).max(min_step);
                continue;
            };
            if step <= min_step || close(&prev, &next, stepover) {
                break Some(next);
            }
            step = (0.5 * step).max(min_step);
        };
        let Some(next) = found else {
            break;
        };
        d += step;
        last = step;
        prev = Contacts::new(&next, stepover);
        out.push(next);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Vec3;
    use swarf_tool::Pose;
    use swarf_toolpath::{Contact, PathPoint};

    /// Passes whose contacts lie on the surface z = f(y) at y = d (a line along x).
    fn at(d: f64, f: impl Fn(f64) -> f64) -> Vec<Pass> {
        let points = (0..5)
            .map(|i| {
                let x = f64::from(i);
                PathPoint {
                    pose: Pose::vertical(Point3::new(x, d, f(d))),
                    contact: Some(Contact {
                        point: Point3::new(x, d, f(d)),
                        normal: Vec3::z(),
                        face: 0,
                        uv: [0.0; 2],
                    }),
                    lifted: 0.0,
                }
            })
            .collect();
        vec![Pass {
            points,
            ..Pass::default()
        }]
    }

    #[test]
    fn steps_shrink_on_a_slope_and_recover_on_the_flat() {
        // z = 0 for y < 2, then a 60 degree slope: contacts 0.5 apart in 3D need
        // 0.25 steps in XY there.
        let f = |y: f64| {
            if y < 2.0 {
                0.0
            } else {
                (y - 2.0) * 3f64.sqrt()
            }
        };
        let sets = step_out(&at(0.0, f), 0.5, 0.01, 12, |d| Some(at(d, f)));
        let ys: Vec<f64> = sets.iter().map(|s| s[0].points[0].pose.cl.y).collect();
        let mut prev = 0.0;
        for y in &ys {
            let gap = ((y - prev).powi(2) + (f(*y) - f(prev)).powi(2)).sqrt();
            assert!(gap <= 0.5 + 1e-12, "{prev} -> {y}: {gap}");
            prev = *y;
        }
        assert_eq!(ys[..4], [0.5, 1.0, 1.5, 2.0]);
        assert!(
            ys[4..]
                .windows(2)
                .all(|w| (w[1] - w[0] - 0.25).abs() < 1e-12),
            "{ys:?}"
        );
        // Nothing left stops the family, the last set within the smallest step of
        // the end.
        let sets = step_out(&at(0.0, f), 0.5, 0.01, 9, |d| (d < 1.2).then(|| at(d, f)));
        let last = sets.last().unwrap()[0].points[0].pose.cl.y;
        assert!((1.19..1.2).contains(&last), "{last}");
    }
}
