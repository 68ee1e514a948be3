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
/// Largest number of Newton iterations of the local solvers.
pub const MAX_NEWTON_ITERATIONS: usize = 50;
