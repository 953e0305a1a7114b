#!/usr/bin/env python3
"""Copies each `<!-- verbatim: PATH NAME -->` region of compiled client code into the guide
chapter block below the marker (what tests/guide.rs checks), after an API change."""
import pathlib, re

root = pathlib.Path(__file__).resolve().parent.parent

def region(path, name):
    lines = (root / path).read_text().split('\n')
    start = next(i for i, l in enumerate(lines) if l.strip() == f'// guide: {name}')
    end = next(i for i in range(start, len(lines)) if lines[i].strip() == '// guide: end')
    body = lines[start + 1:end]
    indent = min((len(l) - len(l.lstrip()) for l in body if l.strip()), default=0)
    return ''.join(l[indent:] + '\n' for l in body)

for chapter in sorted((root / 'docs' / 'guide').glob('*.md')):
    text = chapter.read_text()
    pattern = re.compile(r'(<!-- verbatim: (\S+) (\S+) -->\n```rust,ignore\n)(.*?)(```)', re.S)
    new = pattern.sub(lambda m: m.group(1) + region(m.group(2), m.group(3)) + m.group(5), text)
    if new != text:
        chapter.write_text(new)
        print('synced', chapter.relative_to(root))
