"""``auszug studio``: argument checks that fail before any server starts."""

from __future__ import annotations

import pytest

from auszug.cli import main
from auszug.cli.studio import resolve_paths
from auszug.errors import AuszugError


def test_resolve_paths_defaults_to_drawing_folder(workspace):
    assert resolve_paths(str(workspace / "tn-2.uc"), None) == (workspace.resolve(), "tn-2.uc")
    assert resolve_paths(None, workspace) == (workspace.resolve(), None)


def test_drawing_outside_workspace_refused(workspace, tmp_path):
    sub = workspace / "sub"
    sub.mkdir()
    with pytest.raises(AuszugError, match="inside the workspace"):
        resolve_paths(str(workspace / "tn-2.uc"), sub)


def test_missing_drawing_exit_2(tmp_path, capsys):
    assert main(["studio", str(tmp_path / "nope.uc"), "--no-browser"]) == 2
    assert "no such file" in capsys.readouterr().err


def test_help_lists_options(capsys):
    assert main(["studio", "--help"]) == 0
    out = capsys.readouterr().out
    assert "--workspace" in out and "--no-browser" in out and "--port" in out


def test_missing_bundle_names_build_command(workspace, tmp_path, monkeypatch, capsys):
    """Without the built front end the command stops before serving and says how to build it."""
    import auszug.studio.server as server

    monkeypatch.setattr(server, "static_dir", lambda: tmp_path / "no-static")
    assert main(["studio", str(workspace / "tn-2.uc"), "--no-browser"]) == 2
    assert "make web" in capsys.readouterr().err
