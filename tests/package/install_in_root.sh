#!/bin/bash
# Run as root inside a fresh `debootstrap --variant=minbase` root of the package's Debian release
# (/proc and /dev mounted, the .deb copied in): installs the .deb with apt, which must resolve its
# Depends from the archive alone (libgpiod3 on Debian 13, libgpiod2 on 12), runs a move on the
# simulated machine with the installed example config and stepmodctl, then purges.
#   install_in_root.sh /path/in/root/stepmod_<version>_<arch>.deb     -> "PKGTEST_PASS", exit 0
set -euo pipefail
deb=$1
apt-get update -q >/dev/null
DEBIAN_FRONTEND=noninteractive apt-get install -y -q "$deb" >/tmp/install.log 2>&1 || { cat /tmp/install.log; exit 1; }
dpkg-query -W -f='${Depends}\n' stepmod
dpkg -l libgpiod3 | tail -1
name=pkg13
# As tests/package/package_test.sh: the late-edge guard relaxed for a shared test machine (what is
# under test is the package, not this machine's timer latency).
sed -e "s/^name = .*/name = \"$name\"/" -e "s/^late_limit_us = .*/late_limit_us = 1000000/" \
  /etc/stepmod/3601-sim.toml > /tmp/3601.toml
stepmodd --config /tmp/3601.toml > /tmp/daemon.log 2>&1 &
pid=$!
for _ in $(seq 100); do [ -e /dev/shm/stepmod.$name ] && break; sleep 0.1; done
ctl="stepmodctl -n $name"
$ctl configure --home --cw-limit --ccw-limit --estop >/dev/null
$ctl move rel 1500 -s 2000 -a 10 -d 10 >/dev/null
$ctl wait-idle --max 20 >/dev/null
$ctl status | grep -Eq '^  position = 1500$' || { $ctl status; cat /tmp/daemon.log; exit 1; }
kill -TERM $pid; wait $pid || { cat /tmp/daemon.log; exit 1; }
DEBIAN_FRONTEND=noninteractive apt-get purge -y -q stepmod >/dev/null
! dpkg-query -W -f='${Status}' stepmod 2>/dev/null | grep -q installed
[ ! -e /etc/stepmod ]
echo PKGTEST_PASS
