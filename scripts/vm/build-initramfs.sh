#!/usr/bin/env bash
# Builds the base initramfs of the test VM (cached, keyed on the kernel and busybox versions):
# busybox-static, configfs.ko and whatever it depends on from Debian's modules tree, gpio-sim.ko,
# and /lib/modules/stepmod-vm/load.list (insmod order). run.sh appends a second cpio archive
# with /init, the test cases and programs: the kernel unpacks both, one over the other.
# Usage: scripts/vm/build-initramfs.sh KABI CACHEDIR    (CACHEDIR has gpio-sim.ko)
#        -> CACHEDIR/base.cpio (kept if up to date)
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

kabi=${1:?usage: build-initramfs.sh KABI CACHEDIR}
cache=${2:?usage: build-initramfs.sh KABI CACHEDIR}
simko=$cache/gpio-sim.ko
[[ -f "$simko" ]] || vm_die "$simko missing (scripts/vm/build-gpio-sim.sh builds it)"
busybox=/bin/busybox
[[ -x "$busybox" ]] || vm_die "$busybox missing (apt-get install busybox-static)"
if LC_ALL=C readelf -d "$busybox" 2>/dev/null | grep -q NEEDED; then
  vm_die "$busybox is not statically linked (install busybox-static, not busybox)"
fi

stamp="$kabi $(vm_pkg_version "linux-image-$kabi") busybox $(vm_pkg_version busybox-static) sim $(cat "$simko.stamp") $(sha256sum "${BASH_SOURCE[0]}" | cut -c1-16)"
if [[ -f "$cache/base.cpio" && "$(cat "$cache/base.cpio.stamp" 2>/dev/null)" == "$stamp" ]]; then
  vm_log "base initramfs up to date ($cache/base.cpio)"
  exit 0
fi

root=$(mktemp -d "$cache/base.XXXXXX")
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,sbin,usr/bin,usr/sbin,dev,proc,sys,tmp,run,etc,lib/modules/stepmod-vm}
cp "$busybox" "$root/bin/busybox"

# configfs and its dependencies, in load order, as modprobe would load them.
mods=$root/lib/modules/stepmod-vm
: >"$mods/load.list"
deps=$(modinfo -F depends "$simko" | tr ',' ' ')
for dep in $deps; do
  plan=$(modprobe -S "$kabi" --show-depends "$dep") ||
    vm_die "modprobe -S $kabi --show-depends $dep failed: is linux-image-$kabi installed?"
  while read -r verb path _; do
    [[ "$verb" == insmod ]] || continue
    base=$(basename "$path")
    base=${base%.xz}
    base=${base%.zst}
    grep -qx "$base" "$mods/load.list" && continue
    case "$path" in
      *.ko.xz) xz -dc "$path" >"$mods/$base" ;;
      *.ko.zst) zstd -qdc "$path" >"$mods/$base" ;;
      *) cp "$path" "$mods/$base" ;;
    esac
    echo "$base" >>"$mods/load.list"
  done <<<"$plan"
done
cp "$simko" "$mods/gpio-sim.ko"
echo gpio-sim.ko >>"$mods/load.list"
vm_log "modules: $(tr '\n' ' ' <"$mods/load.list")"

(cd "$root" && find . -mindepth 1 | LC_ALL=C sort | cpio --quiet -o -H newc --owner=0:0) >"$cache/base.cpio.tmp.$$"
mv "$cache/base.cpio.tmp.$$" "$cache/base.cpio"
printf '%s\n' "$stamp" >"$cache/base.cpio.stamp"
vm_log "built $cache/base.cpio ($(du -h "$cache/base.cpio" | cut -f1))"
