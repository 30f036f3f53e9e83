"""Test-session settings shared by every test folder.

Hypothesis runs derandomized by default (the same examples on every run and machine), so the
default suite and CI cannot turn red on a newly drawn example; the ``explore`` profile
(``HYPOTHESIS_PROFILE=explore pytest ...``) draws fresh random examples and keeps a database, to
look for new counter-examples on purpose (then pin each as an ``@example``).
"""

from __future__ import annotations

import os

from hypothesis import settings

settings.register_profile("deterministic", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "deterministic"))
