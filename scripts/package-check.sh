#!/usr/bin/env bash
# Does the Debian package work on a machine that never saw the source? Builds the .deb
# (cpack -G DEB in build/), bootstraps a clean Debian 12 root (mmdebstrap --variant=minbase:
# nothing but apt), installs the package there with apt, which must resolve every runtime
# dependency from the package's own Depends, and runs, in a chroot with no DISPLAY, from a
# directory outside any source tree:
#   iblab --version                and checks it prints "iblab <version>"
#   iblab render -o x.png          and checks that x.png is a 1280x720 PNG with a lit sphere
# Needs root, mmdebstrap and python3 (installed when missing).
#   scripts/package-check.sh                  # build the package from build/, then check it
#   scripts/package-check.sh --deb FILE.deb   # check a package built elsewhere (CI: the fresh root's)
#   scripts/package-check.sh --build-only     # only build it; prints the .deb's path
#   scripts/package-check.sh --keep           # leave the root for a look (path printed)
# Mounts and the root are removed on any exit, a failing step included.
set -euo pipefail
cd "$(dirname "$0")/.."

deb=
build_only=0
keep=0
while [ $# -gt 0 ]; do
  case "$1" in
    --deb) deb=$(realpath "$2"); shift 2 ;;
    --build-only) build_only=1; shift ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "package-check: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

start=$(date +%s)
step() { echo "package-check: $* ($(( $(date +%s) - start )) s)" >&2; }

if [ -z "$deb" ]; then
  build_dir=${IBLAB_BUILD_DIR:-build}
  [ -f "$build_dir/CMakeCache.txt" ] || cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
  step "building the package in $build_dir"
  # Only what the package holds (cmake/Install.cmake), not the tests; cpack installs it into a
  # staging directory and runs dpkg-shlibdeps on its binaries for the Depends.
  cmake --build "$build_dir" -j"$(nproc)" --target iblab iblab_oiio >&2
  (cd "$build_dir" && cpack -G DEB >&2)
  deb=$(ls -t "$PWD/$build_dir"/iblab_*.deb | head -n 1)
  step "built $deb"
  if [ "$build_only" -eq 1 ]; then
    echo "$deb"
    exit 0
  fi
fi
[ -f "$deb" ] || { echo "package-check: $deb: no such package" >&2; exit 2; }

if [ "$(id -u)" -ne 0 ]; then
  echo "package-check: needs root (chroot and bind mounts)" >&2
  exit 2
fi
# mmdebstrap makes the root; Python reads the rendered PNG back (below).
tools=()
command -v mmdebstrap >/dev/null || tools+=(mmdebstrap)
command -v python3 >/dev/null || tools+=(python3-minimal)
if [ ${#tools[@]} -gt 0 ]; then
  step "installing ${tools[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${tools[@]}" >/dev/null
fi

# shellcheck source=lib/debian-root.sh
. scripts/lib/debian-root.sh
debian_root_keep=$keep
step "bootstrapping Debian 12 (minbase)"
debian_root_create iblab-package
echo "package-check: root at $root" >&2
debian_root_mount
cp "$deb" "$root/tmp/"

in_root() {
  # A clean environment: no DISPLAY, no variables of the caller's session.
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb DEBIAN_FRONTEND=noninteractive \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$1"
}

step "installing $(basename "$deb") with apt"
in_root "apt-get update -qq && apt-get install -y -qq --no-install-recommends /tmp/$(basename "$deb") >/dev/null"
in_root "dpkg -L iblab | grep -E 'bin/iblab|libiblab_oiio.so|shaders/pbr.frag|environments/courtyard.exr'" >&2

expected_version=$(dpkg-deb -f "$deb" Version)
step "iblab --version"
version=$(in_root 'mkdir -p /root/elsewhere && cd /root/elsewhere && iblab --version')
echo "  $version" >&2
[ "$version" = "iblab $expected_version" ] || { echo "package-check: --version printed '$version', expected 'iblab $expected_version'" >&2; exit 1; }

step "iblab render -o x.png"
in_root 'cd /root/elsewhere && iblab render -o x.png' >&2
png="$root/root/elsewhere/x.png"
# A PNG of the default size whose pixels are not all one value (a render that only cleared
# the frame, or a sky without the sphere, would be): the header's signature and IHDR size,
# and, decoded by Python's zlib, more than a few distinct byte values in the image data.
python3 - "$png" <<'EOF'
import struct, sys, zlib
path = sys.argv[1]
data = open(path, "rb").read()
if data[:8] != b"\x89PNG\r\n\x1a\n":
    sys.exit(f"package-check: {path}: not a PNG")
width, height = struct.unpack(">II", data[16:24])
if (width, height) != (1280, 720):
    sys.exit(f"package-check: {path}: {width}x{height}, expected the default 1280x720")
pos, idat = 8, b""
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    if kind == b"IDAT":
        idat += data[pos + 8:pos + 8 + length]
    pos += 12 + length
distinct = len(set(zlib.decompress(idat)))
if distinct < 64:
    sys.exit(f"package-check: {path}: only {distinct} distinct byte values: not a lit scene")
print(f"  {path}: PNG {width}x{height}, {distinct} distinct byte values", file=sys.stderr)
EOF
step "passed"
