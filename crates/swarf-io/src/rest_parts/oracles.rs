//! Oracles for the built-in mesh parts' tests, written from the parts' descriptions
//! and sharing no code with the generators: for each part a distance to its analytic
//! surface (an upper bound, exact on the curved faces), its height as seen from
//! above, and the outward normal.
//!
//! The fillet pocket's air (below z = 20) is the set of points within 3 of the convex
//! set C = {xy within 2 of R = [25, 75] x [25, 55], z >= 3} (the sharp pocket opened
//! by a ball of radius 3), so its surface is the level set dist(p, C) = 3.

use swarf_geom::{Point3, Vec3};

// ---- fillet-pocket oracle ----

/// Nearest point of R = [25, 75] x [25, 55] to (x, y), and the distance to it.
pub(super) fn core_nearest(x: f64, y: f64) -> ([f64; 2], f64) {
    let c = [x.clamp(25.0, 75.0), y.clamp(25.0, 55.0)];
    (c, (x - c[0]).hypot(y - c[1]))
}

/// Nearest point of C to p.
pub(super) fn c_nearest(p: &Point3) -> Point3 {
    let (c, d) = core_nearest(p.x, p.y);
    let [x, y] = if d <= 2.0 {
        [p.x, p.y]
    } else {
        [c[0] + 2.0 * (p.x - c[0]) / d, c[1] + 2.0 * (p.y - c[1]) / d]
    };
    Point3::new(x, y, p.z.max(3.0))
}

/// Distance from p to the top face (the ring outside the opening, to rounding when
/// R's projection is outside) and to the pocket surface; the smaller.
pub(super) fn pocket_dists(p: &Point3) -> (f64, f64) {
    let (_, d) = core_nearest(p.x, p.y);
    let top = if d >= 5.0 {
        (p.z - 20.0).abs()
    } else if d > 0.0 {
        (p.z - 20.0).hypot(5.0 - d)
    } else {
        f64::INFINITY
    };
    let pocket = if p.z <= 20.0 {
        ((c_nearest(p) - p).norm() - 3.0).abs()
    } else {
        f64::INFINITY
    };
    (top, pocket)
}

pub(super) fn pocket_dist(p: &Point3) -> f64 {
    let (top, pocket) = pocket_dists(p);
    top.min(pocket)
}

pub(super) fn pocket_height(x: f64, y: f64) -> f64 {
    let (_, d) = core_nearest(x, y);
    if d >= 5.0 {
        20.0
    } else if d <= 2.0 {
        0.0
    } else {
        3.0 - (9.0 - (d - 2.0).powi(2)).sqrt()
    }
}

pub(super) fn pocket_normal(p: &Point3) -> Vec3 {
    let (top, pocket) = pocket_dists(p);
    if top < pocket {
        Vec3::z()
    } else {
        (c_nearest(p) - p).normalize()
    }
}

// ---- v-grooves and short-grooves oracles ----

/// (x of the bottom, included angle in degrees).
pub(super) const V: [(f64, f64); 3] = [(20.0, 60.0), (55.0, 90.0), (105.0, 120.0)];

pub(super) fn v_height(x: f64, _y: f64) -> f64 {
    V.iter().fold(10.0, |h: f64, &(x0, deg)| {
        let half = (deg / 2.0).to_radians();
        h.min((x - x0).abs() * half.cos() / half.sin())
    })
}

/// (y of the bottom, x start, x end).
pub(super) const SHORT: [(f64, f64, f64); 4] = [
    (15.0, 10.0, 30.0),
    (15.0, 31.5, 51.5),
    (45.0, 10.0, 30.0),
    (45.0, 35.0, 55.0),
];

pub(super) fn short_height(x: f64, y: f64) -> f64 {
    SHORT
        .iter()
        .filter(|g| g.1 <= x && x <= g.2)
        .fold(0.0, |h: f64, g| h.min((y - g.0).abs() - 4.0))
}

/// The nearest end wall to p among those whose triangle p lies over (in the wall's
/// plane), within `slack` of it: (distance, outward normal's x).
pub(super) fn short_wall(p: &Point3, slack: f64) -> Option<(f64, f64)> {
    let inside = |g: &&(f64, f64, f64)| (g.0 - p.y).abs() - 4.0 <= p.z + 1e-9 && p.z <= 1e-9;
    SHORT
        .iter()
        .filter(inside)
        .flat_map(|g| [(g.1, 1.0), (g.2, -1.0)])
        .map(|(x, side)| ((p.x - x).abs(), side))
        .filter(|(d, _)| *d <= slack)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

pub(super) fn short_dist(p: &Point3) -> f64 {
    let graph = (p.z - short_height(p.x, p.y)).abs();
    short_wall(p, f64::INFINITY).map_or(graph, |(d, _)| graph.min(d))
}

/// Upward unit normal of a height field by central differences.
pub(super) fn graph_normal(h: fn(f64, f64) -> f64, p: &Point3) -> Vec3 {
    let e = 1e-6;
    let hx = (h(p.x + e, p.y) - h(p.x - e, p.y)) / (2.0 * e);
    let hy = (h(p.x, p.y + e) - h(p.x, p.y - e)) / (2.0 * e);
    Vec3::new(-hx, -hy, 1.0).normalize()
}

pub(super) fn short_normal(p: &Point3) -> Vec3 {
    match short_wall(p, 1e-9) {
        Some((_, side)) => Vec3::new(side, 0.0, 0.0),
        None => graph_normal(short_height, p),
    }
}

pub(super) fn v_normal(p: &Point3) -> Vec3 {
    graph_normal(v_height, p)
}

// ---- boss and ramp-step oracles ----

/// Boss ribs: (y of the centre line, side angle in degrees); tops 6 wide at z = 10.
pub(super) const RIB: [(f64, f64); 4] = [(30.0, 45.0), (65.0, 65.0), (95.0, 80.0), (120.0, 90.0)];

pub(super) fn boss_height(_x: f64, y: f64) -> f64 {
    RIB.iter().fold(0.0, |h: f64, &(yc, deg)| {
        let off = (y - yc).abs() - 3.0;
        let rib = if off <= 0.0 {
            10.0
        } else if deg == 90.0 {
            0.0
        } else {
            (10.0 - off * deg.to_radians().tan()).max(0.0)
        };
        h.max(rib)
    })
}

/// The vertical rib's sides y = 117 (facing -y) and y = 123 (facing +y) for z in
/// [0, 10]: (distance, outward normal's y) of the nearer one within `slack`.
pub(super) fn boss_wall(p: &Point3, slack: f64) -> Option<(f64, f64)> {
    if p.z < -1e-9 || p.z > 10.0 + 1e-9 {
        return None;
    }
    [(117.0, -1.0), (123.0, 1.0)]
        .into_iter()
        .map(|(y, side)| ((p.y - y).abs(), side))
        .filter(|(d, _)| *d <= slack)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

pub(super) fn boss_dist(p: &Point3) -> f64 {
    let graph = (p.z - boss_height(p.x, p.y)).abs();
    boss_wall(p, f64::INFINITY).map_or(graph, |(d, _)| graph.min(d))
}

pub(super) fn boss_normal(p: &Point3) -> Vec3 {
    match boss_wall(p, 1e-9) {
        Some((_, side)) => Vec3::new(0.0, side, 0.0),
        None => graph_normal(boss_height, p),
    }
}

pub(super) fn step_height(x: f64, _y: f64) -> f64 {
    (60.0 - x).clamp(0.0, 20.0)
}

/// Each part: name, block size, distance oracle, height oracle, normal oracle.
pub(super) type Oracle = (
    &'static str,
    [f64; 2],
    fn(&Point3) -> f64,
    fn(f64, f64) -> f64,
    fn(&Point3) -> Vec3,
);
pub(super) const PARTS: [Oracle; 5] = [
    (
        "fillet-pocket",
        [100.0, 80.0],
        pocket_dist,
        pocket_height,
        pocket_normal,
    ),
    (
        "v-grooves",
        [140.0, 60.0],
        |p| (p.z - v_height(p.x, p.y)).abs(),
        v_height,
        v_normal,
    ),
    (
        "short-grooves",
        [70.0, 60.0],
        short_dist,
        short_height,
        short_normal,
    ),
    ("boss", [80.0, 140.0], boss_dist, boss_height, boss_normal),
    (
        "ramp-step",
        [120.0, 40.0],
        |p| (p.z - step_height(p.x, p.y)).abs(),
        step_height,
        |p| graph_normal(step_height, p),
    ),
];
