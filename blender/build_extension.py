"""Builds the fairsub Blender extension: the add-on in ``blender/fairsub_blender/`` with the
fairsub wheel bundled (``wheels = [...]`` in its manifest), as the ``.zip`` that Blender 4.2+
installs (Preferences > Get Extensions > Install from Disk, or
``blender --command extension install-file -r user_default FILE``).

    python blender/build_extension.py target/wheels/fairsub-*.whl --out dist/

The package is built and validated by Blender's own extension tool: ``blender --command
extension build`` when a ``blender`` executable is given (``--blender``) or on the PATH, else
the same tool's script inside the ``bpy`` module of the running Python
(``bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py``). Prints the path of the package."""

import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
ADDON = HERE / "fairsub_blender"


def wheel_platforms(wheel):
    """Blender's platform names for a wheel's platform tag (``manylinux_2_35_x86_64`` ->
    ``linux-x64``); empty for a pure-Python wheel."""
    tag = pathlib.Path(wheel).stem.split("-")[-1]
    if tag == "any":
        return []
    machine = {"x86_64": "x64", "amd64": "x64", "aarch64": "arm64", "arm64": "arm64"}
    out = []
    for t in tag.split("."):
        system = "linux" if "linux" in t else "windows" if t.startswith("win") else "macos"
        arch = next((v for k, v in machine.items() if t.endswith(k)), None)
        if arch is None:
            raise SystemExit(f"unknown wheel platform '{t}' in {wheel}")
        out.append(f"{system}-{arch}")
    return sorted(set(out))


def blender_ext_command(blender):
    """The command that runs Blender's extension tool."""
    exe = blender or shutil.which("blender")
    if exe:
        return [exe, "--factory-startup", "--command", "extension"]
    try:
        import bpy  # noqa: F401  (only to find the module's own copy of the tool)
    except ImportError:
        raise SystemExit(
            "Blender's extension tool is needed: give --blender PATH, put blender on the PATH, "
            "or run this with a Python that has the bpy module"
        )
    # bpy's Python package lives in <version>/scripts/modules/bpy; the tool beside it
    scripts = pathlib.Path(sys.modules["bpy"].__file__).resolve().parents[2]
    tool = scripts / "addons_core" / "bl_pkg" / "cli" / "blender_ext.py"
    if not tool.is_file():
        raise SystemExit(f"no {tool.relative_to(scripts)} in the bpy module's {scripts}")
    return [sys.executable, str(tool)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("wheel", help="the fairsub wheel (maturin build --release -m python/Cargo.toml)")
    ap.add_argument("--out", default="dist", help="output folder (default dist/)")
    ap.add_argument("--blender", help="a blender executable (4.2 or later)")
    a = ap.parse_args()
    wheel = pathlib.Path(a.wheel).resolve()
    if not wheel.is_file() or not re.match(r"fairsub-[^-]+-.*\.whl$", wheel.name):
        raise SystemExit(f"{a.wheel}: not a fairsub wheel")
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        src = pathlib.Path(tmp) / "fairsub_blender"
        shutil.copytree(ADDON, src, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
        (src / "wheels").mkdir()
        shutil.copy2(wheel, src / "wheels" / wheel.name)
        manifest = (src / "blender_manifest.toml").read_text()
        lines = [f'wheels = ["./wheels/{wheel.name}"]']
        platforms = wheel_platforms(wheel.name)
        if platforms:
            lines.append("platforms = [" + ", ".join(f'"{p}"' for p in platforms) + "]")
        # the top-level keys go before the first table
        head, sep, tail = manifest.partition("\n[")
        manifest = head.rstrip("\n") + "\n" + "\n".join(lines) + "\n" + sep + tail
        (src / "blender_manifest.toml").write_text(manifest)
        cmd = blender_ext_command(a.blender) + [
            "build", "--source-dir", str(src), "--output-dir", str(out),
        ]
        r = subprocess.run(cmd, capture_output=True, text=True)
        sys.stderr.write(r.stderr)
        if r.returncode != 0:
            sys.stderr.write(r.stdout)
            raise SystemExit(f"Blender's extension build failed ({r.returncode})")
    made = sorted(out.glob("fairsub_blender-*.zip"), key=os.path.getmtime)
    print(made[-1])


if __name__ == "__main__":
    main()
