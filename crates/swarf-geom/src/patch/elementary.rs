//! The elementary surfaces of CAD files (plane, cylinder, cone, sphere, torus) as exact
//! NURBS patches over a given parameter window.
//!
//! A plane is a bilinear patch. The others are surfaces of revolution about the
//! frame's `z` axis: a profile curve in the `(rho, z)` half-plane (a line for the
//! cylinder and the cone, a circular arc for the sphere and the torus) swept by a
//! circular arc in `u`. Both arcs are rational quadratic B-splines (NURBS Book
//! section 7.5, algorithm A7.1: at most 90 degrees a segment, middle control point
//! at `1 / cos(d/2)` from the centre with weight `cos(d/2)`, `d` the segment's sweep),
//! and the tensor product `P_ij = (rho_j c_i, z_j)`, `w_ij = w_i w_j` is exactly the
//! surface of revolution (section 8.5: the `u` denominator factors out of each
//! profile term). The knots of an arc are the segment ends' angles in radians, so a
//! patch's `u` equals the angle at those knots (between them it differs slightly:
//! the rational arc is not arc-length parametrised); the `v` knots are heights (mm)
//! for lines and angles for arcs.

use super::Patch;
use crate::error::GeomError;
use crate::math::{Point3, Vec3};

/// A right-handed orthonormal frame: origin and axes (`z` is the axis of revolution).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Origin, mm.
    pub origin: Point3,
    /// Unit x axis (angle 0 of a surface of revolution).
    pub x: Vec3,
    /// Unit y axis.
    pub y: Vec3,
    /// Unit z axis (the axis of revolution, the plane's normal).
    pub z: Vec3,
}

impl Frame {
    /// The world point of local coordinates `(a, b, c)`.
    pub fn to_world(&self, a: f64, b: f64, c: f64) -> Point3 {
        self.origin + self.x * a + self.y * b + self.z * c
    }

    /// Local coordinates of world point `p`.
    pub fn to_local(&self, p: &Point3) -> [f64; 3] {
        let d = p - self.origin;
        [d.dot(&self.x), d.dot(&self.y), d.dot(&self.z)]
    }
}

/// A rational curve in the `(rho, z)` half-plane: degree, knots, points, weights.
struct Profile {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<[f64; 2]>,
    weights: Vec<f64>,
}

/// The circular arc of `radius` about `center` from angle `a0` to `a1` (radians,
/// `a1 > a0`) as a rational quadratic B-spline whose knots are the segment angles.
fn arc(center: [f64; 2], radius: f64, a0: f64, a1: f64) -> Profile {
    let n = ((a1 - a0) / std::f64::consts::FRAC_PI_2 - 1e-9)
        .ceil()
        .max(1.0) as usize;
    let d = (a1 - a0) / n as f64;
    let w = (d / 2.0).cos();
    let at = |a: f64, s: f64| [center[0] + s * a.cos(), center[1] + s * a.sin()];
    let mut knots = vec![a0; 3];
    let mut points = vec![at(a0, radius)];
    let mut weights = vec![1.0];
    for k in 0..n {
        let s = a0 + d * k as f64;
        let e = if k + 1 == n { a1 } else { s + d };
        points.push(at(s + d / 2.0, radius / w));
        points.push(at(e, radius));
        weights.extend([w, 1.0]);
        knots.extend(std::iter::repeat_n(e, if k + 1 == n { 3 } else { 2 }));
    }
    Profile {
        degree: 2,
        knots,
        points,
        weights,
    }
}

/// The parameter of a patch built here (its `u`, or the `v` of a sphere or torus)
/// at which its arc over `angles` reaches `angle` (radians, within `angles`): the
/// inverse of the rational arc's parametrisation. On a segment of sweep `d` centred
/// at `m`, `tan((angle - m) / 2) = s tan(d / 4)` with `s = 2t - 1` the local
/// parameter (substitute into the segment's rational form), so `t` is closed-form.
pub fn arc_parameter(angles: [f64; 2], angle: f64) -> f64 {
    let (a0, a1) = (angles[0], angles[1]);
    let n = ((a1 - a0) / std::f64::consts::FRAC_PI_2 - 1e-9)
        .ceil()
        .max(1.0);
    let d = (a1 - a0) / n;
    let k = ((angle - a0) / d).floor().clamp(0.0, n - 1.0);
    let s = a0 + k * d;
    let local = angle.clamp(a0, a1) - (s + d / 2.0);
    let t = 0.5 * (1.0 + (local / 2.0).tan() / (d / 4.0).tan());
    if k + 1.0 == n && t >= 1.0 {
        a1
    } else {
        s + t.clamp(0.0, 1.0) * d
    }
}

/// The straight profile from `(rho0, z0)` to `(rho1, z1)`, parametrised over `[t0, t1]`.
fn line(p0: [f64; 2], p1: [f64; 2], t: [f64; 2]) -> Profile {
    Profile {
        degree: 1,
        knots: vec![t[0], t[0], t[1], t[1]],
        points: vec![p0, p1],
        weights: vec![1.0, 1.0],
    }
}

fn check_range(name: &str, r: [f64; 2]) -> Result<(), GeomError> {
    if r.iter().all(|x| x.is_finite()) && r[1] > r[0] {
        Ok(())
    } else {
        Err(GeomError::patch(
            name,
            format!(
                "expected a finite range with end > start, found [{}, {}]",
                r[0], r[1]
            ),
        ))
    }
}

fn check_angles(name: &str, a: [f64; 2]) -> Result<(), GeomError> {
    check_range(name, a)?;
    if a[1] - a[0] > std::f64::consts::TAU * (1.0 + 1e-12) {
        return Err(GeomError::patch(
            name,
            format!("expected at most one turn, found {} rad", a[1] - a[0]),
        ));
    }
    Ok(())
}

/// The surface of revolution of `profile` about `frame.z` over angles `angles`.
fn revolve(frame: &Frame, profile: Profile, angles: [f64; 2]) -> Result<Patch, GeomError> {
    check_angles("angles", angles)?;
    let c = arc([0.0, 0.0], 1.0, angles[0], angles[1]);
    let mut points = Vec::with_capacity(c.points.len() * profile.points.len());
    let mut weights = Vec::with_capacity(points.capacity());
    for (ci, wi) in c.points.iter().zip(&c.weights) {
        for (pj, wj) in profile.points.iter().zip(&profile.weights) {
            points.push(frame.to_world(pj[0] * ci[0], pj[0] * ci[1], pj[1]));
            weights.push(wi * wj);
        }
    }
    Patch::new(
        [2, profile.degree],
        points,
        [Some(c.knots), Some(profile.knots)],
        Some(weights),
    )
}

impl Patch {
    /// The plane of `frame` (normal `frame.z`) over local `x` in `us` and `y` in `vs`:
    /// `S(u, v) = origin + u x + v y`.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] for an empty or non-finite range.
    pub fn plane(frame: &Frame, us: [f64; 2], vs: [f64; 2]) -> Result<Patch, GeomError> {
        check_range("u", us)?;
        check_range("v", vs)?;
        let points = vec![
            frame.to_world(us[0], vs[0], 0.0),
            frame.to_world(us[0], vs[1], 0.0),
            frame.to_world(us[1], vs[0], 0.0),
            frame.to_world(us[1], vs[1], 0.0),
        ];
        let k = |r: [f64; 2]| Some(vec![r[0], r[0], r[1], r[1]]);
        Patch::new([1, 1], points, [k(us), k(vs)], None)
    }

    /// The cylinder of `radius` about `frame.z` over `angles` (radians from `frame.x`
    /// towards `frame.y`) and `heights` along the axis (mm).
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] for a bad range or radius.
    pub fn cylinder(
        frame: &Frame,
        radius: f64,
        angles: [f64; 2],
        heights: [f64; 2],
    ) -> Result<Patch, GeomError> {
        GeomError::check_positive("radius", radius)?;
        check_range("heights", heights)?;
        let p = line([radius, heights[0]], [radius, heights[1]], heights);
        revolve(frame, p, angles)
    }

    /// The cone `S(a, v) = origin + (radius + v tan(half_angle)) (cos a x + sin a y)
    /// + v z` (ISO 10303-42 `conical_surface`) over `angles` and `vs` (mm along z).
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] for a bad range, or a window crossing the apex.
    pub fn cone(
        frame: &Frame,
        radius: f64,
        half_angle: f64,
        angles: [f64; 2],
        vs: [f64; 2],
    ) -> Result<Patch, GeomError> {
        check_range("v", vs)?;
        let t = half_angle.tan();
        let r0 = radius + vs[0] * t;
        let r1 = radius + vs[1] * t;
        if !(t.is_finite()
            && r0 >= -1e-12 * radius.abs().max(1.0)
            && r1 >= -1e-12 * radius.abs().max(1.0))
        {
            return Err(GeomError::patch(
                "v",
                format!("the cone's window [{}, {}] crosses its apex", vs[0], vs[1]),
            ));
        }
        let p = line([r0.max(0.0), vs[0]], [r1.max(0.0), vs[1]], vs);
        revolve(frame, p, angles)
    }

    /// The sphere of `radius` about `frame.origin` over longitudes `angles` and
    /// latitudes `lats` (radians, within `[-pi/2, pi/2]`).
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] for a bad range or radius.
    pub fn sphere(
        frame: &Frame,
        radius: f64,
        angles: [f64; 2],
        lats: [f64; 2],
    ) -> Result<Patch, GeomError> {
        GeomError::check_positive("radius", radius)?;
        check_range("lats", lats)?;
        let h = std::f64::consts::FRAC_PI_2 * (1.0 + 1e-12);
        if lats[0] < -h || lats[1] > h {
            return Err(GeomError::patch(
                "lats",
                "expected latitudes within [-pi/2, pi/2]",
            ));
        }
        revolve(frame, arc([0.0, 0.0], radius, lats[0], lats[1]), angles)
    }

    /// The torus of `major` radius (axis to tube centre) and `minor` radius (tube)
    /// over `angles` about the axis and `tube` angles (0 = outermost, towards +z).
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] for a bad range or radius.
    pub fn torus(
        frame: &Frame,
        major: f64,
        minor: f64,
        angles: [f64; 2],
        tube: [f64; 2],
    ) -> Result<Patch, GeomError> {
        GeomError::check_positive("major", major)?;
        GeomError::check_positive("minor", minor)?;
        check_angles("tube", tube)?;
        revolve(frame, arc([major, 0.0], minor, tube[0], tube[1]), angles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    fn frame() -> Frame {
        let z = Vec3::new(1.0, 2.0, 2.0) / 3.0;
        let x = Vec3::new(2.0, 1.0, -2.0) / 3.0;
        Frame {
            origin: Point3::new(1.0, -2.0, 3.0),
            x,
            y: z.cross(&x),
            z,
        }
    }

    /// Points on a grid of the patch, in the frame's local coordinates.
    fn locals(p: &Patch, f: &Frame) -> Vec<[f64; 3]> {
        let [du, dv] = p.domain();
        let mut out = Vec::new();
        for i in 0..=13 {
            for j in 0..=7 {
                let u = du[0] + (du[1] - du[0]) * i as f64 / 13.0;
                let v = dv[0] + (dv[1] - dv[0]) * j as f64 / 7.0;
                out.push(f.to_local(&p.eval(u, v)));
            }
        }
        out
    }

    #[test]
    fn cylinder_points_lie_at_the_radius_and_cover_the_angles() {
        let f = frame();
        let p = Patch::cylinder(&f, 2.5, [-0.3, TAU - 0.3], [1.0, 4.0]).unwrap();
        for l in locals(&p, &f) {
            assert!(((l[0].hypot(l[1])) - 2.5).abs() < 1e-12, "{l:?}");
            assert!(l[2] >= 1.0 - 1e-12 && l[2] <= 4.0 + 1e-12);
        }
        // At knots u equals the angle exactly.
        let q = f.to_local(&p.eval(-0.3 + TAU / 4.0, 2.0));
        assert!((q[1].atan2(q[0]) - (-0.3 + TAU / 4.0)).abs() < 1e-12);
        assert!((q[2] - 2.0).abs() < 1e-12);
    }

    #[test]
    fn cone_follows_its_closed_form() {
        let f = frame();
        let (r, a) = (3.0, 0.4);
        let p = Patch::cone(&f, r, a, [0.0, 2.0], [-2.0, 5.0]).unwrap();
        for l in locals(&p, &f) {
            let rho = r + l[2] * a.tan();
            assert!((l[0].hypot(l[1]) - rho).abs() < 1e-12, "{l:?}");
        }
        assert!(Patch::cone(&f, r, a, [0.0, 1.0], [-10.0, 1.0]).is_err());
    }

    #[test]
    fn sphere_and_torus_points_satisfy_their_implicit_equations() {
        let f = frame();
        let s = Patch::sphere(&f, 4.0, [0.0, TAU], [-FRAC_PI_2, FRAC_PI_2]).unwrap();
        for l in locals(&s, &f) {
            assert!(((l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt() - 4.0).abs() < 1e-12);
        }
        let t = Patch::torus(&f, 5.0, 1.5, [0.0, TAU], [-PI, PI]).unwrap();
        let mut zmax: f64 = 0.0;
        for l in locals(&t, &f) {
            let rho = l[0].hypot(l[1]);
            assert!(((rho - 5.0).hypot(l[2]) - 1.5).abs() < 1e-12, "{l:?}");
            zmax = zmax.max(l[2]);
        }
        assert!(zmax > 1.4);
        // Knot angles in v are exact: tube angle pi/2 is the top of the tube.
        let q = f.to_local(&t.eval(0.0, FRAC_PI_2));
        assert!(
            (q[0] - 5.0).abs() < 1e-12 && (q[2] - 1.5).abs() < 1e-12,
            "{q:?}"
        );
    }

    #[test]
    fn arc_parameter_inverts_the_arc() {
        let f = frame();
        let w = [-0.7, 4.9];
        let p = Patch::cylinder(&f, 2.0, w, [0.0, 1.0]).unwrap();
        for k in 0..=40 {
            let a = w[0] + (w[1] - w[0]) * k as f64 / 40.0;
            let q = f.to_local(&p.eval(arc_parameter(w, a), 0.5));
            let back = q[1].atan2(q[0]);
            let diff = (back - a).rem_euclid(TAU);
            assert!(diff.min(TAU - diff) < 1e-12, "{a} {back}");
        }
    }

    #[test]
    fn plane_is_the_frame_map() {
        let f = frame();
        let p = Patch::plane(&f, [-1.0, 2.0], [0.5, 3.0]).unwrap();
        let q = p.eval(0.25, 1.75);
        assert!((q - f.to_world(0.25, 1.75, 0.0)).norm() < 1e-12);
        assert!(Patch::plane(&f, [1.0, 1.0], [0.0, 1.0]).is_err());
        assert!(Patch::torus(&f, 1.0, 0.5, [0.0, 7.0], [0.0, 1.0]).is_err());
    }
}
