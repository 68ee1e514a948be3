//! Side step between adjacent passes from the scallop height limit `h`.
//!
//! # Ball end mill (exact in the cross-section)
//!
//! In the plane normal to the feed direction the surface is replaced by its osculating
//! circle in the side direction `B` (radius `rho = 1 / |kappa|`, `kappa` the normal
//! curvature along `B` with the normal facing the tool: `kappa > 0` concave, `kappa < 0`
//! convex) and each pass's swept ball by a circle of radius `r` tangent to it. With `O`
//! the centre of the surface circle, the tool centres lie at `R_c = rho + r` (convex)
//! or `rho - r` (concave) from `O`, an angle `2 alpha` apart; the cusp of the scallop
//! lies on the bisector at `d = rho + h` (convex) or `rho - h` (concave) from `O`, and
//! `r^2 = R_c^2 + d^2 - 2 R_c d cos(alpha)` (law of cosines). Since `|R_c - d| = r - h`
//! in both cases, the half-angle form avoids the cancellation of `1 - cos(alpha)`:
//!
//! `sin(alpha / 2) = sqrt((2 r h - h^2) / (4 R_c d))`, side step (arc length on the
//! surface) `l = 2 alpha rho`.
//!
//! Written with the signed curvature, `R_c d = rho^2 (1 - r kappa)(1 - h kappa)`; with
//! `q = sqrt((2 r h - h^2) / (4 (1 - r kappa)(1 - h kappa)))`,
//! `l = 4 q asin(|kappa| q) / (|kappa| q)`, which tends to the flat-surface step
//! `2 sqrt(2 r h - h^2)` as `kappa -> 0` with no special case. This is the exact
//! circle-intersection form behind paper 004's `delta_l = sqrt(8 rho h / (rho +- r))`
//! (after Lo 2000): expanding `asin` and dropping `h^2` gives
//! `l ~ sqrt(8 rho r h / (rho +- r))`. The extracted text of paper 004 lost the factor
//! `r` under the root (its formula is not a length); [`ball_step_approx`] restores it,
//! and the tests check that the two forms agree for small `h`.
//!
//! Where the circle model has no answer (a concave radius at most `r`, where the ball
//! cannot reach the bottom and the gouge check takes over, or `|kappa| q > 1`), the
//! step is capped at [`MAX_STEP_RADII`] effective radii.
//!
//! # Flat, bull, cone and APT cutters: effective cutting radius
//!
//! A vertical tool fed horizontally sweeps, in the plane normal to the feed, exactly
//! its meridian outline (the silhouette of a solid of revolution seen across its
//! axis). The scallop left on a *plane* tilted by `theta` (the angle between the
//! surface normal and the tool axis in that section) by two such outlines a distance
//! `s` apart is computed exactly in 2D: the vertical gap between each outline and the
//! line is convex, zero at the contact, so the crest of the scallop is where the two
//! gaps are equal (bisection), and `s(h)` follows by bisection on `s`. The *effective
//! cutting radius* in the side direction is the radius of the ball that leaves the
//! same scallop on that plane: `r_e = (s^2 / 4 + h^2) / (2 h)` (the flat-surface ball
//! formula solved for `r`; it gives `r_e = r` for a ball). Curvature then enters
//! through the ball formula with `r_e`. The approximations: the section of the swept
//! volume is the outline only for horizontal feeds (on climbing passes the true
//! section of a flat or bull tool is wider, so the scallop is smaller: conservative),
//! and on a curved surface the outline is treated as a circle of radius `r_e`
//! (exact for a ball and for a bull whose contacts and crest stay on its corner arc).
//! `r_e` is tabulated over the tilt once per plan and read conservatively (the smaller
//! of the two neighbouring entries).
//!
//! # Convex ridges
//!
//! The effective radius assumes both tools lean the same way, as on a plane. A
//! vertical tool touches a surface that rises toward one side with its corner on that
//! side, its body lying the other way. Where the surface rises from one contact toward
//! the next and falls beyond it (a convex ridge between two passes), the two tools
//! touch with their corners facing, bodies turned away, and only the corners cut the
//! ridge: the scallop is that of two balls of the corner radius ([`SideStep::corner`];
//! a sharp rim, radius 0, leaves the ridge uncut at any step). A nearly level bull has
//! an effective radius of tens of millimetres (its flat bottom), so without this rule
//! the step across a ridge leaves it uncut or scalloped several times `h` (measured on
//! wave with the swept-tool oracle of the tests: 0.43 mm for `bull:d=10,r=2` at
//! `h = 0.15`).

use crate::error::PathError;
use swarf_geom::Vec3;
use swarf_tool::{Cutter, Profile};

/// Side steps are capped at this many effective radii where the circle model of a
/// concave region has no answer (dimensionless).
pub const MAX_STEP_RADII: f64 = 2.0;

/// Tilts of the effective-radius table run from 0 to this angle (radians, just under
/// 90 degrees: a vertical wall has no scallop across a vertical tool's feed).
const MAX_TILT: f64 = 89.5 * std::f64::consts::PI / 180.0;

/// Entries in the effective-radius table.
const TILT_SAMPLES: usize = 180;

/// Bisection steps of the 2D profile scallop solvers (halves the bracket each time).
const BISECTIONS: usize = 60;

/// Exact ball side step (arc length on the surface, mm) for tool radius `r`, signed
/// side curvature `kappa` (1/mm, positive concave as seen from the tool) and scallop
/// height `h`; `None` where the circle model has no solution (module doc).
///
/// # Units
/// mm, 1/mm.
pub fn ball_step(r: f64, kappa: f64, h: f64) -> Option<f64> {
    let a = (1.0 - r * kappa) * (1.0 - h * kappa);
    if a.is_nan() || a <= 0.0 || h.is_nan() || h <= 0.0 || h >= r {
        return None;
    }
    let q = ((2.0 * r * h - h * h) / (4.0 * a)).sqrt();
    let x = kappa.abs() * q;
    if x > 1.0 {
        return None;
    }
    Some(4.0 * q * asin_over_x(x))
}

/// Paper 004's approximate ball side step `sqrt(8 rho r h / (rho +- r))` (with the
/// factor `r` its extracted text lost, module doc); `None` on a concave radius at most
/// `r`.
///
/// # Units
/// mm, 1/mm.
pub fn ball_step_approx(r: f64, kappa: f64, h: f64) -> Option<f64> {
    let a = 1.0 - r * kappa;
    (a > 0.0).then(|| (8.0 * r * h / a).sqrt())
}

/// Scallop height (mm) left by two ball passes a surface distance `step` apart on a
/// surface of signed side curvature `kappa`: the inverse of [`ball_step`]. `None`
/// where the two circles do not meet above the surface.
///
/// # Units
/// mm, 1/mm.
pub fn ball_scallop(r: f64, kappa: f64, step: f64) -> Option<f64> {
    if kappa.abs() * r < 1e-12 {
        let half = 0.5 * step;
        return (half <= r).then(|| r - (r * r - half * half).sqrt());
    }
    let rho = 1.0 / kappa.abs();
    let alpha = 0.5 * step / rho;
    let (s, c) = alpha.sin_cos();
    if kappa < 0.0 {
        let rc = rho + r;
        let disc = r * r - rc * rc * s * s;
        (disc >= 0.0).then(|| rc * c - disc.sqrt() - rho)
    } else {
        let rc = rho - r;
        let disc = r * r - rc * rc * s * s;
        (rc > 0.0 && disc >= 0.0).then(|| rho - (rc * c + disc.sqrt()))
    }
}

/// `asin(x) / x`, 1 at 0.
fn asin_over_x(x: f64) -> f64 {
    if x < 1e-8 {
        1.0 + x * x / 6.0
    } else {
        x.asin() / x
    }
}

/// The side-step model of one cutter at one scallop height: effective cutting radius
/// over the tilt, and the step and predicted scallop from it.
#[derive(Debug, Clone)]
pub struct SideStep {
    h: f64,
    ball: Option<f64>,
    table: Vec<f64>,
    corner: f64,
}

impl SideStep {
    /// The model for `cutter` and scallop limit `h`.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] on `scallop` when `h` is not in
    /// `(0, tool radius)`.
    pub fn new(cutter: &Cutter, h: f64) -> Result<SideStep, PathError> {
        check_scallop(cutter, h)?;
        if let Cutter::Ball { radius, .. } = cutter {
            return Ok(SideStep {
                h,
                ball: Some(*radius),
                table: Vec::new(),
                corner: *radius,
            });
        }
        let profile = cutter.profile();
        let table = (0..=TILT_SAMPLES)
            .map(|k| {
                let tilt = MAX_TILT * k as f64 / TILT_SAMPLES as f64;
                let s = plane_step(&profile, tilt, h);
                (0.25 * s * s + h * h) / (2.0 * h)
            })
            .collect();
        Ok(SideStep {
            h,
            ball: None,
            table,
            corner: corner_radius(cutter),
        })
    }

    /// Radius of the cutter's rounded corner (module doc, "Convex ridges"), mm.
    pub fn corner(&self) -> f64 {
        self.corner
    }

    /// Side step (mm) between two tools touching a convex ridge with their corners
    /// facing (module doc, "Convex ridges"), at signed side curvature `kappa` (1/mm):
    /// the ball step of the corner radius; 0 for a sharp rim.
    pub fn corner_step(&self, kappa: f64) -> f64 {
        if self.corner <= 0.0 {
            return 0.0;
        }
        self.step_for_radius(self.corner, kappa)
    }

    /// Predicted scallop (mm) between two tools a surface distance `step` apart with
    /// their corners facing across a ridge of side curvature `kappa`; `None` where
    /// the corners do not meet (always for a sharp rim).
    pub fn corner_scallop(&self, step: f64, kappa: f64) -> Option<f64> {
        if self.corner <= 0.0 {
            return None;
        }
        ball_scallop(self.corner, kappa, step).map(|s| s.max(0.0))
    }

    /// The scallop height limit, mm.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// Effective cutting radius (mm) at `tilt` (radians between the surface normal and
    /// the tool axis, in the section normal to the feed); conservative between table
    /// entries.
    pub fn effective_radius(&self, tilt: f64) -> f64 {
        if let Some(r) = self.ball {
            return r;
        }
        let x = (tilt.abs().min(MAX_TILT) / MAX_TILT) * TILT_SAMPLES as f64;
        let k = (x.floor() as usize).min(TILT_SAMPLES);
        let next = (k + 1).min(TILT_SAMPLES);
        self.table[k].min(self.table[next])
    }

    /// The least effective cutting radius over all tilts, mm.
    pub fn min_effective_radius(&self) -> f64 {
        self.ball
            .unwrap_or_else(|| self.table.iter().copied().fold(f64::INFINITY, f64::min))
    }

    /// The least effective cutting radius over tilts from 0 to `tilt` (radians), mm.
    pub fn least_radius_up_to(&self, tilt: f64) -> f64 {
        if let Some(r) = self.ball {
            return r;
        }
        let x = (tilt.abs().min(MAX_TILT) / MAX_TILT) * TILT_SAMPLES as f64;
        let k = ((x.ceil() as usize) + 1).min(TILT_SAMPLES + 1);
        self.table[..k]
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }

    /// Side step (surface distance, mm) at signed side curvature `kappa` (1/mm,
    /// positive concave) and `tilt` (radians).
    pub fn step(&self, kappa: f64, tilt: f64) -> f64 {
        self.step_for_radius(self.effective_radius(tilt), kappa)
    }

    /// Side step (mm) of the ball model with effective radius `re` (mm) at signed side
    /// curvature `kappa` (1/mm).
    pub fn step_for_radius(&self, re: f64, kappa: f64) -> f64 {
        let cap = MAX_STEP_RADII * re;
        ball_step(re, kappa, self.h).map_or(cap, |s| s.min(cap))
    }

    /// Predicted scallop height (mm) between two passes a surface distance `step`
    /// apart, from the same model; `None` where the model leaves the material uncut.
    pub fn scallop(&self, step: f64, kappa: f64, tilt: f64) -> Option<f64> {
        let re = self.effective_radius(tilt);
        if step > MAX_STEP_RADII * re {
            return None;
        }
        match ball_scallop(re, kappa, step) {
            Some(s) => Some(s.max(0.0)),
            None if kappa > 0.0 => Some(0.0),
            None => None,
        }
    }
}

/// Checks a scallop limit `h` (mm) for `cutter`: finite, in `(0, tool radius)`.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `scallop` otherwise.
pub(crate) fn check_scallop(cutter: &Cutter, h: f64) -> Result<(), PathError> {
    let r = cutter.radius();
    if h.is_finite() && h > 0.0 && h < r {
        return Ok(());
    }
    Err(PathError::InvalidParameter {
        field: "scallop".into(),
        message: format!("expected 0 < scallop < tool radius {r} mm, found {h} mm"),
    })
}

/// Radius of the cutter's rounded corner: the ball's radius, the torus's, the tip
/// ball of a tapered ball, the APT corner radius; 0 for a sharp rim.
fn corner_radius(cutter: &Cutter) -> f64 {
    match *cutter {
        Cutter::Ball { radius, .. } => radius,
        Cutter::Bull { corner, .. } => corner,
        Cutter::TaperBall { tip_radius, .. } => tip_radius,
        Cutter::Apt(a) => a.r,
        Cutter::Flat { .. } | Cutter::Cone { .. } => 0.0,
    }
}

/// Smallest horizontal lean `|N . e|` that counts as leaning to one side.
const LEAN: f64 = 1e-9;

/// True when two contacts with normals `n0` and `n1` (toward the tool), the second
/// at `toward` from the first, have a convex ridge between them that the tools touch
/// with facing corners (module doc, "Convex ridges"): the surface rises from the
/// first toward the second and falls beyond it, across the horizontal direction of
/// `toward`.
pub fn corners_face(n0: &Vec3, n1: &Vec3, toward: &Vec3) -> bool {
    Vec3::new(toward.x, toward.y, 0.0)
        .try_normalize(LEAN)
        .is_some_and(|e| n0.dot(&e) < -LEAN && n1.dot(&e) > LEAN)
}

/// Vertical gap (mm) at `x` between a tool outline resting on the line
/// `z = -x tan(theta)` and that line; `f64::INFINITY` beyond the tool.
struct TiltedGap<'a> {
    profile: &'a Profile,
    slope: f64,
    contact: f64,
    lift: f64,
}

impl<'a> TiltedGap<'a> {
    /// The outline touching the line; the contact is found by ternary search (the gap
    /// is convex in `x`, least on the downhill half `[-radius, 0]`).
    fn new(profile: &'a Profile, tilt: f64) -> TiltedGap<'a> {
        let mut gap = TiltedGap {
            profile,
            slope: tilt.tan(),
            contact: 0.0,
            lift: 0.0,
        };
        let (mut lo, mut hi) = (-profile.radius(), 0.0);
        for _ in 0..BISECTIONS {
            let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if gap.raw(a) <= gap.raw(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        gap.contact = 0.5 * (lo + hi);
        gap.lift = -gap.raw(gap.contact);
        gap
    }

    fn raw(&self, x: f64) -> f64 {
        self.profile
            .height_at_radius(x.abs())
            .map_or(f64::INFINITY, |g| g + x * self.slope)
    }

    fn at(&self, x: f64) -> f64 {
        self.raw(x) + self.lift
    }

    /// Scallop (normal to the line, mm) between this outline and itself moved a
    /// distance `s` along the line.
    fn scallop(&self, s: f64, tilt: f64) -> f64 {
        let dx = s * tilt.cos();
        let c = self.contact;
        let (mut lo, mut hi) = (c, c + dx);
        for _ in 0..BISECTIONS {
            let m = 0.5 * (lo + hi);
            if self.at(m) < self.at(m - dx) {
                lo = m;
            } else {
                hi = m;
            }
        }
        // The lower envelope may jump at a sharp rim: take the larger bracket end.
        let crest = |x: f64| self.at(x).min(self.at(x - dx));
        crest(lo).max(crest(hi)) * tilt.cos()
    }
}

/// Scallop (mm, normal to the plane) that two outlines of `profile` a distance `step`
/// apart along a plane tilted by `tilt` leave on it: the exact 2D model of the module
/// doc, the inverse of the step it tabulates. `None` for a tilt outside `[0, pi/2)`,
/// a negative or non-finite step, or where the outlines leave a strip uncut.
///
/// # Units
/// mm, radians.
pub fn plane_scallop(profile: &Profile, tilt: f64, step: f64) -> Option<f64> {
    let valid = (0.0..std::f64::consts::FRAC_PI_2).contains(&tilt) && step.is_finite();
    if !valid || step < 0.0 {
        return None;
    }
    let h = TiltedGap::new(profile, tilt).scallop(step, tilt);
    h.is_finite().then_some(h.max(0.0))
}

/// Step along a plane tilted by `tilt` that leaves scallop `h` between two outlines
/// of `profile` (the 2D model of the module doc), mm.
fn plane_step(profile: &Profile, tilt: f64, h: f64) -> f64 {
    let gap = TiltedGap::new(profile, tilt);
    let width = 2.0 * profile.radius() / tilt.cos().max(1e-6);
    let (mut lo, mut hi) = (0.0, width);
    if gap.scallop(hi, tilt) <= h {
        return hi;
    }
    for _ in 0..BISECTIONS {
        let m = 0.5 * (lo + hi);
        if gap.scallop(m, tilt) <= h {
            lo = m;
        } else {
            hi = m;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: f64, b: f64, eps: f64) -> bool {
        (a - b).abs() <= eps
    }

    /// Brute-force scallop of two circles of radius `r` tangent to a circle of radius
    /// `rho` (convex or concave) at points an arc `s` apart: the largest distance
    /// from the surface circle to the lower envelope of the two tool circles, sampled.
    fn brute_ball_scallop(r: f64, kappa: f64, s: f64) -> f64 {
        let n = 20_000;
        let mut worst: f64 = 0.0;
        let centre = |phi: f64| -> (f64, f64) {
            if kappa.abs() < 1e-15 {
                (phi, r)
            } else {
                let rho = 1.0 / kappa.abs();
                let (sa, ca) = (phi / rho).sin_cos();
                if kappa < 0.0 {
                    ((rho + r) * sa, (rho + r) * ca - rho)
                } else {
                    ((rho - r) * sa, rho - (rho - r) * ca)
                }
            }
        };
        let (c0, c1) = (centre(-0.5 * s), centre(0.5 * s));
        for k in 0..=n {
            let phi = -0.5 * s + s * k as f64 / n as f64;
            let (x, z, nx, nz) = if kappa.abs() < 1e-15 {
                (phi, 0.0, 0.0, 1.0)
            } else {
                let rho = 1.0 / kappa.abs();
                let (sa, ca) = (phi / rho).sin_cos();
                if kappa < 0.0 {
                    (rho * sa, rho * ca - rho, sa, ca)
                } else {
                    (rho * sa, rho - rho * ca, -sa, ca)
                }
            };
            // Distance along the normal from the surface to the first tool circle.
            let enter = |c: (f64, f64)| -> f64 {
                let (wx, wz) = (x - c.0, z - c.1);
                let b = wx * nx + wz * nz;
                let cc = wx * wx + wz * wz - r * r;
                let disc = b * b - cc;
                if disc < 0.0 {
                    f64::INFINITY
                } else {
                    -b - disc.sqrt()
                }
            };
            worst = worst.max(enter(c0).min(enter(c1)));
        }
        worst
    }

    #[test]
    fn flat_surface_closed_form() {
        let (r, h) = (4.0, 0.15);
        let s = ball_step(r, 0.0, h).unwrap();
        assert!(close(s, 2.0 * (2.0 * r * h - h * h).sqrt(), 1e-12));
        assert!(close(ball_scallop(r, 0.0, s).unwrap(), h, 1e-12));
        let approx = ball_step_approx(r, 0.0, h).unwrap();
        assert!(close(approx, (8.0 * r * h).sqrt(), 1e-12));
    }

    #[test]
    fn concave_tighter_than_the_ball_has_no_circle_answer() {
        assert!(ball_step(4.0, 1.0 / 3.0, 0.1).is_none());
        assert!(ball_step_approx(4.0, 1.0 / 3.0, 0.1).is_none());
        let ss = SideStep::new(&Cutter::ball(8.0, None).unwrap(), 0.1).unwrap();
        assert_eq!(ss.step(1.0 / 3.0, 0.0), MAX_STEP_RADII * 4.0);
    }

    #[test]
    fn bad_scallop_names_the_field() {
        let ball = Cutter::ball(8.0, None).unwrap();
        for h in [0.0, -1.0, 4.0, f64::NAN] {
            let e = SideStep::new(&ball, h).unwrap_err().to_string();
            assert!(e.starts_with("scallop"), "{e}");
        }
    }

    #[test]
    fn ball_effective_radius_is_its_radius_and_bull_flat_bottom_widens_the_step() {
        let ball = SideStep::new(&Cutter::ball(8.0, None).unwrap(), 0.15).unwrap();
        assert_eq!(ball.effective_radius(0.7), 4.0);
        // The 2D outline model for a ball outline reproduces r at moderate tilts.
        let profile = Cutter::ball(8.0, None).unwrap().profile();
        for tilt in [0.0, 0.3, 0.8] {
            let s = plane_step(&profile, tilt, 0.15);
            let re = (0.25 * s * s + 0.15 * 0.15) / 0.3;
            assert!(close(re, 4.0, 1e-6), "tilt {tilt}: {re}");
        }
        // Bull d=10 r=2 on a level plane: flat bottom (6 mm) plus the corner arcs.
        let bull = Cutter::bull(10.0, 2.0, None).unwrap();
        let s = plane_step(&bull.profile(), 0.0, 0.15);
        let want = 6.0 + 2.0 * (2.0 * 2.0 * 0.15 - 0.15f64 * 0.15).sqrt();
        assert!(close(s, want, 1e-6), "{s} vs {want}");
        // Flat end mill on a plane tilted by theta: a sawtooth of height s sin cos.
        let flat = Cutter::flat(6.0, None).unwrap();
        let tilt = 0.4f64;
        let s = plane_step(&flat.profile(), tilt, 0.1);
        assert!(close(s, 0.1 / (tilt.sin() * tilt.cos()), 1e-6), "{s}");
        // The table is read conservatively and never exceeds the exact value.
        let ss = SideStep::new(&bull, 0.15).unwrap();
        for k in 0..50 {
            let tilt = 1.5 * k as f64 / 50.0;
            let s = plane_step(&bull.profile(), tilt, 0.15);
            let exact = (0.25 * s * s + 0.15 * 0.15) / 0.3;
            assert!(ss.effective_radius(tilt) <= exact + 1e-9, "tilt {tilt}");
        }
    }

    #[test]
    fn facing_corners_only_across_a_convex_ridge() {
        let lean = |a: f64| Vec3::new(0.0, a.sin(), a.cos());
        let toward = Vec3::new(0.0, 2.0, 0.1);
        // Rising from the first contact toward the second, falling beyond it.
        assert!(corners_face(&lean(-0.2), &lean(0.1), &toward));
        // Both on one slope, a valley, or the other way round: no ridge between.
        assert!(!corners_face(&lean(-0.2), &lean(-0.1), &toward));
        assert!(!corners_face(&lean(0.2), &lean(0.1), &toward));
        assert!(!corners_face(&lean(0.2), &lean(-0.1), &toward));
        assert!(!corners_face(&lean(-0.2), &lean(0.1), &(-toward)));
        // Across a ridge two bull corners act as balls of the corner radius; a flat
        // end's rim cuts nothing there.
        let bull = SideStep::new(&Cutter::bull(10.0, 2.0, None).unwrap(), 0.15).unwrap();
        assert_eq!(bull.corner(), 2.0);
        let step = bull.corner_step(-0.02);
        assert!(close(step, ball_step(2.0, -0.02, 0.15).unwrap(), 1e-12));
        assert!(close(bull.corner_scallop(step, -0.02).unwrap(), 0.15, 1e-9));
        let flat = SideStep::new(&Cutter::flat(6.0, None).unwrap(), 0.15).unwrap();
        assert_eq!((flat.corner(), flat.corner_step(-0.02)), (0.0, 0.0));
        assert!(flat.corner_scallop(0.1, -0.02).is_none());
        let ball = SideStep::new(&Cutter::ball(8.0, None).unwrap(), 0.15).unwrap();
        assert_eq!(ball.corner_step(-0.02), ball.step(-0.02, 0.3));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn exact_step_matches_brute_force_scallop(
            r in 1.0..6.0f64, hfrac in 0.002..0.2f64, rho in 6.0..300.0f64, convex in any::<bool>(),
        ) {
            let h = hfrac * r;
            let kappa = if convex { -1.0 / rho } else { 1.0 / rho };
            let Some(s) = ball_step(r, kappa, h) else { return Ok(()) };
            let brute = brute_ball_scallop(r, kappa, s);
            prop_assert!(close(brute, h, 2e-4 * h + 1e-9), "brute {} vs h {}", brute, h);
            let back = ball_scallop(r, kappa, s).unwrap();
            prop_assert!(close(back, h, 1e-9 * r), "inverse {} vs {}", back, h);
        }

        #[test]
        fn paper_formula_agrees_for_small_scallops(
            r in 1.0..6.0f64, rho in 10.0..300.0f64, convex in any::<bool>(),
        ) {
            let h = 1e-4 * r;
            let kappa = if convex { -1.0 / rho } else { 1.0 / rho };
            let exact = ball_step(r, kappa, h).unwrap();
            let approx = ball_step_approx(r, kappa, h).unwrap();
            prop_assert!(close(exact, approx, 1e-3 * exact));
        }
    }
}
