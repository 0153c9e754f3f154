//! Where an output came from: the version (with the git revision of the
//! checkout it was built in) and the command line, written into every
//! output.

use std::path::Path;
use std::process::Command;
use std::sync::OnceLock;

/// `umbra <version>`, with ` (git <revision>)` when the checkout it was
/// built in is there to ask (`-modified` when its tracked files differ
/// from the revision). The revision is read from that checkout when first
/// asked, not stamped at build time, so a commit or checkout never
/// rebuilds the simulator.
#[must_use]
pub fn version() -> String {
    static REVISION: OnceLock<String> = OnceLock::new();
    let revision = REVISION.get_or_init(|| revision(Path::new(env!("CARGO_MANIFEST_DIR"))));
    if revision.is_empty() {
        format!("umbra {}", env!("CARGO_PKG_VERSION"))
    } else {
        format!("umbra {} (git {revision})", env!("CARGO_PKG_VERSION"))
    }
}

/// The short revision of the git checkout holding `dir`, `-modified` when
/// its tracked files differ from it; empty when there is none (a package
/// built from a source archive, a binary moved off its checkout).
fn revision(dir: &Path) -> String {
    let git = |args: &[&str]| {
        Command::new("git")
            .arg("-C")
            .arg(dir)
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
    };
    match git(&["rev-parse", "--short=12", "HEAD"]).filter(|r| !r.is_empty()) {
        None => String::new(),
        Some(r) if git(&["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty()) => {
            format!("{r}-modified")
        }
        Some(r) => r,
    }
}

/// `arg` as a POSIX shell word: as it is when it needs no quoting, else in
/// single quotes.
#[must_use]
pub(crate) fn shell_word(arg: &str) -> String {
    if !arg.is_empty() && arg.chars().all(|c| c.is_ascii_alphanumeric() || "-_./=,:+%@".contains(c)) {
        arg.to_owned()
    } else {
        format!("'{}'", arg.replace('\'', r"'\''"))
    }
}

/// An argument as the OS gave it, as a shell word: UTF-8 as
/// [`shell_word`] writes it; otherwise (Unix) in the `$'…'` quoting of
/// bash and zsh, each byte outside printable ASCII as `\ooo`, so the word
/// stands for the same bytes.
#[must_use]
pub(crate) fn os_shell_word(arg: &std::ffi::OsStr) -> String {
    if let Some(text) = arg.to_str() {
        return shell_word(text);
    }
    #[cfg(unix)]
    {
        use std::fmt::Write as _;
        use std::os::unix::ffi::OsStrExt;
        let mut word = String::from("$'");
        for &b in arg.as_bytes() {
            match b {
                b'\'' | b'\\' => {
                    word.push('\\');
                    word.push(char::from(b));
                }
                0x20..=0x7e => word.push(char::from(b)),
                _ => {
                    let _ = write!(word, "\\{b:03o}");
                }
            }
        }
        word.push('\'');
        word
    }
    #[cfg(not(unix))]
    shell_word(&arg.to_string_lossy())
}

/// This process's command line, each argument a shell word (an argument
/// that is not UTF-8 included: see `os_shell_word`).
#[must_use]
pub fn command_line() -> String {
    std::env::args_os().map(|a| os_shell_word(&a)).collect::<Vec<_>>().join(" ")
}

/// The FNV-1a 64-bit hash of `bytes`, in hex: names a sweep file's exact
/// text in its outputs (not a cryptographic digest; it tells sweeps apart).
#[must_use]
pub(crate) fn hash(bytes: &[u8]) -> String {
    let h = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3));
    format!("{h:016x}")
}

#[cfg(test)]
mod tests {
    use std::process::Command;

    /// The revision is the checkout's, read when asked: a repository's
    /// HEAD as `git` itself reports it, `-modified` once a tracked file
    /// changes, and nothing outside a repository.
    #[test]
    fn the_revision_is_the_checkouts_as_git_reports_it() {
        let dir = tempfile::tempdir().expect("temp dir");
        let d = dir.path();
        assert_eq!(super::revision(d), "", "no repository");
        let git = |args: &[&str]| {
            let o = Command::new("git")
                .arg("-C")
                .arg(d)
                .args(["-c", "user.name=u", "-c", "user.email=u@example.org"])
                .args(args)
                .output()
                .expect("git runs");
            assert!(o.status.success(), "git {args:?}: {}", String::from_utf8_lossy(&o.stderr));
            String::from_utf8_lossy(&o.stdout).trim().to_owned()
        };
        git(&["init", "-q"]);
        std::fs::write(d.join("a.txt"), "a").expect("write");
        git(&["add", "a.txt"]);
        git(&["commit", "-q", "-m", "a"]);
        let head = git(&["rev-parse", "HEAD"]);
        assert_eq!(super::revision(d), head[..12]);
        std::fs::write(d.join("a.txt"), "b").expect("write");
        assert_eq!(super::revision(d), format!("{}-modified", &head[..12]));
    }
}
