#!/usr/bin/env bash
# Every system call stepmodd made (an strace -f log of a run) is allowed by the unit's
# SystemCallFilter= lines (allow lists, then ~deny lists, groups expanded with systemd-analyze):
# a filter that forbids one would make the service fail on a board (EPERM), which the exposure
# score cannot see.
#   syscall_filter.sh UNIT_FILE STRACE_LOG
set -euo pipefail
unit=$1
log=$2

# expand NAME...: the system calls of each name, groups (@name) expanded recursively.
expand() {
  local n
  for n in "$@"; do
    if [[ $n == @* ]]; then
      expand $(systemd-analyze syscall-filter --no-pager "$n" 2>/dev/null |
        awk 'NR > 1 && $1 !~ /^#/ && NF { print $1 }')
    else
      echo "$n"
    fi
  done
}

allowed=$(mktemp) denied=$(mktemp) used=$(mktemp)
trap 'rm -f "$allowed" "$denied" "$used"' EXIT
grep '^SystemCallFilter=' "$unit" | sed 's/^SystemCallFilter=//' | while read -r line; do
  if [[ $line == ~* ]]; then expand ${line#\~} >>"$denied"; else expand $line >>"$allowed"; fi
done
[ -s "$allowed" ] || { echo "FAIL: the unit has no SystemCallFilter allow list" >&2; exit 1; }

# "1234  name(args..." and "1234  <... name resumed>": the names.
sed -nE 's/^[0-9]+ +([a-z0-9_]+)\(.*/\1/p; s/^[0-9]+ +<\.\.\. ([a-z0-9_]+) resumed>.*/\1/p' "$log" |
  sort -u >"$used"
[ -s "$used" ] || { echo "FAIL: no system calls in $log" >&2; exit 1; }
bad=""
while read -r call; do
  if ! grep -qx "$call" "$allowed" || grep -qx "$call" "$denied"; then bad+=" $call"; fi
done <"$used"
echo "system calls of stepmodd: $(wc -l <"$used"), all allowed by the unit's SystemCallFilter${bad:+ but:$bad}"
[ -z "$bad" ] || { echo "FAIL: the unit's SystemCallFilter forbids:$bad" >&2; exit 1; }
