#!/usr/bin/env python3
"""Checks that every relative link of the README and the user guide resolves.

Markdown (default: README.md and docs/guide/src/**/*.md, or the files given): every inline
link, image and reference definition `[label]: target`, and every `href`/`src` of inline HTML,
outside code blocks and code spans, that is not a URL (`https:`, `mailto:`, ...) must name a
file or folder that exists, relative to the page; a `#anchor` must be a heading of the target
page (or of the page itself), by the slug rule mdBook and GitHub share: the heading's text in
lower case, whitespace to `-`, characters other than letters, digits, `-` and `_` dropped, a
repeated slug numbered `-1`, `-2`, ...; `{#id}` attributes and HTML `id`/`name` count too.
Every fenced block must say what it is (an info string: `sh`, `console`, `text`, `rust`, ...):
rustdoc would compile a bare one as Rust (the pages are doctests: src/lib.rs, `doctests`).
A line `{{#include FILE}}` (mdBook's include, FILE relative to the page; a `:range` or `:anchor`
suffix is ignored and the whole file taken) is replaced by FILE's lines, as mdBook does, so
their links are checked relative to the including page and their headings are its anchors;
FILE must exist, and a file that a checked page includes is not checked again on its own.

--book DIR (after `mdbook build`): every local `href`/`src` of the rendered HTML pages must
name a file of the book, and its `#anchor` an `id` of that file; this catches what only the
rendering shows (a page missing from SUMMARY.md, a link that leaves the book).

Prints `FILE:LINE: reason` per broken link and exits with 1 if there is one.
Standard library only (CI runs it with the system's python3).
"""

import argparse
import html.parser
import os
import re
import sys
import urllib.parse

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})(.*)$")
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
EXPLICIT_ID = re.compile(r"\s*\{#([^}\s]+)[^}]*\}\s*$")
INLINE_LINK = re.compile(
    r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*(<[^>]*>|[^()\s]*(?:\([^()\s]*\)[^()\s]*)*)"
    r"(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)"
)
INCLUDE = re.compile(r"^\s*\{\{#include\s+([^}:\s]+)(?::[^}]*)?\s*\}\}\s*$")
REF_DEF = re.compile(r"^ {0,3}\[([^\]]+)\]:\s*(<[^>]*>|\S+)")
HTML_ATTR = re.compile(r"""\b(href|src)\s*=\s*(?:"([^"]*)"|'([^']*)')""", re.I)
HTML_ID = re.compile(r"""\b(?:id|name)\s*=\s*(?:"([^"]*)"|'([^']*)')""", re.I)
CODE_SPAN = re.compile(r"(`+)(.+?)(?<!`)\1(?!`)")
URL_SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def slug(text):
    """The anchor of a heading's text (mdBook's id_from_content; GitHub's rule alike)."""
    out = []
    for ch in text.strip().lower():
        if ch.isalnum() or ch in "-_":
            out.append(ch)
        elif ch.isspace():
            out.append("-")
    return "".join(out)


def heading_text(markdown):
    """The visible text of a heading's Markdown: code spans, emphasis, links and tags undone."""
    text = CODE_SPAN.sub(lambda m: m.group(2).strip(), markdown)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text)
    text = re.sub(r"\\(.)", r"\1", text)
    return text.replace("*", "").replace("_", "_")


def expand_includes(path, lines, included, depth=0):
    """(line number, text) of a page's lines with every `{{#include FILE}}` line replaced by
    FILE's lines (numbered as the include line), the included paths added to `included`, and
    the problems of includes that name no file."""
    out, problems = [], []
    for number, line in enumerate(lines, 1):
        m = INCLUDE.match(line)
        if not m:
            out.append((number, line))
            continue
        target = os.path.normpath(os.path.join(os.path.dirname(path), m.group(1)))
        if depth > 8 or not os.path.isfile(target):
            problems.append((number, f"{{{{#include {m.group(1)}}}}}: no file {os.path.relpath(target, REPO)}"))
            continue
        included.add(target)
        with open(target, encoding="utf-8") as f:
            inner, inner_problems = expand_includes(target, f.read().split("\n"), included, depth + 1)
        out += [(number, text) for _, text in inner]
        problems += [(number, f"in {os.path.relpath(target, REPO)}: {reason}") for _, reason in inner_problems]
    return out, problems


def lines_outside_code(numbered):
    """(line number, text) of the lines outside fenced blocks, and the fences' problems."""
    out, problems = [], []
    fence = None
    number = 0
    for number, line in numbered:
        m = FENCE.match(line)
        if fence is None:
            if m:
                fence = m.group(2)
                if not m.group(3).strip():
                    problems.append(
                        (number, "fenced block without an info string (sh, console, text, rust, ...)")
                    )
                continue
            out.append((number, line))
        elif m and m.group(2)[0] == fence[0] and len(m.group(2)) >= len(fence) and not m.group(3).strip():
            fence = None
    if fence is not None:
        problems.append((number, "unclosed fenced block"))
    return out, problems


class Page:
    """A Markdown page's anchors and links."""

    def __init__(self, path):
        self.path = path
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        self.included = set()
        numbered, include_problems = expand_includes(path, lines, self.included)
        self.text_lines, self.problems = lines_outside_code(numbered)
        self.problems += include_problems
        self.anchors = set()
        used = set()
        for _, line in self.text_lines:
            for m in HTML_ID.finditer(line):
                self.anchors.add(m.group(1) or m.group(2))
            h = HEADING.match(line)
            if not h:
                continue
            content = h.group(2)
            explicit = EXPLICIT_ID.search(content)
            if explicit:
                self.anchors.add(explicit.group(1))
                used.add(explicit.group(1))
                continue
            base = slug(heading_text(content))
            anchor, k = base, 0
            while anchor in used:
                k += 1
                anchor = f"{base}-{k}"
            used.add(anchor)
            self.anchors.add(anchor)

    def links(self):
        """(line number, target) of every link outside code."""
        for number, line in self.text_lines:
            plain = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
            for m in INLINE_LINK.finditer(plain):
                yield number, m.group(3).strip("<>")
            m = REF_DEF.match(plain)
            if m:
                yield number, m.group(2).strip("<>")
            for m in HTML_ATTR.finditer(plain):
                yield number, m.group(2) if m.group(2) is not None else m.group(3)


def check_markdown(files):
    pages = {}

    def page(path):
        if path not in pages:
            pages[path] = Page(path)
        return pages[path]

    errors = []
    included = set()
    for path in files:
        included |= page(path).included
    for path in files:
        if path in included:
            continue
        p = page(path)
        rel = os.path.relpath(path, REPO)
        for number, reason in p.problems:
            errors.append(f"{rel}:{number}: {reason}")
        for number, target in p.links():
            if not target or URL_SCHEME.match(target):
                continue
            where, _, anchor = target.partition("#")
            where = urllib.parse.unquote(where.split("?")[0])
            anchor = urllib.parse.unquote(anchor)
            if where.startswith("/"):
                errors.append(f"{rel}:{number}: {target}: an absolute path (links are relative to the page)")
                continue
            dest = os.path.normpath(os.path.join(os.path.dirname(path), where)) if where else path
            if not os.path.exists(dest):
                errors.append(f"{rel}:{number}: {target}: no file {os.path.relpath(dest, REPO)}")
                continue
            if anchor:
                if not dest.endswith(".md"):
                    continue
                if anchor not in page(dest).anchors:
                    errors.append(
                        f"{rel}:{number}: {target}: no heading with the anchor #{anchor} "
                        f"in {os.path.relpath(dest, REPO)}"
                    )
    return errors


class HtmlRefs(html.parser.HTMLParser):
    """The ids and the href/src values of an HTML page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids, self.refs = set(), []

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if value is None:
                continue
            if name in ("id", "name"):
                self.ids.add(value)
            elif name in ("href", "src"):
                self.refs.append((self.getpos()[0], value))


def check_book(book):
    parsed = {}

    def parse(path):
        if path not in parsed:
            p = HtmlRefs()
            with open(path, encoding="utf-8", errors="replace") as f:
                p.feed(f.read())
            parsed[path] = p
        return parsed[path]

    errors = []
    for root, _, names in os.walk(book):
        for name in sorted(names):
            if not name.endswith(".html"):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, REPO)
            for number, target in parse(path).refs:
                if not target or URL_SCHEME.match(target) or target.startswith("//"):
                    continue
                where, _, anchor = target.partition("#")
                where = urllib.parse.unquote(where.split("?")[0])
                anchor = urllib.parse.unquote(anchor)
                dest = os.path.normpath(os.path.join(root, where)) if where else path
                if not os.path.exists(dest):
                    errors.append(f"{rel}:{number}: {target}: no file {os.path.relpath(dest, REPO)}")
                    continue
                if anchor and dest.endswith(".html") and anchor not in parse(dest).ids:
                    errors.append(f"{rel}:{number}: {target}: no id {anchor} in {os.path.relpath(dest, REPO)}")
    return errors


def default_files():
    files = [os.path.join(REPO, "README.md")]
    for root, _, names in os.walk(os.path.join(REPO, "docs", "guide", "src")):
        files += [os.path.join(root, n) for n in names if n.endswith(".md")]
    return sorted(files)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*", help="Markdown pages (default: README.md and the guide)")
    ap.add_argument("--book", help="also check the HTML book that mdbook built into this folder")
    args = ap.parse_args()
    files = [os.path.abspath(f) for f in args.files] or default_files()
    errors = check_markdown(files)
    checked = f"{len(files)} pages"
    if args.book:
        if not os.path.isdir(args.book):
            print(f"check-links: no book folder {args.book}", file=sys.stderr)
            return 1
        errors += check_book(os.path.abspath(args.book))
        checked += " and the book"
    for e in errors:
        print(e)
    print(f"check-links: {checked}, {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
