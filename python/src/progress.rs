//! Long work with the interpreter released, its progress reported to a
//! Python callback from the calling thread.

use std::time::{Duration, Instant};

use indicatif::ProgressBar;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// How often the callback hears of progress.
const EVERY: Duration = Duration::from_millis(200);

/// Run `work` on its own thread (on a pool of `threads` workers when
/// given, else rayon's global pool) with the interpreter released;
/// meanwhile, and once at the end, call `callback(done, total)` with
/// `bar`'s position and length from this thread.
///
/// # Errors
/// The callback's exception, or a `RuntimeError` if the work panicked
/// or the pool could not be built.
pub(crate) fn run<T: Send>(
    py: Python<'_>,
    bar: &ProgressBar,
    callback: Option<&Bound<'_, PyAny>>,
    threads: Option<usize>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    let pool = match threads {
        Some(0) => return Err(PyValueError::new_err("threads: must be at least 1")),
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("threads: {e}")))?,
        ),
        None => None,
    };
    let work = move || match &pool {
        Some(p) => p.install(work),
        None => work(),
    };
    let Some(callback) = callback else {
        return Ok(py.detach(work));
    };
    std::thread::scope(|s| {
        let handle = s.spawn(work);
        loop {
            let finished = py.detach(|| {
                let start = Instant::now();
                while !handle.is_finished() && start.elapsed() < EVERY {
                    std::thread::sleep(Duration::from_millis(5));
                }
                handle.is_finished()
            });
            callback.call1((bar.position(), bar.length().unwrap_or(0)))?;
            if finished {
                break;
            }
        }
        handle.join().map_err(|_| PyRuntimeError::new_err("the simulator stopped on an internal error"))
    })
}
