//! The stock every job is cut from (`[stock]`, in a job and in a sequence): a block
//! over the part, the design raised by an allowance, or a mesh. Planning needs how
//! high it reaches ([`Stock::top`]): no rapid goes below the link's approach above
//! it ([`swarf_toolpath::Linking::material_top`]), and the default clearance plane
//! is above it. The passes are cut to where the tool may go
//! ([`swarf_toolpath::reach`]): above the floor ([`Stock::floor`]) and within the
//! tool's radius of the stock's XY box ([`Stock::footprint`]). A sequence cuts the
//! stock as its in-process dexel stock.
//!
//! Without a `[stock]` table a job is cut from a box 1 mm above the part, a
//! five-axis job from the design raised by 1 mm ([`Stock::near_net`]).
//!
//! ```toml
//! [stock]
//! kind = "box"          # "box" (top, margin), "offset" (allowance) or "mesh" (file)
//! top = 21              # box top, mm (default 1 mm above the part)
//! margin = 5            # box: XY margin round the part, mm
//! floor = 0             # lowest height of the tool tip, mm (default: the part's lowest point)
//! ```

use crate::error::{AppError, Result};
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::Path;
use swarf_geom::domain::show;
use swarf_geom::{Aabb, TriMesh};

/// Height of the default box stock above the part, mm.
pub const DEFAULT_BOX_ABOVE: f64 = 1.0;

/// The stock a job or a sequence starts from.
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Stock {
    /// `box`, `offset` or `mesh`.
    pub kind: StockKind,
    /// Box: top, mm (default 1 mm above the part; not below it).
    pub top: Option<f64>,
    /// Box: XY margin round the part, mm (0 to 1000).
    pub margin: f64,
    /// Offset: material above the design, mm (0 to 1000).
    pub allowance: f64,
    /// Mesh: the stock's file (STL or OBJ), relative to the job file.
    pub file: Option<String>,
    /// The lowest height the tool may reach, mm (its lowest point: a vertical tool's
    /// tip, a tilted tool's point facing straight down; default: the part's lowest
    /// point; not above the part's top): passes are cut where they would go below,
    /// and the verification gate refuses a motion below it.
    pub floor: Option<f64>,
    /// Cell of a sequence's in-process stock, mm (0.01 to 10).
    pub cell: f64,
    /// Gouge and rest tolerance of a sequence's per-operation reports, mm (more than
    /// 0, at most 10).
    pub tol: f64,
}

impl Default for Stock {
    fn default() -> Self {
        Stock {
            kind: StockKind::Box,
            top: None,
            margin: 0.0,
            allowance: 1.0,
            file: None,
            floor: None,
            cell: 0.25,
            tol: 0.01,
        }
    }
}

/// How the stock is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum StockKind {
    /// A block over the part's XY extent (grown by the margin).
    #[default]
    Box,
    /// The design raised by an allowance.
    Offset,
    /// A mesh's upper envelope.
    Mesh,
}

impl Stock {
    /// The default stock of a five-axis job: the design raised by the default
    /// allowance. A five-axis program finishes (or drops and spins at an edge) what
    /// roughing left near net; a tilted tool in a block is buried to its holder.
    pub fn near_net() -> Stock {
        Stock {
            kind: StockKind::Offset,
            ..Stock::default()
        }
    }

    /// Checks every field's domain.
    ///
    /// # Errors
    /// The first field out of its domain, as `stock.field: value: expected ...`.
    pub fn check(&self) -> std::result::Result<(), String> {
        let s = self;
        let cell_ok = s.cell.is_finite() && (0.01..=10.0).contains(&s.cell);
        if !cell_ok {
            return Err(format!(
                "stock.cell: {} mm: expected 0.01 to 10 mm",
                show(s.cell)
            ));
        }
        if !(s.tol.is_finite() && s.tol > 0.0 && s.tol <= 10.0) {
            return Err(format!(
                "stock.tol: {} mm: expected more than 0, at most 10 mm",
                show(s.tol)
            ));
        }
        if !(s.margin.is_finite() && (0.0..=1000.0).contains(&s.margin)) {
            return Err(format!(
                "stock.margin: {} mm: expected 0 to 1000 mm",
                show(s.margin)
            ));
        }
        if !(s.allowance.is_finite() && (0.0..=1000.0).contains(&s.allowance)) {
            return Err(format!(
                "stock.allowance: {} mm: expected 0 to 1000 mm",
                show(s.allowance)
            ));
        }
        if let Some(top) = s.top
            && !(top.is_finite() && top.abs() <= 1e6)
        {
            return Err(format!(
                "stock.top: {} mm: expected a height within 1e6 mm",
                show(top)
            ));
        }
        if let Some(floor) = s.floor
            && !(floor.is_finite() && floor.abs() <= 1e6)
        {
            return Err(format!(
                "stock.floor: {} mm: expected a height within 1e6 mm",
                show(floor)
            ));
        }
        if s.kind == StockKind::Mesh && s.file.is_none() {
            return Err("stock.file: a mesh stock needs its file (STL or OBJ)".into());
        }
        Ok(())
    }

    /// The mesh of a mesh stock, its file read relative to `dir` (`None` for the
    /// other kinds).
    ///
    /// # Errors
    /// A file that cannot be read, as `stock.file: ...`.
    pub fn mesh(&self, dir: &Path) -> Result<Option<TriMesh>> {
        if self.kind != StockKind::Mesh {
            return Ok(None);
        }
        let file = self.file.as_deref().unwrap_or_default();
        swarf_io::read_mesh(&dir.join(file))
            .map(Some)
            .map_err(|e| AppError::Message(format!("stock.file: {e}")))
    }

    /// How high the stock reaches over a part whose highest point is `part_top`, mm
    /// (`mesh`: the mesh stock, when there is one).
    ///
    /// # Errors
    /// A box top, or a mesh stock's top, below the part's top: the stock would not
    /// hold the part.
    pub fn top(&self, part_top: f64, mesh: Option<&TriMesh>) -> Result<f64> {
        let (top, field) = match (self.kind, mesh) {
            (StockKind::Mesh, Some(m)) => (m.aabb().max.z, "stock.file"),
            (StockKind::Offset, _) => (part_top + self.allowance, "stock.allowance"),
            _ => (
                self.top.unwrap_or(part_top + DEFAULT_BOX_ABOVE),
                "stock.top",
            ),
        };
        if top < part_top - 1e-9 {
            return Err(AppError::Message(format!(
                "{field}: the stock's top {} mm is below the part's top ({part_top:.3} mm): \
                 expected a stock that holds the part",
                show(top)
            )));
        }
        Ok(top)
    }

    /// The lowest height the tool may reach over a part whose lowest and
    /// highest points are `bottom` and `top`, mm: the job's `floor`, else `bottom`.
    ///
    /// # Errors
    /// A floor above the part's top.
    pub fn floor(&self, bottom: f64, top: f64) -> Result<f64> {
        let floor = self.floor.unwrap_or(bottom);
        if floor > top + 1e-9 {
            return Err(AppError::Message(format!(
                "stock.floor: {} mm is above the part's top ({top:.3} mm): expected a floor \
                 at or below the part's top",
                show(floor)
            )));
        }
        Ok(floor)
    }

    /// The stock's XY box, `[x_min, y_min, x_max, y_max]`, mm, over a part held in
    /// `part` (`mesh`: the mesh stock, when there is one): a box's grown by its
    /// margin, an offset's the part's, a mesh's its own.
    pub fn footprint(&self, part: &Aabb, mesh: Option<&TriMesh>) -> [f64; 4] {
        let (b, grow) = match (self.kind, mesh) {
            (StockKind::Mesh, Some(m)) => (m.aabb(), 0.0),
            (StockKind::Offset, _) => (*part, self.allowance),
            _ => (*part, self.margin),
        };
        [
            b.min.x - grow,
            b.min.y - grow,
            b.max.x + grow,
            b.max.y + grow,
        ]
    }
}
