#!/usr/bin/env bash
# Every documentation reference resolves where the package installs it (issue 33: the man pages
# and --help pointed to README and commissioning.md, which were not shipped; the installed
# README and interface.md linked to docs that were not either). ROOT is an installed tree
# (dpkg-deb -x, or DESTDIR=ROOT cmake --install):
#   * every relative link of every .md under usr/share/doc/stepmod resolves from its file;
#   * every /usr/share/doc/stepmod/... path named in a man page or a unit's Documentation= exists;
#   * every docs/NAME.md and README that `stepmodd --help`, `stepmodctl --help` and
#     `stepmod-web --help` name exists under usr/share/doc/stepmod (programs taken from BIN_DIR,
#     default ROOT/usr/bin; BIN_DIR "-": not checked, for a package whose programs cannot run
#     here, another architecture's or release's: their --help is the source's, which the build
#     tree's package.docs and the repository's docs.links check).
#   doc_refs.sh ROOT [BIN_DIR]
set -euo pipefail
root=$1
bin=${2:-$root/usr/bin}
doc=$root/usr/share/doc/stepmod
programs=(stepmodd stepmodctl stepmod-web)
bad=0
miss() { echo "doc_refs: $*" >&2; bad=1; }
[ -d "$doc" ] || { echo "doc_refs: $doc missing" >&2; exit 1; }

# Markdown links: ](target), without web links, anchors and mail.
while IFS= read -r md; do
  dir=$(dirname "$md")
  while IFS= read -r target; do
    target=${target%%#*}
    target=${target%% *}
    [ -n "$target" ] || continue
    case $target in http://*|https://*|mailto:*) continue ;; esac
    [ -e "$dir/$target" ] || miss "${md#"$root"}: link to $target does not resolve"
  done < <(grep -o '](\([^)]*\))' "$md" | sed 's/^](//; s/)$//')
done < <(find "$doc" -name '*.md')

# Absolute paths of the documentation in man pages (groff's \- is a -) and units.
refs=$( { for m in "$root"/usr/share/man/man*/*.gz; do zcat "$m"; done
          cat "$root"/usr/lib/systemd/system/*.service 2>/dev/null || true; } |
        sed 's/\\-/-/g' | grep -o '/usr/share/doc/stepmod[A-Za-z0-9_./-]*' | sed 's/[.]$//' | sort -u)
for r in $refs; do
  [ -e "$root$r" ] || miss "a man page or unit names $r, which the package does not ship"
done

# What the programs' --help points to.
[ "$bin" != - ] || programs=()
for p in "${programs[@]}"; do
  [ -x "$bin/$p" ] || { miss "$bin/$p missing"; continue; }
  help=$("$bin/$p" --help 2>&1 || true)
  for d in $(grep -o 'docs/[A-Za-z0-9_-]*\.md' <<<"$help" | sort -u); do
    [ -e "$doc/$d" ] || miss "$p --help names $d, not in /usr/share/doc/stepmod"
  done
  if grep -qw README <<<"$help" && [ ! -e "$doc/README.md" ]; then
    miss "$p --help names README, not in /usr/share/doc/stepmod"
  fi
done
what="every link and man page path"
[ "${#programs[@]}" = 0 ] || what="every link, man page path and --help reference"
[ $bad = 0 ] && echo "doc_refs: $what resolves"
exit $bad
