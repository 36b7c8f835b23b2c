#!/usr/bin/env python3
"""long_functions.py [--max N] FILE... — function definitions longer than N
lines (default 100), by brace matching at file level: a line that starts a
definition (no indentation, ends with ')' or '{' after a parameter list)
through its closing brace in column 0.  Prints "lines file:line name",
longest first; exit 1 if any."""
import re, sys

def functions(path):
    lines = open(path, encoding='utf-8', errors='replace').read().split('\n')
    i = 0
    while i < len(lines):
        l = lines[i]
        m = re.match(r'^[A-Za-z_][\w \*\(\),]*?\b([A-Za-z_]\w*)\s*\(', l)
        if m and l.rstrip().endswith('}') and '{' in l:  # a one-line definition
            i += 1
            continue
        if m and not l.rstrip().endswith(';') and not l.startswith(('typedef', 'struct', 'enum', 'static const', 'const', '#')) or \
           (m and l.startswith('static const') and '(' in l and not '=' in l):
            j = i
            while j < len(lines) and lines[j] != '{' and not lines[j].rstrip().endswith('{'):
                if lines[j].rstrip().endswith(';'): break
                j += 1
            if j < len(lines) and (lines[j] == '{' or lines[j].rstrip().endswith('{')) and not lines[j].rstrip().endswith(';'):
                k = j + 1
                while k < len(lines) and lines[k] != '}':
                    k += 1
                if k < len(lines):
                    yield (k - i + 1, i + 1, m.group(1))
                    i = k + 1
                    continue
        i += 1

def main(argv):
    mx = 100
    if argv[:1] == ['--max']:
        mx = int(argv[1]); argv = argv[2:]
    out = []
    for p in argv:
        for n, line, name in functions(p):
            if n > mx:
                out.append((n, '%s:%d' % (p, line), name))
    for n, where, name in sorted(out, reverse=True):
        print('%5d %s %s' % (n, where, name))
    return 1 if out else 0

sys.exit(main(sys.argv[1:]))
