//! Rounded ring corners, and the stepover that keeps the engagement in them.
//!
//! An inner ring of a pocket has sharp corners where the pocket has (the offset of
//! a corner is a corner). Cut outwards, a tool turning such a corner pivots with
//! material all round its front, far beyond the straight-stretch engagement. So the
//! rings are opened by a radius `rho` (eroded, then dilated: every convex corner
//! becomes an arc of radius `rho`, nothing else moves), with geo's buffers; a region
//! narrower than `2 rho`, or with a channel narrower (opening would leave it out,
//! though the tool fits), is opened by half the radius, and so on [`HALVINGS`]
//! times, else left sharp. The outermost ring is opened too: it leaves the corners of the
//! allowed region uncut (a corner of angle `a` keeps `rho (1 / sin(a/2) - 1)` along
//! its bisector), rest for a smaller tool, which the in-process stock carries to the
//! next operation.
//!
//! In an opened corner of half-angle `a/2` the band between two rings is `s / sin(a/2)`
//! wide at the arc's apex (the corners of two rings `s` apart are `s / sin(a/2)`
//! apart along the bisector), cut on an arc of radius `rho` that turns towards the
//! cleared side. A tool on such an arc, centre `O` at `rho` from its centre `P`, meets
//! material beyond `rho + R - w` from `O`; a rim point at angle `t` from the outward
//! normal is `sqrt(rho² + R² + 2 rho R cos t)` from `O`, so the engagement `phi`
//! allows the band `w(rho, phi) = rho + R - sqrt(rho² + R² + 2 rho R cos phi)`
//! (`R (1 - cos phi)` as `rho` grows, 0 for a pivot). The stepover is
//! `w(rho, phi) sin(a/2)` for the sharpest corner to be held, a right angle.
//!
//! The stepover therefore belongs to a ring, not to the plan: a ring opened by a
//! halved radius turns tighter and must step over less. The ring inside it may be
//! sharper still: its apex then lies nearer the corner, `s √2 + (rho' - rho)(√2 - 1)`
//! from the outer ring's apex with `rho' <= rho`, so the band the outer ring cuts
//! is no wider than with equal radii, and the outer ring's own radius sets its
//! stepover (`regions.rs`).

use super::regions::Ring;
use geo::algorithm::buffer::{BufferStyle, LineJoin};
use geo::{Area, BooleanOps, Buffer, LineString, MultiPolygon, Polygon, Simplify};

/// Angle step of the buffers' round joins, radians (arc sag `rho (1 - cos 0.025)`,
/// 3e-4 of the radius).
const JOIN_ANGLE: f64 = 0.05;
/// How many times the corner radius is halved for a region too narrow for it.
pub(crate) const HALVINGS: u32 = 4;
/// Most area, in squared radii, that opening may take from one place: a corner of
/// angle `a` loses `r² (cot(a/2) - (π - a)/2)`, 0.21 for a right angle, 0.69 for 60
/// degrees; more is a channel the tool fits in, which opening would leave uncut.
const CORNER_LOSS: f64 = 0.75;
/// Tolerance of the channels' outline, in radii, for the neighbourhood round
/// them ([`with_channels`]).
const NEAR_SIMPLIFY: f64 = 0.01;
/// Half of the sharpest corner angle whose engagement is held (a right angle).
const HALF_CORNER: f64 = std::f64::consts::FRAC_PI_4;

/// The band a tool of radius `radius` may cut at engagement `phi` (radians) on an
/// arc of radius `rho` turning towards the cleared side (module doc), mm.
pub(crate) fn band(rho: f64, radius: f64, phi: f64) -> f64 {
    rho + radius - (rho * rho + radius * radius + 2.0 * rho * radius * phi.cos()).sqrt()
}

/// The stepover that holds engagement `phi` in right-angled corners opened by `rho`.
pub(crate) fn stepover(rho: f64, radius: f64, phi: f64) -> f64 {
    band(rho, radius, phi) * HALF_CORNER.sin()
}

/// `poly` offset by `d` (inwards when negative), round joins.
pub(crate) fn offset(poly: &Polygon, d: f64) -> MultiPolygon {
    poly.buffer_with_style(BufferStyle::new(d).line_join(LineJoin::Round(JOIN_ANGLE)))
}

/// `region` opened by `rho`, or by half of it when that leaves nothing, and so on
/// [`HALVINGS`] times (module doc), with the radius that opened it; `None` when
/// every try leaves nothing. Channels that the opening would take whole (more than
/// a corner's rounding: [`CORNER_LOSS`]) are kept, opened by the halved radii
/// ([`with_channels`]).
pub(crate) fn opened(region: &Polygon, rho: f64) -> Option<(MultiPolygon, f64)> {
    (0..HALVINGS).find_map(|h| {
        let r = rho / f64::from(1u32 << h);
        let grown = open(region, r)?;
        Some((with_channels(region, grown, r, HALVINGS - 1 - h), r))
    })
}

/// `region` opened by `r` (eroded, dilated); `None` when nothing is left.
fn open(region: &Polygon, r: f64) -> Option<MultiPolygon> {
    let shrunk = offset(region, -r);
    if shrunk.unsigned_area() <= 0.0 {
        return None;
    }
    let grown: Vec<Polygon> = shrunk.iter().flat_map(|p| offset(p, r)).collect();
    (!grown.is_empty()).then(|| MultiPolygon::new(grown))
}

/// `grown` (`region` opened by `r`) with the channels it lost put back: each part
/// of `region` it misses that is more than a corner's rounding, as far as the
/// region opened by half the radius covers it, and so on `halvings` times; past
/// that the channel is kept sharp.
fn with_channels(region: &Polygon, grown: MultiPolygon, r: f64, halvings: u32) -> MultiPolygon {
    let whole = MultiPolygon::new(vec![region.clone()]);
    let lost = whole.difference(&grown);
    let channels: Vec<Polygon> = lost
        .into_iter()
        .filter(|p| p.unsigned_area() > CORNER_LOSS * r * r)
        .collect();
    if channels.is_empty() {
        return grown;
    }
    // The channels and a radius round them (where they join the rest). Only a
    // neighbourhood, cut from the region opened finer: simplified first, as the
    // lost slivers' many tiny edges would each get a round join.
    let near = MultiPolygon::new(
        channels
            .iter()
            .flat_map(|c| offset(&c.simplify(NEAR_SIMPLIFY * r), r))
            .collect(),
    );
    let finer = match (halvings > 0).then(|| open(region, r / 2.0)).flatten() {
        Some(f) => with_channels(region, f, r / 2.0, halvings - 1),
        None => whole,
    };
    grown.union(&finer.intersection(&near))
}

/// The smallest radius [`opened`] tries for `rho`.
pub(crate) fn smallest(rho: f64) -> f64 {
    rho / f64::from(1u32 << (HALVINGS - 1))
}

/// The loops of `poly`: its exterior counter-clockwise, then its holes clockwise
/// (the last point, a repeat of the first, dropped).
pub(crate) fn loops_of(poly: &Polygon) -> Vec<Ring> {
    std::iter::once(oriented(poly.exterior(), true))
        .chain(poly.interiors().iter().map(|h| oriented(h, false)))
        .collect()
}

/// A closed line string as a ring (last point dropped), counter-clockwise or not.
fn oriented(ls: &LineString, ccw: bool) -> Ring {
    let mut pts: Ring = ls.0.iter().map(|c| [c.x, c.y]).collect();
    if pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    let area = Polygon::new(ls.clone(), Vec::new()).signed_area();
    if (area > 0.0) != ccw {
        pts.reverse();
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::Coord;

    #[test]
    fn band_is_the_straight_one_far_out_and_nothing_at_a_pivot() {
        let r = 5.0;
        let phi = 60f64.to_radians();
        assert!((band(1e9, r, phi) - r * (1.0 - phi.cos())).abs() < 1e-6);
        assert!(band(0.0, r, phi).abs() < 1e-12);
        // rho = R, 60 degrees: 2R - R sqrt(3).
        assert!((band(r, r, phi) - r * (2.0 - 3f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn opening_rounds_the_corners_of_a_square() {
        let poly = |pts: &[[f64; 2]]| {
            Polygon::new(
                LineString::new(pts.iter().map(|p| Coord { x: p[0], y: p[1] }).collect()),
                Vec::new(),
            )
        };
        let (out, r) = opened(
            &poly(&[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]),
            2.0,
        )
        .unwrap();
        assert_eq!(r, 2.0);
        assert_eq!(out.0.len(), 1);
        let area = out.unsigned_area();
        // 100 less the four corners (2² - pi 2² / 4 each), to the joins' sag.
        let want = 100.0 - 4.0 * (4.0 - std::f64::consts::PI);
        assert!(area > 0.0 && (area - want).abs() < 0.02, "{area} vs {want}");
        // A strip 1 wide: opened by 2 / 8 = 0.25 after three halvings.
        let strip = opened(
            &poly(&[[0.0, 0.0], [10.0, 0.0], [10.0, 1.0], [0.0, 1.0]]),
            2.0,
        );
        let (strip, r) = strip.unwrap();
        assert_eq!(r, 0.25);
        let a = strip.unsigned_area();
        assert!(
            (a - (10.0 - 0.0625 * (4.0 - std::f64::consts::PI))).abs() < 0.01,
            "{a}"
        );
        let sliver = [[0.0, 0.0], [10.0, 0.0], [10.0, 0.1], [0.0, 0.1]];
        assert!(opened(&poly(&sliver), 2.0).is_none());
        let ring = loops_of(&poly(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]));
        assert_eq!(
            ring[0],
            vec![[1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]
        );
    }
}
