#!/usr/bin/env bash
# Extracts the uncompressed ELF kernel (vmlinux) from Debian's /boot/vmlinuz-KABI: qemu boots it
# directly through its PVH entry point (CONFIG_PVH=y), which is much faster under TCG than
# booting the bzImage. Debian compresses the kernel with xz: find the xz magic, xz -dc.
# Usage: scripts/vm/extract-vmlinux.sh KABI OUTDIR    -> OUTDIR/vmlinux (kept if up to date)
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

kabi=${1:?usage: extract-vmlinux.sh KABI OUTDIR}
out=${2:?usage: extract-vmlinux.sh KABI OUTDIR}
vmlinuz=/boot/vmlinuz-$kabi
[[ -f "$vmlinuz" ]] || vm_die "$vmlinuz missing (run scripts/vm/install-deps.sh)"

stamp="$kabi $(vm_pkg_version "linux-image-$kabi")"
if [[ -f "$out/vmlinux" && "$(cat "$out/vmlinux.stamp" 2>/dev/null)" == "$stamp" ]]; then
  vm_log "vmlinux up to date ($out)"
  exit 0
fi
mkdir -p "$out"
tmp="$out/vmlinux.tmp.$$"
trap 'rm -f "$tmp"' EXIT

is_elf() { [[ "$(head -c 4 "$1" | od -An -c | tr -d ' \n')" == '177ELF' ]]; }

vm_log "extracting vmlinux from $vmlinuz"
found=
for off in $(LC_ALL=C grep -obUaP '\xFD7zXZ\x00' "$vmlinuz" | cut -d: -f1); do
  # (not a pipe: tail gets SIGPIPE when xz stops after the first stream, and pipefail is on)
  if xz -dc --single-stream < <(tail -c +$((off + 1)) "$vmlinuz") >"$tmp" 2>/dev/null && is_elf "$tmp"; then
    found=$off
    break
  fi
done
[[ -n "$found" ]] || vm_die "no xz-compressed ELF kernel found in $vmlinuz (is CONFIG_KERNEL_XZ set?)"
grep -q '^CONFIG_PVH=y' "/boot/config-$kabi" 2>/dev/null ||
  vm_die "/boot/config-$kabi does not have CONFIG_PVH=y: qemu cannot boot vmlinux directly"
mv "$tmp" "$out/vmlinux"
printf '%s\n' "$stamp" >"$out/vmlinux.stamp"
vm_log "extracted $out/vmlinux ($(du -h "$out/vmlinux" | cut -f1))"
