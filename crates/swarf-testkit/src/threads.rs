//! Running a computation on a given number of threads, for the tests that hold
//! results to be the same single- or multi-threaded.

/// `f` run inside a rayon pool of `threads` threads.
///
/// # Panics
/// When the pool cannot be built (a test fixture: the test fails).
pub fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a rayon pool")
        .install(f)
}
