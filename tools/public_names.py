#!/usr/bin/env python3
"""tools/public_names.py HEADER... - every name a C header declares at file scope, one per line:

    HEADER<TAB>NAME<TAB>KIND      KIND: func, type, tag, object, enum (constant), macro

Used by tools/parity.sh (make parity-check) to hold each public name to its family's header.
A small parser, not a grep: comments, string literals, function bodies and the C++ guard are
removed first; then every file-scope statement is split into its declarators, so a name on a
continuation line, a second name in one typedef ("typedef struct x qo_a, *qo_b;"), a function-
pointer type ("typedef void (*qo_f)(void);"), an object, an enum constant and a #define (also a
lower-case one) are all seen. It understands the C99 the headers are written in, and fails
(exit 2) on what it cannot split (unbalanced braces) rather than guess.
"""
import re
import sys

IDENT = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
KEYWORDS = {
    'typedef', 'struct', 'union', 'enum', 'static', 'inline', 'extern', 'const', 'volatile',
    'unsigned', 'signed', 'int', 'char', 'short', 'long', 'float', 'double', 'void', 'restrict',
    'register', '_Bool', 'sizeof', 'AGGREGATE',
}


def strip(text):
    """Comments and literals out, preprocessor lines collected apart."""
    text = re.sub(r'/\*.*?\*/', lambda m: ' ' + '\n' * m.group(0).count('\n'), text, flags=re.S)
    text = re.sub(r'//[^\n]*', '', text)
    text = re.sub(r'"(\\.|[^"\\\n])*"', '""', text)
    text = re.sub(r"'(\\.|[^'\\\n])*'", "''", text)
    text = text.replace('\\\n', ' ')
    macros, body, skip = [], [], 0
    for line in text.split('\n'):
        s = line.strip()
        if s.startswith('#'):
            d = s[1:].strip()
            if re.match(r'if(def)?\s*(defined\s*\(?\s*)?__cplusplus', d):
                skip += 1
                continue
            if skip and d.startswith('if'):
                skip += 1
            elif skip and d.startswith('endif'):
                skip -= 1
            m = re.match(r'define\s+([A-Za-z_][A-Za-z0-9_]*)', d)
            if m and not skip:
                macros.append(m.group(1))
            continue
        if not skip:
            body.append(line)
    return macros, ' '.join(body)


def declarator_name(decl):
    """The name a declarator declares: (*name)(...), name[...], name(...), *name."""
    m = re.search(r'\(\s*\*\s*([A-Za-z_][A-Za-z0-9_]*)\s*\)', decl)
    if m:
        return m.group(1), 'fptr'
    d = re.sub(r'\[[^\]]*\]', '', decl)
    d = d.split('=')[0]
    m = re.match(r'^(.*?)([A-Za-z_][A-Za-z0-9_]*)\s*\(', d)
    if m:
        return m.group(2), 'func'
    ids = [i for i in IDENT.findall(d) if i not in KEYWORDS]
    return (ids[-1], 'plain') if ids else (None, None)


def split_top(s, sep=','):
    """s split at sep outside parentheses."""
    out, depth, cur = [], 0, ''
    for c in s:
        if c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
        if c == sep and depth == 0:
            out.append(cur)
            cur = ''
        else:
            cur += c
    out.append(cur)
    return out


def names(path):
    with open(path, encoding='utf-8') as f:
        macros, code = strip(f.read())
    found = [(m, 'macro') for m in macros]
    i, n, stmt = 0, len(code), ''
    while i < n:
        c = code[i]
        if c == '{':
            head = stmt
            j, depth = i + 1, 1
            while j < n and depth:
                depth += {'{': 1, '}': -1}.get(code[j], 0)
                j += 1
            if depth:
                raise ValueError(path + ': unbalanced braces')
            inner = code[i + 1:j - 1]
            aggregate = re.search(r'\b(struct|union|enum)\b\s*([A-Za-z_][A-Za-z0-9_]*)?\s*$', head)
            if aggregate:
                if aggregate.group(2):
                    found.append((aggregate.group(2), 'tag'))
                if aggregate.group(1) == 'enum':
                    for item in split_top(inner):
                        m = IDENT.match(item.strip())
                        if m:
                            found.append((m.group(0), 'enum'))
                stmt = head[:aggregate.start()] + ' AGGREGATE '
                i = j
                continue
            # a function definition: its name is the declarator before the body
            name, _ = declarator_name(head)
            if name:
                found.append((name, 'func'))
            stmt = ''
            i = j
            continue
        if c == ';':
            s = stmt.strip()
            stmt = ''
            i += 1
            if not s:
                continue
            typedef = re.match(r'^typedef\b', s) is not None
            rest = re.sub(r'^typedef\b', '', s).strip()
            m = re.match(r'^(struct|union|enum)\s+([A-Za-z_][A-Za-z0-9_]*)$', rest)
            if m:  # a forward declaration names a tag
                found.append((m.group(2), 'tag'))
                continue
            for decl in split_top(rest):
                name, form = declarator_name(decl)
                if not name:
                    continue
                if typedef:
                    found.append((name, 'type'))
                elif form == 'func':
                    found.append((name, 'func'))
                else:
                    found.append((name, 'object'))
            continue
        stmt += c
        i += 1
    return found


def main():
    status = 0
    for path in sys.argv[1:]:
        try:
            for name, kind in names(path):
                print(f'{path}\t{name}\t{kind}')
        except (OSError, ValueError) as e:
            print(f'public_names: {e}', file=sys.stderr)
            status = 2
    return status


if __name__ == '__main__':
    sys.exit(main())
