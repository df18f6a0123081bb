"""The examples of the module's docstrings (`help(pdd)`, `help(pdd.solve)`, ...) run as written:
every `>>>` line of every docstring is run by doctest from the source tree (the examples read
fixtures/ by relative path) and must print what the docstring shows. A change of behaviour
(the resolver's number of rounds, a value) therefore fails here until the text says it."""
import doctest
import os

import numpy
import pytest

import pdd
from conftest import SOURCE_DIR


def documented():
    out = [("pdd", pdd.__doc__)]
    for name in sorted(dir(pdd)):
        doc = getattr(getattr(pdd, name), "__doc__", None)
        if isinstance(doc, str) and ">>>" in doc and not name.startswith("__"):
            out.append((f"pdd.{name}", doc))
    return out


def test_the_examples_exist():
    names = {n for n, _ in documented()}
    functions = {f"pdd.{n}" for n in dir(pdd) if callable(getattr(pdd, n)) and not n.startswith("_")}
    assert {"pdd.solve", "pdd.contact_energy", "pdd.read_mesh"} <= functions
    assert {"pdd"} | functions <= names, "no example: " + ", ".join(sorted(functions - names))


@pytest.mark.parametrize("name,doc", documented(), ids=[n for n, _ in documented()])
def test_docstring_example(name, doc, monkeypatch):
    monkeypatch.chdir(SOURCE_DIR)
    test = doctest.DocTestParser().get_doctest(doc, {"pdd": pdd, "numpy": numpy}, name, None, 0)
    assert test.examples, name
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{name}: {result.failed} of {result.attempted} examples differ (output above)"
