"""docker-compose.yml and the Dockerfile: no Docker engine runs here, so their structure is checked,
and the commands they run are the ones the scale-out tests start as plain processes."""

from __future__ import annotations

import shlex
import tomllib
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

ROOT = Path(__file__).resolve().parents[1]
COMPOSE = yaml.safe_load((ROOT / "docker-compose.yml").read_text())
SERVICES = COMPOSE["services"]


def _command(service: str) -> list[str]:
    command = SERVICES[service]["command"]
    return command if isinstance(command, list) else shlex.split(command)


def test_the_five_services_are_there():
    assert set(SERVICES) == {"web", "worker", "redis", "postgres", "migrate"}


@pytest.mark.parametrize("service", ["web", "worker"])
def test_web_and_workers_wait_for_the_migration_and_a_healthy_broker(service):
    depends = SERVICES[service]["depends_on"]
    assert depends["migrate"]["condition"] == "service_completed_successfully"
    assert depends["redis"]["condition"] == "service_healthy"


def test_the_migration_waits_for_a_healthy_database_and_runs_once():
    assert SERVICES["migrate"]["depends_on"]["postgres"]["condition"] == "service_healthy"
    assert SERVICES["migrate"]["restart"] == "no"
    assert "grader db upgrade" in " ".join(_command("migrate"))


@pytest.mark.parametrize("service", ["postgres", "redis", "web", "worker"])
def test_long_running_services_have_health_checks(service):
    assert SERVICES[service]["healthcheck"]["test"]


def test_the_database_keeps_its_data_in_a_named_volume():
    volume = SERVICES["postgres"]["volumes"][0].split(":")[0]
    assert volume in COMPOSE["volumes"]


def test_web_runs_the_wsgi_app_under_gunicorn_as_the_scale_out_test_does():
    command = _command("web")
    assert command[0] == "gunicorn" and command[-1] == "grader.web.wsgi:app"
    assert "grader.web.wsgi:app" in (ROOT / "tests" / "web" / "test_scale_out.py").read_text()


def test_workers_run_the_celery_app_the_worker_test_runs():
    command = _command("worker")
    assert command[:4] == ["celery", "-A", "grader.jobs.celery_worker", "worker"]
    assert '"-A", "grader.jobs.celery_worker", "worker"' in (ROOT / "tests" / "jobs" / "test_celery_worker.py").read_text()


def test_every_service_of_ours_shares_the_settings_that_scale_out():
    for service in ("web", "worker", "migrate"):
        environment = SERVICES[service]["environment"]
        assert environment["DATABASE_URL"].startswith("postgresql+psycopg://")
        assert environment["GRADER_BROKER_URL"].startswith("redis://")
        assert environment["LAGRADE_RATELIMIT_STORAGE_URI"].startswith("redis://")


@pytest.mark.parametrize("arguments", [["db", "upgrade", "--help"], ["db", "load-problems", "--help"]])
def test_the_grader_commands_compose_runs_exist(arguments):
    from grader.cli import main

    assert CliRunner().invoke(main, arguments).exit_code == 0


def test_the_image_installs_the_deploy_extra_with_what_the_services_import():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    deploy = " ".join(project["optional-dependencies"]["deploy"])
    assert "[deploy]" in (ROOT / "Dockerfile").read_text()
    for package in ("gunicorn", "psycopg", "celery"):
        assert package in deploy
