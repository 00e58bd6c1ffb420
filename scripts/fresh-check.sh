#!/usr/bin/env bash
# Runs the README's two commands on a freshly installed Debian 12: bootstraps a minimal
# bookworm root (mmdebstrap --variant=minbase, nothing but apt), clones this repository's
# committed HEAD into it and runs, inside a chroot with no DISPLAY, exactly the first two
# command lines of README.md's "The two commands" block; then builds the Debian package
# there and installs it into a second clean root (scripts/package-check.sh); then any --also
# commands.
# A package that scripts/install-deps.sh forgets fails here, where a developer's machine
# (which has it installed from earlier work) would hide it. Needs root and mmdebstrap.
#   scripts/fresh-check.sh                          # both README commands
#   scripts/fresh-check.sh --also 'scripts/fuzz.sh 60'   # then more, in the same root
#   scripts/fresh-check.sh --keep                   # leave the root for a look (path printed)
# Uncommitted changes are not tested: commit first. Mounts and the root are removed on
# any exit, a failing step included.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD

also=()
keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --also) also+=("$2"); shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "fresh-check: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

if [ "$(id -u)" -ne 0 ]; then
  echo "fresh-check: needs root (chroot and bind mounts)" >&2
  exit 2
fi
if ! command -v mmdebstrap >/dev/null; then
  echo "fresh-check: installing mmdebstrap"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mmdebstrap >/dev/null
fi

# The README's block: the first two lines that are neither comments nor blank.
mapfile -t readme_commands < <(awk '
  /^## The two commands/ { in_section = 1; next }
  in_section && /^```sh/ { in_block = 1; next }
  in_block && /^```/ { exit }
  in_block && !/^[[:space:]]*(#|$)/ { print }' README.md)
if [ ${#readme_commands[@]} -ne 2 ]; then
  echo "fresh-check: README.md's 'The two commands' block should hold 2 commands, found ${#readme_commands[@]}" >&2
  exit 1
fi

step() { echo; echo "fresh-check: $* ($(( $(date +%s) - start )) s)"; }
start=$(date +%s)

# shellcheck source=lib/debian-root.sh
. scripts/lib/debian-root.sh
debian_root_keep=$keep
step "bootstrapping Debian 12 (minbase)"
debian_root_create iblab-fresh
echo "fresh-check: root at $root"

step "cloning $(git rev-parse --short HEAD) into the root"
mkdir -p "$root/work"
git clone --quiet --no-local "$repo" "$root/work/iblab"
git -C "$root/work/iblab" checkout --quiet "$(git rev-parse HEAD)"
# The tests read optional candidate assets from ../shared/assets when it exists beside the
# checkout (CI has it); give the root the same, so that the same tests run.
if [ -d "$repo/../shared/assets" ]; then
  mkdir -p "$root/work/shared"
  cp -r "$repo/../shared/assets" "$root/work/shared/"
fi

debian_root_mount
# The host's own certificate authorities too (a network that inspects TLS, as this machine's
# does, has its CA there): apt reads plain HTTP, but npm's registry is HTTPS. ca-certificates,
# installed by the first command, adds them to the root's bundle, which npm is pointed at.
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  mkdir -p "$root/usr/local/share/ca-certificates"
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
fi

in_root() {
  # A clean environment: no DISPLAY, no variables of the caller's session.
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb npm_config_cafile=/etc/ssl/certs/ca-certificates.crt \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    /bin/bash -c "cd /work/iblab && $1"
}

n=1
for command in "${readme_commands[@]}"; do
  step "command $n: $command"
  in_root "$command"
  n=$((n + 1))
done

step "checking that the first command wrote the headless render"
in_root 'test -s iblab-default.png' || { echo "fresh-check: iblab-default.png is missing" >&2; exit 1; }

# The Debian package, built here from the README's build, installed into a second, clean root
# (scripts/package-check.sh): a user's machine has none of the build's packages.
step "building the Debian package"
deb=$(in_root 'scripts/package-check.sh --build-only')
step "checking the package in a clean root"
scripts/package-check.sh --deb "$root$deb"

for command in "${also[@]}"; do
  step "command $n: $command"
  in_root "$command"
  n=$((n + 1))
done
step "passed"
