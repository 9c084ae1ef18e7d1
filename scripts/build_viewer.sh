#!/usr/bin/env bash
# Builds the browser viewer of `scenesmith view` into <repo>/target/viewer/.
#
#   scripts/build_viewer.sh [--quiet]
#
# Idempotent and cheap when nothing changed:
# - `npm ci` in src/view/web only when node_modules is missing or package-lock.json changed
#   (stamp: src/view/web/node_modules/.scenesmith-lock.sha256);
# - the bundle is rebuilt only when package-lock.json or a top-level file of src/view/web changed
#   (stamp: target/viewer/.stamp, a hidden file the server does not serve).
# Prints one line (nothing with --quiet); errors go to stderr with a non-zero exit.
# Needs node >= 18 and npm; the npm registry is only contacted by `npm ci`.
set -euo pipefail

quiet=0
case "${1:-}" in
  --quiet) quiet=1 ;;
  "") ;;
  *) echo "usage: $0 [--quiet]" >&2; exit 2 ;;
esac

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
web="$repo/src/view/web"
out="$repo/target/viewer"

die() { echo "build_viewer: $*" >&2; exit 1; }
say() { [ "$quiet" = 1 ] || echo "$*"; }

command -v node >/dev/null || die "node not found: install Node.js >= 18 (Debian: apt-get install nodejs npm)"
command -v npm >/dev/null || die "npm not found: install npm (Debian: apt-get install npm)"
node_major="$(node -p 'process.versions.node.split(".")[0]')"
[ "$node_major" -ge 18 ] || die "node $(node --version) is too old: the viewer build needs node >= 18"

mkdir -p "$repo/target"
# Serialise concurrent runs (parallel tests may all ask for the viewer at once).
if command -v flock >/dev/null; then
  exec 9>"$repo/target/.viewer.lock"
  flock 9
fi

lock_hash="$(sha256sum "$web/package-lock.json" | cut -d' ' -f1)"
lock_stamp="$web/node_modules/.scenesmith-lock.sha256"
installed=no
if [ ! -f "$lock_stamp" ] || [ "$(cat "$lock_stamp")" != "$lock_hash" ]; then
  log="$(mktemp)"
  # No install scripts: the only one (esbuild's) re-checks a binary npm already installed.
  if ! (cd "$web" && npm ci --ignore-scripts --no-audit --no-fund) >"$log" 2>&1; then
    cat "$log" >&2
    rm -f "$log"
    die "npm ci failed in $web (output above)"
  fi
  rm -f "$log"
  echo "$lock_hash" >"$lock_stamp"
  installed=yes
fi

# Sources: every top-level file of src/view/web (package-lock.json included), by relative name,
# so a new style sheet counts without editing this list and the repository may move.
source_hash="$(cd "$web" && find . -maxdepth 1 -type f -print0 | sort -z | xargs -0 sha256sum | sha256sum | cut -d' ' -f1)"
if [ -f "$out/.stamp" ] && [ "$(cat "$out/.stamp")" = "$source_hash" ]; then
  say "viewer: up to date in $out"
  exit 0
fi

# Build beside the old bundle and swap, so a running server never sees a half-written one.
staging="$out.tmp"
rm -rf "$staging" "$out.old"
node "$web/build.mjs" "$staging" || die "the viewer bundle did not build (esbuild errors above)"
echo "$source_hash" >"$staging/.stamp"
[ -d "$out" ] && mv "$out" "$out.old"
mv "$staging" "$out"
rm -rf "$out.old"
say "viewer: built $out (npm ci: $installed)"
