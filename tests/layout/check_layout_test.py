#!/usr/bin/env python3
"""scripts/check_layout.py finds what it must and nothing else: a file one line over
the limit, a function body one line over it (with braces in comments, strings and a
constructor's initialiser list that must not count, nor hide the body), and passes the same file at the
limits, and walks src/, include/ and tests/. Usage: check_layout_test.py SOURCE_DIR"""
import os
import subprocess
import sys
import tempfile

source_dir = sys.argv[1]
script = os.path.join(source_dir, 'scripts', 'check_layout.py')
sys.path.insert(0, os.path.dirname(script))
import check_layout  # noqa: E402

FILE_LIMIT, FUNCTION_LIMIT = check_layout.MAX_FILE_LINES, check_layout.MAX_FUNCTION_LINES


def function(name, body_lines):
    """A function whose body, braces included, is body_lines lines, with braces that
    must not count: in a comment, a string, a character and a raw string."""
    inner = ['  int x = 0; // } {', '  const char *s = "}}{";', "  char c = '}';",
             '  const char *r = R"x(})x";', '  /* { */']
    inner += ['  ++x;'] * (body_lines - 2 - len(inner))
    return [f'int {name}()', '{'] + inner + ['}']


def source(function_body_lines, pad_to):
    lines = ['namespace demo {', 'struct S {', '  S(int a) : a_{a}, b_(a) {}',
             '  int a_, b_;', '  int get() const { return a_; }', '};']
    lines += function('long_one', function_body_lines)
    # A constructor whose initialiser list holds braces: its body is the last brace pair.
    ctor = function('ignored', function_body_lines)
    lines += ['Demo::Demo(int a)', '  : a_{a}, b_{a}'] + ctor[1:]
    lines += ['} // namespace demo']
    lines += ['// padding'] * (pad_to - len(lines))
    return '\n'.join(lines) + '\n'


def run(text):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, 'demo.cpp')
        with open(path, 'w') as f:
            f.write(text)
        done = subprocess.run([sys.executable, script, folder, '--files', path],
                              capture_output=True, text=True)
        return done.returncode, done.stdout


failures = []
code, out = run(source(FUNCTION_LIMIT, FILE_LIMIT))
if code != 0:
    failures.append(f'a file and a function at the limits failed: {out}')
code, out = run(source(FUNCTION_LIMIT + 1, FILE_LIMIT))
if code != 1 or 'long_one' not in out or 'Demo::Demo' not in out or f'{FUNCTION_LIMIT + 1} lines' not in out:
    failures.append(f'a function one line over the limit passed or was misreported: {code} {out}')
code, out = run(source(FUNCTION_LIMIT, FILE_LIMIT + 1))
if code != 1 or f'{FILE_LIMIT + 1} lines' not in out or 'function' in out:
    failures.append(f'a file one line over the limit passed or was misreported: {code} {out}')
# The tree's walk reaches every source folder, the tests' included: a test one line
# over the limit in each of them fails the tree.
with tempfile.TemporaryDirectory() as root:
    for folder in ('src', 'include', 'tests/unit'):
        os.makedirs(os.path.join(root, folder))
        with open(os.path.join(root, folder, 'long_test.cpp'), 'w') as f:
            f.write(source(FUNCTION_LIMIT, FILE_LIMIT + 1))
    done = subprocess.run([sys.executable, script, root], capture_output=True, text=True)
    for folder in ('src', 'include', 'tests/unit'):
        if done.returncode != 1 or f'{folder}/long_test.cpp: {FILE_LIMIT + 1} lines' not in done.stdout:
            failures.append(f'the tree\'s walk missed {folder}/: {done.returncode} {done.stdout}')
for failure in failures:
    print('FAIL:', failure)
sys.exit(1 if failures else 0)
