"""The shipped closed form does not import the offline fit, and the old import paths still work
(with a DeprecationWarning naming the new one) for one release."""

from __future__ import annotations

import subprocess
import sys

import pytest


def test_closed_form_does_not_import_the_fit():
    code = ("import sys, coathertz.closedform.method, coathertz.closedform.refit as R; "
            "R.load(); "
            "bad = sorted(m for m in sys.modules if m.startswith(('coathertz.fitalpha', 'coathertz.runner', "
            "'coathertz.store', 'coathertz.refit'))); "
            "assert not bad, bad")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


@pytest.mark.parametrize("old, new", [
    ("coathertz.hertz", "coathertz.closedform.hertz"),
    ("coathertz.extended", "coathertz.closedform.extended"),
    ("coathertz.alpha", "coathertz.closedform.alpha"),
    ("coathertz.literature", "coathertz.closedform.literature"),
    ("coathertz.predictor", "coathertz.closedform.method"),
    ("coathertz.refit.rule", "coathertz.closedform.refit.rule"),
    ("coathertz.refit.sweep", "coathertz.fitalpha.sweep"),
    ("coathertz.fem.plastic_method", "coathertz.fem.plastic.method"),
    ("coathertz.fem.j2", "coathertz.fem.plastic.j2"),
])
def test_old_paths_forward_with_a_warning(old, new):
    code = (f"import warnings, importlib; warnings.simplefilter('error', DeprecationWarning)\n"
            f"try:\n    importlib.import_module({old!r})\nexcept DeprecationWarning as w:\n"
            f"    assert 'moved to' in str(w) and {new.split('.')[1]!r} in str(w), w\n"
            f"else:\n    raise SystemExit('no warning')\n"
            f"warnings.simplefilter('ignore')\nimport sys\n"
            f"assert importlib.import_module({old!r}) is importlib.import_module({new!r})")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr + out.stdout


def test_old_refit_package_names():
    code = ("import warnings; warnings.simplefilter('ignore')\n"
            "from coathertz.refit import load, predict\n"
            "import coathertz.closedform.refit as R\nassert load is R.load and predict is R.predict")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
