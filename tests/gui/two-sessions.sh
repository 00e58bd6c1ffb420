#!/usr/bin/env bash
# What the GUI remembers between sessions: runs tests/gui/sessions/first.txt, then second.txt
# in a new process with the same config folder, then unreadable.txt after garbling the file.
# Every folder is under WORKDIR: the user's own config, pictures and documents are not touched.
#   tests/gui/two-sessions.sh WORKDIR IBLAB
set -euo pipefail
work=$1 iblab=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work/config" "$work/documents"
cd "$work"
export HOME="$work" XDG_CONFIG_HOME="$work/config" XDG_DOCUMENTS_DIR="$work/documents"
unset XDG_PICTURES_DIR
echo 'XDG_PICTURES_DIR="$HOME/Shots"' > "$XDG_CONFIG_HOME/user-dirs.dirs"
prefs="$XDG_CONFIG_HOME/iblab/gui.json"
"$iblab" --script "$here/sessions/first.txt" --offscreen
[ -f "$prefs" ] || { echo "two-sessions: the first session left no $prefs" >&2; exit 1; }
"$iblab" --script "$here/sessions/second.txt" --offscreen
echo '{"sections": ' > "$prefs"
"$iblab" --script "$here/sessions/unreadable.txt" --offscreen 2> "$work/stderr.txt"
grep -q "gui.json: not valid JSON" "$work/stderr.txt" || { echo "two-sessions: no warning naming the unreadable $prefs:" >&2; cat "$work/stderr.txt" >&2; exit 1; }
echo "two-sessions: passed"
