#!/usr/bin/env bash
# lintian on every .deb in DIR: no error and no warning (informational tags are printed, not
# counted). Skipped with a message when lintian is missing, except in CI (CI=true). Then every
# documentation reference of each package resolves among the files it installs (doc_refs.sh on
# its contents; the programs' --help is checked where they run, in the package test).
#   package_lint.sh DIR
set -euo pipefail
dir=$1
here=$(dirname "$0")
status=0
for deb in "$dir"/*.deb; do
  [ -f "$deb" ] || { echo "FAIL: no .deb in $dir" >&2; exit 1; }
  contents=$(mktemp -d /tmp/stepmod-lint.XXXXXX)
  dpkg-deb -x "$deb" "$contents"
  echo "documentation references of $(basename "$deb"):"
  "$here/doc_refs.sh" "$contents" - | sed 's/^/  /' || status=1
  rm -rf "$contents"
done
if ! command -v lintian >/dev/null; then
  if [ "${CI:-}" = true ] || [ "${CI:-}" = 1 ]; then
    echo "FAIL: lintian missing (scripts/install-deps installs it)" >&2; exit 1
  fi
  echo "lintian: SKIPPED, not installed (apt-get install lintian, or scripts/install-deps)"
  exit "$status"
fi
for deb in "$dir"/*.deb; do
  [ -f "$deb" ] || { echo "FAIL: no .deb in $dir" >&2; exit 1; }
  # --no-cfg: the machine's lintianrc must not change the verdict; running as root is fine here.
  out=$(lintian --no-cfg --display-info "$deb" 2>&1 | grep -v 'running with root privileges' || true)
  echo "lintian $(basename "$deb"):"
  [ -z "$out" ] || echo "$out" | sed 's/^/  /'
  if echo "$out" | grep -q '^[EW]: '; then
    echo "FAIL: lintian reports errors or warnings for $(basename "$deb")" >&2
    status=1
  fi
done
exit "$status"
