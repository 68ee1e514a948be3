//! The built-in boss (parts/README.md) measured where a ball can reach: its ribs'
//! concave feet keep the ball's fillet, and its open ends are rounded by the tool.

/// Ribs of the boss: centre line y, wall angle (degrees); tops 6 wide, 10 high.
pub const RIBS: [(f64, f64); 4] = [(30.0, 45.0), (65.0, 65.0), (95.0, 80.0), (120.0, 90.0)];

/// Cells this close to the plate's open ends (x = 0 and 80) are left out, mm.
pub const END: f64 = 1.0;

/// Distance in XY (across y) from the foot of a rib wall within which a ball of
/// radius `r` cannot reach a corner of wall angle `a` (degrees): it touches the floor
/// `r tan(a / 2)` from the foot, and the wall as far up along it.
pub fn fillet_band(r: f64, a: f64) -> f64 {
    r * (0.5 * a.to_radians()).tan()
}

/// Whether a ball of radius `r` reaches the boss at `(x, y)`: outside the fillet
/// band of every rib foot (0.1 mm of slack each side) and the open ends.
pub fn reachable(r: f64, x: f64, y: f64) -> bool {
    let fillet = RIBS.iter().any(|&(yc, a)| {
        let foot = 3.0 + 10.0 / a.to_radians().tan();
        let off = (y - yc).abs() - foot;
        off > -fillet_band(r, a) * a.to_radians().cos() - 0.1 && off < fillet_band(r, a) + 0.1
    });
    !fillet && (END..=80.0 - END).contains(&x)
}

/// Deviations over the reachable boss.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// Cells counted.
    pub counted: usize,
    /// Largest deviation counted, mm, and where.
    pub worst: (f64, [f64; 2]),
    /// Smallest deviation anywhere (the deepest gouge), mm.
    pub deepest: f64,
}

/// The deviations `values` (cell `k` at `xy(k)`; non-finite: unmeasured) of a cut
/// with a ball of radius `r`, counted where it reaches the boss.
pub fn reach(values: &[f64], xy: impl Fn(usize) -> [f64; 2], r: f64) -> Reach {
    let mut out = Reach {
        counted: 0,
        worst: (0.0, [0.0; 2]),
        deepest: 0.0,
    };
    for (k, &dev) in values.iter().enumerate() {
        if !dev.is_finite() {
            continue;
        }
        out.deepest = out.deepest.min(dev);
        let p = xy(k);
        if reachable(r, p[0], p[1]) {
            out.counted += 1;
            if dev > out.worst.0 {
                out.worst = (dev, p);
            }
        }
    }
    out
}
