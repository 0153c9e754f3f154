//! Text broken into lines at spaces, the one way every writer of prose
//! fits a width: a picture's caption, the command's brief output.

/// `text` broken at spaces into lines of at most `chars` characters; a
/// word longer than a line stands on a line of its own, uncut.
///
/// ```
/// use umbra_sim::output::lines::lines;
/// assert_eq!(lines("a bb ccc dddd", 6), ["a bb", "ccc", "dddd"]);
/// assert_eq!(lines("verylongword x", 4), ["verylongword", "x"]);
/// ```
#[must_use]
pub fn lines(text: &str, chars: usize) -> Vec<String> {
    let mut out = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > chars {
            out.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    out.push(line);
    out
}
