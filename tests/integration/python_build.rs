//! The Python package reuses what the workspace built: cargo reuses a
//! crate's build only under the same profile, the same path from the
//! workspace's root, the same versions and the same features of it and of
//! every crate below it. So `python/` is a member of the workspace (one
//! root, one `Cargo.lock`, one release profile, one target folder), and
//! `umbra-sim` turns on in its dependencies' dependencies what the
//! package's numpy and pyo3 turn on (`sim/Cargo.toml`): `pip install
//! ./python` after `cargo umbra` then builds only the extension's crates.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn python_is_a_member_of_the_workspace() {
    let manifest = std::fs::read_to_string(root().join("Cargo.toml")).expect("the workspace's manifest");
    let members = manifest.lines().find(|l| l.starts_with("members")).expect("a members line");
    assert!(members.contains("\"python\""), "{members}");
    let python = std::fs::read_to_string(root().join("python/Cargo.toml")).expect("python/Cargo.toml");
    for own in ["[workspace]", "[profile."] {
        assert!(!python.contains(own), "python/Cargo.toml has its own {own}");
    }
    for own in ["python/Cargo.lock", "python/.cargo"] {
        assert!(!root().join(own).exists(), "{own} would part the package's build from the workspace's");
    }
}

/// Each package's features (`cargo tree`'s lines `name version [features]`)
/// in the build of `packages`, normal and build-time dependencies apart.
fn features(packages: &[&str]) -> BTreeMap<String, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut found = BTreeMap::new();
    for edges in ["normal", "build"] {
        let mut command = Command::new(&cargo);
        command.current_dir(root()).args(["tree", "--offline", "--locked", "--prefix", "none", "-f", "{p} [{f}]"]);
        for p in packages {
            command.args(["-p", p]);
        }
        let out = command.args(["-e", edges]).output().expect("cargo tree runs");
        assert!(out.status.success(), "cargo tree: {}", String::from_utf8_lossy(&out.stderr));
        for line in String::from_utf8_lossy(&out.stdout).lines() {
            let line = line.trim_end_matches(" (*)").replace(" (proc-macro)", "");
            if let Some((package, features)) = line.split_once(" [") {
                found.insert(format!("{edges} {package}"), features.trim_end_matches(']').to_owned());
            }
        }
    }
    found
}

#[test]
#[ignore = "needs the Python package's dependencies downloaded (`cargo clippy --workspace` fetches them); .ci/run runs it"]
fn python_builds_the_workspaces_crates_with_their_features() {
    let workspace = features(&["umbra-cli", "umbra"]);
    let python = features(&["umbra-python"]);
    let shared: Vec<&String> = python.keys().filter(|p| workspace.contains_key(*p)).collect();
    // serde, rayon, image, gltf, parry, … and the model's own crates.
    assert!(shared.len() > 100, "{} packages shared", shared.len());
    assert!(shared.iter().any(|p| p.starts_with("normal umbra-sim ")), "{shared:?}");
    for p in shared {
        assert_eq!(python[p], workspace[p], "{p}: the Python package's features, then the command's");
    }
}
