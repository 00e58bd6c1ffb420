#!/usr/bin/env bash
# The prefiltered cubes the GPU reads, for the accuracy study (docs/accuracy-study.md): the
# default bake of every bundled, unseen and procedural map of the study, written by
# `iblab bake --out` to DIR/<map>/ (bundled maps by their stem, the unseen ones as
# pmndrs-<stem>, the builtins as builtin-<name>: the study's names), so that
# `accuracy_study eval|fit --bakes DIR` reads what shading reads.
#   scripts/accuracy-bakes.sh [DIR]       (default build/accuracy_bakes)
#   BAKE_ARGS="--prefilter-shading-lights 4" scripts/accuracy-bakes.sh DIR   (options added to
#                                         every bake: a DIR per variant, since a bake present is kept)
set -euo pipefail
cd "$(dirname "$0")/.."
iblab=${IBLAB:-build/app/iblab}
out=${1:-build/accuracy_bakes}
mkdir -p "$out"
bake() { # MAP NAME
  # shellcheck disable=SC2086
  [ -f "$out/$2/bake.json" ] || "$iblab" bake --env "$1" --no-errors ${BAKE_ARGS:-} --out "$out/$2" >/dev/null
}
for f in assets/environments/*.exr; do bake "$f" "$(basename "$f" .exr)"; done
for f in ../shared/assets/hdri/pmndrs/*.exr; do [ -f "$f" ] && bake "$f" "pmndrs-$(basename "$f" .exr)"; done
for name in sun sky studio; do bake "builtin:$name" "builtin-$name"; done
echo "$out"
