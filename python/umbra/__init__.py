"""Umbra from Python: render, cost, study and plan shadow-mapping hardware.

Scenes and architectures are bundled, read from files, or built in code;
a render's maps and per-pixel results come back as numpy arrays, a
study's rows as a pandas DataFrame with typed columns (the rows
``umbra study`` writes to ``results.csv``). Long work releases the
interpreter and reports ``progress(done, total)`` to a callback.

>>> import umbra
>>> r = umbra.render("weiskopf-l", width=96, height=72, map=256, rays=1)
>>> r["shadow"].shape
(72, 96)

Every error is an :class:`UmbraError` with the message the command line
prints: the file (or ``--set``, or the argument), the key and the problem.
"""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np
import pandas as pd

from . import _umbra
from ._umbra import Arch, Config, Scene, UmbraError

__all__ = [
    "Arch",
    "Config",
    "Scene",
    "UmbraError",
    "VERSION",
    "allow_read",
    "arch",
    "bundled_archs",
    "bundled_scenes",
    "config",
    "cost",
    "plan",
    "print_progress",
    "read_results",
    "render",
    "scene",
    "study",
]

#: The version of the simulator, as every output records it.
VERSION: str = _umbra.VERSION

#: ``progress(done, total)``: how long work reports how far it is.
Progress = Callable[[int, int], Any]

#: The study's text columns that take few values: categorical in a DataFrame.
CATEGORIES = (
    "scene",
    "algorithm",
    "family",
    "culling",
    "depth_format",
    "filter_name",
    "arch",
    "base_arch",
    "arch_params",
    "status",
    "light_bottleneck",
    "camera_bottleneck",
)


def bundled_scenes() -> list[str]:
    """The bundled scenes' names."""
    return list(_umbra.bundled_scenes())


def bundled_archs() -> list[str]:
    """The bundled architectures' names."""
    return list(_umbra.bundled_archs())


def _plain(value: Any, where: str) -> Any:
    """``value`` with numpy arrays and scalars made lists and numbers, and
    ``None`` entries left out: what a scene or sweep file can hold."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {str(k): _plain(v, f"{where}.{k}") for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, (str, bool, int, float)):
        return value
    if isinstance(value, Path):
        return str(value)
    raise UmbraError(f"{where}: a {type(value).__name__} cannot be written in a file")


def _toml(parts: Mapping[str, Any], what: str) -> str:
    return _umbra.toml_from_json(json.dumps(_plain(parts, what), allow_nan=True), what)


def scene(
    source: Union[str, Path, Mapping[str, Any], Scene],
    name: str = "(scene dict)",
    camera: Optional[str] = None,
    light_from: Optional[Sequence[float]] = None,
) -> Scene:
    """A scene: a bundled scene's name, a scene file's path, a glTF file's
    path (``.gltf`` or ``.glb``; ``camera`` chooses its camera by name or
    index, its first by default), or a dict with the scene file's keys
    (``image``, ``camera``, ``lights``, ``objects``). ``light_from``, a
    point ``(x, y, z)``, moves its first light there, aimed at the centre
    of the scene's bounds (``umbra render --light-from X,Y,Z``).

    An object's ``mesh`` is a generator (``{"sphere": {...}}``), an OBJ file
    (``{"obj": "bunny.obj"}``) or arrays (``{"arrays": {"positions": P,
    "triangles": T}}``, ``P`` an ``n × 3`` float array, ``T`` an ``m × 3``
    integer array of vertex indices). ``name`` names a dict in errors.
    """
    if isinstance(source, Scene):
        made = source
    elif isinstance(source, Mapping):
        made = Scene.from_toml(_toml(source, name), name)
    else:
        made = Scene(str(source), camera)
    return made if light_from is None else made.with_light_from([float(v) for v in light_from])


def allow_read(folder: Union[str, Path]) -> None:
    """Let glTF models read their buffers from ``folder`` too: by default a
    model reads only files in its own folder and below (``umbra
    --allow-read``)."""
    _umbra.allow_read(Path(folder))


def arch(source: Union[str, Path, Arch]) -> Arch:
    """An architecture: a bundled one's name or an architecture file's path."""
    return source if isinstance(source, Arch) else Arch(str(source))


_as_scene, _as_arch = scene, arch


def config(scene: Union[str, Scene, Mapping[str, Any]], **flags: Any) -> Config:
    """A render configuration of a scene, checked: the keywords are the
    render's parameters, ``umbra render``'s flags (``umbra schema render``
    lists each with its Python keyword: ``algo``, ``depth``, ``map``,
    ``filter``, ``bias``, ``reference_rays`` or ``rays``, ...), each
    defaulting as the flag does."""
    return _umbra.config(_as_scene(scene), **flags)




def render(
    scene: Union[str, Scene, Mapping[str, Any]] = "table-and-sphere",
    progress: Optional[Progress] = None,
    threads: Optional[int] = None,
    **flags: Any,
) -> dict[str, Any]:
    """Render a scene against its exact reference, as ``umbra render`` does.

    Returns the metrics (``misclassified_percent``, ``acne_px``,
    ``detachment_px``, ``leaks_px``, ``aliasing_px``, ``penumbra_px``, ...)
    and the arrays, all ``height × width`` but the
    maps: ``z1`` and ``z2`` (the stored integers, ``map × map``; ``None``
    where the algorithm keeps none), ``shadow`` (float32, 0 lit to 1
    shadowed, NaN for the background), ``reference`` (the exact shadowed
    area fraction) and ``verdict`` (uint8: 0 unevaluated, 1 right, 2
    aliasing, 3 acne, 4 leak, 5 detachment, 6 penumbra, 7 clipped); and
    ``render_again``, the command line
    that renders it again.
    """
    s = _as_scene(scene)
    metrics, arrays = _umbra.render(s, _umbra.config(s, **flags), progress, threads)
    out = json.loads(metrics)
    out.update(arrays)
    return out


def cost(
    scene: Union[str, Scene, Mapping[str, Any]] = "table-and-sphere",
    config: Union[Config, Mapping[str, Any], None] = None,
    arch: Union[str, Arch] = "talisman",
) -> dict[str, Any]:
    """The cost of a render on an architecture, as ``umbra cost`` reports
    it in ``cost.json``: nested dicts whose keys carry their units
    (``seconds``, ``frames_per_second``, ``dram_bytes``, ...)."""
    s = _as_scene(scene)
    c = config if isinstance(config, Config) else _umbra.config(s, **dict(config or {}))
    return json.loads(_umbra.cost(s, c, _as_arch(arch)))


def study(
    sweep: Union[str, Path, Mapping[str, Any]] = "quick",
    shard: tuple[int, int] = (0, 1),
    progress: Optional[Progress] = None,
    threads: Optional[int] = None,
) -> pd.DataFrame:
    """Run a sweep, as ``umbra study`` does: a bundled sweep's name
    (``quick``, ``full``), a sweep file's path, or a dict with the sweep
    file's keys. Returns its rows (shard ``i`` of ``n`` when given) as a
    DataFrame typed by the schema: integers and numbers numeric (the
    architecture axes in SI units, named so), the algorithm, family,
    scene, architecture and other few-valued text categorical."""
    if isinstance(sweep, Mapping):
        rows, schema = _umbra.study(
            text=_toml(sweep, "(sweep dict)"), shard=tuple(shard), progress=progress, threads=threads
        )
    else:
        rows, schema = _umbra.study(name=str(sweep), shard=tuple(shard), progress=progress, threads=threads)
    return _typed(rows, schema)


def read_results(folder: Union[str, Path]) -> pd.DataFrame:
    """The rows of a study's output folder (``results.csv``, typed by its
    ``schema.csv``), as :func:`study` returns them."""
    folder = Path(folder)
    return _typed((folder / "results.csv").read_text(), (folder / "schema.csv").read_text())


def _typed(rows: str, schema: str) -> pd.DataFrame:
    """``results.csv``'s text as a DataFrame, each column typed as
    ``schema.csv`` says."""
    kinds = pd.read_csv(io.StringIO(schema), dtype=str, keep_default_na=False)
    frame = pd.read_csv(io.StringIO(rows), dtype=str, keep_default_na=False)
    for column, kind in zip(kinds["column"], kinds["type"]):
        cells = frame[column]
        if kind == "integer":
            frame[column] = pd.to_numeric(cells.replace("", None)).astype("Int64")
        elif kind == "number":
            numbers = pd.to_numeric(cells.replace("", None), errors="coerce")
            # An architecture axis may be a flag or a name: kept as text.
            numeric = numbers.notna() | (cells == "")
            frame[column] = numbers.astype("float64") if numeric.all() else cells.astype("category")
        elif kind == "boolean":
            frame[column] = cells.map({"true": True, "false": False, "": pd.NA}).astype("boolean")
        elif column in CATEGORIES:
            frame[column] = cells.astype("category")
        else:
            frame[column] = cells.astype("string")
    return frame


def plan(
    scene: Union[str, Scene, Mapping[str, Any]],
    budget: Union[None, float, str, Sequence[Union[float, str]]] = None,
    arch: Union[str, Arch] = "talisman",
    sweep: Optional[str] = None,
    maps: Optional[Sequence[int]] = None,
    image: Optional[tuple[int, int]] = None,
    objective: Optional[str] = None,
    max_area: Optional[str] = None,
    max_energy: Optional[str] = None,
    progress: Optional[Progress] = None,
    threads: Optional[int] = None,
) -> dict[str, Any]:
    """The least costly configuration on ``arch`` meeting every budget, as
    ``umbra plan`` chooses it (``plan.json``): the pick, its figures, the
    runners-up and why each lost. A budget is spelt as ``umbra plan
    --budget`` spells it (``"acne=0.01%"``, ``"misclassified=0.1"``), or a
    number: percent artifacts; give a list for several at once; none
    means ``umbra plan``'s default, ``artifacts=0.1%`` and
    ``misclassified=2%``. ``sweep``
    (``"quick"``, ``"full"`` or a sweep file), ``maps`` and ``image``
    choose the candidates as the command's flags do; ``objective``
    (``"cycles"``, ``"energy"``, ``"area"``, ``"edp"``, ``"edap"`` or weights
    such as ``"cycles=1,area=2"``), ``max_area`` (``"2mm2"``) and
    ``max_energy`` (``"150uJ"``) as ``--objective``, ``--max-area`` and
    ``--max-energy`` do."""
    budgets = [budget] if isinstance(budget, (int, float, str)) else list(budget or [])
    spelt = [b if isinstance(b, str) else f"artifacts={float(b)!r}%" for b in budgets]
    return json.loads(
        _umbra.plan(
            _as_scene(scene),
            spelt,
            _as_arch(arch),
            sweep,
            None if maps is None else [int(m) for m in maps],
            None if image is None else (int(image[0]), int(image[1])),
            objective,
            max_area,
            max_energy,
            progress,
            threads,
        )
    )


def print_progress(done: int, total: int) -> None:
    """A progress callback that prints ``done/total`` on one line."""
    end = "\n" if total and done >= total else ""
    print(f"\r{done}/{total}", end=end, file=sys.stderr, flush=True)
