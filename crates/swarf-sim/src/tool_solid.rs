//! The signed distance to the tool solid that the tilted march steps by.
//!
//! A ball or bull cutter (radius `R`, corner `r > 0`, flute `L >= 2 r`) is the union
//! of two solid cylinders' pieces in meridian coordinates `(rho, u)` (distance from
//! the axis, height along it from the tip): the core `rho <= R - r`,
//! `r <= u <= L - r` grown by the corner ball `r` (flat bottom, torus, side, rounded
//! top), and the top slab `rho <= R`, `L - r <= u <= L` (the flat top and its sharp
//! rim). The distance to a union is the least of the distances (exact outside, where
//! the march steps; of the right sign inside), and the distance to a solid cylinder is
//! the 2D box distance, so the tool's distance costs a few operations instead of the
//! walk over the profile's segments ([`Profile::signed_distance_rho_z`], used for
//! every other cutter).

use swarf_tool::{Cutter, Profile};

/// A tool solid and how the distance to it is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolSolid {
    /// The profile (its exact signed distance for every tool but a ball or bull).
    profile: Profile,
    /// A ball's or bull's radius `R`, corner `r` and flute length `L`, mm.
    rounded: Option<Rounded>,
}

/// A ball or bull: its core grown by the corner, and its top slab.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rounded {
    radius: f64,
    corner: f64,
    length: f64,
}

impl ToolSolid {
    /// The solid of `cutter`, whose profile is `profile`.
    pub fn of(cutter: &Cutter, profile: &Profile) -> ToolSolid {
        let (radius, corner) = match *cutter {
            Cutter::Ball { radius, .. } => (radius, radius),
            Cutter::Bull { radius, corner, .. } => (radius, corner),
            _ => (0.0, 0.0),
        };
        let length = profile.length();
        let rounded =
            (corner > 0.0 && corner <= radius && 2.0 * corner <= length).then_some(Rounded {
                radius,
                corner,
                length,
            });
        ToolSolid {
            profile: *profile,
            rounded,
        }
    }

    /// True when the distance is the ball's or bull's own (not the profile walk).
    pub fn is_rounded(&self) -> bool {
        self.rounded.is_some()
    }

    /// Signed distance from the meridian point `(rho, u)` (negative inside), mm.
    #[inline]
    pub fn distance(&self, rho: f64, u: f64) -> f64 {
        match self.rounded {
            Some(Rounded {
                radius,
                corner,
                length,
            }) => {
                let core = cylinder(rho, u, radius - corner, (corner, length - corner)) - corner;
                core.min(cylinder(rho, u, radius, (length - corner, length)))
            }
            None => self.profile.signed_distance_rho_z(rho, u),
        }
    }
}

/// Signed distance from `(rho, u)` to the solid cylinder of radius `a` between the
/// heights `span` (the box distance in the meridian plane).
#[inline]
fn cylinder(rho: f64, u: f64, a: f64, span: (f64, f64)) -> f64 {
    let dr = rho - a;
    let du = (span.0 - u).max(u - span.1);
    let out = dr.max(0.0).hypot(du.max(0.0));
    out + dr.max(du).min(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounded_distances_are_the_profiles() {
        for spec in [
            "ball:d=8,length=20",
            "bull:d=10,r=2,length=15",
            "bull:d=38.1,r=6.35,length=25.4",
        ] {
            let cutter: Cutter = spec.parse().unwrap();
            let profile = cutter.profile();
            let solid = ToolSolid::of(&cutter, &profile);
            assert!(solid.is_rounded(), "{spec}");
            let (r, l) = (profile.radius(), profile.length());
            for k in 0..=60 {
                for m in 0..=60 {
                    let rho = 1.5 * r * k as f64 / 60.0;
                    let u = -3.0 + (l + 6.0) * m as f64 / 60.0;
                    let (got, want) = (
                        solid.distance(rho, u),
                        profile.signed_distance_rho_z(rho, u),
                    );
                    if want > 0.0 {
                        assert!(
                            (got - want).abs() < 1e-12,
                            "{spec} ({rho}, {u}): {got} {want}"
                        );
                    } else {
                        // Inside: the same sign, never nearer the boundary than it is.
                        assert!(
                            got <= 1e-12 && got >= want - 1e-12,
                            "{spec} ({rho}, {u}): {got} {want}"
                        );
                    }
                }
            }
        }
        for spec in ["flat:d=6", "cone:d=6,angle=60", "ball:d=8,length=6"] {
            let cutter: Cutter = spec.parse().unwrap();
            let solid = ToolSolid::of(&cutter, &cutter.profile());
            assert!(!solid.is_rounded(), "{spec}");
        }
    }
}
