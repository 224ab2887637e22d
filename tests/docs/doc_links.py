#!/usr/bin/env python3
"""Every documentation reference resolves in the repository (issue 33).

What a reader is sent to must exist:
  * every relative Markdown link ](target#anchor) of every tracked .md file: the target file,
    and the anchor among the target's headings (GitHub's slugs) or its <a id/name> tags;
  * every path into the tree (docs/x.md, ../README.md, scripts/package, tests/package/...)
    named in README.md, CHANGELOG.md's links, docs/*.md, the other READMEs, the man pages
    (packaging/man), the web console's pages (web/www) and the string literals of the programs'
    sources (their --help and messages): the file or directory, from the repository's top or
    from the naming file's directory;
  * a section named after such a path ('docs/performance.md "A CPU of its own"'): a heading of
    that file contains it.
The installed package's side (the same references where the package puts them) is
tests/package/doc_refs.sh. Usage: doc_links.py SOURCE_DIR
"""
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()


def tree_files():
    """The tree's files: git's list, or (no git, or a copy without .git: scripts/test-in-root)
    every file but build trees."""
    if shutil.which("git"):
        git = subprocess.run(["git", "-C", str(ROOT), "ls-files"], capture_output=True, text=True)
        if git.returncode == 0 and git.stdout:
            return git.stdout.split()
    return [str(p.relative_to(ROOT)) for p in ROOT.rglob("*")
            if p.is_file() and not p.relative_to(ROOT).parts[0].startswith(("build", ".git"))]


TRACKED = tree_files()
# Paths are recognised by their first part: a top-level entry of the tree (build/ is not one).
TOPS = sorted({p.split("/")[0] for p in TRACKED}, key=len, reverse=True)
PATH = re.compile(r"(?<![\w/.~$-])((?:\.\./)*(?:%s)(?:/[\w.+-]+)*/?)" %
                  "|".join(re.escape(t) for t in TOPS))
# A section named after the path: "Title", \"Title\" (in a C++ literal) or “Title”.
SECTION = re.compile(r'^,?\s*(?:section\s+)?(?:\\?"|“)([^"\\”]+)(?:\\?"|”)')
LINK = re.compile(r"\]\(([^)\s]+)\)")
# Paths that are not this tree's, though they start like one: (file, path prefix) and why.
ELSEWHERE = {
    ("openplc/README.md", "core/"): "OpenPLC_v3's tree",
    ("openplc/README.md", "scripts/change_hardware_layer.sh"): "OpenPLC_v3's tree",
    ("openplc/README.md", "scripts/compile_program.sh"): "OpenPLC_v3's tree",
    ("docs/ARCHITECTURE.md", "docs/Code_Overview.md"): "Klipper's tree",
}
CODE = re.compile(r"^\s*(```|~~~)")
errors = []


def text_lines(path):
    """The file's lines, Markdown code fences included (a command names real paths too)."""
    return path.read_text(encoding="utf-8", errors="replace").splitlines()


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    heading = re.sub(r"`|\*\*|__|\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip())
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def headings(md):
    """(titles, anchors) of a Markdown file: headings outside code fences, <a id/name>."""
    titles, anchors, fenced = [], set(), False
    for line in text_lines(md):
        if CODE.match(line):
            fenced = not fenced
            continue
        m = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m and not fenced:
            titles.append(m.group(1))
            base, n = slug(m.group(1)), 1
            anchor = base
            while anchor in anchors:
                anchor, n = f"{base}-{n}", n + 1
            anchors.add(anchor)
        anchors.update(re.findall(r'<a\s+(?:id|name)="([^"]+)"', line))
    return titles, anchors


def where(path, n):
    return f"{path.relative_to(ROOT)}:{n}"


def check_links(md):
    for n, line in enumerate(text_lines(md), 1):
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):  # https:, mailto:
                continue
            file, _, anchor = target.partition("#")
            dest = (md.parent / file).resolve() if file else md
            if not dest.exists():
                errors.append(f"{where(md, n)}: link to {target}: {file} does not exist")
            elif anchor and dest.suffix == ".md" and anchor not in headings(dest)[1]:
                errors.append(f"{where(md, n)}: link to {target}: no heading #{anchor} in {file or md.name}")


def resolves(ref):
    """The stem of files of the tree: rt/pulse_thread (.cpp and .hpp), ipc/modbus_ (a family)."""
    return any(p.startswith(ref) and (ref.endswith(("_", "-")) or p[len(ref):len(ref) + 1] == ".")
               for p in TRACKED)


def check_paths(path, lines):
    rel = str(path.relative_to(ROOT))
    for n, line in enumerate(lines, 1):
        for m in PATH.finditer(line):
            ref = m.group(1).rstrip(".")
            if "XXX" in ref or any(f == rel and ref.startswith(r) for f, r in ELSEWHERE):
                continue  # a placeholder (module_types/mXXXX/), or another project's path
            dest = next((d for d in (ROOT / ref, path.parent / ref) if d.exists()), None)
            if dest is None and resolves(str((path.parent / ref).resolve().relative_to(ROOT))
                                         if ref.startswith("..") else ref):
                continue
            if dest is None:
                errors.append(f"{where(path, n)}: names {ref}, which is not in the repository")
                continue
            section = SECTION.match(line[m.end():].lstrip())
            if section and dest.suffix == ".md":
                title = section.group(1).lower()
                if not any(title in t.lower() for t in headings(dest)[0]):
                    errors.append(f'{where(path, n)}: names {ref} "{section.group(1)}", no such heading')


def man_lines(page):
    """A man page's text: groff's \\- is a hyphen, font changes go."""
    return [re.sub(r"\\f[BIRP]|\\f\(..", "", l.replace("\\-", "-")) for l in text_lines(page)]


def literal_lines(source):
    """The string literals of a C++ source, one joined line per source line (not #include's:
    the compiler checks those, and some name generated headers)."""
    return ["" if l.lstrip().startswith("#include") else
            " ".join(re.findall(r'"((?:[^"\\]|\\.)*)"', l)) for l in text_lines(source)]


def main():
    for rel in TRACKED:
        p = ROOT / rel
        if rel.endswith(".md"):
            check_links(p)
        if rel.startswith(("tests/", "bench/")) or not p.is_file():
            continue
        if rel in ("README.md",) or re.match(r"(docs/[^/]+|.*/README)\.md$", rel) or rel.startswith("web/www/"):
            check_paths(p, text_lines(p))
        elif rel.startswith("packaging/man/"):
            check_paths(p, man_lines(p))
        elif rel.endswith((".cpp", ".hpp")):
            check_paths(p, literal_lines(p))
    for e in errors:
        print(f"doc_links: {e}", file=sys.stderr)
    if errors:
        print(f"doc_links: {len(errors)} reference(s) do not resolve", file=sys.stderr)
        return 1
    print("doc_links: every link and path reference resolves in the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main())
