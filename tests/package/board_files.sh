#!/usr/bin/env bash
# docs/board.md's list of what the package installs (between <!-- package-files --> and
# <!-- /package-files -->) against the package's files (issue 33: the list had gone stale).
# Entries are paths, a directory ending in '/' (everything under it) or a glob ('*'). Every
# packaged file must be under an entry, and every entry must match a packaged file.
#   board_files.sh BOARD_MD FILE_LIST   (FILE_LIST: one path a line, as `dpkg-deb -c` gives
#                                        them without the leading '.'; directories left out)
set -euo pipefail
board=$1
files=$2
mapfile -t entries < <(sed -n '/<!-- package-files -->/,/<!-- \/package-files -->/p' "$board" |
  grep '^/' || true)
[ ${#entries[@]} -gt 0 ] || { echo "board_files: no package-files list in $board" >&2; exit 1; }
matches() {  # ENTRY PATH
  case $1 in
    */) [[ $2 == "$1"* ]] ;;
    *) [[ $2 == $1 ]] ;;  # unquoted: a glob
  esac
}
bad=0
declare -A used=()
while IFS= read -r f; do
  [ -n "$f" ] || continue
  hit=0
  for e in "${entries[@]}"; do
    if matches "$e" "$f"; then hit=1; used[$e]=1; fi
  done
  [ $hit = 1 ] || { echo "board_files: $f is in the package but not in docs/board.md's list" >&2; bad=1; }
done <"$files"
for e in "${entries[@]}"; do
  [ -n "${used[$e]:-}" ] || { echo "board_files: docs/board.md lists $e, which the package does not have" >&2; bad=1; }
done
[ $bad = 0 ] && echo "board_files: docs/board.md's list matches the package (${#entries[@]} entries)"
exit $bad
