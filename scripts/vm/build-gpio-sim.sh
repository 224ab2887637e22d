#!/usr/bin/env bash
# Builds gpio-sim as an out-of-tree module for Debian's kernel KABI (Debian 12's kernel does not
# enable CONFIG_GPIO_SIM). Three files of linux-source-<major> are compiled into one module
# gpio-sim.ko: drivers/gpio/gpio-sim.c, drivers/gpio/gpiolib.h and kernel/irq/irq_sim.c
# (CONFIG_IRQ_SIM is not set either). 6.1 does not export irq_to_desc(), so irq_sim.c's
# handle_simple_irq(irq_to_desc(irq)) becomes generic_handle_domain_irq(domain, hwirq), and its
# exports go (the functions are used inside this module only).
# Usage: scripts/vm/build-gpio-sim.sh KABI OUTDIR     -> OUTDIR/gpio-sim.ko (kept if up to date)
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

kabi=${1:?usage: build-gpio-sim.sh KABI OUTDIR}
out=${2:?usage: build-gpio-sim.sh KABI OUTDIR}
major=${kabi%%.0-*}
src_tar=/usr/src/linux-source-$major.tar.xz
kdir=/lib/modules/$kabi/build
[[ -f "$src_tar" ]] || vm_die "$src_tar missing (run scripts/vm/install-deps.sh)"
[[ -d "$kdir" ]] || vm_die "$kdir missing (run scripts/vm/install-deps.sh)"

# The module is keyed on the exact package versions and on this script.
vs=$(vm_pkg_version "linux-source-$major")
vh=$(vm_pkg_version "linux-headers-$kabi")
[[ "$vs" == "$vh" ]] || vm_die "linux-source-$major $vs and linux-headers-$kabi $vh differ: the module would not match the kernel"
stamp="$kabi $vs $(sha256sum "${BASH_SOURCE[0]}" | cut -c1-16)"
if [[ -f "$out/gpio-sim.ko" && "$(cat "$out/gpio-sim.ko.stamp" 2>/dev/null)" == "$stamp" ]]; then
  vm_log "gpio-sim.ko up to date ($out)"
  exit 0
fi

mkdir -p "$out"
work=$(mktemp -d "$out/build.XXXXXX")
trap 'rm -rf "$work"' EXIT

vm_log "extracting gpio-sim.c, gpiolib.h, irq_sim.c from $src_tar"
tar -xJf "$src_tar" -C "$work" --occurrence=1 --strip-components=3 \
  "linux-source-$major/drivers/gpio/gpio-sim.c" \
  "linux-source-$major/drivers/gpio/gpiolib.h" ||
  vm_die "could not extract drivers/gpio/{gpio-sim.c,gpiolib.h} from $src_tar"
tar -xJf "$src_tar" -C "$work" --occurrence=1 --strip-components=3 \
  "linux-source-$major/kernel/irq/irq_sim.c" ||
  vm_die "could not extract kernel/irq/irq_sim.c from $src_tar"

# irq_sim.c: dispatch through the (exported) domain helper, drop the exports.
sed -i \
  -e '/^\s*int irqnum;\s*$/d' \
  -e '/^\s*irqnum = irq_find_mapping(work_ctx->domain, offset);\s*$/d' \
  -e 's/^\(\s*\)handle_simple_irq(irq_to_desc(irqnum));/\1generic_handle_domain_irq(work_ctx->domain, offset);/' \
  -e '/^EXPORT_SYMBOL_GPL(.*);\s*$/d' \
  "$work/irq_sim.c"
if grep -q 'irq_to_desc\|irqnum = \|EXPORT_SYMBOL' "$work/irq_sim.c" ||
  ! grep -q 'generic_handle_domain_irq(work_ctx->domain, offset);' "$work/irq_sim.c"; then
  vm_die "irq_sim.c of linux-source-$major $vs does not look as expected; the patch in $0 needs updating"
fi

# gpio-sim-main.c so that the module itself can be called gpio-sim (module name gpio_sim).
mv "$work/gpio-sim.c" "$work/gpio-sim-main.c"
cat >"$work/Kbuild" <<'KBUILD'
obj-m := gpio-sim.o
gpio-sim-y := gpio-sim-main.o irq_sim.o
KBUILD

vm_log "building gpio-sim.ko against $kdir"
if ! make -C "$kdir" M="$work" modules >"$work/build.log" 2>&1; then
  cat "$work/build.log" >&2
  vm_die "building gpio-sim.ko failed (log above)"
fi
if grep -E 'undefined!|ERROR' "$work/build.log" >&2; then
  vm_die "gpio-sim.ko links against symbols the kernel does not export (above)"
fi
modinfo -F vermagic "$work/gpio-sim.ko" | grep -q "^$kabi " ||
  vm_die "built gpio-sim.ko has vermagic '$(modinfo -F vermagic "$work/gpio-sim.ko")', not $kabi"
cp "$work/gpio-sim.ko" "$work/gpio-sim.ko.done"
mv "$work/gpio-sim.ko.done" "$out/gpio-sim.ko"
printf '%s\n' "$stamp" >"$out/gpio-sim.ko.stamp"
vm_log "built $out/gpio-sim.ko"
