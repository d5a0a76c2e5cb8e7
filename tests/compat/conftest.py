"""Fixtures of the compat-switch tests: the real ARGoS the argos-target tests find or build
(tests/targets/argos/conftest.py), so that this folder runs on its own too."""

from targets.argos.conftest import argos_prefix  # noqa: F401  (this folder's fixture of the same name)
