#!/bin/bash
# Run as root inside a fresh copy of a `debootstrap --variant=minbase` root of the package's
# Debian release (scripts/install-check puts it there, with /proc and /dev): installs the .deb
# with apt, which must resolve its Depends from that release's archive alone (libgpiod3 on
# Debian 13, libgpiod2 on Debian 12); runs a move on the simulated machine with the installed
# example config and the installed stepmodctl; purges the package and checks nothing is left.
#   install_in_root.sh /path/in/root/stepmod_<version>_<arch>.deb     -> "PKGTEST_PASS", exit 0
set -euo pipefail
deb=$1
fail() { echo "FAIL: $*" >&2; exit 1; }

apt-get update -q >/dev/null
DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "$deb" \
  >/tmp/install.log 2>&1 || { cat /tmp/install.log; fail "apt-get install $deb"; }
depends=$(dpkg-query -W -f='${Depends}' stepmod)
echo "installed $(basename "$deb"); Depends: $depends"
gpiod=$(grep -o 'libgpiod[0-9]*' <<<"$depends" | head -n 1)
[ -n "$gpiod" ] || fail "Depends names no libgpiod"
dpkg-query -W -f='${Package} ${Version}: ${Status}\n' "$gpiod"

# The installed example as a user starts from, with its own name and the late-edge guard at its
# loosest for a shared test machine (what is under test is the package, not this machine's timer
# latency; the guard has its own tests).
name=pkgroot
sed -e "s/^name = .*/name = \"$name\"/" -e "s/^\[rt\]$/[rt]\nlate_limit_us = 1000000/" \
  -e "s/^lag_limit_steps = .*/lag_limit_steps = 1000000/" \
  /etc/stepmod/3601-sim.toml >/tmp/3601.toml
grep -q '^late_limit_us = 1000000' /tmp/3601.toml || fail "the example has no [rt] section"
stepmodd --config /tmp/3601.toml >/tmp/daemon.log 2>&1 &
pid=$!
for _ in $(seq 100); do [ -e "/dev/shm/stepmod.$name" ] && break; sleep 0.1; done
[ -e "/dev/shm/stepmod.$name" ] || { cat /tmp/daemon.log; fail "the installed stepmodd made no image"; }
ctl="stepmodctl -n $name"
$ctl configure --home --cw-limit --ccw-limit --estop >/dev/null
$ctl move rel 1500 -s 10000 -a 10 -d 10 >/dev/null
$ctl wait-idle --max 20 >/dev/null
$ctl status | grep -Eq '^  position = 1500$' || { $ctl status; cat /tmp/daemon.log; fail "position after the move"; }
kill -TERM "$pid"
wait "$pid" || { cat /tmp/daemon.log; fail "stepmodd did not end cleanly on SIGTERM"; }

DEBIAN_FRONTEND=noninteractive apt-get purge -y -q stepmod >/tmp/purge.log 2>&1 ||
  { cat /tmp/purge.log; fail "apt-get purge stepmod"; }
! dpkg-query -W -f='${Status}' stepmod 2>/dev/null | grep -q installed || fail "still installed"
for f in /usr/bin/stepmodd /usr/bin/stepmodctl /etc/stepmod /var/lib/stepmod \
         /etc/security/limits.d/stepmod.conf /usr/lib/udev/rules.d/60-stepmod-gpio.rules; do
  [ ! -e "$f" ] || fail "$f left after purge"
done
! getent passwd stepmod >/dev/null || fail "the stepmod user left after purge"
echo PKGTEST_PASS
