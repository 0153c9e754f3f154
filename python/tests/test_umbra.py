"""The Python package against the command line: the same renders bit for
bit, the same rows, the same errors.

The command line is ``target/release/umbra`` of this repository (or
``$UMBRA_BIN``); ``.ci/run`` builds it before these tests run.
"""

from __future__ import annotations

import json
import os
import struct
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import umbra

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("UMBRA_BIN", ROOT / "target" / "release" / "umbra"))

#: A small render: quick enough for a test, large enough to have shadows.
SMALL = dict(width=96, height=54, map=256, rays=1)


def cli(*args: str) -> subprocess.CompletedProcess:
    if not BIN.is_file():
        pytest.fail(f"{BIN} is not built: cargo build --release -p umbra-cli")
    return subprocess.run([str(BIN), *args], capture_output=True, text=True)


def flags(**f) -> list[str]:
    out = []
    for k, v in f.items():
        out += ["--reference-rays" if k == "rays" else f"--{k}", str(v)]
    return out


def test_render_arrays_are_the_cli_npy_files_bit_for_bit(tmp_path):
    for algo, depth in [("dual", "d16"), ("first", "d24"), ("second", "f32")]:
        out = tmp_path / algo
        done = cli("render", "weiskopf-l", "--algo", algo, "--depth", depth, *flags(**SMALL), "--out", str(out))
        assert done.returncode == 0, done.stderr
        r = umbra.render("weiskopf-l", algo=algo, depth=depth, **SMALL)
        for name in ["shadow", "reference", "verdict", "z1", "z2"]:
            path = out / f"{name}.npy"
            if not path.exists():
                assert r[name] is None, f"{algo}: {name} without a file"
                continue
            want = np.load(path)
            assert r[name].dtype == want.dtype and r[name].shape == want.shape, (algo, name)
            assert r[name].tobytes() == want.tobytes(), f"{algo} {depth}: {name} differs"
        written = json.loads((out / "metrics.json").read_text())
        assert r["misclassified_percent"] == written["misclassified_percent"]
        assert r["acne_px"] == written["acne_px"] and r["leaks_px"] == written["leaks_px"]
        # The verdict codes count what the metrics count.
        assert int((r["verdict"] == 3).sum()) == r["acne_px"]
        assert int((r["verdict"] == 4).sum()) == r["leaks_px"]
        assert int((r["verdict"] == 2).sum()) == r["aliasing_px"]
        assert int((r["verdict"] == 5).sum()) == r["detachment_px"]
        assert int((r["verdict"] == 6).sum()) == r["penumbra_px"]
        assert int((r["verdict"] == 7).sum()) == r["clipped_px"]


def test_maps_are_the_stored_integers():
    r = umbra.render("weiskopf-l", algo="dual", depth="d16", **SMALL)
    assert r["z1"].dtype == np.uint16 and r["z1"].shape == (256, 256)
    # The clear value is the far plane, 2^16 - 1, and the second depth lies behind the first.
    assert r["z1"].max() == 0xFFFF and (r["z2"] >= r["z1"]).all()
    assert umbra.render("weiskopf-l", algo="volumes", **SMALL)["z1"] is None


def test_progress_reports_every_reference_row():
    seen = []
    umbra.render("weiskopf-l", progress=lambda done, total: seen.append((done, total)), **SMALL)
    assert seen and seen[-1] == (54, 54)
    assert all(a <= b for (a, _), (b, _) in zip(seen, seen[1:]))


SWEEP = """
name = "py-test"
scenes = ["weiskopf-l"]
images = [[64, 36]]
reference_rays = 1
formats = ["d16", "d24"]
maps = [128]
filters = ["point", "bilinear"]
archs = ["talisman", "pixelflow"]
budgets = [1.0]

[[algorithms]]
algo = "first"
bias = [0.002]

[[algorithms]]
algo = "dual"
offset = [0.005]
"""


def test_study_is_the_cli_results_csv(tmp_path):
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(SWEEP)
    done = cli("study", "--sweep", str(sweep), "--out", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr
    frame = umbra.study(str(sweep))
    written = umbra.read_results(tmp_path / "out")
    # The same rows, bar the build that made them (the package and the
    # command are built apart, and may name their revisions apart).
    assert frame["umbra_version"].str.startswith("umbra ").all()
    same = [c for c in frame.columns if c != "umbra_version"]
    pd.testing.assert_frame_equal(frame[same], written[same])
    # 2 algorithms × 2 formats × 2 filters × 2 architectures.
    assert len(frame) == 16
    assert frame["algorithm"].dtype == "category" and frame["depth_format"].dtype == "category"
    assert pd.api.types.is_float_dtype(frame["artifact_percent"])
    assert pd.api.types.is_integer_dtype(frame["acne_px"])
    # A dict with the file's keys is the same sweep (its hash is of its own text).
    as_dict = umbra.study(
        {
            "name": "py-test",
            "scenes": ["weiskopf-l"],
            "images": [[64, 36]],
            "reference_rays": 1,
            "formats": ["d16", "d24"],
            "maps": [128],
            "filters": ["point", "bilinear"],
            "archs": ["talisman", "pixelflow"],
            "budgets": [1.0],
            "algorithms": [{"algo": "first", "bias": [0.002]}, {"algo": "dual", "offset": [0.005]}],
        }
    )
    numbers = frame.select_dtypes("number").columns
    pd.testing.assert_frame_equal(as_dict[numbers], frame[numbers])


def test_cost_is_the_cli_report(tmp_path):
    done = cli("cost", "weiskopf-l", "--arch", "talisman", *flags(**SMALL), "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    written = json.loads((tmp_path / "cost.json").read_text())
    report = umbra.cost("weiskopf-l", dict(SMALL), "talisman")
    theirs = written["reports"][0]
    assert sorted(report) == sorted(theirs)
    for key in report:
        if key != "version":
            assert report[key] == theirs[key], key


def test_architectures_are_set_and_shown_with_units():
    a = umbra.arch("talisman")
    d = a.to_dict()
    assert d["dram.bandwidth"].endswith("B/s") and d["clock"].endswith("Hz")
    b = a.set("dram.bandwidth", "2.4GB/s")
    assert b.to_dict()["dram.bandwidth"] == "2.4GB/s" and a.to_dict() == d
    slow = umbra.cost("weiskopf-l", dict(SMALL), b)
    fast = umbra.cost("weiskopf-l", dict(SMALL), a.set("dram.bandwidth", "240GB/s"))
    assert slow["seconds"] >= fast["seconds"]


def test_a_scene_from_numpy_arrays_is_the_scene_from_its_file():
    import tomllib

    path = ROOT / "scenes" / "weiskopf-l.toml"
    from_file = umbra.scene(str(path))
    parts = tomllib.loads(path.read_text())
    # Each mesh as placed in the scene, given as arrays instead.
    for o, placed in zip(parts["objects"], from_file.objects()):
        positions = np.asarray(placed["positions"], dtype=np.float64)
        triangles = np.asarray(placed["triangles"], dtype=np.int64)
        o["mesh"] = {"arrays": {"positions": positions, "triangles": triangles}}
    built = umbra.scene(parts, "weiskopf-l (dict)")
    assert [o["solid"] for o in built.objects()] == [o["solid"] for o in from_file.objects()]
    a = umbra.render(from_file, **SMALL)
    b = umbra.render(built, **SMALL)
    for name in ["shadow", "reference", "verdict", "z1", "z2"]:
        assert a[name].tobytes() == b[name].tobytes(), name
    assert a["misclassified_percent"] == b["misclassified_percent"]


def test_a_gltf_file_renders_as_the_cli_renders_it(tmp_path):
    made = cli("scene", "city", "--out", str(tmp_path / "city"))
    assert made.returncode == 0, made.stderr
    glb = tmp_path / "city" / "city.glb"
    out = tmp_path / "render"
    done = cli("render", str(glb), "--camera", "0", *flags(**SMALL), "--out", str(out))
    assert done.returncode == 0, done.stderr
    s = umbra.scene(glb, camera="0")
    assert s.notes == ["lights: lights[0] `sun`, lights[1] `street lamp`"], s.notes
    r = umbra.render(s, **SMALL)
    # Two lights: the files are each light's; the arrays the first light's.
    for name in ["shadow", "reference", "verdict", "z1", "z2"]:
        assert r[name].tobytes() == np.load(out / f"{name}-light0.npy").tobytes(), name
    written = json.loads((out / "metrics.json").read_text())
    assert len(r["lights"]) == 2 and r["lights"] == written["lights"]
    assert r["evaluated_px"] == written["evaluated_px"] == sum(l["evaluated_px"] for l in r["lights"])
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene(glb, camera="9")
    assert "no camera `9`" in str(e.value)


def test_a_gltf_buffer_outside_its_folder_is_read_only_where_allowed(tmp_path):
    made = cli("scene", "city", "--side", "2", "--columns", "2", "--storeys", "2", "--out", str(tmp_path / "city"))
    assert made.returncode == 0, made.stderr
    glb = (tmp_path / "city" / "city.glb").read_bytes()
    # The .glb's JSON with its binary chunk as a file one folder up.
    (json_length,) = struct.unpack("<I", glb[12:16])
    doc = json.loads(glb[20 : 20 + json_length])
    bin_at = 20 + json_length
    (bin_length,) = struct.unpack("<I", glb[bin_at : bin_at + 4])
    shared = tmp_path / "shared"
    shared.mkdir()
    (shared / "city.bin").write_bytes(glb[bin_at + 8 : bin_at + 8 + bin_length])
    doc["buffers"][0]["uri"] = "../shared/city.bin"
    model = tmp_path / "model"
    model.mkdir()
    (model / "city.gltf").write_text(json.dumps(doc))
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene(model / "city.gltf")
    assert "buffers[0].uri" in str(e.value) and "umbra.allow_read" in str(e.value), str(e.value)
    # Through a link in its folder, once the shared folder is allowed.
    (model / "city.bin").symlink_to(shared / "city.bin")
    doc["buffers"][0]["uri"] = "city.bin"
    (model / "city.gltf").write_text(json.dumps(doc))
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene(model / "city.gltf")
    assert "symbolic link" in str(e.value), str(e.value)
    umbra.allow_read(shared)
    s = umbra.scene(model / "city.gltf")
    assert s.notes == ["lights: lights[0] `sun`, lights[1] `street lamp`"], s.notes


def test_plan_names_a_configuration_within_its_budgets():
    p = umbra.plan(
        "weiskopf-l", ["acne=5%", "misclassified=50"], "talisman", sweep="quick", maps=[128], image=(96, 54)
    )
    assert p["arch"] == "talisman" and p["pick"]["command"].startswith("umbra render weiskopf-l")
    # What it measured of its pick is within both budgets, spelt as the
    # command spells them.
    assert p["meets"] and p["pick"]["percent"]["acne"] <= 5.0 and p["pick"]["percent"]["misclassified"] <= 50.0
    assert [b["measure"] for b in p["budgets"]] == ["acne", "misclassified"]
    # A bare number is an artifacts budget.
    q = umbra.plan("weiskopf-l", 50.0, "talisman", sweep="quick", maps=[128], image=(96, 54))
    assert q["budgets"] == [{"measure": "artifacts", "percent": 50.0}]
    # No budget: the command's default, artifacts and misclassified pixels.
    d = umbra.plan("weiskopf-l", arch="talisman", sweep="quick", maps=[128], image=(96, 54))
    assert d["budgets"] == [
        {"measure": "artifacts", "percent": 0.1},
        {"measure": "misclassified", "percent": 2.0},
    ]
    with pytest.raises(umbra.UmbraError) as e:
        umbra.plan("weiskopf-l", "glare=1%", "talisman")
    assert "glare" in str(e.value)
    # By silicon area, under an energy limit: the pick is the least area of
    # every candidate within the budget and the limit (its runners-up
    # after it take at least as much), and it is within the limit.
    r = umbra.plan(
        "weiskopf-l", 50.0, "mobile-tbdr", sweep="quick", maps=[128], image=(96, 54),
        objective="area", max_energy="1mJ",
    )
    assert r["objective"] == "area" and r["pick"]["joules"] <= 1e-3
    dearer = [x["candidate"]["square_metres"] for x in r["runners_up"] if not x["cheaper"]]
    assert all(a >= r["pick"]["square_metres"] for a in dearer), (r["pick"], dearer)
    with pytest.raises(umbra.UmbraError) as e:
        umbra.plan("weiskopf-l", 50.0, "talisman", objective="speed")
    assert "objective" in str(e.value)


def test_bad_input_names_the_file_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('name = "bad"\nimage = [96, 54]\n[camera]\neye = [0, 1, 2]\n')
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene(str(bad))
    assert "bad.toml" in str(e.value)
    with pytest.raises(umbra.UmbraError) as e:
        umbra.arch("talisman").set("dram.bandwidth", "fast")
    assert "dram.bandwidth" in str(e.value)
    with pytest.raises(umbra.UmbraError) as e:
        umbra.render("weiskopf-l", algo="nonsense", **SMALL)
    assert "algo" in str(e.value)
    import tomllib

    parts = tomllib.loads((ROOT / "scenes" / "weiskopf-l.toml").read_text())
    parts["objects"][0]["mesh"] = {"arrays": {"positions": np.zeros((3, 3)), "triangles": np.array([[0, 1, 5]])}}
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene(parts, "mine")
    assert "mine" in str(e.value) and "objects[0].mesh.arrays.triangles[0]" in str(e.value), str(e.value)
    done = cli("render", str(bad), "--out", str(tmp_path / "o"))
    assert done.returncode != 0 and "bad.toml" in done.stderr


def test_a_light_moves_where_it_is_put():
    # The scene's bounds reach 5.69 from their centre (0, 0.55, 0): a light
    # must stand 1.2 times that, 6.83, away. 10 above is; 0.5 above is not.
    moved = umbra.scene("table-and-sphere", light_from=(0, 10, 0))
    assert any("moved to 0,10,0" in n for n in moved.notes), moved.notes
    with pytest.raises(umbra.UmbraError) as e:
        umbra.scene("table-and-sphere", light_from=(0, 0.5, 0))
    assert "within its bounds' sphere" in str(e.value)


def test_cascades_are_a_keyword_as_on_the_command_line(tmp_path):
    out = tmp_path / "street"
    done = cli("render", "street", "--cascades", "3,lambda=1", *flags(**SMALL), "--out", str(out))
    assert done.returncode == 0, done.stderr
    r = umbra.render("street", cascades="3,lambda=1", **SMALL)
    written = json.loads((out / "metrics.json").read_text())
    assert r["misclassified_percent"] == written["misclassified_percent"]
    assert len(r["cascades"][0]) == 3 and r["cascades"] == written["cascades"]
    assert r["shadow"].tobytes() == np.load(out / "shadow.npy").tobytes()
