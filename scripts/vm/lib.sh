# shellcheck shell=bash
# Common helpers of the VM test scripts (sourced, not run).
# The VM: Debian 12's own kernel under qemu (TCG), an initramfs of busybox-static, the kernel's
# configfs module, an out-of-tree gpio-sim module and the test programs. See scripts/vm/README.md.

VM_SCRIPTS_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck disable=SC2034 # used by the scripts that source this file
VM_REPO_DIR=$(cd "$VM_SCRIPTS_DIR/../.." && pwd)

vm_log() { printf 'stepmod-vm: %s\n' "$*" >&2; }
vm_die() {
  printf 'stepmod-vm: ERROR: %s\n' "$*" >&2
  exit 1
}

# The kernel ABI name (e.g. 6.1.0-56-amd64) of Debian's current linux-image-amd64, or
# $STEPMOD_VM_KVER when set. Needs the apt package lists.
vm_kernel_abi() {
  if [[ -n "${STEPMOD_VM_KVER:-}" ]]; then
    printf '%s\n' "$STEPMOD_VM_KVER"
    return
  fi
  local dep
  dep=$(apt-cache depends linux-image-amd64 2>/dev/null |
    sed -n 's/^ *Depends: linux-image-\([0-9][^ ]*-amd64\)$/\1/p' | head -n1)
  [[ -n "$dep" ]] || vm_die "cannot tell the kernel version: 'apt-cache depends linux-image-amd64' names no linux-image-*-amd64 (run apt-get update?)"
  printf '%s\n' "$dep"
}

# Installed version of a Debian package, empty if not installed.
vm_pkg_version() {
  dpkg-query -W -f='${db:Status-Status} ${Version}\n' "$1" 2>/dev/null | sed -n 's/^installed //p'
}

# Cache directory of one kernel ABI: module, vmlinux, base initramfs.
vm_cache_dir() {
  printf '%s/%s\n' "${STEPMOD_VM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/stepmod-vm}" "$1"
}
