# .ci/debian_packages.sh — sourced by the scripts that need Debian packages the library does not
# (python/ci.sh, bench/run_peers.sh): require_debian_packages CALLER PACKAGE... installs those
# that are missing when run as root, and otherwise stops with the apt-get line to run.
require_debian_packages() {
  local caller=$1 missing="" p
  shift
  for p in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed"; then missing="$missing $p"; fi
  done
  [ -z "$missing" ] && return 0
  if [ "$(id -u)" != 0 ]; then
    echo "$caller: missing$missing; as root: apt-get install$missing" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  echo "installing$missing"
  # The package lists may be absent or stale on a fresh machine: update only then.
  if ! apt-get install -y -qq $missing > /dev/null; then
    apt-get update -qq
    apt-get install -y -qq $missing > /dev/null
  fi
}
