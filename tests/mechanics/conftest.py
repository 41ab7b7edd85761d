"""Shared fixtures for the engine's tests: derivations are cached per scene file, since each takes
a second or more and several tests read the same one."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import pytest

from grader.mechanics.lagrange import derive
from grader.mechanics.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]
SCENES = Path(__file__).resolve().parent / "scenes"


@lru_cache(maxsize=None)
def derivation_of(path: str):
    return derive(load_scene(path))


@pytest.fixture
def derived():
    """derived("problems/sphere.toml") or derived("double_pendulum") (a scene under tests/mechanics/scenes)."""

    def get(name: str):
        path = ROOT / name if name.endswith(".toml") else SCENES / f"{name}.toml"
        return derivation_of(str(path))

    return get
