#!/usr/bin/env bash
# Install slamcourse (system packages via apt when missing, Python packages via pip into .venv),
# put the `slamcourse` command on your PATH (a link in ~/.local/bin), and start the bundled
# course: `slamcourse next` in this terminal, or `bash scripts/start.sh serve` for the browser.
# Progress lives in an embedded SQLite file (`slamcourse doctor` prints where). A first argument
# that names another command runs it (`bash scripts/start.sh status`, `… list`, `… doctor`);
# options alone go to `next` (`bash scripts/start.sh --no-context`).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
EXTRAS="" source scripts/setup.sh

# The command, in every new shell: ~/.local/bin/slamcourse -> .venv/bin/slamcourse, and
# ~/.local/bin on PATH (the usual place for a user's commands; pipx does the same).
bin="$HOME/.local/bin"
mkdir -p "$bin"
ln -sf "$PWD/.venv/bin/slamcourse" "$bin/slamcourse"
line='case ":$PATH:" in *":$HOME/.local/bin:"*) ;; *) export PATH="$HOME/.local/bin:$PATH" ;; esac'
for rc in "$HOME/.bashrc" "$HOME/.profile" ${ZDOTDIR:+"$ZDOTDIR/.zshrc"}; do
  if ! grep -qs "# slamcourse: ~/.local/bin on PATH" "$rc"; then
    printf '\n# slamcourse: ~/.local/bin on PATH\n%s\n' "$line" >> "$rc"
    added=1
  fi
done
case ":$PATH:" in
  *":$bin:"*) ;;
  *) echo "==> \`slamcourse\` is in $bin; new shells find it (${added:+added to ~/.bashrc and ~/.profile; }or run: export PATH=\"$bin:\$PATH\")" >&2 ;;
esac

case "${1:-next}" in
  serve) shift; exec .venv/bin/slamcourse serve "$@" ;;
  next) [ $# -gt 0 ] && shift; exec .venv/bin/slamcourse next "$@" ;;
  -*) exec .venv/bin/slamcourse next "$@" ;;
  *) exec .venv/bin/slamcourse "$@" ;;
esac
