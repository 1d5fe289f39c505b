"""Bad input from Python: every case raises roadbrdf.InputError with the CLI's message,
never a crash or a RuntimeError."""
import json

import numpy as np
import pytest

import roadbrdf
from roadbrdf import _roadbrdf


def test_low_level_delta_reflectance_checks_the_parameter_count():
    model = _roadbrdf.make_model("simonot")
    with pytest.raises(roadbrdf.InputError, match="parameters"):
        model.delta_reflectance([], 0.5)
    with pytest.raises(roadbrdf.InputError, match="parameters"):
        model.delta_reflectance([0.5], 0.5)


def test_low_level_evaluate_flat_checks_lengths():
    model = _roadbrdf.make_model("lambert")
    a = np.zeros(3)
    with pytest.raises(roadbrdf.InputError):
        model.evaluate_flat(a, a, a, np.zeros(2), np.full(3, 0.3))


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def lambert_fit(albedo):
    return json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                       "fits": [{"model": "lambert", "wavelengths": [400, 500],
                                 "parameters": {"albedo": albedo}}]})


@pytest.mark.parametrize("text, fragment", [
    ('{"format": "roadbrdf-fit", "fits": [{"options": ' + "[" * 100000 + "]" * 100000 + "}]}",
     "nested deeper than 64 levels"),
    (lambert_fit([0.2, 0.3]).replace('"best": "lambert"', '"best": "lambert", "best": "x"'), "best: duplicate key"),
    (lambert_fit([0.2, 0.3]).replace("0.3", "1e400"), "number overflow"),
    (lambert_fit([0.2, -5]), "outside its bounds"),
    (lambert_fit([0.2, "x"]), "fits[0].parameters.albedo[1]: must be a number"),
])
def test_bad_fit_files_raise_input_error(tmp_path, text, fragment):
    path = write(tmp_path, "bad.fit.json", text)
    with pytest.raises(roadbrdf.InputError, match=None) as error:
        roadbrdf.read_fit(path)
    assert fragment in str(error.value)
    assert "bad.fit.json" in str(error.value)


@pytest.mark.parametrize("change, fragment", [
    (dict(wavelengths=[np.nan, 600.0]), "wavelengths[0]"),
    (dict(brdf=[[np.inf, 0.1]]), "infinite"),
    (dict(metadata={"bad\nkey": "x"}), "metadata key"),
    (dict(metadata={"note": "two\nlines"}), "one line"),
])
def test_dataset_write_refuses_what_its_reader_would_refuse(tmp_path, change, fragment):
    fields = dict(angles=[[0, 0, 30, 180]], wavelengths=[500.0, 600.0], brdf=[[0.1, 0.1]])
    fields.update(change)
    target = tmp_path / "out.csv"
    with pytest.raises(roadbrdf.InputError, match=None) as error:
        roadbrdf.Dataset(**fields).write(target)
    assert fragment in str(error.value)
    assert not target.exists()


@pytest.mark.parametrize("cells, fragment", [
    (np.full((29, 20), np.nan), "no defined cell"),
    (np.full((29, 20), 1e308), "cannot be written"),
    (np.full((29, 20), -0.01), "cannot be written"),
])
def test_rtable_write_refuses_what_its_readers_would_refuse(tmp_path, cells, fragment):
    table = roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})
    table["r"] = cells
    for format in ("csv", "rtb", "radiance"):
        target = tmp_path / f"r.{format}"
        with pytest.raises(roadbrdf.InputError, match=None) as error:
            table.write(target, format)
        assert fragment in str(error.value)
        assert not target.exists()


@pytest.mark.parametrize("bad, fragment", [
    (np.array(["a", "b", "c"]), "expected numbers"),
    (np.array([object(), object(), object()]), "expected numbers"),
    (np.array([1 + 1j, 0, 0]), "complex"),
    ("abc", "expected numbers"),
])
def test_low_level_arrays_of_non_numbers_raise_input_error(bad, fragment):
    model = _roadbrdf.make_model("lambert")
    a = np.zeros(3)
    with pytest.raises(roadbrdf.InputError, match=fragment):
        model.evaluate_flat(bad, a, a, a, np.full(3, 0.3))


def test_low_level_arrays_are_converted_when_numpy_can():
    # Integers, lists and non-contiguous views are numbers: converted, same values as float64 arrays.
    model = _roadbrdf.make_model("lambert")
    strided = np.zeros(6)[::2]
    out = model.evaluate_flat([0, 0, 0], np.zeros(3, dtype=np.int64), strided, strided, np.full(6, 0.3)[::2])
    np.testing.assert_allclose(out, 0.3 / np.pi, rtol=1e-15)


@pytest.mark.parametrize("call", [
    lambda: roadbrdf.Model("lambert").evaluate("x", 0, 30, 180, albedo=0.3),
    lambda: roadbrdf.Model("lambert").evaluate(0, 0, 30, 180, albedo=1 + 0.5j),
    lambda: roadbrdf.road_to_zenith_azimuth(0, ["a"], 0, 0),
    lambda: roadbrdf.Dataset([[0, 0, 30, "north"]], [500.0], [[0.1]]),
])
def test_high_level_non_numbers_raise_input_error_naming_the_argument(call):
    with pytest.raises(roadbrdf.InputError, match="theta_i|albedo|alpha|angles"):
        call()


def test_dataset_free_comments_are_kept_and_written_back(tmp_path):
    source = tmp_path / "in.csv"
    source.write_text("# operator J.D.\n# sample: concrete\ntheta_i,phi_i,theta_r,phi_r,500\n0,0,30,180,0.1\n")
    d = roadbrdf.read_dataset(source)
    assert d.comments == ["operator J.D."]
    assert d.metadata["sample"] == "concrete"
    d.comments.append("re-written by the test")
    d.write(tmp_path / "out.csv")
    back = roadbrdf.read_dataset(tmp_path / "out.csv")
    assert back.comments == ["operator J.D.", "re-written by the test"]
    d.comments = ["operator: J.D."]
    with pytest.raises(roadbrdf.InputError, match="would read back as metadata"):
        d.write(tmp_path / "refused.csv")
    assert not (tmp_path / "refused.csv").exists()
