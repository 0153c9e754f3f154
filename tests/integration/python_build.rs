//! The Python package builds into the workspace's target folder and reuses
//! what the workspace built there: cargo reuses a crate's build only under
//! the same release profile and the same version of every package, so
//! `python/` must state the folder, the profile and the versions as the
//! workspace does.

use std::collections::BTreeMap;
use std::path::Path;

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// `[[package]]` name → versions in a `Cargo.lock` (a name can be locked
/// at more than one version).
fn locked(path: &Path) -> BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(path).expect("a lock file");
    let mut packages: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for block in text.split("[[package]]").skip(1) {
        let field = |key: &str| {
            block.lines().find_map(|l| {
                l.strip_prefix(key)?
                    .trim()
                    .strip_prefix('=')?
                    .trim()
                    .strip_prefix('"')?
                    .strip_suffix('"')
                    .map(str::to_owned)
            })
        };
        let (Some(name), Some(version)) = (field("name "), field("version ")) else {
            panic!("{}: a package without name or version", path.display())
        };
        packages.entry(name).or_default().push(version);
    }
    packages
}

/// The lines of `[profile.release]` in a manifest, comments dropped.
fn release_profile(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("a manifest");
    text.lines()
        .skip_while(|l| l.trim() != "[profile.release]")
        .skip(1)
        .take_while(|l| !l.trim_start().starts_with('['))
        .map(|l| l.split('#').next().unwrap_or("").trim().to_owned())
        .filter(|l| !l.is_empty())
        .collect()
}

#[test]
fn python_reuses_the_workspaces_build() {
    let workspace = locked(&root().join("Cargo.lock"));
    let python = locked(&root().join("python/Cargo.lock"));
    let shared: Vec<&String> = python.keys().filter(|n| workspace.contains_key(*n)).collect();
    // serde, rayon, image, gltf, … and the model's own crates.
    assert!(shared.len() > 50, "{} packages shared", shared.len());
    for name in shared {
        for v in &python[name] {
            assert!(
                workspace[name].contains(v),
                "python/Cargo.lock has {name} {v}; the workspace's {:?}",
                workspace[name]
            );
        }
    }
    let profile = release_profile(&root().join("Cargo.toml"));
    assert!(profile.iter().any(|l| l.starts_with("lto")), "{profile:?}");
    assert_eq!(release_profile(&root().join("python/Cargo.toml")), profile);
    let config = std::fs::read_to_string(root().join("python/.cargo/config.toml")).expect("python/.cargo/config.toml");
    assert!(config.lines().any(|l| l.replace(' ', "") == "target-dir=\"../target\""), "{config}");
}
