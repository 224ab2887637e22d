#!/usr/bin/env bash
# One ctest per VM test case: looks up the case's line in the results file that run.sh wrote
# (the vm.boot fixture) and exits as ctest expects: 0 PASS, 77 SKIP, 1 FAIL or no result.
# Usage: scripts/vm/check-result.sh RESULTS NAME
set -euo pipefail
results=${1:?usage: check-result.sh RESULTS NAME}
name=${2:?usage: check-result.sh RESULTS NAME}
dir=$(dirname "$results")

if [[ ! -f "$results" ]]; then
  echo "no VM results ($results): the vm.boot test did not run (ctest -L vm runs it first)" >&2
  exit 1
fi
line=$(grep -m1 "^STEPMOD-VM-TEST $name " "$results" || true)
if [[ -z "$line" ]]; then
  echo "no result for $name in $results" >&2
  grep '^STEPMOD-VM-HARNESS\|^STEPMOD-VM-SETUP' "$results" >&2 || true
  exit 1
fi
read -r _ _ status detail <<<"$line"
# The case's own output, from the console log.
if [[ -f "$dir/console.log" ]]; then
  tr -d '\r' <"$dir/console.log" | grep -a "^\[$name\] " || true
fi
echo "$name: $status ${detail:-}"
case "$status" in
  PASS) exit 0 ;;
  SKIP) exit 77 ;;
  *) exit 1 ;;
esac
