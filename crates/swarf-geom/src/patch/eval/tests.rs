//! Tests of the evaluator: closed forms, central differences, grids bit for bit equal
//! to single points, clamping, exact quadrics, and a de Casteljau oracle for random
//! rational Bezier patches.

use super::super::fixtures::{
    die, die_closed_form, nurbs_spline, quarter_cylinder, shared_patches, sphere_octant,
};
use super::*;
use proptest::prelude::*;

fn grid(n: u32) -> impl Iterator<Item = (f64, f64)> {
    (0..=n).flat_map(move |i| {
        (0..=n).map(move |j| (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n)))
    })
}

fn near(a: &Vec3, b: &Vec3, eps: f64) -> bool {
    (a - b).norm() <= eps
}

#[test]
fn die_matches_its_closed_form_and_hand_derivatives() {
    let p = die();
    for (u, v) in grid(10) {
        let d = p.derivs(u, v);
        let want = Vec3::from(die_closed_form(u, v));
        assert!(near(&d.point.coords, &want, 1e-9), "point at ({u}, {v})");
        assert!(
            near(&p.eval(u, v).coords, &want, 1e-9),
            "eval at ({u}, {v})"
        );
        let du = Vec3::new(
            0.0,
            -131.3 + 56.2 * u,
            5.9 * (2.0 * u * v * v + 2.0 * u * v) - 3.9 * v * v + 152.4 * u - 27.3 * v - 50.8,
        );
        let dv = Vec3::new(
            88.9 + 11.2 * v,
            0.0,
            5.9 * (2.0 * u * u * v + u * u) - 7.8 * u * v + 13.4 * v - 27.3 * u + 25.0,
        );
        let duu = Vec3::new(0.0, 56.2, 5.9 * (2.0 * v * v + 2.0 * v) + 152.4);
        let duv = Vec3::new(0.0, 0.0, 5.9 * (4.0 * u * v + 2.0 * u) - 7.8 * v - 27.3);
        let dvv = Vec3::new(11.2, 0.0, 5.9 * 2.0 * u * u - 7.8 * u + 13.4);
        assert!(
            near(&d.du, &du, 1e-9) && near(&d.dv, &dv, 1e-9),
            "first at ({u}, {v})"
        );
        assert!(near(&d.duu, &duu, 1e-9), "duu at ({u}, {v})");
        assert!(
            near(&d.duv, &duv, 1e-9) && near(&d.dvv, &dvv, 1e-9),
            "({u}, {v})"
        );
    }
}

/// Central differences of `eval` for the first and of `derivs` for the second partials.
fn check_against_differences(p: &Patch, name: &str) {
    let [[u0, u1], [v0, v1]] = p.domain();
    let (hu, hv) = (1e-6 * (u1 - u0), 1e-6 * (v1 - v0));
    let scale = p.control_box().size().norm();
    for (fu, fv) in grid(8) {
        let u = u0 + (u1 - u0) * (0.01 + 0.98 * fu);
        let v = v0 + (v1 - v0) * (0.01 + 0.98 * fv);
        let d = p.derivs(u, v);
        let du = (p.eval(u + hu, v) - p.eval(u - hu, v)) / (2.0 * hu);
        let dv = (p.eval(u, v + hv) - p.eval(u, v - hv)) / (2.0 * hv);
        let eps1 = 1e-6 * scale / (u1 - u0).min(v1 - v0);
        assert!(
            near(&d.du, &du, eps1) && near(&d.dv, &dv, eps1),
            "{name} first at ({u}, {v})"
        );
        let (a, b) = (p.derivs(u + hu, v), p.derivs(u - hu, v));
        let (c, e) = (p.derivs(u, v + hv), p.derivs(u, v - hv));
        let eps2 = eps1 / (u1 - u0).min(v1 - v0);
        assert!(
            near(&d.duu, &((a.du - b.du) / (2.0 * hu)), eps2),
            "{name} duu at ({u}, {v})"
        );
        assert!(
            near(&d.duv, &((a.dv - b.dv) / (2.0 * hu)), eps2),
            "{name} duv at ({u}, {v})"
        );
        assert!(
            near(&d.duv, &((c.du - e.du) / (2.0 * hv)), eps2),
            "{name} dvu at ({u}, {v})"
        );
        assert!(
            near(&d.dvv, &((c.dv - e.dv) / (2.0 * hv)), eps2),
            "{name} dvv at ({u}, {v})"
        );
        assert_eq!(d.point, p.eval(u, v), "{name}: eval and derivs agree");
    }
}

#[test]
fn derivatives_of_every_shared_part_match_central_differences() {
    for (name, p) in shared_patches() {
        check_against_differences(&p, name);
    }
    check_against_differences(&nurbs_spline(), "nurbs spline");
    check_against_differences(&sphere_octant(10.0), "sphere");
    check_against_differences(&quarter_cylinder(5.0, 3.0), "cylinder");
}

/// `n + 1` parameters across `[lo, hi]` and two outside it (clamped).
fn across(lo: f64, hi: f64, n: u32) -> Vec<f64> {
    (0..=n)
        .map(|k| lo + (hi - lo) * f64::from(k) / f64::from(n))
        .chain([lo - 1.0, hi + 2.0])
        .collect()
}

/// Every grid value is bit for bit `derivs` there, each visited once in order.
fn check_grid(p: &Patch, name: &str) {
    let [[u0, u1], [v0, v1]] = p.domain();
    let (us, vs) = (across(u0, u1, 13), across(v0, v1, 9));
    let mut next = 0;
    p.derivs_on_grid(&us, &vs, |j, column| {
        assert_eq!(
            (j, column.len()),
            (next, us.len()),
            "{name}: columns in order"
        );
        for (i, d) in column.iter().enumerate() {
            assert_eq!(*d, p.derivs(us[i], vs[j]), "{name} at ({i}, {j})");
        }
        next += 1;
    });
    assert_eq!(next, vs.len(), "{name}: every column");
}

#[test]
fn grid_values_are_those_of_derivs() {
    for (name, p) in shared_patches() {
        check_grid(&p, name);
    }
    check_grid(&nurbs_spline(), "nurbs spline");
    check_grid(&sphere_octant(10.0), "sphere");
    check_grid(&quarter_cylinder(5.0, 3.0), "cylinder");
}

#[test]
fn parameters_are_clamped_into_the_domain() {
    let p = nurbs_spline();
    assert_eq!(p.eval(-3.0, 9.0), p.eval(0.0, 3.0));
    assert_eq!(p.derivs(7.0, -2.0), p.derivs(2.5, -1.0));
    assert!(
        p.eval(f64::NAN, 0.5).x.is_nan(),
        "NaN in, NaN out, no panic"
    );
}

#[test]
fn exact_quadrics() {
    let s = sphere_octant(7.5);
    let c = quarter_cylinder(5.0, 2.0);
    for (u, v) in grid(13) {
        let u = (u * 1.37).fract();
        assert!(
            (s.eval(u, v).coords.norm() - 7.5).abs() < 1e-12,
            "sphere at ({u}, {v})"
        );
        let q = c.eval(u, v);
        assert!((q.x.hypot(q.y) - 5.0).abs() < 1e-12 && (q.z - 2.0 * v).abs() < 1e-12);
    }
}

/// De Casteljau on homogeneous points in both directions: the Bezier oracle.
fn de_casteljau(deg: [usize; 2], hom: &[Vector4<f64>], u: f64, v: f64) -> Point3 {
    let curve = |mut c: Vec<Vector4<f64>>, t: f64| {
        for k in (1..c.len()).rev() {
            for i in 0..k {
                c[i] = c[i] * (1.0 - t) + c[i + 1] * t;
            }
        }
        c[0]
    };
    let rows: Vec<_> = (0..=deg[0])
        .map(|i| curve(hom[i * (deg[1] + 1)..(i + 1) * (deg[1] + 1)].to_vec(), v))
        .collect();
    let h = curve(rows, u);
    Point3::new(h.x / h.w, h.y / h.w, h.z / h.w)
}

fn random_bezier() -> impl Strategy<Value = (Patch, Vec<Vector4<f64>>)> {
    (1usize..6, 1usize..6, any::<bool>()).prop_flat_map(|(du, dv, rational)| {
        let n = (du + 1) * (dv + 1);
        (
            proptest::collection::vec((-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64), n),
            proptest::collection::vec(0.2..3.0f64, n),
        )
            .prop_map(move |(raw, w)| {
                let pts: Vec<Point3> = raw.iter().map(|c| Point3::new(c.0, c.1, c.2)).collect();
                let w = if rational { w } else { vec![1.0; n] };
                let hom = pts
                    .iter()
                    .zip(&w)
                    .map(|(q, w)| homogeneous(q, *w))
                    .collect();
                let p = Patch::new([du, dv], pts, [None, None], Some(w)).unwrap();
                (p, hom)
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn basis_evaluation_agrees_with_de_casteljau(
        (p, hom) in random_bezier(), u in 0.0..=1.0f64, v in 0.0..=1.0f64,
    ) {
        let want = de_casteljau(p.degree(), &hom, u, v);
        prop_assert!((p.eval(u, v) - want).norm() < 1e-10);
        prop_assert!((p.derivs(u, v).point - want).norm() < 1e-10);
    }

    #[test]
    fn grid_agrees_with_derivs_for_any_degree((p, _) in random_bezier()) {
        check_grid(&p, "random");
    }

    #[test]
    fn bezier_on_another_range_is_the_same_surface(
        (p, _) in random_bezier(), a in -10.0..10.0f64, len in 0.1..20.0f64,
        c in -10.0..10.0f64, len_v in 0.1..20.0f64, fu in 0.0..=1.0f64, fv in 0.0..=1.0f64,
    ) {
        let [du, dv] = p.degree();
        let clamped = |lo: f64, hi: f64, deg: usize| {
            let mut k = vec![lo; deg + 1];
            k.extend(std::iter::repeat_n(hi, deg + 1));
            Some(k)
        };
        let knots = [clamped(a, a + len, du), clamped(c, c + len_v, dv)];
        let w = p.weights().map(<[f64]>::to_vec);
        let q = Patch::new(p.degree(), p.points().to_vec(), knots, w).unwrap();
        let (s, t) = (a + len * fu, c + len_v * fv);
        let (dp, dq) = (p.derivs(fu, fv), q.derivs(s, t));
        let eps = 1e-9 * (1.0 + dp.duu.norm() + dp.dvv.norm() + dp.duv.norm());
        prop_assert!((dp.point - dq.point).norm() < 1e-10);
        prop_assert!((dp.du - dq.du * len).norm() < eps);
        prop_assert!((dp.dv - dq.dv * len_v).norm() < eps);
        prop_assert!((dp.duu - dq.duu * len * len).norm() < eps);
        prop_assert!((dp.duv - dq.duv * len * len_v).norm() < eps);
        prop_assert!((dp.dvv - dq.dvv * len_v * len_v).norm() < eps);
    }
}
