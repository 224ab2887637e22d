#!/usr/bin/env bash
# The Debian package end to end (ctest label "package"): builds it with cpack from this build
# tree, installs it with dpkg -i, checks what a board gets (user, groups, udev rule, unit, man
# pages, conffiles, copyright, changelog), checks docs/board.md's list of installed files against
# the package (board_files.sh) and that every documentation reference resolves where it is
# installed (doc_refs.sh), runs lintian (no error, no warning), checks the unit's
# hardening (exposure <= 3.0 with what stepmodd needs kept), runs the installed stepmodd as the
# stepmod user without privileges on an example config and drives a move with the installed
# stepmodctl (under strace: every system call allowed by the unit's filter), verifies the unit
# with systemd-analyze, then removes and purges the package and checks that nothing is left.
#   package_test.sh BUILD_DIR
# Exit 77 (skipped) unless root with dpkg, or when stepmod is already installed (not ours).
set -euo pipefail
build=$1

if [ "$(id -u)" -ne 0 ] || ! command -v dpkg >/dev/null; then
  echo "SKIP: needs root and dpkg"; exit 77
fi
if dpkg-query -W -f='${Status}' stepmod 2>/dev/null | grep -q installed; then
  echo "SKIP: a stepmod package is installed on this machine; not touching it"; exit 77
fi

# The tools this test runs (scripts/install-deps installs them). One missing: skipped with its
# name, except in CI (CI=true), where every test must run and a missing tool fails.
missing=()
for tool in cpack dpkg-deb dpkg-shlibdeps file groff systemd-analyze man setpriv getent zcat adduser python3; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
if [ "${#missing[@]}" -gt 0 ]; then
  if [ "${CI:-}" = true ] || [ "${CI:-}" = 1 ]; then
    echo "FAIL: missing ${missing[*]} (CI=true; scripts/install-deps installs them)" >&2; exit 1
  fi
  echo "SKIP: missing ${missing[*]} (scripts/install-deps installs them)"; exit 77
fi

tmp=$(mktemp -d /tmp/stepmod-pkg.XXXXXX)
chmod 755 "$tmp"
daemon_pid=""
cleanup() {
  [ -n "$daemon_pid" ] && kill -9 "$daemon_pid" 2>/dev/null || true
  if dpkg-query -W -f='${Status}' stepmod 2>/dev/null | grep -q installed; then
    dpkg -P stepmod >/dev/null 2>&1 || true
  fi
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
step() { echo "==> $*"; }

step "cpack -G DEB"
(cd "$build" && cpack -G DEB -B "$tmp/out" >"$tmp/cpack.log" 2>&1) || { cat "$tmp/cpack.log"; fail "cpack"; }
arch=$(dpkg --print-architecture)
deb=$(ls "$tmp"/out/stepmod_*_"$arch".deb)
echo "$deb"
dpkg-deb -c "$deb" | awk '{print $6}' >"$tmp/files"
for f in ./usr/bin/stepmodd ./usr/bin/stepmodctl ./usr/include/stepmod/stepmod_image.h \
         ./usr/lib/systemd/system/stepmodd@.service ./usr/lib/udev/rules.d/60-stepmod-gpio.rules \
         ./etc/stepmod/3601-sim.toml ./etc/stepmod/3602-sim.toml ./etc/stepmod/3202-sim.toml \
         ./usr/share/doc/stepmod/examples/3602-sim.toml ./etc/security/limits.d/stepmod.conf \
         ./usr/share/man/man8/stepmodd.8.gz ./usr/share/man/man1/stepmodctl.1.gz; do
  grep -qx "$f" "$tmp/files" || fail "$f not in the package"
done
dpkg-deb -f "$deb" Depends | grep -q adduser || fail "Depends lacks adduser"
dpkg-deb -e "$deb" "$tmp/control"
for f in 3601-sim 3601-board 3602-sim 3202-sim; do
  grep -qx "/etc/stepmod/$f.toml" "$tmp/control/conffiles" || fail "example $f is not a conffile"
done

step "copyright, changelog, lintian, the unit's exposure"
for f in ./usr/share/doc/stepmod/copyright ./usr/share/doc/stepmod/changelog.gz \
         ./usr/share/man/man5/stepmod.toml.5.gz ./usr/share/doc/stepmod/docs/interface.md; do
  grep -qx "$f" "$tmp/files" || fail "$f not in the package"
done
dpkg-deb -x "$deb" "$tmp/root"
# The changelog names the upstream version; the package's adds the Debian release (+deb12).
version=$(dpkg-deb -f "$deb" Version)
version=${version%+deb[0-9]*}
zcat "$tmp/root/usr/share/doc/stepmod/changelog.gz" | head -n 1 | grep -q "^stepmod ($version) " ||
  fail "the changelog's newest entry is not $version: $(zcat "$tmp/root/usr/share/doc/stepmod/changelog.gz" | head -n 1)"
head -n 1 "$tmp/root/usr/share/doc/stepmod/copyright" |
  grep -qx 'Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' ||
  fail "copyright is not machine-readable (DEP-5)"
# docs/board.md's list of installed files, and every documentation reference where installed.
dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print substr($6, 2)}' | sort >"$tmp/plain-files"
"$(dirname "$0")/board_files.sh" "$(dirname "$0")/../../docs/board.md" "$tmp/plain-files"
"$(dirname "$0")/doc_refs.sh" "$tmp/root"
"$(dirname "$0")/package_lint.sh" "$tmp/out"
"$(dirname "$0")/unit_exposure.sh" "$tmp/root/usr/lib/systemd/system/stepmodd@.service" "$tmp"

step "dpkg -i"
had_gpio=0
getent group gpio >/dev/null && had_gpio=1
dpkg -i "$deb"
getent passwd stepmod >/dev/null || fail "no stepmod user"
[ "$(getent passwd stepmod | cut -d: -f7)" != /bin/bash ] || fail "stepmod user has a login shell"
id -nG stepmod | tr ' ' '\n' | grep -qx gpio || fail "stepmod is not in the gpio group"
id -nG stepmod | tr ' ' '\n' | grep -qx stepmod || fail "stepmod has no stepmod group"
grep -q 'GROUP="gpio"' /usr/lib/udev/rules.d/60-stepmod-gpio.rules || fail "udev rule"
for page in /usr/share/man/man8/stepmodd.8.gz /usr/share/man/man1/stepmodctl.1.gz \
            /usr/share/man/man5/stepmod.toml.5.gz; do
  zcat "$page" | groff -man -Tutf8 -ww -z 2>"$tmp/groff.log" || fail "$page does not render"
  [ ! -s "$tmp/groff.log" ] || { cat "$tmp/groff.log"; fail "$page: groff warnings"; }
done
/usr/bin/stepmodd --help | grep -q -- --config || fail "stepmodd --help"

step "systemd-analyze verify"
# A template is verified through an instance; the example config exists for this one.
cp /usr/lib/systemd/system/stepmodd@.service "$tmp/stepmodd@3601-sim.service"
systemd-analyze verify "$tmp/stepmodd@3601-sim.service" 2>&1 | tee "$tmp/verify.log"
if grep -v -e 'Failed to open /dev/tty' -e '^$' "$tmp/verify.log" | grep -q .; then
  fail "systemd-analyze verify reported problems"
fi
grep -q '^WatchdogSec=' /usr/lib/systemd/system/stepmodd@.service || fail "no WatchdogSec"
grep -q '^Type=notify' /usr/lib/systemd/system/stepmodd@.service || fail "not Type=notify"

step "the installed stepmodd, as the stepmod user, on the example config"
name="pkgtest-$$"
# The installed example as a user starts from, with its own name and the late-edge guard at its
# loosest (pause 1 s, no lag limit in practice) for a shared test machine: the unprivileged
# daemon has no SCHED_FIFO here, and what is under test is the package, not this machine's timer
# latency (the guard has its own tests).
sed -e "s/^name = .*/name = \"$name\"/" -e "s/^\[rt\]$/[rt]\nlate_limit_us = 1000000/" \
  -e "s/^lag_limit_steps = .*/lag_limit_steps = 1000000/" \
  /etc/stepmod/3601-sim.toml >"$tmp/3601-sim.toml"
grep -q '^late_limit_us = 1000000' "$tmp/3601-sim.toml" || fail "example config has no late_limit_us"
# With the Modbus server on (a free port), so that its sockets run under the unit's filters too.
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
printf '\n[modbus]\nenabled = true\nlisten = "127.0.0.1:%s"\n' "$port" >>"$tmp/3601-sim.toml"
chmod 644 "$tmp/3601-sim.toml"
# As the unit runs it: no new privileges, no capabilities. Under strace when it is there, for the
# unit's system call filter (syscall_filter.sh below).
tracer=()
if command -v strace >/dev/null; then
  install -m 666 /dev/null "$tmp/strace.log"
  tracer=(strace -f -qq -o "$tmp/strace.log")
fi
setpriv --reuid stepmod --regid stepmod --init-groups --no-new-privs --bounding-set -all \
  "${tracer[@]}" /usr/bin/stepmodd --config "$tmp/3601-sim.toml" >"$tmp/daemon.log" 2>&1 &
daemon_pid=$!
for _ in $(seq 100); do
  [ -e "/dev/shm/stepmod.$name" ] && break
  sleep 0.1
done
[ -e "/dev/shm/stepmod.$name" ] || { cat "$tmp/daemon.log"; fail "no image"; }
[ "$(stat -c '%U:%G %a' "/dev/shm/stepmod.$name")" = "stepmod:stepmod 660" ] ||
  fail "image owner/mode: $(stat -c '%U:%G %a' "/dev/shm/stepmod.$name")"
ctl="/usr/bin/stepmodctl -n $name"
$ctl configure --home --cw-limit --ccw-limit --estop >/dev/null
$ctl move rel 1500 -s 10000 -a 10 -d 10 >/dev/null
$ctl wait-idle --max 10 >/dev/null
$ctl status | grep -Eq '^  position = 1500$' || { $ctl status; fail "position after the move"; }
# Input register 1000: the module type, over Modbus/TCP.
if command -v mbpoll >/dev/null; then
  mbpoll -m tcp -p "$port" -0 -1 -t 3 -r 1000 -c 1 127.0.0.1 | grep -q '^\[1000\]:[[:space:]]*3601' ||
    fail "Modbus: input register 1000 is not 3601"
fi
# Under strace the daemon is strace's child: the signal goes to stepmodd itself.
stepmodd_pid=$daemon_pid
[ "${#tracer[@]}" -eq 0 ] || stepmodd_pid=$(pgrep -P "$daemon_pid")
kill -TERM "$stepmodd_pid"
rc=0
wait "$daemon_pid" || rc=$?
daemon_pid=""
[ "$rc" -eq 0 ] || { cat "$tmp/daemon.log"; fail "stepmodd exit status $rc"; }
if [ "${#tracer[@]}" -gt 0 ]; then
  "$(dirname "$0")/syscall_filter.sh" /usr/lib/systemd/system/stepmodd@.service "$tmp/strace.log"
elif [ "${CI:-}" = true ] || [ "${CI:-}" = 1 ]; then
  fail "strace missing (scripts/install-deps installs it)"
else
  echo "system call filter: SKIPPED, strace not installed (scripts/install-deps installs it)"
fi
[ ! -e "/dev/shm/stepmod.$name" ] || fail "image left behind"

step "dpkg -r, then dpkg -P"
echo "# edited" >>/etc/stepmod/3601-sim.toml
dpkg -r stepmod
[ ! -e /usr/bin/stepmodd ] || fail "stepmodd left after remove"
[ -e /etc/stepmod/3601-sim.toml ] || fail "remove deleted a conffile"
dpkg -P stepmod
[ ! -e /etc/stepmod ] || fail "/etc/stepmod left after purge"
[ ! -e /etc/security/limits.d/stepmod.conf ] || fail "limits left after purge"
[ ! -e /usr/lib/udev/rules.d/60-stepmod-gpio.rules ] || fail "udev rule left after purge"
! getent passwd stepmod >/dev/null || fail "stepmod user left after purge"
! getent group stepmod >/dev/null || fail "stepmod group left after purge"
if [ "$had_gpio" -eq 0 ]; then
  ! getent group gpio >/dev/null || fail "gpio group (created by the package) left after purge"
else
  getent group gpio >/dev/null || fail "purge removed a gpio group it had not created"
fi
[ ! -e /var/lib/stepmod ] || fail "/var/lib/stepmod left after purge"
echo "PASS"
