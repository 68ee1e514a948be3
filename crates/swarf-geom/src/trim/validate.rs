//! Checks and orients trimming loops ([`super::Trim::new`]).

use super::Uv;
use crate::error::GeomError;

/// Cleans, checks and orients `loops` (module doc of [`super`]).
pub(super) fn check(loops: Vec<Vec<Uv>>) -> Result<Vec<Vec<Uv>>, GeomError> {
    if loops.is_empty() {
        return Err(GeomError::patch("trim", "no loops: expected an outer loop"));
    }
    let mut out = Vec::with_capacity(loops.len());
    for (k, l) in loops.into_iter().enumerate() {
        if let Some(i) = l
            .iter()
            .position(|p| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(GeomError::patch(
                format!("loop[{k}]"),
                format!("point {i} is not finite"),
            ));
        }
        let mut l: Vec<Uv> = l;
        l.dedup();
        while l.len() > 1 && l.first() == l.last() {
            l.pop();
        }
        if l.len() < 3 {
            return Err(GeomError::patch(
                format!("loop[{k}]"),
                format!("{} distinct points: expected at least 3", l.len()),
            ));
        }
        let area = signed_area(&l);
        if area == 0.0 || !area.is_finite() {
            return Err(GeomError::patch(format!("loop[{k}]"), "encloses no area"));
        }
        if (k == 0) != (area > 0.0) {
            l.reverse();
        }
        out.push(l);
    }
    check_crossings(&out)?;
    for (k, hole) in out.iter().enumerate().skip(1) {
        if !super::bands::Bands::new(&out[..1]).contains(&out[..1], hole[0][0], hole[0][1]) {
            return Err(GeomError::patch(
                format!("loop[{k}]"),
                "a hole outside the outer loop (loop[0])",
            ));
        }
    }
    Ok(out)
}

/// Twice the signed area (shoelace), positive counter-clockwise.
fn signed_area(l: &[Uv]) -> f64 {
    (0..l.len())
        .map(|k| {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

/// Plane sweep over the edges' `u` extents: no two edges may cross or touch unless
/// they are neighbours on one loop (sharing their common point only).
fn check_crossings(loops: &[Vec<Uv>]) -> Result<(), GeomError> {
    struct Edge {
        lo: f64,
        hi: f64,
        lp: usize,
        k: usize,
        a: Uv,
        b: Uv,
    }
    let mut edges: Vec<Edge> = Vec::new();
    for (lp, l) in loops.iter().enumerate() {
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            edges.push(Edge {
                lo: a[0].min(b[0]),
                hi: a[0].max(b[0]),
                lp,
                k,
                a,
                b,
            });
        }
    }
    edges.sort_by(|x, y| x.lo.total_cmp(&y.lo));
    for i in 0..edges.len() {
        let e = &edges[i];
        for f in edges[i + 1..].iter().take_while(|f| f.lo <= e.hi) {
            let n = loops[e.lp].len();
            let neighbours = e.lp == f.lp && ((e.k + 1) % n == f.k || (f.k + 1) % n == e.k);
            if touch(e.a, e.b, f.a, f.b, neighbours) {
                let name = format!("loop[{}]", e.lp);
                let other = if e.lp == f.lp {
                    format!("its edge {}", f.k)
                } else {
                    format!("loop[{}] edge {}", f.lp, f.k)
                };
                return Err(GeomError::patch(
                    name,
                    format!(
                        "edge {} from ({}, {}) crosses or touches {other}: expected loops that do not intersect",
                        e.k, e.a[0], e.a[1]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Sign of the turn `a -> b -> c` (exact for the f64 inputs up to rounding of one
/// product difference, enough to reject crossings; touching within rounding is rare).
fn orient(a: Uv, b: Uv, c: Uv) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether segments `a-b` and `c-d` share a point; `neighbours` allows the one shared
/// end of consecutive edges (but not an overlap along them).
fn touch(a: Uv, b: Uv, c: Uv, d: Uv, neighbours: bool) -> bool {
    let (o1, o2, o3, o4) = (
        orient(a, b, c),
        orient(a, b, d),
        orient(c, d, a),
        orient(c, d, b),
    );
    if neighbours {
        // Consecutive edges share exactly one end; they overlap only when collinear
        // and folding back.
        let collinear = o1 == 0.0 && o2 == 0.0;
        let shared = if b == c { b } else { a };
        let (p, q) = if b == c { (a, d) } else { (b, c) };
        return collinear
            && (p[0] - shared[0]) * (q[0] - shared[0]) + (p[1] - shared[1]) * (q[1] - shared[1])
                > 0.0;
    }
    let straddle = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
    if straddle(o1, o2) && straddle(o3, o4) {
        return true;
    }
    let on = |p: Uv, q: Uv, r: Uv| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    (o1 == 0.0 && on(a, b, c))
        || (o2 == 0.0 && on(a, b, d))
        || (o3 == 0.0 && on(c, d, a))
        || (o4 == 0.0 && on(c, d, b))
}
