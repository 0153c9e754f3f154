//! The `umbra` command's limit options: a request beyond a limit ends in
//! an error that names it and the option that moves it, before anything is
//! written, and the option moves it.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{dir, umbra};

/// `dir(name)`, made, holding `file` with `contents`; the file's path.
fn input(name: &str, file: &str, contents: &str) -> (common::Scratch, PathBuf) {
    let d = dir(name);
    std::fs::create_dir_all(&d).expect("temp dir");
    let path = d.join(file);
    std::fs::write(&path, contents).expect("write");
    (d, path)
}

fn text(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 temp path")
}

/// `umbra` succeeded; its output.
fn succeeds(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// `umbra` failed, and its message holds each of `needles`.
fn fails_saying(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "succeeded: {}", String::from_utf8_lossy(&o.stdout));
    for n in needles {
        assert!(err.contains(n), "`{n}` missing from: {err}");
    }
}

#[test]
fn a_map_side_beyond_the_limit_is_refused_and_the_option_moves_the_limit() {
    let out = dir("map");
    let o = umbra(&["--max-map-side", "64", "depth", "--map", "96", "--out", text(&out)]);
    fails_saying(&o, &["--map 96", "map side 96", "limit of 64", "max_map_side"]);
    assert!(!out.exists(), "nothing is written");
    // After the subcommand too (the options are global), and at the limit.
    succeeds(&umbra(&["depth", "--map", "96", "--max-map-side", "96", "--out", text(&out)]));
    let z1 = std::fs::read(out.join("z1.npy")).expect("z1 written");
    assert!(z1.len() > 96 * 96 * 4, "a 96² map of 32-bit texels: {} bytes", z1.len());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_mesh_beyond_the_triangle_or_file_limit_is_refused_before_it_is_built() {
    // Three triangles around a centre.
    let (out, obj) =
        input("mesh", "fan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 3 4\nf 1 4 5\n");
    let maps = out.join("maps");
    let mesh = ["depth", "--mesh", text(&obj), "--map", "32", "--out", text(&maps)];
    fails_saying(&umbra(&[&["--max-triangles", "2"][..], &mesh].concat()), &["3 triangles", "max_triangles"]);
    fails_saying(&umbra(&[&["--max-file-bytes", "16"][..], &mesh].concat()), &["fan.obj", "max_file_bytes"]);
    assert!(!maps.exists(), "nothing is written");
    assert!(succeeds(&umbra(&[&["--max-triangles", "3"][..], &mesh].concat())).contains("triangles 3 submitted"));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_scene_beyond_the_image_or_triangle_limit_is_refused_when_it_is_read() {
    let out = dir("scene");
    // The bundled table: a 960×540 image of 2280 triangles.
    let o = umbra(&["render", "table-and-sphere", "--max-image-pixels", "518399", "--out", text(&out)]);
    fails_saying(&o, &["image", "960x540", "max_image_pixels"]);
    let o = umbra(&["cost", "table-and-sphere", "--max-image-side", "959", "--out", text(&out)]);
    fails_saying(&o, &["image side 960", "max_image_side"]);
    let o = umbra(&["plan", "table-and-sphere", "--max-triangles", "2279", "--out", text(&out)]);
    fails_saying(&o, &["2280 triangles", "max_triangles"]);
    let o = umbra(&["study", "--quick", "--maps", "64", "--max-map-side", "32", "--out", text(&out)]);
    fails_saying(&o, &["--maps 64", "max_map_side"]);
    let o = umbra(&["study", "--quick", "--maps", "0", "--out", text(&out)]);
    fails_saying(&o, &["--maps 0", "outside 1..="]);
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn every_file_the_command_reads_is_a_regular_file_within_the_file_limit() {
    // A light matrix in a file: the identity, 41 bytes of JSON.
    let (out, matrix) = input("files", "matrix.json", "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]");
    let maps = out.join("maps");
    let depth = ["depth", "--map", "32", "--out", text(&maps), "--matrix"];
    fails_saying(&umbra(&[&depth[..], &["/dev/zero"]].concat()), &["--matrix", "not a regular file"]);
    let small = [&["--max-file-bytes", "20"][..], &depth, &[text(&matrix)]].concat();
    fails_saying(&umbra(&small), &["--matrix", "max_file_bytes"]);
    succeeds(&umbra(&[&depth[..], &[text(&matrix)]].concat()));
    // A study's results to merge.
    let merged = out.join("merged");
    fails_saying(&umbra(&["merge", "/dev/zero", "--out", text(&merged)]), &["/dev/zero", "not a regular file"]);
    // A lone results file is no shard: its folder holds no manifest.
    let rows = out.join("results.jsonl");
    std::fs::write(&rows, "x".repeat(100)).expect("write");
    fails_saying(&umbra(&["merge", text(&rows), "--out", text(&merged)]), &["manifest.json", "no run wrote it"]);
    // A shard's files are read within the limit: its manifest's listing
    // is checked before the file is.
    let sweep = out.join("tiny.toml");
    std::fs::write(
        &sweep,
        "name = \"tiny\"\nscenes = [\"table-and-sphere\"]\nimages = [[48, 27]]\nreference_rays = 1\n\
         formats = [\"d16\"]\nmaps = [64]\nfilters = [\"point\"]\nbudgets = [1.0]\n[[algorithms]]\nalgo = \"second\"\n",
    )
    .expect("sweep");
    let shard = out.join("shard");
    succeeds(&umbra(&["study", "--sweep", text(&sweep), "--shard", "0/1", "--out", text(&shard)]));
    let o = umbra(&["merge", text(&shard), "--out", text(&merged), "--max-file-bytes", "99"]);
    fails_saying(&o, &["results.jsonl", "above the limit of 99"]);
    assert!(!merged.exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&out);
}

/// `--max-memory` reads sizes as architecture files do (one reader of
/// sizes): `1TiB`, `2 GiB`, `512MB` and plain bytes are taken; a size in
/// an unknown unit is refused with the reader's own words, the same an
/// architecture key of bytes gives (a cache's `size = "16 furlongs"`).
#[test]
fn the_memory_bound_reads_sizes_as_architecture_files_do() {
    for size in ["1TiB", "2 GiB", "512MB", "17179869184"] {
        let o = umbra(&["arch", "show", "--arch", "talisman", "--max-memory", size]);
        succeeds(&o);
    }
    let flag = umbra(&["arch", "show", "--arch", "talisman", "--max-memory", "16 furlongs"]);
    fails_saying(&flag, &["`16 furlongs` is not a size such as 64B, 16KiB, 2MB or 1TiB"]);
    let (d, arch) =
        input("sizes", "mine.toml", &std::fs::read_to_string("../../arch/talisman.toml").expect("talisman"));
    let file = std::fs::read_to_string(&arch).expect("read");
    std::fs::write(&arch, file.replacen("size = \"16KiB\"", "size = \"16 furlongs\"", 1)).expect("write");
    fails_saying(&umbra(&["arch", "show", "--arch", text(&arch)]), &["`16 furlongs` is not a size such as 64B"]);
    let _ = std::fs::remove_dir_all(&d);
}

/// The reference-ray bound is stated once: `umbra render`, `umbra study`
/// and a sweep file refuse 17 rays a side, each naming the bound `1..=16`
/// (or the flag's range), and take 16.
#[test]
fn the_reference_ray_bound_is_one_for_every_door() {
    let d = dir("rays");
    std::fs::create_dir_all(&d).expect("dir");
    let o = |name: &str| d.join(name).to_string_lossy().into_owned();
    fails_saying(&umbra(&["render", "--reference-rays", "17", "--out", &o("r")]), &["--reference-rays", "1..=16"]);
    let small = ["--width", "16", "--height", "9", "--map", "16", "--reference-rays", "16"];
    succeeds(&umbra(&[&["render"][..], &small, &["--out", &o("r16")]].concat()));
    fails_saying(&umbra(&["study", "--quick", "--reference-rays", "17", "--out", &o("s")]), &["1..=16"]);
    let sweep = |rays: u32| {
        let path = d.join(format!("rays-{rays}.toml"));
        let text = format!(
            "name = \"rays\"\nscenes = [\"quad\"]\nimages = [[16, 9]]\nreference_rays = {rays}\nformats = [\"d24\"]\n\
             maps = [16]\nfilters = [\"point\"]\nbudgets = [1.0]\n[[algorithms]]\nalgo = \"second\"\n"
        );
        std::fs::write(&path, text).expect("sweep");
        path.to_string_lossy().into_owned()
    };
    fails_saying(
        &umbra(&["study", "--sweep", &sweep(17), "--out", &o("w17")]),
        &["reference_rays", "17 is outside 1..=16"],
    );
    succeeds(&umbra(&["study", "--sweep", &sweep(16), "--out", &o("w16")]));
    let _ = std::fs::remove_dir_all(&d);
}

/// The limits are listed once, in `umbra --help`'s Limits section; each
/// subcommand's help (a nested one's too) says where they are instead, and
/// each takes them after its name as `umbra` takes them before it.
#[test]
fn the_limits_are_listed_once_and_taken_before_or_after_the_subcommand() {
    let top = succeeds(&umbra(&["--help"]));
    let section = top.split("\nLimits:").nth(1).expect("a Limits section");
    for flag in ["--max-map-side", "--max-image-pixels", "--max-triangles", "--max-memory"] {
        assert!(section.contains(flag), "`{flag}` is not under Limits: {top}");
    }
    for command in [&["render", "--help"][..], &["study", "--help"], &["arch", "show", "--help"], &["help", "depth"]] {
        let help = succeeds(&umbra(command));
        assert!(!help.contains("--max-map-side") && !help.contains("Limits:"), "{command:?} lists the limits: {help}");
        assert!(help.contains("(--max-*): see `umbra --help`"), "{command:?} does not say where they are: {help}");
        // The global options that are not limits are still listed.
        assert!(help.contains("--threads"), "{command:?}: {help}");
    }
    let arch = concat!(env!("CARGO_MANIFEST_DIR"), "/../../arch/mobile-tbdr.toml");
    let limit = ["--max-text-bytes", "10"];
    let show = ["arch", "show", "--arch", arch];
    for args in [[&limit[..], &show].concat(), [&show[..], &limit].concat()] {
        fails_saying(&umbra(&args), &["above the limit of 10", "max_text_bytes"]);
    }
}
