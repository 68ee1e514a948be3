//! Rest regions: raw pieces from the samples, then the boundary operations of
//! thesis 002 §5.3.
//!
//! **Raw pieces.** Pairs (valley double contacts, ramp points) are grouped by the
//! spatial directory ([`crate::directory`], pitch `p`) and each group ordered into
//! chains ([`crate::order`]). The rest under a group is the polygon `A A' A'' B'' B'
//! B` of the thesis's figure 24: the union of the convex hulls of consecutive pairs
//! of a chain (the contacts of two neighbouring poses and the material between them)
//! and of a strip of half-width `p/4` around each pair's own segment (a lone pair
//! has no area otherwise). Two neighbouring directory vertices only join when the
//! part between their samples is not above both tool tips by more than `p`
//! ([`linked`]): a thin high wall between two valleys keeps them apart (the thesis
//! asks for this test and leaves it open; under a valley's tool the part is below
//! the tip). In-process stock gives pieces directly as cells ([`crate::stock`]).
//!
//! **Boundary operations**, on the union of all pieces, with geo's buffers
//! (polygon offsets with round joins) and booleans:
//! 1. *smoothing and merging*: a morphological closing, offset out by
//!    `c = max(smoothness, merge / 2)` then back in by `c`. It rounds concave
//!    corners to radius `c`, fills gaps narrower than `2c` (pieces closer than
//!    `merge` become one region) and always contains what it closes (every raw point
//!    is within `c` of the outward offset's boundary... and inside it);
//! 2. *deletion*: a region whose raw area (the pieces' union inside it) is below
//!    `min_area` is dropped;
//! 3. *overlap*: each surviving region is offset out by `overlap`, for a margin of
//!    cleanup around what detection found and a smooth transition to the finishing
//!    path. Regions stay apart even where their overlaps meet: merging is the merge
//!    distance's business alone.
//!
//! The final boundaries therefore contain the raw regions they come from; the tests
//! check it point by point.

use crate::directory::group;
use crate::error::RestError;
use crate::order::{chains, open_path};
use crate::pair::{RestKind, RestPair};
use geo::{
    Area, BooleanOps, BoundingRect, Buffer, ConvexHull, Coord, Intersects, LineString, MultiPoint,
    MultiPolygon, Point, Polygon, unary_union,
};
use swarf_geom::Point3;
use swarf_geom::domain::Domain;
use swarf_tool::drop::MeshDropper;

/// Consecutive samples of a chain at most this many directory pitches apart are
/// joined (neighbouring vertices are at most `sqrt 2` pitches apart, and each
/// sample up to `sqrt 2 / 2` from its vertex).
pub const LINK_PITCHES: f64 = 3.0;

/// Half-width of the strip around a pair's own segment, in directory pitches.
pub const STRIP_PITCHES: f64 = 0.05;

/// Parameters of the boundary operations (thesis 002 §5.3), all mm or mm².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionParams {
    /// Samples shallower than this are not rest (the machining tolerance plus the
    /// scallop the parent leaves anyway), mm; `>= 0`.
    pub threshold: f64,
    /// Regions closer than this become one, mm; `> 0`.
    pub merge: f64,
    /// Outward offset of the final boundaries, mm; `> 0`.
    pub overlap: f64,
    /// Regions with less raw area than this are dropped, mm²; `> 0`.
    pub min_area: f64,
    /// Concave corners of the boundaries are rounded at least to this radius, mm;
    /// `>= 0`.
    pub smoothness: f64,
}

impl Default for RegionParams {
    fn default() -> Self {
        RegionParams {
            threshold: 0.01,
            merge: 2.0,
            overlap: 1.0,
            min_area: 0.5,
            smoothness: 0.5,
        }
    }
}

/// Rest thickness thresholds, mm.
pub const THRESHOLD: Domain = Domain::new(0.0, 1000.0, "mm", "a rest thickness");
/// Merge distances between regions, mm.
pub const MERGE: Domain = Domain::new(1e-3, 1000.0, "mm", "a merge distance");
/// Outward offsets of region boundaries, mm.
pub const OVERLAP: Domain = Domain::new(1e-3, 1000.0, "mm", "an overlap");
/// Least raw area of a region, mm².
pub const MIN_AREA: Domain = Domain::new(1e-6, 1e12, "mm²", "a least region area");
/// Corner rounding radii of region boundaries, mm.
pub const SMOOTHNESS: Domain = Domain::new(0.0, 1000.0, "mm", "a corner radius");

impl RegionParams {
    /// The parameters with their names (as the job's strategy table names them) and
    /// domains.
    pub fn domains(&self) -> [(&'static str, f64, Domain); 5] {
        [
            ("threshold", self.threshold, THRESHOLD),
            ("merge", self.merge, MERGE),
            ("overlap", self.overlap, OVERLAP),
            ("min_area", self.min_area, MIN_AREA),
            ("smoothness", self.smoothness, SMOOTHNESS),
        ]
    }

    /// Checks every domain (see the fields and [`RegionParams::domains`]).
    ///
    /// # Errors
    /// [`RestError::InvalidParameter`] naming the field.
    pub fn validate(&self) -> Result<(), RestError> {
        for (name, value, domain) in self.domains() {
            domain
                .check(value)
                .map_err(|expected| RestError::InvalidParameter {
                    field: name.to_string(),
                    value: swarf_geom::domain::show(value),
                    expected: expected
                        .strip_prefix("expected ")
                        .unwrap_or(&expected)
                        .to_string(),
                })?;
        }
        Ok(())
    }
}

/// A raw piece of rest: a group of samples (or stock cells) and its shape.
#[derive(Debug, Clone)]
pub struct RawPiece {
    /// What left it (sorted, no repeats).
    pub kinds: Vec<RestKind>,
    /// Its shape in XY.
    pub shape: MultiPolygon<f64>,
    /// Largest rest thickness in it, mm.
    pub depth: f64,
    /// Where that is, mm.
    pub deepest: Point3,
    /// Its samples (none for stock cells), in chain order.
    pub pairs: Vec<RestPair>,
    /// The ordered chains, as index ranges into `pairs`.
    pub chains: Vec<std::ops::Range<usize>>,
}

/// One rest region after the boundary operations.
#[derive(Debug, Clone)]
pub struct RestRegion {
    /// The kinds of rest it holds, sorted.
    pub kinds: Vec<RestKind>,
    /// The final boundary (smoothed, merged, with the overlap).
    pub boundary: Polygon<f64>,
    /// What detection found inside it (the union of its raw pieces), before the
    /// boundary operations.
    pub raw: MultiPolygon<f64>,
    /// Area of `raw`, mm².
    pub raw_area: f64,
    /// Area inside `boundary`, mm².
    pub area: f64,
    /// Largest rest thickness, mm.
    pub depth: f64,
    /// Where that is, mm.
    pub deepest: Point3,
    /// The samples inside, chain by chain.
    pub pairs: Vec<RestPair>,
    /// The ordered chains, as index ranges into `pairs`.
    pub chains: Vec<std::ops::Range<usize>>,
}

/// True when the part between the centres of samples `a` and `b` is not above both
/// tool tips by more than `pitch` (no thin wall between them; module doc).
pub fn linked(dropper: &MeshDropper, a: &RestPair, b: &RestPair, pitch: f64) -> bool {
    let (ca, cb) = (a.centre(), b.centre());
    let top = a.cl.z.max(b.cl.z) + pitch;
    (1..4).all(|k| {
        let t = f64::from(k) / 4.0;
        let (x, y) = (ca[0] + t * (cb[0] - ca[0]), ca[1] + t * (cb[1] - ca[1]));
        dropper.surface_z(x, y).is_none_or(|z| z <= top)
    })
}

/// The raw pieces of `pairs` (those at least `threshold` deep): directory groups of
/// pitch `pitch`, ordered into chains, shaped as in the module doc.
pub fn pieces_from_pairs(
    dropper: &MeshDropper,
    pairs: &[RestPair],
    pitch: f64,
    threshold: f64,
) -> Vec<RawPiece> {
    let kept: Vec<RestPair> = pairs
        .iter()
        .filter(|p| p.depth >= threshold && p.depth.is_finite())
        .copied()
        .collect();
    let centres: Vec<[f64; 2]> = kept.iter().map(RestPair::centre).collect();
    let groups = group(&centres, pitch, |i, j| {
        linked(dropper, &kept[i], &kept[j], pitch)
    });
    groups
        .into_iter()
        .map(|g| {
            let pts: Vec<[f64; 2]> = g.iter().map(|&k| centres[k]).collect();
            let order = open_path(&pts);
            let mut pairs = Vec::with_capacity(g.len());
            let mut ranges = Vec::new();
            for chain in chains(&pts, &order, LINK_PITCHES * pitch) {
                let start = pairs.len();
                pairs.extend(chain.iter().map(|&i| kept[g[i]]));
                ranges.push(start..pairs.len());
            }
            piece_of(pairs, ranges, pitch)
        })
        .collect()
}

fn xy(p: &Point3) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

/// The shape of a group's chains (module doc).
fn piece_of(pairs: Vec<RestPair>, chains: Vec<std::ops::Range<usize>>, pitch: f64) -> RawPiece {
    let w = STRIP_PITCHES * pitch;
    let mut polys: Vec<Polygon<f64>> = pairs.iter().map(|p| strip(p, w)).collect();
    for r in &chains {
        for w in pairs[r.clone()].windows(2) {
            let pts: Vec<Point<f64>> = [w[0].a, w[0].b, w[1].a, w[1].b]
                .iter()
                .map(|p| Point::from(xy(p)))
                .collect();
            let hull = MultiPoint::from(pts).convex_hull();
            if hull.unsigned_area() > 0.0 {
                polys.push(hull);
            }
        }
    }
    let deepest = pairs
        .iter()
        .fold(None::<&RestPair>, |m, p| match m {
            Some(q) if q.depth >= p.depth => Some(q),
            _ => Some(p),
        })
        .map_or((0.0, Point3::origin()), |p| (p.depth, p.deepest));
    let mut kinds: Vec<RestKind> = pairs.iter().map(|p| p.kind).collect();
    kinds.sort();
    kinds.dedup();
    RawPiece {
        kinds,
        shape: unary_union(polys.iter()),
        depth: deepest.0,
        deepest: deepest.1,
        pairs,
        chains,
    }
}

/// The rectangle of half-width `w` around the segment `a b` of a pair (extended by
/// `w` past its ends).
fn strip(p: &RestPair, w: f64) -> Polygon<f64> {
    let (a, b) = (xy(&p.a), xy(&p.b));
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len = dx.hypot(dy);
    let (ux, uy) = if len > 0.0 {
        (dx / len, dy / len)
    } else {
        (1.0, 0.0)
    };
    let (nx, ny) = (-uy * w, ux * w);
    let (ex, ey) = (ux * w, uy * w);
    Polygon::new(
        LineString::from(vec![
            (a.x - ex + nx, a.y - ey + ny),
            (a.x - ex - nx, a.y - ey - ny),
            (b.x + ex - nx, b.y + ey - ny),
            (b.x + ex + nx, b.y + ey + ny),
        ]),
        vec![],
    )
}

/// The regions of `pieces` after the boundary operations (module doc), ordered by
/// their lowest-left corner.
///
/// # Errors
/// [`RestError::InvalidParameter`] for a parameter out of its domain.
pub fn regions(pieces: Vec<RawPiece>, params: &RegionParams) -> Result<Vec<RestRegion>, RestError> {
    params.validate()?;
    let raw = unary_union(pieces.iter().flat_map(|p| p.shape.0.iter()));
    let c = params.smoothness.max(0.5 * params.merge);
    let closed = raw.buffer(c).buffer(-c);
    let kept: Vec<Polygon<f64>> = closed
        .0
        .into_iter()
        .filter(|p| {
            raw.intersection(&MultiPolygon(vec![p.clone()]))
                .unsigned_area()
                >= params.min_area
        })
        .collect();
    let mut out: Vec<RestRegion> = kept
        .into_iter()
        .filter_map(|p| region_of(&p, params.overlap, &pieces))
        .collect();
    let corner = |r: &RestRegion| {
        r.boundary
            .bounding_rect()
            .map_or([0.0, 0.0], |b| [b.min().y, b.min().x])
    };
    out.sort_by(|a, b| {
        let (ka, kb) = (corner(a), corner(b));
        ka[0].total_cmp(&kb[0]).then(ka[1].total_cmp(&kb[1]))
    });
    Ok(out)
}

/// The region of the closed polygon `closed`: the pieces that meet it (each lies
/// inside one closed polygon: the closing contains what it closes), its boundary
/// grown by `overlap` (the largest polygon of the offset; `None` when it has none).
fn region_of(closed: &Polygon<f64>, overlap: f64, pieces: &[RawPiece]) -> Option<RestRegion> {
    let boundary = closed
        .buffer(overlap)
        .0
        .into_iter()
        .max_by(|a, b| a.unsigned_area().total_cmp(&b.unsigned_area()))?;
    let mine: Vec<&RawPiece> = pieces
        .iter()
        .filter(|p| p.shape.intersects(closed))
        .collect();
    let raw_inside = unary_union(mine.iter().flat_map(|p| p.shape.0.iter()));
    let mut kinds: Vec<RestKind> = mine.iter().flat_map(|p| p.kinds.iter().copied()).collect();
    kinds.sort();
    kinds.dedup();
    let mut pairs = Vec::new();
    let mut chains = Vec::new();
    for p in &mine {
        let base = pairs.len();
        pairs.extend(p.pairs.iter().copied());
        chains.extend(p.chains.iter().map(|r| base + r.start..base + r.end));
    }
    let deepest = mine
        .iter()
        .fold(None::<&&RawPiece>, |m, p| match m {
            Some(q) if q.depth >= p.depth => Some(q),
            _ => Some(p),
        })
        .map_or((0.0, Point3::origin()), |p| (p.depth, p.deepest));
    Some(RestRegion {
        kinds,
        area: boundary.unsigned_area(),
        boundary,
        raw_area: raw_inside.unsigned_area(),
        raw: raw_inside,
        depth: deepest.0,
        deepest: deepest.1,
        pairs,
        chains,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::Contains;

    fn square(x: f64, y: f64, s: f64) -> RawPiece {
        RawPiece {
            kinds: vec![RestKind::Stock],
            shape: MultiPolygon(vec![Polygon::new(
                LineString::from(vec![(x, y), (x + s, y), (x + s, y + s), (x, y + s)]),
                vec![],
            )]),
            depth: 1.0,
            deepest: Point3::new(x, y, 0.0),
            pairs: vec![],
            chains: vec![],
        }
    }

    #[test]
    fn merge_delete_and_overlap() {
        // Four 1x1 squares: two 1.5 apart, one 5 away, one tiny (0.2 x 0.2).
        let pieces = vec![
            square(0.0, 0.0, 1.0),
            square(2.5, 0.0, 1.0),
            square(8.5, 0.0, 1.0),
            square(20.0, 0.0, 0.2),
        ];
        let params = RegionParams {
            merge: 2.0,
            min_area: 0.1,
            overlap: 0.5,
            smoothness: 0.0,
            threshold: 0.0,
        };
        let r = regions(pieces.clone(), &params).unwrap();
        assert_eq!(
            r.len(),
            2,
            "{:?}",
            r.iter().map(|r| r.area).collect::<Vec<_>>()
        );
        assert!((r[0].raw_area - 2.0).abs() < 1e-9 && (r[1].raw_area - 1.0).abs() < 1e-9);
        // With a merge distance below the gap nothing merges.
        let apart = RegionParams {
            merge: 1.0,
            ..params
        };
        assert_eq!(regions(pieces.clone(), &apart).unwrap().len(), 3);
        // Every raw corner lies inside its final boundary.
        for region in &r {
            for poly in &region.raw {
                for c in poly.exterior().coords() {
                    assert!(region.boundary.contains(&Point::from(*c)), "{c:?}");
                }
            }
        }
        // Bad parameters are errors, naming the field.
        let e = regions(
            pieces,
            &RegionParams {
                overlap: 0.0,
                ..params
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("overlap"), "{e}");
    }
}
