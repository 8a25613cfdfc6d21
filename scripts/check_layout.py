#!/usr/bin/env python3
"""Checks the size limits of the source tree: no C++ file under src/, include/ or
tests/ over MAX_FILE_LINES lines, no C++ function body over MAX_FUNCTION_LINES lines
(a test's body, TEST(...) { ... }, counts as a function).

    check_layout.py [ROOT] [--files F ...]

Prints one line per offender (path:line: what) and exits 1 if there is any, 0
otherwise. A function's length counts the lines of its body, from its opening brace
to its closing brace. The scan counts braces after removing comments, string and
character literals and preprocessor lines; it needs no compiler. A brace after a
parenthesised signature (at namespace or class scope) opens a function; a lambda or
local class counts as part of the function it stands in.
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 100
SOURCE_ENDINGS = ('.cpp', '.hpp', '.h', '.cc', '.cxx', '.hxx', '.in')
SOURCE_FOLDERS = ('src', 'include', 'tests')
SCOPE_WORDS = re.compile(r'\b(namespace|class|struct|union|enum)\b')


def strip_code(text):
    """Text with comments, literals and preprocessor lines blanked (newlines kept)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in ' \t':
            out.append(c)
            i += 1
            continue
        if line_start and c == '#':
            # Preprocessor line, with its backslash continuations.
            while i < n and not (text[i] == '\n' and text[i - 1] != '\\'):
                out.append('\n' if text[i] == '\n' else ' ')
                i += 1
            continue
        line_start = False
        if text.startswith('//', i):
            while i < n and text[i] != '\n':
                i += 1
            continue
        if text.startswith('/*', i):
            end = text.find('*/', i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:end]))
            i = end
            continue
        raw = re.match(r'(?:u8|u|U|L)?R"([^(\s]*)\(', text[i:i + 40])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            end = text.find(')' + raw.group(1) + '"', i + raw.end())
            end = n if end < 0 else end + len(raw.group(1)) + 2
            out.append('""' + re.sub(r'[^\n]', ' ', text[i + 2:end]))
            i = end
            continue
        if c in '"\'':
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(' ')
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(c + c)
            i = j + 1
            continue
        if c == '\n':
            line_start = True
        out.append(c)
        i += 1
    return ''.join(out)


def top_level_equals(header):
    """Whether header has an '=' outside brackets that is not part of operator=,
    ==, <=, >=, != (an initialiser: `T table[] = {`)."""
    depth = 0
    for k, c in enumerate(header):
        if c in '([<':
            depth += 1
        elif c in ')]>':
            depth = max(0, depth - 1)
        elif c == '=' and depth == 0:
            before, after = header[k - 1:k], header[k + 1:k + 2]
            if before in '=<>!' and before != '' or after == '=':
                continue
            if re.search(r'operator\s*$', header[:k]):
                continue
            return True
    return False


def classify(header):
    """'function', 'scope' (namespace, class, ...) or 'other' for the text before '{'."""
    text = re.sub(r'\s+', ' ', header).strip()
    text = re.sub(r'^(template ?<[^{;]*?> ?)+', '', text)
    if '(' in text and not top_level_equals(text):
        before_paren = text[:text.index('(')]
        if SCOPE_WORDS.search(before_paren) and not re.search(r'\boperator\b', before_paren):
            return 'scope'
        if re.match(r'^(if|for|while|switch|catch|do)\b', text):
            return 'other'
        return 'function'
    if SCOPE_WORDS.search(text) or text.startswith('extern'):
        return 'scope'
    return 'other'


def is_member_initialiser(header):
    """A brace in a constructor's initialiser list (`: value_{x}`) opens no body."""
    text = re.sub(r'\s+', ' ', header).rstrip()
    return bool(re.search(r'\)\s*(noexcept\s*)?:(?!:)', text)) and bool(re.search(r'[\w>]$', text))


def long_functions(path, text, limit):
    """(line, length, name) for every function body in text longer than limit lines."""
    code = strip_code(text)
    found = []
    stack = []  # per open brace: (kind, start line, name)
    header = ''
    line = 1
    in_function = 0
    for c in code:
        if c == '\n':
            line += 1
        if in_function:
            if c == '{':
                stack.append(('inner', line, ''))
            elif c == '}':
                kind, start, name = stack.pop()
                if kind == 'function':
                    in_function -= 1
                    if line - start + 1 > limit:
                        found.append((start, line - start + 1, name))
                    header = ''
            continue
        if c == '{':
            if is_member_initialiser(header):
                stack.append(('init', line, ''))
                header += c
                continue
            kind = classify(header)
            start = line
            name_match = re.search(r'([~\w:]+(?:operator\s*\S+)?)\s*\(', re.sub(r'\s+', ' ', header))
            stack.append((kind, start, name_match.group(1) if name_match else '?'))
            if kind == 'function':
                in_function = 1
            header = ''
        elif c == '}':
            kind = stack.pop()[0] if stack else 'scope'
            if kind == 'init':
                header += c
                continue
            header = ''
        elif c == ';':
            header = ''
        else:
            header += c
    return found


def source_files(root):
    for top in SOURCE_FOLDERS:
        for folder, _, names in os.walk(os.path.join(root, top)):
            for name in sorted(names):
                if name.endswith(SOURCE_ENDINGS):
                    yield os.path.join(folder, name)


def check(paths, root):
    offenders = []
    for path in sorted(paths):
        with open(path, encoding='utf-8', errors='replace') as f:
            text = f.read()
        shown = os.path.relpath(path, root)
        lines = text.count('\n') + (0 if text.endswith('\n') or not text else 1)
        if lines > MAX_FILE_LINES:
            offenders.append(f'{shown}: {lines} lines (limit {MAX_FILE_LINES}): split the file by concern')
        for start, length, name in long_functions(path, text, MAX_FUNCTION_LINES):
            offenders.append(f'{shown}:{start}: function {name} is {length} lines '
                             f'(limit {MAX_FUNCTION_LINES}): split it into named steps')
    return offenders


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    files = None
    args = list(argv)
    if '--files' in args:
        k = args.index('--files')
        files, args = args[k + 1:], args[:k]
    if args:
        root = os.path.abspath(args[0])
    offenders = check(files if files is not None else list(source_files(root)), root)
    for line in offenders:
        print(line)
    if offenders:
        print(f'check_layout: {len(offenders)} offender(s)', file=sys.stderr)
        return 1
    print('check_layout: no file over %d lines, no function over %d lines'
          % (MAX_FILE_LINES, MAX_FUNCTION_LINES))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
