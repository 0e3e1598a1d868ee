"""The extension package as a user installs it: ``blender/build_extension.py`` bundles the
fairsub wheel (``$FAIRSUB_WHEEL``, else the newest ``target/wheels/fairsub-*.whl``) and Blender's
own extension tool builds and validates the package; then a fresh Blender (the ``bpy`` module,
with its own user folder) installs it through Blender's "Install from Disk" operator
(``extensions.package_install_files``), which installs the bundled wheel into the extension's
own site-packages and enables the add-on, and the operator runs from there. Blender's
``extension validate`` passes on the package and on the add-on's folder. In that Blender the
``fairsub`` module may come only from the bundled wheel (a finder refuses any other copy)."""

import json
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import REPO

SCRIPT = r"""
import importlib.abc, importlib.machinery, json, os, sys
root = os.environ["BLENDER_USER_RESOURCES"]

class OnlyBundled(importlib.abc.MetaPathFinder):
    # fairsub from the extension's site-packages (under the user folder), or not at all
    def find_spec(self, name, path, target=None):
        if name != "fairsub":
            return None
        spec = importlib.machinery.PathFinder.find_spec(
            name, [p for p in sys.path if p.startswith(root)])
        if spec is None:
            raise ModuleNotFoundError("fairsub is not installed from the extension's wheel")
        return spec

sys.meta_path.insert(0, OnlyBundled())
import bpy
r = bpy.ops.extensions.package_install_files(
    filepath=sys.argv[1], repo="user_default", enable_on_install=True)
import fairsub
bpy.ops.mesh.primitive_cube_add()
bpy.ops.fairsub.subdivide(scheme="catmull-clark", levels=2)
me = bpy.context.active_object.data
print("RESULT " + json.dumps({
    "install": sorted(r),
    "addons": sorted(bpy.context.preferences.addons.keys()),
    "fairsub": fairsub.__file__,
    "counts": [len(me.vertices), len(me.polygons)],
}))
"""


def extension_tool():
    """Blender's extension tool as ``build_extension.py`` finds it."""
    sys.path.insert(0, str(REPO / "blender"))
    try:
        import build_extension
    finally:
        sys.path.pop(0)
    return build_extension.blender_ext_command(None)


def wheel():
    given = os.environ.get("FAIRSUB_WHEEL")
    if given:
        return pathlib.Path(given)
    found = sorted((REPO / "target" / "wheels").glob("fairsub-*.whl"), key=os.path.getmtime)
    if found:
        return found[-1]
    if os.environ.get("FAIRSUB_REQUIRE_BLENDER") == "1":
        raise AssertionError("no fairsub wheel: set FAIRSUB_WHEEL or run maturin build")
    pytest.skip("no fairsub wheel (maturin build --release -m python/Cargo.toml)")


def test_the_extension_installs_and_runs_in_blender(tmp_path):
    whl = wheel()
    built = subprocess.run(
        [sys.executable, str(REPO / "blender" / "build_extension.py"), str(whl), "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=300,
    )
    assert built.returncode == 0, built.stderr
    package = pathlib.Path(built.stdout.strip().splitlines()[-1])
    assert package.is_file() and package.suffix == ".zip"
    # Blender's extension validator (the checks of extensions.blender.org's upload) passes on
    # the package as built, with its wheel and platforms, and on the add-on's folder
    for target in (package, REPO / "blender" / "fairsub_blender"):
        checked = subprocess.run(
            extension_tool() + ["validate", str(target)], capture_output=True, text=True, timeout=120
        )
        assert checked.returncode == 0 and "Success" in checked.stdout, checked.stdout + checked.stderr
    user = tmp_path / "user"
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(user))
    env.pop("PYTHONPATH", None)
    run = subprocess.run(
        [sys.executable, "-c", SCRIPT, str(package)],
        capture_output=True, text=True, timeout=300, env=env, cwd=tmp_path,
    )
    lines = [line for line in run.stdout.splitlines() if line.startswith("RESULT ")]
    assert run.returncode == 0 and lines, run.stdout + run.stderr
    r = json.loads(lines[-1][len("RESULT "):])
    assert r["install"] == ["FINISHED"]
    assert "bl_ext.user_default.fairsub_blender" in r["addons"]
    assert r["fairsub"].startswith(str(user))
    assert r["counts"] == [98, 96]
