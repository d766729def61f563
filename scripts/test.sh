#!/usr/bin/env bash
# Install everything the tests need (system packages via apt when missing, Python packages via
# pip into .venv), then run lint, type checks, the course validator and the whole test suite.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
EXTRAS="[test]" source scripts/setup.sh

echo "==> ruff"
.venv/bin/ruff check src tests benchmarks
echo "==> ruff format --check"
.venv/bin/ruff format --check src tests benchmarks
echo "==> mypy"
.venv/bin/mypy
# The bundled course is validated once, by pytest (tests/content/test_bundled_course.py: one test
# per exercise, 20 variants each, code exercises' files graded in the sandbox, plus the checks of
# the course as a whole). Here only the command itself runs, on one exercise of that course.
echo "==> slamcourse validate (the command, on one exercise of the bundled course)"
.venv/bin/slamcourse validate --variants 0 state/state-vector-size
echo "==> pytest"
rc=0
.venv/bin/python -m pytest -q -p no:cacheprovider "$@" || rc=$?
if [ "$rc" -eq 5 ]; then echo "pytest: no tests collected"; exit 1; fi
exit "$rc"
