#!/usr/bin/env bash
# Install everything the tests need (system packages via apt when missing, Python packages via
# pip into .venv), then run lint, type checks and the whole test suite.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export DEBIAN_FRONTEND=noninteractive PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INPUT=1
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
PY="${PYTHON:-python3}"

need=()
command -v bwrap >/dev/null 2>&1 || need+=(bubblewrap)        # the learner-code sandbox
"$PY" -c "import ensurepip, venv" >/dev/null 2>&1 || need+=(python3-venv)
if [ "${#need[@]}" -gt 0 ]; then
  echo "==> apt-get install ${need[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

if [ ! -x .venv/bin/python ] || ! .venv/bin/python -c "" 2>/dev/null; then
  rm -rf .venv
  "$PY" -m venv .venv
fi
echo "==> pip install -e .[test]"
.venv/bin/python -m pip install -q -e ".[test]"

echo "==> ruff"
.venv/bin/ruff check src tests benchmarks
echo "==> mypy"
.venv/bin/mypy
echo "==> slamcourse validate (bundled course)"
.venv/bin/slamcourse validate --variants 10
echo "==> pytest"
rc=0
.venv/bin/python -m pytest -q -p no:cacheprovider "$@" || rc=$?
if [ "$rc" -eq 5 ]; then echo "pytest: no tests collected"; exit 1; fi
exit "$rc"
