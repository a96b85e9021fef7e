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
