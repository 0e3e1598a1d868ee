"""Shared helpers of the Python tests: the fairsub command line to compare with."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def cli_path():
    """The `fairsub` binary: $FAIRSUB_BIN, else the repository's release build."""
    p = pathlib.Path(os.environ.get("FAIRSUB_BIN", REPO / "target" / "release" / "fairsub"))
    if not p.exists():
        raise RuntimeError(
            f"no fairsub binary at {p}: run `cargo build --release` (or set FAIRSUB_BIN)"
        )
    return str(p)


@pytest.fixture(scope="session")
def cli():
    """Runs `fairsub ARGS...`; returns (exit code, stdout, stderr)."""
    exe = cli_path()

    def run(*args):
        r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        return r.returncode, r.stdout, r.stderr

    return run
