#!/usr/bin/env bash
# The trace tools of docs/traces.md on VCDs made here with known contents (1 ns timescale and a
# long idle lead-in, as stepmodd writes them):
#   sigrok   the documented sigrok-cli import options (vcd:downsample=1000:compress=1000) give
#            every step pulse, the idle lead-in compressed, and the timing decoder's intervals
#   plot-axis a trapezoid move (Vs 1000, Vp 10000, 10 steps/ms/s, 20000 steps): its position,
#            speed and phases from --data, the ideal profile's figures, a PNG
#   plot-path on a one-axis trace: exit 2 and what it needs, not gnuplot's "all points undefined!"
#   trace_tools_test.sh SOURCE_DIR sigrok|plot-axis|plot-path
# Exit 77 (skipped, with the missing tool named) without sigrok-cli or gnuplot, except in CI
# (CI=true), where scripts/install-deps has installed them and a missing one fails.
set -euo pipefail
src=$1
what=$2
tmp=$(mktemp -d /tmp/stepmod-trace.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
need() {
  command -v "$1" >/dev/null && return 0
  if [ "${CI:-}" = true ] || [ "${CI:-}" = 1 ]; then fail "$1 missing (apt-get install $2)"; fi
  echo "SKIP: $1 missing (apt-get install $2, or scripts/install-deps)"; exit 77
}

# header NAME...: a stepmodd-like VCD header declaring axisN wires ! " # $ ... in order.
header() {
  echo '$timescale 1 ns $end'
  echo '$scope module stepmod $end'
  local ids='!"#$%&' i=0
  for w in "$@"; do echo "\$var wire 1 ${ids:i:1} $w \$end"; i=$((i + 1)); done
  echo '$upscope $end'
  echo '$enddefinitions $end'
  echo '#0'
  echo '$dumpvars'
  i=0
  for _ in "$@"; do echo "0${ids:i:1}"; i=$((i + 1)); done
  echo '$end'
}

# steps VS VP A_STEPS_PER_S2 D N START_NS: the step times (ns) of the manual's trapezoid, one a line.
steps() {
  awk -v vs="$1" -v vp="$2" -v a="$3" -v d="$4" -v n="$5" -v t0="$6" 'BEGIN {
    up = (vp * vp - vs * vs) / (2 * a); dn = (vp * vp - vs * vs) / (2 * d)
    ta = (vp - vs) / a; tc = (n - up - dn) / vp; te = ta + tc + (vp - vs) / d
    for (k = 0; k < n; k++) {
      if (k < up) t = (-vs + sqrt(vs * vs + 2 * a * k)) / a
      else if (k < n - dn) t = ta + (k - up) / vp
      else { r = n - k; t = te - (-vs + sqrt(vs * vs + 2 * d * r)) / d }
      printf "%.0f\n", t0 + t * 1e9
    }
  }'
}

pulses() {  # pulses ID < step times: a 2 us pulse at each time
  awk -v id="$1" '{ printf "#%.0f\n1%s\n#%.0f\n0%s\n", $1, id, $1 + 2000, id }'
}

case "$what" in
  sigrok)
    need sigrok-cli sigrok-cli
    # 2000 pulses at 10 kHz after a 4.4 s idle lead-in, then 1 s idle.
    { header axis1.step axis1.dir
      echo '#4399995000'; echo '1"'
      awk 'BEGIN { for (k = 0; k < 2000; k++) printf "%.0f\n", 4.4e9 + k * 1e5 }' | pulses '!'
      echo '#5600000000'; } >"$tmp/t.vcd"
    # The command of docs/traces.md: 1 us resolution, idle stretches cut to 1 ms.
    timeout 120 sigrok-cli -I vcd:downsample=1000:compress=1000 -i "$tmp/t.vcd" -O vcd >"$tmp/out.vcd" ||
      fail "sigrok-cli -I vcd:downsample=1000:compress=1000 did not finish in 120 s"
    grep -q '^\$timescale 1 us \$end' "$tmp/out.vcd" || fail "not resampled to 1 us: $(grep timescale "$tmp/out.vcd")"
    read -r count first < <(awk '/^#/ { for (i = 2; i <= NF; i++) if ($i == "1!") { c++; if (c == 1) f = substr($1, 2) } }
                                   END { print c + 0, f }' "$tmp/out.vcd")
    [ "$count" -eq 2000 ] || fail "sigrok-cli saw $count step pulses, not 2000"
    [ "$first" -le 2000 ] || fail "the idle lead-in was not compressed: first pulse at $first us"
    timeout 120 sigrok-cli -I vcd:downsample=1000:compress=1000 -i "$tmp/t.vcd" \
      -P timing:data=axis1.step -A timing >"$tmp/timing.txt" || fail "sigrok-cli -P timing"
    gaps=$(grep -c 'timing-1: 98.000 μs' "$tmp/timing.txt" || true)
    [ "$gaps" -eq 1999 ] || fail "timing decoder: $gaps gaps of 98 us between the 2000 pulses, not 1999"
    ;;
  plot-axis)
    need gnuplot gnuplot-nox
    { header axis1.step axis1.dir axis1.home
      echo '#999995000'; echo '1"'
      steps 1000 10000 10000 10000 20000 1000000000 | pulses '!'
      echo '#6000000000'; } >"$tmp/t.vcd"
    "$src/scripts/plot-axis" --ideal 1000 10000 10 10 --data "$tmp/d.txt" "$tmp/t.vcd" "$tmp/t.png" axis1 \
      >"$tmp/out.txt" || fail "plot-axis: $(cat "$tmp/out.txt")"
    cat "$tmp/out.txt"
    [ "$(head -c 4 "$tmp/t.png" | tail -c 3)" = PNG ] || fail "no PNG written"
    grep -q 'ideal (the first move of the window): 20000 steps, top speed 10000 steps/s, 0.9000 s accel, 1.0100 s at speed, 0.9000 s decel' \
      "$tmp/out.txt" || fail "the ideal profile's figures"
    # The measured table: end position, top speed, the phases in order and their durations.
    awk 'BEGIN { last = -1 }
      { if ($2 > pos) pos = $2; v = $3 < 0 ? -$3 : $3; if (v > top) top = v
        if ($4 != last) { seq = seq $4; last = $4 }
        if (NR > 1) dur[prev] += $1 - pt; prev = $4; pt = $1 }
      END {
        printf "end %d, top %.0f, phases %s, accel %.3f s, at speed %.3f s, decel %.3f s\n", pos, top, seq, dur[1], dur[2], dur[3]
        ok = pos == 20000 && top > 9900 && top < 10100 && seq == "01230"
        ok = ok && dur[1] > 0.8 && dur[1] < 0.95 && dur[2] > 0.95 && dur[2] < 1.15 && dur[3] > 0.8 && dur[3] < 0.95
        exit ok ? 0 : 1
      }' "$tmp/d.txt" || fail "plot-axis --data does not show the trapezoid"
    "$src/scripts/plot-axis" "$tmp/t.vcd" "$tmp/t.png" axis2 2>"$tmp/err.txt" && fail "axis2 accepted"
    grep -q 'has no wire axis2.step (its wires: axis1.step axis1.dir axis1.home)' "$tmp/err.txt" ||
      fail "plot-axis on a missing axis: $(cat "$tmp/err.txt")"
    ;;
  plot-path)
    need gnuplot gnuplot-nox
    { header axis1.step axis1.dir
      awk 'BEGIN { for (k = 0; k < 100; k++) printf "%.0f\n", 1e9 + k * 1e6 }' | pulses '!'; } >"$tmp/t.vcd"
    rc=0
    "$src/scripts/plot-path" "$tmp/t.vcd" "$tmp/t.png" 2>"$tmp/err.txt" || rc=$?
    cat "$tmp/err.txt"
    [ "$rc" -eq 2 ] || fail "plot-path on a one-axis trace: exit $rc, not 2"
    grep -q 'has no wire axis2.step: a path needs the step and dir wires of two axes' "$tmp/err.txt" ||
      fail "plot-path does not say what it needs"
    grep -q 'scripts/plot-axis' "$tmp/err.txt" || fail "plot-path does not point at plot-axis"
    ! grep -q 'all points undefined' "$tmp/err.txt" || fail "gnuplot's message"
    ;;
  *) fail "unknown part $what" ;;
esac
echo PASS
