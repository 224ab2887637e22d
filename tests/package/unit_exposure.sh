#!/usr/bin/env bash
# The installed unit's hardening: `systemd-analyze security --offline=true` exposure <= 3.0, with
# what stepmodd needs still allowed (gpiochips, a /dev/shm the PLC shares, SCHED_FIFO, memlock,
# the journal and Modbus sockets).
#   unit_exposure.sh UNIT_FILE TMPDIR
set -euo pipefail
unit=$1
tmp=$2
fail() { echo "FAIL: $*" >&2; exit 1; }

# A template is analysed through an instance.
cp "$unit" "$tmp/stepmodd@exposure.service"
systemd-analyze security --offline=true --no-pager "$tmp/stepmodd@exposure.service" >"$tmp/security.txt" 2>&1 ||
  { cat "$tmp/security.txt"; fail "systemd-analyze security failed"; }
exposure=$(sed -n 's/.*Overall exposure level for stepmodd@exposure.service: \([0-9.]*\).*/\1/p' "$tmp/security.txt")
[ -n "$exposure" ] || { cat "$tmp/security.txt"; fail "no exposure level in systemd-analyze's output"; }
echo "systemd-analyze security: exposure $exposure (limit 3.0)"
awk -v e="$exposure" 'BEGIN { exit !(e <= 3.0) }' ||
  { grep '✗' "$tmp/security.txt" || true; fail "exposure $exposure is above 3.0"; }

# What stepmodd needs (a hardening that takes it away would pass the score and break a board).
want() { grep -Eq "^$1" "$unit" || fail "the unit lacks $1"; }
deny() { ! grep -Eq "^$1" "$unit" || fail "the unit has $1"; }
want 'DeviceAllow=char-gpiochip rw$'
want 'LimitRTPRIO=99$'
want 'LimitMEMLOCK=infinity$'
want 'RestrictAddressFamilies=AF_UNIX AF_INET AF_INET6$'
want 'SupplementaryGroups=gpio$'
deny 'PrivateDevices=(yes|true|1)'
deny 'RestrictRealtime=(yes|true|1)'
deny 'PrivateIPC=(yes|true|1)'
deny 'RemoveIPC=(yes|true|1)'
deny 'PrivateNetwork=(yes|true|1)'
deny 'MemoryLimit|MemoryMax'
