//! Deviation along the design normals: "mow the grass" (thesis 000 §2.5, after
//! Jerard et al.): blades grow from the design surface along its outward normal, the
//! cutter mows them, and what is left of each blade is the deviation there, measured
//! perpendicular to the surface rather than vertically.
//!
//! On a Z-map stock the machined surface is `M(x, y)`, the bilinear interpolation of
//! the cell heights between cell centres. From the design point `P` with unit upward
//! normal `N`, the blade ends where `F(t) = M(P_xy + t N_xy) - (P_z + t N_z)` vanishes.
//! `F(0)` is the vertical deviation `dz`; where the machined surface runs parallel to
//! the design, `F'(t) = -1 / N_z`, so the first-order root is `t1 = dz N_z` (exact for a
//! uniform offset of a plane). Secant steps from `0` and `t1` refine it to
//! [`MOW_RESIDUAL`], kept between two points that straddle the root once they are
//! found (Illinois): at the foot of a wall the surface drops within one cell and a
//! free secant step flies off. Where the blade leaves the grid or meets a cell
//! without material, or the iteration does not settle in [`MOW_STEPS`], the
//! first-order value is kept and the cell is counted. On steep walls a vertical
//! deviation overstates the error by `1 / cos(slope)`; the normal deviation does not.

use crate::grid::Grid;
use rayon::prelude::*;

/// The blade's end is found when `|F|` drops below this, mm.
pub const MOW_RESIDUAL: f64 = 1e-10;
/// Most secant steps per blade.
pub const MOW_STEPS: usize = 30;

/// Machined height at `(x, y)` by bilinear interpolation between cell centres
/// (extended linearly over the half cell beyond the outer centres); NaN off the grid
/// or next to a cell without material.
pub fn bilinear(grid: &Grid, heights: &[f64], x: f64, y: f64) -> f64 {
    let fx = (x - grid.origin[0]) / grid.cell - 0.5;
    let fy = (y - grid.origin[1]) / grid.cell - 0.5;
    let lim = |f: f64, n: usize| f >= -0.5 && f <= n as f64 - 0.5;
    if !(lim(fx, grid.nx) && lim(fy, grid.ny)) {
        return f64::NAN;
    }
    let split = |f: f64, n: usize| {
        let i = (f.floor().max(0.0) as usize).min(n.saturating_sub(2));
        (i, f - i as f64)
    };
    let (i, tx) = split(fx, grid.nx);
    let (j, ty) = split(fy, grid.ny);
    let at = |a: usize, b: usize| heights[(b.min(grid.ny - 1)) * grid.nx + a.min(grid.nx - 1)];
    let (h00, h10, h01, h11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
    let v = (h00 * (1.0 - tx) + h10 * tx) * (1.0 - ty) + (h01 * (1.0 - tx) + h11 * tx) * ty;
    if v.is_finite() { v } else { f64::NAN }
}

/// Deviation along the design normals per cell, from the vertical deviation
/// `vertical` (NaN where not measured), and the number of cells that kept the
/// first-order value.
pub fn normal_deviation(
    grid: &Grid,
    machined: &[f64],
    design: &[f64],
    normals: &[[f32; 3]],
    vertical: &[f64],
) -> (Vec<f64>, usize) {
    let out: Vec<(f64, bool)> = (0..vertical.len())
        .into_par_iter()
        .map(|k| {
            let dz = vertical[k];
            if dz.is_nan() {
                return (f64::NAN, false);
            }
            let [x, y] = grid.centre(k % grid.nx, k / grid.nx);
            let n = normals[k].map(f64::from);
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if len.is_nan() || len <= 0.0 || n[2] <= 0.0 {
                return (dz, true);
            }
            let n = n.map(|c| c / len);
            blade(grid, machined, [x, y, design[k]], n, dz)
        })
        .collect();
    let fallback = out.iter().filter(|(_, f)| *f).count();
    (out.into_iter().map(|(v, _)| v).collect(), fallback)
}

/// The blade from `p` along `n`: `(length, kept first order)`. Secant steps from
/// `0` and the first-order root until two points straddle the root; from then on
/// the Illinois variant of regula falsi, which keeps the root between them (the
/// machined surface has kinks, at cell centres and where a wall drops, on which a
/// free secant step can fly off).
fn blade(grid: &Grid, machined: &[f64], p: [f64; 3], n: [f64; 3], dz: f64) -> (f64, bool) {
    let first = dz * n[2];
    if dz.abs() <= MOW_RESIDUAL {
        return (first, false);
    }
    let f = |t: f64| bilinear(grid, machined, p[0] + t * n[0], p[1] + t * n[1]) - (p[2] + t * n[2]);
    let (mut t0, mut f0) = (0.0, dz);
    let (mut t1, mut f1) = (first, f(first));
    let mut straddled = false;
    for _ in 0..MOW_STEPS {
        if f1.is_nan() {
            return (first, true);
        }
        if f1.abs() <= MOW_RESIDUAL || (straddled && (t1 - t0).abs() <= MOW_RESIDUAL) {
            return (t1, false);
        }
        straddled = straddled || (f0 < 0.0) != (f1 < 0.0);
        let den = f1 - f0;
        if den == 0.0 {
            break;
        }
        let t2 = t1 - f1 * (t1 - t0) / den;
        let f2 = f(t2);
        if !straddled || (f2 < 0.0) != (f1 < 0.0) {
            (t0, f0) = (t1, f1);
        } else {
            // The same side twice: halve the far end's value (Illinois).
            f0 *= 0.5;
        }
        (t1, f1) = (t2, f2);
    }
    (first, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_of_a_tilted_plane_is_measured_along_the_normal() {
        let g = Grid::covering([0.0, 0.0], [10.0, 10.0], 0.25, 1 << 20).unwrap();
        let (a, b, c) = (0.7, -0.3, 0.2);
        let mut design = vec![0.0; g.len()];
        let mut machined = vec![0.0; g.len()];
        for j in 0..g.ny {
            for i in 0..g.nx {
                let [x, y] = g.centre(i, j);
                design[j * g.nx + i] = a * x + b * y;
                machined[j * g.nx + i] = a * x + b * y + c;
            }
        }
        let l = (1.0f64 + a * a + b * b).sqrt();
        let n = [(-a / l) as f32, (-b / l) as f32, (1.0 / l) as f32];
        let normals = vec![n; g.len()];
        let vertical: Vec<f64> = machined.iter().zip(&design).map(|(m, d)| m - d).collect();
        let (dev, fallback) = normal_deviation(&g, &machined, &design, &normals, &vertical);
        // Normals are stored as f32 (7 digits): agreement to 1e-6 mm.
        let k = 20 * g.nx + 20;
        assert!((dev[k] - c / l).abs() < 1e-6, "{} vs {}", dev[k], c / l);
        // Blades near the rim leave the grid and keep the first-order value (the same
        // here, a plane).
        assert!(fallback < g.len() / 4);
        assert!(dev.iter().all(|d| (d - c / l).abs() < 1e-6));
    }

    #[test]
    fn a_dip_is_found_along_the_tilted_blade() {
        // Flat design, machined surface sloping up along x: a blade tilted toward +x
        // meets it further out than the vertical deviation says.
        let g = Grid::covering([0.0, 0.0], [10.0, 2.0], 0.1, 1 << 20).unwrap();
        let design = vec![0.0; g.len()];
        let machined: Vec<f64> = (0..g.len()).map(|k| 0.1 * (g.x(k % g.nx) - 4.0)).collect();
        let n = [0.6f32, 0.0, 0.8];
        let normals = vec![n; g.len()];
        let vertical: Vec<f64> = machined.clone();
        let (dev, _) = normal_deviation(&g, &machined, &design, &normals, &vertical);
        // Line z = 0.1 (x - 4) meets the blade (x0 + 0.6 t, 0.8 t):
        // 0.8 t = 0.1 (x0 + 0.6 t - 4) -> t = 0.1 (x0 - 4) / 0.74.
        let k = 5 * g.nx + 60;
        let x0 = g.x(60);
        assert!(
            (dev[k] - 0.1 * (x0 - 4.0) / 0.74).abs() < 1e-6,
            "{}",
            dev[k]
        );
        assert!(bilinear(&g, &machined, -1.0, 1.0).is_nan());
    }

    #[test]
    fn a_blade_past_an_uncut_column_at_a_wall_foot_finds_its_root() {
        // One column of cells left 17 mm high beside cut ones (a sliver at the foot
        // of a wall): from its centre, a blade nearly horizontal (a fillet's top)
        // leaves the column within one cell. The machined surface along the blade is
        // the straight line between the centres (the heights vary with x only), so
        // the root is that line's crossing with the blade, found here by bisection.
        let g = Grid::covering([0.0, 0.0], [4.0, 1.0], 0.05, 1 << 20).unwrap();
        let wall = 10;
        let high = |i: usize| if i <= wall { 19.917 } else { 0.0 };
        let design_z = 2.77;
        let machined: Vec<f64> = (0..g.len()).map(|k| high(k % g.nx)).collect();
        let design = vec![design_z; g.len()];
        let (nx, nz) = (0.996f64, 0.0891f64);
        let l = nx.hypot(nz);
        let normals = vec![[(nx / l) as f32, 0.0, (nz / l) as f32]; g.len()];
        let n = normals[0].map(f64::from);
        let vertical: Vec<f64> = machined.iter().zip(&design).map(|(m, d)| m - d).collect();
        let (dev, _) = normal_deviation(&g, &machined, &design, &normals, &vertical);
        let k = 10 * g.nx + wall;
        let x0 = g.x(wall);
        // Along the blade x = x0 + t n_x: height 19.917 falling linearly to 0 over one cell.
        let line = |t: f64| 19.917 * (1.0 - (t * n[0] / 0.05).clamp(0.0, 1.0));
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if line(mid) - (design_z + mid * n[2]) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!(x0 > 0.0);
        assert!((dev[k] - lo).abs() < 1e-9, "{} against {lo}", dev[k]);
        assert!(dev[k] < 0.05, "the blade leaves the column within a cell");
    }
}
