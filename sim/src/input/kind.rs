//! What kind of file a user gave, read from its first bytes — a scene
//! file, an OBJ mesh or a glTF model — so that a file given where another
//! kind is read is named for what it is, with what reads it.

/// A kind of file the simulator reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// A TOML scene file (`[camera]`, `[[lights]]`, `[[objects]]`).
    Scene,
    /// A Wavefront OBJ mesh (`v`, `f` records).
    Obj,
    /// A glTF 2.0 model: JSON with an `asset`, or a binary `.glb`.
    Gltf,
}

/// How many bytes of a file its kind is read from.
const HEAD: usize = 4096;

impl FileKind {
    /// The kind `bytes` (a file's contents, or their start) show, if they
    /// show one.
    ///
    /// ```
    /// use umbra_sim::input::kind::FileKind;
    /// assert_eq!(FileKind::of(b"# a mesh\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), Some(FileKind::Obj));
    /// assert_eq!(FileKind::of(b"name = \"x\"\n[camera]\nfov = 50.0\n"), Some(FileKind::Scene));
    /// assert_eq!(FileKind::of(b"{\"asset\": {\"version\": \"2.0\"}}"), Some(FileKind::Gltf));
    /// assert_eq!(FileKind::of(b"hello"), None);
    /// ```
    #[must_use]
    pub fn of(bytes: &[u8]) -> Option<Self> {
        let head = bytes.get(..HEAD).unwrap_or(bytes);
        if head.starts_with(b"glTF") {
            return Some(Self::Gltf);
        }
        let text = String::from_utf8_lossy(head);
        if text.trim_start().starts_with('{') && text.contains("\"asset\"") {
            return Some(Self::Gltf);
        }
        let records = || text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#'));
        if records().any(|l| ["[camera]", "[[lights]]", "[[objects]]"].contains(&l)) {
            return Some(Self::Scene);
        }
        let obj = |l: &str| {
            let word = l.split_whitespace().next().unwrap_or("");
            ["v", "vn", "vt", "f", "o", "g", "s", "l", "p", "mtllib", "usemtl"].contains(&word) && !l.contains('=')
        };
        (records().take(8).any(|l| l.starts_with("v ")) && records().take(8).all(obj)).then_some(Self::Obj)
    }

    /// What it is, in words.
    #[must_use]
    pub const fn what(self) -> &'static str {
        match self {
            Self::Scene => "a scene file",
            Self::Obj => "an OBJ mesh",
            Self::Gltf => "a glTF model",
        }
    }

    /// What reads it.
    #[must_use]
    pub const fn read_by(self) -> &'static str {
        match self {
            Self::Scene => "`umbra render FILE` renders it",
            Self::Obj => {
                "`umbra depth --mesh FILE` draws it, and a scene file places it with `mesh = { obj = \"FILE\" }`"
            }
            Self::Gltf => "`umbra render FILE.glb` (or `.gltf`) renders it, by its extension",
        }
    }
}
