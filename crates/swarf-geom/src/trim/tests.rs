use super::*;

fn circle(c: Uv, r: f64, n: usize) -> Vec<Uv> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            [c[0] + r * a.cos(), c[1] + r * a.sin()]
        })
        .collect()
}

fn square(lo: f64, hi: f64) -> Vec<Uv> {
    vec![[lo, lo], [hi, lo], [hi, hi], [lo, hi]]
}

/// Brute-force inside test (winding number), independent of the bands.
fn winding(loops: &[Vec<Uv>], u: f64, v: f64) -> i32 {
    let mut w = 0;
    for l in loops {
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            let side = (b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0]);
            if a[1] <= v && b[1] > v && side > 0.0 {
                w += 1;
            } else if a[1] > v && b[1] <= v && side < 0.0 {
                w -= 1;
            }
        }
    }
    w
}

#[test]
fn inside_agrees_with_winding_numbers_on_a_plate_with_holes() {
    let t = Trim::new(vec![
        circle([0.5, 0.5], 0.5, 700),
        // Given counter-clockwise: must be turned clockwise.
        circle([0.3, 0.5], 0.1, 300),
        square(0.6, 0.8),
    ])
    .unwrap();
    assert!(signed(&t.loops()[0]) > 0.0);
    assert!(signed(&t.loops()[1]) < 0.0 && signed(&t.loops()[2]) < 0.0);
    let mut disagreements = 0;
    for i in 0..=200 {
        for j in 0..=200 {
            let (u, v) = (
                i as f64 / 200.0 * 1.2 - 0.1,
                j as f64 / 200.0 * 1.2 - 0.1 + 1e-7,
            );
            let w = winding(t.loops(), u + 1e-9, v);
            if t.contains(u + 1e-9, v) != (w == 1) {
                disagreements += 1;
            }
        }
    }
    assert_eq!(disagreements, 0);
}

fn signed(l: &[Uv]) -> f64 {
    (0..l.len())
        .map(|k| {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

#[test]
fn intervals_clip_a_line_through_a_hole() {
    let t = Trim::new(vec![square(0.0, 1.0), square(0.4, 0.6)]).unwrap();
    let iv = t.intervals([-1.0, 0.5], [2.0, 0.5]);
    let want = [[1.0 / 3.0, 1.4 / 3.0], [1.6 / 3.0, 2.0 / 3.0]];
    assert_eq!(iv.len(), 2, "{iv:?}");
    for (g, w) in iv.iter().zip(want) {
        assert!(
            (g[0] - w[0]).abs() < 1e-12 && (g[1] - w[1]).abs() < 1e-12,
            "{iv:?}"
        );
    }
    assert!(t.intervals([2.0, 0.0], [3.0, 1.0]).is_empty());
    assert_eq!(t.intervals([0.1, 0.1], [0.2, 0.2]), vec![[0.0, 1.0]]);
}

#[test]
fn bad_loops_are_named() {
    let e = |l: Vec<Vec<Uv>>| Trim::new(l).unwrap_err().to_string();
    assert!(e(vec![]).contains("no loops"));
    assert!(e(vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 0.0]]]).contains("2 distinct points"));
    assert!(e(vec![vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]]).contains("no area"));
    assert!(e(vec![vec![[0.0, f64::NAN], [1.0, 0.0], [2.0, 1.0]]]).starts_with("loop[0]: point 0"));
    let bow = vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 1.0]];
    assert!(e(vec![bow]).starts_with("loop[0]: edge"));
    let msg = e(vec![square(0.0, 1.0), square(0.5, 1.5)]);
    assert!(msg.contains("loop[1]"), "{msg}");
    let msg = e(vec![square(0.0, 1.0), square(2.0, 3.0)]);
    assert!(msg.starts_with("loop[1]: a hole outside"), "{msg}");
    // Touching: a hole whose corner lies on the outer loop.
    let touching = vec![[0.0, 0.5], [0.5, 0.2], [0.5, 0.8]];
    assert!(e(vec![square(0.0, 1.0), touching]).contains("touches"));
    // A spike folding back along itself.
    let spike = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 0.5]];
    assert!(Trim::new(vec![spike]).is_err());
}

#[test]
fn closing_and_repeated_points_are_dropped_and_serde_validates() {
    let mut l = square(0.0, 1.0);
    l.insert(1, l[0]);
    l.push(l[0]);
    let t = Trim::new(vec![l]).unwrap();
    assert_eq!(t.point_count(), 4);
    let json = serde_json_like(&t);
    assert_eq!(json, t.loops().to_vec());
    let bad: Result<Trim, _> = Trim::try_from(vec![vec![[0.0, 0.0]]]);
    assert!(bad.is_err());
    assert_eq!(t.uv_box(), [[0.0, 1.0], [0.0, 1.0]]);
}

/// What serde writes (the loops, through `Into`).
fn serde_json_like(t: &Trim) -> Vec<Vec<Uv>> {
    Vec::<Vec<Uv>>::from(t.clone())
}
