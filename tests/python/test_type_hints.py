"""The public Python API is typed (PEP 561, py.typed): every callable exported by roadbrdf, and every
public method of an exported class, annotates its parameters and its return value."""
import inspect
import pathlib

import roadbrdf


def _unannotated(function, is_method):
    signature = inspect.signature(function)
    names = list(signature.parameters)
    if is_method and names and names[0] in ("self", "cls"):
        names = names[1:]
    missing = [n for n in names if signature.parameters[n].annotation is inspect.Parameter.empty]
    if signature.return_annotation is inspect.Signature.empty and function.__name__ != "__init__":
        missing.append("return")
    return missing


def _public_callables():
    for name in roadbrdf.__all__:
        value = getattr(roadbrdf, name)
        module = getattr(value, "__module__", "") or ""
        # roadbrdf.studies is typed on its own; the exceptions come from the binding.
        if not module.startswith("roadbrdf.") or module.startswith(("roadbrdf.studies", "roadbrdf._roadbrdf")):
            continue
        if inspect.isclass(value):
            for attribute, member in vars(value).items():
                if inspect.isfunction(member) and (not attribute.startswith("_") or attribute == "__init__"):
                    yield f"{name}.{attribute}", member, True
        elif inspect.isfunction(value):
            yield name, value, False


def test_public_callables_are_annotated():
    missing = {name: m for name, f, is_method in _public_callables() if (m := _unannotated(f, is_method))}
    assert not missing, missing


def test_the_package_is_marked_typed():
    assert (pathlib.Path(roadbrdf.__file__).parent / "py.typed").exists()
