# A throwaway Debian 12 root for the fresh-root checks (scripts/fresh-check.sh,
# scripts/package-check.sh), sourced by them:
#   debian_root_create NAME   bootstraps bookworm (mmdebstrap --variant=minbase: nothing but
#                             apt) in a new temporary directory, sets $root and arranges its
#                             removal on exit; $debian_root_keep=1 keeps it for a look
#   debian_root_mount         binds /proc, /sys and /dev into it and copies resolv.conf
# The caller must be root and have mmdebstrap.

debian_root_keep=${debian_root_keep:-0}
debian_root_mounted=()

debian_root_cleanup() {
  local status=$?
  # Unmount in reverse order; the root is deleted only once nothing is mounted below it, so
  # rm can never reach the host's /dev, /proc or /sys through a bind mount.
  for ((i = ${#debian_root_mounted[@]} - 1; i >= 0; i--)); do
    umount -R "${debian_root_mounted[i]}" 2>/dev/null || umount -R -l "${debian_root_mounted[i]}" || true
  done
  if grep -q " $root/" /proc/mounts; then
    echo "$debian_root_name: mounts remain under $root; not deleting it" >&2
  elif [ "$debian_root_keep" -eq 1 ]; then
    echo "$debian_root_name: root kept at $root" >&2
  else
    rm -rf --one-file-system "$root"
  fi
  exit "$status"
}

debian_root_create() {
  debian_root_name=$1
  root=$(mktemp -d "${TMPDIR:-/tmp}/$debian_root_name.XXXXXX")
  trap debian_root_cleanup EXIT
  trap 'exit 130' INT TERM
  local sources=/etc/apt/sources.list.d/debian.sources
  [ -f "$sources" ] || sources=/etc/apt/sources.list
  mmdebstrap --variant=minbase --quiet bookworm "$root" "$sources"
}

debian_root_mount() {
  for fs in proc sys dev; do
    mount --rbind "/$fs" "$root/$fs"
    debian_root_mounted+=("$root/$fs")
    mount --make-rslave "$root/$fs"
  done
  cp /etc/resolv.conf "$root/etc/resolv.conf"
}
