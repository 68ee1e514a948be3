//! swarf-report: what the machinist reads: pictures (PNG) and 3D scenes (glTF).
//!
//! Drawing primitives, independent of the simulator:
//! - [`canvas`]: a small RGB raster (rectangles, lines, rings, anti-aliased text in
//!   an embedded DejaVu Sans subset) and its PNG encoding.
//! - [`page`]: the layout of a report picture: map at one scale, axes with tick
//!   labels, legend, wrapped title and footer, every text box placed clear of the
//!   others ([`page::Cells`]: the cell lattice a map shows).
//!
//! Pictures of results:
//! - [`picture`]: the deviation heat map (a percentile colour scale, the tolerance
//!   band neutral) and the tool-path picture of a dexel verification (swarf-sim).
//! - [`rest_picture`]: rest regions over the part.
//! - [`classify_picture`]: steep, horizontal and other areas over the part.
//! - [`chart`]: bar charts of figures without a map (material left at an edge's
//!   stations, the stock after each operation of a sequence).
//!
//! Pages:
//! - [`html`]: a self-contained report page (inline CSS, no script) of console text,
//!   tables, pictures and links, and the relative links it holds.
//!
//! 3D scenes:
//! - [`gltf`]: GLB files of the design, the tool path, the cutter and the simulated
//!   stock coloured by deviation, for the viewer page and any glTF viewer.
//!
//! Units: millimetres in the world, pixels on the canvas.

pub mod canvas;
pub mod chart;
pub mod classify_picture;
pub mod error;
pub mod gltf;
pub mod html;
pub mod page;
pub mod picture;
pub mod rest_picture;

pub use error::ReportError;
