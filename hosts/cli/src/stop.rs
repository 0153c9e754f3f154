//! Ctrl-C and SIGTERM (what Slurm sends at a job's time limit): the first
//! asks the run to stop ([`umbra_sim::base::stop`]) — it finishes the
//! work under way, takes no more, leaves its output folder marked
//! unfinished and releases its lock, and the command exits with
//! [`STATUS`] — and the second exits at once.

use std::io::IsTerminal;

use anyhow::{Context, Result};

/// The exit status of a run stopped by a signal: 128 + SIGINT, as a shell
/// reports a command Ctrl-C ended.
pub(super) const STATUS: u8 = 130;

/// What the first signal prints, on stderr.
const STOPPING: &str = "stopping: finishing the work under way (a study's configurations, a render's reference); \
                        the output folder stays marked incomplete (Ctrl-C again to exit at once)";

/// Answer Ctrl-C and SIGTERM as the module says.
///
/// # Errors
/// When the handler cannot be installed.
pub(super) fn on_signals() -> Result<()> {
    ctrlc::set_handler(|| {
        if umbra_sim::base::stop::requested() {
            std::process::exit(i32::from(STATUS));
        }
        umbra_sim::base::stop::request();
        // On a terminal, below the line the echoed `^C` and a progress bar share.
        let below = if std::io::stderr().is_terminal() { "\n" } else { "" };
        eprintln!("{below}{STOPPING}");
    })
    .context("installing the Ctrl-C handler")
}
