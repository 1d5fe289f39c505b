"""Property-based test of the study results store (studies/store.py) against torn and malformed lines.

Whatever bytes follow the header, opening the store either loads exactly the complete, well-formed records
(the later line of a key winning) after removing a torn last line, or refuses with an InputError naming the
line; it never raises anything else, never changes a complete line, and a store it opened takes new records
that read back."""

import json
import os
import tempfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import roadbrdf
from roadbrdf.studies.store import Store

HEADER = json.dumps({"format": "roadbrdf-study-store", "version": 1}) + "\n"

keys = st.text(alphabet="0123456789abcdef", min_size=1, max_size=8)
numbers = st.one_of(st.none(), st.floats(allow_nan=False, allow_infinity=False), st.integers(-10 ** 6, 10 ** 6))
rows = st.lists(st.fixed_dictionaries({"method": st.sampled_from(["areal", "mastic", "hapke"])},
                                      optional={"Q0": numbers, "S1": numbers, "white_sky": numbers,
                                                "class": st.text(max_size=5)}), max_size=3)
records = st.builds(lambda key, error, rows: {"key": key, "error": error, "rows": [] if error else rows,
                                              "cpu_seconds": 0.0},
                    keys, st.one_of(st.none(), st.text(max_size=20)), rows)
# Lines that are not records: torn JSON, other JSON values, records with a field missing or of another type.
malformed = st.one_of(
    st.text(max_size=30).filter(lambda t: "\n" not in t and "\r" not in t),
    st.sampled_from(['{"key": "a"}', '{"key": "a", "error": null}', '{"key": "a", "error": null, "rows": 3}',
                     '{"key": 1, "error": null, "rows": []}', "[]", "null", "{", '{"key": "a", "error": 2, "rows": []}',
                     '{"key": "a", "error": null, "rows": [[]]}']))


def _write(folder, text):
    path = os.path.join(folder, "store.jsonl")
    with open(path, "wb") as f:
        f.write(text)
    return path


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(records, max_size=6), st.binary(max_size=40).filter(lambda b: b"\n" not in b))
def test_complete_records_load_and_a_torn_last_line_is_removed(good, torn):
    with tempfile.TemporaryDirectory() as folder:
        body = HEADER + "".join(json.dumps(r) + "\n" for r in good)
        path = _write(folder, body.encode() + torn)
        store = Store(path)
        try:
            expected = {}
            for r in good:
                expected[r["key"]] = r
            assert store.results == expected
            with open(path, "rb") as f:
                assert f.read() == body.encode()  # only the torn tail is gone
            store.add("new", {"error": None, "rows": [{"method": "areal"}]})
        finally:
            store.close()
        again = Store(path)
        try:
            assert again.results["new"]["rows"] == [{"method": "areal"}]
            assert len(again.results) == len(expected | {"new": None})
        finally:
            again.close()


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(records, max_size=4), malformed, st.lists(records, max_size=2))
def test_a_malformed_line_is_a_located_error(before, bad, after):
    with tempfile.TemporaryDirectory() as folder:
        lines = [json.dumps(r) for r in before] + [bad] + [json.dumps(r) for r in after]
        text = (HEADER + "".join(line + "\n" for line in lines)).encode()
        path = _write(folder, text)
        try:
            store = Store(path)
        except roadbrdf.InputError as e:
            line = 2 + len(before)
            assert f"{path}:{line}:" in str(e)
        else:  # the text happened to be a valid record (e.g. a blank line is not: it must be refused)
            store.close()
            assert bad.strip().startswith("{")
        with open(path, "rb") as f:
            assert f.read() == text  # a refused store is left as it was


@settings(max_examples=100, deadline=None)
@given(st.binary(max_size=60))
def test_any_bytes_are_loaded_or_refused_with_an_input_error(data):
    with tempfile.TemporaryDirectory() as folder:
        path = _write(folder, data)
        try:
            Store(path).close()
        except roadbrdf.InputError:
            pass
