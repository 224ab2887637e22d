#!/usr/bin/env bash
# Boots the stepmod test VM and runs the test cases in it: Debian's kernel under qemu (TCG), a
# gpio-sim chip laid out like a real board, the cases and programs given here. Installs its
# Debian packages (as root), builds and caches gpio-sim.ko, vmlinux and the base initramfs.
#
# Usage: scripts/vm/run.sh [options]
#   --cases DIR      test cases: every executable file in DIR (repeatable; default tests/vm/cases)
#   --bin FILE       a program to put in the VM's PATH (/vm/bin; repeatable). Dynamically linked
#                    programs get their shared libraries copied too; static ones need nothing.
#                    Without any --bin, tests/vm/gpiod_check.c is built and used.
#   --board FILE     a stepmod config whose [[axis]] lines make up the gpio-sim chip (repeatable;
#                    default tests/vm/board*.toml; the first one's [gpio] chip is checked)
#   --sysroot DIR    the --bin programs are files inside DIR, a Debian root (e.g. the Debian 13
#                    one of scripts/test-in-root --vm), and run with DIR's shared libraries, which
#                    are resolved in DIR (chroot DIR ldd) and copied from there: the VM boots this
#                    machine's kernel with that root's userland
#   --select REGEX   only the cases whose name matches REGEX (grep -E), e.g. '^(daemon|module)_'
#   --out DIR        where results.txt, console.log and the initramfs go (default build-vm/vm)
#   --timeout SECS   the whole VM run (default 300)
#   --case-timeout SECS   one case (default 60)
#   --fixture        exit 0 once every case has reported, even if some failed (for the ctest
#                    fixture; the per-case ctests report the failures)
# Exit status: 0 all cases passed (or skipped); 1 a case failed, or the VM did not boot or did
# not finish; 2 bad usage; 77 skipped (see below).
#
# Skipping: STEPMOD_VM=0 skips on purpose. Outside CI, a non-root user without the packages
# skips with a message. In CI (CI=true) nothing else skips: a VM that cannot run fails.
#
# results.txt: the VM's result lines (protocol in scripts/vm/guest/init):
#   STEPMOD-VM-TEST <name> PASS|FAIL|SKIP <detail>
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

cases_dirs=()
bins=()
boards=()
sysroot=
select=
out=$VM_REPO_DIR/build-vm/vm
timeout_s=300
case_timeout=60
fixture=0
while (($#)); do
  case "$1" in
    --cases) cases_dirs+=("$(realpath "${2:?}")") && shift ;;
    --bin) bins+=("$(realpath "${2:?}")") && shift ;;
    --board) boards+=("$(realpath "${2:?}")") && shift ;;
    --sysroot) sysroot=$(realpath "${2:?}") && shift ;;
    --select) select=${2:?} && shift ;;
    --out) out=${2:?} && shift ;;
    --timeout) timeout_s=${2:?} && shift ;;
    --case-timeout) case_timeout=${2:?} && shift ;;
    --fixture) fixture=1 ;;
    -h | --help)
      sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
      exit 0
      ;;
    *)
      echo "run.sh: unknown argument '$1' (see --help)" >&2
      exit 2
      ;;
  esac
  shift
done
((${#cases_dirs[@]})) || cases_dirs=("$VM_REPO_DIR/tests/vm/cases")
if ((${#boards[@]} == 0)); then
  boards=("$VM_REPO_DIR/tests/vm/board.toml")
  for b in "$VM_REPO_DIR"/tests/vm/board?*.toml; do [[ -f "$b" ]] && boards+=("$b"); done
fi
mkdir -p "$out"
out=$(realpath "$out")
results=$out/results.txt
rm -f "$results" "$out/console.log" "$out/results.raw"

# The cases, by name (file name without extension), in name order.
declare -A case_file=()
for d in "${cases_dirs[@]}"; do
  [[ -d "$d" ]] || vm_die "cases directory $d does not exist"
  for f in "$d"/*; do
    b=$(basename "$f")
    [[ -f "$f" && "$b" != README* ]] || continue
    [[ -x "$f" ]] || vm_die "test case $f is not executable (chmod +x it)"
    n=${b%.*}
    [[ "$n" =~ ^[A-Za-z0-9_-]+$ ]] || vm_die "case name '$n' ($f): use letters, digits, _ and -"
    [[ -z "${case_file[$n]:-}" ]] || vm_die "two cases named $n: ${case_file[$n]} and $f"
    [[ -z "$select" ]] || grep -Eq -- "$select" <<<"$n" || continue
    case_file[$n]=$f
  done
done
mapfile -t case_names < <(printf '%s\n' "${!case_file[@]}" | LC_ALL=C sort)
((${#case_names[@]})) || vm_die "no test cases (executable files${select:+ matching $select}) in ${cases_dirs[*]}"
if [[ -n "$sysroot" ]]; then
  [[ -x "$sysroot/usr/bin/ldd" ]] || vm_die "--sysroot $sysroot: not a Debian root (no usr/bin/ldd)"
  [[ $(id -u) -eq 0 ]] || vm_die "--sysroot needs root (chroot to resolve the programs' libraries)"
fi

skip_all() {
  vm_log "SKIPPED: $*"
  for n in "${case_names[@]}"; do echo "STEPMOD-VM-TEST $n SKIP $*"; done >"$results"
  exit 77
}
ci=0
[[ "${CI:-}" == true || "${CI:-}" == 1 ]] && ci=1
case "${STEPMOD_VM:-}" in
  0 | off | no | skip) skip_all "STEPMOD_VM=${STEPMOD_VM} (VM tests turned off)" ;;
esac
if [[ $(id -u) -ne 0 ]] && ! command -v qemu-system-x86_64 >/dev/null; then
  ((ci)) && vm_die "CI: qemu-system-x86_64 is missing and this user cannot install it: the VM tests cannot run"
  skip_all "qemu-system-x86_64 missing and not root to install it (scripts/vm/install-deps.sh as root)"
fi

# The VM's RAM: the initramfs (base, programs, their libraries) is unpacked into it.
vm_ram_mb=256
t_start=$(date +%s.%N)
elapsed() { awk -v a="$t_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }

# 1. Packages, kernel version, cached artefacts.
if [[ $(id -u) -eq 0 ]]; then
  kabi=$("$VM_SCRIPTS_DIR/install-deps.sh")
else
  kabi=$(vm_kernel_abi)
  vm_log "not root: using the installed packages for $kabi as they are"
fi
cache=$(vm_cache_dir "$kabi")
mkdir -p "$cache"
"$VM_SCRIPTS_DIR/build-gpio-sim.sh" "$kabi" "$cache"
"$VM_SCRIPTS_DIR/extract-vmlinux.sh" "$kabi" "$cache"
"$VM_SCRIPTS_DIR/build-initramfs.sh" "$kabi" "$cache"
vm_log "kernel, module and base initramfs ready after $(elapsed) s ($cache)"

# 2. The test overlay: /init, the board, the cases, the programs and their libraries.
ov=$(mktemp -d "$out/overlay.XXXXXX")
trap 'rm -rf "$ov"' EXIT
mkdir -p "$ov/vm/cases" "$ov/vm/bin"
install -m 755 "$VM_SCRIPTS_DIR/guest/init" "$ov/init"
install -m 755 "$VM_SCRIPTS_DIR/guest/board-setup.sh" "$ov/vm/board-setup.sh"
install -m 644 "$VM_SCRIPTS_DIR/guest/lib.sh" "$ov/vm/lib.sh"
i=0
for b in "${boards[@]}"; do
  [[ -f "$b" ]] || vm_die "board config $b does not exist"
  # board.toml first: board-setup.sh takes [gpio] chip from the first one.
  install -m 644 "$b" "$ov/vm/board$(printf '%02d' $i)-$(basename "$b")"
  i=$((i + 1))
done
for n in "${case_names[@]}"; do
  f=${case_file[$n]}
  install -m 755 "$f" "$ov/vm/cases/$(basename "$f")"
  basename "$f" >>"$ov/vm/cases.list"
done
# The shared libraries (and the loader) a dynamic program needs, as paths: this machine's, or with
# --sysroot the root's (resolved inside it: its symbolic links may be absolute).
program_libs() {
  if [[ -z "$sysroot" ]]; then
    ldd "$1" | sed -n 's/.*=> \(\/[^ ]*\) .*/\1/p; s/^\s*\(\/[^ ]*\) (.*/\1/p'
    return
  fi
  local rel=${1#"$sysroot"}
  [[ "$rel" != "$1" ]] || vm_die "--bin $1 is not inside --sysroot $sysroot"
  chroot "$sysroot" ldd "$rel" | sed -n 's/.*=> \(\/[^ ]*\) .*/\1/p; s/^\s*\(\/[^ ]*\) (.*/\1/p'
}
copy_lib() {  # LIB: its path in the VM; copied from this machine or the sysroot
  local lib=$1 src=$1
  if [[ -n "$sysroot" ]]; then
    src=$sysroot$(chroot "$sysroot" readlink -f "$lib") || vm_die "cannot resolve $lib in $sysroot"
  fi
  [[ -f "$src" ]] || return 0
  mkdir -p "$ov$(dirname "$lib")"
  cp -L "$src" "$ov$lib"
}
copy_with_libs() {
  local f=$1 lib dest
  dest="$ov/vm/bin/$(basename "$f")"
  # Without its debug information (a RelWithDebInfo stepmodd is ~28 MB): the initramfs is
  # unpacked into the VM's RAM, and one that does not fit fails to unpack. The symbols stay
  # (--strip-debug): a crash's backtrace still names its functions.
  objcopy --strip-debug "$f" "$dest" 2>/dev/null || cp "$f" "$dest"
  chmod 755 "$dest"
  LC_ALL=C readelf -d "$f" 2>/dev/null | grep -q NEEDED || return 0
  # Dynamically linked: bring its shared libraries and the loader, at their paths.
  while read -r lib; do
    [[ -n "$lib" ]] && copy_lib "$lib"
  done < <(program_libs "$f")
}
if ((${#bins[@]} == 0)); then
  # Run by hand without programs: build the harness's own check program (ctest passes --bin).
  gcc -std=c11 -O2 -Wall -Wextra -Werror -static -o "$out/gpiod_check" \
    "$VM_REPO_DIR/tests/vm/gpiod_check.c" -l:libgpiod.a ||
    vm_die "building tests/vm/gpiod_check.c failed (libgpiod-dev installed?)"
  bins=("$out/gpiod_check")
fi
for b in "${bins[@]}"; do
  [[ -f "$b" && -x "$b" ]] || vm_die "program $b does not exist or is not executable"
  copy_with_libs "$b"
done
printf 'CASE_TIMEOUT=%s\n' "$case_timeout" >"$ov/vm/settings"
if [[ -n "$sysroot" ]]; then
  userland="Debian $(cat "$sysroot/etc/debian_version" 2>/dev/null || echo '?')"
  printf 'USERLAND="%s"\n' "$userland" >>"$ov/vm/settings"
  vm_log "programs with the libraries of $sysroot ($userland), kernel $kabi"
fi
(cd "$ov" && find . -mindepth 1 | LC_ALL=C sort | cpio --quiet -o -H newc --owner=0:0) >"$out/overlay.cpio"
cat "$cache/base.cpio" "$out/overlay.cpio" >"$out/initramfs.cpio"
rm -f "$out/overlay.cpio"
# The kernel unpacks the initramfs beside its loaded image in the VM's RAM (-m below): at 70 MB of
# 256 it failed ("Initramfs unpacking failed: write error", then no /vm/board-setup.sh).
initramfs_mb=$(du -m "$out/initramfs.cpio" | cut -f1)
((initramfs_mb <= vm_ram_mb / 4)) ||
  vm_die "the initramfs is ${initramfs_mb} MB: more than a quarter of the VM's ${vm_ram_mb} MB of RAM, it may not unpack (programs too large?)"
vm_log "initramfs ready after $(elapsed) s: ${#case_names[@]} cases, ${#bins[@]} programs ($(du -h "$out/initramfs.cpio" | cut -f1))"

# 3. Boot. Console on ttyS0 -> console.log, result lines on ttyS1 -> results.raw.
qemu=(qemu-system-x86_64 -accel tcg -M pc -cpu max -m "$vm_ram_mb" -smp 1 -nodefaults -display none
  -no-reboot -monitor none
  -kernel "$cache/vmlinux" -initrd "$out/initramfs.cpio"
  -append "console=ttyS0 quiet loglevel=3 panic=-1 oops=panic"
  -serial "file:$out/console.log" -serial "file:$out/results.raw")
vm_log "booting: ${qemu[*]}"
set +e
timeout --kill-after=10 "$timeout_s" "${qemu[@]}" </dev/null >"$out/qemu.log" 2>&1
qrc=$?
set -e
vm_log "VM exited (status $qrc) after $(elapsed) s"

# 4. Results.
sed -e 's/\r$//' "$out/console.log" 2>/dev/null | sed 's/^/  vm| /' >&2 || true
tr -d '\r' <"$out/results.raw" 2>/dev/null | grep -a '^STEPMOD-VM-' >"$results" || true
problem=
if [[ $qrc -eq 124 || $qrc -eq 137 ]]; then
  problem="the VM did not power off within ${timeout_s}s (see console above)"
elif [[ $qrc -ne 0 ]]; then
  problem="qemu failed (status $qrc): $(tail -n 5 "$out/qemu.log" | tr '\n' ' ')"
elif ! grep -q '^STEPMOD-VM-BEGIN' "$results"; then
  problem="the VM did not start the tests (kernel or /init failed: see console above)"
elif grep -q '^STEPMOD-VM-SETUP FAIL' "$results"; then
  problem="VM setup failed: $(sed -n 's/^STEPMOD-VM-SETUP FAIL //p' "$results" | head -n 1)"
elif ! grep -q '^STEPMOD-VM-END' "$results"; then
  problem="the VM stopped before the end of the tests (see console above)"
fi
missing=()
for n in "${case_names[@]}"; do
  grep -q "^STEPMOD-VM-TEST $n " "$results" || missing+=("$n")
done
if [[ -z "$problem" && ${#missing[@]} -gt 0 ]]; then
  problem="no result from: ${missing[*]}"
fi

grep '^STEPMOD-VM-TEST ' "$results" | sed 's/^STEPMOD-VM-TEST /  /' >&2 || true
if [[ -n "$problem" ]]; then
  echo "STEPMOD-VM-HARNESS FAIL $problem" >>"$results"
  vm_die "$problem (console: $out/console.log, total $(elapsed) s)"
fi
npass=$(grep -c '^STEPMOD-VM-TEST [^ ]* PASS' "$results" || true)
nfail=$(grep -c '^STEPMOD-VM-TEST [^ ]* FAIL' "$results" || true)
nskip=$(grep -c '^STEPMOD-VM-TEST [^ ]* SKIP' "$results" || true)
vm_log "$npass passed, $nfail failed, $nskip skipped; total $(elapsed) s (results: $results)"
if ((nfail && !fixture)); then
  exit 1
fi
exit 0
