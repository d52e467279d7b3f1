#!/usr/bin/python3
"""Checks the sizes docs/architecture.md sets for the C++ of packages/: a file of at most 600 lines, a function of
at most 80 (from the first line of its signature to its closing brace; a lambda counts with the function it is in).

Usage: check_sizes.py [--list] [SOURCE_ROOT]   (default: the repository this script is in)

A longer file or function is allowed where it reads better in one piece, with its reason on one line:
`// size: <reason>` among the first 20 lines of the file, or on the lines just above a function's signature (or
inside its body). Prints each offender as `file:line: function NAME is N lines (limit 80)` or
`file: N lines (limit 600)` and exits 1 if there is any. --list prints every function over 40 lines as well,
longest first, to see what comes next.

Functions are found by their braces, not by a compiler: comments, strings and preprocessor lines are blanked, and
a `{` at namespace or class level opens a function when the text before it (since the last `;`, `{` or `}`) has
a parameter list and is not a class, enum, namespace or initialiser.
"""
import pathlib
import re
import sys

FILE_LIMIT, FUNCTION_LIMIT = 600, 80
REASON = re.compile(r'//\s*size:\s*\S')
SUFFIXES = {'.cpp', '.hpp', '.h', '.cc'}


def blank_comments_and_strings(text):
    """The text with comments, string and character literals and preprocessor lines replaced by spaces (line breaks
    kept, so line numbers stay)."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == '#':  # a preprocessor line, with its continuations
            j = i
            while j < n and (text[j] != '\n' or text[j - 1] == '\\'):
                j += 1
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
            continue
        if c == '/' and text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
            continue
        if c == '/' and text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
            continue
        if c == 'R' and text.startswith('R"', i):  # raw string R"delim( ... )delim"
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(')' + m.group(1) + '"', i)
                j = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r'[^\n]', ' ', text[i:j]))
                i = j
                continue
        if c in '"\'':
            if c == "'" and i > 0 and (text[i - 1].isalnum()):  # a digit separator (1'000)
                out.append(' ')
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(' ' * (min(j + 1, n) - i))
            i = j + 1
            continue
        out.append(c)
        at_line_start = c == '\n' or (at_line_start and c in ' \t')
        i += 1
    return ''.join(out)


def strip_templates(head):
    """The head without its template parameter lists (template <class T, int N>)."""
    return re.sub(r'\btemplate\s*<[^{};]*?>', ' ', head)


def classify(head, enclosing):
    """What a `{` opens, from the text before it: namespace, class, function or other."""
    h = strip_templates(head).strip()
    if enclosing not in ('namespace', 'class'):
        return 'other'
    if re.search(r'\bnamespace\b', h) or re.fullmatch(r'extern\s*', h):
        return 'namespace'
    if re.search(r'\)\s*(const|noexcept|override|final|mutable|->[^=]*|:.*|\s)*$', h, re.S) and '(' in h:
        if re.search(r'=\s*$', h) or re.match(r'.*\)\s*:\s*[\w:]+\s*$', h, re.S) and enclosing == 'class':
            return 'other'
        return 'function'
    if re.search(r'\b(class|struct|union|enum)\b', h) and '=' not in h.split('(')[0]:
        return 'class'
    if re.search(r'\)\s*:', h) and re.search(r'[\w>]\s*$', h):  # a constructor's initialiser with braces
        return 'function'
    return 'other'


def is_braced_member_initialiser(head):
    """Whether a `{` after this head initialises a member in a constructor's initialiser list (`S() : a_(1), b_{`),
    which belongs to the head of the constructor, not to a body."""
    h = strip_templates(head)
    return bool(re.search(r'\)\s*:(?!:)', h) and re.search(r'(?:,|\)\s*:(?!:))\s*[\w:]+\s*$', h))


def functions(text):
    """(name, first line, last line) of each function of the text (1-based lines)."""
    code = blank_comments_and_strings(text)
    stack, found = [], []  # stack entries: (kind, head start line, name)
    head_start = 0
    line = 1
    for i, c in enumerate(code):
        if c == '\n':
            line += 1
        if c not in '{};':
            continue
        if c == '{':
            head = code[head_start:i]
            enclosing = stack[-1][0] if stack else 'namespace'
            if enclosing in ('namespace', 'class') and is_braced_member_initialiser(head):
                stack.append(('initialiser', 0, ''))
                continue  # the constructor's head goes on
            kind = classify(head, enclosing)
            if kind == 'function' and enclosing == 'function':
                kind = 'other'
            start = head_start + len(head) - len(head.lstrip())
            first = line - code[start:i].count('\n')
            m = re.search(r'(operator\s*[^\s(]+|[~\w:]+)\s*\(', strip_templates(head))
            stack.append((kind, first, m.group(1) if m else '?'))
        elif c == '}':
            if stack:
                kind, first, name = stack.pop()
                if kind == 'initialiser':
                    continue
                if kind == 'function' and not any(k == 'function' for k, _, _ in stack):
                    found.append((name, first, line))
        head_start = i + 1
    return found


def check_file(root, path):
    """The size problems of root/path, and every function's size, each naming path."""
    text = (root / path).read_text(errors='replace')
    lines = text.splitlines()
    problems, listing = [], []
    if len(lines) > FILE_LIMIT and not any(REASON.search(l) for l in lines[:20]):
        problems.append(f'{path}: {len(lines)} lines (limit {FILE_LIMIT})')
    for name, first, last in functions(text):
        size = last - first + 1
        listing.append((size, f'{path}:{first}: {name} {size}'))
        if size <= FUNCTION_LIMIT:
            continue
        around = lines[max(0, first - 4):last]
        if any(REASON.search(l) for l in around):
            continue
        problems.append(f'{path}:{first}: function {name} is {size} lines (limit {FUNCTION_LIMIT})')
    return problems, listing


def main(argv):
    show = '--list' in argv
    argv = [a for a in argv if a != '--list']
    root = pathlib.Path(argv[0] if argv else pathlib.Path(__file__).resolve().parents[1])
    sources = sorted(p for p in (root / 'packages').rglob('*') if p.suffix in SUFFIXES and p.is_file())
    if not sources:
        print(f'check_sizes.py: no C++ sources under {root / "packages"}', file=sys.stderr)
        return 2
    problems, listing = [], []
    for p in sources:
        pr, li = check_file(root, p.relative_to(root))
        problems += pr
        listing += li
    if show:
        for size, entry in sorted(listing, reverse=True):
            if size > 40:
                print(entry)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
