"""Repository-wide pytest set-up: docstring examples run from the repository root.

``--doctest-modules`` (see ``pyproject.toml``) runs the examples in every module under ``grader/``;
the engine's examples read ``problems/*.toml`` by relative path, as a user at the root would.
"""

import pytest
from _pytest.doctest import DoctestItem

# Importing this module lowers the importing process's CPU priority (it is a derivation child's
# entry point): collecting it for doctests would nice the whole test run.
# grader/web/wsgi.py makes an app and starts workers when imported (it is gunicorn's entry point).
collect_ignore = ["grader/jobs/derivation_child.py", "grader/web/wsgi.py"]


@pytest.fixture(autouse=True)
def _examples_run_from_the_repository_root(request, monkeypatch):
    if isinstance(request.node, DoctestItem):
        monkeypatch.chdir(request.config.rootpath)
