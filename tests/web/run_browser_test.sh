#!/usr/bin/env bash
# web.browser: installs puppeteer-core from package-lock.json (npm ci, offline from the npm cache when it can) under
# the test's build folder, then runs browser_test.mjs against `freeplay serve --web` in Debian's headless chromium.
# Usage: run_browser_test.sh FREEPLAY SCENARIO OUTDIR. Exit 77 (skipped, saying why) without chromium, node or npm.
set -euo pipefail
freeplay=$1 scenario=$2 out=$3
here=$(cd "$(dirname "$0")" && pwd)
chromium=${FREEPLAY_CHROMIUM:-$(command -v chromium || true)}
[ -n "$chromium" ] || { echo "SKIPPED: no chromium (scripts/setup.sh installs Debian's)"; exit 77; }
command -v node >/dev/null && command -v npm >/dev/null || { echo "SKIPPED: no node/npm"; exit 77; }
mkdir -p "$out/npm"
cp "$here/package.json" "$here/package-lock.json" "$here/browser_test.mjs" "$out/npm/"
if [ ! -d "$out/npm/node_modules/puppeteer-core" ] || [ "$here/package-lock.json" -nt "$out/npm/node_modules/.package-lock.json" ]; then
  if ! (cd "$out/npm" && npm ci --prefer-offline --no-audit --no-fund --loglevel=error >"$out/npm-ci.log" 2>&1); then
    echo "SKIPPED: npm ci could not install puppeteer-core (npm registry unreachable and not in the npm cache):"
    tail -5 "$out/npm-ci.log"
    exit 77
  fi
fi
cd "$out/npm"
exec env FREEPLAY_CHROMIUM="$chromium" node browser_test.mjs "$freeplay" "$scenario" "$out" "$here/expected"
