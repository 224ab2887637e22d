#!/usr/bin/env bash
# The package's documentation without building the package (ctest package.docs, no root): the
# build tree installed into a temporary DESTDIR (the tree cpack packs), then docs/board.md's file
# list (board_files.sh) and every documentation reference (doc_refs.sh) checked against it.
#   docs_check.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
here=$(dirname "$0")
tmp=$(mktemp -d /tmp/stepmod-docs.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
DESTDIR="$tmp/root" cmake --install "$build" --prefix /usr >"$tmp/install.log" 2>&1 ||
  { cat "$tmp/install.log"; echo "FAIL: cmake --install" >&2; exit 1; }
(cd "$tmp/root" && find . ! -type d | sed 's/^\.//' | sort) >"$tmp/files"
"$here/board_files.sh" "$src/docs/board.md" "$tmp/files"
"$here/doc_refs.sh" "$tmp/root"
