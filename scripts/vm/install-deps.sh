#!/usr/bin/env bash
# Installs the Debian packages the VM tests need, the kernel image, headers and source all of
# ONE version (the one linux-image-amd64 points at), and checks that they match.
# Usage: scripts/vm/install-deps.sh        (prints the kernel ABI name, e.g. 6.1.0-56-amd64)
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

export DEBIAN_FRONTEND=noninteractive
# The VM boots the kernel directly; no initramfs-tools image is needed for the host's /boot.
export INITRD=No

apt_get() {
  if [[ $(id -u) -ne 0 ]]; then
    vm_die "need root to run 'apt-get $*' (or install the packages by hand: see scripts/vm/README.md)"
  fi
  apt-get -q -o Dpkg::Use-Pty=0 "$@" >&2
}

# Package lists are needed both for apt-cache and for apt-get install.
if ! apt-cache show linux-image-amd64 >/dev/null 2>&1; then
  vm_log "apt package lists missing: apt-get update"
  apt_get update
fi

kabi=$(vm_kernel_abi)
want=$(apt-cache policy "linux-image-$kabi" | sed -n 's/^ *Candidate: //p')
[[ -n "$want" && "$want" != "(none)" ]] || vm_die "no candidate version for linux-image-$kabi"
major=${kabi%%.0-*} # 6.1.0-56-amd64 -> 6.1

need=()
for p in qemu-system-x86 busybox-static xz-utils cpio kmod build-essential libgpiod-dev pkg-config; do
  [[ -n "$(vm_pkg_version "$p")" ]] || need+=("$p")
done
for p in "linux-image-$kabi" "linux-headers-$kabi" "linux-source-$major"; do
  [[ "$(vm_pkg_version "$p")" == "$want" ]] || need+=("$p=$want")
done

if ((${#need[@]})); then
  vm_log "installing: ${need[*]}"
  if ! apt_get install -y --no-install-recommends "${need[@]}"; then
    vm_log "apt-get install failed; refreshing the package lists and trying once more"
    apt_get update
    apt_get install -y --no-install-recommends "${need[@]}" ||
      vm_die "apt-get install ${need[*]} failed (is linux-source-$major=$want in the archive?)"
  fi
fi

# Image, headers and source must be the very same version: the module is built against the
# headers from the source and loaded into the image.
vi=$(vm_pkg_version "linux-image-$kabi")
vh=$(vm_pkg_version "linux-headers-$kabi")
vs=$(vm_pkg_version "linux-source-$major")
if ! [[ "$vi" == "$vh" && "$vi" == "$vs" ]]; then
  vm_die "kernel packages do not match: linux-image-$kabi $vi, linux-headers-$kabi $vh, linux-source-$major $vs (all must be one version)"
fi
[[ -f /boot/vmlinuz-$kabi ]] || vm_die "/boot/vmlinuz-$kabi missing although linux-image-$kabi $vi is installed"
[[ -d /lib/modules/$kabi/build ]] || vm_die "/lib/modules/$kabi/build missing although linux-headers-$kabi $vh is installed"
[[ -f /usr/src/linux-source-$major.tar.xz ]] || vm_die "/usr/src/linux-source-$major.tar.xz missing although linux-source-$major $vs is installed"
vm_log "kernel $kabi: image, headers and source all $vi"
printf '%s\n' "$kabi"
