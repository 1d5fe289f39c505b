"""Library messages name request fields, never command-line flags (core/error.h): fails, listing
file:line and the literal, when a string literal of a C++ source under the given folders holds a
long flag ("--name"). Comments are skipped; raw string literals are not used in the library. The
flag of a request's field-table row ({"field", "--flag", ...}, core/request_fields.h) is its
declaration, not a message, and is allowed.

Usage: library_names_no_flags.py ROOT [--exclude SUBFOLDER ...]  (ROOT: src/roadbrdf)
       library_names_no_flags.py FILE ...                       (the control: check these files)
"""
import pathlib
import re
import sys

FLAG = re.compile(r"--[A-Za-z]")
# A literal that is nothing but a flag's spelling ("--class", "-o,--output") is the flag column of a
# request's field table (core/request_fields.h), the one place the library declares its flags.
FIELD_TABLE_FLAG = re.compile(r"(-[A-Za-z],)?--[a-z][a-z0-9-]*")


def string_literals(text):
    """(line, offset of the body, literal body) of every "..." literal of C++ source `text`, outside
    comments and character literals."""
    i, line, n = 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            line += text.count("\n", i, end)
            i = end
        elif c in "\"'":
            start, i = i + 1, i + 1
            while i < n and text[i] != c and text[i] != "\n":
                i += 2 if text[i] == "\\" else 1
            if c == '"':
                yield line, start, text[start:i]
            i += 1
        else:
            i += 1


# A row of a request's field table (core/request_fields.h): {"field_name", "--flag", ...}. The table is
# where a field's flag is declared, once; the command line reads it from there.
TABLE_ROW = re.compile(r'\{\s*"[a-z][a-z0-9_.]*"\s*,\s*"$')


def offending(path):
    text = path.read_text(encoding="utf-8")
    found = []
    for line, start, body in string_literals(text):
        in_table_row = TABLE_ROW.search(text[max(0, start - 80):start]) or FIELD_TABLE_FLAG.fullmatch(body)
        if FLAG.search(body) and not in_table_row:
            found.append((line, body))
    return found


def main(argv):
    if not argv:
        print(__doc__)
        return 2
    excluded = []
    if "--exclude" in argv:
        at = argv.index("--exclude")
        excluded = argv[at + 1:]
        argv = argv[:at]
    files = []
    for arg in argv:
        p = pathlib.Path(arg)
        if p.is_dir():
            files += sorted(f for f in p.rglob("*") if f.suffix in (".h", ".cpp") and
                            not any(f.relative_to(p).parts[0] == e for e in excluded))
        else:
            files.append(p)
    found = 0
    for f in files:
        for line, body in offending(f):
            print(f"{f}:{line}: a library message names a flag: \"{body}\" (name the request field; "
                  "the command line maps it to its flag, see core/error.h)")
            found += 1
    if found:
        return 1
    print(f"{len(files)} files, no flag named in a string literal")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
