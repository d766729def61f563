# Sourced by start.sh and test.sh: system packages via apt when missing, then a venv in .venv
# with slamcourse installed (EXTRAS selects pip extras, e.g. "[test]"). pip runs only when
# pyproject.toml changed since the last install with these extras (a stamp in .venv).
export DEBIAN_FRONTEND=noninteractive PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_NO_INPUT=1
SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
PY="${PYTHON:-python3}"

need=()
command -v "$PY" >/dev/null 2>&1 || need+=(python3)
command -v bwrap >/dev/null 2>&1 || need+=(bubblewrap)          # the learner-code sandbox
"$PY" -c "import ensurepip, venv" >/dev/null 2>&1 || need+=(python3-venv)
# browser tests: Playwright drives Debian's chromium (never `playwright install`)
case "${EXTRAS:-}" in
  *test*)
    command -v chromium >/dev/null 2>&1 || need+=(chromium)
    # the JupyterHub test's proxy, configurable-http-proxy, comes from npm (below)
    command -v npm >/dev/null 2>&1 || need+=(npm) ;;
esac
if [ "${#need[@]}" -gt 0 ] && command -v apt-get >/dev/null 2>&1; then
  echo "==> apt-get install ${need[*]}" >&2
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

if [ ! -x .venv/bin/python ] || ! .venv/bin/python -c "" 2>/dev/null; then
  rm -rf .venv
  "$PY" -m venv .venv
fi
stamp_of() { echo ".venv/.slamcourse-installed${1:+-$(echo "$1" | tr -cd 'a-z,')}"; }
want="$(sha256sum pyproject.toml | cut -d' ' -f1)"
stamp="$(stamp_of "${EXTRAS:-}")"
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "==> pip install -e .${EXTRAS:-}" >&2
  .venv/bin/python -m pip install -q -e ".${EXTRAS:-}"
  echo "$want" > "$stamp"
  echo "$want" > "$(stamp_of "")"       # any install with extras includes the base install
fi
# tests: configurable-http-proxy (npm) for the JupyterHub test, kept inside the venv
case "${EXTRAS:-}" in
  *test*)
    if [ ! -x .venv/chp/node_modules/.bin/configurable-http-proxy ] && command -v npm >/dev/null 2>&1; then
      echo "==> npm install configurable-http-proxy (into .venv/chp)" >&2
      npm install --prefix .venv/chp --no-audit --no-fund --loglevel=error \
        "configurable-http-proxy@^4" >/dev/null
    fi ;;
esac
