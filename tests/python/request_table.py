"""Checks of a request table (core/request_fields.h) shared by the tests of the commands made from one:
every row is an option of the command and a keyword of the Python function, and a bad value is refused
with the same message by both, each spelling the field its own way."""
import re

import pytest

import roadbrdf
from roadbrdf import _roadbrdf


def fields(command):
    return _roadbrdf.request_fields(command)


def check_every_row_is_shown(cli, command, function):
    """The command's --help shows each row's flag, the function's docstring each keyword and its help."""
    help_text = cli(command, "--help").stdout
    doc = " ".join(function.__doc__.split())
    for row in fields(command):
        assert re.search(r"(^|[\s,\[])" + re.escape(row["long_flag"]) + r"\b", help_text), row
        assert f" {row['name']}: " in doc or f" {row['name']} [" in doc, row["name"]
        assert " ".join(row["help"].split())[:40] in doc, row["name"]


def spelt_as_fields(command, message, from_cli):
    """The message with every field written as its name: the command's flags and placeholders (from_cli), or
    Python's `name` references."""
    for row in sorted(fields(command), key=lambda r: -len(r["long_flag"])):
        if from_cli:
            flag = r"(?<![\w-])" + re.escape(row["long_flag"]) + r"(?![\w-])"
            # "--fix albedo: ..." is the field fixed.albedo
            message = re.sub(flag + r" ([\w.+-]+):", row["name"] + r".\1:", message)
            message = re.sub(flag, row["name"], message)
        else:
            message = message.replace("`" + row["name"] + "`", row["name"])
    return message


def check_refused_alike(command, row, cli_result, python_error):
    """The command failed with the message Python raised, apart from the spelling of the fields."""
    assert cli_result.returncode == 2, cli_result.stderr
    assert cli_result.stderr.startswith("roadbrdf: error: "), cli_result.stderr
    from_cli = cli_result.stderr[len("roadbrdf: error: "):].strip()
    from_python = str(python_error)
    assert spelt_as_fields(command, from_cli, True) == spelt_as_fields(command, from_python, False)
    if from_python.startswith(row["name"] + ": ") or from_python.startswith(row["name"] + "."):
        assert from_cli.startswith(row["long_flag"]), from_cli


def check_bad_value_refused_alike(cli, command, function, row, cli_args, args=(), kwargs=None):
    """`roadbrdf COMMAND CLI_ARGS` and `function(*args, **kwargs)` refuse the row's bad value with one message."""
    result = cli(command, *cli_args, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        function(*args, **(kwargs or {}))
    check_refused_alike(command, row, result, error.value)
