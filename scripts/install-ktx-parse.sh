#!/usr/bin/env bash
# Installs the npm package the export tests read KTX 2.0 files with (ktx-parse, an
# independent reader), at the version and integrity hash of tests/ktx2/package-lock.json,
# into tests/ktx2/node_modules (ignored by git). Needs Debian's nodejs and npm
# (scripts/install-deps.sh). The tests skip the KTX 2.0 checks, saying so, until it has run.
set -euo pipefail
cd "$(dirname "$0")/../tests/ktx2"
npm ci --no-audit --no-fund --silent
