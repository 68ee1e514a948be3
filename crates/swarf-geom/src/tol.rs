//! Named numeric epsilons (units in the names' docs). Machining tolerances are
//! parameters of the algorithms, not constants: these are only for numerics.

/// Lengths below this are treated as zero (mm).
pub const LENGTH_EPS: f64 = 1e-12;
/// Convergence target of iterative geometric solvers on lengths (mm).
pub const SOLVER_LENGTH: f64 = 1e-11;
/// Convergence target of iterative solvers on surface parameters (dimensionless).
pub const SOLVER_PARAM: f64 = 1e-14;
/// Cosines within this of 1 are treated as parallel (dimensionless).
pub const PARALLEL_COS: f64 = 1e-12;
/// Smallest patch a part may hold: the longest side of the box of its control points
/// (mm).
/// Far below any machined feature (1 nm), and far above the sizes where the products of
/// derivatives in a patch's normal and curvature underflow (a 1e-200 mm patch has
/// `S_u x S_v = 0` in f64 and infinite curvature); curvatures stay below about 1e6 /mm.
pub const MIN_PATCH_EXTENT: f64 = 1e-6;
/// Largest number of Newton iterations of the local solvers.
pub const MAX_NEWTON_ITERATIONS: usize = 50;
