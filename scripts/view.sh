#!/usr/bin/env bash
# Serves the dbss viewer (web/viewer/) on 127.0.0.1 and prints its URL.
#
#   bash scripts/view.sh [FILE.dbss] [--rate BYTES_PER_S] [--port N]
#
# Without FILE it opens the shipped example, build/example/double-torus.dbss
# (encoded here first if scripts/example.sh has not made it).  --rate sends
# .dbss files slowly, in 1 KB pieces, to watch the levels arrive.  Builds
# the WebAssembly module first if it is missing (scripts/web-build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
file=""
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rate|--port|--piece) args+=("$1" "$2"); shift 2 ;;
    -*) echo "view: unknown option $1" >&2; exit 2 ;;
    *) file=$1; shift ;;
  esac
done
if [ ! -f build-web/dist/dbss_wasm.wasm ] || [ ! -d web/node_modules/three ]; then
  bash scripts/web-build.sh build-web
fi
if [ -z "$file" ]; then
  file=build/example/double-torus.dbss
  if [ ! -f "$file" ]; then
    [ -x build/bin/dbss ] || { echo "view: no $file and no build/bin/dbss: run bash scripts/example.sh first" >&2; exit 1; }
    mkdir -p build/example
    build/bin/dbss encode examples/double-torus.xyz -o "$file" >/dev/null
  fi
fi
[ -f "$file" ] || { echo "view: $file: no such file" >&2; exit 1; }
exec node web/tools/serve.mjs "${args[@]}" "$file"
