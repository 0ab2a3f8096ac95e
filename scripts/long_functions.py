#!/usr/bin/env python3
"""long_functions.py [LIMIT] DIR...: every function definition in the C++
files under DIR whose body is longer than LIMIT lines (default 150), as
"FILE:LINE: N lines: SIGNATURE", longest first.  A definition is a line
opening at the left margin (or one indent in a class) with a parameter list
whose body's braces are then matched, skipping strings and comments."""
import os
import re
import sys

limit = 150
args = sys.argv[1:]
if args and args[0].isdigit():
    limit, args = int(args[0]), args[1:]

skip = re.compile(r'^\s*(namespace|class|struct|enum|union|extern|#|//|/\*|\*|template\s*<[^>]*>\s*$)')


def code_only(text):
    """text with string and character literals and comments blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i)); i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j])); i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(')' + m.group(1) + '"', i) + len(m.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:end])); i = end
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == '\\' else 1
            out.append(c + ' ' * (j - i - 1) + c); i = j + 1
        else:
            out.append(c); i += 1
    return ''.join(out)


found = []
for root in args:
    for folder, _, files in os.walk(root):
        for name in files:
            if not name.endswith(('.cpp', '.hpp', '.cpp.in')):
                continue
            path = os.path.join(folder, name)
            lines = code_only(open(path, encoding='utf-8').read()).split('\n')
            original = open(path, encoding='utf-8').read().split('\n')
            i = 0
            while i < len(lines):
                line = lines[i]
                if re.match(r'^( {0,2})\S', line) and '(' in line and not skip.match(line) and not line.rstrip().endswith(';'):
                    # the body opens on this line or within the next few (a long signature)
                    j = i
                    while j < len(lines) and j < i + 6 and '{' not in lines[j] and ';' not in lines[j]:
                        j += 1
                    if j < len(lines) and '{' in lines[j] and ';' not in lines[j].split('{')[0]:
                        depth, k = 0, j
                        while k < len(lines):
                            depth += lines[k].count('{') - lines[k].count('}')
                            if depth <= 0:
                                break
                            k += 1
                        length = k - i + 1
                        if length > limit:
                            found.append((length, path, i + 1, original[i].strip()))
                        i = k + 1
                        continue
                i += 1
for length, path, line, signature in sorted(found, reverse=True):
    print(f'{path}:{line}: {length} lines: {signature}')
sys.exit(1 if found else 0)
