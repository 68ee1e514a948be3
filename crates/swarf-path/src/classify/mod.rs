//! Steep, horizontal and other areas of a triangle mesh (thesis 002 §6.1): the
//! classification that steep-and-shallow finishing splits a part by.
//!
//! **Triangles** (§6.1.2). With `a = +z` the tool axis and `n` a triangle's unit
//! normal, `n . a = cos s` where `s` is the facet's slope from horizontal. A triangle
//! is *steep* when `n . a < cos(steep_angle)` (walls, vertical faces and overhangs
//! included), *horizontal* when `n . a > cos(flat_angle)`, *other* in between;
//! `flat_angle < steep_angle` keeps the two apart. With a feed angle `phi` the slope
//! is the one raster passes fed along `phi` see instead (thesis 002 §3.1.2): with
//! `c = (-sin phi, cos phi, 0)` across the passes, `sin s_c = |n . c|`, the slope of
//! the facet's section normal to the feed (the passes then lie `d / cos(s_c)` apart
//! along the facet); a wall the passes run down has `s_c = 0`. Degenerate triangles (no normal)
//! have no class and no area; nor have triangles facing down (`n . a < 0` beyond
//! vertical), which a tool coming from above never sees: the bottom of a closed
//! solid would otherwise cover the whole part as steep.
//!
//! **Go board** (§6.1.1, the AMDB grid). Square cells of side `cell` cover the mesh's
//! XY box; each cell holds the triangles whose XY projection meets it (a positive
//! area of it; for a vertical triangle, whose projection is a segment, a positive
//! length). A cell takes the strongest class it holds: steep over horizontal over
//! other (the thesis marks a cell steep or horizontal from its triangles; a steep
//! wall must never be hidden by the floor beside it, and horizontal is the class
//! whose tool path differs most from the rest). Cells with no triangle have no class.
//!
//! **Regions** (§6.1.2, the boundary tracing refined by the triangles of the boundary
//! cells). A cell is *interior* when its eight neighbours exist and share its class;
//! it joins its class's region whole. In the other (boundary) cells each class gets
//! the exact XY projection of its triangles clipped to the cell; a vertical steep
//! triangle has no XY area, so a cell it meets is steep whole. The regions are the
//! unions of those pieces, made disjoint by the same precedence (horizontal minus
//! steep, other minus both). So every steep triangle's XY footprint lies in the steep
//! region, a class's region differs from the exact projection of its triangles only
//! in interior cells of another class and in the cells of vertical walls, and the XY
//! area error of the steep region is at most about one cell times its perimeter.
//!
//! Deterministic: triangles are binned and clipped in parallel but collected in mesh
//! order, and the unions run in one thread.

mod board;
mod regions;

use crate::error::PathError;
use geo::MultiPolygon;
use rayon::prelude::*;
use swarf_geom::units::shown_degrees;
use swarf_geom::{TriMesh, Vec3};

/// Most cells the Go board may have: a finer cell over a larger part is refused
/// before anything is allocated.
pub const MAX_CELLS: usize = 1 << 24;

/// Most (triangle, cell) pairs the binning may visit, counted over the triangles'
/// XY boxes before binning.
pub const MAX_INCIDENCES: usize = 1 << 26;

/// Parameters of the classification (thesis 002 §6.1.2: `alpha`, `beta` and the grid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClassifyParams {
    /// Facets sloping more than this from horizontal are steep, radians, in
    /// `(0, pi/2]`. Default 40 degrees: the flat-model raster's scallop grows as
    /// `1 / cos² s` with the slope `s` (1.7 times at 40, twice at 45), and 45-degree
    /// walls, a common design angle, then classify as steep with a margin.
    pub steep_angle: f64,
    /// Facets sloping less than this are horizontal, radians, in `[0, steep_angle)`.
    /// Default 10 degrees: a raster there spaces its passes within 1.5 % of the
    /// flat step, while a Z-level path would space them `1 / sin 10` = 5.8 times its
    /// Z step.
    pub flat_angle: f64,
    /// Side of the square Go-board cells, mm; finite and `> 0`. Default 1.
    pub cell: f64,
    /// Slopes measured across raster passes fed along this XY angle (from +X,
    /// radians; module doc) instead of the steepest slope. Default `None`.
    pub feed_angle: Option<f64>,
}

impl Default for ClassifyParams {
    fn default() -> Self {
        ClassifyParams {
            steep_angle: 40f64.to_radians(),
            flat_angle: 10f64.to_radians(),
            cell: 1.0,
            feed_angle: None,
        }
    }
}

impl ClassifyParams {
    /// Checks the ranges in the field docs.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming `classify.steep_angle`,
    /// `classify.flat_angle` (with both values in degrees when they are out of
    /// order) or `classify.cell`.
    pub fn validate(&self) -> Result<(), PathError> {
        let bad = |field: &str, message: String| {
            Err(PathError::InvalidParameter {
                field: field.into(),
                message,
            })
        };
        let right = std::f64::consts::FRAC_PI_2;
        if !(self.steep_angle > 0.0 && self.steep_angle <= right) {
            return bad(
                "classify.steep_angle",
                format!(
                    "{} degrees: expected an angle above 0 and at most 90 degrees",
                    shown_degrees(self.steep_angle)
                ),
            );
        }
        if !(self.flat_angle >= 0.0 && self.flat_angle < right) {
            return bad(
                "classify.flat_angle",
                format!(
                    "{} degrees: expected an angle of at least 0 and below 90 degrees",
                    shown_degrees(self.flat_angle)
                ),
            );
        }
        if self.flat_angle >= self.steep_angle {
            return bad(
                "classify.steep_angle",
                format!(
                    "{} degrees is not above classify.flat_angle = {} degrees: expected \
                     the steep angle above the flat angle",
                    shown_degrees(self.steep_angle),
                    shown_degrees(self.flat_angle)
                ),
            );
        }
        if !(self.cell.is_finite() && self.cell > 0.0) {
            return bad(
                "classify.cell",
                format!(
                    "{} mm: expected a finite cell size above 0",
                    swarf_geom::domain::show(self.cell)
                ),
            );
        }
        if self.feed_angle.is_some_and(|a| !a.is_finite()) {
            return bad("classify.feed_angle", "expected a finite angle".to_string());
        }
        Ok(())
    }

    /// The class of a facet with unit normal `normal` (module doc).
    pub fn class_of(&self, normal: &Vec3) -> SurfaceClass {
        let (steep, flat) = match self.feed_angle {
            None => (
                normal.z < self.steep_angle.cos(),
                normal.z > self.flat_angle.cos(),
            ),
            Some(phi) => {
                let across = (normal.y * phi.cos() - normal.x * phi.sin()).abs();
                (
                    across > self.steep_angle.sin(),
                    across < self.flat_angle.sin(),
                )
            }
        };
        if steep {
            SurfaceClass::Steep
        } else if flat {
            SurfaceClass::Horizontal
        } else {
            SurfaceClass::Other
        }
    }
}

/// The class of a triangle or a Go-board cell, weakest first (`Ord` is the
/// precedence of the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SurfaceClass {
    /// Neither steep nor horizontal.
    Other,
    /// Sloping less than the flat angle.
    Horizontal,
    /// Sloping more than the steep angle.
    Steep,
}

impl SurfaceClass {
    /// The three classes, strongest first.
    pub const ALL: [SurfaceClass; 3] = [
        SurfaceClass::Steep,
        SurfaceClass::Horizontal,
        SurfaceClass::Other,
    ];

    /// Lowercase name: `steep`, `horizontal`, `other`.
    pub fn name(self) -> &'static str {
        match self {
            SurfaceClass::Steep => "steep",
            SurfaceClass::Horizontal => "horizontal",
            SurfaceClass::Other => "other",
        }
    }
}

/// The Go board: a class per cell (`None` where no triangle is), row by row.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ClassGrid {
    /// XY of the first cell's lower-left corner, mm.
    pub origin: [f64; 2],
    /// Side of a cell, mm.
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Class of cell `(i, j)` at `j * nx + i`.
    pub classes: Vec<Option<SurfaceClass>>,
}

/// One class's share of the part.
#[derive(Debug, Clone, PartialEq)]
pub struct ClassRegion {
    /// The region in XY (module doc), mm.
    pub region: MultiPolygon<f64>,
    /// Area of `region`, mm².
    pub xy_area: f64,
    /// Total 3D area of the class's triangles, mm².
    pub surface_area: f64,
    /// Number of the class's triangles.
    pub triangles: usize,
    /// Number of Go-board cells of the class.
    pub cells: usize,
}

impl Default for ClassRegion {
    fn default() -> Self {
        ClassRegion {
            region: MultiPolygon::new(Vec::new()),
            xy_area: 0.0,
            surface_area: 0.0,
            triangles: 0,
            cells: 0,
        }
    }
}

/// The classification of a mesh: three regions and the Go board they came from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Classification {
    /// Steep areas.
    pub steep: ClassRegion,
    /// Horizontal areas.
    pub horizontal: ClassRegion,
    /// The rest of the part.
    pub other: ClassRegion,
    /// Class of each triangle in mesh order (`None`: degenerate or facing down).
    pub triangle_classes: Vec<Option<SurfaceClass>>,
    /// Number of degenerate triangles (no normal; left out).
    pub degenerate: usize,
    /// Number of triangles facing down, hidden from a tool coming from above (the
    /// bottom of a closed solid, undercuts; left out).
    pub facing_down: usize,
    /// The Go board.
    pub grid: ClassGrid,
}

impl Classification {
    /// The region of `class`.
    pub fn region(&self, class: SurfaceClass) -> &ClassRegion {
        match class {
            SurfaceClass::Steep => &self.steep,
            SurfaceClass::Horizontal => &self.horizontal,
            SurfaceClass::Other => &self.other,
        }
    }
}

/// Classifies `mesh` into steep, horizontal and other areas (module doc).
///
/// # Units
/// Angles in radians, lengths in mm, areas in mm².
///
/// # Errors
/// [`PathError::InvalidParameter`] for parameters out of range
/// ([`ClassifyParams::validate`]) and on `classify.cell` for a board of more than
/// [`MAX_CELLS`] cells or [`MAX_INCIDENCES`] (triangle, cell) pairs.
///
/// # Example
/// ```
/// use swarf_path::classify::{classify, ClassifyParams};
/// let boss = swarf_io::builtin_mesh("boss").unwrap();
/// let c = classify(&boss, &ClassifyParams::default()).unwrap();
/// assert!((c.steep.surface_area - 7252.83).abs() < 0.01);
/// assert!(c.horizontal.xy_area > 8000.0 && c.other.triangles == 0);
/// ```
pub fn classify(mesh: &TriMesh, params: &ClassifyParams) -> Result<Classification, PathError> {
    params.validate()?;
    let tris: Vec<board::Facet> = (0..mesh.len())
        .into_par_iter()
        .map(|i| board::Facet::new(mesh, i, params))
        .collect();
    let Some(board) = board::Board::new(&tris, params.cell)? else {
        return Ok(Classification {
            triangle_classes: tris.iter().map(|t| t.class).collect(),
            degenerate: tris.iter().filter(|t| t.degenerate).count(),
            facing_down: tris.iter().filter(|t| !t.degenerate).count(),
            ..Classification::default()
        });
    };
    let cells = board.bin(&tris);
    let grid = board.classes(&tris, &cells);
    let [steep, horizontal, other] = regions::regions(&board, &grid, &tris, &cells);
    let share = |class: SurfaceClass, region: MultiPolygon<f64>| {
        let of = tris.iter().filter(|t| t.class == Some(class));
        ClassRegion {
            xy_area: geo::Area::unsigned_area(&region),
            region,
            surface_area: of.clone().fold(0.0, |sum, t| sum + t.area),
            triangles: of.count(),
            cells: grid.classes.iter().filter(|c| **c == Some(class)).count(),
        }
    };
    Ok(Classification {
        steep: share(SurfaceClass::Steep, steep),
        horizontal: share(SurfaceClass::Horizontal, horizontal),
        other: share(SurfaceClass::Other, other),
        degenerate: tris.iter().filter(|t| t.degenerate).count(),
        facing_down: tris
            .iter()
            .filter(|t| !t.degenerate && t.class.is_none())
            .count(),
        triangle_classes: tris.iter().map(|t| t.class).collect(),
        grid,
    })
}

#[cfg(test)]
mod tests;
