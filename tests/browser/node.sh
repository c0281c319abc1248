#!/usr/bin/env bash
# Runs the browser tests' node steps for CTest (tests/browser/CMakeLists.txt):
#   node.sh install DIR        npm ci of package-lock.json in DIR (the build tree's copy), skipped
#                              when DIR/node_modules already matches the lock file. No browser is
#                              downloaded: the tests drive Debian's /usr/bin/chromium.
#   node.sh run SCRIPT ARGS... node SCRIPT ARGS...
# Without node or npm: exit 77, which CTest counts as skipped, except under CI, which fails.
set -euo pipefail
in_ci() { [ -n "${CI:-}" ] && [ "$CI" != false ] && [ "$CI" != 0 ]; }
need() {
  if command -v "$1" >/dev/null 2>&1; then return; fi
  if in_ci; then
    echo "$1 is missing, and CI must have it (scripts/setup installs it)"
    exit 1
  fi
  echo "skipped: $1 is missing (scripts/setup installs it)"
  exit 77
}
case "${1:-}" in
  install)
    need npm
    cd "$2"
    stamp=node_modules/.masnet-package-lock.json
    if [ -f "$stamp" ] && cmp -s package-lock.json "$stamp"; then
      echo "node_modules matches package-lock.json"
      exit 0
    fi
    export PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1
    npm ci --no-audit --no-fund --ignore-scripts
    cp package-lock.json "$stamp"
    ;;
  run)
    need node
    shift
    exec node "$@"
    ;;
  *)
    echo "usage: node.sh install DIR | node.sh run SCRIPT ARGS..." >&2
    exit 2
    ;;
esac
