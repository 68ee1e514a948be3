//! Ordering passes: pieces of one row joined, rows cut zigzag or one way.
//!
//! A strategy produces *rows* in side order from the start side: one row per drive
//! plane, constant parameter or scallop path, each holding its pieces in travel order
//! (a row splits where it leaves the part or dips under another patch). Consecutive
//! pieces of a row whose ends are at most `max_gap` apart in XY are joined through a
//! *bridge*: points on the straight XY line between them at most `step` apart, each at
//! the height where the vertical cutter first touches the part (a short drop-cutter
//! path across the gap, so the tool neither lifts off nor cuts in). Otherwise a piece
//! is its own pass and the machine links to it through the clearance plane.
//!
//! Zigzag reverses every other row (pieces and points), so consecutive passes start
//! near where the previous one ended; one-way keeps every row in its travel order.

use swarf_geom::Point3;
use swarf_tool::Pose;
use swarf_toolpath::{Pass, PathPoint};

/// The pieces of one row, in travel order.
pub type Row = Vec<Pass>;

/// How rows are joined into passes.
pub struct Joining<F> {
    /// Longest XY gap bridged inside a row, mm.
    pub max_gap: f64,
    /// Longest step between bridge points, mm.
    pub step: f64,
    /// Height of the first contact at `(x, y)`; `None` off the part.
    pub drop: F,
}

/// The rows as passes in cutting order (module doc).
pub fn order_rows<F>(rows: Vec<Row>, zigzag: bool, join: &Joining<F>) -> Vec<Pass>
where
    F: Fn(f64, f64) -> Option<f64>,
{
    let mut out = Vec::new();
    for (k, row) in rows.into_iter().enumerate() {
        let mut passes = join_row(row, join);
        if zigzag && k % 2 == 1 {
            passes.reverse();
            for p in &mut passes {
                p.points.reverse();
            }
        }
        out.extend(passes);
    }
    out
}

fn join_row<F>(row: Row, join: &Joining<F>) -> Vec<Pass>
where
    F: Fn(f64, f64) -> Option<f64>,
{
    let mut out: Vec<Pass> = Vec::new();
    for piece in row.into_iter().filter(|p| !p.points.is_empty()) {
        let bridged = out.last_mut().and_then(|last| {
            let a = last.points.last()?.pose.cl;
            let b = piece.points.first()?.pose.cl;
            let points = bridge(&a, &b, join)?;
            last.points.extend(points);
            Some(())
        });
        match bridged {
            Some(()) => {
                if let Some(last) = out.last_mut() {
                    last.points.extend(piece.points);
                }
            }
            None => out.push(piece),
        }
    }
    out
}

/// Points strictly between `a` and `b` on their XY line, dropped onto the part; `None`
/// when the gap is too wide or the line leaves the part.
fn bridge<F>(a: &Point3, b: &Point3, join: &Joining<F>) -> Option<Vec<PathPoint>>
where
    F: Fn(f64, f64) -> Option<f64>,
{
    let gap = (b.x - a.x).hypot(b.y - a.y);
    if gap > join.max_gap {
        return None;
    }
    let n = (gap / join.step).ceil() as usize;
    (1..n)
        .map(|i| {
            let t = i as f64 / n as f64;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            let z = (join.drop)(x, y)?;
            Some(PathPoint::new(Pose::vertical(Point3::new(x, y, z))))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(xs: &[f64], y: f64) -> Pass {
        Pass {
            points: xs
                .iter()
                .map(|&x| PathPoint::new(Pose::vertical(Point3::new(x, y, 0.0))))
                .collect(),
            ..Pass::default()
        }
    }

    fn xs(p: &Pass) -> Vec<f64> {
        p.points.iter().map(|q| q.pose.cl.x).collect()
    }

    #[test]
    fn zigzag_reverses_odd_rows_and_bridges_small_gaps() {
        let join = Joining {
            max_gap: 3.0,
            step: 1.0,
            drop: |x: f64, _y: f64| (x < 50.0).then_some(1.0),
        };
        let rows = vec![
            vec![pass(&[0.0, 1.0], 0.0), pass(&[3.5, 4.0], 0.0)],
            vec![pass(&[0.0, 1.0], 1.0), pass(&[9.0, 10.0], 1.0)],
            vec![pass(&[40.0, 49.0], 2.0), pass(&[51.0, 52.0], 2.0)],
        ];
        let out = order_rows(rows.clone(), true, &join);
        assert_eq!(out.len(), 5);
        // Row 0: gap 2.5 bridged at 1.0-spaced points, dropped to z = 1.
        let mid = |t: f64| 1.0 + t * 2.5;
        assert_eq!(
            xs(&out[0]),
            vec![0.0, 1.0, mid(1.0 / 3.0), mid(2.0 / 3.0), 3.5, 4.0]
        );
        assert_eq!(out[0].points[2].pose.cl.z, 1.0);
        assert!(out[0].points[2].contact.is_none());
        // Row 1: not bridged (gap 8), reversed.
        assert_eq!(xs(&out[1]), vec![10.0, 9.0]);
        assert_eq!(xs(&out[2]), vec![1.0, 0.0]);
        // Row 2: the bridge would leave the part: two passes, not reversed.
        assert_eq!(xs(&out[3]), vec![40.0, 49.0]);
        assert_eq!(xs(&out[4]), vec![51.0, 52.0]);
        let one_way = order_rows(rows, false, &join);
        assert_eq!(xs(&one_way[1]), vec![0.0, 1.0]);
    }
}
