#!/usr/bin/env python3
"""Write the roadbrdf(1) man page from the program's own --help texts.

Usage: make_manpage.py PROGRAM VERSION OUTPUT.1
"""
import re
import subprocess
import sys


def help_text(program, *args):
    out = subprocess.run([program, *args, "--help"], capture_output=True, text=True, check=True).stdout
    # The usage line names the program by its build path: show the plain name.
    return re.sub(r"Usage: \S*roadbrdf", "Usage: roadbrdf", out)


def roff(text):
    """Plain text as a no-fill roff block (backslashes and leading dots escaped)."""
    lines = []
    for line in text.rstrip().splitlines():
        line = line.replace("\\", "\\e")
        if line.startswith((".", "'")):
            line = "\\&" + line
        lines.append(line)
    return ".nf\n" + "\n".join(lines) + "\n.fi\n"


def main():
    program, version, output = sys.argv[1:4]
    top = help_text(program)
    commands = []
    in_list = False
    for line in top.splitlines():
        if line.startswith("Subcommands:"):
            in_list = True
            continue
        if in_list:
            m = re.match(r"^  (\S+)\s", line)
            if m:
                commands.append(m.group(1))
            elif line.strip() == "":
                in_list = False
    parts = [
        f'.TH ROADBRDF 1 "" "roadbrdf {version}" "User Commands"\n',
        ".SH NAME\nroadbrdf \\- spectral BRDF models, fitting, mixing, solar albedo and road photometry\n",
        ".SH SYNOPSIS\n.B roadbrdf\n.I COMMAND\n[\\fIOPTIONS\\fR]\n",
        ".SH DESCRIPTION\n" + roff(top),
    ]
    for command in commands:
        if command == "plot":
            text = subprocess.run([program, "plot", "--help"], capture_output=True, text=True).stdout or \
                "Figures, drawn by the roadbrdf Python package: roadbrdf plot KIND --help\n"
        else:
            text = help_text(program, command)
        parts.append(f".SH COMMAND {command.upper()}\n" + roff(text))
    parts.append(".SH EXIT STATUS\n0 on success, 2 for bad input (the message names file, line and column or the key), "
                 "3 for an internal error.\n")
    parts.append(".SH FILES\n.I PREFIX/share/roadbrdf/data\nbundled data tables (override with \\fBROADBRDF_DATA\\fR).\n")
    with open(output, "w", encoding="utf-8") as f:
        f.write("".join(parts))


if __name__ == "__main__":
    main()
