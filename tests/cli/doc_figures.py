#!/usr/bin/env python3
"""doc_figures.py — every figure the README and the manual write down is one
the reports hold.

A *figure* is a number written in a page's prose, tables or ```text blocks
(the output of a run that cannot be repeated byte for byte): a decimal
(12.5, 3.6e-13, 0.004) or an integer of four or more digits (3113, 10,000),
years 1900-2099 excepted.  Code spans, link targets, commands ("$ ..." lines)
and ```console/```sh blocks are not prose: the console examples are run by
test_readme_examples.sh, and the figures their outputs show count as held.

A figure is held when a number in reports/ (every .md, .tsv and .txt, and
the .dat files of the report directories the page names, "reports/NAME") or
in a console example's output, rounded to the figure's significant digits,
equals it (a page may quote 8.6e-15 for 8.5512e-15; signs are ignored).  A
figure that is not a measurement (a parameter, a limit, a paper's printed
value, a figure of a test in docs/ranges.md) is listed with its reason in
tests/cli/doc_figures_exempt.tsv (page or "*" for every page, figure or "*"
for the whole page, why).  A paragraph (up to the next blank line) whose
figures a test or a peer benchmark under tests/ measures, rather than an experiment, says so where it
starts: <!-- figures from: tests/PATH --> (the file must exist).

Usage: doc_figures.py ROOT [PAGE...]   (default pages: README.md docs/*.md)
Prints one line per figure not held ("page:line: figure") and exits 1 if any.
"""
import glob
import os
import re
import sys
from decimal import Decimal, InvalidOperation

NUMBER = re.compile(r"(?<![\w.])(\d{1,3}(?:,\d{3})+|\d+(?:\.\d+)?(?:e[-+−]?\d+)?)(?![\w]|\.\d)")


def sig_key(text, digits=None):
    """(digits, normalised string) of a number rounded to `digits`
    significant digits (its own count when None); None if not a number."""
    t = text.replace("−", "-").replace(",", "").lstrip("-+")
    try:
        d = Decimal(t)
    except InvalidOperation:
        return None
    if d == 0:
        return (digits or 1, "0")
    if digits is None:
        mant = t.split("e")[0].split("E")[0].replace(".", "").lstrip("0")
        digits = max(1, len(mant))
        if "." not in t and "e" not in t.lower():   # an integer: its trailing zeros count
            digits = len(t.lstrip("0"))
    return (digits, format(d, "." + str(digits - 1) + "e"))


def figures(line):
    """The figures of one prose line (code spans and link targets removed)."""
    line = re.sub(r"`[^`]*`", " ", line)
    line = re.sub(r"\]\([^)]*\)", "]", line)
    line = re.sub(r"<!--.*?-->", " ", line)
    out = []
    for m in NUMBER.finditer(line):
        t = m.group(1)
        plain = t.replace(",", "")
        if re.fullmatch(r"\d+", plain):
            if len(plain) < 4 or 1900 <= int(plain) <= 2099:
                continue
        elif "," in t:
            continue
        out.append(t)
    return out


MARK = re.compile(r"<!-- figures from: ([^ ]+) -->")


def page_parts(path, root="."):
    """Yield (kind, lineno, text): kind 'prose' for figures to check,
    'held' for console-example output (numbers that count as held),
    'tested' for a paragraph marked <!-- figures from: FILE --> (its figures
    are what the test FILE measures; FILE must exist), 'badmark' for a mark
    naming no file."""
    fence = None
    marked = False
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            s = line.rstrip("\n")
            m = re.match(r"^```(\w*)", s)
            if m:
                fence = None if fence is not None else (m.group(1) or "plain")
                continue
            if fence is None:
                mk = MARK.search(re.sub(r"`[^`]*`", " ", s))
                if mk:
                    marked = os.path.isfile(os.path.join(root, mk.group(1)))
                    if not marked:
                        yield "badmark", n, mk.group(1)
                if not s.strip():
                    marked = False
                yield ("tested" if marked else "prose"), n, s
            elif fence == "console":
                if not s.startswith("$ "):
                    yield "held", n, s
            elif fence == "text":
                if not s.startswith("$ "):
                    yield "prose", n, s


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    pages = sys.argv[2:] or ["README.md"] + sorted(
        os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "docs", "*.md")))
    held = set()

    def hold(into, text):
        for m in re.finditer(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", text):
            k = sig_key(m.group(0))
            if k is None:
                continue
            for d in range(1, k[0] + 1):
                into.add(sig_key(m.group(0), d))

    for p in sorted(glob.glob(os.path.join(root, "reports", "**", "*"), recursive=True)):
        if os.path.isfile(p) and p.rsplit(".", 1)[-1] in ("md", "tsv", "txt"):
            with open(p, encoding="utf-8", errors="replace") as f:
                hold(held, f.read())
    for page in pages:
        for kind, _, text in page_parts(os.path.join(root, page)):
            if kind == "held":
                hold(held, text)

    exempt = set()
    with open(os.path.join(root, "tests", "cli", "doc_figures_exempt.tsv"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            cells = line.rstrip("\n").split("\t")
            if len(cells) != 3 or not cells[2].strip():
                print("doc_figures_exempt.tsv: not 'page<TAB>figure<TAB>why': " + line.strip())
                return 2
            exempt.add((cells[0], cells[1].replace("−", "-")))

    dat_cache = {}

    def page_held(page):
        """The data files (.dat) of the report directories the page names
        (a link or a path "reports/NAME"): a page quotes the data of the
        experiments it points to."""
        with open(os.path.join(root, page), encoding="utf-8") as f:
            names = sorted(set(re.findall(r"(?:reports|experiments)/([A-Za-z0-9_]+)", f.read())))
        extra = set()
        for name in names:
            if name not in dat_cache:
                dat_cache[name] = set()
                for p in glob.glob(os.path.join(root, "reports", name, "**", "*.dat"), recursive=True):
                    with open(p, encoding="utf-8", errors="replace") as f:
                        hold(dat_cache[name], f.read())
            extra |= dat_cache[name]
        return extra

    bad = 0
    for page in pages:
        if (page, "*") in exempt:
            continue
        scope = page_held(page)
        for kind, n, text in page_parts(os.path.join(root, page), root):
            if kind == "badmark":
                print("%s:%d: <!-- figures from: %s --> names no file" % (page, n, text))
                bad += 1
            if kind != "prose":
                continue
            for t in figures(text):
                if (page, t.replace("−", "-").lstrip("-")) in exempt or ("*", t) in exempt:
                    continue
                k = sig_key(t)
                if k not in held and k not in scope:
                    print("%s:%d: %s" % (page, n, t))
                    bad += 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
