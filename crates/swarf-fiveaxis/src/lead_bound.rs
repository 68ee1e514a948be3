//! The least lead angle the design's curvature allows: a bound that every positioning
//! of an inclined torus must respect, found before any gouge check (thesis 000 ch. 7-8:
//! "gouging can be defined as the interference of the back of the tool").
//!
//! **Derivation.** At a CC point with unit normal `n` (out of the material) and unit
//! tangent feed `f`, the inclined tool's axis `a = cos(alpha) n + sin(alpha) f` lies in
//! the plane of `n` and `f` ([`crate::inclined`], eq. 7.3), so that plane is a meridian
//! plane of the torus (major radius `R`, axis to insert centre; insert radius `r`): it
//! cuts the torus in two insert circles. The front one touches the design at the CC
//! point, centre `C1 = CC + r n`; the back one has its centre
//! `C2 = C1 + 2R (sin(alpha) n - cos(alpha) f)`. Replace the design's normal section in
//! that plane by its osculating circle: radius `rho = 1 / k`, `k` the normal curvature
//! along `f`, centre `O = CC + rho n` when the design is concave there (`k > 0`, bending
//! toward the tool). The tool's section lies inside that circle iff both insert circles
//! do (the flat bottom between them is a chord of the disc `|X - O| <= rho - r` moved
//! by `r`), i.e. iff `|C2 - O| <= rho - r`. With `rho' = rho - r`,
//!
//! ```text
//! |C2 - O|^2 = 4 R^2 - 4 R rho' sin(alpha) + rho'^2 <= rho'^2
//!   <=>  sin(alpha) >= R / (rho - r)
//! ```
//!
//! the same as asking that the circle through both inserts, of radius `R / sin(alpha) +
//! r` (the tool's effective cutting radius in the feed plane), be no larger than `rho`.
//! So the lead is at least `asin(R / (rho - r))`; convex or flat along the feed
//! (`k <= 0`) it is 0; where `rho < R + r` no lead below 90 degrees fits (the tool
//! cannot follow the surface there, [`LeadBound::unfit`]). The bound grows with `k`, so
//! its maximum over a path sits at the largest concave curvature along the feed.
//!
//! The bound holds for a tool without side tilt (with a tilt the feed plane is no
//! longer a meridian plane). It is local: the osculating circle stands for the design
//! in the feed plane, and only the bottom of the tool (inserts and flat) is compared
//! (the side lines, parallel to `a` at `R + r` from it, leave a circle of radius
//! `rho >= R + r` only about `rho` above the contact, far above a flute).
//!
//! **Cutters** ([`TorusBottom::of`]): bull `(R, r) = (radius - corner, corner)`; ball
//! `(0, radius)` (bound 0 where `rho >= r`); flat `(radius, 0)`; tapered ball
//! `(0, tip_radius)` (its ball tip, which cuts at leads below `90 - half_angle`
//! degrees); an APT tool with a flat bottom (`alpha = 0`) `(e, r)`, its corner torus.
//! Cones and APT tools with a conical bottom touch with a sharp tip whose section is a
//! wedge, not a pair of circles: no bound (`None`).
//!
//! The feed direction at a CC point is the tangent of its path there: the derivative of
//! the parabola through three consecutive CC points, parametrised by chord length
//! ([`path_tangents`], second order also at the ends of a pass; the one-sided chord
//! of [`crate::inclined::feed_directions`] is first order there, and on die at 60
//! degrees it turns the bound at the end of a pass on the edge from 12.95 into 13.03
//! degrees). The normal curvature comes from the patch's exact derivatives at the
//! contact's `(u, v)` ([`swarf_geom::patch`]).

use std::f64::consts::FRAC_PI_2;
use swarf_geom::tol::LENGTH_EPS;
use swarf_geom::{Part, Point3, Vec3};
use swarf_tool::Cutter;
use swarf_toolpath::Contact;

/// The bottom of a cutter seen as a torus (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorusBottom {
    /// Distance from the axis to the insert centre `R`, mm.
    pub major: f64,
    /// Insert (corner) radius `r`, mm.
    pub minor: f64,
}

impl TorusBottom {
    /// The torus bottom of `cutter`; `None` for a cone or an APT tool with a conical
    /// bottom (module doc).
    pub fn of(cutter: &Cutter) -> Option<TorusBottom> {
        let t = |major: f64, minor: f64| Some(TorusBottom { major, minor });
        match *cutter {
            Cutter::Flat { radius, .. } => t(radius, 0.0),
            Cutter::Ball { radius, .. } => t(0.0, radius),
            Cutter::Bull { radius, corner, .. } => t(radius - corner, corner),
            Cutter::TaperBall { tip_radius, .. } => t(0.0, tip_radius),
            Cutter::Cone { .. } => None,
            Cutter::Apt(a) if a.alpha == 0.0 => t(a.e, a.r),
            Cutter::Apt(_) => None,
        }
    }

    /// The least lead angle at a point where the design's normal curvature along the
    /// feed is `k` (positive: concave, bending toward the tool): 0 for `k <= 0`,
    /// `asin(R / (1/k - r))` otherwise; `None` where no lead fits (`(R + r) k > 1`).
    ///
    /// # Units
    /// `k` in 1/mm; radians.
    ///
    /// # Example
    /// ```
    /// use swarf_fiveaxis::lead_bound::TorusBottom;
    /// let bull = TorusBottom { major: 12.7, minor: 6.35 };
    /// let lead = bull.least_lead(1.0 / 62.9).unwrap();
    /// assert!((lead.to_degrees() - 12.97).abs() < 0.01);
    /// assert_eq!(bull.least_lead(-0.1), Some(0.0));
    /// assert_eq!(bull.least_lead(1.0 / 15.0), None);
    /// ```
    pub fn least_lead(&self, k: f64) -> Option<f64> {
        if k.is_nan() {
            return None;
        }
        if k <= 0.0 {
            return Some(0.0);
        }
        if (self.major + self.minor) * k > 1.0 {
            return None;
        }
        if self.major == 0.0 {
            return Some(0.0);
        }
        let ratio = self.major * k / (1.0 - self.minor * k);
        Some(ratio.min(1.0).asin())
    }
}

/// The normal curvature of the design along `feed` at `contact` (its patch and
/// `(u, v)`), signed positive where the design is concave seen from the tool (bending
/// toward the contact's normal, out of the material). `None` for a contact without a
/// patch (a mesh face, a face index past the part's patches, non-finite parameters), at
/// a degenerate point, or for a feed along the normal.
///
/// # Units
/// 1/mm.
pub fn feed_curvature(part: &Part, contact: &Contact, feed: &Vec3) -> Option<f64> {
    let patch = part.patches.get(contact.face)?;
    let [u, v] = contact.uv;
    if !(u.is_finite() && v.is_finite()) {
        return None;
    }
    let d = patch.derivs(u, v);
    let n = d.normal()?;
    let k = d.normal_curvature(feed)?;
    Some(if n.dot(&contact.normal) < 0.0 { -k } else { k })
}

/// Tangents of a path through `points` (not normalised): at each point the derivative,
/// by chord length, of the parabola through it and its neighbours (the first three or
/// last three points at the ends; the chord for two points). A repeated point gives a
/// zero tangent there. `None` for fewer than two points.
pub fn path_tangents(points: &[Point3]) -> Option<Vec<Vec3>> {
    let n = points.len();
    if n < 2 {
        return None;
    }
    if n == 2 {
        return Some(vec![points[1] - points[0]; 2]);
    }
    Some(
        (0..n)
            .map(|i| {
                let m = i.clamp(1, n - 2);
                let (a, b, c) = (points[m - 1], points[m], points[m + 1]);
                let (d1, d2) = (b - a, c - b);
                let (h1, h2) = (d1.norm(), d2.norm());
                if h1 <= LENGTH_EPS || h2 <= LENGTH_EPS {
                    return d1 + d2;
                }
                // Slopes of the two chords, and the parabola's slope at a, b or c.
                let (s1, s2) = (d1 / h1, d2 / h2);
                let curve = (s2 - s1) / (h1 + h2);
                match i.cmp(&m) {
                    std::cmp::Ordering::Less => s1 - curve * h1,
                    std::cmp::Ordering::Equal => s1 + curve * h1,
                    std::cmp::Ordering::Greater => s2 + curve * h2,
                }
            })
            .collect(),
    )
}

/// The largest local lead bound over a set of CC paths, and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeadBound {
    /// The least lead any positioning can have on these paths, radians: the maximum
    /// over the CC points of the bound at each, `pi / 2` when the tool cannot fit
    /// somewhere.
    pub lead: f64,
    /// The CC point of the largest concave curvature along the feed (where `lead` is
    /// reached), mm.
    pub at: Point3,
    /// Its pass and point index.
    pub at_index: [usize; 2],
    /// The design's radius of curvature along the feed there, mm (infinite where no
    /// point is concave).
    pub radius: f64,
    /// CC points where no lead fits (concave radius along the feed below `R + r`).
    pub unfit: usize,
    /// CC points evaluated (those with a patch, a regular normal and a feed direction).
    pub points: usize,
}

/// The local lead bound of `cutter` on the CC paths `cc` of `part` (module doc): the
/// bound at every CC point from the design's normal curvature along the feed, and its
/// maximum. `None` for a cutter without a torus bottom ([`TorusBottom::of`]) or when no
/// CC point can be evaluated ([`feed_curvature`]).
///
/// # Units
/// mm, radians.
pub fn lead_bound(cutter: &Cutter, part: &Part, cc: &[Vec<Contact>]) -> Option<LeadBound> {
    let torus = TorusBottom::of(cutter)?;
    let mut worst: Option<(f64, [usize; 2], Point3)> = None;
    let (mut unfit, mut points) = (0, 0);
    for (k, pass) in cc.iter().enumerate() {
        let at: Vec<Point3> = pass.iter().map(|c| c.point).collect();
        let Some(feeds) = path_tangents(&at) else {
            continue;
        };
        for (i, (c, f)) in pass.iter().zip(&feeds).enumerate() {
            let Some(curv) = feed_curvature(part, c, f) else {
                continue;
            };
            points += 1;
            if torus.least_lead(curv).is_none() {
                unfit += 1;
            }
            if worst.is_none_or(|(w, _, _)| curv > w) {
                worst = Some((curv, [k, i], c.point));
            }
        }
    }
    let (curv, at_index, at) = worst?;
    Some(LeadBound {
        lead: torus.least_lead(curv).unwrap_or(FRAC_PI_2),
        at,
        at_index,
        radius: if curv > 0.0 {
            1.0 / curv
        } else {
            f64::INFINITY
        },
        unfit,
        points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::FRAC_1_SQRT_2;
    use swarf_geom::Patch;
    use swarf_tool::Apt;

    /// Exact NURBS trough: the circle of radius `rho` about the line `x = 0, z = rho`
    /// (parallel to y) from -45 to +45 degrees, lowest at z = 0; u along the arc, v
    /// along y from 0 to 40.
    fn trough(rho: f64) -> Patch {
        let s = FRAC_1_SQRT_2;
        let arc = [
            ([-rho * s, rho - rho * s], 1.0),
            ([0.0, rho - rho * 2f64.sqrt()], s),
            ([rho * s, rho - rho * s], 1.0),
        ];
        let (mut p, mut w) = (Vec::new(), Vec::new());
        for ([x, z], wi) in arc {
            for y in [0.0, 40.0] {
                p.push(Point3::new(x, y, z));
                w.push(wi);
            }
        }
        Patch::new([2, 1], p, [None, None], Some(w)).unwrap()
    }

    fn part(patch: Patch) -> Part {
        Part::new("test", vec![patch])
    }

    /// Contacts along u at `v`, normal toward the trough's axis (`inside`) or away.
    fn around(part: &Part, rho: f64, v: f64, inside: bool) -> Vec<Contact> {
        (0..=40)
            .map(|i| {
                let u = 0.05 + 0.9 * i as f64 / 40.0;
                let point = part.patches[0].eval(u, v);
                let axis = Point3::new(0.0, point.y, rho);
                let n = (axis - point).normalize();
                Contact {
                    point,
                    normal: if inside { n } else { -n },
                    face: 0,
                    uv: [u, v],
                }
            })
            .collect()
    }

    #[test]
    fn concave_cylinder_around_its_circumference_gives_the_closed_form() {
        let rho = 62.9;
        let p = part(trough(rho));
        let cc = vec![around(&p, rho, 0.3, true), around(&p, rho, 0.8, true)];
        let bull: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
        let b = lead_bound(&bull, &p, &cc).unwrap();
        let expect = (12.7 / (rho - 6.35)).asin();
        assert!((b.lead - expect).abs() < 1e-9, "{} vs {expect}", b.lead);
        assert!((b.radius - rho).abs() < 1e-7, "{}", b.radius);
        assert_eq!((b.unfit, b.points), (0, 82));
        let ball: Cutter = "ball:d=20".parse().unwrap();
        assert_eq!(lead_bound(&ball, &p, &cc).unwrap().lead, 0.0);
        let flat: Cutter = "flat:d=20".parse().unwrap();
        let f = lead_bound(&flat, &p, &cc).unwrap().lead;
        assert!((f - (10.0 / rho).asin()).abs() < 1e-9, "{f}");
    }

    #[test]
    fn convex_side_and_plane_give_zero() {
        let rho = 30.0;
        let p = part(trough(rho));
        let cc = vec![around(&p, rho, 0.5, false)];
        let bull: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
        let b = lead_bound(&bull, &p, &cc).unwrap();
        assert_eq!(b.lead, 0.0);
        assert!((b.radius.is_infinite()) && b.unfit == 0, "{b:?}");
        let z = |x: f64, y: f64| Point3::new(x, y, 0.3 * x - 0.2 * y + 5.0);
        let plane = part(
            Patch::bezier(
                [1, 1],
                vec![z(0.0, 0.0), z(0.0, 50.0), z(50.0, 0.0), z(50.0, 50.0)],
            )
            .unwrap(),
        );
        let n = Vec3::new(-0.3, 0.2, 1.0).normalize();
        let pass: Vec<Contact> = (0..=20)
            .map(|i| {
                let (u, v) = (i as f64 / 20.0, 0.2 + 0.03 * i as f64);
                let point = plane.patches[0].eval(u, v);
                Contact {
                    point,
                    normal: n,
                    face: 0,
                    uv: [u, v],
                }
            })
            .collect();
        let b = lead_bound(&bull, &plane, &[pass]).unwrap();
        assert_eq!((b.lead, b.unfit, b.points), (0.0, 0, 21));
    }

    #[test]
    fn a_tool_wider_than_the_trough_cannot_fit() {
        let rho = 15.0;
        let p = part(trough(rho));
        let cc = vec![around(&p, rho, 0.5, true)];
        let bull: Cutter = "bull:d=38.1,r=6.35".parse().unwrap();
        let b = lead_bound(&bull, &p, &cc).unwrap();
        assert_eq!((b.lead, b.unfit, b.points), (FRAC_PI_2, 41, 41));
        let ball: Cutter = "ball:d=40".parse().unwrap();
        assert_eq!(lead_bound(&ball, &p, &cc).unwrap().unfit, 41);
        let small: Cutter = "ball:d=29.9".parse().unwrap();
        let s = lead_bound(&small, &p, &cc).unwrap();
        assert_eq!((s.lead, s.unfit), (0.0, 0));
    }

    #[test]
    fn contacts_without_a_patch_are_skipped() {
        let p = part(trough(40.0));
        let mut pass = around(&p, 40.0, 0.5, true);
        pass[3].face = 7;
        pass[4].uv = [f64::NAN; 2];
        let bull: Cutter = "bull:d=20,r=2".parse().unwrap();
        assert_eq!(lead_bound(&bull, &p, &[pass]).unwrap().points, 39);
        let short = vec![around(&p, 40.0, 0.5, true)[..1].to_vec()];
        assert!(lead_bound(&bull, &p, &short).is_none());
    }

    #[test]
    fn torus_bottoms_of_the_cutter_shapes() {
        let of = |s: &str| TorusBottom::of(&s.parse::<Cutter>().unwrap());
        let t = |major: f64, minor: f64| Some(TorusBottom { major, minor });
        assert_eq!(of("bull:d=20,r=3"), t(7.0, 3.0));
        assert_eq!(of("ball:d=20"), t(0.0, 10.0));
        assert_eq!(of("flat:d=20"), t(10.0, 0.0));
        assert_eq!(of("cone:d=20,angle=90"), None);
        assert_eq!(of("taperball:d=20,angle=10,tip=2"), t(0.0, 2.0));
        let apt = Apt::from_corner(20.0, 3.0, 0.0, 0.1, 30.0).unwrap();
        assert_eq!(TorusBottom::of(&Cutter::Apt(apt)), t(apt.e, 3.0));
        let conical = Apt::from_corner(20.0, 3.0, 0.1, 0.0, 30.0).unwrap();
        assert_eq!(TorusBottom::of(&Cutter::Apt(conical)), None);
    }

    /// The derivation in the feed plane, by brute force: at the bound the back insert
    /// touches the osculating circle from inside (sampled insert points reach it), a
    /// tenth of a degree less and it crosses it, and the front insert touches at the CC
    /// point. Plane coordinates: `f` along x, `n` along y, CC at the origin.
    #[test]
    fn at_the_bound_the_back_insert_touches_the_circle() {
        for (major, minor, rho) in [(12.7, 6.35, 62.9), (6.35, 6.35, 40.0), (10.0, 0.0, 25.0)] {
            let torus = TorusBottom { major, minor };
            let bound = torus.least_lead(1.0 / rho).unwrap();
            let reach = |alpha: f64| {
                let (s, c) = alpha.sin_cos();
                let centres = [[0.0, minor], [-2.0 * major * c, minor + 2.0 * major * s]];
                let mut out = [f64::NEG_INFINITY; 2];
                for (k, [x, y]) in centres.into_iter().enumerate() {
                    for i in 0..36000 {
                        let t = i as f64 * std::f64::consts::PI / 18000.0;
                        let q = [x + minor * t.cos(), y + minor * t.sin()];
                        out[k] = out[k].max(q[0].hypot(q[1] - rho) - rho);
                    }
                }
                out
            };
            let [front, back] = reach(bound);
            assert!(front.abs() < 1e-9 && back.abs() < 1e-6, "{front} {back}");
            assert!(reach(bound - 0.1f64.to_radians())[1] > 1e-3);
            assert!(reach(bound + 0.1f64.to_radians())[1] < -1e-3);
        }
    }

    /// On a circle sampled unevenly the tangents are second order: within
    /// `step^2 / 4` (radians) of the exact ones, ends included, where the one-sided
    /// chord is off by half a step.
    #[test]
    fn path_tangents_are_second_order_on_a_circle() {
        let angles = [0.0, 0.08, 0.2, 0.26, 0.4, 0.47];
        let r = 30.0;
        let pts: Vec<Point3> = angles
            .iter()
            .map(|t: &f64| Point3::new(r * t.cos(), r * t.sin(), 2.0 * t))
            .collect();
        let tangents = path_tangents(&pts).unwrap();
        for (k, (t, a)) in tangents.iter().zip(angles).enumerate() {
            let exact = Vec3::new(-r * a.sin(), r * a.cos(), 2.0);
            let err = t.angle(&exact);
            assert!(err < 0.14f64.powi(2) / 4.0, "point {k}: {err}");
        }
        let chord = (pts[5] - pts[4]).angle(&Vec3::new(-r * 0.47f64.sin(), r * 0.47f64.cos(), 2.0));
        assert!(chord > 0.03, "{chord}");
        let two = path_tangents(&pts[..2]).unwrap();
        assert_eq!(two, vec![pts[1] - pts[0]; 2]);
        assert!(path_tangents(&pts[..1]).is_none());
        let repeated = path_tangents(&[pts[0], pts[0], pts[1]]).unwrap();
        assert_eq!(repeated[0], pts[1] - pts[0]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Along a helix on the inside of a cylinder the normal curvature is
        /// `cos^2(phi) / rho` (Euler), and the bound follows the closed form.
        #[test]
        fn helical_feeds_follow_euler(
            rho in 20.0f64..200.0,
            phi in -1.4f64..1.4,
            u in 0.05f64..0.95,
            major in 0.0f64..8.0,
            minor in 0.0f64..6.0,
        ) {
            let p = part(trough(rho));
            let d = p.patches[0].derivs(u, 0.5);
            let contact = Contact {
                point: d.point,
                normal: (Point3::new(0.0, d.point.y, rho) - d.point).normalize(),
                face: 0,
                uv: [u, 0.5],
            };
            let feed = phi.cos() * d.du.normalize() + phi.sin() * Vec3::y();
            let k = feed_curvature(&p, &contact, &feed).unwrap();
            let expect = phi.cos().powi(2) / rho;
            prop_assert!((k - expect).abs() < 1e-12, "{} vs {}", k, expect);
            let torus = TorusBottom { major, minor };
            let lead = torus.least_lead(k).unwrap();
            let closed = if major == 0.0 { 0.0 } else { (major / (1.0 / expect - minor)).asin() };
            prop_assert!((lead - closed).abs() < 1e-9);
        }
    }
}
