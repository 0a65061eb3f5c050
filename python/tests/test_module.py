"""The module itself: it imports, documents units, and every function has a docstring."""
import inspect

import camsim


def test_help_documents_units():
    doc = camsim.__doc__
    for unit in ("lm·s", "nm", "DN", "e⁻", "SI"):
        assert unit in doc, unit


def test_every_public_function_has_a_docstring():
    names = [n for n in dir(camsim) if not n.startswith("_")]
    assert {"load", "default_scene", "capture", "Scene", "InputError", "read_exr"} <= set(names)
    for name in names:
        obj = getattr(camsim, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__.strip()) > 20, name
    for name, member in inspect.getmembers(camsim.Scene):
        if not name.startswith("_"):
            assert member.__doc__ and member.__doc__.strip(), name
    assert "electrons" in camsim.capture.__doc__ and "uint16" in camsim.capture.__doc__


def test_input_error_is_a_value_error():
    assert issubclass(camsim.InputError, ValueError)
