"""``auszug`` itself: help for every command, version, usage errors, the console script."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from auszug.cli import COMMANDS, main
from tests.cli.conftest import BAD_LINE, TN


def test_help_lists_every_command(cli):
    r = cli("--help")
    assert r.code == 0
    for name in COMMANDS:
        assert name in r.out


@pytest.mark.parametrize("name", COMMANDS)
def test_every_command_has_help(cli, name):
    r = cli(name, "--help")
    assert r.code == 0 and r.out.startswith(f"usage: auszug {name}")
    assert "examples:" in r.out or name == "demo"


def test_version(cli):
    r = cli("--version")
    assert r.code == 0 and r.out.startswith("auszug ")


@pytest.mark.parametrize("args", [[], ["frobnicate"], ["build"], ["build", "x.uc", "--samples", "1"],
                                  ["build", "x.uc", "--param", "spline"], ["render", "x.uc", "--width", "ten"]])
def test_usage_errors_exit_2_without_traceback(cli, args):
    r = cli(*args)
    assert r.code == 2
    assert "usage:" in r.err and "Traceback" not in r.err


def test_main_reads_sys_argv_when_given_none(monkeypatch, capsys):
    monkeypatch.setattr(sys, "argv", ["auszug", "--version"])
    assert main() == 0
    assert capsys.readouterr().out.startswith("auszug ")


def _script() -> str:
    exe = Path(sys.executable).with_name("auszug")
    return str(exe) if exe.exists() else "auszug"


def test_console_script_builds_and_reports_bad_input(tmp_path, bad_uc):
    env = {**os.environ, "COLUMNS": "100"}
    ok = subprocess.run([_script(), "build", str(TN / "tn-1.uc"), "-o", str(tmp_path / "a.network.json")],
                        capture_output=True, text=True, env=env)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "a.network.json").stat().st_size > 0
    bad = subprocess.run([_script(), "build", str(bad_uc), "-o", str(tmp_path / "b.obj")],
                         capture_output=True, text=True, env=env)
    assert bad.returncode == 2
    assert bad.stderr == f"auszug: {bad_uc}:{BAD_LINE}: 'ptPos': 'x' is not a number\n"
    assert not (tmp_path / "b.obj").exists()
    mod = subprocess.run([sys.executable, "-m", "auszug.cli", "info", "--help"], capture_output=True, text=True)
    assert mod.returncode == 0 and mod.stdout.startswith("usage: auszug info")


def test_build_does_not_import_matplotlib_or_rich(tmp_path):
    code = ("import sys; from auszug.cli import main; "
            f"rc = main(['build', {str(TN / 'tn-1.uc')!r}, {str(TN / 'tn-2.uc')!r}, '-o', {str(tmp_path)!r}]); "
            "print(rc, 'matplotlib' in sys.modules, 'rich' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split()[-3:] == ["0", "False", "False"]
