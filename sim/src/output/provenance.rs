//! Where an output came from: the version (with the git revision when built
//! from a checkout) and the command line, written into every output.

/// `umbra <version>`, with ` (git <revision>)` when built from a checkout
/// (`-modified` when its tracked files differed from the revision).
#[must_use]
pub fn version() -> String {
    let revision = env!("UMBRA_GIT_REVISION");
    if revision.is_empty() {
        format!("umbra {}", env!("CARGO_PKG_VERSION"))
    } else {
        format!("umbra {} (git {revision})", env!("CARGO_PKG_VERSION"))
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
