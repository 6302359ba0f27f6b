#!/usr/bin/env python3
"""Room a maintainer can change: file and function lengths in libs/ and apps/.

Prints the largest .cpp/.h files in libs/ (lines) and every function in the
.cpp files of libs/ and apps/ longer than --max-function lines, then exits 1
when a limit is exceeded (0 otherwise, 2 on bad usage).

Functions are found by a brace-matching scan that skips comments, string and
character literals (raw strings too): a brace block at namespace level (or
inside a class body) whose head ends in ')' (optionally followed by const,
noexcept, override, final, a trailing return type or a constructor's member
initializer list) is a function; its length is the number of lines from the
line of its name to the line of its closing brace. Lambdas and blocks inside
a function count towards that function.

  scripts/check_rooms.py [--max-file 800] [--max-function 150]
                         [--top 10] [--exempt PATH]...
"""
import argparse
import os
import re
import sys

SOURCE_ENDINGS = (".cpp", ".h", ".hpp", ".cc")
SCOPE_KEYWORDS = ("namespace", "class", "struct", "union", "enum", "extern")


def strip_code(text):
    """Returns text with comments, string and char literals blanked out.

    Newlines are kept, so line numbers stay valid; a literal's contents
    become spaces, so braces inside them do not count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "/" and i + 1 < n and text[i + 1] == "/":
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c == "/" and i + 1 < n and text[i + 1] == "*":
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (
                i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^()\\\s]{0,16})\(', text[i:])
            if not m:
                out.append(c)
                i += 1
                continue
            end = ")" + m.group(1) + '"'
            j = text.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            # a digit separator (1'000) is not a char literal
            if c == "'" and i > 0 and text[i - 1].isalnum() and \
                    i + 1 < n and text[i + 1].isalnum():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1:j - 1]) + c
                       if j - i >= 2 else text[i:j])
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def strip_preprocessor(code):
    """Blanks preprocessor lines (with their continuations)."""
    lines = code.split("\n")
    continued = False
    for k, line in enumerate(lines):
        if continued or line.lstrip().startswith("#"):
            continued = line.rstrip().endswith("\\")
            lines[k] = ""
        else:
            continued = False
    return "\n".join(lines)


_TRAILER = re.compile(
    r"\)\s*(?:(?:const|noexcept|override|final|mutable|volatile|&&|&)\s*"
    r"|noexcept\s*\([^()]*\)\s*|->\s*[\w:<>,\s\*&]+)*$")


def head_kind(head):
    """'function' with its name, 'scope', or None for other blocks."""
    h = " ".join(head.split())
    if not h:
        return None, ""
    first = re.match(r"[A-Za-z_]\w*", h)
    if first and first.group(0) in SCOPE_KEYWORDS and "(" not in h:
        return "scope", ""
    if h.startswith("extern"):
        return "scope", ""
    # constructor initializer list: cut at the ':' after the parameter list
    depth, cut = 0, len(h)
    for k, ch in enumerate(h):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                rest = h[k + 1:].lstrip()
                if rest.startswith(":") and not rest.startswith("::"):
                    cut = k + 1
                    break
    sig = h[:cut]
    if "=" in sig.split("(")[0]:
        return None, ""  # an initializer such as `auto f = [](...) {`
    if not _TRAILER.search(sig):
        return None, ""
    m = re.search(r"([~\w:]+(?:operator\s*[^\s(]+)?)\s*\(", sig)
    name = m.group(1) if m else "?"
    if name in ("if", "for", "while", "switch", "catch", "return"):
        return None, ""
    return "function", name


def find_functions(text):
    """Yields (name, first_line, last_line) for each function definition."""
    code = strip_preprocessor(strip_code(text))
    stack = []  # entries: 'scope' | 'function' | 'other'
    head_start = 0
    line = 1
    func_start = None
    for k, ch in enumerate(code):
        if ch == "\n":
            line += 1
        elif ch in ";":
            if not stack or stack[-1] == "scope":
                head_start = k + 1
        elif ch == "{":
            if stack and stack[-1] != "scope":
                stack.append("other")
                continue
            head = code[head_start:k]
            kind, name = head_kind(head)
            if kind == "function":
                offset = len(head) - len(head.lstrip())
                first_line = code.count("\n", 0, head_start + offset) + 1
                # begin at the line that carries the name
                name_at = head.find(name.split("::")[-1]) if name else -1
                if name_at >= 0:
                    first_line = code.count("\n", 0, head_start + name_at) + 1
                func_start = (name, first_line)
                stack.append("function")
            elif kind == "scope":
                stack.append("scope")
            else:
                stack.append("other")
            head_start = k + 1
        elif ch == "}":
            if not stack:
                head_start = k + 1
                continue
            kind = stack.pop()
            if kind == "function" and func_start:
                yield func_start[0], func_start[1], line
                func_start = None
            if not stack or stack[-1] == "scope":
                head_start = k + 1
        elif ch == ":" and (not stack or stack[-1] == "scope"):
            # access specifiers and labels at class level end a head
            before = code[head_start:k].strip()
            if before in ("public", "private", "protected"):
                head_start = k + 1


def source_files(root, sub, endings):
    base = os.path.join(root, sub)
    for dirpath, dirnames, filenames in os.walk(base):
        dirnames.sort()
        for f in sorted(filenames):
            if f.endswith(endings):
                yield os.path.join(dirpath, f)


def count_lines(path):
    with open(path, encoding="utf-8", errors="replace") as fh:
        return sum(1 for _ in fh)


def main(argv):
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.dirname(here),
                    help="source tree (default: this checkout)")
    ap.add_argument("--max-file", type=int, default=800,
                    help="lines a file in libs/ may have (default 800)")
    ap.add_argument("--max-function", type=int, default=150,
                    help="lines a function may have (default 150)")
    ap.add_argument("--top", type=int, default=10,
                    help="how many of the largest files to list")
    ap.add_argument("--exempt", action="append", default=[],
                    metavar="PATH",
                    help="a file (relative to the root) whose size and "
                    "functions are listed but not held to the limits; "
                    "repeatable")
    args = ap.parse_args(argv)
    root = os.path.abspath(args.root)
    exempt = {os.path.normpath(p) for p in args.exempt}

    def rel(p):
        return os.path.relpath(p, root)

    failed = False
    sizes = sorted(((count_lines(p), rel(p))
                    for p in source_files(root, "libs", SOURCE_ENDINGS)),
                   key=lambda t: (-t[0], t[1]))
    print("largest files in libs/ (lines, limit %d):" % args.max_file)
    for n, p in sizes[:args.top]:
        mark = ""
        if n > args.max_file:
            if p in exempt:
                mark = "  (exempt)"
            else:
                mark = "  OVER"
                failed = True
        print("  %5d  %s%s" % (n, p, mark))
    for n, p in sizes[args.top:]:
        if n > args.max_file and p not in exempt:
            print("  %5d  %s  OVER" % (n, p))
            failed = True

    longest = []
    for sub in ("libs", "apps"):
        for p in source_files(root, sub, (".cpp", ".cc")):
            with open(p, encoding="utf-8", errors="replace") as fh:
                text = fh.read()
            for name, a, b in find_functions(text):
                longest.append((b - a + 1, rel(p), a, name))
    longest.sort(key=lambda t: (-t[0], t[1], t[2]))
    over = [f for f in longest if f[0] > args.max_function]
    print("functions in libs/ and apps/ longer than %d lines: %d"
          % (args.max_function, len(over)))
    for n, p, a, name in over:
        mark = "  (exempt)" if p in exempt else ""
        failed = failed or p not in exempt
        print("  %5d  %s:%d  %s%s" % (n, p, a, name, mark))
    if longest and not over:
        n, p, a, name = longest[0]
        print("  longest: %d  %s:%d  %s" % (n, p, a, name))
    print("rooms: " + ("OVER the limits" if failed else "within the limits"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
