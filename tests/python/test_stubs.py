"""The type stubs (lagrange/__init__.pyi) describe exactly the module's public API."""

import ast
import inspect
import pathlib
import re

import pytest

import lagrange

NOTEBOOK = {"_repr_latex_", "_repr_html_"}


def stub_classes():
    path = pathlib.Path(lagrange.__file__).with_name("__init__.pyi")
    tree = ast.parse(path.read_text())
    return tree, {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}


def members(node):
    methods = {i.name for i in node.body if isinstance(i, ast.FunctionDef)}
    attributes = {i.target.id for i in node.body if isinstance(i, ast.AnnAssign)}
    return {n for n in methods if not n.startswith("_") or n in NOTEBOOK}, attributes


def test_the_stubbed_names_are_the_modules():
    tree, classes = stub_classes()
    functions = {n.name for n in tree.body if isinstance(n, ast.FunctionDef)}
    assert set(classes) | functions == set(lagrange.__all__)


@pytest.mark.parametrize("name", ["Equations", "Run", "Model", "Stepper"])
def test_class_members_match(name):
    _, classes = stub_classes()
    methods, _ = members(classes[name])
    cls = getattr(lagrange, name)
    actual = {n for n in dir(cls) if (not n.startswith("_") or n in NOTEBOOK)}
    assert methods == actual


def test_exception_attributes_match():
    _, classes = stub_classes()
    with pytest.raises(lagrange.ModelError) as model_error:
        lagrange.loads("name: x\n")
    m = lagrange.loads("name: m\ncoordinates:\n  x: {initial: 0}\nkinetic: (1 - t)*der(x)^2/2\n")
    with pytest.raises(lagrange.SimulationError) as simulation_error:
        m.forward([0.0], [1.0], t=2.0)
    for info in (model_error, simulation_error):
        _, attributes = members(classes[type(info.value).__name__])
        assert attributes == set(vars(info.value))


def test_functions_take_the_stubbed_keywords():
    tree, _ = stub_classes()
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            stubbed = [a.arg for a in node.args.args + node.args.kwonlyargs]
            function = getattr(lagrange, node.name)
            try:  # a Python function (lagrange.sweep) has a signature to inspect
                names = list(inspect.signature(function).parameters)
            except ValueError:  # a pybind11 function: its signature is its doc's first line
                signature = inspect.getdoc(function).splitlines()[0]
                names = re.findall(r"[(,]\s*(\w+)\s*:", signature)
            assert names == stubbed, node.name
