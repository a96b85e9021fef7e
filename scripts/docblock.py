# SPDX-License-Identifier: Apache-2.0
"""The generated blocks of docs/*.md: the text between <!-- NAME:begin --> and
<!-- NAME:end -->, rewritten by the scripts that measure it (results, pareto, workloads).
Imported by those scripts (scripts/ on sys.path or PYTHONPATH)."""
import re


def replace_block(text, name, body):
    """(text with block NAME's body set to `body`, True) when the block is there exactly
    once; (text unchanged, False) otherwise."""
    pattern = r"(<!-- %s:begin -->\n).*?(<!-- %s:end -->)" % (re.escape(name), re.escape(name))
    new, n = re.subn(pattern, lambda m: m.group(1) + body + "\n" + m.group(2), text, flags=re.S)
    return (new, True) if n == 1 else (text, False)


def rewrite_blocks(doc, bodies):
    """Sets each block NAME of the file `doc` to bodies[NAME] and writes the file back;
    returns the names that are not there exactly once, in which case it writes nothing."""
    text = open(doc).read()
    missing = []
    for name, body in bodies.items():
        text, found = replace_block(text, name, body)
        if not found:
            missing.append(name)
    if not missing:
        open(doc, "w").write(text)
    return missing
