//! The vertical ray through `(x, y)` against one patch: Newton's method on
//! `S_xy(u, v) = (x, y)` (derivation in [`super`]).

use crate::math::Vec3;
use crate::patch::PowerPatch;

/// Newton stops when the ray's XY residual is below this, mm.
pub const NEWTON_XY: f64 = 1e-10;
/// A Newton step shorter than this fraction of the parameter range is the last one:
/// the next would change the point by about `|S''| step^2 / 2`, below 1e-10 mm for
/// second derivatives up to 1e4 mm per unit parameter squared (dimensionless).
pub const NEWTON_ACCEPT: f64 = 1e-7;
/// Most Newton steps per query and patch.
pub const NEWTON_STEPS: usize = 16;
/// After [`NEWTON_STEPS`], an XY residual up to this still counts as a hit, mm.
pub const NEWTON_LATE_XY: f64 = 1e3 * NEWTON_XY;
/// A Jacobian determinant `|S_u.xy x S_v.xy|` at or below this is singular, mm^2.
pub const SINGULAR_DET: f64 = 1e-300;

/// How the vertical ray against one patch ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ray {
    /// Converged: the patch point above `(x, y)`.
    Hit {
        /// Height, mm.
        z: f64,
        /// Unit normal turned upward (`+z` where it is not defined).
        normal: Vec3,
        /// The parameters of the point.
        uv: [f64; 2],
    },
    /// The ray passes beside the patch: Newton was pushed against the domain
    /// boundary with a residual left, or ran out of steps far from `(x, y)`.
    Off,
    /// The Jacobian is singular (a vertical tangent plane or a pole): no step.
    Singular,
}

/// Unit normal `S_u x S_v`, turned upward; `+z` where it vanishes.
fn upward(du: Vec3, dv: Vec3) -> Vec3 {
    let n = du.cross(&dv);
    let n = if n.z < 0.0 { -n } else { n };
    n.try_normalize(0.0).unwrap_or(Vec3::z())
}

/// Solves `S_xy(u, v) = (x, y)` on `patch` from `uv`, parameters clamped into the
/// domain.
///
/// # Units
/// mm.
pub fn vertical_ray(patch: &PowerPatch, x: f64, y: f64, uv: [f64; 2]) -> Ray {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let (mut u, mut v) = (uv[0], uv[1]);
    let small = [NEWTON_ACCEPT * (u1 - u0), NEWTON_ACCEPT * (v1 - v0)];
    for _ in 0..NEWTON_STEPS {
        let (p, du, dv) = patch.eval1(u, v);
        let (rx, ry) = (x - p.x, y - p.y);
        if rx * rx + ry * ry <= NEWTON_XY * NEWTON_XY {
            return Ray::Hit {
                z: p.z,
                normal: upward(du, dv),
                uv: [u, v],
            };
        }
        let det = du.x * dv.y - du.y * dv.x;
        if det.is_nan() || det.abs() <= SINGULAR_DET {
            return Ray::Singular;
        }
        let su = (rx * dv.y - ry * dv.x) / det;
        let sv = (du.x * ry - du.y * rx) / det;
        let (cu, cv) = ((u + su).clamp(u0, u1), (v + sv).clamp(v0, v1));
        if cu == u && cv == v {
            return Ray::Off;
        }
        if cu == u + su && cv == v + sv && su.abs() <= small[0] && sv.abs() <= small[1] {
            // The last step is so short that the step after it would be below
            // rounding (quadratic convergence): take the tangent plane's height.
            return Ray::Hit {
                z: p.z + du.z * su + dv.z * sv,
                normal: upward(du, dv),
                uv: [cu, cv],
            };
        }
        (u, v) = (cu, cv);
    }
    let (p, du, dv) = patch.eval1(u, v);
    if (x - p.x).hypot(y - p.y) <= NEWTON_LATE_XY {
        Ray::Hit {
            z: p.z,
            normal: upward(du, dv),
            uv: [u, v],
        }
    } else {
        Ray::Off
    }
}
