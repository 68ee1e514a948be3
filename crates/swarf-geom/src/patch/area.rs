//! The area of a face: a patch, whole or inside its trimming loops.
//!
//! `A = ∬_D |S_u × S_v| du dv`. With `F(u, v) = ∫_{u_0}^{u} |S_u × S_v|(s, v) ds`,
//! `∂F/∂u` is the integrand, so Green's theorem turns the area into a line integral
//! around the domain's boundary, `A = ∮_{∂D} F dv` (counter-clockwise outer loop,
//! clockwise holes, as [`Trim`] orients them). Each loop edge is a straight segment in
//! `(u, v)`: `∫ F(u(t), v(t)) v'(t) dt` by Gauss-Legendre on the segment cut where it
//! crosses a knot line (where the integrand's smoothness breaks), and `F` by
//! Gauss-Legendre on `[u_0, u]` cut at the knots and in [`PIECES_PER_SPAN`] per span
//! (the integrand is smooth inside a span). An untrimmed patch is its domain
//! rectangle. The trimming loops are the readers' polylines, so the area is exact for
//! them and within their chordal error of the exact trim.

use super::Patch;
use crate::trim::{Trim, Uv};

/// Gauss-Legendre nodes and weights on `[-1, 1]`, 8 points.
const GAUSS: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];
/// Pieces of each knot span in `u` for the inner integral.
const PIECES_PER_SPAN: usize = 4;
/// Gauss pieces per loop edge for the outer integral.
const PIECES_PER_EDGE: usize = 2;

impl Patch {
    /// The area of the face: the whole patch, or the part inside `trim`.
    ///
    /// # Units
    /// mm².
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3, trim::Trim};
    /// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    /// let plate = Patch::bezier([1, 1], vec![p(0.0, 0.0), p(0.0, 20.0), p(10.0, 0.0), p(10.0, 20.0)]).unwrap();
    /// assert!((plate.area(None) - 200.0).abs() < 1e-9);
    /// let half = Trim::new(vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]).unwrap();
    /// assert!((plate.area(Some(&half)) - 100.0).abs() < 1e-9);
    /// ```
    pub fn area(&self, trim: Option<&Trim>) -> f64 {
        let [[u0, u1], [v0, v1]] = self.domain();
        let rectangle = [vec![[u0, v0], [u1, v0], [u1, v1], [u0, v1]]];
        let loops: &[Vec<Uv>] = match trim {
            Some(t) => t.loops(),
            None => &rectangle,
        };
        let breaks = self.u_breaks();
        let knots = [0, 1].map(|d| {
            let p = self.degree()[d];
            let k = self.knots(d);
            k[p..k.len() - p].to_vec()
        });
        let mut sum = 0.0;
        for l in loops {
            for k in 0..l.len() {
                let (a, b) = (l[k], l[(k + 1) % l.len()]);
                let dv = b[1] - a[1];
                if dv == 0.0 {
                    continue;
                }
                // The integrand is smooth between the knots the edge crosses.
                let mut ts = vec![0.0, 1.0];
                for d in 0..2 {
                    let span = b[d] - a[d];
                    if span != 0.0 {
                        ts.extend(
                            knots[d]
                                .iter()
                                .map(|x| (x - a[d]) / span)
                                .filter(|t| *t > 0.0 && *t < 1.0),
                        );
                    }
                }
                ts.sort_by(f64::total_cmp);
                ts.dedup();
                for w in ts.windows(2) {
                    for piece in 0..PIECES_PER_EDGE {
                        let f = |i: usize| w[0] + (w[1] - w[0]) * i as f64 / PIECES_PER_EDGE as f64;
                        let (s0, s1) = (f(piece), f(piece + 1));
                        for (x, g) in GAUSS {
                            let t = s0 + (s1 - s0) * 0.5 * (x + 1.0);
                            let u = a[0] + t * (b[0] - a[0]);
                            let v = a[1] + t * dv;
                            sum += g * 0.5 * (s1 - s0) * dv * self.area_to(&breaks, u, v);
                        }
                    }
                }
            }
        }
        sum
    }

    /// Knots of `u` (distinct, with the domain's ends), each span cut in
    /// [`PIECES_PER_SPAN`].
    fn u_breaks(&self) -> Vec<f64> {
        let p = self.degree()[0];
        let k = self.knots(0);
        let mut out = vec![k[p]];
        for w in k[p..k.len() - p].windows(2).filter(|w| w[1] > w[0]) {
            for i in 1..=PIECES_PER_SPAN {
                out.push(w[0] + (w[1] - w[0]) * i as f64 / PIECES_PER_SPAN as f64);
            }
        }
        out
    }

    /// `F(u, v)`: the area element integrated along `u` from the domain's start.
    fn area_to(&self, breaks: &[f64], u: f64, v: f64) -> f64 {
        let mut sum = 0.0;
        for w in breaks.windows(2) {
            let (lo, hi) = (w[0], w[1].min(u));
            if hi <= lo {
                break;
            }
            for (x, g) in GAUSS {
                let s = lo + (hi - lo) * 0.5 * (x + 1.0);
                let d = self.derivs(s, v);
                sum += g * 0.5 * (hi - lo) * d.du.cross(&d.dv).norm();
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use crate::patch::fixtures::{quarter_cylinder, sphere_octant, wave};
    use crate::trim::Trim;

    #[test]
    fn a_full_torus_of_several_spans_has_its_closed_form() {
        // R = 10, r = 3 about z, as rational biquadratic circles of 4 spans each way.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let ring = [
            (1.0, 0.0, 1.0),
            (1.0, 1.0, h),
            (0.0, 1.0, 1.0),
            (-1.0, 1.0, h),
            (-1.0, 0.0, 1.0),
            (-1.0, -1.0, h),
            (0.0, -1.0, 1.0),
            (1.0, -1.0, h),
            (1.0, 0.0, 1.0),
        ];
        let mut pts = Vec::new();
        let mut ws = Vec::new();
        for (cu, su, wu) in ring {
            for (cv, sv, wv) in ring {
                let rho = 10.0 + 3.0 * cv;
                pts.push(crate::math::Point3::new(rho * cu, rho * su, 3.0 * sv));
                ws.push(wu * wv);
            }
        }
        let k = vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.];
        let torus = crate::Patch::new([2, 2], pts, [Some(k.clone()), Some(k)], Some(ws)).unwrap();
        let want = 4.0 * std::f64::consts::PI.powi(2) * 30.0;
        assert!(
            (torus.area(None) - want).abs() < 1e-9 * want,
            "{} vs {want}",
            torus.area(None)
        );
    }

    #[test]
    fn closed_forms_of_a_cylinder_and_a_sphere() {
        let cyl = quarter_cylinder(30.0, 12.0);
        let want = std::f64::consts::FRAC_PI_2 * 30.0 * 12.0;
        assert!(
            (cyl.area(None) - want).abs() < 1e-9 * want,
            "{}",
            cyl.area(None)
        );
        let s = sphere_octant(10.0);
        let want = std::f64::consts::PI * 100.0 / 2.0;
        assert!(
            (s.area(None) - want).abs() < 1e-9 * want,
            "{}",
            s.area(None)
        );
    }

    #[test]
    fn a_trimmed_wave_has_the_area_of_a_fine_tessellation() {
        let w = wave();
        let [[u0, u1], [v0, v1]] = w.domain();
        let s = |a: f64, b: f64| [u0 + a * (u1 - u0), v0 + b * (v1 - v0)];
        let hole: Vec<[f64; 2]> = (0..300)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 300.0;
                s(0.5 + 0.2 * t.cos(), 0.5 + 0.2 * t.sin())
            })
            .collect();
        let outer = vec![
            s(0.0, 0.0),
            s(0.7, 0.0),
            s(1.0, 0.3),
            s(1.0, 1.0),
            s(0.0, 1.0),
        ];
        let trim = Trim::new(vec![outer, hole]).unwrap();
        let exact = w.area(Some(&trim));

        let mesh_area = |tol: f64| {
            let m = w.tessellate_trimmed(&trim, tol).unwrap();
            m.triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| m.vertices[i as usize]);
                    0.5 * (b - a).cross(&(c - a)).norm()
                })
                .sum::<f64>()
        };
        let errors = [1e-2, 1e-3, 1e-4].map(|tol| (exact - mesh_area(tol)).abs());
        assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
        assert!(errors[2] / exact < 5e-7, "{errors:?} of {exact}");
        let whole = w.area(None);
        let rect = Trim::new(vec![vec![
            s(0.0, 0.0),
            s(1.0, 0.0),
            s(1.0, 1.0),
            s(0.0, 1.0),
        ]])
        .unwrap();
        assert!((w.area(Some(&rect)) - whole).abs() < 1e-9 * whole);
    }
}
