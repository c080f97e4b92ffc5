#!/usr/bin/env bash
# The web tests: node (hashes against native, the streaming API) and
# headless Chromium (the viewer).  Needs scripts/web-build.sh's output and
# the native command (DBSS_BIN, default build/bin/dbss).  scripts/test.sh's
# "== web ==" step.
set -euo pipefail
cd "$(dirname "$0")/../.."
export DBSS_BIN=${DBSS_BIN:-$PWD/build/bin/dbss}
node --test --test-reporter=spec web/test/hashes.test.mjs web/test/streaming.test.mjs web/test/browser.test.mjs
