#!/usr/bin/env python3
"""A lexical screen in front of scripts/check-function-size: which translation units can hold a
function as long as the threshold, so that clang-tidy parses only those (a clang-tidy pass over
the whole tree costs ~7 CPU-minutes, most of CI's two cores for minutes).

The screen is conservative: it tokenizes each product source and header (comments, string and
character literals and preprocessor lines dropped) and looks at every brace block of at least
MIN_LINES lines. A block is let through unscreened only when it is positively a container or an
initializer:
  * a container: the declaration before it begins with namespace, class, struct, union or enum
    (after template<...> and attributes), or is extern "C";
  * an initializer: the token before the brace is `=`, `,`, `(` or `{`, or an identifier or `>`
    with no parenthesis in the declaration (`std::array<Row, 3> kRows{`) or in a constructor's
    member initializers (`X(int a) : a_{`), or the `]` of an array declarator (`kRows[] {`).
Every other long block (a function body, a lambda, a constructor after its brace initializers,
anything unrecognised) makes its file a candidate, and so does a file whose braces do not
balance (#if branches that open braces differently). Being wrong costs only a clang-tidy run.

A candidate header is checked through one unit that includes it (the build's dependency log,
`ninja -t deps`); a unit that log does not know (not built yet) is parsed whole.

Usage: function_size_screen.py --root DIR --build DIR --min-lines N UNIT...
Prints the units clang-tidy must check, one per line; a summary on standard error.
"""
import argparse
import os
import re
import subprocess
import sys

CONTAINER_WORDS = {"namespace", "class", "struct", "union", "enum"}
LEADING_WORDS = {"template", "export", "inline", "typedef"}
TOKEN = re.compile(r"""
    (?P<raw>(?:u8|u|U|L)?R"(?P<delim>[^ ()\\\t\n]{0,16})\()   # a raw string's opening
  | (?P<str>(?:u8|u|U|L)?"(?:[^"\\\n]|\\.)*")
  | (?P<chr>(?:u8|u|U|L)?'(?:[^'\\\n]|\\.)+')
  | (?P<num>\.?[0-9](?:[eEpP][+-]|[\w.'])*)                     # 1'000'000 is one number
  | (?P<id>[A-Za-z_]\w*)
  | (?P<op>->|::|\S)
""", re.VERBOSE)


def lex(text):
    """(kind, value, line) of each token; comments and preprocessor lines dropped, each string
    or character literal one token "" (a brace inside one is not a brace)."""
    i, n, line, at_line_start = 0, len(text), 1, True
    while i < n:
        c = text[i]
        if c == "\n" or c.isspace():
            line += c == "\n"
            at_line_start = at_line_start or c == "\n"
            i += 1
            continue
        end = None
        if text.startswith("//", i):
            end = text.find("\n", i)
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = -1 if end < 0 else end + 2
        elif at_line_start and c == "#":
            end = i
            while True:  # a directive runs on over backslash-newlines
                end = text.find("\n", end)
                if end < 0 or text[end - 1] != "\\":
                    break
                end += 1
        if end is not None:
            end = n if end < 0 else end
            line += text.count("\n", i, end)
            i = end
            continue
        at_line_start = False
        m = TOKEN.match(text, i)
        kind, value = m.lastgroup, m.group(0)
        if m.group("raw") is not None:
            close = text.find(")" + m.group("delim") + '"', m.end())
            end = n if close < 0 else close + len(m.group("delim")) + 2
            kind, value = "str", text[i:end]
        elif kind == "chr":
            kind = "str"
        yield kind, ('""' if kind == "str" else value), line
        line += value.count("\n")
        i += len(value)


def declaration_head(intro):
    """The introducer without leading template<...>, attributes and specifier words."""
    i = 0
    while i < len(intro):
        value = intro[i][1]
        if value == "template" and i + 1 < len(intro) and intro[i + 1][1] == "<":
            depth, i = 0, i + 1
            while i < len(intro):
                depth += {"<": 1, ">": -1}.get(intro[i][1], 0)
                i += 1
                if depth == 0:
                    break
            continue
        if value == "[" and i + 1 < len(intro) and intro[i + 1][1] == "[":
            while i < len(intro) and not (intro[i][1] == "]" and i > 0 and intro[i - 1][1] == "]"):
                i += 1
            i += 1
            continue
        if value in LEADING_WORDS:
            i += 1
            continue
        break
    return intro[i:]


def is_scope(intro):
    """Whether these tokens open a namespace, class, struct, union, enum or extern "C" block."""
    head = declaration_head(intro)
    return bool(head) and (head[0][1] in CONTAINER_WORDS or head[0][1] == "extern")


def is_container_or_initializer(intro, opened_inside=False):
    """Whether the block after these tokens is positively not a function's body."""
    if is_scope(intro):
        return True
    if not intro:
        # Right after an opening brace: a nested initializer ({{...}}) or a statement block;
        # after ; or } : a statement block, or unrecognised.
        return opened_inside
    last = intro[-1][1]
    if last in {"=", ",", "(", "{"}:
        return True
    has_paren = any(v == "(" for _, v, _ in intro)
    if intro[-1][0] == "id" or last == ">":
        return not has_paren or in_constructor_initializers(intro)
    if last == "]" and len(intro) >= 2:
        # kRows[] { or kRows[3] { : an array declarator; [] { or [x] { : a lambda.
        opening = max(i for i, (_, v, _) in enumerate(intro) if v == "[")
        return opening > 0 and intro[opening - 1][0] == "id" and intro[opening - 1][1] != "return"
    return False


def in_constructor_initializers(intro):
    """Whether the tokens end inside a constructor's member initializers: `X(int a) : a_`."""
    closed = False
    for _, value, _ in intro:
        closed = closed or value == ")"
        if closed and value == ":":
            return True
    return False


def long_function_blocks(text, min_lines):
    """The (first, last) lines of each block of min_lines or more that may be a function's body;
    [(1, 0)] when the braces do not balance (the file cannot be screened)."""
    stack, intro, found, previous = [], [], [], None
    for kind, value, line in lex(text):
        if value == "{":
            stack.append((line, is_container_or_initializer(intro, previous == "{"), intro))
            intro = []
        elif value == "}":
            if not stack:
                return [(1, 0)]
            first, not_function, outer = stack.pop()
            if line - first + 1 >= min_lines and not not_function:
                found.append((first, line))
            # An initializer's braces are part of the declaration around them (a constructor's
            # a_{x}, b_{y} before its body); any other block ends one.
            intro = outer + [("op", "{}", line)] if not_function and not is_scope(outer) else []
        elif value == ";":
            intro = []
        else:
            intro.append((kind, value, line))
        previous = value
    return found if not stack else [(1, 0)]




def unit_dependencies(build, root):
    """{unit source: [product files it reads]} from the build's dependency log, or None."""
    try:
        out = subprocess.run(["ninja", "-C", build, "-t", "deps"], capture_output=True,
                             text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    deps, current = {}, None
    for line in out.splitlines():
        if not line.startswith(" "):
            current = None if "(VALID)" not in line else []
            continue
        path = os.path.realpath(os.path.join(build, line.strip()))
        if current is None:
            continue
        if not current:
            deps[path] = current  # the first dependency is the unit's own source
        if path.startswith(root + os.sep):
            current.append(path)
    return deps


def product_file(path, root):
    rel = os.path.relpath(path, root)
    return not rel.startswith(("..", "tests/", "bench/", "build"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--min-lines", type=int, required=True)
    ap.add_argument("units", nargs="+")
    args = ap.parse_args()
    root = os.path.realpath(args.root)
    units = [os.path.realpath(u) for u in args.units]
    deps = unit_dependencies(os.path.realpath(args.build), root) or {}
    # A unit the dependency log does not know (not built yet) is parsed whole: clang-tidy then
    # reads its headers itself.
    known = [u for u in units if u in deps]
    unknown = [u for u in units if u not in deps]
    files = sorted({f for u in known for f in deps[u] if product_file(f, root)})
    flagged = {f for f in files
               if long_function_blocks(open(f, encoding="utf-8", errors="replace").read(),
                                       args.min_lines)}
    chosen = set(unknown) | {u for u in known if u in flagged}
    for header in sorted(flagged - set(units)):
        if not any(header in deps.get(u, ()) for u in chosen):
            chosen.add(min(u for u in known if header in deps[u]))
    if unknown:
        print(f"function-size screen: no dependency log for {len(unknown)} of {len(units)} units "
              "(not built): parsed whole", file=sys.stderr)
    print(f"function-size screen: {len(flagged)} of {len(files)} product files hold a block of "
          f"{args.min_lines}+ lines that may be a function; {len(chosen)} of {len(units)} units "
          "to check", file=sys.stderr)
    for unit in sorted(chosen):
        print(unit)
    return 0


if __name__ == "__main__":
    sys.exit(main())
